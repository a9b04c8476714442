"""The window program: one control period's local planning problem, written once.

The local twin of :class:`~optplan.formulations.program.PathProgram` (DESIGN.md, "Local
programs"). Its decision variables are the commands ``U`` of ``K`` control intervals over
the horizon, piecewise constant: ``(v, w)`` for a unicycle, ``(v, w, vy)`` for an omni
robot (``K = 1`` is DWA's one constant command). The states ``Z`` (``(N + 1, 3)`` rows
``x, y, theta``, ``m`` Euler steps per interval, the simulator's motion model) follow
from them. Terms and constraints are written once, each with

* a **batched** view over many command sequences at once (``(S, K, nu)``), what a
  sampling solver evaluates (numpy, no loop over samples), and
* a **symbolic** view (CasADi), what the NMPC solver differentiates.

Both views see the same :class:`Situation`: the robot's state, the subgoal, the global
path, the static distance field and the movers. Where the symbolic view cannot hold the
exact function (the static distance field is a sampled table), it holds its first-order
model around a reference trajectory (the warm start); every solver's answer is then
judged by :meth:`LocalProgram.evaluate`, the batched view, exactly as a sample is.

    lp = LocalProgram(robot, horizon=2.0, intervals=10)
    lp.minimize(1.0 * LT.goal_distance() + 0.5 * LT.path_distance() - 0.2 * LT.speed()
                + LT.custom(lambda Z, U, m: ..., name="prefer_left"))
    lp.subject_to(LT.clearance() >= 0.05)
    lp.subject_to(LT.can_stop())
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..errors import ParameterError
from ..world.robot import RobotSpec
from .namespaces import Batch, BatchNamespace, Sym, SymbolicNamespace

# metres of shortfall added for touching a static obstacle: more than any mover shortfall
# can be (the sum of two radii and margins), so any plan clear of the walls ranks first
CONTACT_PENALTY = 10.0
_SMOOTH = 1e-9  # under square roots of the symbolic view: differentiable at 0


@dataclass
class Situation:
    """What a window program is solved for at one control step.

    Attributes:
        state: ``(x, y, theta, v, w, vy)`` now.
        subgoal: ``(2,)`` target point, metres.
        path: ``(N, 2)`` global path, metres.
        static_distance: ``(..., 2) -> (...)`` signed distance from a point to the static
            obstacles known now (robot radius not subtracted).
        movers: ``(k, 5)`` rows ``(x, y, vx, vy, radius)`` now.
        distance_error: how much ``static_distance`` may overestimate the true distance, m
            (a position within it of an obstacle counts as touching it).
        mover_ends: ``(k, 2)`` rows ``(behind, ahead)``, or ``None``: where each mover is known
            to turn round, metres along its direction of motion from where it is now
            (``behind <= 0 <= ahead``; ``-inf`` / ``inf``: not known on that side). A mover is
            predicted at constant speed, turning round at its known ends
            (:func:`mover_intervals`); ``None`` (or infinite ends): straight on.
        mover_seen: ``(k, 2)`` rows ``(behind, ahead)``, or ``None``: the farthest points of
            its line each mover has been seen at, behind and ahead of it (``<= 0``, ``>= 0``).
            Given, a mover may also turn round at any point at or beyond them where no end is
            known, so it is predicted as an interval of its line; ``None``: an end not known
            is not predicted (straight on past it).
        mover_reach: ``(k, 2)`` rows ``(behind, ahead)``, or ``None``: how far along its line
            each mover can go before it touches a static obstacle the robot knows or the map's
            border (``-inf`` / ``inf``: no such limit). A mover turns round there at the latest,
            where no end is known on that side.
        samples: a sampling solver's assessed samples of this step
            (:class:`optplan.local.preset_programs.SampleSet`), for the terms judged against
            the other samples of their step (the papers' critics); ``None`` otherwise.
    """

    state: np.ndarray
    subgoal: np.ndarray
    path: np.ndarray
    static_distance: Callable[[np.ndarray], np.ndarray]
    movers: np.ndarray = field(default_factory=lambda: np.zeros((0, 5)))
    distance_error: float = 0.0
    mover_ends: np.ndarray | None = None
    mover_seen: np.ndarray | None = None
    mover_reach: np.ndarray | None = None
    samples: object | None = None


def bounce(run: np.ndarray, behind: np.ndarray, ahead: np.ndarray) -> np.ndarray:
    """Position along its line of a point that has moved ``run`` metres (``>= 0``) from 0 in the
    positive direction, turning round at ``ahead`` (``>= 0``) and ``behind`` (``<= 0``);
    an infinite end means no turn on that side. Arrays broadcast against each other.

    Both ends finite: a back-and-forth motion between them (unfolded onto a circle of length
    twice the span). Only ``ahead`` finite: one turn there, then straight back (the point
    is not known to turn anywhere behind). Only ``behind`` finite, or none: straight on (a
    turn behind needs a turn ahead first)."""
    run, lo, hi = np.broadcast_arrays(*(np.asarray(a, float) for a in (run, behind, ahead)))
    fin_lo, fin_hi = np.isfinite(lo), np.isfinite(hi)
    L = np.where(fin_lo, np.minimum(lo, 0.0), 0.0)
    H = np.where(fin_hi, np.maximum(hi, 0.0), 0.0)
    span = np.maximum(H - L, 1e-12)
    u = np.mod(run - L, 2.0 * span)
    both = L + np.where(u <= span, u, 2.0 * span - u)
    once = np.where(run <= H, run, 2.0 * H - run)
    return np.where(fin_hi, np.where(fin_lo, both, once), run)


def mover_intervals(speed: np.ndarray, ends: np.ndarray | None, seen: np.ndarray | None,
                    t: np.ndarray, reach: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``(lo, hi)``, each ``(k, T)``: the stretch of its line each of ``k`` movers may be on
    ``t`` ``(T,)`` seconds ahead, metres along its direction of motion from where it is now.

    A mover drives at its constant ``speed`` ``(k,)`` and turns round at its known ends
    (``ends``, as :attr:`Situation.mover_ends`): then ``lo == hi``, one predicted position
    (:func:`bounce`). With ``seen`` (:attr:`Situation.mover_seen`) it may also turn round at
    any point at or beyond the farthest point seen on a side whose end is not known (a
    shuttle turns only at the ends of its track, and the track holds every point it was seen
    at), so the stretch is the hull of every such motion: with the end ahead unknown, from
    where a turn at the farthest point seen ahead ``a0`` brings it back (``2 a0 - run``, not
    past a known end behind) to straight on (``run``); with the end ahead known at ``a`` and
    the one behind unknown, from its position ``q`` after the turn at ``a`` to where a turn at
    the farthest point seen behind ``b0`` brings it (``2 b0 - q``, not past ``a``).

    ``reach`` (:attr:`Situation.mover_reach`): a mover cannot drive through a wall, so on a side
    whose end is not known it turns round where it would touch one at the latest; straight on
    past that point is never predicted."""
    speed = np.asarray(speed, float).reshape(-1)
    run = speed[:, None] * np.asarray(t, float).reshape(1, -1)
    E = np.full((len(speed), 2), [-np.inf, np.inf]) if ends is None else np.asarray(ends, float).reshape(-1, 2)
    b, a = E[:, :1], E[:, 1:]
    ak, bk = np.isfinite(a), np.isfinite(b)
    if reach is not None:   # where no end is known, the wall is where it turns at the latest
        R = np.asarray(reach, float).reshape(-1, 2)
        b, a = np.where(bk, b, np.minimum(R[:, :1], 0.0)), np.where(ak, a, np.maximum(R[:, 1:], 0.0))
    point = bounce(run, b, a)
    if seen is None:
        return point, point
    V = np.asarray(seen, float).reshape(-1, 2)
    b0, a0 = np.minimum(V[:, :1], 0.0), np.maximum(V[:, 1:], 0.0)
    ahead_open = ~ak & (run > a0)                      # it may have turned at an unknown end ahead
    behind_open = ak & ~bk & (point < b0)              # back past the farthest point seen behind
    # (not behind a known end or the wall behind: ``b`` is either, or -inf)
    lo = np.where(ahead_open, np.minimum(np.maximum(2.0 * a0 - run, b), point), point)
    hi = np.where(behind_open, np.minimum(2.0 * b0 - point, a), point)
    return lo, hi


def predicted_movers(movers: np.ndarray, ends: np.ndarray | None, t: np.ndarray,
                     seen: np.ndarray | None = None,
                     reach: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``(A, B)``, each ``(k, T, 2)``: the ends of the stretch each mover ``(k, 5)`` may be on
    at ``t`` ``(T,)`` seconds ahead (:func:`mover_intervals`; ``A == B`` where its motion is
    predicted exactly, e.g. every mover when ``seen`` is ``None``)."""
    M = np.asarray(movers, float).reshape(-1, 5)
    t = np.asarray(t, float).reshape(-1)
    speed = np.hypot(M[:, 2], M[:, 3])
    u = M[:, 2:4] / np.where(speed > 0, speed, 1.0)[:, None]
    lo, hi = mover_intervals(speed, ends, seen, t, reach)
    lo, hi = (np.where(speed[:, None] > 0, x, 0.0) for x in (lo, hi))   # a standing mover stays
    return M[:, None, :2] + lo[..., None] * u[:, None, :], M[:, None, :2] + hi[..., None] * u[:, None, :]


def motion_known(sit: "Situation") -> np.ndarray:
    """``(k,)``: whether each mover's motion is known: both its turning points seen
    (:attr:`Situation.mover_ends`), so it is predicted exactly, a shuttle between them. A
    clearance's ``mover_growth`` (a prediction errs more the farther it looks) is the error of
    a motion not known, and is not added for these."""
    k = np.asarray(sit.movers, float).reshape(-1, 5).shape[0]
    if sit.mover_ends is None:
        return np.zeros(k, dtype=bool)
    return np.isfinite(np.asarray(sit.mover_ends, float).reshape(-1, 2)).all(axis=1)


def _segment_gap(P: np.ndarray, A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Distance from points ``P`` ``(S, T, 2)`` to the segments ``A[t] -> B[t]`` ``(T, 2)``
    (the symbolic rows' formula: a point segment is its point)."""
    d = B - A
    k = np.clip(((P - A) * d).sum(axis=-1) / ((d * d).sum(axis=-1) + _SMOOTH), 0.0, 1.0)
    return np.hypot(*(P - A - k[..., None] * d).transpose(2, 0, 1))


# ----------------------------------------------------------------------------- expressions
class LocalTerm:
    """One scalar term of the objective: ``batched(Z, U, sit, prog) -> (S,)`` and
    ``symbolic(Z, U, ps, prog) -> casadi scalar``, ``ps`` the :class:`SymbolicSituation`
    (the situation as solver parameters, so a solver is built once)."""

    name = "term"

    def batched(self, Z, U, sit: Situation, prog: "LocalProgram") -> np.ndarray:
        raise NotImplementedError

    def symbolic(self, Z, U, ps: "SymbolicSituation", prog: "LocalProgram"):
        raise NotImplementedError

    def __mul__(self, w) -> "LocalObjective":
        return LocalObjective([(float(w), self)])

    __rmul__ = __mul__

    def __add__(self, other) -> "LocalObjective":
        return LocalObjective([(1.0, self)]) + other

    def __sub__(self, other) -> "LocalObjective":
        return LocalObjective([(1.0, self)]) + (-1.0) * other

    def __neg__(self) -> "LocalObjective":
        return LocalObjective([(-1.0, self)])


class LocalObjective:
    """A weighted sum of :class:`LocalTerm`."""

    def __init__(self, parts: list[tuple[float, LocalTerm]]) -> None:
        self.parts = list(parts)

    def __add__(self, other) -> "LocalObjective":
        other = other if isinstance(other, LocalObjective) else LocalObjective([(1.0, other)])
        return LocalObjective(self.parts + other.parts)

    __radd__ = __add__

    def __sub__(self, other) -> "LocalObjective":
        return self + (-1.0) * (other if isinstance(other, LocalObjective) else LocalObjective([(1.0, other)]))

    def __mul__(self, w) -> "LocalObjective":
        return LocalObjective([(float(w) * a, t) for a, t in self.parts])

    __rmul__ = __mul__

    def __neg__(self) -> "LocalObjective":
        return self * -1.0


class LocalConstraint:
    """A constraint: ``batched(...) -> (S,)`` violation (0 when it holds) and
    ``symbolic(...) -> list of (expression, lower bound)`` rows ``expression >= lower``."""

    name = "constraint"

    def batched(self, Z, U, sit: Situation, prog: "LocalProgram") -> np.ndarray:
        raise NotImplementedError

    def symbolic(self, Z, U, ps: "SymbolicSituation", prog: "LocalProgram") -> list:
        raise NotImplementedError


def _point_segment_distance(P: np.ndarray, A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Distance from points ``(..., 2)`` to the nearest of segments ``A[i] -> B[i]``."""
    d = B - A
    L2 = np.maximum((d * d).sum(axis=1), 1e-18)
    rel = P[..., None, :] - A
    t = np.clip((rel * d).sum(axis=-1) / L2, 0.0, 1.0)
    q = A + t[..., None] * d
    return np.sqrt(((P[..., None, :] - q) ** 2).sum(axis=-1)).min(axis=-1)


def _near_path(sit: Situation, reach: float) -> tuple[np.ndarray, np.ndarray]:
    """The global path's segments within ``reach`` of the robot (all when none is)."""
    P = np.asarray(sit.path, float)
    if len(P) < 2:
        P = np.vstack([sit.state[:2], sit.subgoal])
    A, B = P[:-1], P[1:]
    d = B - A
    L2 = np.maximum((d * d).sum(axis=1), 1e-18)
    t = np.clip(((sit.state[:2] - A) * d).sum(axis=1) / L2, 0.0, 1.0)
    gap = np.hypot(*(A + t[:, None] * d - sit.state[:2]).T)
    keep = gap <= reach
    if not keep.any():
        keep[np.argmin(gap)] = True
    return A[keep], B[keep]


class GoalDistance(LocalTerm):
    """Distance from the last predicted position to the subgoal, metres."""

    name = "goal_distance"

    def batched(self, Z, U, sit, prog):
        return np.hypot(Z[:, -1, 0] - sit.subgoal[0], Z[:, -1, 1] - sit.subgoal[1])

    def symbolic(self, Z, U, ps, prog):
        import casadi as ca

        return ca.sqrt((Z[-1, 0] - ps.subgoal[0]) ** 2 + (Z[-1, 1] - ps.subgoal[1]) ** 2 + _SMOOTH)


class GoalHeading(LocalTerm):
    """``1 - cos`` of the angle between the last predicted heading and the bearing from the
    last predicted position to the subgoal (0 facing it, 2 facing away)."""

    name = "goal_heading"

    def batched(self, Z, U, sit, prog):
        bearing = np.arctan2(sit.subgoal[1] - Z[:, -1, 1], sit.subgoal[0] - Z[:, -1, 0])
        return 1.0 - np.cos(Z[:, -1, 2] - bearing)

    def symbolic(self, Z, U, ps, prog):
        import casadi as ca

        bearing = ca.atan2(ps.subgoal[1] - Z[-1, 1], ps.subgoal[0] - Z[-1, 0])
        return 1.0 - ca.cos(Z[-1, 2] - bearing)


class PathDistance(LocalTerm):
    """Mean distance of the predicted positions to the global path, metres. The symbolic
    view measures each position against the segment its reference position is nearest to:
    its line, or its end point where the reference lies beyond it."""

    name = "path_distance"

    def batched(self, Z, U, sit, prog):
        A, B = _near_path(sit, prog.reach)
        return _point_segment_distance(Z[:, 1:, :2], A, B).mean(axis=1)

    def symbolic(self, Z, U, ps, prog):
        import casadi as ca

        total = 0
        for j in range(1, Z.shape[0]):
            nx, ny, c, end, ex, ey = (ps.lines[j - 1, i] for i in range(6))
            line = ca.sqrt((nx * Z[j, 0] + ny * Z[j, 1] - c) ** 2 + _SMOOTH)
            point = ca.sqrt((Z[j, 0] - ex) ** 2 + (Z[j, 1] - ey) ** 2 + _SMOOTH)
            total += (1 - end) * line + end * point
        return total / (Z.shape[0] - 1)


class Speed(LocalTerm):
    """Mean forward speed over the intervals, m/s (reward it with a negative weight)."""

    name = "speed"

    def batched(self, Z, U, sit, prog):
        return U[:, :, 0].mean(axis=1)

    def symbolic(self, Z, U, ps, prog):
        import casadi as ca

        return ca.sum1(U[:, 0]) / U.shape[0]


class Smoothness(LocalTerm):
    """Sum of squared command changes from the current command on, per interval
    (``(m/s)^2`` and ``(rad/s)^2``)."""

    name = "smoothness"

    def batched(self, Z, U, sit, prog):
        now = prog.current_command(sit)
        D = np.diff(np.concatenate([np.broadcast_to(now, (len(U), 1, U.shape[2])), U], axis=1), axis=1)
        return (D ** 2).sum(axis=(1, 2))

    def symbolic(self, Z, U, ps, prog):
        import casadi as ca

        prev = ps.command.T
        total = 0
        for k in range(U.shape[0]):
            total += ca.sumsqr(U[k, :] - prev)
            prev = U[k, :]
        return total


class Custom(LocalTerm):
    """``fn(Z, U, m)`` over the predicted states ``Z`` ``(N + 1, 3)`` and commands ``U``
    ``(K, nu)``, with ``m`` a numpy-like namespace (``sum``, ``sqrt``, ``exp``, ``atan2``,
    ...): written once, evaluated batched and symbolically."""

    def __init__(self, fn: Callable, name: str = "custom") -> None:
        if not callable(fn):
            raise ParameterError(f"custom needs a function fn(Z, U, m), got {fn!r:.60}")
        self.fn, self.name = fn, str(name)

    def batched(self, Z, U, sit, prog):
        out = self.fn(Batch(Z), Batch(U), BatchNamespace)
        a = out.a if isinstance(out, Batch) else np.broadcast_to(np.asarray(out, float), (len(Z),))
        if a.shape != (len(Z),):
            raise ParameterError(f"custom term {self.name!r} must return one number per trajectory, got shape "
                                 f"{a.shape[1:]} per trajectory")
        return np.asarray(a, float)

    def symbolic(self, Z, U, ps, prog):
        out = self.fn(Sym(Z, tuple(Z.shape)), Sym(U, tuple(U.shape)), SymbolicNamespace)
        if isinstance(out, Sym):
            if out.shape != ():
                raise ParameterError(f"custom term {self.name!r} must return a scalar, got shape {out.shape}")
            return out.m
        return float(out)


class ObstacleCost(LocalTerm):
    """Mean over the predicted positions of ``exp(-gap / scale)`` summed over the static
    obstacles' gap and each predicted mover's (edge to edge, metres); the symbolic view
    holds the solver's mover slots, the nearest movers."""

    name = "obstacle_cost"

    def __init__(self, scale: float = 0.3) -> None:
        self.scale = float(scale)

    def batched(self, Z, U, sit, prog):
        total = np.exp(-prog.static_gap(Z, sit) / self.scale)
        for gap in prog.mover_gaps(Z, sit):
            total += np.exp(-gap / self.scale)
        return total.mean(axis=1)

    def symbolic(self, Z, U, ps, prog):
        import casadi as ca

        rows = prog.static_rows(Z, ps) + prog.mover_rows(Z, ps, squared=False)
        total = 0
        for expr in rows:
            total += ca.exp(-expr / self.scale)
        return total / max(Z.shape[0] - 1, 1)


class Clearance(LocalConstraint):
    """Every predicted position keeps ``margin`` metres between the robot's edge and the
    static obstacles, and ``margin + mover_margin + mover_growth * t`` from every mover as
    predicted (``t`` seconds ahead: a prediction errs more the farther it looks; the growth is
    not added for a mover whose motion is known, :func:`motion_known`): at constant speed,
    turning round at its known ends, and, where a turn is possible but not known, the whole
    stretch of its line it may be on (:func:`mover_intervals`, from :attr:`Situation.mover_ends`
    and :attr:`Situation.mover_seen`). Its violation is the deepest shortfall along the
    window, plus :data:`CONTACT_PENALTY` where the robot would touch a static obstacle."""

    name = "clearance"

    def __init__(self, margin: float = 0.0, mover_margin: float = 0.0, mover_growth: float = 0.0,
                 mover_turns: bool = False) -> None:
        for what, v in (("margin", margin), ("mover_margin", mover_margin), ("mover_growth", mover_growth)):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
                raise ParameterError(f"clearance {what} must be a finite number >= 0, got {v!r}")
        if not isinstance(mover_turns, bool):
            raise ParameterError(f"clearance mover_turns must be True or False, got {mover_turns!r}")
        self.margin, self.mover_margin, self.mover_growth = float(margin), float(mover_margin), float(mover_growth)
        self.mover_turns = mover_turns

    def __ge__(self, margin: float) -> "Clearance":
        return Clearance(margin, self.mover_margin, self.mover_growth, self.mover_turns)

    def _mover_need(self, prog, n: int) -> tuple[float, np.ndarray]:
        """``(fixed, growth (n,))``: the mover margin is ``fixed + growth[j]`` at state ``j``,
        the growth only for movers whose motion is not known (:func:`motion_known`)."""
        return self.margin + self.mover_margin, self.mover_growth * prog.h * np.arange(1, n + 1)

    def batched(self, Z, U, sit, prog):
        gap = prog.static_gap(Z, sit)
        # touching a static obstacle is certain harm, a mover's predicted shortfall is not: when
        # nothing holds (a mover closing in), the least violating plan must not be one that
        # trades mover clearance for contact with a wall
        touch = gap - sit.distance_error
        short = np.maximum(self.margin - gap, 0.0) + np.where(touch < 0.0, CONTACT_PENALTY - touch, 0.0)
        fixed, growth = self._mover_need(prog, Z.shape[1] - 1)
        known = motion_known(sit) & (not self.mover_turns)
        for i, gap in enumerate(prog.mover_gaps(Z, sit, turns=self.mover_turns)):
            short = np.maximum(short, fixed + (0.0 if known[i] else growth) - gap)
        return short.max(axis=1)   # the deepest shortfall along the window

    def symbolic(self, Z, U, ps, prog):
        rows = [(e, self.margin) for e in prog.static_rows(Z, ps)]
        fixed, growth = self._mover_need(prog, Z.shape[0] - 1)
        rows += [(e, 0.0) for e in prog.mover_rows(Z, ps, squared=True, margin=fixed, growth=growth,
                                                    turns=self.mover_turns)]
        return rows


class CanStop(LocalConstraint):
    """Recursive feasibility: at the end of the horizon the robot can brake to a stop, at
    its acceleration limit, before the static obstacles ahead: ``v_K^2 <= 2 a (gap - margin)``."""

    name = "can_stop"

    def __init__(self, margin: float = 0.0) -> None:
        self.margin = float(margin)

    def batched(self, Z, U, sit, prog):
        gap = prog.static_gap(Z[:, -1:], sit)[:, 0]
        v = np.abs(U[:, -1, 0])
        return np.maximum(v * v - 2.0 * prog.robot.a_max * np.maximum(gap - self.margin, 0.0), 0.0)

    def symbolic(self, Z, U, ps, prog):
        gap = prog.static_rows(Z, ps)[-1]
        return [(2.0 * prog.robot.a_max * (gap - self.margin) - U[-1, 0] ** 2, 0.0)]


class StopClear(LocalConstraint):
    """Recursive feasibility against movers: braking to a stop at the end of the window, at its
    acceleration limit, the robot stands clear of every predicted mover (``margin`` metres,
    edge to edge) for ``hold`` seconds more (sampled at the window's interval times).

    The next window can then always stand still: a plan may not end where the robot would
    have to stop in a mover's way (on a track it is known to sweep, ahead of one driving
    straight at the stopping point), only where it can wait. The robot is counted at its
    stopping point over the whole hold (it gets there within ``v / a`` seconds)."""

    name = "stop_clear"

    def __init__(self, hold: float = 2.0, margin: float = 0.0, sweep: bool = True) -> None:
        for what, v in (("hold", hold), ("margin", margin)):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
                raise ParameterError(f"stop_clear {what} must be a finite number >= 0, got {v!r}")
        self.hold, self.margin = float(hold), float(margin)
        # False: over the hold a mover is predicted on at constant speed, turning round at its
        # known ends only (not anywhere past where it was seen)
        self.sweep = bool(sweep)

    def times(self, prog: "LocalProgram") -> np.ndarray:
        """Seconds from now at which the stopped robot is checked: the window's end plus
        ``hold`` in ``K`` steps."""
        return prog.horizon + self.hold * np.arange(1, prog.K + 1) / prog.K

    def _stop(self, Z, U, prog, symbolic: bool):
        """The stopping point ``(x, y)`` after braking from the last command: the velocity's
        direction times its braking distance ``|u|^2 / (2 a)``."""
        if symbolic:
            import casadi as ca

            cos, sin, fabs, sqrt = ca.cos, ca.sin, ca.fabs, lambda q: ca.sqrt(q + _SMOOTH ** 2)
        else:
            cos, sin, fabs, sqrt = np.cos, np.sin, np.abs, np.sqrt
        omni = prog.nu == 3
        a = prog.robot.a_max / math.sqrt(2) if omni else prog.robot.a_max
        v, vy = U[..., -1, 0] if not symbolic else U[-1, 0], 0.0
        if omni:
            vy = U[..., -1, 2] if not symbolic else U[-1, 2]
        speed = sqrt(v * v + vy * vy) if omni else fabs(v)
        th = Z[..., -1, 2] if not symbolic else Z[-1, 2]
        x0, y0 = (Z[..., -1, 0], Z[..., -1, 1]) if not symbolic else (Z[-1, 0], Z[-1, 1])
        c, s = cos(th), sin(th)
        return x0 + (v * c - vy * s) * speed / (2 * a), y0 + (v * s + vy * c) * speed / (2 * a)

    def stop_gaps(self, Z, U, sit, prog):
        """``(S, T)`` per sensed mover: the gap (edge to edge, m) between the robot stopped after
        the window and that mover at each of :meth:`times` (batched view)."""
        x, y = self._stop(Z, U, prog, False)
        P = np.broadcast_to(np.stack([x, y], axis=-1)[:, None, :], (len(Z), len(self.times(prog)), 2))
        M = np.asarray(sit.movers, float).reshape(-1, 5)
        if not len(M):
            return
        A, B = predicted_movers(M, sit.mover_ends, self.times(prog), sit.mover_seen if self.sweep else None,
                                sit.mover_reach)
        for i in range(len(M)):
            yield _segment_gap(P, A[i], B[i]) - M[i, 4] - prog.robot.radius

    def stop_squared(self, Z, U, ps, prog):
        """``(d2, r)`` per mover slot and time of :meth:`times`: the squared distance from the
        stopped robot to the nearest point of the slot's predicted stretch, and its radius
        (symbolic view; the stretches follow the window's in ``SymbolicSituation.mover_path``)."""
        import casadi as ca

        px, py = self._stop(Z, U, prog, True)
        T, base = len(self.times(prog)), 4 * prog.N
        for i in range(ps.movers.shape[0]):
            for j in range(T):
                ax, ay = ps.mover_path[i, base + j], ps.mover_path[i, base + T + j]
                dx, dy = ps.mover_path[i, base + 2 * T + j] - ax, ps.mover_path[i, base + 3 * T + j] - ay
                k = ca.fmin(1, ca.fmax(0, ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy + _SMOOTH)))
                yield (px - ax - k * dx) ** 2 + (py - ay - k * dy) ** 2, ps.movers[i, 4]

    def batched(self, Z, U, sit, prog):
        short = np.zeros(len(Z))
        for gap in self.stop_gaps(Z, U, sit, prog):
            short = np.maximum(short, (self.margin - gap).max(axis=1))
        return short

    def symbolic(self, Z, U, ps, prog):
        return [(d2 - (prog.robot.radius + r + self.margin) ** 2, 0.0) for d2, r in self.stop_squared(Z, U, ps, prog)]


class StopCost(LocalTerm):
    """The soft twin of :class:`StopClear`: braking to a stop from the end of the window, how
    close the stopped robot comes to each predicted mover over ``hold`` seconds more, as the
    mean over those times of ``exp(-gap / scale)`` summed over the movers (edge to edge,
    metres; movers predicted straight on, turning at ends they were seen to turn at). A plan
    heading where a mover will be soon after the window costs more, before any constraint
    is violated; unlike the constraint, it never leaves a plan infeasible."""

    name = "stop_cost"

    def __init__(self, hold: float = 2.0, scale: float = 0.3) -> None:
        for what, v in (("hold", hold), ("scale", scale)):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ParameterError(f"stop_cost {what} must be a finite number > 0, got {v!r}")
        self.hold, self.scale = float(hold), float(scale)
        self._clear = StopClear(hold, 0.0, sweep=False)

    def times(self, prog: "LocalProgram") -> np.ndarray:
        return self._clear.times(prog)

    def batched(self, Z, U, sit, prog):
        total = np.zeros((len(Z), len(self.times(prog))))
        for gap in self._clear.stop_gaps(Z, U, sit, prog):
            total += np.exp(-gap / self.scale)
        return total.mean(axis=1)

    def symbolic(self, Z, U, ps, prog):
        import casadi as ca

        total = 0
        for d2, r in self._clear.stop_squared(Z, U, ps, prog):
            total += ca.exp(-(ca.sqrt(d2 + _SMOOTH) - r - prog.robot.radius) / self.scale)
        return total / max(len(self.times(prog)), 1)


class SymbolicSituation:
    """The situation as CasADi parameters of one built solver (``opti.parameter``): the
    state ``(6,)``, the subgoal ``(2,)``, the current command ``(nu,)``, each predicted
    position's path line ``(N, 6)`` (unit normal, offset, and whether the reference lies
    beyond the segment, with that end point), the static field's model
    ``(N, 5)`` (value, gradient, reference point), ``(max_movers, 5)`` mover slots and the
    stretches they are predicted on ``(max_movers, 4 N + 4 H)`` (the ``N`` x and ``N`` y of one
    end, then of the other, at the window's times; the same point twice where the motion is
    predicted exactly; then the same at the ``H`` times of :meth:`LocalProgram.hold_times`),
    and whether each slot's motion is known ``(max_movers,)`` (1 or 0, :func:`motion_known`)."""

    def __init__(self, opti, prog: "LocalProgram", max_movers: int) -> None:
        self.state = opti.parameter(6)
        self.subgoal = opti.parameter(2)
        self.command = opti.parameter(prog.nu)
        self.lines = opti.parameter(prog.N, 6)
        self.static = opti.parameter(prog.N, 5)
        self.movers = opti.parameter(max_movers, 5)
        self.mover_path = opti.parameter(max_movers, 4 * (prog.N + len(prog.hold_times())))
        self.mover_known = opti.parameter(max_movers)
        self.opti = opti

    def set(self, values: dict) -> None:
        for name, value in values.items():
            self.opti.set_value(getattr(self, name), value)


# ----------------------------------------------------------------------------- the program
class LocalProgram:
    """The window program of one robot: commands over ``intervals`` intervals of a
    ``horizon``-second window, ``step``-second Euler steps (the simulator's model).

    Args:
        robot: the :class:`RobotSpec` (model, limits, radius).
        horizon: seconds predicted.
        intervals: piecewise-constant command intervals ``K`` (1 = DWA's constant command).
        step: Euler step of the prediction, seconds (rounded so that each interval holds a
            whole number of steps).
    """

    def __init__(self, robot: RobotSpec, horizon: float = 2.0, intervals: int = 10, step: float = 0.1,
                 name: str = "window") -> None:
        if not isinstance(robot, RobotSpec):
            raise ParameterError(f"robot must be an op.RobotSpec, got {type(robot).__name__}")
        for what, v in (("horizon", horizon), ("step", step)):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ParameterError(f"{what} must be a positive number of seconds, got {v!r}")
        if isinstance(intervals, bool) or not isinstance(intervals, (int, np.integer)) or intervals < 1:
            raise ParameterError(f"intervals must be an integer >= 1, got {intervals!r}")
        self.robot, self.name = robot, str(name)
        self.K = int(intervals)
        self.m = max(1, int(round(horizon / self.K / step)))
        self.h = float(horizon) / (self.K * self.m)
        self.horizon = float(horizon)
        self.omni = robot.model == "omni" and robot.vy_max > 0
        self.nu = 3 if self.omni else 2
        self.objective: list[tuple[float, LocalTerm]] = []
        self.constraints: list[LocalConstraint] = []
        # path segments farther than this from the robot do not matter to the window
        self.reach = self.horizon * max(robot.v_max, 1e-3) + 1.0

    @property
    def N(self) -> int:
        """Predicted states after the start."""
        return self.K * self.m

    def minimize(self, objective) -> "LocalProgram":
        objective = objective if isinstance(objective, LocalObjective) else LocalObjective([(1.0, objective)])
        for w, t in objective.parts:
            if not isinstance(t, LocalTerm) or not math.isfinite(w):
                raise ParameterError(f"an objective is a weighted sum of local terms, got {t!r:.60}")
        self.objective = list(objective.parts)
        return self

    def subject_to(self, constraint: LocalConstraint) -> "LocalProgram":
        if not isinstance(constraint, LocalConstraint):
            raise ParameterError(f"subject_to takes a local constraint (clearance() >= d, can_stop()), "
                                 f"got {constraint!r:.60}")
        self.constraints.append(constraint)
        return self

    # ------------------------------------------------------------------ dynamics
    def current_command(self, sit: Situation) -> np.ndarray:
        s = np.asarray(sit.state, float)
        return np.array([s[3], s[4], s[5]][:self.nu])

    def rollout(self, sit: Situation, U: np.ndarray) -> np.ndarray:
        """States ``(S, N + 1, 3)`` of command sequences ``U`` ``(S, K, nu)`` (batched view)."""
        U = np.asarray(U, float)
        S = len(U)
        Uf = np.repeat(U, self.m, axis=1)                          # (S, N, nu)
        theta = sit.state[2] + np.concatenate([np.zeros((S, 1)), np.cumsum(Uf[:, :, 1] * self.h, axis=1)], axis=1)
        c, s = np.cos(theta[:, :-1]), np.sin(theta[:, :-1])
        vy = Uf[:, :, 2] if self.nu == 3 else 0.0
        dx = (Uf[:, :, 0] * c - vy * s) * self.h
        dy = (Uf[:, :, 0] * s + vy * c) * self.h
        Z = np.empty((S, self.N + 1, 3))
        Z[:, 0, 0], Z[:, 0, 1] = sit.state[0], sit.state[1]
        Z[:, 1:, 0] = sit.state[0] + np.cumsum(dx, axis=1)
        Z[:, 1:, 1] = sit.state[1] + np.cumsum(dy, axis=1)
        Z[:, :, 2] = theta
        return Z

    def step_symbolic(self, z, u):
        """One Euler step of the symbolic view (``z`` a 1x3 row, ``u`` a 1 x nu row)."""
        import casadi as ca

        c, s = ca.cos(z[2]), ca.sin(z[2])
        vy = u[2] if self.nu == 3 else 0.0
        return ca.horzcat(z[0] + (u[0] * c - vy * s) * self.h, z[1] + (u[0] * s + vy * c) * self.h,
                          z[2] + u[1] * self.h)

    # ------------------------------------------------------------------ obstacles, both views
    def hold_times(self) -> np.ndarray:
        """Times after the window at which a :class:`StopClear` constraint checks the movers
        (none without one)."""
        for c in self.constraints:
            if isinstance(c, StopClear):
                return c.times(self)
        for _, t in self.objective:
            if isinstance(t, StopCost):
                return t.times(self)
        return np.zeros(0)

    def static_gap(self, Z: np.ndarray, sit: Situation) -> np.ndarray:
        """``(S, n)``: distance from the robot's edge to the static obstacles at the states
        ``Z[:, :]`` except the start (the start is where the robot is)."""
        P = Z[:, 1:, :2] if Z.shape[1] > 1 else Z[:, :, :2]
        return np.asarray(sit.static_distance(P), float) - self.robot.radius

    def mover_gaps(self, Z: np.ndarray, sit: Situation, turns: bool = False):
        """``(S, n)`` per mover: distance from the robot's edge to that predicted mover's edge
        (:func:`predicted_movers`: constant speed, turning round at its known ends; the
        nearest point of the stretch it may be on where a turn is possible but not known).
        ``turns``: the mover may turn round at any moment, so ``t`` seconds ahead it is
        anywhere on its line within ``|v| t`` of where it is now (a segment, not a point)."""
        P = Z[:, 1:, :2]
        t = self.h * np.arange(1, P.shape[1] + 1)
        M = np.asarray(sit.movers, float).reshape(-1, 5)
        if not turns:
            A, B = predicted_movers(M, sit.mover_ends, t, sit.mover_seen, sit.mover_reach)
        for i, (x, y, vx, vy, r) in enumerate(M):
            if turns:   # state j against its own segment m(0) -/+ v t_j
                a = np.stack([x - vx * t, y - vy * t], axis=1)
                yield _segment_gap(P, a, a + 2.0 * np.stack([vx * t, vy * t], axis=1)) - r - self.robot.radius
            else:       # against the stretch it is predicted on (a point where its motion is known)
                yield _segment_gap(P, A[i], B[i]) - r - self.robot.radius

    def mover_gap(self, Z: np.ndarray, sit: Situation) -> np.ndarray:
        """``(S, n)``: distance from the robot's edge to the nearest predicted mover's edge."""
        gap = np.full((Z.shape[0], Z.shape[1] - 1), np.inf)
        for d in self.mover_gaps(Z, sit):
            np.minimum(gap, d, out=gap)
        return gap

    def static_rows(self, Z, ps: "SymbolicSituation") -> list:
        """Symbolic static gaps, one row per predicted state after the start: the distance
        field's first-order model at the reference positions (:meth:`symbolic_values`)."""
        L = ps.static
        return [L[j - 1, 0] + L[j - 1, 1] * (Z[j, 0] - L[j - 1, 3]) + L[j - 1, 2] * (Z[j, 1] - L[j - 1, 4])
                - self.robot.radius for j in range(1, Z.shape[0])]

    def mover_rows(self, Z, ps: "SymbolicSituation", squared: bool, margin=0.0, growth=0.0,
                   turns: bool = False) -> list:
        """Symbolic mover gaps over the parameter slots of the movers: ``|p - m(t)|^2 -
        (R + r + margin_j)^2`` when ``squared`` (a constraint row ``>= 0``; ``margin`` a number
        or one per predicted state, plus ``growth`` (the same) for a slot whose motion is not
        known, :func:`motion_known`, or for every slot with ``turns``), else the edge distance.
        ``m(t)`` is the nearest point of the predicted stretch (parameters,
        :func:`predicted_movers`). ``turns``: as :meth:`mover_gaps`."""
        import casadi as ca

        margins = np.broadcast_to(np.asarray(margin, float), (Z.shape[0] - 1,))
        growths = np.broadcast_to(np.asarray(growth, float), (Z.shape[0] - 1,))
        n = Z.shape[0] - 1
        rows = []
        for i in range(ps.movers.shape[0]):
            x, y, vx, vy, r = (ps.movers[i, c] for c in range(5))
            unknown = 1.0 if turns else 1.0 - ps.mover_known[i]
            for j in range(1, Z.shape[0]):
                t = self.h * j
                if turns:   # nearest point of the segment m(0) -/+ v t
                    ax, ay, dx, dy = x - vx * t, y - vy * t, 2 * vx * t, 2 * vy * t
                    k = ca.fmin(1, ca.fmax(0, ((Z[j, 0] - ax) * dx + (Z[j, 1] - ay) * dy)
                                           / (dx * dx + dy * dy + _SMOOTH)))
                    d2 = (Z[j, 0] - ax - k * dx) ** 2 + (Z[j, 1] - ay - k * dy) ** 2
                else:       # nearest point of the predicted stretch A -> B (A == B: a point)
                    ax, ay = ps.mover_path[i, j - 1], ps.mover_path[i, n + j - 1]
                    dx, dy = ps.mover_path[i, 2 * n + j - 1] - ax, ps.mover_path[i, 3 * n + j - 1] - ay
                    k = ca.fmin(1, ca.fmax(0, ((Z[j, 0] - ax) * dx + (Z[j, 1] - ay) * dy)
                                           / (dx * dx + dy * dy + _SMOOTH)))
                    d2 = (Z[j, 0] - ax - k * dx) ** 2 + (Z[j, 1] - ay - k * dy) ** 2
                rows.append(d2 - (self.robot.radius + r + margins[j - 1] + unknown * growths[j - 1]) ** 2 if squared
                            else ca.sqrt(d2 + _SMOOTH) - r - self.robot.radius)
        return rows

    def symbolic_values(self, sit: Situation, ref: np.ndarray, max_movers: int) -> dict:
        """The parameter values of :class:`SymbolicSituation` for ``sit``, the symbolic
        model taken around the reference states ``ref`` ``(N + 1, 3)``: each predicted
        position's path line (the nearest segment's), the static field's value and gradient
        (central differences), and the ``max_movers`` nearest movers with their predicted
        stretches (:func:`predicted_movers`; the other slots parked far away)."""
        A, B = _near_path(sit, self.reach)
        d = B - A
        L2 = np.maximum((d * d).sum(axis=1), 1e-18)
        P = ref[1:, :2]
        t = np.clip(((P[:, None, :] - A) * d).sum(axis=2) / L2, 0.0, 1.0)
        gap = np.hypot(*(A + t[..., None] * d - P[:, None, :]).transpose(2, 0, 1))
        k = gap.argmin(axis=1)
        n = np.stack([-d[k, 1], d[k, 0]], axis=1) / np.sqrt(L2[k])[:, None]
        tk = t[np.arange(len(k)), k]
        end = np.where(tk <= 0.0, 1.0, np.where(tk >= 1.0, 1.0, 0.0))
        e = np.where((tk <= 0.0)[:, None], A[k], B[k])
        lines = np.column_stack([n, (n * A[k]).sum(axis=1), end, e])
        eps = 1e-3
        probe = np.stack([P, P + (eps, 0), P - (eps, 0), P + (0, eps), P - (0, eps)], axis=1)
        f = np.asarray(sit.static_distance(probe), float)
        static = np.column_stack([f[:, 0], (f[:, 1] - f[:, 2]) / (2 * eps), (f[:, 3] - f[:, 4]) / (2 * eps), P])
        movers = np.tile([1e6, 1e6, 0.0, 0.0, 0.0], (max_movers, 1))
        path = np.full((max_movers, 4 * (self.N + len(self.hold_times()))), 1e6)
        known = np.ones(max_movers)
        M = np.asarray(sit.movers, float).reshape(-1, 5)
        if len(M) and max_movers:
            near = np.argsort(np.hypot(M[:, 0] - sit.state[0], M[:, 1] - sit.state[1]))[:max_movers]
            movers[:len(near)] = M[near]
            ends, seen, reach = (None if x is None else np.asarray(x, float).reshape(-1, 2)[near]
                                 for x in (sit.mover_ends, sit.mover_seen, sit.mover_reach))
            blocks = []
            stop = next((c for c in self.constraints if isinstance(c, StopClear)), None)
            for t, seen_t in ((self.h * np.arange(1, self.N + 1), seen),
                              (self.hold_times(), seen if stop is not None and stop.sweep else None)):
                A, B = predicted_movers(M[near], ends, t, seen_t, reach)
                blocks += [A[..., 0], A[..., 1], B[..., 0], B[..., 1]]
            path[:len(near)] = np.concatenate(blocks, axis=1)
            known[:len(near)] = motion_known(sit)[near]
        return {"state": np.asarray(sit.state, float), "subgoal": np.asarray(sit.subgoal, float),
                "command": self.current_command(sit), "lines": lines, "static": static, "movers": movers,
                "mover_path": path, "mover_known": known}

    # ------------------------------------------------------------------ the one judgement
    def evaluate(self, sit: Situation, U: np.ndarray) -> tuple[np.ndarray, np.ndarray, dict]:
        """``(cost (S,), violation (S,), {constraint name: (S,)})`` of command sequences
        ``U`` ``(S, K, nu)``: the number every local solver's answer is judged by."""
        U = np.asarray(U, float)
        if U.ndim == 2:
            U = U[None]
        Z = self.rollout(sit, U)
        cost = np.zeros(len(U))
        for w, t in self.objective:
            cost = cost + w * t.batched(Z, U, sit, self)
        parts = {c.name: c.batched(Z, U, sit, self) for c in self.constraints}
        viol = np.zeros(len(U))
        for v in parts.values():
            viol = viol + v
        return cost, viol, parts

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Per-command lower and upper limits ``(nu,)``: the robot's velocity limits."""
        r = self.robot
        lo = [r.v_min, -r.w_max, -r.vy_max][:self.nu]
        hi = [r.v_max, r.w_max, r.vy_max][:self.nu]
        return np.array(lo, float), np.array(hi, float)

    def rates(self) -> np.ndarray:
        """Largest change of each command component per interval (acceleration x interval)."""
        r = self.robot
        a_lin = r.a_max / math.sqrt(2) if self.nu == 3 else r.a_max
        return np.array([a_lin, r.alpha_max, a_lin][:self.nu]) * (self.m * self.h)


# ----------------------------------------------------------------------------- public term names
def goal_distance() -> GoalDistance:
    """Distance from the end of the window to the subgoal."""
    return GoalDistance()


def goal_heading() -> GoalHeading:
    """Heading error at the end of the window towards the subgoal (``1 - cos``)."""
    return GoalHeading()


def path_distance() -> PathDistance:
    """Mean distance of the predicted positions to the global path."""
    return PathDistance()


def speed() -> Speed:
    """Mean forward speed (use a negative weight to reward it)."""
    return Speed()


def smoothness() -> Smoothness:
    """Sum of squared command changes."""
    return Smoothness()


def obstacle_cost(scale: float = 0.3) -> ObstacleCost:
    """Soft cost of being near obstacles and movers: mean ``exp(-gap / scale)``."""
    return ObstacleCost(scale)


def custom(fn: Callable, name: str = "custom") -> Custom:
    """A term ``fn(Z, U, m)`` of your own (see :class:`Custom`)."""
    return Custom(fn, name)


def clearance(mover_margin: float = 0.0, mover_growth: float = 0.0, mover_turns: bool = False) -> Clearance:
    """Clearance constraint; ``clearance() >= d`` keeps ``d`` metres from obstacles and movers,
    and ``mover_margin + mover_growth * t`` more from movers predicted ``t`` seconds ahead
    (``mover_margin`` only from a mover whose motion is known: both its turning points seen).
    ``mover_turns``: a mover may turn round on its line at any moment (shuttling movers), so it
    is kept clear of wherever it can be along its line, not only of where it is heading."""
    return Clearance(0.0, mover_margin, mover_growth, mover_turns)


def can_stop(margin: float = 0.0) -> CanStop:
    """The robot can brake to a stop at the end of the window, ``margin`` metres short of
    the static obstacles."""
    return CanStop(margin)


def stop_cost(hold: float = 2.0, scale: float = 0.3) -> StopCost:
    """Soft twin of :func:`stop_clear`: how close the robot, braked to a stop from the end of the
    window, comes to the predicted movers over ``hold`` seconds (``exp(-gap / scale)``)."""
    return StopCost(hold, scale)


def stop_clear(hold: float = 2.0, margin: float = 0.0, sweep: bool = True) -> StopClear:
    """Braking to a stop at the end of the window, the robot then stands ``margin`` metres
    clear of every predicted mover for ``hold`` seconds (see :class:`StopClear`); ``sweep=False``:
    over the hold a mover runs on at constant speed, turning round only at ends it was seen to
    turn at (not anywhere past where it was seen)."""
    return StopClear(hold, margin, sweep)


def default_local_program(robot: RobotSpec, horizon: float = 2.0, intervals: int = 10, step: float = 0.1,
                          margin: float = 0.02, stop_hold: float = 0.0, stop_sweep: bool = True,
                          stop_cost: float = 0.0) -> LocalProgram:
    """The window program ``mpc`` solves unless given one: reach the subgoal, stay near the
    global path, keep speed, change commands smoothly; clearance and a stop at the end
    (``stop_hold > 0``: and that stop clear of the movers for that many seconds more,
    :func:`stop_clear`, ``stop_sweep`` its ``sweep``; ``stop_cost > 0``: plus that weight of
    :func:`stop_cost`)."""
    lp = LocalProgram(robot, horizon, intervals, step, name="default")
    objective = (1.0 * goal_distance() + 0.3 * goal_heading() + 0.5 * path_distance() - 0.5 * speed()
                 + 0.05 * smoothness() + 0.2 * obstacle_cost())
    if stop_cost > 0:
        objective = objective + stop_cost * StopCost(2.0)   # measured, not adopted (docs/measurements.md)
    lp.minimize(objective)
    lp.subject_to(clearance(mover_margin=0.1, mover_growth=0.1) >= margin)
    lp.subject_to(can_stop(margin))
    if stop_hold > 0:
        lp.subject_to(stop_clear(stop_hold, margin + 0.1, stop_sweep))
    return lp


# Named window programs: what a scenario file, a bench spec or the command line can name
# (``local_program: default``); each is built for the run's robot and control period.
LOCAL_PROGRAMS: dict[str, Callable[[RobotSpec, float], LocalProgram]] = {
    "default": lambda robot, step: default_local_program(robot, step=step),
}


def named_local_program(program: "str | LocalProgram", robot: RobotSpec, step: float) -> LocalProgram:
    """``program`` itself, or the named one of :data:`LOCAL_PROGRAMS` built for ``robot``."""
    if isinstance(program, LocalProgram):
        return program
    if isinstance(program, str) and program.lower() in LOCAL_PROGRAMS:
        return LOCAL_PROGRAMS[program.lower()](robot, step)
    from ..errors import named_with_hints

    if isinstance(program, str):
        raise ParameterError(f"unknown local program {named_with_hints([program], list(LOCAL_PROGRAMS))}; "
                             f"named ones: {', '.join(LOCAL_PROGRAMS)} (or pass an op.LocalProgram)")
    raise ParameterError(f"local_program must be an op.LocalProgram or the name of one "
                         f"({', '.join(LOCAL_PROGRAMS)}), got {type(program).__name__}")
