"""Moving obstacles of a scenario: a disc along a waypoint polygon or at a constant velocity,
its motion in closed form (one time or many at once), and the checks of its values."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ScenarioError
from .file_values import file_number

BORDER_MODES = ("bounce", "stop", "pass")


@dataclass
class DynamicObstacle:
    """A disc that moves along a waypoint polygon or at a constant velocity.

    Attributes:
        radius: metres.
        waypoints: ``(k, 2)`` polygon (metres) for waypoint movers, else ``None``.
        speed: m/s along the polygon.
        loop: drive the polygon closed and repeat (``False``: stop at the last waypoint).
        phase: metres along the polygon already driven at ``t = 0``.
        delay: seconds a waypoint mover waits where it stands at ``t = 0`` before it drives.
        start: ``(2,)`` position at ``t = 0`` of a constant-velocity mover, else ``None``.
        velocity: ``(2,)`` m/s of a constant-velocity mover.
        at_border: ``bounce``, ``stop`` or ``pass`` (constant-velocity movers).
    """

    radius: float
    waypoints: np.ndarray | None = None
    speed: float = 0.0
    loop: bool = True
    phase: float = 0.0
    start: np.ndarray | None = None
    velocity: np.ndarray | None = None
    at_border: str = "bounce"
    delay: float = 0.0

    def state(self, t: float, bounds: tuple[float, float, float, float]) -> tuple[np.ndarray, np.ndarray]:
        """Position ``(2,)`` (m) and velocity ``(2,)`` (m/s) at time ``t`` (s), in closed form."""
        if self.waypoints is not None:
            pos, vel = self._along_polygon_at(np.array([float(t)]))
            return pos[0], vel[0]
        return self._constant_velocity(t, bounds)

    def states(self, times, bounds: tuple[float, float, float, float]) -> tuple[np.ndarray, np.ndarray]:
        """Positions ``(T, 2)`` and velocities ``(T, 2)`` at the times ``(T,)``, all at once and
        equal to :meth:`state` at each time (the simulator tabulates its movers with it)."""
        t = np.asarray(times, dtype=float).reshape(-1)
        if self.waypoints is not None:
            return self._along_polygon_at(t)
        pos, vel = self._constant_velocity(t[:, None], bounds)
        return np.broadcast_to(pos, (len(t), 2)).copy(), np.broadcast_to(vel, (len(t), 2)).copy()

    def _along_polygon_at(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Position and velocity along the waypoint polygon at many times ``(T,)``: arc length
        from the phase, a loop wrapped, repeated waypoints skipped, a finished open route held."""
        P = self.waypoints
        still = (np.repeat(P[:1], len(t), axis=0), np.zeros((len(t), 2)))
        if len(P) == 1 or self.speed == 0:
            return still
        if self.loop:
            P = np.vstack([P, P[:1]])
        seg = np.diff(P, axis=0)
        lengths = np.hypot(seg[:, 0], seg[:, 1])
        cum = np.concatenate([[0.0], np.cumsum(lengths)])
        total = cum[-1]
        if total <= 0:
            return still
        driving = t - self.delay
        s = self.phase + self.speed * np.maximum(driving, 0.0)
        if self.loop:
            s = s % total
        i = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, len(seg) - 1)
        # the first non-empty leg from each leg on (the last leg if none), as the scalar loop skips
        nonempty = np.nonzero(lengths > 0)[0]
        later = np.searchsorted(nonempty, np.arange(len(seg)))
        skip = np.where(later < len(nonempty), nonempty[np.minimum(later, len(nonempty) - 1)], len(seg) - 1)
        i = skip[i]
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.where(lengths[i, None] > 0, seg[i] / lengths[i, None], 0.0)
        pos = P[i] + u * (s - cum[i])[:, None]
        vel = u * self.speed
        if not self.loop:
            done = s >= total
            pos[done] = P[-1]
            vel[done] = 0.0
        vel[driving < 0] = 0.0
        return pos, vel

    def _constant_velocity(self, t: float, bounds) -> tuple[np.ndarray, np.ndarray]:
        p0, v = self.start, self.velocity
        if self.at_border == "pass":
            return p0 + v * t, v.copy()
        lo = np.array(bounds[:2]) + self.radius
        hi = np.array(bounds[2:]) - self.radius
        if np.any(hi < lo):
            # no place inside the map holds the disc: bouncing or stopping would have to put it
            # somewhere it never was (validate() refuses such a mover when the file is read)
            raise ScenarioError(misfit_message("this mover", self.radius, bounds, self.at_border))
        if self.at_border == "stop":
            # the first time either coordinate reaches its limit
            with np.errstate(divide="ignore", invalid="ignore"):
                t_hit = np.where(v > 0, (hi - p0) / v, np.where(v < 0, (lo - p0) / v, np.inf))
            t_stop = max(float(np.min(t_hit)), 0.0)
            stopped = np.asarray(t >= t_stop)  # element-wise, so states() can ask for many times
            return np.where(stopped, p0 + v * t_stop, p0 + v * t), np.where(stopped, 0.0, v)
        # bounce: each coordinate is a triangle wave between lo and hi. A disc that starts over
        # the border moves straight on until it is wholly inside, and bounces from then on
        # (one moving away from the map, or not moving in that coordinate, never comes in);
        # folding its start into [lo, hi] instead would move it at t = 0.
        span = hi - lo
        free = p0 + v * t
        u = free - lo
        period = 2 * span
        with np.errstate(divide="ignore", invalid="ignore"):
            t_in = np.where(p0 < lo, np.where(v > 0, (lo - p0) / v, np.inf),
                            np.where(p0 > hi, np.where(v < 0, (hi - p0) / v, np.inf), 0.0))
        s = np.mod(u, np.where(period > 0, period, 1.0))
        back = s > span
        pos = np.where(span > 0, lo + np.where(back, period - s, s), lo)   # span 0: the disc just fits
        vel = np.where(span > 0, np.where(back, -v, v), 0.0)
        outside = t < t_in
        return np.where(outside, free, pos), np.where(outside, v, vel)


def check_mover(ob: DynamicObstacle, i: int, bounds=None) -> None:
    """Check mover ``i``'s values (and, given ``bounds``, that a bouncing or stopping disc fits the map)."""
    key = f"dynamic_obstacles[{i}]"
    file_number(ob.radius, f"{key}.radius", positive=True)
    if (ob.waypoints is None) == (ob.start is None):
        raise ScenarioError(f"{key} needs either waypoints (+ speed) or start (+ velocity)")
    if ob.waypoints is not None:
        file_number(ob.speed, f"{key}.speed", non_negative=True)
        file_number(ob.phase, f"{key}.phase", non_negative=True)
        file_number(ob.delay, f"{key}.delay", non_negative=True)
    else:
        if ob.velocity is None or np.shape(ob.velocity) != (2,) or not np.all(np.isfinite(ob.velocity)):
            raise ScenarioError(f"{key}.velocity must be [vx, vy] in m/s")
        if ob.at_border not in BORDER_MODES:
            raise ScenarioError(f"{key}.at_border must be one of {', '.join(BORDER_MODES)}, got {ob.at_border!r}")
        if bounds is not None and ob.at_border != "pass":
            xmin, ymin, xmax, ymax = bounds
            if 2 * ob.radius > min(xmax - xmin, ymax - ymin):
                raise ScenarioError(misfit_message(key, ob.radius, bounds, ob.at_border))


def misfit_message(key: str, radius: float, bounds, at_border: str) -> str:
    """The error text for a disc too wide to bounce or stop inside the map."""
    xmin, ymin, xmax, ymax = bounds
    return (f"{key} (radius {radius:g} m) is wider than the {xmax - xmin:g} x {ymax - ymin:g} m map, so it cannot "
            f"{at_border} at the border; use a radius of at most {min(xmax - xmin, ymax - ymin) / 2:g} m "
            f"or at_border: pass")
