"""qp-dwa: the QP refinement (OSQP) with its fallback, and the Ruckig limits on the commands."""
from __future__ import annotations

import math

import numpy as np
import pytest

import optplan as op
from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.local.limiter import RuckigLimiter
from optplan.world.fields import grid_distance_field
from optplan.world.robot import RobotSpec, RobotState

DT = 0.1
ROWS = ["0000000000",
        "0000000000",
        "0001100000",
        "0001100000",
        "0000000000",
        "0000000000",
        "0000000000",
        "0000000000",
        "0000000000",
        "0000000000"]


@pytest.fixture(scope="module")
def field():
    return grid_distance_field(op.GridMap.from_rows([[int(c) for c in r] for r in ROWS]))


def ctx_at(field, state, goal, movers=(), t=0.0):
    goal = np.asarray(goal, float)
    return LocalContext(state=state, subgoal=goal, goal=goal, global_path=np.array([[0.5, state.y], goal]),
                        static_distance=field, dynamic=np.asarray(movers, float).reshape(-1, 5), dt=DT, t=t)


def drive(field, robot, steps=70, **params):
    """A small closed loop (unicycle or omni, the simulator's motion model) past a block and
    across a mover's way; returns the commanded velocities, robot at rest first."""
    planner = make_local_planner("qp-dwa", robot, DT, **params)
    st = RobotState(0.8, 8.45, 0.0)  # along the top of the block, 0.25 m (edge to edge) from it
    goal = (9.0, 8.45)
    mover0 = np.array([6.0, 5.5, 0.0, 0.45, 0.3])
    planner.reset(st, np.array([[0.8, 8.45], goal]))
    vel = [(0.0, 0.0, 0.0)]
    for k in range(steps):
        t = k * DT
        mover = mover0 + np.r_[mover0[2:4] * t, 0.0, 0.0, 0.0]
        cmd = planner.command(ctx_at(field, st, goal, [mover], t))
        c, s = math.cos(st.theta), math.sin(st.theta)
        st = RobotState(st.x + (cmd.v * c - cmd.vy * s) * DT, st.y + (cmd.v * s + cmd.vy * c) * DT,
                        st.theta + cmd.w * DT, cmd.v, cmd.w, cmd.vy)
        vel.append((cmd.v, cmd.w, cmd.vy))
    return np.array(vel), st, planner


@pytest.mark.parametrize("jerk", [None, 1.0])
def test_accelerations_and_jerk_within_limits(field, jerk):
    robot = RobotSpec(jerk_max=jerk)
    vel, end, planner = drive(field, robot)
    acc = np.diff(vel, axis=0) / DT  # as the simulator measures them
    assert np.abs(acc[:, 0]).max() <= robot.a_max + 1e-9
    assert np.abs(acc[:, 1]).max() <= robot.alpha_max + 1e-9
    assert end.x > 3.0  # it drove on along the block
    if jerk is not None:
        j = np.diff(acc, axis=0) / DT
        assert np.abs(j[:, 0]).max() <= robot.jerk_max + 1e-9
        assert np.abs(j[:, 1]).max() <= planner.jerk[1] + 1e-9
    assert len(planner.qp_times_us) > 0  # the QP was active along the way


def test_omni_acceleration_vector_within_limits(field):
    robot = RobotSpec(model="omni", vy_max=0.4, jerk_max=1.5)
    vel, _, _ = drive(field, robot, steps=40)
    dv = np.hypot(np.diff(vel[:, 0]), np.diff(vel[:, 2])) / DT
    assert dv.max() <= robot.a_max + 1e-9


def test_qp_solves_and_falls_back_at_max_iter(field):
    robot = RobotSpec()
    st = RobotState(2.5, 8.45, 0.0, 0.4, 0.0)  # 0.25 m (edge to edge) above a block, driving along it
    ctx = ctx_at(field, st, (9.0, 8.45))
    solved = make_local_planner("qp-dwa", robot, DT)
    solved.reset(st, ctx.global_path)
    info = solved.command(ctx).info
    assert info["qp"] == "solved" and info["qp_rows"] > 0
    capped = make_local_planner("qp-dwa", robot, DT, qp_max_iter=1)
    capped.reset(st, ctx.global_path)
    step = capped.evaluate(ctx, capped.window(ctx))
    best, _ = capped.choose(step)
    cmd = capped.command(ctx)
    assert cmd.info["qp"].startswith("fallback: OSQP status")
    sampled = [step.roll.v[best], step.roll.w[best], step.roll.vy[best]]
    assert cmd.info["target"] == pytest.approx(sampled)  # the best sampled command is used


def test_ruckig_limiter_respects_acceleration_and_jerk():
    lim = RuckigLimiter(DT, [0.3, 0.8], [1.0, 3.0])
    lim.reset([0.0, 0.0])
    v = [np.zeros(2)]
    for target in [[1.0, 0.5]] * 15 + [[0.0, -0.5]] * 25:
        out, result = lim.step(target)
        assert result in ("Working", "Finished")
        v.append(out)
    a = np.diff(np.array(v), axis=0) / DT
    assert (np.abs(a) <= np.array([0.3, 0.8]) + 1e-9).all()
    assert (np.abs(np.diff(a, axis=0)) / DT <= np.array([1.0, 3.0]) + 1e-9).all()
    assert v[-1] == pytest.approx([0.0, -0.5], abs=1e-6)
