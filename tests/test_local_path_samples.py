"""Issue 27: samples that follow the global path, critics judged up to the stop before an
obstacle, and a static margin sized by the distance field's error."""
from __future__ import annotations

import math

import numpy as np
import pytest

import optplan as op
from optplan.errors import ParameterError
from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.local.critics import PathProgress
from optplan.local.rollout import assess, rollout_ramped, rollout_tracking
from optplan.world.fields import grid_distance_field
from optplan.world.robot import RobotSpec, RobotState

DT = 0.1
ROBOT = RobotSpec(model="unicycle", radius=0.2, v_max=0.5, w_max=math.radians(90), a_max=1.0,
                  alpha_max=math.radians(180))


def _ctx(state, path, field):
    path = np.asarray(path, float)
    return LocalContext(state=state, subgoal=path[-1], goal=path[-1], global_path=path, static_distance=field,
                        dynamic=np.zeros((0, 5)), dt=DT)


def _open(p):
    return np.full(np.shape(p)[:-1], 10.0)


def test_path_samples_follow_a_straight_path_within_the_velocity_and_acceleration_limits():
    st = RobotState(0.0, 0.0, 0.0, 0.1, 0.0)
    roll = rollout_tracking(st, np.array([[0.0, 0.0], [5.0, 0.0]]), np.array([0.25, 0.5]), np.array([0.25, 0.5]),
                            DT, 30, ROBOT)
    assert roll.n == 4 and roll.tracking.all()
    assert np.abs(roll.z.imag).max() < 1e-12                     # on the path
    speed = np.c_[np.full(roll.n, 0.1), roll.profile]
    assert np.all(np.abs(np.diff(speed, axis=1)) <= ROBOT.a_max * DT + 1e-12)
    assert roll.profile[:, -1] == pytest.approx([0.25, 0.25, 0.5, 0.5])  # each reaches its speed
    assert roll.v == pytest.approx(roll.profile[:, 0])           # the command is the first step's


def test_path_samples_turn_in_place_first_when_the_path_lies_behind():
    st = RobotState(0.0, 0.0, math.pi, 0.0, 0.0)                 # facing away from the path
    roll = rollout_tracking(st, np.array([[0.0, 0.0], [5.0, 0.0]]), np.array([0.5]), np.array([0.5]), DT, 30,
                            ROBOT, turn_first=np.array([0.3]))
    w = np.r_[0.0, roll.theta[0] - np.r_[math.pi, roll.theta[0, :-1]]] / DT
    assert np.all(np.abs(np.diff(w)) <= ROBOT.alpha_max * DT + 1e-9) and np.abs(w).max() <= ROBOT.w_max + 1e-12
    turning = np.abs(np.angle(np.exp(1j * roll.theta[0]))) > 0.3
    assert np.all(roll.profile[0][turning] == 0.0)               # no way is made while turning round
    assert roll.z[0, -1].real > 0.3                               # then it drives along the path


def _l_corridor():
    """A corridor 0.6 m wide going right 1.5 m, then up: cells of 0.1 m."""
    rows = np.ones((30, 30), dtype=int)
    rows[1:7, 1:16] = 0       # y 0.1-0.7, x 0.1-1.6 (image rows: top first, flipped below)
    rows[1:29, 10:16] = 0     # x 1.0-1.6 going up
    grid = op.GridMap(rows.astype(bool), 0.1)
    return grid, grid_distance_field(grid)


def test_a_path_sample_takes_a_bend_that_no_constant_arc_takes():
    grid, field = _l_corridor()
    path = [[0.3, 0.4], [1.3, 0.4], [1.3, 2.8]]
    st = RobotState(0.5, 0.4, 0.0, 0.3, 0.0)
    ctx = _ctx(st, path, field)
    arcs = rollout_ramped(st, np.linspace(0.0, 0.5, 11), np.zeros(11), np.linspace(-1.57, 1.57, 21), DT, 30,
                          (1.0, math.pi, 1.0))
    tracks = rollout_tracking(st, np.asarray(path), np.array([0.5, 1.0]) * 0.5, np.array([0.25, 0.5]), DT, 30, ROBOT,
                              turn_first=np.array([math.pi / 2, 0.3]))
    progress = PathProgress(until_stop=True)
    best = {}
    for name, roll in (("arcs", arcs), ("tracks", tracks)):
        step = assess(ctx, ROBOT, roll, margin=0.02, reaction=DT)
        free = step.admissible & (step.static_hit >= roll.z.shape[1])
        best[name] = progress.score(step)[free].max(initial=0.0)
    assert best["tracks"] > 0.9                         # round the bend, clear of the walls
    assert best["arcs"] < best["tracks"] - 0.3          # a constant arc has to stop short of the bend


def test_a_trajectory_into_a_wall_is_credited_only_the_progress_it_can_drive():
    def wall(p):  # a wall across the path: contact once the centre passes x = 0.5
        return 0.7 - np.asarray(p, float)[..., 0]

    st = RobotState(0.0, 0.0, 0.0, 0.5, 0.0)
    ctx = _ctx(st, [[0.0, 0.0], [5.0, 0.0]], wall)
    step = assess(ctx, ROBOT, rollout_ramped(st, np.array([0.5]), np.zeros(1), np.array([0.0]), DT, 30,
                                             (1.0, math.pi, 1.0)), margin=0.02)
    end, _ = step.pose_at_stop()
    assert end[0].real <= 0.5 and np.all(step.held_at_stop()[0, step.static_hit[0]:] == end[0])
    assert PathProgress().score(step)[0] == pytest.approx(1.5)   # judged by its end, through the wall
    assert PathProgress(until_stop=True).score(step)[0] == pytest.approx(end[0].real)


def test_bad_path_sample_options_say_what_is_wrong():
    with pytest.raises(ParameterError, match="path_samples"):
        make_local_planner("qp-dwa", ROBOT, DT, path_samples=[1.5])
    with pytest.raises(ParameterError, match="path_look_aheads"):
        make_local_planner("qp-dwa", ROBOT, DT, path_samples=[0.5], path_look_aheads=[])


def test_the_static_margin_shrinks_to_the_distance_fields_error_where_the_context_gives_it():
    planner = make_local_planner("qp-dwa", ROBOT, DT)
    ctx = _ctx(RobotState(0.0, 0.0, 0.0), [[0.0, 0.0], [1.0, 0.0]], _open)
    assert planner.static_margin(ctx) == planner.options["margin"] == 0.02       # not known: the full margin
    fine = LocalContext(**{**ctx.__dict__, "distance_error": 0.0045})
    assert planner.static_margin(fine) == pytest.approx(0.0045 + planner.options["swept_margin"])
    coarse = LocalContext(**{**ctx.__dict__, "distance_error": 0.03})            # 1 m cells
    assert planner.static_margin(coarse) == 0.02


def test_the_simulated_field_overestimates_clutter_clearance_by_no_more_than_its_stated_error():
    from optplan.sim.environment import SimEnvironment, box_distance
    from optplan.worldgen.clutter import clutter_scenario

    sc = clutter_scenario(3)
    env, g = SimEnvironment(sc), sc.world
    iy, ix = np.nonzero(g.occ)
    lo = g.to_world(np.stack([ix, iy], axis=1).astype(float))
    p = np.random.default_rng(0).uniform([0, 0], [g.width * g.resolution, g.height * g.resolution], (20000, 2))
    exact = box_distance(p, lo, g.resolution)
    outside = exact > 0
    assert np.max(env.static_distance(p)[outside] - exact[outside]) <= env.distance_error


@pytest.mark.parametrize("seed", [0, 23])
def test_qp_dwa_passes_the_gaps_where_development_worlds_froze(seed):
    # seed 0: every arc into the passage ahead met a block and the QP braked it to a stop;
    # seed 23: the path threads a gap with 1-2 cm to spare, which the fixed 2 cm margin closed
    res = op.simulate("clutter", local_planner="qp-dwa", seed=seed)
    assert res.reached and res.collisions == 0, res.message
    assert res.max_abs_accel <= ROBOT.a_max * (1 + 1e-6) and res.max_abs_ang_accel <= ROBOT.alpha_max * (1 + 1e-6)
