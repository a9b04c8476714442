"""The sweep gate of ``qp-dwa``: learning where movers turn round, and keeping off their tracks.

The gate is a mechanism (:mod:`optplan.local.hooks`): it filters samples, replaces the
constant-velocity prediction of movers whose back-and-forth motion it has learnt, and
publishes what it knows through typed attributes: :attr:`SweepGate.tracks` (one
:class:`Track` per mover seen, with the turning points found so far) and
:meth:`SweepGate.mover_sweeps` (the stretches known exactly, for the navigation layer;
the :class:`~optplan.local.base.MoverSweepSource` capability).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from .base import LocalContext, MoverSweepSource
from .hooks import Mechanism, PlannerView
from .rollout import Step


def bounce(s0: float, heading: float, speed: float, t: np.ndarray, lo, hi) -> np.ndarray:
    """Positions along a line of a point that starts at ``s0``, moves in direction
    ``heading`` (+1 / -1) at ``speed`` and turns round at ``lo`` and ``hi``.

    ``t`` ``(H,)`` are the times; ``lo`` and ``hi`` are scalars or arrays broadcast against
    ``t`` (e.g. ``(m, 1)`` candidate ends give ``(m, H)``); an infinite end means no turn
    on that side. Every end must lie on the correct side of ``s0``."""
    t = np.asarray(t, dtype=float)
    lo, hi = np.broadcast_arrays(np.asarray(lo, dtype=float), np.asarray(hi, dtype=float))
    lo, hi = lo[..., None] if lo.ndim else lo, hi[..., None] if hi.ndim else hi
    fin_lo, fin_hi = np.isfinite(lo), np.isfinite(hi)
    L = np.where(fin_lo, lo, 0.0)
    Hh = np.where(fin_hi, hi, 0.0)
    run = speed * t
    straight = s0 + heading * run
    # both ends known: unfold the back-and-forth motion onto a circle of length 2 span
    span = np.maximum(Hh - L, 1e-9)
    u = np.mod(np.where(heading > 0, s0 - L, 2 * span - (s0 - L)) + run, 2 * span)
    both = L + np.where(u <= span, u, 2 * span - u)
    # one end known: at most one turn within reach
    if heading > 0:
        one = np.where(run < Hh - s0, straight, 2 * Hh - s0 - run)
        return np.where(fin_hi, np.where(fin_lo, both, one), straight)
    one = np.where(run < s0 - L, straight, 2 * L - s0 + run)
    return np.where(fin_lo, np.where(fin_hi, both, one), straight)


@dataclass
class Track:
    """What the robot has learnt about one mover that drives along a straight line."""

    origin: complex          # a point of the line
    axis: complex            # unit direction of the line
    radius: float
    speed: float
    s: float                 # position along the line, m
    heading: float           # +1 / -1 along ``axis``
    seen_lo: float           # extent along the line the mover has been seen on
    seen_hi: float
    t_seen: float
    end_lo: float = -math.inf  # turn-round points once seen (infinite: not yet)
    end_hi: float = math.inf
    reach_lo: float = -math.inf  # farthest the mover can go before it touches a known obstacle
    reach_hi: float = math.inf
    first_seen: float = 0.0

    @property
    def known(self) -> bool:
        """Both turning points have been seen: the motion is known exactly."""
        return math.isfinite(self.end_lo) and math.isfinite(self.end_hi)

    def along(self, p: complex) -> tuple[float, float]:
        """``(position along the line, distance off the line)`` of ``p``."""
        q = (p - self.origin) * np.conj(self.axis)
        return float(q.real), abs(float(q.imag))

    def predicted(self, t: float) -> float:
        """Position along the line ``t`` s after it was last seen, turning at known ends only."""
        return float(bounce(self.s, self.heading, self.speed, np.array([t]), self.end_lo, self.end_hi)[0])

    def centres(self, t: np.ndarray) -> np.ndarray:
        """Complex centres ``t`` s after it was last seen, turning at known ends only."""
        return self.origin + self.axis * bounce(self.s, self.heading, self.speed, t, self.end_lo, self.end_hi)


def match_track(free: list, p: complex, v: complex, r: float, t: float, dt: float, match: float) -> "Track | None":
    """The track of ``free`` a mover sensed at ``p`` with velocity ``v`` and radius ``r``
    continues: the same size, moving along the track's line, the nearest within ``match``
    metres of it, and, if the track was seen a step ago, within ``match`` of where it was
    predicted; ``None`` if there is none (shared by the sweep gate and the program solvers'
    mover tracker)."""
    c = abs(v)
    best, best_off = None, match
    for k in free:
        if abs(k.radius - r) > 1e-6 or abs((v * np.conj(k.axis)).imag) > 0.05 * c:
            continue  # another size, or not moving along this track's line
        s, off = k.along(p)
        if off > best_off:
            continue
        if t - k.t_seen <= 1.5 * dt + 1e-9 and abs(s - k.predicted(t - k.t_seen)) > match:
            continue  # seen a step ago somewhere else on the line
        best, best_off = k, off
    return best


def follow(tracks: list, free: list, p: complex, v: complex, r: float, t: float, dt: float,
           match: float) -> tuple["Track", float, float, bool]:
    """``(track, s, heading, new)``: the track a moving mover sensed at ``p`` continues
    (:func:`match_track` among ``free``, taken out of it), or a new one started at ``p`` and
    appended to ``tracks``; where along its line the mover is and which way it drives."""
    k = match_track(free, p, v, r, t, dt, match)
    new = k is None
    if new:
        c = abs(v)
        k = Track(origin=p, axis=v / c, radius=r, speed=c, s=0.0, heading=1.0, seen_lo=0.0, seen_hi=0.0,
                  t_seen=t, first_seen=t)
        tracks.append(k)
    else:
        free.remove(k)
    s, _ = k.along(p)
    return k, s, (1.0 if (v * np.conj(k.axis)).real > 0 else -1.0), new


def learn_turn(k: "Track", s: float, heading: float, c: float, t: float, dt: float, rejoin: float) -> None:
    """Learn from a mover of track ``k`` seen at ``s`` along the line, driving ``heading``
    (+1 / -1) at speed ``c``, ``t``: a reversal since it was last seen is one turn, at
    ``(s1 + s2 + c dt) / 2`` (constant speed), unless after a gap in sensing (at most
    ``rejoin`` seconds) it had time to cover what it was seen on twice and turn three times.
    The track's position is not moved (:func:`seen_at` does that)."""
    elapsed = t - k.t_seen
    one_turn = elapsed <= 5 * dt + 1e-9 or (elapsed <= rejoin and c * elapsed < 2 * (k.seen_hi - k.seen_lo))
    if heading != k.heading and 0 < elapsed and one_turn:
        if k.heading > 0:
            k.end_hi = max(0.5 * (k.s + s + c * elapsed), k.seen_hi)
        else:
            k.end_lo = min(0.5 * (k.s + s - c * elapsed), k.seen_lo)


def seen_at(k: "Track", s: float, heading: float, c: float, t: float) -> None:
    """Move track ``k`` to where its mover was just seen, and widen the stretch it was seen on."""
    k.s, k.heading, k.speed, k.t_seen = s, heading, c, t
    k.seen_lo, k.seen_hi = min(k.seen_lo, s), max(k.seen_hi, s)


def line_reach(ctx: LocalContext, p: complex, axis: complex, radius: float, step: float = 0.05,
               longest: float = 20.0) -> tuple[float, float]:
    """``(lo, hi)``: how far along ``axis`` (negative, positive) a disc of ``radius`` at
    ``p`` can slide before it touches a static obstacle the robot knows or the border,
    to ``step`` metres (infinite if it can go ``longest`` metres)."""
    d = np.arange(1, int(longest / step) + 1) * step
    out = []
    for sign in (-1.0, 1.0):
        z = p + sign * d * axis
        blocked = np.asarray(ctx.static_distance(np.stack([z.real, z.imag], axis=1))) < radius
        if ctx.bounds is not None:
            x0, y0, x1, y1 = ctx.bounds
            blocked |= (z.real < x0 + radius) | (z.real > x1 - radius) | (z.imag < y0 + radius) | (z.imag > y1 - radius)
        if not blocked.any():
            out.append(sign * math.inf)
            continue
        i = int(np.argmax(blocked))
        out.append(sign * (d[i - 1] if i > 0 else 0.0))
    return out[0], out[1]


@dataclass
class SweepGate(Mechanism, MoverSweepSource):
    """Keep off a mover's track unless crossing it is safe whatever the mover does next.

    The shipped movers drive back and forth along straight segments across the robot's
    path, and where they turn round is unknown until seen. A constant-velocity prediction
    lets the robot pass close behind a mover that then turns round into it (the most
    common failure in ``benchmarks/closed_loop_failures.py`` before this rule).

    For every sensed mover the filter keeps a track: its line, the extent it has been
    seen on and the turning points it has been seen to reach. A turn shows as a reversal
    of the velocity along the line; at constant speed ``c``, a mover seen at ``s1`` and
    ``dt`` later at ``s2`` on its way back turned at ``(s1 + s2 + c dt) / 2``. Over the
    horizon the mover may then be anywhere that a turn at a still-unknown end (no nearer
    than the farthest point it has been seen at) and bounces at the known ends can take it:
    an interval of its line that grows with time, and a single point once both ends are
    known. Samples whose rollout comes closer than ``margin`` to those intervals (or, when
    the robot is already closer, closer than it is now) are rejected, so the robot waits
    off the track and crosses once the mover is far enough away or its motion is known.
    When no safe sample passes, those that come least close are kept.

    The unknown ends are tried on a grid of ``grid`` points up to half the mover's reach
    over the horizon (farther ends give the same motion within the horizon), and the
    interval is widened by one grid step. This is this project's rule, not a paper's.

    Learning first (``learn_first``): a robot that slips through within the horizon may
    still have to stop later inside a sweep it has not seen the end of, and be run into
    there (the commonest failure left with the interval rule alone). So until both turning
    points of a mover are known, and for at most ``learn_time`` seconds after it was first
    seen, the gate keeps the robot off the whole stretch of the mover's line it can reach
    without touching a known obstacle or the border (found on the known map when the track
    starts). A robot waiting there sees the mover turn at both ends within one period.

    Once both ends are known (``exact``), the contact test and the QP's clearance rows
    use the mover's back-and-forth motion instead of the constant-velocity prediction,
    which runs a mover on past the end where it will turn. A turn seen across a gap in
    sensing (the mover left the sensor range and came back heading the other way, within
    ``rejoin`` seconds) is learnt with the same formula.
    """

    name: ClassVar[str] = "sweep_gate"
    margin: float = 0.1
    match: float = 0.3       # m: a sensed mover continues a track if it is this close to its prediction
    memory: float = 60.0     # s: tracks of movers unseen for longer are forgotten
    grid: int = 6
    learn_first: bool = True
    learn_time: float = 20.0  # s: longest a track's whole reachable line is kept clear
    exact: bool = True
    rejoin: float = 10.0      # s: a reversal seen across a sensing gap this long still gives the end
    tracks: list[Track] = field(default_factory=list, init=False)
    _t: float | None = field(default=None, init=False)
    _now: list = field(default_factory=list, init=False)
    _swept: dict = field(default_factory=dict, init=False)  # this step's intervals (qp-dwa's check reuses them)
    _rows: dict = field(default_factory=dict, init=False)    # row of ctx.dynamic -> its track, this step

    def reset(self, view, state, global_path) -> None:
        self.tracks, self._t, self._now, self._swept, self._rows = [], None, [], {}, {}

    def update(self, ctx: LocalContext) -> None:
        """Match the sensed movers to tracks and learn their turning points (once per step)."""
        t = float(ctx.t)
        if self._t is not None and abs(t - self._t) < 1e-12:
            return
        self._t = t
        self._swept = {}
        self.tracks = [k for k in self.tracks if t - k.t_seen <= self.memory]
        free, now = list(self.tracks), []
        self._rows = {}
        for row, (x, y, vx, vy, r) in enumerate(np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5)):
            p, v = complex(x, y), complex(vx, vy)
            c = abs(v)
            if c < 1e-6:
                continue  # a standing obstacle has no track; the planner's clearance handles it
            k, s, heading, new = follow(self.tracks, free, p, v, float(r), t, ctx.dt, self.match)
            if new:
                k.reach_lo, k.reach_hi = line_reach(ctx, p, v / c, float(r))
            learn_turn(k, s, heading, c, t, ctx.dt, self.rejoin)
            seen_at(k, s, heading, c, t)
            now.append(k)
            self._rows[row] = k
        self._now = now

    def predict(self, view, ctx, centres, t):
        if self.exact:
            self.update(ctx)
            for row, k in self._rows.items():
                if k.known:
                    centres[row] = k.centres(t)
        return centres

    def swept(self, k: Track, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(lo, hi)`` ``(H,)``: the interval of its line the mover of ``k`` may occupy at ``t``
        (remembered for the rest of the step: tracks change only in ``update``)."""
        key = (id(k), len(t), float(t[0]) if len(t) else 0.0, float(t[-1]) if len(t) else 0.0)
        if key not in self._swept:
            self._swept[key] = self._swept_now(k, t)
        return self._swept[key]

    def _swept_now(self, k: Track, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        if self.learn_first and not k.known and self._t - k.first_seen <= self.learn_time:
            lo = k.end_lo if math.isfinite(k.end_lo) else min(k.reach_lo, k.seen_lo, k.s)
            hi = k.end_hi if math.isfinite(k.end_hi) else max(k.reach_hi, k.seen_hi, k.s)
            return np.full(len(t), lo), np.full(len(t), hi)
        reach = k.speed * float(t[-1]) if len(t) else 0.0
        steps = np.linspace(0.0, 0.5 * reach, self.grid + 1)
        his = np.array([k.end_hi]) if math.isfinite(k.end_hi) else np.r_[max(k.seen_hi, k.s) + steps, math.inf]
        los = np.array([k.end_lo]) if math.isfinite(k.end_lo) else np.r_[min(k.seen_lo, k.s) - steps, -math.inf]
        pos = bounce(k.s, k.heading, k.speed, t, los[None, :], his[:, None]).reshape(-1, len(t))
        lo, hi = pos.min(axis=0), pos.max(axis=0)
        if k.known:
            return lo, hi
        slack = 0.5 * reach / self.grid
        return lo - slack, hi + slack

    def gaps(self, view: PlannerView, step: Step, rows: np.ndarray | None = None,
             crossings: bool = False) -> tuple[np.ndarray, float]:
        """Smallest edge gap ``(S,)`` of every rollout to the swept intervals, and the gap now;
        with ``rows`` (indices) only those samples are measured (the others are ``inf``).
        With ``crossings``, a rollout that crosses a line between two points where the
        interval may hold the mover gets the deepest gap (:meth:`_crossings`); the strict test
        does not need it (such a rollout has a point within half a step of the line and fails
        it anyway), the least-close relaxation does.

        Gaps up to ``margin`` are exact; a larger value only says the gap exceeds ``margin``
        (rollout times that provably keep farther are not measured), which is all the
        filter's rules (strict, and its least-close relaxation) ask of it."""
        roll = step.roll
        R = view.robot.radius
        z = roll.z if rows is None else roll.z[rows]
        out, now = np.full(len(z), np.inf), math.inf
        # every rollout point at time t lies within (fastest speed) t of the start
        fastest = self._fastest(step)
        reach = fastest * roll.t
        seg = fastest * roll.dt  # longest step between points
        q_buf = None
        for k in self._now:
            lo, hi = self.swept(k, roll.t)
            s0, off0 = k.along(roll.z0)
            now = min(now, math.hypot(off0, s0 - k.s) - k.radius - R)
            nearest = np.hypot(off0, np.maximum(np.maximum(lo - s0, s0 - hi), 0.0)) - k.radius - R
            near = np.flatnonzero(nearest - reach <= self.margin)  # the other times keep farther (exact bound)
            if len(near) == 0:
                continue
            if q_buf is None:  # scratch arrays shared by the tracks, written in place
                q_buf, d_buf, e_buf = np.empty(z.shape, complex), np.empty(z.shape), np.empty(z.shape)
            # every near time (and any far one between), and the one before: a segment into
            # the first near point may cross the line
            c = slice(max(near[0] - 1, 0) if crossings else near[0], near[-1] + 1)
            size, shape = len(z) * (c.stop - c.start), (len(z), c.stop - c.start)
            q, d, e = (buf.ravel()[:size].reshape(shape) for buf in (q_buf, d_buf, e_buf))  # contiguous views
            # in the line's frame: position along the line (real part) and off it (imaginary part)
            np.subtract(z[:, c], k.origin, out=q)
            q *= np.conj(k.axis)
            np.maximum(q.real, lo[c], out=d)  # the interval's nearest point along the line
            np.minimum(d, hi[c], out=d)
            np.subtract(q.real, d, out=d)
            np.square(d, out=d)
            np.square(q.imag, out=e)
            e += d
            g = np.sqrt(e.min(axis=1)) - k.radius - R
            np.minimum(out, g, out=out)
            if crossings:  # a rollout that crosses inside the interval has a point within half a step
                cand = np.flatnonzero((g < 0.5 * seg - k.radius - R) & (out > -k.radius - R))
                if len(cand):
                    self._crossings(k, q[cand], roll.z0 if c.start == 0 else None, lo[c], hi[c], out, cand, R)
        if rows is not None:
            full = np.full(roll.n, np.inf)
            full[rows] = out
            out = full
        return out, now

    @staticmethod
    def _crossings(k: Track, q: np.ndarray, z0: complex | None, lo: np.ndarray, hi: np.ndarray,
                   out: np.ndarray, rows: np.ndarray, R: float) -> None:
        """Lower ``out[rows]`` to the deepest gap, ``-(radius + R)``, for the rollouts ``q`` that cross the
        track's line between two points (or from ``z0`` to the first) where the interval may
        hold the mover. Points 0.1 s apart step over the line, and by how much they miss it
        is chance: between crossing samples, and between a sample and its refinement, the
        filter's least-close test would compare that chance."""
        if z0 is not None:  # the first segment starts where the robot stands
            q = np.concatenate([np.full((len(q), 1), (z0 - k.origin) * np.conj(k.axis)), q], axis=1)
            lo, hi = np.concatenate((lo[:1], lo)), np.concatenate((hi[:1], hi))
        im = q.imag
        s_i, t_i = np.nonzero((im[:, 1:] > 0) != (im[:, :-1] > 0))  # segment t -> t+1 crosses the line
        if len(s_i):
            a, b = q[s_i, t_i], q[s_i, t_i + 1]
            along = a.real + (b.real - a.real) * (a.imag / (a.imag - b.imag))  # never a.imag == b.imag
            inside = (along >= np.minimum(lo[t_i], lo[t_i + 1])) & (along <= np.maximum(hi[t_i], hi[t_i + 1]))
            out[rows[s_i[inside]]] = -k.radius - R

    def strict_filter(self, view, step, crossings: bool = False) -> np.ndarray | None:
        self.update(step.ctx)
        if not self._now:
            return None
        gap, now = self.gaps(view, step, crossings=crossings)
        step.aux["gate_gap"], step.aux["gate_now"] = gap, now
        return gap >= min(self.margin, now)

    def filter(self, view, step) -> np.ndarray | None:
        """The strict test over the samples the planner may choose among (admissible, clear of
        the predicted movers); the others are not measured and not kept (the planner discards
        them anyway, and when none is left it ignores the filters). When no such sample keeps
        off, those that come least close are kept."""
        self.update(step.ctx)
        safe = step.admissible & step.mover_free
        if not self._now or not safe.any():
            return None
        rows = np.flatnonzero(safe)
        gap, now = self.gaps(view, step, rows)
        keep = (gap >= min(self.margin, now)) & safe
        if not keep.any():  # nothing safe keeps off: come least close
            if gap[safe].max() < self._crossing_band(view, step):  # crossings can decide it
                gap, now = self.gaps(view, step, rows, crossings=True)
            keep = (gap >= gap[safe].max() - 1e-9) & safe
        step.aux["gate_gap"], step.aux["gate_now"] = gap, now
        step.aux["gate_rejected"] = int((~keep).sum())
        return keep

    def passes_like(self, view, check, step, i: int) -> bool:
        """The single trajectory of ``check`` keeps off the swept intervals (the strict test),
        or, when no sample kept off this step and the filter kept those that come least
        close, it comes no closer to them than sample ``i``: judged by the strict test alone,
        a refined command could never pass in such a step, however little it moved."""
        keep = self.strict_filter(view, check)
        if keep is None or keep[0]:
            return True
        gap = step.aux.get("gate_gap")
        if gap is None or gap[i] >= min(self.margin, step.aux["gate_now"]):
            return False  # the sample kept off: the strict test was the standard
        if gap[i] < self._crossing_band(view, step):  # measured as the filter measured the sample
            self.strict_filter(view, check, crossings=True)
        return bool(check.aux["gate_gap"][0] >= gap[i] - 1e-9)

    def _crossing_band(self, view, step) -> float:
        """Gaps below which a rollout may cross a line between two points: within half of the
        longest step between rollout points. When the least-close samples keep above it, no
        crossing can change which samples the relaxed rule keeps, and it is not measured."""
        return 0.5 * self._fastest(step) * step.roll.dt - min(k.radius for k in self._now) - view.robot.radius

    @staticmethod
    def _fastest(step) -> float:
        """Fastest planar speed on the rollouts or of the robot now, m/s."""
        state = step.ctx.state
        return max(step.roll.max_speed, math.hypot(state.v, state.vy))

    def clearance_rows(self, view, step, i: int, like=None) -> list[tuple[int, complex, float, float]]:
        """Per track, the rollout point of sample ``i`` nearest to the interval the mover may
        occupy then, the unit normal from the interval to it, its edge gap, and the gap the
        filter asks: its margin (or the gap now, if smaller) when the sample kept off, or the
        sample's own gap when the filter kept it as one that comes least close. With
        ``like = (judged, j)``, what it asked of sample ``j`` of ``judged``."""
        judged, ji = (step, i) if like is None else like
        gap = judged.aux.get("gate_gap")
        if not self._now or gap is None:
            return []
        roll, R = step.roll, view.robot.radius
        tracks = self._now
        origin = np.array([k.origin for k in tracks])
        axis = np.array([k.axis for k in tracks])
        radius = np.array([k.radius for k in tracks])
        swept = [self.swept(k, roll.t) for k in tracks]
        lo, hi = np.array([w[0] for w in swept]), np.array([w[1] for w in swept])
        asked = min(self.margin, judged.aux["gate_now"])  # the threshold the filter used
        asked = asked if gap[ji] >= asked else float(gap[ji])
        z = roll.z[i]
        q = (z[None, :] - origin[:, None]) * np.conj(axis)[:, None]  # (tracks, T) in each line's frame
        nearest = np.clip(q.real, lo, hi)
        d = np.hypot(q.real - nearest, q.imag) - radius[:, None] - R
        j = np.argmin(d, axis=1)
        k = np.arange(len(tracks))
        off = z[j] - (origin + axis * nearest[k, j])
        return [(int(j[n]), off[n] / abs(off[n]), float(d[n, j[n]]), asked) for n in k if abs(off[n]) > 0]

    def report(self, step) -> dict:
        return {"gate_rejected": step.aux["gate_rejected"]} if "gate_rejected" in step.aux else {}

    @property
    def tracks_now(self) -> tuple[Track, ...]:
        """The tracks of the movers sensed at the last :meth:`update`."""
        return tuple(self._now)

    def mover_sweeps(self) -> np.ndarray:
        """The remembered tracks whose two turning points are known, as ``(n, 5)`` rows
        ``(x0, y0, x1, y1, r)`` (see :class:`~optplan.local.base.MoverSweepSource`)."""
        rows = []
        for k in self.tracks:
            if k.known:
                a, b = k.origin + k.axis * k.end_lo, k.origin + k.axis * k.end_hi
                rows.append((a.real, a.imag, b.real, b.imag, k.radius))
        return np.array(rows, dtype=float).reshape(-1, 5)
