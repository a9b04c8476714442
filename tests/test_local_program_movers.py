"""Mover prediction of the window program (issue 42): a mover seen to turn round is predicted
bouncing between the ends it was seen to turn at; one never seen to turn, straight on, or (the
``sweep`` model) as the stretch of its line a turn beyond where it was seen could take it to."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan import local_terms as LT
from optplan.formulations.local_program import (Situation, SymbolicSituation, bounce, mover_intervals,
                                                predicted_movers)
from optplan.local.base import LocalContext
from optplan.local.program_planners import MoverTracker
from optplan.world.robot import RobotState

DT = 0.1
ROBOT = op.RobotSpec(radius=0.2, v_max=0.8, w_max=1.2, a_max=0.8, alpha_max=2.0)


def _shuttle(t: float, a: float = 1.0, b: float = 3.0, speed: float = 0.5) -> np.ndarray:
    """A mover (r 0.15 m) on y = 2 that starts at x = a and shuttles between a and b."""
    span = b - a
    u = (speed * t) % (2 * span)
    x, vx = (a + u, speed) if u < span else (b - (u - span), -speed)
    return np.array([[x, 2.0, vx, 0.0, 0.15]])


def _ctx(t: float, rows: np.ndarray) -> LocalContext:
    return LocalContext(state=RobotState(0.0, 0.0, 0.0), subgoal=np.array([5.0, 0.0]), goal=np.array([5.0, 0.0]),
                        global_path=np.array([[0.0, 0.0], [5.0, 0.0]]), static_distance=lambda P: np.full(
                            np.shape(P)[:-1], 10.0), dynamic=rows, dt=DT, t=t)


def _observe(tracker: MoverTracker, until: float, since: float = 0.0, **shuttle) -> tuple[np.ndarray, np.ndarray]:
    """Feed the tracker the mover every period from ``since`` to ``until`` s; the last row and its ends."""
    ends = None
    for k in range(int(round(since / DT)), int(round(until / DT)) + 1):
        rows = _shuttle(k * DT, **shuttle)
        ends, _, _ = tracker.observe(_ctx(k * DT, rows))
    return rows, ends


def _centres(rows, ends, t):
    """The predicted centres of the one mover of ``rows``: a point at every time (no ``seen``)."""
    A, B = predicted_movers(rows, ends, t)
    assert np.array_equal(A, B)
    return A[0]


def test_bounce_reflects_at_known_ends_only():
    run = np.linspace(0.0, 3.0, 7)
    assert np.allclose(bounce(run, -np.inf, np.inf), run)                      # no end known: straight
    assert np.allclose(bounce(run, -0.5, np.inf), run)                         # a turn behind needs one ahead first
    assert np.allclose(bounce(run, -np.inf, 1.0), [0, 0.5, 1.0, 0.5, 0, -0.5, -1.0])   # once at 1, then straight back
    assert np.allclose(bounce(run, -0.5, 1.0), [0, 0.5, 1.0, 0.5, 0, -0.5, 0.0])       # back and forth


def test_a_mover_seen_to_turn_is_predicted_to_reflect_at_the_observed_end():
    """A mover first seen at A (x = 1) drives to B (x = 3, at 4 s), turns round and drives back.
    On its way back it is predicted straight on past A (it was never seen turning there); once
    it has turned at A too and drives towards B again, the prediction reflects at B within the
    horizon and never runs past it."""
    tracker = MoverTracker()
    rows, ends = _observe(tracker, 5.0)                          # x = 2.5, driving -x after the turn at B
    assert rows[0, 0] == pytest.approx(2.5) and rows[0, 2] < 0
    behind, ahead = ends[0]
    assert ahead == np.inf and behind == pytest.approx(-0.5, abs=1e-6)   # B is 0.5 m behind it
    _, seen, _ = tracker.observe(_ctx(5.0, rows))                   # the same step: the same answer
    assert np.allclose(seen[0], [-0.5, 1.5])                     # seen from A (1.5 m ahead) to B
    t = np.arange(1, 21) * DT
    c = _centres(rows, ends, t)
    assert np.allclose(c[:, 0], 2.5 - 0.5 * t)                   # towards A: straight on

    rows, ends = _observe(tracker, 9.0, since=5.1)               # turned at A (8 s): x = 1.5, driving +x
    assert rows[0, 0] == pytest.approx(1.5) and rows[0, 2] > 0
    behind, ahead = ends[0]
    assert ahead == pytest.approx(1.5, abs=1e-6) and behind == pytest.approx(-0.5, abs=1e-6)
    t = np.arange(1, 41) * DT                                    # 4 s: to B in 3 s, then 0.5 m back
    c = _centres(rows, ends, t)
    assert c[:, 0].max() == pytest.approx(3.0, abs=1e-6)         # reflects at B, never beyond it
    assert c[29, 0] == pytest.approx(3.0) and c[-1, 0] == pytest.approx(2.5)
    assert np.allclose(c[:, 1], 2.0)
    truth = np.array([_shuttle(9.0 + tk)[0, 0] for tk in t])     # the mover's own motion
    assert np.abs(c[:, 0] - truth).max() < 1e-6


def test_a_mover_never_seen_turning_is_predicted_straight():
    tracker = MoverTracker()
    rows, ends = _observe(tracker, 3.0)                          # x = 2.5, driving +x, no turn yet
    assert np.all(ends[0] == [-np.inf, np.inf])
    t = np.arange(1, 21) * DT
    c = _centres(rows, ends, t)
    assert np.allclose(c[:, 0], 2.5 + 0.5 * t) and c[:, 0].max() > 3.0 + 0.4


def test_an_end_the_mover_passes_is_forgotten():
    """Turn points are learnt from observation and unlearnt by it: a mover seen beyond the
    end it was thought to turn at no longer turns there."""
    tracker = MoverTracker()
    _observe(tracker, 5.0)                                       # turned at B = 3
    for k in range(51, 80):                                      # now it drives on in +x past x = 3
        x = 2.5 + 0.5 * (k - 50) * DT
        ends, _, _ = tracker.observe(_ctx(k * DT, np.array([[x, 2.0, 0.5, 0.0, 0.15]])))
    assert x > 3.1 and ends[0, 1] == np.inf


def test_where_a_turn_is_possible_but_not_known_the_mover_is_a_stretch():
    """``mover_seen`` given: a mover may turn at any point at or beyond the farthest point it was
    seen at where no end is known; the stretch is the hull of those motions."""
    t = np.array([0.5, 1.0, 1.5, 3.0])
    inf = np.inf
    # at the farthest point seen ahead, no end known: it may turn now
    lo, hi = mover_intervals([1.0], [[-inf, inf]], [[-2.0, 0.0]], t)
    assert np.allclose(lo, -t) and np.allclose(hi, t)
    # 1 m of seen track ahead: a point until it gets there, then [2 a0 - run, run]
    lo, hi = mover_intervals([1.0], [[-inf, inf]], [[-2.0, 1.0]], t)
    assert np.allclose(lo, [0.5, 1.0, 0.5, -1.0]) and np.allclose(hi, t)
    # ... and not past a known end behind
    lo, _ = mover_intervals([1.0], [[-0.5, inf]], [[-0.5, 1.0]], t)
    assert np.allclose(lo, [0.5, 1.0, 0.5, -0.5])
    # end ahead known at 0.3, none behind, seen 0.5 m behind: exact until it passes -0.5 on the way back
    lo, hi = mover_intervals([1.0], [[-inf, 0.3]], [[-0.5, 0.3]], np.array([0.6, 1.0, 1.2]))
    assert np.allclose(lo, [0.0, -0.4, -0.6]) and np.allclose(hi, [0.0, -0.4, -0.4])
    # both ends known: one position, with or without what was seen
    lo, hi = mover_intervals([1.0], [[-0.5, 0.3]], [[-0.5, 0.3]], t)
    assert np.allclose(lo, hi) and np.allclose(lo, bounce(t, -0.5, 0.3))
    # no seen extents: the point model
    lo, hi = mover_intervals([1.0], [[-inf, inf]], None, t)
    assert np.allclose(lo, t) and np.allclose(hi, t)


@pytest.mark.parametrize("seen", [False, True])
def test_bouncing_movers_are_one_rule_in_both_views(seen):
    """The symbolic mover rows read the same predicted centres (or stretches) as the batched gaps."""
    import casadi as ca

    lp = op.LocalProgram(ROBOT, horizon=2.0, intervals=5, step=0.1)
    lp.subject_to(LT.clearance(mover_margin=0.1, mover_growth=0.1) >= 0.02)
    sit = Situation(state=np.array([0.0, 0.0, 0.1, 0.4, 0.1, 0.0]), subgoal=np.array([5.0, 1.0]),
                    path=np.array([[0.0, 0.0], [5.0, 1.0]]),
                    static_distance=lambda P: np.full(np.shape(P)[:-1], 10.0),
                    movers=np.array([[1.0, 0.1, 0.4, 0.0, 0.2], [1.2, 1.0, 0.0, 0.5, 0.2]]),
                    mover_ends=np.array([[-np.inf, 0.3], [-1.0, np.inf]]),
                    mover_seen=np.array([[-0.2, 0.3], [-1.0, 0.1]]) if seen else None)
    U = np.tile([0.6, 0.0], (1, lp.K, 1))
    Z = lp.rollout(sit, U)[0]
    gaps = np.concatenate([g[0] for g in lp.mover_gaps(Z[None], sit)])
    opti = ca.Opti()
    ps = SymbolicSituation(opti, lp, max_movers=2)
    Zs = opti.parameter(lp.N + 1, 3)
    rows = lp.mover_rows(Zs, ps, squared=False)
    values = lp.symbolic_values(sit, Z, 2)
    ps.set(values)
    opti.set_value(Zs, Z)
    order = np.argsort(np.hypot(sit.movers[:, 0], sit.movers[:, 1]))
    expect = np.concatenate([gaps.reshape(2, -1)[i] for i in order])
    assert np.allclose([float(opti.value(r)) for r in rows], expect, atol=1e-6)
    straight = Situation(**{**sit.__dict__, "mover_ends": None, "mover_seen": None})
    assert not np.allclose(np.concatenate([g[0] for g in lp.mover_gaps(Z[None], straight)]), gaps)
    if seen:   # a stretch holds the bouncing position: never more room than the point model
        point = Situation(**{**sit.__dict__, "mover_seen": None})
        point_gaps = np.concatenate([g[0] for g in lp.mover_gaps(Z[None], point)])
        assert np.all(gaps <= point_gaps + 1e-12) and np.any(gaps < point_gaps - 0.05)


@pytest.mark.parametrize("model", ["bounce", "straight"])
def test_the_program_solvers_take_a_mover_model(model):
    from optplan.local import make_local_planner

    planner = make_local_planner("mpc", ROBOT, DT, mover_model=model)
    assert (planner.sampler.tracker is not None) == (model == "bounce")
    with pytest.raises(op.ParameterError, match="mover_model"):
        make_local_planner("dwa", ROBOT, DT, local_program="default", mover_model="psychic")


@pytest.mark.parametrize("omni", [False, True])
def test_stopping_clear_of_movers_is_one_rule_in_both_views(omni):
    """``stop_clear``: the stopping point after the window keeps clear of the predicted movers
    over the hold; the symbolic rows give the batched shortfall at the reference."""
    import casadi as ca

    from optplan.formulations.local_program import StopClear

    robot = op.RobotSpec(model="omni", radius=0.2, v_max=0.8, vy_max=0.4, w_max=1.2, a_max=0.8,
                         alpha_max=2.0) if omni else ROBOT
    lp = op.LocalProgram(robot, horizon=2.0, intervals=5, step=0.1)
    lp.subject_to(StopClear(hold=2.0, margin=0.1))
    # a mover shuttling across the robot's way 2 m ahead, its far end known: the robot may not
    # stop on its track, but it may stop short of it
    sit = Situation(state=np.array([0.0, 0.0, 0.0, 0.6, 0.0, 0.0]), subgoal=np.array([5.0, 0.0]),
                    path=np.array([[0.0, 0.0], [5.0, 0.0]]),
                    static_distance=lambda P: np.full(np.shape(P)[:-1], 10.0),
                    movers=np.array([[1.6, 1.0, 0.0, 0.5, 0.15]]), mover_ends=np.array([[-3.0, 0.5]]),
                    mover_seen=np.array([[-3.0, 0.5]]))
    nu = lp.nu
    on_track = np.tile([0.6, 0.0, 0.0][:nu], (1, lp.K, 1))        # ends at x = 1.2 m at 0.6 m/s: stops at 1.43
    short = np.tile([0.2, 0.0, 0.0][:nu], (1, lp.K, 1))           # ends at x = 0.4 m, stops at once
    _, _, on = lp.evaluate(sit, on_track)
    _, _, off = lp.evaluate(sit, short)
    assert on["stop_clear"][0] > 0.1 and off["stop_clear"][0] == 0
    for U in (on_track, short):
        Z = lp.rollout(sit, U)[0]
        opti = ca.Opti()
        ps = SymbolicSituation(opti, lp, max_movers=1)
        Zs, Us = opti.parameter(lp.N + 1, 3), opti.parameter(lp.K, nu)
        rows = lp.constraints[0].symbolic(Zs, Us, ps, lp)
        ps.set(lp.symbolic_values(sit, Z, 1))
        opti.set_value(Zs, Z)
        opti.set_value(Us, U[0])
        lower = (lp.robot.radius + 0.15 + 0.1) ** 2
        d = np.sqrt([float(opti.value(e)) + lower for e, _ in rows])   # centre distances, symbolic
        shortfall = max(0.0, float((0.1 - (d - 0.35)).max()))
        assert shortfall == pytest.approx(lp.evaluate(sit, U)[2]["stop_clear"][0], abs=1e-6)


def test_a_mover_whose_motion_is_known_gets_no_growing_margin():
    """``mover_growth`` is the error of a motion not known: a mover seen turning at both ends
    is kept ``mover_margin`` clear at every time, another one ``mover_margin + growth t``; the
    symbolic rows ask the same."""
    import casadi as ca

    from optplan.formulations.local_program import motion_known

    lp = op.LocalProgram(ROBOT, horizon=2.0, intervals=5, step=0.1)
    lp.subject_to(LT.clearance(mover_margin=0.1, mover_growth=0.2) >= 0.0)
    movers = np.array([[1.5, 0.7, 0.0, 0.3, 0.15]])      # driving away from the robot's line
    U = np.tile([0.5, 0.0], (1, lp.K, 1))
    base = dict(state=np.array([0.0, 0.0, 0.0, 0.5, 0.0, 0.0]), subgoal=np.array([5.0, 0.0]),
                path=np.array([[0.0, 0.0], [5.0, 0.0]]), static_distance=lambda P: np.full(np.shape(P)[:-1], 10.0),
                movers=movers)
    known = Situation(**base, mover_ends=np.array([[-0.5, 1.0]]), mover_seen=np.array([[-0.5, 1.0]]))
    unknown = Situation(**base, mover_ends=np.array([[-0.5, np.inf]]), mover_seen=np.array([[-0.5, 1.0]]))
    assert motion_known(known).tolist() == [True] and motion_known(unknown).tolist() == [False]
    Z = lp.rollout(known, U)
    t = lp.h * np.arange(1, lp.N + 1)
    for sit, growth in ((known, 0.0), (unknown, 0.2)):
        gap = next(lp.mover_gaps(Z, sit))[0]
        expect = max(0.0, float((0.1 + growth * t - gap).max()))
        assert lp.evaluate(sit, U)[2]["clearance"][0] == pytest.approx(expect, abs=1e-12)
        opti = ca.Opti()
        ps = SymbolicSituation(opti, lp, max_movers=1)
        Zs = opti.parameter(lp.N + 1, 3)
        rows = lp.constraints[0].symbolic(Zs, opti.parameter(lp.K, 2), ps, lp)[lp.N:]   # after the static rows
        ps.set(lp.symbolic_values(sit, Z[0], 1))
        opti.set_value(Zs, Z[0])
        d = np.sqrt([float(opti.value(e)) + (0.35 + 0.1 + growth * tj) ** 2 for (e, _), tj in zip(rows, t)]) - 0.35
        assert np.allclose(d, gap, atol=1e-9)
        assert max(0.0, float((0.1 + growth * t - d).max())) == pytest.approx(expect, abs=1e-9)


def test_learning_where_movers_turn_round_avoids_a_collision_in_closed_loop():
    """yang2023's fusion world, seed 0: its movers shuttle across the path. Predicted straight
    on (constant velocity) mpc runs into one; predicted from the ends it saw them turn at
    (the default), it reaches the goal without touching any."""
    runs = {m: op.simulate("yang2023_fusion", global_planner="astar", local_planner="mpc", seed=0,
                           planner_params={"mover_model": m}) for m in ("straight", "sweep")}
    assert runs["straight"].collisions > 0
    assert runs["sweep"].reached and runs["sweep"].collisions == 0, runs["sweep"].message
    default = op.simulate("yang2023_fusion", global_planner="astar", local_planner="mpc", seed=0)
    assert np.array_equal(default.trajectory, runs["sweep"].trajectory)   # sweep is the default


def test_a_mover_is_never_predicted_through_a_wall():
    """No end known ahead, a wall 1 m ahead: it turns there at the latest, straight on never past it."""
    t = np.array([1.0, 2.0, 3.0, 4.0])
    # the point model: it bounces off the wall (reach 1 m ahead), not 2, 3, 4 m on
    lo, hi = mover_intervals(np.array([1.0]), None, None, t, reach=np.array([[-np.inf, 1.0]]))
    assert np.allclose(lo, [1.0, 0.0, -1.0, -2.0]) and np.allclose(hi, lo)
    # the stretch model, seen 0.2 m ahead: anywhere from a turn there to a turn at the wall
    lo, hi = mover_intervals(np.array([1.0]), None, np.array([[0.0, 0.2]]), t, reach=np.array([[-np.inf, 1.0]]))
    assert np.all(hi <= 1.0 + 1e-12) and np.allclose(hi, [1.0, 0.0, -1.0, -2.0])
    assert np.allclose(lo, [-0.6, -1.6, -2.6, -3.6]) and np.all(lo <= hi)
    # the tracker reads the wall from the map it is given: x = 4 is a wall for a 0.15 m mover at 3.8 - 0.15
    tracker = MoverTracker()
    wall = lambda P: 4.0 - np.asarray(P, float)[..., 0]      # noqa: E731 - distance to the wall x = 4
    ctx = LocalContext(state=RobotState(0.0, 0.0, 0.0), subgoal=np.array([5.0, 0.0]), goal=np.array([5.0, 0.0]),
                       global_path=np.array([[0.0, 0.0], [3.0, 0.0]]), static_distance=wall,
                       dynamic=np.array([[2.0, 2.0, 0.5, 0.0, 0.15]]), dt=DT, t=0.0)
    _, _, reach = tracker.observe(ctx)
    # to line_reach's 5 cm steps, never past the wall
    assert 1.85 - 0.05 - 1e-9 <= reach[0, 1] <= 1.85 and reach[0, 0] == -np.inf


def test_stop_clear_without_the_sweep_keeps_only_the_straight_prediction():
    """A mover driving away that may turn round anywhere past where it was seen (the sweep) could
    come back to where the robot stops; predicted straight on over the hold, it cannot."""
    import optplan as op
    from optplan import local_terms as LT
    from optplan.formulations.local_program import Situation

    robot = op.RobotSpec(radius=0.2, v_max=0.8, w_max=1.2, a_max=0.8, alpha_max=2.0)
    sit = Situation(state=np.array([2.6, 0.0, 0.0, 0.0, 0.0, 0.0]), subgoal=np.array([5.0, 0.0]),
                    path=np.array([[0.0, 0.0], [5.0, 0.0]]), static_distance=lambda P: np.full(np.shape(P)[:-1], 9.0),
                    movers=np.array([[3.0, 0.0, 0.5, 0.0, 0.2]]), mover_ends=np.array([[-np.inf, np.inf]]),
                    mover_seen=np.array([[0.0, 0.0]]), mover_reach=np.array([[-np.inf, np.inf]]))
    stand = np.zeros((1, 4, 2))
    out = {}
    for sweep in (True, False):
        lp = op.LocalProgram(robot, horizon=2.0, intervals=4)
        lp.minimize(LT.speed())
        lp.subject_to(LT.stop_clear(4.0, 0.1, sweep=sweep))
        out[sweep] = lp.evaluate(sit, stand)[1][0]
    assert out[True] > 0.05 and out[False] == 0.0, out


def test_mpc_asks_its_global_path_for_room_beside_it():
    """mpc's own default (optplan/papers.py GLOBAL_CLEARANCE_EXTRA): its global path keeps the robot
    radius + 0.15 m where such a path exists, also for a scenario given as a file (no family
    options); qp-dwa's keeps the bare radius and threads the narrower gap."""
    import optplan as op
    from optplan.worldgen.clutter import family_scenario

    sc = family_scenario("clutter", 12001)
    clear = {}
    for planner in ("mpc", "qp-dwa"):
        r = op.simulate(sc, local_planner=planner, time_limit=0.2, seed=0)
        clear[planner] = op.path_metrics(sc.world, np.asarray(r.global_path)).min_clearance
    assert clear["mpc"] >= sc.robot.radius + 0.15 - 1e-9 > clear["qp-dwa"], clear
