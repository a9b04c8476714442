"""qp-dwa: the QP refinement (OSQP) with its fallback, and the Ruckig limits on the commands."""
from __future__ import annotations

import math

import numpy as np
import pytest

import optplan as op
from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.local.limiter import RuckigLimiter
from optplan.local.qp_dwa import qp_outcome
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
    # a margin wider than the 0.25 m the robot keeps from the block: the QP has rows to meet
    # (with the default 0.15 m every row holds at the sample and the QP is not run)
    vel, end, planner = drive(field, robot, qp_margin=0.3)
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
    # arcs only: the path-following sample straight along the path would win, and it is not
    # refined; a 0.3 m margin, more than the robot keeps from the block, gives the QP work
    solved = make_local_planner("qp-dwa", robot, DT, path_samples=(), qp_margin=0.3)
    solved.reset(st, ctx.global_path)
    info = solved.command(ctx).info
    assert info["qp"] == "solved" and info["qp_rows"] > 0 and info["qp_change"] > 1e-3
    capped = make_local_planner("qp-dwa", robot, DT, qp_max_iter=1, path_samples=(), qp_margin=0.3)
    capped.reset(st, ctx.global_path)
    step = capped.evaluate(ctx, capped.window(ctx))
    best, _ = capped.choose(step)
    cmd = capped.command(ctx)
    assert cmd.info["qp"].startswith("fallback: OSQP status")
    sampled = [step.roll.v[best], step.roll.w[best], step.roll.vy[best]]
    assert cmd.info["target"] == pytest.approx(sampled)  # the best sampled command is used


def test_qp_is_not_run_when_the_sample_meets_every_row(field):
    """A row within qp_activate that the sample already meets by qp_margin leaves the sample
    the QP's optimum: the QP is not run and the sampled command is the target, exactly."""
    robot = RobotSpec()
    st = RobotState(2.5, 8.45, 0.0, 0.4, 0.0)  # 0.25 m above the block: within 0.6 m, beyond 0.15 m
    ctx = ctx_at(field, st, (9.0, 8.45))
    planner = make_local_planner("qp-dwa", robot, DT, path_samples=())
    planner.reset(st, ctx.global_path)
    step = planner.evaluate(ctx, planner.window(ctx))
    best, _ = planner.choose(step)
    grads, gaps, margins = planner._rows(ctx, step, best)
    assert len(gaps) > 0 and np.all(gaps >= margins)
    cmd = planner.command(ctx)
    assert cmd.info["qp"] == "rows hold at the sample" and qp_outcome(cmd.info) == "not run"
    assert cmd.info["target"] == [step.roll.v[best], step.roll.w[best], step.roll.vy[best]]
    assert planner.qp_times_us == []


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


def test_lean_osqp_calls_match_the_public_api():
    """The direct calls of ``LeanOSQP`` (used by qp-dwa's control step) and the public
    ``update/warm_start/solve`` give the same solution on a sequence of updated QPs."""
    import osqp
    import scipy.sparse as sp

    from optplan.local.qp_dwa import LeanOSQP

    rng = np.random.default_rng(3)
    n, m = 3, 5
    P = sp.diags([2.0, 1.0, 1e3]).tocsc()
    pattern = sp.csc_matrix(np.vstack([np.eye(n), np.ones((m, n))]))
    solvers = []
    for direct in (True, False):
        qp = osqp.OSQP()
        qp.setup(P, np.zeros(n), pattern, np.full(n + m, -np.inf), np.full(n + m, np.inf), verbose=False,
                 polishing=False, eps_abs=1e-8, eps_rel=1e-8)
        lean = LeanOSQP(qp)
        if not direct:
            lean.core = None
        solvers.append(lean)
    assert solvers[0].core is not None  # the installed osqp exposes its compiled solver
    for _ in range(5):
        rows = np.vstack([np.eye(n), np.c_[rng.normal(size=(m, n - 1)), np.ones(m)]])
        Ax = rows.T[pattern.T.toarray().astype(bool)]  # column-major values of the fixed pattern
        q = np.r_[rng.normal(size=n - 1), 10.0]
        lower = np.r_[-np.ones(n - 1), 0.0, rng.normal(size=m)]
        upper = np.r_[np.ones(n - 1), np.inf, np.full(m, np.inf)]
        out = [s.step(q, lower.copy(), upper.copy(), Ax, np.zeros(n)) for s in solvers]
        assert out[0][0] == out[1][0] == osqp.SolverStatus.OSQP_SOLVED
        np.testing.assert_allclose(out[0][2], out[1][2], atol=1e-6)
        assert np.all(rows[n:] @ out[0][2] >= lower[n:] - 1e-5)  # constraints hold


def test_qp_outcome_classifies_the_planners_statuses():
    from optplan.local.qp_dwa import qp_outcome
    assert qp_outcome({}) is None
    assert qp_outcome({"qp": "solved"}) == "used"
    assert qp_outcome({"qp": "inactive"}) == qp_outcome({"qp": "path sample"}) == "not run"
    assert qp_outcome({"qp": "fallback: OSQP status 'maximum iterations reached'"}) == "fallback"
    assert qp_outcome({"qp": "fallback: refined command failed the rollout check (not admissible)"}) == "fallback"


TWO_BLOCKS = ["0000000000",
              "0000000000",
              "0001100000",
              "0001100000",
              "0000000110",
              "0000000000",
              "0010000000",
              "0000000000",
              "0000010000",
              "0000000000"]


def test_a_refinement_that_meets_an_unrowed_obstacle_is_relinearised_or_shortened():
    """Heading down past the block at (7-9, 5-6), 0.3 m asked: the first QP's command swings the
    trajectory into a wall no row was linearised at. With one pass the planner takes a quarter
    of that step (the half still comes too close); with two, the second pass adds rows where
    the first command came close and its whole answer keeps its distance. Both commands are
    checked here on the planner's own rollout."""
    field = grid_distance_field(op.GridMap.from_rows([[int(c) for c in r] for r in TWO_BLOCKS]))
    robot = RobotSpec()
    st = RobotState(9.379, 6.642, -1.363, 0.182, 0.0)
    goal = np.array([9.0, 1.0])
    ctx = LocalContext(state=st, subgoal=goal, goal=goal, global_path=np.array([[st.x, st.y], goal]),
                       static_distance=field, dynamic=np.zeros((0, 5)), dt=DT, t=0.0)
    infos = {}
    for passes in (1, 2):
        planner = make_local_planner("qp-dwa", robot, DT, path_samples=(), qp_margin=0.3, qp_passes=passes)
        planner.reset(st, ctx.global_path)
        step = planner.evaluate(ctx, planner.window(ctx))
        best, _ = planner.choose(step)
        info = infos[passes] = planner.command(ctx).info
        assert qp_outcome(info) == "used" and info["qp_change"] > 0.05
        v, w, vy = info["target"]
        check = planner._assess(ctx, planner.rollout_of(st, [v], [vy], [w]))
        H = int(round(planner.options["qp_horizon"] / DT))
        allowed = min(step.static_gap[best, :H].min(), 0.3)
        assert check.admissible[0] and check.static_gap[0, :H].min() >= allowed - 1e-5
    assert infos[1]["qp"] == "solved: 0.25 of the step" and infos[1]["qp_passes"] == 1
    assert infos[2]["qp"] == "solved" and infos[2]["qp_passes"] == 2 and "qp_fraction" not in infos[2]
    assert infos[2]["qp_change"] > infos[1]["qp_change"]



def by_passes(ctx, robot, **params):
    """``{passes: (command info, first verdict of the QP's answer)}`` for one and two passes of
    a fresh qp-dwa on ``ctx``."""
    out = {}
    for passes in (1, 2):
        planner = make_local_planner("qp-dwa", robot, DT, qp_passes=passes, **params)
        planner.reset(ctx.state, ctx.global_path)
        seen = []
        verdict = planner._verdict
        planner._verdict = lambda *a: seen.append(verdict(*a)[0]) or verdict(*a)
        out[passes] = planner.command(ctx).info, seen[0] if seen else None
    return out

# a robot among ten movers on the shipped 50x50 map (benchmarks/dwa_step.py's contexts 37 and 214)
CROWDS = {
    "earlier mover contact": ((0.5, 8.5, math.pi / 4, 0.5, 0.1), (3.5, 13.5), [
        [1.7055, 9.476, -0.1736, -0.5267, 0.3], [1.6928, 9.7586, 0.1807, 0.4795, 0.3],
        [2.475, 8.7505, 0.4249, 0.3534, 0.3], [1.7921, 9.7071, 0.3937, 0.3319, 0.3],
        [1.0491, 10.5146, 0.1729, -0.5408, 0.3], [0.7036, 10.0157, -0.0052, 0.3686, 0.3],
        [1.8264, 10.0852, -0.3381, -0.3732, 0.3], [2.1661, 10.7699, 0.4878, 0.1343, 0.3],
        [1.5281, 5.0224, 0.4353, -0.3476, 0.3], [1.8405, 9.4392, -0.222, 0.2885, 0.3]]),
    "filter": ((32.5, 42.5, math.pi / 2, 0.5, 0.1), (35.5, 44.5), [
        [31.3708, 43.1101, 0.2579, -0.1801, 0.3], [33.6135, 40.3677, 0.5844, 0.0734, 0.3],
        [30.7034, 39.1925, -0.1249, -0.4503, 0.3], [31.8873, 43.7276, -0.4672, -0.2583, 0.3],
        [33.8986, 40.2167, -0.5244, 0.082, 0.3], [35.2712, 40.3974, 0.3546, 0.4005, 0.3],
        [30.6753, 43.866, -0.412, -0.0762, 0.3], [29.2277, 41.4449, 0.3027, 0.308, 0.3],
        [31.6378, 44.0229, 0.4325, 0.2605, 0.3], [34.9182, 39.5769, -0.3313, -0.0031, 0.3]]),
}


@pytest.mark.parametrize("failed", sorted(CROWDS))
def test_a_refinement_that_fails_a_filter_or_meets_a_mover_earlier_is_repaired(failed):
    """Among ten movers the first QP's command fails a test the sample passed: it meets a
    mover earlier, or comes closer to a mover's swept line than the gate allowed the sample.
    With one pass it falls back to the sample (or a shortened step); with two, rows for that
    test are added and the whole answer passes every check, verified here on the planner's
    own rollout: admissible, no earlier mover contact, the gate's judgement of the sample
    (where the gate judged it)."""
    from optplan.world.papermaps import paper_map

    grid, start, goal = paper_map("hou2024_base50")
    field = grid_distance_field(grid)
    path = op.shortest_path(grid, tuple(start), tuple(goal)).path
    (x, y, theta, v, w), sub, movers = CROWDS[failed]
    st = RobotState(x, y, theta, v, w)
    ctx = LocalContext(state=st, subgoal=np.array(sub), goal=path[-1], global_path=path, static_distance=field,
                       dynamic=np.array(movers), dt=DT, t=0.0, bounds=grid.bounds)
    robot = RobotSpec()
    runs = by_passes(ctx, robot, n_v=20, n_w=40)
    assert runs[1][1] == runs[2][1] == failed
    infos = {passes: info for passes, (info, _) in runs.items()}
    assert qp_outcome(infos[1]) == "fallback" or infos[1].get("qp_fraction", 1.0) < 1.0
    assert infos[2]["qp"] == "solved" and infos[2]["qp_passes"] == 2 and infos[2]["qp_change"] > 0.01
    planner = make_local_planner("qp-dwa", robot, DT, n_v=20, n_w=40)
    planner.reset(st, path)
    step = planner.evaluate(ctx, planner.window(ctx))
    best, how = planner.choose(step)
    assert best == infos[2]["index"]
    v, w, vy = infos[2]["target"]
    check = planner._assess(ctx, planner.rollout_of(st, [v], [vy], [w]))
    assert check.admissible[0] and check.mover_contact[0] >= step.mover_contact[best]
    # the filters judged this step's samples only if one was safe ("sample" mode); otherwise
    # the planner evaded the movers and no filter applies
    assert how["mode"] == ("sample" if failed == "filter" else "evade")
    if how["mode"] == "sample":
        assert all(m.passes_like(planner.view, check, step, best) for m in planner.roles.filters)


def test_a_refinement_that_cannot_stop_before_a_block_is_repaired():
    """At 0.87 m/s beside the block at (7-9, 5-6), 0.3 m asked: the first QP's command could not
    stop before the block (not admissible). With one pass the planner keeps a shortened step
    or the sample; with two, rows at the first colliding points (on the sample's trajectory,
    which is clear there) are added and the whole answer is admissible, checked here on the
    planner's own rollout."""
    field = grid_distance_field(op.GridMap.from_rows([[int(c) for c in r] for r in TWO_BLOCKS]))
    robot = RobotSpec()
    st = RobotState(8.684260378825256, 6.685889383290613, -0.2939023107739782, 0.8724148860798918,
                    -0.20174539676612746)
    goal = np.array([5.717301253482249, 3.7648661308701983])
    ctx = LocalContext(state=st, subgoal=goal, goal=goal, global_path=np.array([[st.x, st.y], goal]),
                       static_distance=field, dynamic=np.zeros((0, 5)), dt=DT, t=0.0)
    runs = by_passes(ctx, robot, path_samples=(), qp_margin=0.3)
    assert runs[1][1] == runs[2][1] == "not admissible"
    infos = {passes: info for passes, (info, _) in runs.items()}
    assert qp_outcome(infos[1]) == "fallback" or infos[1].get("qp_fraction", 1.0) < 1.0
    assert infos[2]["qp"] == "solved" and infos[2]["qp_passes"] == 2 and infos[2]["qp_change"] > 0.05
    v, w, vy = infos[2]["target"]
    planner = make_local_planner("qp-dwa", robot, DT, path_samples=(), qp_margin=0.3)
    planner.reset(st, ctx.global_path)
    check = planner._assess(ctx, planner.rollout_of(st, [v], [vy], [w]))
    assert check.admissible[0]
