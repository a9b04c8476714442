"""The sweep gate of qp-dwa: learning where a mover turns round, and keeping off its track."""
from __future__ import annotations

import math

import numpy as np
import pytest

from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.local.rollout import rollout, rollout_ramped
from optplan.local.sweep_gate import SweepGate, bounce, line_reach
from optplan.sim.closed_loop import simulate
from optplan.world.robot import RobotSpec, RobotState
from optplan.world.scenario import load_scenario

T = np.arange(1, 31) * 0.1


def stepped(s0, heading, speed, t, lo, hi, dt=1e-4):
    """Reference: integrate the back-and-forth motion in small steps."""
    s, h, now, out = s0, heading, 0.0, []
    for tt in t:
        while now < tt - 1e-12:
            s += h * speed * dt
            now += dt
            if s > hi:
                s, h = 2 * hi - s, -1.0
            if s < lo:
                s, h = 2 * lo - s, 1.0
        out.append(s)
    return np.array(out)


@pytest.mark.parametrize("lo,hi", [(-0.4, 0.7), (-math.inf, 0.3), (-0.2, math.inf), (-math.inf, math.inf)])
@pytest.mark.parametrize("heading", [1.0, -1.0])
def test_bounce_matches_stepped_motion(lo, hi, heading):
    got = bounce(0.1, heading, 0.6, T, lo, hi)
    assert np.abs(got - stepped(0.1, heading, 0.6, T, lo, hi)).max() < 1e-3


def test_bounce_broadcasts_candidate_ends():
    los = np.array([-0.5, -math.inf])[None, :]
    his = np.array([0.4, 1.0, math.inf])[:, None]
    got = bounce(0.0, 1.0, 0.5, T, los, his)
    assert got.shape == (3, 2, len(T))
    for i in range(3):
        for j in range(2):
            assert np.allclose(got[i, j], bounce(0.0, 1.0, 0.5, T, los[0, j], his[i, 0]))


ROBOT = RobotSpec(model="unicycle", radius=0.2, v_max=1.0, w_max=math.radians(40), a_max=0.3,
                  alpha_max=math.radians(40))


def mover_at(t, a=(6.0, 1.0), b=(6.0, 5.0), speed=0.5, radius=0.35):
    """Row ``(x, y, vx, vy, r)`` of a mover driving a <-> b, at a when t = 0."""
    a, b = np.array(a), np.array(b)
    length = float(np.hypot(*(b - a)))
    s = stepped(0.0, 1.0, speed, [t], 0.0, length)[0] if t > 0 else 0.0
    u = (b - a) / length
    # direction: going out while the unfolded distance is in the first half of the period
    going_out = (speed * t) % (2 * length) < length
    v = u * speed * (1 if going_out else -1)
    p = a + u * s
    return np.array([[p[0], p[1], v[0], v[1], radius]])


def context(t, state=None, dynamic=None):
    state = state or RobotState(x=3.0, y=3.0, theta=0.0)
    return LocalContext(state=state, subgoal=np.array([11.0, 3.0]), goal=np.array([11.0, 3.0]),
                        global_path=np.array([[0.5, 3.0], [11.0, 3.0]]),
                        static_distance=lambda p: np.full(np.shape(p)[:-1], 10.0),
                        dynamic=mover_at(t) if dynamic is None else dynamic, dt=0.1, t=t)


def test_gate_learns_both_turning_points_then_predicts_the_motion():
    gate = SweepGate()
    gate.reset(None, RobotState(3.0, 3.0, 0.0), np.zeros((2, 2)))
    for k in range(0, 200):  # 20 s: the mover (4 m at 0.5 m/s) turns at 8 s and 16 s
        gate.update(context(round(k * 0.1, 10)))
    (track,) = gate.tracks
    ends = sorted([track.end_lo, track.end_hi])
    span = ends[1] - ends[0]
    assert span == pytest.approx(4.0, abs=0.01)  # the two turning points, 4 m apart
    lo, hi = gate.swept(track, T)
    assert np.allclose(lo, hi)  # both ends known: a single predicted position
    # the prediction is where the mover will be
    t_now = 19.9
    truth = np.array([mover_at(t_now + tt)[0, 1] for tt in T])  # y coordinate along the vertical track
    sign = 1.0 if track.axis.imag > 0 else -1.0
    predicted_y = track.origin.imag + sign * lo
    assert np.abs(predicted_y - truth).max() < 0.02
    # the learnt sweep, for the navigation layer's stuck recovery: a 0.35 m disc from a to b
    (row,) = gate.mover_sweeps()
    ends = sorted([tuple(row[:2]), tuple(row[2:4])], key=lambda p: p[1])
    assert np.allclose(ends, [(6.0, 1.0), (6.0, 5.0)], atol=0.02) and row[4] == pytest.approx(0.35)


def test_a_track_with_an_unseen_end_is_not_reported_as_a_sweep():
    gate = SweepGate()
    gate.reset(None, RobotState(3.0, 3.0, 0.0), np.zeros((2, 2)))
    for k in range(0, 120):  # 12 s: one turn (at b, 8 s) seen, the other not yet
        gate.update(context(round(k * 0.1, 10)))
    assert len(gate.tracks) == 1 and not gate.tracks[0].known
    assert gate.mover_sweeps().shape == (0, 5)


def test_before_a_turn_is_seen_the_mover_may_turn_round_at_once():
    gate = SweepGate(learn_first=False)  # the interval rule on its own
    gate.reset(None, RobotState(3.0, 3.0, 0.0), np.zeros((2, 2)))
    for k in range(0, 31):  # 3 s heading out from a: no turn seen yet
        gate.update(context(round(k * 0.1, 10)))
    (track,) = gate.tracks
    assert not math.isfinite(track.end_hi) and not math.isfinite(track.end_lo)
    lo, hi = gate.swept(track, T)
    # it may go on (s + c t) or turn now (s - c t): the interval covers both
    assert np.all(lo <= track.s - 0.5 * T + 1e-9) and np.all(hi >= track.s + 0.5 * T - 1e-9)


def test_remembered_intervals_follow_what_each_step_learns():
    """The intervals are remembered within a step (qp-dwa asks twice) but never across steps:
    once the turn at 8 s is seen, the next step's interval must use it."""
    gate = SweepGate(learn_first=False)
    gate.reset(None, RobotState(3.0, 3.0, 0.0), np.zeros((2, 2)))
    for k in range(0, 80):
        gate.update(context(round(k * 0.1, 10)))
    (track,) = gate.tracks
    before = gate.swept(track, T)
    assert gate.swept(track, T) is before  # same step: the remembered interval
    for k in range(80, 83):  # the mover turns round at the far end (8 s)
        gate.update(context(round(k * 0.1, 10)))
    assert math.isfinite(track.end_hi) or math.isfinite(track.end_lo)
    after = gate.swept(track, T)
    fresh = SweepGate._swept_now(gate, track, T)
    assert np.array_equal(after[0], fresh[0]) and np.array_equal(after[1], fresh[1])
    assert not np.array_equal(after[1] - after[0], before[1] - before[0])


def test_gate_rejects_passing_close_behind_a_mover_that_may_turn():
    planner = make_local_planner("qp-dwa", ROBOT, 0.1)
    # the robot drives at 0.6 m/s towards x = 6; the mover has just crossed y = 3 going up
    state = RobotState(x=4.6, y=3.0, theta=0.0, v=0.6)
    planner.reset(state, np.array([[0.5, 3.0], [11.0, 3.0]]))
    t = 4.5  # mover at y = 3.25, moving away from the robot's line
    ctx = context(t, state)
    step = planner.evaluate(ctx, planner.window(ctx))
    (gate,) = [m for m in planner.mechanisms if isinstance(m, SweepGate)]
    keep = gate.filter(planner.view, step)
    clear_by_prediction = step.admissible & step.mover_free
    # the constant-velocity prediction clears samples that the possible turn-round does not
    assert (clear_by_prediction & ~keep).any()
    # the kept ones stay off where the mover could be if it turned now
    (track,) = gate.tracks_now
    lo, hi = gate.swept(track, step.roll.t)
    q = (step.roll.z[keep] - track.origin) * np.conj(track.axis)
    beyond = np.maximum(np.maximum(lo - q.real, q.real - hi), 0.0)
    assert (np.hypot(q.imag, beyond) - track.radius - ROBOT.radius).min() >= gate.margin - 1e-9
    # the command reports how many samples the gate turned away
    cmd = make_local_planner("qp-dwa", ROBOT, 0.1)
    cmd.reset(state, np.array([[0.5, 3.0], [11.0, 3.0]]))
    assert cmd.command(ctx).info["gate_rejected"] == int((~keep).sum()) > 0


def turn_round_scenario(up: float, speed: float, phase: float):
    """A mover drives up and down x = 6 across the robot's straight path y = 4 and turns
    round ``up`` metres above it, just after the robot would have passed behind it."""
    return load_scenario({
        "name": "turn_round", "map": [[0] * 12 for _ in range(8)], "start": [0.5, 4.0, 0], "goal": [11.5, 4.0],
        "robot": {"model": "unicycle", "radius": 0.2, "v_max": 1.0, "w_max_deg": 40, "a_max": 0.3,
                  "alpha_max_deg": 40},
        "sensor_range": 3.0, "dt": 0.1, "time_limit": 60,
        "dynamic_obstacles": [{"radius": 0.35, "waypoints": [[6.0, 1.0], [6.0, 4.0 + up]], "speed": speed,
                               "phase": phase}]})


@pytest.mark.parametrize("up,speed,phase", [(1.0, 0.5, 1.0), (1.2, 0.6, 0.5), (0.9, 0.4, 1.5)])
def test_qp_dwa_waits_for_a_mover_that_turns_round(up, speed, phase):
    sc = turn_round_scenario(up, speed, phase)
    without = simulate(sc, global_planner="astar", local_planner="qp-dwa", seed=0,
                       planner_params={"sweep_gate": False})
    assert without.collisions > 0  # the scenario does catch a constant-velocity prediction out
    gated = simulate(sc, global_planner="astar", local_planner="qp-dwa", seed=0)
    assert gated.reached and gated.collisions == 0 and gated.min_clearance >= 0


def test_strict_filter_judges_one_trajectory_without_the_fallback():
    """qp-dwa checks its refined command with ``strict_filter``: a lone trajectory that
    comes too close to a mover's possible interval fails it, although ``filter`` (which
    keeps the least-close samples when none keeps off) would let it through."""
    planner = make_local_planner("qp-dwa", ROBOT, 0.1)
    state = RobotState(x=4.6, y=3.0, theta=0.0, v=0.6)
    planner.reset(state, np.array([[0.5, 3.0], [11.0, 3.0]]))
    ctx = context(4.5, state)
    straight = planner._assess(ctx, planner.rollout_of(state, [0.6], [0.0], [0.0]))  # on into the track
    (gate,) = [m for m in planner.mechanisms if isinstance(m, SweepGate)]
    assert straight.admissible[0] and straight.mover_free[0]
    assert not gate.strict_filter(planner.view, straight)[0]
    assert gate.filter(planner.view, straight)[0]


def test_a_refined_command_is_judged_as_the_gate_judged_the_sample():
    """When no sample keeps off the swept intervals the gate keeps those that come least
    close; a refined command is then accepted if it comes no closer than the chosen sample
    (the strict test alone would reject every one), and rejected if it comes closer."""
    planner = make_local_planner("qp-dwa", ROBOT, 0.1)
    state = RobotState(x=4.8, y=3.0, theta=0.0, v=0.6)  # too fast to keep off the line
    planner.reset(state, np.array([[0.5, 3.0], [11.0, 3.0]]))
    ctx = context(4.5, state)
    (gate,) = [m for m in planner.mechanisms if isinstance(m, SweepGate)]
    step = planner.evaluate(ctx, planner.window(ctx))
    keep = gate.filter(planner.view, step)
    safe = step.admissible & step.mover_free
    gap = step.aux["gate_gap"]
    assert keep is not None and keep.any() and (gap[safe] < gate.margin).all()  # the relaxed rule was used
    i = int(np.flatnonzero(keep)[0])
    closer = np.flatnonzero(safe & (gap < gap[i] - 0.05))
    assert len(closer)

    def alone(j):  # sample j's command as a refined command: one trajectory, assessed afresh
        r = step.roll
        return planner._assess(ctx, planner.rollout_of(state, [r.v[j]], [r.vy[j]], [r.w[j]]))

    same = alone(i)
    assert not gate.strict_filter(planner.view, same)[0]
    assert gate.passes_like(planner.view, same, step, i)
    assert not gate.passes_like(planner.view, alone(int(closer[0])), step, i)


def test_the_gates_clearance_rows_are_its_gap_and_linearise_it():
    """The gate's test as QP rows: the smallest row gap is the gate's gap of the sample, asked
    as the gate judged it (here relaxed: no closer than the sample), and a small change of the
    command moves the gate's gap as the row's normal and the rollout's derivative predict."""
    planner = make_local_planner("qp-dwa", ROBOT, 0.1)
    state = RobotState(x=4.8, y=3.0, theta=0.0, v=0.6)
    planner.reset(state, np.array([[0.5, 3.0], [11.0, 3.0]]))
    ctx = context(4.5, state)
    (gate,) = [m for m in planner.mechanisms if isinstance(m, SweepGate)]
    step = planner.evaluate(ctx, planner.window(ctx))
    keep = gate.filter(planner.view, step)
    i = int(np.flatnonzero(keep)[0])
    rows = gate.clearance_rows(planner.view, step, i)
    assert rows and min(r[2] for r in rows) == pytest.approx(step.aux["gate_gap"][i], abs=1e-9)
    assert all(r[3] == pytest.approx(step.aux["gate_gap"][i]) for r in rows)  # relaxed: the sample's gap
    t, normal, gap, _ = min(rows, key=lambda r: r[2])
    r, h = step.roll, 1e-3
    for dv, dw in ((h, 0.0), (0.0, h)):
        moved = planner._assess(ctx, planner.rollout_of(state, [r.v[i] + dv], [r.vy[i]], [r.w[i] + dw]))
        gate.strict_filter(planner.view, moved)
        base = planner.rollout_of(state, [r.v[i]], [r.vy[i]], [r.w[i]])
        predicted = gap + (np.conj(normal) * (moved.roll.z[0, t] - base.z[0, t])).real
        change = moved.aux["gate_gap"][0] - gap
        assert abs(change) > 1e-4 and abs(moved.aux["gate_gap"][0] - predicted) <= 0.15 * abs(change)


def test_line_reach_stops_at_known_obstacles_and_the_border():
    wall = lambda p: 8.0 - np.asarray(p)[..., 0]  # a wall at x = 8 (signed distance from it)
    ctx = LocalContext(state=RobotState(1.0, 1.0, 0.0), subgoal=np.zeros(2), goal=np.zeros(2),
                       global_path=np.zeros((2, 2)), static_distance=wall, dynamic=np.zeros((0, 5)), dt=0.1,
                       bounds=(0.0, 0.0, 10.0, 10.0))
    def within_one_step(got, exact):  # never past the true reach, at most one 5 cm step short
        return abs(exact) - 0.05 - 1e-9 <= abs(got) <= abs(exact) + 1e-9 and np.sign(got) == np.sign(exact)

    lo, hi = line_reach(ctx, complex(6.0, 3.0), 1.0 + 0j, 0.35)
    assert within_one_step(hi, 8.0 - 0.35 - 6.0)  # to the wall, less the radius
    assert within_one_step(lo, -(6.0 - 0.35))      # to the border x = 0
    lo, hi = line_reach(ctx, complex(6.0, 3.0), 1j, 0.35)  # along the wall: the border only
    assert within_one_step(lo, -(3.0 - 0.35)) and within_one_step(hi, 10.0 - 0.35 - 3.0)
    free = LocalContext(state=ctx.state, subgoal=ctx.subgoal, goal=ctx.goal, global_path=ctx.global_path,
                        static_distance=lambda p: np.full(np.shape(p)[:-1], 10.0), dynamic=ctx.dynamic, dt=0.1)
    assert line_reach(free, complex(6.0, 3.0), 1j, 0.35) == (-math.inf, math.inf)


def crossing_step(t, track_end, **gate):
    """The robot drives at 0.6 m/s towards x = 6 on y = 3; a mover drives up and down x = 6
    from y = 4.5 to ``track_end``, seen from t = 0. Returns the step at ``t``, the gate's mask
    and the mask of samples that reach x = 6."""
    planner = make_local_planner("qp-dwa", ROBOT, 0.1, sweep_gate=gate)
    state = RobotState(x=4.6, y=3.0, theta=0.0, v=0.6)
    planner.reset(state, np.array([[0.5, 3.0], [11.0, 3.0]]))
    (g,) = [m for m in planner.mechanisms if isinstance(m, SweepGate)]
    rows = lambda tt: mover_at(tt, a=(6.0, 4.5), b=(6.0, track_end))
    for k in range(int(round(t / 0.1))):
        g.update(context(round(k * 0.1, 10), state, rows(k * 0.1)))
    ctx = context(t, state, rows(t))
    step = planner.evaluate(ctx, planner.window(ctx))
    return step, g.strict_filter(planner.view, step), step.roll.z.real.max(axis=1) > 5.9


def test_until_both_ends_are_seen_the_whole_reachable_line_is_kept_clear():
    # at t = 2 s the mover is at y = 5.5 going up: even turning at once it stays more than
    # 1 m from y = 3 for the whole horizon, so the interval rule lets the robot cross ...
    step, keep, crossing = crossing_step(2.0, 8.5, learn_first=False)
    assert (keep & crossing & step.admissible).any()
    # ... but its far end is unknown, and so is how far down its line goes: learning first
    # keeps every sample off the line
    step, keep, crossing = crossing_step(2.0, 8.5)
    assert crossing.any() and not (keep & crossing).any()
    # past learn_time without a turn seen (a 15.5 m track), the interval rule is back
    step, keep, crossing = crossing_step(23.0, 20.0)
    assert (keep & crossing & step.admissible).any()
    step, keep, crossing = crossing_step(23.0, 20.0, learn_time=30.0)
    assert not (keep & crossing).any()


def test_known_ends_replace_the_constant_velocity_prediction():
    """A mover heading for the end it will turn at (y = 5) does not run on into a robot
    waiting just beyond it (y = 5.9), as the constant-velocity prediction says it would."""
    state = RobotState(x=6.0, y=5.9, theta=0.0)
    verdicts = {}
    for exact in (True, False):
        planner = make_local_planner("qp-dwa", ROBOT, 0.1, sweep_gate={"exact": exact})
        planner.reset(state, np.array([[0.5, 3.0], [11.0, 3.0]]))
        (g,) = [m for m in planner.mechanisms if isinstance(m, SweepGate)]
        for k in range(230):  # turns seen at 8 s (y = 5) and 16 s (y = 1)
            g.update(context(round(k * 0.1, 10), state))
        (track,) = g.tracks
        assert track.known
        ctx = context(23.0, state)  # mover at y = 4.5 going up
        assert ctx.dynamic[0, 1] == pytest.approx(4.5, abs=1e-3) and ctx.dynamic[0, 3] > 0
        step = planner._assess(ctx, planner.rollout_of(state, [0.0], [0.0], [0.0]))  # stand still
        verdicts[exact] = bool(step.mover_free[0])
        if exact:
            assert np.abs(step.movers[0].imag - 5.0).min() < 0.06 and step.movers[0].imag.max() <= 5.0 + 1e-9
    assert verdicts == {True: True, False: False}


@pytest.mark.parametrize("rejoin,learnt", [(10.0, True), (1.0, False)])
def test_a_turn_made_out_of_sight_is_learnt_when_the_mover_comes_back(rejoin, learnt):
    gate = SweepGate(rejoin=rejoin)
    gate.reset(None, RobotState(3.0, 3.0, 0.0), np.zeros((2, 2)))
    for k in range(0, 110):  # unseen from 7 s to 10 s, while it turns round at y = 5 (8 s)
        t = round(k * 0.1, 10)
        gate.update(context(t, dynamic=np.zeros((0, 5)) if 7.0 < t < 10.0 else None))
    (track,) = gate.tracks
    assert math.isfinite(track.end_hi) == learnt
    if learnt:
        assert track.end_hi == pytest.approx(4.0, abs=0.01)


def test_no_end_is_guessed_when_the_mover_may_have_turned_three_times_out_of_sight():
    """A 1 m track at 0.5 m/s, seen for 1.5 s, then unseen for 5.8 s (turns at 2, 4 and 6 s):
    the one-turn formula would put the far end at 2 m; the gate learns nothing instead."""
    rows = lambda t: mover_at(t, a=(6.0, 1.0), b=(6.0, 2.0))
    gate = SweepGate()
    gate.reset(None, RobotState(3.0, 3.0, 0.0), np.zeros((2, 2)))
    for k in range(0, 74):
        t = round(k * 0.1, 10)
        gate.update(context(t, dynamic=np.zeros((0, 5)) if 1.5 < t < 7.3 else rows(t)))
    (track,) = gate.tracks
    assert track.heading < 0  # it came back heading the other way
    assert not math.isfinite(track.end_hi) and not math.isfinite(track.end_lo)


def test_a_robot_held_beside_a_busy_sweep_goes_round_it():
    """li2023_exp2_4, seed 14: next to the start a mover sweeps 1.1 m back and forth
    across the path every 4.9 s. This robot (0.2 m/s^2) needs about 3.7 s from rest to
    cross the band, and the gap between two passes lasts about 1.5 s, so it used to wait
    there until its stuck re-plans ran out (status "stuck"). The stuck re-plan now treats
    the learnt sweep as an obstacle and finds the way north round the block."""
    res = simulate("li2023_exp2_4", global_planner="astar", local_planner="qp-dwa", seed=14)
    assert res.reached and res.collisions == 0 and res.replans >= 1


def test_a_rollout_that_crosses_the_movers_line_between_two_points_gets_the_deepest_gap():
    """Rollout points 0.1 s apart step over a mover's line and miss it by chance (here by
    more than 5 mm); measured for the gate's least-close rule, a straight rollout that crosses
    the line where the mover may be gets the gap of the line's middle, ``-(r + R)``, and one
    that stops short of the line keeps its points' gap."""
    planner = make_local_planner("qp-dwa", ROBOT, 0.1)
    state = RobotState(x=4.8, y=3.1, theta=0.0, v=0.6)
    planner.reset(state, np.array([[0.5, 3.0], [11.0, 3.0]]))
    ctx = context(4.5, state)
    (gate,) = [m for m in planner.mechanisms if isinstance(m, SweepGate)]
    deep = -(0.35 + ROBOT.radius)  # the mover's and the robot's radii
    stepped_over = 0
    for v in np.linspace(0.0, 0.7, 71):
        straight = planner._assess(ctx, planner.rollout_of(state, [v], [0.0], [0.0]))
        gate.strict_filter(planner.view, straight, crossings=True)  # as the least-close rule measures
        gap = straight.aux["gate_gap"][0]
        x = straight.roll.z[0].real
        points_gap = np.abs(x - 6.0).min() - 0.35 - ROBOT.radius
        if x[-1] > 6.0:
            assert gap == pytest.approx(deep, abs=1e-12)
            stepped_over += points_gap > deep + 0.005
        else:
            assert gap == pytest.approx(points_gap, abs=1e-9)
    assert stepped_over >= 5
