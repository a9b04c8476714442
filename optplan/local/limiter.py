"""Jerk-limited velocity commands through Ruckig's velocity interface.

Each velocity component (v, w and, for the omni model, vy) is one degree of freedom,
driven independently (no time synchronisation) towards its target velocity by Ruckig's
time-optimal profile with bounded acceleration and jerk. The command for the next
period is the profile's velocity one control period ahead. Because consecutive commands
are samples of one continuous profile, the accelerations the simulator measures,
``(v_k - v_{k-1}) / dt``, are period averages of the profile's acceleration and stay within
its bound, and their differences over ``dt`` stay within the jerk bound.

Ruckig's ``intermediate_positions`` (a remote service) is never used.
"""
from __future__ import annotations

import numpy as np
from ruckig import ControlInterface, InputParameter, OutputParameter, Result, Ruckig, Synchronization, Trajectory


class RuckigLimiter:
    """Turns target velocities into a jerk-limited command sequence.

    Args:
        dt: control period, s.
        max_acceleration: per component (m/s^2 or rad/s^2).
        max_jerk: per component (m/s^3 or rad/s^3); ``inf`` = unlimited.
        scale: limits handed to Ruckig are multiplied by this (slightly below 1) so that
            round-off never pushes a measured acceleration over the robot's limit.
    """

    def __init__(self, dt: float, max_acceleration, max_jerk, scale: float = 0.999) -> None:
        self.dt = float(dt)
        self.n = len(max_acceleration)
        self.max_acceleration = np.asarray(max_acceleration, dtype=float) * scale
        self.max_jerk = np.asarray(max_jerk, dtype=float) * scale
        self._otg = Ruckig(self.n, self.dt)
        self._inp = InputParameter(self.n)
        self._out = OutputParameter(self.n)
        inp = self._inp
        inp.control_interface = ControlInterface.Velocity
        inp.synchronization = Synchronization.No
        inp.max_acceleration = list(self.max_acceleration)
        inp.max_jerk = list(self.max_jerk)
        inp.target_acceleration = [0.0] * self.n
        self.reset(np.zeros(self.n))

    @property
    def velocity(self) -> np.ndarray:
        return np.array(self._inp.current_velocity)

    @property
    def acceleration(self) -> np.ndarray:
        return np.array(self._inp.current_acceleration)

    def reset(self, velocity, acceleration=None) -> None:
        """Start a new profile from ``velocity`` (and ``acceleration``, default 0)."""
        inp = self._inp
        inp.current_position = [0.0] * self.n  # unused by the velocity interface, kept bounded
        inp.current_velocity = [float(v) for v in velocity]
        acc = np.zeros(self.n) if acceleration is None else np.clip(acceleration, -self.max_acceleration,
                                                                   self.max_acceleration)
        inp.current_acceleration = [float(a) for a in acc]

    def sync(self, velocity, tol: float = 1e-6) -> bool:
        """Restart from the measured ``velocity`` if it differs from the profile (someone else
        commanded the robot); returns whether it did."""
        if np.max(np.abs(np.asarray(velocity, dtype=float) - self.velocity)) > tol:
            self.reset(velocity)
            return True
        return False

    def snapshot(self) -> tuple[np.ndarray, np.ndarray]:
        """``(velocity, acceleration)`` of the profile now (for :meth:`restore`)."""
        return self.velocity, self.acceleration

    def restore(self, snap: tuple[np.ndarray, np.ndarray]) -> None:
        """Go back to a :meth:`snapshot`."""
        inp = self._inp
        inp.current_position = [0.0] * self.n
        inp.current_velocity = [float(v) for v in snap[0]]
        inp.current_acceleration = [float(a) for a in snap[1]]

    def braking(self, steps: int) -> np.ndarray:
        """``(steps, n)``: the commands of the next ``steps`` periods that bring every
        component to rest from the profile's current state (the profile to zero velocity
        sampled one period apart, as :meth:`step` would give them). The state is unchanged."""
        inp = self._inp
        target = list(inp.target_velocity)
        inp.target_velocity = [0.0] * self.n
        traj = Trajectory(self.n)
        result = self._otg.calculate(inp, traj)
        inp.target_velocity = target
        if result not in (Result.Working, Result.Finished):
            # acceleration-limited stop (jerk unbounded), as step's fallback
            cur = self.velocity
            k = np.arange(1, steps + 1)[:, None] * self.dt
            return np.sign(cur) * np.maximum(np.abs(cur) - self.max_acceleration * k, 0.0)
        T = traj.duration
        return np.array([traj.at_time(min(k * self.dt, T))[1] if k * self.dt < T else [0.0] * self.n
                         for k in range(1, steps + 1)])

    def step(self, target) -> tuple[np.ndarray, str]:
        """The velocity one period ahead on the profile towards ``target``, and Ruckig's result."""
        inp, out = self._inp, self._out
        inp.target_velocity = [float(t) for t in target]
        result = self._otg.update(inp, out)
        if result in (Result.Working, Result.Finished):
            v = np.array(out.new_velocity)
            out.pass_to_input(inp)
            inp.current_position = [0.0] * self.n
            return v, result.name
        # Ruckig refused the input: fall back to an acceleration-limited step (jerk unbounded)
        cur = self.velocity
        v = cur + np.clip(np.asarray(target, dtype=float) - cur, -self.max_acceleration * self.dt,
                          self.max_acceleration * self.dt)
        self.reset(v)
        return v, f"ruckig error {result}"
