"""qp-dwa's recursive feasibility check: whatever the QP (or the sampler) proposes, the
command sent leaves a safe continuation - a stop that stays clear of the static map and
the predicted movers, or holding the command through a free horizon (issue 27 item 3;
the ``continuation_check`` option, off by default)."""
from __future__ import annotations

import numpy as np

from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.world.robot import RobotState
from optplan.worldgen.clutter import BARN_ROBOT

DT = 0.1
R = BARN_ROBOT.radius
WALL_X = R + 0.14  # 14 cm between the robot's front and a wall across its way


def _ctx(v=0.5, dynamic=None, wall_x=WALL_X):
    return LocalContext(state=RobotState(0.0, 0.0, 0.0, v=v), subgoal=np.array([0.1, 0.0]), goal=np.array([0.1, 0.0]),
                        global_path=np.array([[0.0, 0.0], [0.1, 0.0]]),
                        static_distance=lambda P: wall_x - np.asarray(P)[..., 0],
                        dynamic=np.zeros((0, 5)) if dynamic is None else np.asarray(dynamic, float), dt=DT)


def _stop_distance(v: float) -> float:
    """Shortest distance (m) a robot commanded ``v`` for one period can stop within, with
    any command sequence that respects a_max (held for one period each)."""
    d, a = v * DT, BARN_ROBOT.a_max
    while v > 1e-12:
        v = max(v - a * DT, 0.0)
        d += v * DT
    return d


def _planner(refined):
    """qp-dwa whose QP always proposes ``refined`` (a stand-in for a wrong refinement)."""
    planner = make_local_planner("qp-dwa", BARN_ROBOT, DT, continuation_check=True)
    planner.reset(_ctx().state, _ctx().global_path)

    def refine(ctx, window, u0, step, info):
        info["qp"] = "solved"
        return refined
    planner.refine = refine
    return planner


def test_a_refined_command_without_a_safe_stop_is_not_sent():
    planner = _planner((0.5, 0.0, 0.0))           # full speed on, into the wall
    cmd = planner.command(_ctx())
    assert cmd.info["continuation"] in ("brake", "cross")
    assert cmd.info["continuation_fallback"] in ("sampled", "brake")
    assert cmd.info["qp"].startswith("fallback")
    # independent check: the robot can still stop before the wall after this command
    assert _stop_distance(cmd.v) < WALL_X - R


def test_without_the_check_the_same_refinement_would_be_sent_and_hit_the_wall():
    planner = _planner((0.5, 0.0, 0.0))
    planner.safe_continuation = lambda ctx, out: "brake"  # the check switched off
    cmd = planner.command(_ctx())
    assert cmd.v > 0.49 and _stop_distance(cmd.v) > WALL_X - R


def test_a_refinement_with_a_safe_stop_is_kept():
    planner = _planner((0.3, 0.0, 0.0))
    cmd = planner.command(_ctx(wall_x=5.0))
    assert cmd.info["continuation"] == "brake" and "continuation_fallback" not in cmd.info
    assert cmd.info["target"][0] == 0.3


def test_a_stop_in_a_movers_way_is_not_a_safe_continuation():
    # open map; a mover 1 m ahead drives at the robot at 0.4 m/s: stopping there is hit,
    # so braking is not a safe continuation, and holding the course is not either
    planner = make_local_planner("qp-dwa", BARN_ROBOT, DT, continuation_check=True)
    ctx = _ctx(v=0.0, wall_x=50.0, dynamic=[[1.0, 0.0, -0.4, 0.0, 0.15]])
    planner.reset(ctx.state, ctx.global_path)
    out, _ = planner.limiter.step(np.array([0.0, 0.0]))
    assert planner.safe_continuation(ctx, out) == ""
    # the same mover driving away: standing is safe
    away = _ctx(v=0.0, wall_x=50.0, dynamic=[[1.0, 0.0, 0.4, 0.0, 0.15]])
    assert planner.safe_continuation(away, out) == "brake"


def test_the_check_is_off_by_default_and_then_changes_nothing():
    planner = make_local_planner("qp-dwa", BARN_ROBOT, DT)
    planner.reset(_ctx().state, _ctx().global_path)
    assert planner.command(_ctx()).info["continuation"] == "unchecked"
