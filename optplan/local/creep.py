"""Path creep: when the sampled window has stopped the robot, follow the global path by
straight, checked legs (turn on the spot, then drive straight), slowly.

Why: in dense clutter a global path planned with the robot's footprint may thread gaps
only a centimetre or two wider than the robot. Every sampled trajectory of a dynamic
window is a constant command (or a ramp to one) over seconds; near such a gap almost all
of them graze an obstacle, the few that do not make no progress, and the planner brakes
to a stop in front of the gap (issue 27). A disc robot can always pass where its path is
valid: turning on the spot does not move the disc, and driving straight sweeps a capsule
that the clearance check of the leg covers. So this mechanism takes over from the sampler
once the robot has stood still beside obstacles for ``stall_time`` seconds:

1. **carrot** - the farthest point of the global path, at most ``look_ahead`` metres of
   path beyond the robot's projection onto it, that the robot sees along a straight leg
   keeping ``radius + clearance`` from every static obstacle (the known map plus what has
   been sensed; ``clearance`` covers the distance field's error and the spacing of the
   points checked along the leg);
2. **turn** - on the spot, towards the carrot, with the fastest yaw rate that can still
   stop on the bearing (``sqrt(2 alpha d)``, and the exact remainder in the last period);
3. **drive** - straight along the heading the robot has, never faster than ``speed`` nor
   than lets it stop, at ``a_max``, before the end of the free straight ahead or the carrot.
   In the unicycle model the robot moves along its heading at the start of each period, so
   with ``w = 0`` the leg it drives is exactly the one checked; braking from one period's
   admissible speed stays admissible the next (recursive feasibility for static obstacles).

The creep ends (the sampler takes over again) once the robot has followed ``length``
metres of path, when no carrot is visible, or when the leg would bring the robot within
``mover_gap`` metres (edge to edge) of a sensed mover within ``mover_time`` seconds (both
at constant velocity) and standing would not be clearly worse: waiting among movers is
the sampler's and its mover terms' job. One case is the creep's at once, without the
stall: a robot standing where a mover will come within ``mover_gap`` of it. In clutter
the sampler's window can hold the robot pinned against an obstacle (every forward arc
grazes it) while a mover closes in along its track; a straight leg that the exact rule
lets through often leads out of the mover's way.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..errors import ParameterError
from ..world.geometry import wrap_angle
from ..world.robot import RobotState
from .base import LocalContext
from .critics import point_at_arc, project_on_path
from .hooks import Mechanism, PlannerView
from .window import Window

_SPACING = 0.005  # m between the points checked along a leg (the field is 1-Lipschitz)


@dataclass
class PathCreep(Mechanism):
    """Follow the global path by checked straight legs after a stall (module docstring).

    Attributes:
        stall_time: seconds the robot must have stood (speed below ``stall_speed``) first,
            without turning on the spot by more than ``stall_turn`` rad in one direction.
        stall_speed: m/s under which the robot counts as standing.
        stall_turn: rad of steady turning on the spot that restart the count: the sampler
            turning the robot away from a wall (its escape turn) is a way out, not a stall;
            standing ``3 * stall_time`` s in all counts whatever the turning.
        speed: top speed of the creep, m/s (at most the robot's ``v_max``).
        look_ahead: metres of path beyond the robot's projection searched for the carrot.
        length: metres of path progress after which the sampler takes over again.
        clearance: metres kept beyond the robot radius along a leg, on top of the distance
            field's error bound when the context gives it.
        aim: bearing error (rad) below which the robot drives instead of turning.
        mover_gap, mover_time, mover_gain: a leg on which a sensed mover comes within
            ``mover_gap`` m of the robot within ``mover_time`` s (constant velocity) is driven
            only if it keeps ``mover_gain`` m more from the movers than standing would.
        static_near: the creep starts only where the robot stands within this many metres
            (edge to edge) of a static obstacle: standing in the open, nothing static holds
            the robot, and the sampler is waiting for movers.
    """

    name: ClassVar[str] = "path_creep"
    stall_time: float = 1.0
    stall_speed: float = 0.02
    stall_turn: float = 0.3
    speed: float = 0.25
    look_ahead: float = 1.5
    length: float = 1.5
    clearance: float = 0.001
    aim: float = 0.01
    mover_gap: float = 0.5
    mover_time: float = 3.0
    mover_gain: float = 0.05
    static_near: float = 0.25
    stalled_for: float = field(default=0.0, init=False)
    standing_for: float = field(default=0.0, init=False)
    stall_heading: float = field(default=0.0, init=False)
    active: bool = field(default=False, init=False)
    start_arc: float = field(default=0.0, init=False)
    arc: float = field(default=0.0, init=False)
    legs: int = field(default=0, init=False)
    leg: complex | None = field(default=None, init=False)
    floor: float = field(default=np.inf, init=False)
    path: np.ndarray | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        for key in ("stall_time", "stall_speed", "stall_turn", "speed", "look_ahead", "length", "clearance", "aim", "mover_gap",
                    "mover_time", "mover_gain", "static_near"):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0 \
                    or (value == 0 and key in ("speed", "look_ahead", "length", "aim")):
                raise ParameterError(f"path_creep {key} must be a finite number "
                                     f"{'> 0' if key in ('speed', 'look_ahead', 'length', 'aim') else '>= 0'}, "
                                     f"got {value!r}")

    def reset(self, view: PlannerView, state: RobotState, global_path: np.ndarray) -> None:
        self.stalled_for, self.active, self.start_arc, self.arc, self.legs = 0.0, False, 0.0, 0.0, 0
        self.standing_for, self.stall_heading = 0.0, float(state.theta)
        self.leg, self.floor, self.path = None, np.inf, None

    # ------------------------------------------------------------------ geometry
    def required_gap(self, view: PlannerView, ctx: LocalContext) -> float:
        """Distance (m, from the robot centre) a leg keeps from static obstacles: the radius and
        ``clearance``, plus (when only the distance field is given) its error bound and half
        the spacing of the points checked along the leg."""
        extra = 0.0 if ctx.segments_free is not None else \
            (0.0 if ctx.distance_error is None else float(ctx.distance_error)) + 0.5 * _SPACING
        return view.robot.radius + self.clearance + extra

    def legs_free(self, ctx: LocalContext, origin: complex, ends: np.ndarray, need: float) -> np.ndarray:
        """Whether each straight leg ``origin -> ends[k]`` keeps ``need`` from static obstacles:
        the exact segment rule when the context gives it, else the field at points
        ``_SPACING`` apart (the field is 1-Lipschitz, so half a spacing more is asked)."""
        ends = np.atleast_1d(np.asarray(ends, dtype=complex))
        if ctx.segments_free is not None:
            a = np.broadcast_to([origin.real, origin.imag], (len(ends), 2))
            return np.asarray(ctx.segments_free(a, np.stack([ends.real, ends.imag], axis=1), need), dtype=bool)
        n = max(2, int(math.ceil(float(np.abs(ends - origin).max(initial=0.0)) / _SPACING)) + 1)
        z = origin + np.multiply.outer(ends - origin, np.linspace(0.0, 1.0, n))     # (K, n)
        d = np.asarray(ctx.static_distance(np.stack([z.real, z.imag], axis=-1)), dtype=float)
        return (d >= need).all(axis=1)

    def free_ahead(self, ctx: LocalContext, origin: complex, heading: complex, need: float) -> float:
        """How far (m, up to ``look_ahead``, to 1 cm) the straight leg along ``heading`` keeps ``need``."""
        lengths = np.arange(1, int(round(self.look_ahead / 0.01)) + 1) * 0.01
        ok = self.legs_free(ctx, origin, origin + heading * lengths, need)
        first_bad = len(ok) if ok.all() else int(np.argmin(ok))
        return float(lengths[first_bad - 1]) if first_bad > 0 else 0.0

    def carrot(self, view: PlannerView, ctx: LocalContext, here: complex) -> tuple[complex, float] | None:
        """The farthest path point within ``look_ahead`` (of path) beyond the robot's projection
        that a straight leg from ``here`` reaches with the required gap, and its arc length."""
        path = ctx.global_path
        s0, _ = project_on_path(path, np.array([here]), near=here, reach=1.0)
        s0 = max(float(s0[0]), self.arc)
        s = s0 + np.arange(1, int(self.look_ahead / 0.02) + 1) * 0.02
        pts = point_at_arc(path, s)
        keep = np.abs(pts - here) > 0.03
        if not keep.any():
            return None
        pts, s = pts[keep], s[keep]
        full = self.legs_free(ctx, here, pts, self.need(view, ctx))
        if not full.any():
            return None
        k = int(np.flatnonzero(full)[-1])
        return complex(pts[k]), float(s[k])

    def mover_gaps(self, view: PlannerView, ctx: LocalContext, here: complex, heading: complex, reach: float,
                   wait: float = 0.0) -> tuple[float, float]:
        """Least edge-to-edge gap (m) to any sensed mover over ``mover_time`` s at its measured
        velocity: ``(moving, standing)`` - the robot waiting ``wait`` s, then driving ``reach`` m
        along ``heading`` (at ``a_max`` up to the creep speed, stopping at the end), versus
        the robot standing where it is. ``inf`` without movers."""
        movers = np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5)
        if not len(movers):
            return math.inf, math.inf
        robot = view.robot
        t = np.linspace(0.0, self.mover_time, 31)
        v0 = max(0.0, ctx.state.v)
        vc, a = max(v0, min(self.speed, robot.v_max)), robot.a_max
        # distance driven by time tau of a trapezoid from v0 to vc that stops at ``reach``
        tau = np.maximum(t - wait, 0.0)
        t_up = (vc - v0) / a
        up = np.where(tau < t_up, v0 * tau + 0.5 * a * tau ** 2, v0 * t_up + 0.5 * a * t_up ** 2 + vc * (tau - t_up))
        stop_from = max(0.0, reach - 0.5 * vc * vc / a)
        t_stop = t_up + max(0.0, stop_from - (v0 * t_up + 0.5 * a * t_up ** 2)) / vc if vc > 0 else 0.0
        after = np.maximum(tau - t_stop, 0.0)
        down = stop_from + vc * np.minimum(after, vc / a) - 0.5 * a * np.minimum(after, vc / a) ** 2
        driven = np.clip(np.where(tau <= t_stop, up, down), 0.0, max(reach, 0.0))
        robot_at = here + heading * driven
        centres = (movers[:, 0] + 1j * movers[:, 1])[:, None] + (movers[:, 2] + 1j * movers[:, 3])[:, None] * t
        edge = movers[:, 4:5] + robot.radius
        moving = float((np.abs(centres - robot_at) - edge).min())
        standing = float((np.abs(centres - here) - edge).min())
        return moving, standing

    def leg_safe_from_movers(self, view: PlannerView, ctx: LocalContext, here: complex, heading: complex,
                             reach: float, wait: float = 0.0) -> bool:
        """Whether creeping ``reach`` m along ``heading`` (after ``wait`` s) is safe enough from
        the movers: it keeps ``mover_gap`` from them, or it keeps clearly more than standing
        does (a robot the sampler holds pinned in a mover's way moves out of it)."""
        moving, standing = self.mover_gaps(view, ctx, here, heading, reach, wait)
        return moving >= self.mover_gap or (moving > 0.0 and moving >= standing + self.mover_gain)

    # ------------------------------------------------------------------ the role
    def override(self, view: PlannerView, ctx: LocalContext, window: Window) -> tuple[float, float, dict] | None:
        robot, state, dt = view.robot, ctx.state, view.dt
        here = complex(state.x, state.y)
        speed = math.hypot(state.v, state.vy)
        standing = speed < self.stall_speed
        if not self.active:
            # moving, or standing in the open, is no stall; standing beside obstacles counts, and
            # at once when a mover will reach the robot there
            in_open = standing and \
                float(ctx.static_distance(np.array([state.x, state.y]))) - robot.radius > self.static_near
            if not standing or in_open:
                self.stalled_for = self.standing_for = 0.0
                self.stall_heading = float(state.theta)
            elif self.mover_gaps(view, ctx, here, 1.0, 0.0)[1] < self.mover_gap:
                # held still in a mover's way: creep at once if a leg is safer than standing
                # (checked below); a mover that keeps its distance is waited for by the sampler
                self.stalled_for = self.stall_time
            else:
                self.stalled_for += dt
                self.standing_for += dt
                if abs(wrap_angle(state.theta - self.stall_heading)) > self.stall_turn:
                    self.stalled_for, self.stall_heading = 0.0, float(state.theta)
            if self.stalled_for < self.stall_time - 1e-9 and self.standing_for < 3 * self.stall_time - 1e-9:
                return None
            s0, _ = project_on_path(ctx.global_path, np.array([here]), near=here, reach=1.0)
            self.active, self.start_arc, self.arc, self.leg = True, float(s0[0]), float(s0[0]), None
            self.path = ctx.global_path
            # never ask less of a leg than the robot has where the creep starts: a threshold that
            # followed the robot's own clearance down would let it creep into a wall
            self.floor = self.start_floor(view, ctx, here)
        if ctx.global_path is not self.path:
            return self._release()
        progress, _ = project_on_path(ctx.global_path, np.array([here]), near=here, reach=1.0)
        self.arc = max(self.arc, float(progress[0]))
        if standing:  # a new leg: the farthest visible path point
            if self.arc - self.start_arc >= self.length:
                return self._release()
            found = self.carrot(view, ctx, here)
            if found is None:
                return self._release()
            self.leg = found[0]
        target = self.leg
        bearing = math.atan2(target.imag - here.imag, target.real - here.real)
        err = float(wrap_angle(bearing - state.theta))
        info = {"carrot": [target.real, target.imag], "heading_error": err}
        # the turn still to make, then the leg: is it safe enough from the movers?
        turning = 0.0 if not standing else abs(err) / robot.w_max + robot.w_max / robot.alpha_max
        way = np.exp(1j * (bearing if standing else state.theta))
        if not self.leg_safe_from_movers(view, ctx, here, way, abs(target - here), turning):
            return self._release()
        if standing and abs(err) > self.aim:
            return self._turn(robot, dt, err, info)
        heading = np.exp(1j * state.theta)
        ahead = self.free_ahead(ctx, here, heading, self.need(view, ctx))
        to_carrot = max(0.0, ((target - here) * np.conj(heading)).real)
        room = max(0.0, min(ahead, to_carrot) - 0.001)
        if standing and room < 0.02:
            # the bearing is within ``aim`` but the straight ahead is shut: aim exactly
            return self._turn(robot, dt, err, info) if abs(err) > 1e-6 else self._release()
        # fastest v with v dt + v^2 / (2 a) <= room: the robot can still stop within the room
        a = robot.a_max
        v = min(self.speed, robot.v_max, a * (-dt + math.sqrt(dt * dt + 2.0 * room / a)))
        self.legs += 1
        return v, 0.0, {"mode": "creep-drive", "room": room, **info}

    def start_floor(self, view: PlannerView, ctx: LocalContext, here: complex) -> float:
        """The gap legs keep in this creep: the required one, or (to 1 mm) what the robot keeps
        where it stands when that is less: a robot stopped a little inside the requirement
        may leave, but a threshold that followed its clearance down would let it creep into a wall."""
        need = self.required_gap(view, ctx)
        for k in range(21):
            if self.legs_free(ctx, here, np.array([here]), need - 0.001 * k)[0]:
                return need - 0.001 * k
        return need - 0.021

    def need(self, view: PlannerView, ctx: LocalContext) -> float:
        """The gap a leg keeps in this creep (:meth:`start_floor`)."""
        return min(self.required_gap(view, ctx), self.floor)

    @staticmethod
    def _turn(robot, dt: float, err: float, info: dict) -> tuple[float, float, dict]:
        """On the spot towards the bearing: the fastest yaw rate that can still stop on it, and
        the exact remainder in the last period."""
        w = math.copysign(min(robot.w_max, math.sqrt(2.0 * robot.alpha_max * abs(err)), abs(err) / dt), err)
        return 0.0, w, {"mode": "creep-turn", **info}

    def _release(self) -> None:
        self.active, self.stalled_for, self.standing_for, self.leg, self.path = False, 0.0, 0.0, None, None
        return None
