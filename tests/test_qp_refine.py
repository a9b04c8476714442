"""QP corridor smoother (refine='qp'): valid by construction, OSQP == cvxpy, honest fallbacks."""
from __future__ import annotations

import json

import numpy as np
import pytest

import optplan as op
from optplan.solvers.qp import build_corridor, corridor_program, smooth_path_qp
from optplan.solvers.qp.corridor import sample_for_corridor
from optplan.world.metrics import path_length
from optplan.world.papermaps import paper_map


@pytest.fixture(scope="module")
def circle_case():
    world, s, g = paper_map("yang2023_env1")
    seed = op.plan(world, s, g, algorithm="pso", seed=1, pop=20, iters=40, encoding="paper")   # a spline to refine
    assert seed.feasible
    return world, seed.path


def test_grid_refinement_validates_and_shortens_an_astar_seed():
    world, s, g = paper_map("chen2025_20")
    pure = op.plan(world, s, g, algorithm="astar")
    ref = op.plan(world, s, g, algorithm="astar", refine="qp")
    opt = op.shortest_path(world, s, g, method="visibility").length
    assert ref.refined and ref.feasible and op.validate_path(world, ref.path)
    assert opt - 1e-9 <= ref.length <= pure.length
    assert ref.length <= 1.01 * opt          # A*'s homotopy class holds the optimum on this map
    assert ref.turn_angle_deg < pure.turn_angle_deg


def test_circle_refinement_validates_and_is_not_longer(circle_case):
    world, seed = circle_case
    r = smooth_path_qp(world, seed)
    assert r.success and op.validate_path(world, r.path)
    assert path_length(r.path) <= path_length(seed) + 1e-9
    np.testing.assert_allclose(r.path[[0, -1]], seed[[0, -1]])


def test_corridor_contains_the_seed_and_excludes_the_obstacles(circle_case):
    world, seed = circle_case
    X = sample_for_corridor(world, seed, 40)
    c = build_corridor(world, X, cushion=0.0)
    assert np.all(c.lo <= X + 1e-12) and np.all(X <= c.hi + 1e-12)
    for e in (0, 1):
        val = np.einsum("ikj,ij->ik", c.normals, X[e:len(X) - 1 + e])
        assert np.all(val >= c.offsets - 1e-9)
    # every active half-plane keeps the grown circle it was built from outside: n.c + R <= b
    centres = world.circles[:, :2]
    for i in range(len(X) - 1):
        for n, b in zip(c.normals[i], c.offsets[i]):
            if np.isfinite(b):
                dist = centres @ n - b       # signed distance of each centre below the boundary
                assert np.any(np.isclose(dist, -world.radii, atol=1e-9))


@pytest.mark.parametrize("name", ["yang2023_env1", "li2023_30"])
def test_osqp_and_cvxpy_reach_the_same_optimum(name):
    world, s, g = paper_map(name)
    seed = op.plan(world, s, g, algorithm="astar" if name.startswith("li") else "visibility").path
    c = build_corridor(world, sample_for_corridor(world, seed, 50))
    a = corridor_program(c.n_points, c.k_slots, 0.5, "osqp").solve(c)
    b = corridor_program(c.n_points, c.k_slots, 0.5, "cvxpy").solve(c)
    assert a.ok and b.ok
    assert a.objective == pytest.approx(b.objective, rel=1e-6)
    np.testing.assert_allclose(a.points, b.points, atol=1e-4)
    full = smooth_path_qp(world, seed, backend="cvxpy")
    assert full.success and full.objective == pytest.approx(smooth_path_qp(world, seed).objective, rel=1e-5)


def test_topologically_wrong_seed_falls_back_with_the_reason():
    world = op.GridMap.from_rows([[0] * 9] * 3 + [[0, 0, 0, 1, 1, 1, 0, 0, 0]] * 3 + [[0] * 9] * 3)
    seed = np.array([[0.5, 4.5], [8.5, 4.5]])  # straight through the block
    r = smooth_path_qp(world, seed)
    assert not r.success and "not collision-free" in r.message
    np.testing.assert_array_equal(r.path, seed)
    res = op.plan(world, (0.5, 4.5), (8.5, 4.5), algorithm="astar", refine="qp")
    assert res.refined and res.feasible  # a valid seed of the same query refines fine


def test_blocked_goal_falls_back_with_the_reason():
    world = op.GridMap.from_rows([[0, 0, 0], [0, 1, 0], [0, 0, 0]])
    r = smooth_path_qp(world, [[0.5, 0.5], [1.5, 1.5]])
    assert not r.success and "goal" in r.message


def test_clearance_is_kept():
    world, _, _ = paper_map("chen2025_20")
    res = op.plan(world, (1.5, 1.5), (18.5, 18.5), algorithm="astar", refine="qp", clearance=0.2)
    assert res.refined and res.feasible and op.validate_path(world, res.path, clearance=0.2)
    assert res.min_clearance >= 0.2 - 1e-6
    circles, s, g = paper_map("yang2023_env1")
    seed = op.plan(circles, s + 0.3, g - 0.3, algorithm="visibility", clearance=0.3).path
    r = smooth_path_qp(circles, seed, clearance=0.3)
    assert r.success and op.validate_path(circles, r.path, clearance=0.3)


def test_cli_plan_with_qp_refinement(capsys):
    from optplan.cli import main

    code = main(["plan", "li2023_11", "--start", "0.5", "0.5", "--goal", "10.5", "10.5", "--algo", "astar",
                 "--refine", "qp", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code in (0, None) and out["refined"] and out["feasible"]
