"""The general encoding (issue 26): every path class on every map, always collision-free,
the fallback from the paper encodings, programs, the CLI and the seeded map generator."""
from __future__ import annotations

import json

import numpy as np
import pytest

import optplan as op
from optplan import terms as T
from optplan.cli import main
from optplan.errors import ParameterError
from optplan.formulations.encodings import GeneralPath
from optplan.world.metrics import path_length
from optplan.worldgen.maps import MAP_KINDS, generate_map, map_query


@pytest.fixture(scope="module")
def rooms():
    grid = generate_map("rooms", 24, seed=101)
    s, g = map_query(grid, seed=101)
    return grid, s, g


def test_decoded_length_is_the_table_sum_and_every_decoded_path_is_collision_free(rooms):
    grid, s, g = rooms
    enc = GeneralPath(grid, s, g, m=3)
    X = np.random.default_rng(0).uniform(enc.lower, enc.upper, size=(40, enc.dim))
    P = enc.decode(X)
    assert np.allclose(path_length(P), enc.leg_length(X))
    assert all(op.validate_path(grid, p).ok for p in P)
    exact = op.shortest_path(grid, s, g, method="visibility").length
    assert enc.leg_length(X).min() >= exact - 1e-9


@pytest.mark.parametrize("algo", ["missa", "msiar-gwo", "pso", "ipso", "iba", "gwo"])
def test_every_metaheuristic_is_feasible_with_the_general_encoding(rooms, algo):
    grid, s, g = rooms
    r = op.plan(grid, s, g, algorithm=algo, encoding="general", max_evals=3000, seed=1)
    assert r.feasible and r.encoding == "general"
    exact = op.shortest_path(grid, s, g, method="visibility").length
    assert r.length <= 1.05 * exact


def test_same_seed_same_path(rooms):
    grid, s, g = rooms
    a = op.plan(grid, s, g, algorithm="missa", encoding="general", max_evals=1500, seed=7)
    b = op.plan(grid, s, g, algorithm="missa", encoding="general", max_evals=1500, seed=7)
    assert np.array_equal(a.path, b.path)


def test_a_map_the_column_encoding_cannot_represent_falls_back_and_says_so():
    occ = np.zeros((10, 10), bool)
    occ[0:8, 4] = True                 # a wall open only at the top ...
    occ[2:10, 6] = True                # ... then one open only at the bottom: a path must turn back in x
    occ[1, 5] = occ[8, 5] = False
    grid = op.GridMap(occ)
    s, g = (0.5, 0.5), (9.5, 0.5)
    r = op.plan(grid, s, g, algorithm="missa", encoding="paper", max_evals=2000, seed=0)
    assert r.feasible and r.encoding == "general"
    assert "encoding='general'" in r.message
    with pytest.raises(op.OptplanError):     # asked for explicitly: no silent replacement
        op.plan(grid, s, g, algorithm="missa", encoding="columns", max_evals=2000, seed=0, init="feasible")


def test_paper_encodings_stay_when_they_represent_the_solution():
    grid = generate_map("random", 16, seed=5, density=0.1)
    s, g = map_query(grid, seed=5)
    r = op.plan(grid, s, g, algorithm="msiar-gwo", encoding="paper", max_evals=1500, seed=0)
    assert r.encoding in ("columns", "general")
    if r.encoding == "columns":
        assert r.feasible


def test_general_vias_as_program_variables(rooms):
    grid, s, g = rooms
    prog = op.PathProgram(grid, s, g, variables=op.GeneralVias(2))
    prog.minimize(T.length())
    r = prog.solve("pso", max_evals=1500, seed=0)
    assert r.feasible
    # the decoded path, its repeated points moved to the end (where they change no term)
    P = r.path
    moves = np.r_[True, np.any(np.diff(P, axis=0) != 0, axis=1)]
    k = int(moves.sum())
    np.testing.assert_array_equal(P[:k], prog.variables.encoding.waypoints(r.x))
    assert np.all(P[k:] == g)
    assert prog.evaluate(r.path)[0] == pytest.approx(r.cost)


def test_iga_runs_its_loop_on_via_points_and_refuses_other_encodings(rooms):
    """li2023's GA loop on the general encoding's via points (iga's default): every chromosome
    decodes to a collision-free path, and the run reaches the exact optimum on this map."""
    grid, s, g = rooms
    r = op.plan(grid, s, g, algorithm="iga", pop=20, iters=60, seed=0)
    best = op.shortest_path(grid, s, g, method="visibility").length
    assert r.encoding == "general" and r.feasible and "via points" in r.message
    assert r.length == pytest.approx(best, rel=1e-9)
    again = op.plan(grid, s, g, algorithm="iga", pop=20, iters=60, seed=0)
    np.testing.assert_array_equal(r.path, again.path)
    with pytest.raises(ParameterError, match="cell"):
        op.plan(grid, s, g, algorithm="iga", encoding="waypoints")
    with pytest.raises(ParameterError, match="waypoints"):
        op.plan(grid, s, g, algorithm="iga", encoding="cells", waypoints=4)


def test_cli_encoding_and_gap_split(tmp_path, capsys, rooms):
    grid, s, g = rooms
    path = tmp_path / "rooms.npy"
    np.save(path, grid.occ[::-1].astype(np.uint8))   # file rows are top-first
    code = main(["plan", str(path), "--start", str(s[0]), str(s[1]), "--goal", str(g[0]), str(g[1]),
                 "--algo", "pso", "--encoding", "general", "--iters", "40", "--json"])
    d = json.loads(capsys.readouterr().out.strip())
    assert code == 0 and d["encoding"] == "general" and d["feasible"]
    assert d["gap"] == pytest.approx(d["class_gap"] + d["in_class_gap"], abs=1e-12)
    assert d["class_length"] <= d["length"] + 1e-9


def test_map_generator_is_seeded_and_checks_its_arguments():
    for kind in MAP_KINDS:
        a, b = generate_map(kind, 32, seed=3), generate_map(kind, 32, seed=3)
        assert np.array_equal(a.occ, b.occ)
        assert not np.array_equal(a.occ, generate_map(kind, 32, seed=4).occ)
    dens = generate_map("random", 64, seed=0, density=0.25).occ.mean()
    assert 0.2 < dens < 0.3
    with pytest.raises(ParameterError, match="map kind"):
        generate_map("forest", 32)
    with pytest.raises(ParameterError, match="size"):
        generate_map("maze", 4)


def test_corridor_start_decodes_to_the_geodesic_through_its_node(rooms):
    grid, s, g = rooms
    enc = GeneralPath(grid, s, g, m=4)
    X = enc.sample_corridors(25, np.random.default_rng(3))
    L = enc.leg_length(X)
    S, G = len(enc.points) - 2, len(enc.points) - 1
    # each individual is start -> v -> goal along geodesics: its length is D[S, v] + D[v, G] for its
    # corridor node v, and no via node lies off that path (which would make it longer still)
    idx = enc.nodes_of(X)
    through = enc.table[S, idx[:, 1:-1]] + enc.table[idx[:, 1:-1], G]
    assert np.allclose(L, through.max(axis=1))
    assert np.all(through <= L[:, None] + 1e-9)
    assert np.array_equal(X, enc.sample_corridors(25, np.random.default_rng(3)))


def test_general_encoding_on_a_circle_world():
    world = op.CircleWorld(bounds=(0, 0, 10, 10), circles=[(5, 5, 1.5), (2.5, 7, 0.8), (7.5, 3, 1.0)])
    s, g = (0.5, 5.0), (9.5, 5.0)
    r = op.plan(world, s, g, algorithm="pso", encoding="general", max_evals=2000, seed=0)
    exact = op.shortest_path(world, s, g, method="visibility").length
    assert r.feasible and r.encoding == "general"
    assert exact - 1e-6 <= r.length <= exact * (1 / np.cos(np.pi / 32)) + 1e-6   # polygon sides, not arcs


def test_legs_between_roadmap_parts_run_through_the_start():
    """The start sees corners of two parts of the roadmap that see no corner of each other
    (seeded random map): the legs between them run through the start instead of raising
    'roadmap leg between unconnected nodes', and the planner reaches the exact optimum."""
    from optplan.formulations.encodings import GeneralPath
    from optplan.world.roadmap import walk_legs
    from optplan.worldgen.maps import generate_map

    grid = generate_map("random", 32, 1030)
    s, g = np.array([2.389801788440688, 30.18134265615101]), np.array([20.412691713480836, 2.09220741242778])
    enc = GeneralPath(grid, s, g)
    r = enc.reachable
    legs = walk_legs(enc.succ, np.repeat(r, len(r)), np.tile(r, len(r)))
    P = enc.points[legs]
    length = np.hypot(*np.diff(P, axis=1).transpose(2, 0, 1)).sum(axis=1)
    np.testing.assert_allclose(length, enc.table[np.repeat(r, len(r)), np.tile(r, len(r))], rtol=1e-12)
    res = op.plan(grid, s, g, algorithm="pso", encoding="general", max_evals=3000, iters=None, pop=20, seed=0)
    best = op.shortest_path(grid, s, g, method="visibility").length
    assert res.feasible and res.length == pytest.approx(best, rel=1e-9)


def test_the_default_encoding_is_general_and_paper_is_one_word_away():
    grid = generate_map("random", 16, seed=5, density=0.1)
    s, g = map_query(grid, seed=5)
    default = op.plan(grid, s, g, algorithm="missa", max_evals=600, seed=0)
    assert default.encoding == "general" and default.feasible
    paper = op.plan(grid, s, g, algorithm="missa", encoding="paper", max_evals=600, seed=0)
    columns = op.plan(grid, s, g, algorithm="missa", encoding="columns", max_evals=600, seed=0)
    assert paper.encoding == "columns"
    np.testing.assert_array_equal(paper.path, columns.path)
    # yang2023's planners: the paper's encoding is spline handles; li2023's GAs keep their chromosome
    assert op.plan(grid, s, g, algorithm="ipso", encoding="paper", max_evals=600, seed=0).encoding == "spline"
    assert op.plan(grid, s, g, algorithm="iga", encoding="paper", pop=10, iters=5, seed=0).algorithm == "iga"
    with pytest.raises(ParameterError, match="paper"):
        op.plan(grid, s, g, algorithm="missa", encoding="papers", max_evals=600)


def test_the_cli_plans_with_the_general_encoding_unless_told(tmp_path, capsys):
    grid = generate_map("random", 16, seed=5, density=0.1)
    s, g = map_query(grid, seed=5)
    path = tmp_path / "m.txt"
    np.savetxt(path, grid.occ[::-1].astype(int), fmt="%d")
    base = ["plan", str(path), "--start", str(s[0]), str(s[1]), "--goal", str(g[0]), str(g[1]), "--algo", "missa",
            "--iters", "20", "--json"]
    assert main(base) == 0
    assert json.loads(capsys.readouterr().out)["encoding"] == "general"
    assert main(base + ["--encoding", "paper"]) == 0
    assert json.loads(capsys.readouterr().out)["encoding"] == "columns"
