"""The tube stage of refine='casadi': changing homotopy class near the seed, honestly."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.cli import main as cli_main
from optplan.solvers.nlp import smooth_path
from optplan.solvers.refine import refine_path, refine_result
from optplan.solvers.tube import (cells_within, default_tube_radius, distance_to_polyline, obstacle_width,
                                  refine_in_tube, tube_path)
from optplan.world.metrics import path_length


def block_world():
    """12 x 7 cells, a 3 x 3 block in columns 5-7, rows 1-3: from (0.5, 3.5) to (11.5, 3.5)
    the short way passes above it (0.5 m up), the long way below (2.5 m down)."""
    occ = np.zeros((7, 12), dtype=bool)
    occ[1:4, 5:8] = True
    return op.GridMap(occ), np.array([0.5, 3.5]), np.array([11.5, 3.5])


LONG_WAY = np.array([[0.5, 3.5], [4.5, 0.5], [8.5, 0.5], [11.5, 3.5]])


def test_grid_seed_on_the_long_side_moves_to_the_short_side():
    world, s, g = block_world()
    assert op.validate_path(world, LONG_WAY)
    opt = op.shortest_path(world, s, g, method="visibility").length
    assert obstacle_width(world) == pytest.approx(3.0) and default_tube_radius(world) == pytest.approx(6.0)
    local = refine_path(world, LONG_WAY, "casadi", tube_radius=0)
    tube = refine_path(world, LONG_WAY, "casadi")                    # the default tube
    assert local.success and path_length(local.path) > 1.05 * opt   # stays below the block
    assert tube.success and op.validate_path(world, tube.path)
    assert opt - 1e-9 <= path_length(tube.path) <= 1.01 * opt
    assert np.all(tube.path[:, 1] >= 3.5 - 1e-6)                     # it passes above
    assert "shorter" in tube.message
    # through op.plan's result: the same, validated by make_plan_result
    seed_result = op.PlanResult("seed", LONG_WAY, True, float(path_length(LONG_WAY)), 0.0, 0, 0.0, 0.0)
    res = refine_result(world, seed_result)
    assert res.refined and res.feasible and res.length <= 1.01 * opt


def test_radius_zero_is_the_purely_local_smoother():
    world, _, _ = block_world()
    old = smooth_path(world, LONG_WAY)
    for new in (refine_path(world, LONG_WAY, "casadi", tube_radius=0.0),
                refine_in_tube(world, LONG_WAY, smooth_path, 0.0)):
        # same problem, same solver; IPOPT may differ in the last bits between calls in one
        # process (about 1e-13 m, seen when other tests ran casadi before this one)
        np.testing.assert_allclose(new.path, old.path, rtol=0, atol=1e-9)
        assert new.success == old.success and new.message == old.message
    # qp stays purely local by default; it takes the same option
    qp_default = refine_path(world, LONG_WAY, "qp")
    qp_zero = refine_path(world, LONG_WAY, "qp", tube_radius=0)
    np.testing.assert_array_equal(qp_default.path, qp_zero.path)
    qp_tube = refine_path(world, LONG_WAY, "qp", tube_radius=6.0)
    assert qp_tube.success and path_length(qp_tube.path) < path_length(qp_zero.path)


def test_circle_world_seed_on_the_long_side():
    world = op.CircleWorld((0, 0, 10, 10), [(5.0, 4.6, 1.0)])
    s, g = (1.0, 5.0), (9.0, 5.0)
    seed = np.array([s, (5.0, 3.2), g])                              # below the circle: the long side
    assert op.validate_path(world, seed)
    opt = op.shortest_path(world, s, g, method="visibility").length
    local = refine_path(world, seed, "casadi", tube_radius=0)
    tube = refine_path(world, seed, "casadi")                        # 2 diameters = 4 m
    assert path_length(local.path) > 1.03 * opt
    assert tube.success and op.validate_path(world, tube.path)
    assert opt - 1e-9 <= path_length(tube.path) <= 1.01 * opt
    # the raster path is collision-free in the circle world itself
    t = tube_path(world, seed, default_tube_radius(world))
    assert t.found and op.validate_path(world, t.path) and t.grid.resolution == pytest.approx(0.05)


def test_a_tube_without_a_path_falls_back_with_the_reason():
    world, s, g = block_world()
    # 0.2 m around a diagonal seed leaves the cells it crosses disconnected
    seed = np.array([[0.5, 0.5], [4.5, 6.5]])
    t = tube_path(world, seed, 0.2)
    assert not t.found and t.path is None and "no path within 0.2 m" in t.message
    r = refine_in_tube(world, seed, smooth_path, 0.2)
    assert r.success and "no path within 0.2 m" in r.message
    np.testing.assert_allclose(r.path, smooth_path(world, seed).path, atol=1e-9)  # the seed's own smoothing
    # circle world: a start touching a circle has its raster cell blocked
    cw = op.CircleWorld((0, 0, 10, 10), [(3.0, 5.0, 1.0)])
    seed = np.array([[2.0, 5.0], [2.0, 8.0], [9.0, 8.0]])
    t = tube_path(cw, seed, 2.0)
    assert not t.found and "start cell" in t.message
    r = refine_path(cw, seed, "casadi", tube_radius=2.0)
    assert r.success and op.validate_path(cw, r.path) and "start cell" in r.message


def test_blocked_goal_and_bad_radius_are_refused():
    world, s, _ = block_world()
    r = refine_path(world, np.array([s, [6.5, 2.5]]), "casadi")      # goal inside the block
    assert not r.success and "goal" in r.message
    with pytest.raises(op.OptplanError, match="tube_radius"):
        refine_path(world, LONG_WAY, "casadi", tube_radius=-1.0)
    with pytest.raises(op.OptplanError, match="tube_radius"):
        op.plan(world, s, (11.5, 3.5), algorithm="astar", refine="casadi", refine_options={"tube_radius": "big"})
    assert cli_main(["plan", "li2023_11", "--start", "0.5", "0.5", "--goal", "10.5", "10.5", "--tube-radius", "2"]) == 2


def test_reproducible_and_exposed_through_plan():
    world, s, g = block_world()
    a = op.plan(world, s, g, algorithm="pso", seed=3, pop=10, iters=20, refine="casadi",
                refine_options={"tube_radius": 6.0})
    b = op.plan(world, s, g, algorithm="pso", seed=3, pop=10, iters=20, refine="casadi",
                refine_options={"tube_radius": 6.0})
    # equal up to rounding: the QP smoother reuses a cached OSQP instance per size, and its first
    # solve in a process differs from later ones in the last bits (~1e-13 m)
    np.testing.assert_allclose(a.path, b.path, rtol=0, atol=1e-9)
    assert a.refined and a.feasible and a.message == b.message
    t1, t2 = tube_path(world, LONG_WAY, 6.0), tube_path(world, LONG_WAY, 6.0)
    np.testing.assert_array_equal(t1.path, t2.path)


def test_tube_mask_is_the_exact_point_to_polyline_rule():
    rng = np.random.default_rng(0)
    seed = np.cumsum(rng.uniform(-1.5, 3.0, size=(12, 2)), axis=0)
    for h, radius in ((1.0, 2.0), (0.25, 1.3), (0.1, 0.45)):
        W = H = int(30 / h)
        mask = cells_within(W, H, h, (0.0, 0.0), seed, radius)
        iy, ix = np.mgrid[0:H, 0:W]
        centres = (np.stack([ix.ravel(), iy.ravel()], axis=1) + 0.5) * h
        np.testing.assert_array_equal(mask.ravel(), distance_to_polyline(centres, seed) <= radius)
