"""Issue 43: qp-dwa's clutter mechanisms (path samples, path critics judged to the stop, path
creep) are its defaults where the global path is tight, a rule that reads the world the planner
sees, not a scenario family's name."""
from __future__ import annotations

import math

import numpy as np
import pytest

import optplan as op
from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.local.creep import PathCreep
from optplan.local.qp_dwa import TIGHT_PATH_PARAMS, path_is_tight
from optplan.world.grid import GridMap
from optplan.world.robot import RobotSpec, RobotState
from optplan.world.scenario import Scenario

RES = 0.15
# a disc of BARN's size and limits, built here so that nothing names a generated family
ROBOT = RobotSpec(model="unicycle", radius=0.2, v_max=0.5, w_max=math.radians(90.0), a_max=1.0,
                  alpha_max=math.radians(180.0))
START, GOAL = (0.6, 2.4), (3.9, 0.6)


def gap_world() -> GridMap:
    """Two blocks whose facing corners are 2 x 2 cells apart: the only way from left to right
    is the diagonal gap between them, 1.2 cm wider than the robot on each side."""
    occ = np.zeros((22, 30), dtype=bool)
    occ[0:10, 10:12] = True
    occ[12:22, 14:16] = True
    return GridMap(occ[::-1], RES)


def open_world() -> GridMap:
    """The same ground with no obstacle on it."""
    return GridMap(np.zeros((22, 30), dtype=bool), RES)


def context(world: GridMap, at=START, heading: float = 0.0) -> LocalContext:
    path = op.shortest_path(world, START, GOAL, method="astar", clearance=ROBOT.radius).path
    return LocalContext(state=RobotState(at[0], at[1], heading), subgoal=np.asarray(GOAL), goal=np.asarray(GOAL),
                        global_path=np.asarray(path), static_distance=world.clearance, dynamic=np.zeros((0, 5)),
                        dt=0.1, distance_error=0.0045)


def scenario(world: GridMap) -> Scenario:
    return Scenario(world, ROBOT, np.array([*START, 0.0]), np.array(GOAL), sensor_range=2.5, dt=0.1,
                    time_limit=60.0, goal_tolerance=0.2, name="two-blocks")


def test_the_rule_reads_how_much_of_the_path_near_the_robot_runs_close_to_obstacles():
    tight, open_ = context(gap_world()), context(open_world())
    assert path_is_tight(tight, ROBOT.radius, 0.15, 3.0)            # the gap lies within 3 m of path
    assert not path_is_tight(open_, ROBOT.radius, 0.15, 3.0)
    assert not path_is_tight(tight, ROBOT.radius, 0.15, 0.3)        # ... but not within 0.3 m
    assert not path_is_tight(tight, ROBOT.radius, 0.0, 3.0)         # gap 0: nowhere
    assert path_is_tight(open_, ROBOT.radius, math.inf, 3.0)        # gap inf: everywhere
    # sensed beside the straight path: one disc (r 0.3 m) 0.1 m from the footprint is passed
    # within 0.15 m over less than half the stretch (not tight); walls along both sides 0.1 m
    # from the footprint are (tight), but not when asking for 5 cm; a disc sensed on the path
    # blocks it (not tight: the navigator re-plans it)
    mid = (np.asarray(START) + np.asarray(GOAL)) / 2
    u = (np.asarray(GOAL) - np.asarray(START)) / math.dist(START, GOAL)
    normal = np.array([-u[1], u[0]])
    off = ROBOT.radius + 0.1

    def disc(c):
        return lambda p: np.hypot(*(p - c).T) - 0.3

    def wall(side):   # a half-plane edge parallel to the path, ``off`` metres to one side
        return lambda p: (p - np.asarray(START)) @ (side * normal) * -1 + off

    cases = (([disc(mid + (off + 0.3) * normal)], 0.15, False), ([wall(1), wall(-1)], 0.15, True),
             ([wall(1), wall(-1)], 0.05, False), ([disc(mid)], 0.15, False))
    for parts, gap, tight_there in cases:
        def sensed(p, parts=parts):
            p = np.asarray(p, dtype=float).reshape(-1, 2)
            return np.minimum(open_world().clearance(p), np.min([f(p) for f in parts], axis=0))

        ctx = LocalContext(**{**open_.__dict__, "static_distance": sensed, "global_path": np.array([START, GOAL])})
        assert path_is_tight(ctx, ROBOT.radius, gap, 3.0) is tight_there


def _step_config(world: GridMap, **params):
    planner = make_local_planner("qp-dwa", ROBOT, 0.1, **params)
    ctx = context(world, at=(1.3, 1.9), heading=-0.6)
    planner.reset(ctx.state, ctx.global_path)
    cmd = planner.command(ctx)
    until_stop = {c.name: c.until_stop for c, _ in planner.terms if hasattr(c, "until_stop")}
    creep = any(isinstance(m, PathCreep) for m in planner.roles.takes_over)
    return cmd.info, planner.options["path_samples"], until_stop, creep


def test_the_same_default_uses_the_mechanisms_on_a_tight_path_and_not_on_an_open_one():
    info, samples, until_stop, creep = _step_config(gap_world())
    assert info["tight"] is True
    assert samples == tuple(TIGHT_PATH_PARAMS["path_samples"]) and creep
    assert until_stop == {"path_progress": True, "path_deviation": True, "path_heading": True}
    tight_samples = info["n_samples"]
    info, samples, until_stop, creep = _step_config(open_world())
    assert info["tight"] is False
    assert samples == () and not creep and not any(until_stop.values())
    # the path-following samples are rolled out only where the path is tight
    assert info["n_samples"] < tight_samples


def test_a_parameter_the_user_gives_applies_everywhere():
    info, samples, until_stop, creep = _step_config(gap_world(), path_samples=(), path_creep=False,
                                                    path_heading={"until_stop": False})
    assert info["tight"] is True and samples == () and not creep
    assert until_stop == {"path_progress": True, "path_deviation": True, "path_heading": False}
    info, samples, until_stop, creep = _step_config(open_world(), path_samples=(0.5,), path_creep={})
    assert info["tight"] is False and samples == (0.5,) and creep
    # nothing left to the rule: the planner does not evaluate it
    off = {"path_samples": (), "path_creep": False, **{k: {"until_stop": False} for k in
                                                         ("path_progress", "path_heading", "path_deviation")}}
    assert "tight" not in _step_config(gap_world(), **off)[0]


def test_bad_rule_options_say_what_is_wrong():
    with pytest.raises(op.ParameterError, match="tight_gap"):
        make_local_planner("qp-dwa", ROBOT, 0.1, tight_gap=-0.1)
    with pytest.raises(op.ParameterError, match="tight_ahead"):
        make_local_planner("qp-dwa", ROBOT, 0.1, tight_ahead="far")
    make_local_planner("qp-dwa", ROBOT, 0.1, tight_gap=math.inf)


# the window's static margin made wider than the gap's 1.2 cm to spare (as in test_local_creep),
# so that only the creep can take the robot through it
NARROW = {"swept_margin": 0.01}


def test_qp_dwa_by_default_creeps_through_a_gap_the_window_stops_in_front_of():
    modes = []
    res = op.simulate(scenario(gap_world()), local_planner="qp-dwa", seed=0, planner_params=NARROW,
                      progress=lambda t, s, info: modes.append(info["command"].info.get("mode")))
    assert res.reached and res.collisions == 0, res.message
    assert "creep-drive" in modes
    # the same world with the rule switched off: the window alone stops in front of the gap
    res = op.simulate(scenario(gap_world()), local_planner="qp-dwa", seed=0,
                      planner_params={**NARROW, "tight_gap": 0.0})
    assert res.status == "timeout" and not res.reached and res.collisions == 0


def test_on_open_ground_the_default_drives_as_without_the_mechanisms():
    sc = scenario(open_world())
    default = op.simulate(sc, local_planner="qp-dwa", seed=0)
    off = op.simulate(sc, local_planner="qp-dwa", seed=0, planner_params={"tight_gap": 0.0})
    assert default.reached and np.array_equal(default.trajectory, off.trajectory)


def test_a_clutter_family_lays_no_qp_dwa_parameters_under_the_callers():
    from optplan.worldgen.clutter import family_options

    assert "qp-dwa" not in family_options("clutter").get("local_params", {})
