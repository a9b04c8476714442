"""The papers' DWA mechanisms: the parts of their variants that are not cost terms.

Each one plays roles of :mod:`optplan.local.hooks` in the control step: hou2024's
adaptive velocity (:class:`~optplan.local.hooks.CapsWindow`), yang2023's velocity
obstacles (:class:`~optplan.local.hooks.FiltersSamples`), li2023's brake-and-wait and
initial heading (:class:`~optplan.local.hooks.TakesOver`). This
project's sweep gate of ``qp-dwa`` lives in :mod:`optplan.local.sweep_gate`, its path creep
(added by the clutter families' parameters) in :mod:`optplan.local.creep`.
:data:`MECHANISMS` names them all for the presets and for ``planner_params``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..world.geometry import wrap_angle
from ..world.polyline import segment_point_distances
from ..world.robot import RobotState
from .base import LocalContext
from .critics import body_direction
from .hooks import Mechanism, PlannerView
from .rollout import Step
from .creep import PathCreep
from .sweep_gate import SweepGate
from .window import Window


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

    def reset(self, view: PlannerView, state: RobotState, global_path: np.ndarray) -> None:
        self.v_r = self.w_r = self.phi = None

    def navigable_fraction(self, view: PlannerView, ctx: LocalContext) -> float:
        r = self.look_ahead * np.arange(1, self.rings + 1) / self.rings
        a = 2 * np.pi * np.arange(self.rays) / self.rays
        z = complex(ctx.state.x, ctx.state.y) + np.multiply.outer(r, np.exp(1j * a)).ravel()
        R = view.robot.radius
        free = np.asarray(ctx.static_distance(z.view(np.float64).reshape(-1, 2))) > R
        for x, y, _, _, rad in np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5):
            free &= np.abs(z - complex(x, y)) > rad + R
        return float(free.mean())

    def adjust_window(self, view: PlannerView, ctx: LocalContext, window: Window) -> Window:
        robot = view.robot
        phi = self.navigable_fraction(view, ctx)
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

    ``hard_filter``: yang2023 uses the VO only as that judgement (§5.1: "we use a fusion of
    VO and IDWA"; eq 19 switches ``lambda`` on when the VO predicts a collision) - the
    samples are still scored, not removed. ``False`` (default) follows the paper; ``True``
    also rejects every sample whose velocity lies in a collision cone (the earlier reading,
    which with the infinite ray of eq 13 rejects most forward motion near a crossing mover).
    """

    name: ClassVar[str] = "velocity_obstacle"
    horizon: float | None = None
    margin: float = 0.0
    hard_filter: bool = False

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

    def filter(self, view: PlannerView, step: Step) -> np.ndarray | None:
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
            rho = step.mover_r[k] + view.robot.radius + self.margin
            if self.hard_filter:   # the samples' cones are only needed to reject samples
                keep &= ~np.isfinite(self._contact_time(v_samples - step.mover_vel[k], c, rho))
            t_now = float(self._contact_time(np.array([v_now - step.mover_vel[k]]), c, rho)[0])
            if t_now < t_threat:
                threat, t_threat = k, t_now
        step.aux["vo_threat"] = threat
        if not self.hard_filter:
            step.aux["vo_rejected"] = 0
            return None
        step.aux["vo_rejected"] = int((~keep).sum())
        return keep

    def strict_filter(self, view: PlannerView, step: Step) -> np.ndarray | None:
        """The same test: it has no fallback to leave out."""
        return self.filter(view, step)

    def passes_like(self, view: PlannerView, check: Step, step: Step, i: int) -> bool:
        """The same test (it never relaxes)."""
        keep = self.strict_filter(view, check)
        return keep is None or bool(keep[0])

    def clearance_rows(self, view: PlannerView, step: Step, i: int, like=None) -> list:
        """None: the cone test is on velocities, not a clearance."""
        return []

    def report(self, step: Step) -> dict:
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
    crossing. When the robot would come to rest (braking at ``a_max`` from its speed) inside,
    or already stands inside, a threat's swept corridor (its straight
    track over the next ``d_s / speed`` seconds, widened by both radii and ``margin``), it
    does not wait there to be run over; the step is left to the DWA, whose trajectories avoid
    the predicted movers. ``judge_at_rest=False`` judges the corridor where the robot stands
    only (the earlier reading, which let a robot brake onto the track).
    """

    name: ClassVar[str] = "brake_and_wait"
    d_s: float = 2.0
    v_s: float = 0.05
    front_angle: float = math.pi / 3
    cross_angle: float = 3 * math.pi / 4
    margin: float = 0.05
    clear_when_leaving: bool = True
    judge_at_rest: bool = True

    def threats(self, ctx: LocalContext, robot_radius: float = 0.0) -> np.ndarray:
        """Indices of the movers that meet the four conditions and are still in front of the
        robot's way: on its forward lane (the robot's heading line widened by both radii and
        ``margin``) or heading towards it. A mover that has crossed the lane and drives away
        from it has "disappeared in front of the planned path" (§5.4) and no longer holds the
        robot, even while it is nearer than ``d_s`` (``clear_when_leaving=False``: wait until
        it is farther than ``d_s``, the distance rule alone)."""
        d = np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5)
        rel = d[:, 0] - ctx.state.x + 1j * (d[:, 1] - ctx.state.y)
        vel = d[:, 2] + 1j * d[:, 3]
        ahead = np.abs(wrap_angle(np.angle(rel) - ctx.state.theta)) <= self.front_angle
        near = np.abs(rel) < self.d_s
        fast = np.abs(vel) > self.v_s
        crossing = np.abs(wrap_angle(np.angle(vel) - ctx.state.theta)) <= self.cross_angle
        threat = ahead & near & fast & crossing
        if self.clear_when_leaving:
            turn = np.exp(-1j * ctx.state.theta)             # robot frame: x forward, y left
            lateral, lateral_v = (rel * turn).imag, (vel * turn).imag
            on_lane = np.abs(lateral) < d[:, 4] + robot_radius + self.margin
            approaching = lateral * lateral_v < 0
            threat &= on_lane | approaching
        return np.flatnonzero(threat)

    def in_swept_corridor(self, ctx: LocalContext, movers: np.ndarray, robot_radius: float,
                          stop_distance: float = 0.0) -> bool:
        """Whether the robot, braking from where it is along its direction of travel over
        ``stop_distance`` m, comes onto the straight track of any of ``movers`` (rows
        ``x, y, vx, vy, r``) over the time they need to cover ``d_s``."""
        state = ctx.state
        way = np.exp(1j * (state.theta + body_direction(state.v, state.vy))) * np.linspace(0.0, stop_distance, 6)
        stops = np.column_stack([state.x + way.real, state.y + way.imag])
        p, v, r = movers[:, :2], movers[:, 2:4], movers[:, 4]
        horizon = self.d_s / np.maximum(np.hypot(v[:, 0], v[:, 1]), self.v_s)
        ends = p + v * horizon[:, None]
        gap = np.array([segment_point_distances(np.stack([p[k], ends[k]]), stops).min() for k in range(len(p))])
        return bool(np.any(gap - r - robot_radius < self.margin))

    def override(self, view: PlannerView, ctx: LocalContext, window: Window) -> tuple[float, float, dict] | None:
        k = self.threats(ctx, view.robot.radius)
        if len(k) == 0:
            return None
        movers = np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5)[k]
        robot, speed = view.robot, math.hypot(ctx.state.v, ctx.state.vy)
        # where the brake leaves the robot: the window sheds a_max dt per period
        stop = speed * view.dt + speed * speed / (2 * robot.a_max) if robot.a_max > 0 and self.judge_at_rest else 0.0
        if self.in_swept_corridor(ctx, movers, robot.radius, stop):
            return None  # waiting there would be waiting to be hit
        return 0.0, 0.0, {"mode": "brake-and-wait", "waiting_for": [int(i) for i in k]}


@dataclass
class InitialHeading(Mechanism):
    """li2023 §5.3, eq 11: start each run facing the first subgoal.

    The heading ``theta = atan2(y_1 - y_s, x_1 - x_s)`` of the first global path segment is
    published as :attr:`heading` (``DWAPlanner.initial_heading`` reads it; the navigation
    layer may use it to set the start pose, as the paper does); until the robot faces it
    within ``tol`` rad, the planner turns on the spot (the paper's ``arctan k`` is taken
    with the quadrant, ``atan2``).
    """

    name: ClassVar[str] = "initial_heading"
    tol: float = math.radians(5.0)
    aligned: bool = field(default=True, init=False)
    heading: float | None = field(default=None, init=False)

    def reset(self, view: PlannerView, state: RobotState, global_path: np.ndarray) -> None:
        p = np.asarray(global_path, dtype=float).reshape(-1, 2)
        d = np.hypot(p[:, 0] - state.x, p[:, 1] - state.y)
        nearest = int(np.argmin(d)) if len(d) else 0
        ahead = nearest + np.flatnonzero(d[nearest:] > 1e-6)  # first node past the robot's
        if len(ahead) == 0:
            self.heading, self.aligned = None, True
            return
        x1, y1 = p[ahead[0]]
        self.heading = math.atan2(y1 - state.y, x1 - state.x)
        self.aligned = abs(wrap_angle(self.heading - state.theta)) <= self.tol

    def override(self, view: PlannerView, ctx: LocalContext, window: Window) -> tuple[float, float, dict] | None:
        if self.aligned or self.heading is None:
            return None
        err = float(wrap_angle(self.heading - ctx.state.theta))
        if abs(err) <= self.tol:
            self.aligned = True
            return None
        robot = view.robot
        # the fastest turn that can still stop at the target heading
        w = math.copysign(min(robot.w_max, math.sqrt(2 * robot.alpha_max * abs(err))), err)
        return 0.0, w, {"mode": "align-initial-heading", "heading_error": err}


@dataclass
class ReachSubgoal(Mechanism):
    """Ours, not a paper's: the speed is capped where the subgoal would lie inside both of the
    robot's tightest turning circles (radius ``v / w_max``, left and right; a unicycle's), from where no
    turn reaches it and the robot orbits it at full speed. A target at lateral offset ``y``
    and distance ``d`` stays outside the circle on its side while ``v <= w_max d^2 / (2 |y|)``.

    Fox's velocity term rewards speed and a one-step heading term (yang2023 §5.2) barely
    tells a slower turn from a faster one, so nothing in idwa's evaluation slows the robot
    for a target beside it (docs/fidelity/yang2023.md: orbits round the goal, or round the
    end of a wall the path turns about)."""

    name: ClassVar[str] = "reach_subgoal"

    def adjust_window(self, view: PlannerView, ctx: LocalContext, window: Window) -> Window:
        st = ctx.state
        dx, dy = float(ctx.subgoal[0]) - st.x, float(ctx.subgoal[1]) - st.y
        lateral = abs(-math.sin(st.theta) * dx + math.cos(st.theta) * dy)
        if lateral < 1e-9:
            return window  # straight ahead or behind: a turn in place then a straight line reaches it
        return window.capped(v_hi=view.robot.w_max * (dx * dx + dy * dy) / (2.0 * lateral))


MECHANISMS: dict[str, type[Mechanism]] = {m.name: m for m in (
    AdaptiveVelocity, VelocityObstacle, BrakeAndWait, InitialHeading, SweepGate, PathCreep, ReachSubgoal)}
