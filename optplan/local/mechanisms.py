"""Parts of the papers' DWA variants that are not cost terms.

Each mechanism hooks into one place of the control step:

* ``adjust_window``: narrows the dynamic window (hou2024's adaptive velocity, eq 23-24);
* ``override``: replaces the sampled choice by a fixed manoeuvre for this step
  (li2023's brake-and-wait, §5.4, and initial heading, eq 11);
* ``predict``: replaces the constant-velocity prediction of movers whose motion it knows
  better (the sweep gate, once it has seen where a mover turns round);
* ``filter``: removes samples and reports findings to the cost terms through
  ``step.aux`` (yang2023's velocity-obstacle test, eq 12-14; this project's sweep gate
  of ``qp-dwa``, which keeps the robot off a mover's track while the mover could turn
  round into it); ``report`` copies what a filter found into ``Command.info``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from ..world.robot import RobotState
from .base import LocalContext
from .critics import body_direction, wrap_angle
from .rollout import Step
from .window import Window

if TYPE_CHECKING:  # pragma: no cover
    from .dwa import DWAPlanner


class Mechanism:
    """A hook into the control step (see the module docstring). Hooks default to no-ops."""

    name: ClassVar[str] = ""

    def reset(self, planner: "DWAPlanner", state: RobotState, global_path: np.ndarray) -> None:
        """Forget the previous run."""

    def adjust_window(self, planner: "DWAPlanner", ctx: LocalContext, window: Window) -> Window:
        return window

    def override(self, planner: "DWAPlanner", ctx: LocalContext, window: Window) -> tuple[float, float, dict] | None:
        """``(v_desired, w_desired, info)`` to clip into the window instead of sampling, or ``None``."""
        return None

    def predict(self, planner: "DWAPlanner", ctx: LocalContext, centres: np.ndarray, t: np.ndarray) -> np.ndarray:
        """Predicted mover centres ``(K, H)`` complex at the rollout times ``t`` (one row per
        row of ``ctx.dynamic``); ``centres`` is the prediction so far, which may be updated in place."""
        return centres

    def filter(self, planner: "DWAPlanner", step: Step) -> np.ndarray | None:
        """Mask of samples to keep (``None`` = all)."""
        return None

    def strict_filter(self, planner: "DWAPlanner", step: Step) -> np.ndarray | None:
        """``filter`` without any relaxation it applies when nothing passes: judges a single
        trajectory on its own (``qp-dwa`` checks its refined command with it)."""
        return self.filter(planner, step)

    def report(self, step: Step) -> dict:
        """What this step's ``filter`` found, for ``Command.info`` (empty by default)."""
        return {}

    def sweeps(self) -> np.ndarray:
        """``(n, 5)`` rows ``(x0, y0, x1, y1, r)``: stretches movers are known to sweep back
        and forth (a disc of radius ``r`` between the two ends); none by default."""
        return np.zeros((0, 5))


@dataclass
class AdaptiveVelocity(Mechanism):
    """hou2024 §3.1.3, eq 23-24: caps on the linear and angular speed that follow how much
    of the surroundings is navigable.

    ``phi_path`` (the "navigable area") is measured as the free fraction of a fixed polar
    grid of points within ``look_ahead`` metres of the robot (a point is free when the robot
    could stand there without touching a static obstacle or a sensed mover); ``phi_max`` = 1.

    * eq 23: ``v_r(t+1) = v_r(t) + k_v (phi(t+1) - phi(t)) / phi_max * v_max`` - the cap falls
      as the surroundings close in. It starts at ``v_max * phi(0)`` (so with ``k_v`` = 1 it
      stays ``v_max * phi``) and never drops below ``v_floor * v_max``.
    * eq 24: ``w_r(t+1) = w_max - k_w v_r(t) / v_max * w_r(t)`` - slower driving allows faster
      turning; the fixed point is ``w_max / (1 + k_w v_r / v_max)``.

    The paper gives no values for ``k_v``, ``k_w``; 1.0 and 0.5 are our choices.
    """

    name: ClassVar[str] = "adaptive_velocity"
    k_v: float = 1.0
    k_w: float = 0.5
    look_ahead: float = 3.0
    v_floor: float = 0.2
    rings: int = 6
    rays: int = 24
    v_r: float | None = field(default=None, init=False)
    w_r: float | None = field(default=None, init=False)
    phi: float | None = field(default=None, init=False)

    def reset(self, planner, state, global_path) -> None:
        self.v_r = self.w_r = self.phi = None

    def navigable_fraction(self, planner: "DWAPlanner", ctx: LocalContext) -> float:
        r = self.look_ahead * np.arange(1, self.rings + 1) / self.rings
        a = 2 * np.pi * np.arange(self.rays) / self.rays
        z = complex(ctx.state.x, ctx.state.y) + np.multiply.outer(r, np.exp(1j * a)).ravel()
        R = planner.robot.radius
        free = np.asarray(ctx.static_distance(z.view(np.float64).reshape(-1, 2))) > R
        for x, y, _, _, rad in np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5):
            free &= np.abs(z - complex(x, y)) > rad + R
        return float(free.mean())

    def adjust_window(self, planner, ctx, window) -> Window:
        robot = planner.robot
        phi = self.navigable_fraction(planner, ctx)
        if self.v_r is None:
            self.v_r, self.w_r = robot.v_max * phi, robot.w_max
        else:
            v_prev = self.v_r
            self.v_r = self.v_r + self.k_v * (phi - self.phi) * robot.v_max  # eq 23
            self.w_r = robot.w_max - self.k_w * v_prev / robot.v_max * self.w_r  # eq 24
        self.phi = phi
        self.v_r = float(np.clip(self.v_r, self.v_floor * robot.v_max, robot.v_max))
        self.w_r = float(np.clip(self.w_r, 0.0, robot.w_max))
        return window.capped(v_hi=self.v_r, w_abs=self.w_r)


@dataclass
class VelocityObstacle(Mechanism):
    """yang2023 §5.1, eq 12-14: the relative collision cone of each sensed mover.

    For a sample's velocity ``V_rob`` (its speed along the mean heading of the first control
    period) and a mover's ``V_obs``, the relative velocity is ``V_r = V_rob - V_obs``
    (eq 12); the ray ``P_r + V_r t, t >= 0`` (eq 13) entering the mover's disc enlarged by the
    robot radius (eq 14) means a predicted collision, and the sample is rejected.
    ``horizon`` (s) truncates the ray (``None`` = the paper's infinite ray).

    The same test on the robot's current velocity gives eq 19's "is collision": the mover
    with the earliest predicted contact is stored in ``step.aux["vo_threat"]`` for the
    ``vh`` term (eq 17), which is zero when nothing is flagged.
    """

    name: ClassVar[str] = "velocity_obstacle"
    horizon: float | None = None
    margin: float = 0.0

    def _contact_time(self, vrel: np.ndarray, c: complex, rho: float) -> np.ndarray:
        """Time at which ``vrel t`` enters the disc of radius ``rho`` around ``c`` (inf = never)."""
        if abs(c) <= rho:
            return np.zeros(np.shape(vrel))
        s2 = np.abs(vrel) ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            t_closest = (c * np.conj(vrel)).real / s2
            miss2 = np.abs(c) ** 2 - t_closest ** 2 * s2  # squared distance of closest approach
            t_in = t_closest - np.sqrt(np.maximum(rho * rho - miss2, 0.0) / s2)
        hit = (s2 > 0) & (t_closest > 0) & (miss2 < rho * rho)
        if self.horizon is not None:
            hit &= t_in <= self.horizon
        return np.where(hit, t_in, np.inf)

    def filter(self, planner, step) -> np.ndarray | None:
        ctx, roll = step.ctx, step.roll
        if len(step.mover_r) == 0:
            return None
        mid_heading = roll.theta0 + 0.5 * roll.w * ctx.dt + body_direction(roll.v, roll.vy)
        v_samples = roll.speed * np.exp(1j * mid_heading)
        state = ctx.state
        v_now = math.hypot(state.v, state.vy) * np.exp(1j * (state.theta + body_direction(state.v, state.vy)))
        keep = np.ones(roll.n, dtype=bool)
        threat, t_threat = None, np.inf
        for k in range(len(step.mover_r)):
            c = step.movers[k, 0] - step.mover_vel[k] * roll.t[0] - roll.z0  # mover now, relative
            rho = step.mover_r[k] + planner.robot.radius + self.margin
            keep &= ~np.isfinite(self._contact_time(v_samples - step.mover_vel[k], c, rho))
            t_now = float(self._contact_time(np.array([v_now - step.mover_vel[k]]), c, rho)[0])
            if t_now < t_threat:
                threat, t_threat = k, t_now
        step.aux["vo_threat"] = threat
        step.aux["vo_rejected"] = int((~keep).sum())
        return keep

    def report(self, step) -> dict:
        threat = step.aux.get("vo_threat")
        return {} if threat is None else {"vo_threat": threat}


@dataclass
class BrakeAndWait(Mechanism):
    """li2023 §5.4: emergency brake and wait while a moving obstacle (1) is ahead of the robot
    (bearing within ``front_angle`` rad of its heading), (2) is closer than ``d_s`` m
    (centre to centre), (3) moves faster than ``v_s`` m/s, and (4) moves in a direction within
    ``cross_angle`` (3 pi / 4) of the robot's heading, i.e. crosses or leads rather than
    comes head-on (those are left to the DWA). The robot moves on once no mover meets all
    four conditions (the paper: once the mover is farther than ``d_s`` from the path ahead).
    ``d_s``, ``v_s`` and ``front_angle`` are left to the user by the paper; the defaults are ours.

    Waiting is only safe off the mover's track: the paper assumes the robot stops before the
    crossing. When the robot already stands inside a threat's swept corridor (its straight
    track over the next ``d_s / speed`` seconds, widened by both radii and ``margin``), it
    does not wait there to be run over; the step is left to the DWA, whose trajectories avoid
    the predicted movers.
    """

    name: ClassVar[str] = "brake_and_wait"
    d_s: float = 2.0
    v_s: float = 0.05
    front_angle: float = math.pi / 3
    cross_angle: float = 3 * math.pi / 4
    margin: float = 0.05

    def threats(self, ctx: LocalContext) -> np.ndarray:
        """Indices of the movers that meet the four conditions."""
        d = np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5)
        rel = d[:, 0] - ctx.state.x + 1j * (d[:, 1] - ctx.state.y)
        vel = d[:, 2] + 1j * d[:, 3]
        ahead = np.abs(wrap_angle(np.angle(rel) - ctx.state.theta)) <= self.front_angle
        near = np.abs(rel) < self.d_s
        fast = np.abs(vel) > self.v_s
        crossing = np.abs(wrap_angle(np.angle(vel) - ctx.state.theta)) <= self.cross_angle
        return np.flatnonzero(ahead & near & fast & crossing)

    def in_swept_corridor(self, ctx: LocalContext, movers: np.ndarray, robot_radius: float) -> bool:
        """Whether the robot's position lies on the straight track of any of ``movers`` (rows
        ``x, y, vx, vy, r``) over the time they need to cover ``d_s``."""
        q = np.array([ctx.state.x, ctx.state.y])
        p, v, r = movers[:, :2], movers[:, 2:4], movers[:, 4]
        horizon = self.d_s / np.maximum(np.hypot(v[:, 0], v[:, 1]), self.v_s)
        seg = v * horizon[:, None]
        t = np.clip(np.einsum("ij,ij->i", q - p, seg) / np.maximum(np.einsum("ij,ij->i", seg, seg), 1e-12), 0.0, 1.0)
        gap = np.hypot(*(p + t[:, None] * seg - q).T) - r - robot_radius
        return bool(np.any(gap < self.margin))

    def override(self, planner, ctx, window):
        k = self.threats(ctx)
        if len(k) == 0:
            return None
        movers = np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5)[k]
        if self.in_swept_corridor(ctx, movers, planner.robot.radius):
            return None  # waiting here would be waiting to be hit
        return 0.0, 0.0, {"mode": "brake-and-wait", "waiting_for": [int(i) for i in k]}


@dataclass
class InitialHeading(Mechanism):
    """li2023 §5.3, eq 11: start each run facing the first subgoal.

    The heading ``theta = atan2(y_1 - y_s, x_1 - x_s)`` of the first global path segment is
    stored as ``planner.initial_heading`` (the navigation layer may use it to set the start
    pose, as the paper does); until the robot faces it within ``tol`` rad, the planner turns
    on the spot (the paper's ``arctan k`` is taken with the quadrant, ``atan2``).
    """

    name: ClassVar[str] = "initial_heading"
    tol: float = math.radians(5.0)
    aligned: bool = field(default=True, init=False)

    def reset(self, planner, state, global_path) -> None:
        p = np.asarray(global_path, dtype=float).reshape(-1, 2)
        d = np.hypot(p[:, 0] - state.x, p[:, 1] - state.y)
        nearest = int(np.argmin(d)) if len(d) else 0
        ahead = nearest + np.flatnonzero(d[nearest:] > 1e-6)  # first node past the robot's
        if len(ahead) == 0:
            planner.initial_heading, self.aligned = None, True
            return
        x1, y1 = p[ahead[0]]
        planner.initial_heading = math.atan2(y1 - state.y, x1 - state.x)
        self.aligned = abs(wrap_angle(planner.initial_heading - state.theta)) <= self.tol

    def override(self, planner, ctx, window):
        if self.aligned or planner.initial_heading is None:
            return None
        err = float(wrap_angle(planner.initial_heading - ctx.state.theta))
        if abs(err) <= self.tol:
            self.aligned = True
            return None
        robot = planner.robot
        # the fastest turn that can still stop at the target heading
        w = math.copysign(min(robot.w_max, math.sqrt(2 * robot.alpha_max * abs(err))), err)
        return 0.0, w, {"mode": "align-initial-heading", "heading_error": err}


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
class _Track:
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
class SweepGate(Mechanism):
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
    tracks: list = field(default_factory=list, init=False)
    _t: float | None = field(default=None, init=False)
    _now: list = field(default_factory=list, init=False)
    _swept: dict = field(default_factory=dict, init=False)  # this step's intervals (qp-dwa's check reuses them)
    _rows: dict = field(default_factory=dict, init=False)    # row of ctx.dynamic -> its track, this step

    def reset(self, planner, state, global_path) -> None:
        self.tracks, self._t, self._now, self._swept, self._rows = [], None, [], {}, {}

    def _match(self, p: complex, v: complex, r: float, t: float, dt: float, free: list) -> "_Track | None":
        c = abs(v)
        best, best_off = None, self.match
        for k in free:
            if abs(k.radius - r) > 1e-6 or abs((v * np.conj(k.axis)).imag) > 0.05 * c:
                continue  # another size, or not moving along this track's line
            s, off = k.along(p)
            if off > best_off:
                continue
            if t - k.t_seen <= 1.5 * dt + 1e-9 and abs(s - k.predicted(t - k.t_seen)) > self.match:
                continue  # seen a step ago somewhere else on the line
            best, best_off = k, off
        return best

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
            k = self._match(p, v, float(r), t, ctx.dt, free)
            if k is None:
                k = _Track(origin=p, axis=v / c, radius=float(r), speed=c, s=0.0, heading=1.0, seen_lo=0.0,
                           seen_hi=0.0, t_seen=t, first_seen=t)
                k.reach_lo, k.reach_hi = line_reach(ctx, p, v / c, float(r))
                self.tracks.append(k)
            else:
                free.remove(k)
            s, _ = k.along(p)
            heading = 1.0 if (v * np.conj(k.axis)).real > 0 else -1.0
            elapsed = t - k.t_seen
            # a reversal since it was last seen means one turn, unless (after a gap in sensing) it
            # had time to cover what it was seen on twice and turn three times
            one_turn = elapsed <= 5 * ctx.dt + 1e-9 or (elapsed <= self.rejoin and c * elapsed < 2 * (k.seen_hi - k.seen_lo))
            if heading != k.heading and 0 < elapsed and one_turn:
                if k.heading > 0:
                    k.end_hi = max(0.5 * (k.s + s + c * elapsed), k.seen_hi)
                else:
                    k.end_lo = min(0.5 * (k.s + s - c * elapsed), k.seen_lo)
            k.s, k.heading, k.speed, k.t_seen = s, heading, c, t
            k.seen_lo, k.seen_hi = min(k.seen_lo, s), max(k.seen_hi, s)
            now.append(k)
            self._rows[row] = k
        self._now = now

    def predict(self, planner, ctx, centres, t):
        if self.exact:
            self.update(ctx)
            for row, k in self._rows.items():
                if k.known:
                    centres[row] = k.centres(t)
        return centres

    def swept(self, k: _Track, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(lo, hi)`` ``(H,)``: the interval of its line the mover of ``k`` may occupy at ``t``
        (remembered for the rest of the step: tracks change only in ``update``)."""
        key = (id(k), len(t), float(t[0]) if len(t) else 0.0, float(t[-1]) if len(t) else 0.0)
        if key not in self._swept:
            self._swept[key] = self._swept_now(k, t)
        return self._swept[key]

    def _swept_now(self, k: _Track, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
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

    def gaps(self, planner, step: Step) -> tuple[np.ndarray, float]:
        """Smallest edge gap ``(S,)`` of every rollout to the swept intervals, and the gap now."""
        roll = step.roll
        R = planner.robot.radius
        out, now = np.full(roll.n, np.inf), math.inf
        state = step.ctx.state
        # every rollout point at time t lies within (fastest speed) t of the start
        reach = max(roll.max_speed, math.hypot(state.v, state.vy)) * roll.t
        for k in self._now:
            lo, hi = self.swept(k, roll.t)
            s0, off0 = k.along(roll.z0)
            now = min(now, math.hypot(off0, s0 - k.s) - k.radius - R)
            nearest = np.hypot(off0, np.maximum(np.maximum(lo - s0, s0 - hi), 0.0)) - k.radius - R
            if (nearest - reach).min() > self.margin:
                continue  # no rollout can come near this mover's interval (exact bound)
            q = (roll.z - k.origin) * np.conj(k.axis)
            beyond = np.maximum(np.maximum(lo - q.real, q.real - hi), 0.0)
            np.minimum(out, (np.hypot(q.imag, beyond) - k.radius - R).min(axis=1), out=out)
        return out, now

    def strict_filter(self, planner, step) -> np.ndarray | None:
        self.update(step.ctx)
        if not self._now:
            return None
        gap, now = self.gaps(planner, step)
        step.aux["gate_gap"] = gap
        return gap >= min(self.margin, now)

    def filter(self, planner, step) -> np.ndarray | None:
        keep = self.strict_filter(planner, step)
        if keep is None:
            return None
        gap = step.aux["gate_gap"]
        safe = step.admissible & step.mover_free
        if safe.any() and not (keep & safe).any():
            keep = gap >= gap[safe].max() - 1e-9  # nothing safe keeps off: come least close
        step.aux["gate_rejected"] = int((~keep).sum())
        return keep

    def report(self, step) -> dict:
        return {"gate_rejected": step.aux["gate_rejected"]} if "gate_rejected" in step.aux else {}

    def sweeps(self) -> np.ndarray:
        """The remembered tracks whose two turning points are known (see :meth:`Mechanism.sweeps`)."""
        rows = []
        for k in self.tracks:
            if k.known:
                a, b = k.origin + k.axis * k.end_lo, k.origin + k.axis * k.end_hi
                rows.append((a.real, a.imag, b.real, b.imag, k.radius))
        return np.array(rows, dtype=float).reshape(-1, 5)


MECHANISMS: dict[str, type[Mechanism]] = {m.name: m for m in (
    AdaptiveVelocity, VelocityObstacle, BrakeAndWait, InitialHeading, SweepGate)}
