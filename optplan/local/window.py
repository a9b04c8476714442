"""The dynamic window and the braking-distance admissibility of the DWA.

* ``V_m`` (hou2024 eq 20, yuan2021 eq 19): the robot's speed limits.
* ``V_d`` (hou2024 eq 21, yuan2021 eq 20): the velocities reachable within one control
  period ``dt`` from the current velocity under the acceleration limits. With a jerk limit
  (qp-dwa, whose commands pass through Ruckig) the reachable interval also depends on the
  current acceleration and is computed exactly for a jerk-limited ramp.
* ``V_a`` (hou2024 eq 22): a velocity is admissible when the robot can stop before the first
  collision on its predicted trajectory. The papers write ``v <= sqrt(2 dist)`` (hou2024) or
  ``v <= sqrt(2 dist v)`` (yuan2021, li2023 eq 9), with the deceleration left out or written as
  a speed; we use the physical form ``v <= sqrt(2 a_max dist)`` (Fox et al. 1997), optionally
  with a reaction time ``t_r`` during which the robot keeps moving before braking:
  ``v t_r + v^2 / (2 a) <= dist``. The papers' angular part ``w <= sqrt(2 dist)`` is dropped:
  it mixes units, and a disc-shaped robot cannot hit anything by turning on the spot.

Units: m/s, rad/s, m/s^2, rad/s^2, seconds, metres.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..world.robot import RobotSpec, RobotState


@dataclass(frozen=True)
class Window:
    """Closed intervals of the velocities that may be commanded for the next period.

    Attributes:
        v: ``(lo, hi)`` forward speed, m/s.
        w: ``(lo, hi)`` yaw rate, rad/s.
        vy: ``(lo, hi)`` sideways speed (omni model; ``(0, 0)`` for a unicycle), m/s.
    """

    v: tuple[float, float]
    w: tuple[float, float]
    vy: tuple[float, float] = (0.0, 0.0)

    def capped(self, v_hi: float | None = None, w_abs: float | None = None) -> "Window":
        """The window with the forward speed capped at ``v_hi`` and ``|w|`` at ``w_abs``;
        a cap below the reachable interval collapses it to the nearest reachable value
        (the window never becomes empty)."""
        v, w = self.v, self.w
        if v_hi is not None:
            v = (v[0], float(np.clip(v_hi, v[0], v[1])))
        if w_abs is not None:
            w = (float(np.clip(-w_abs, w[0], w[1])), float(np.clip(w_abs, w[0], w[1])))
        return replace(self, v=v, w=w)

    def clip(self, v: float, w: float, vy: float = 0.0) -> tuple[float, float, float]:
        """The nearest velocity inside the window."""
        return (float(np.clip(v, *self.v)), float(np.clip(w, *self.w)), float(np.clip(vy, *self.vy)))

    def contains(self, v: float, w: float, vy: float = 0.0, tol: float = 1e-9) -> bool:
        return (self.v[0] - tol <= v <= self.v[1] + tol and self.w[0] - tol <= w <= self.w[1] + tol
                and self.vy[0] - tol <= vy <= self.vy[1] + tol)


def reachable_change(a0: float, a_max: float, jerk: float | None, dt: float) -> float:
    """Largest velocity increase within ``dt`` starting at acceleration ``a0`` when the
    acceleration may not exceed ``a_max`` and changes at most at rate ``jerk``
    (``None`` = unlimited jerk, the classic window ``a_max dt``)."""
    if jerk is None or not np.isfinite(jerk):
        return a_max * dt
    a0 = min(max(a0, -a_max), a_max)
    t1 = min(max((a_max - a0) / jerk, 0.0), dt)  # time to ramp up to a_max
    return a0 * t1 + 0.5 * jerk * t1 * t1 + a_max * (dt - t1)


def _interval(current: float, lo_limit: float, hi_limit: float, up: float, down: float) -> tuple[float, float]:
    """``[current - down, current + up]`` intersected with the limits; when they do not
    overlap (a state outside the limits) the reachable value nearest to them is kept."""
    lo_w, hi_w = current - down, current + up
    return (float(np.clip(lo_limit, lo_w, hi_w)), float(np.clip(hi_limit, lo_w, hi_w)))


def dynamic_window(robot: RobotSpec, state: RobotState, dt: float, *, omni: bool = False,
                   accel: tuple[float, float, float] = (0.0, 0.0, 0.0),
                   jerk: tuple[float | None, float | None] = (None, None), a_lin: float | None = None) -> Window:
    """``V_m`` intersected with ``V_d`` (hou2024 eq 20-21).

    Args:
        robot: limits.
        state: current velocity ``(v, w, vy)``.
        dt: control period, s.
        omni: also open the sideways speed ``vy`` (hou2024 eq 19); otherwise ``vy`` is 0.
        accel: current accelerations ``(dv, dw, dvy)``, only used with a jerk limit.
        jerk: ``(linear, angular)`` jerk limits (m/s^3, rad/s^3); ``None`` = unlimited.
        a_lin: acceleration limit of each linear component ``v``, ``vy`` (default ``a_max``;
            an omni robot whose limit applies to the vector may pass ``a_max / sqrt(2)``).
    """
    jl, ja = jerk
    a = robot.a_max if a_lin is None else a_lin
    v = _interval(state.v, robot.v_min, robot.v_max, reachable_change(accel[0], a, jl, dt),
                  reachable_change(-accel[0], a, jl, dt))
    w = _interval(state.w, -robot.w_max, robot.w_max,
                  reachable_change(accel[1], robot.alpha_max, ja, dt),
                  reachable_change(-accel[1], robot.alpha_max, ja, dt))
    if omni and robot.model == "omni" and robot.vy_max > 0:
        vy = _interval(state.vy, -robot.vy_max, robot.vy_max, reachable_change(accel[2], a, jl, dt),
                       reachable_change(-accel[2], a, jl, dt))
    else:
        vy = (0.0, 0.0)
    return Window(v, w, vy)


def stopping_distance(speed, decel: float, reaction: float = 0.0):
    """Distance covered by a robot at ``speed`` that reacts after ``reaction`` s and then
    brakes at ``decel``: ``v t_r + v^2 / (2 a)`` (the braking distance of hou2024 eq 22)."""
    s = np.abs(speed)
    return s * reaction + s * s / (2.0 * decel)


def sample_grid(window: Window, n_v: int, n_w: int, n_vy: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Evenly spaced samples of the window: ``(lin_v, lin_vy, w)`` with the linear pairs
    ``(v, vy)`` flattened v-major (``n_v * n_vy`` of them) and ``n_w`` yaw rates. Sample
    ``s`` of the full grid is linear pair ``s // n_w`` with yaw rate ``s % n_w`` (the order of
    the textbook double loop ``for v: for w:``)."""
    v = np.linspace(window.v[0], window.v[1], n_v)
    vy = np.linspace(window.vy[0], window.vy[1], n_vy) if n_vy > 1 else np.array([0.5 * (window.vy[0] + window.vy[1])])
    w = np.linspace(window.w[0], window.w[1], n_w)
    lin_v = np.repeat(v, len(vy))
    lin_vy = np.tile(vy, len(v))
    return lin_v, lin_vy, w
