"""CasADi/IPOPT refinement: validated, near the exact optimum, honest fallbacks."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.solvers.nlp import smooth_path
from optplan.world.metrics import path_length
from optplan.world.papermaps import paper_map


def test_astar_seeds_refined_near_the_exact_optimum():
    """Issue 5 asks for 1 % in at least 90 % of runs. A*'s homotopy class holds the
    optimum on these maps; the QP polish removes the NLP's sampling cushion
    (hou2024_env2: 1.2 % without it)."""
    for name in ["chen2025_20", "chen2025_30", "li2023_30", "yuan2021_25", "hou2024_env2"]:
        world, s, g = paper_map(name)
        opt = op.shortest_path(world, s, g, method="visibility").length
        res = op.plan(world, s, g, algorithm="astar", refine="casadi")
        assert res.refined and res.feasible and op.validate_path(world, res.path)
        assert opt - 1e-9 <= res.length <= 1.01 * opt, name
    unpolished = smooth_path(world, op.plan(world, s, g, algorithm="astar").path, polish=False)
    assert unpolished.success and path_length(unpolished.path) > res.length


def test_refinement_keeps_the_optimum_on_a_circle_world():
    world, s, g = paper_map("yang2023_env1")
    best = op.shortest_path(world, s, g, method="visibility")
    r = smooth_path(world, best.path)
    assert r.success and op.validate_path(world, r.path)
    assert best.length - 1e-9 <= path_length(r.path) <= 1.01 * best.length


def test_refined_metaheuristic_path_is_valid_and_not_longer():
    world, s, g = paper_map("yang2023_env1")
    pure = op.plan(world, s, g, algorithm="pso", seed=1, pop=20, iters=40, encoding="paper")
    ref = op.plan(world, s, g, algorithm="pso", seed=1, pop=20, iters=40, refine="casadi", encoding="paper")
    assert pure.feasible
    assert ref.refined and op.validate_path(world, ref.path) and ref.length <= pure.length + 1e-9


def test_clearance_is_respected():
    world, _, _ = paper_map("chen2025_20")
    s, g = (1.5, 1.5), (18.5, 18.5)
    res = op.plan(world, s, g, algorithm="astar", refine="casadi", clearance=0.2)
    assert res.refined and res.feasible and op.validate_path(world, res.path, clearance=0.2)
    assert res.min_clearance >= 0.2 - 1e-6


def test_topologically_wrong_seed_falls_back_or_validates():
    world = op.GridMap.from_rows([[0] * 9] * 3 + [[0, 0, 0, 1, 1, 1, 0, 0, 0]] * 3 + [[0] * 9] * 3)
    seed = np.array([[0.5, 4.5], [8.5, 4.5]])  # straight through the block
    r = smooth_path(world, seed)
    if r.success:
        assert op.validate_path(world, r.path)
    else:
        np.testing.assert_array_equal(r.path, seed)
        assert "attempt" in r.message


def test_seed_through_a_closed_wall_falls_back_with_the_reason():
    world = op.GridMap.from_rows([[0, 0, 0, 1, 0, 0, 0]] * 5)  # no way round the wall
    seed = np.array([[0.5, 2.5], [6.5, 2.5]])
    r = smooth_path(world, seed)
    assert not r.success and "attempt 2" in r.message and "IPOPT" in r.message
    np.testing.assert_array_equal(r.path, seed)


def test_blocked_goal_gives_the_reason_not_a_crash():
    world = op.GridMap.from_rows([[0, 0, 0], [0, 1, 0], [0, 0, 0]])
    r = smooth_path(world, [[0.5, 0.5], [1.5, 1.5]])
    assert not r.success and "goal" in r.message


def test_infeasible_seed_result_is_not_refined():
    world, s, g = paper_map("chen2025_20")
    bad = op.PlanResult("x", np.array([s, g]), False, 30.0, 0.0, 0, 0.0, 0.0)
    from optplan.solvers.refine import refine_result

    out = refine_result(world, bad)
    assert not out.refined and "infeasible" in out.message


def test_warm_start_reaches_the_cold_solution_in_fewer_iterations():
    world, s, g = paper_map("yang2023_env1")
    seed = op.plan(world, s, g, algorithm="pso", seed=1, pop=20, iters=40).path
    first = smooth_path(world, seed)
    assert first.success and first.warm is not None
    again = smooth_path(world, seed, warm_start=first)
    assert again.success and again.iterations < first.iterations
    np.testing.assert_allclose(again.path, first.path, atol=1e-5)
    # replanning: the start moves a little along the path; warm and cold agree
    moved = np.vstack([first.path[0] + 0.3 * (first.path[1] - first.path[0]), seed[1:]])
    warm = smooth_path(world, moved, warm_start=first)
    cold = smooth_path(world, moved, n_points=len(first.path))
    assert warm.success and cold.success and warm.iterations < cold.iterations
    np.testing.assert_allclose(warm.path, cold.path, atol=1e-3)   # IPOPT tol 1e-6 on J, not on points
    assert warm.objective == pytest.approx(cold.objective, rel=1e-5)


def test_warm_start_of_the_wrong_type_is_refused():
    world, s, g = paper_map("yang2023_env1")
    with pytest.raises(op.OptplanError, match="warm_start"):
        smooth_path(world, np.array([s, g]), warm_start=np.zeros((3, 2)))


def test_refined_vs_pure_example_every_refined_path_validates(tmp_path):
    import subprocess
    import sys
    from pathlib import Path

    script = Path(__file__).resolve().parents[1] / "examples" / "refined_vs_pure.py"
    proc = subprocess.run([sys.executable, str(script), "--quick", "--maps", "li2023_11", "yang2023_env1",
                           "--iters", "30", "--out", str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    rows = [line.split(" | ") for line in (tmp_path / "refined_vs_pure.md").read_text().splitlines()
            if line.startswith("| li2023_11 |") or line.startswith("| yang2023_env1 |")]
    table = [r for r in rows if len(r) == 11]
    assert {r[2] for r in table} == {"pure", "casadi-local", "casadi", "qp"}
    for r in table:
        valid = r[9].split("/")
        assert valid[0] == valid[1], r           # every path (pure and refined) validates
    assert (tmp_path / "li2023_11.png").stat().st_size > 0 and (tmp_path / "yang2023_env1.png").exists()
    assert "within 1 %" in proc.stdout
