"""refine='casadi' with tube_radius=0 is local: it keeps the seed's homotopy class (issue 26)."""
from __future__ import annotations

import numpy as np

import optplan as op

from optplan.solvers.homotopy import class_shortest_path
from optplan.solvers.nlp import smooth_path
from optplan.solvers.refine import refine_path
from optplan.world.geometry import validate_path
from optplan.world.metrics import path_length
from optplan.world.roadmap import Roadmap, h_signature
from optplan.worldgen.maps import generate_map

# a taut seed on a 20 % random map that the bare NLP carried across a one-cell obstacle
# (cell (6, 15)) into a class 2.8 % longer (found by benchmarks/general_planning.py)
SEED = np.array([[0.5, 3.5], [3.5, 11.5], [7.5, 19.5]])


def tunnel_map():
    return generate_map("random", 20, seed=7050, density=0.20)


def test_h_signature_is_the_roadmaps():
    grid = tunnel_map()
    rm = Roadmap.of(grid)
    for P in (SEED, np.array([[0.5, 3.5], [7.0, 15.0], [7.5, 19.5]])):
        assert np.array_equal(h_signature(grid, P), rm.signature(P))


def test_casadi_local_refinement_keeps_the_seed_class_and_reaches_its_optimum():
    grid = tunnel_map()
    assert validate_path(grid, SEED)
    bare = smooth_path(grid, SEED, 0.0)
    out = refine_path(grid, SEED, "casadi", tube_radius=0.0)
    assert out.success and validate_path(grid, out.path)
    target = h_signature(grid, SEED)
    assert np.array_equal(h_signature(grid, out.path), target)
    _, C, _ = class_shortest_path(grid, SEED[0], SEED[-1], SEED)
    assert path_length(out.path) <= 1.01 * C
    if not np.array_equal(h_signature(grid, bare.path), target):  # the case the correction is for
        assert "corridor QP" in out.message


def test_in_class_result_is_the_nlps_own():
    occ = np.zeros((7, 12), dtype=bool)
    occ[1:4, 5:8] = True
    grid = op.GridMap(occ)
    seed = np.array([[0.5, 3.5], [4.5, 0.5], [8.5, 0.5], [11.5, 3.5]])  # below the block, the long way
    bare = smooth_path(grid, seed, 0.0)
    out = refine_path(grid, seed, "casadi", tube_radius=0.0)
    # the same solve (a first solve can differ from later ones in the last bits)
    assert bare.success and np.allclose(out.path, bare.path, rtol=0, atol=1e-9) and out.message == bare.message
    assert np.array_equal(h_signature(grid, out.path), h_signature(grid, seed))
