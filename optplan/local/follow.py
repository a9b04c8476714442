"""``follow``: the global path driven as it is, with no local obstacle avoidance.

The baseline the papers' fusions are measured against when they say a global planner alone
cannot avoid what its map does not hold (hou2024 §4.4, Fig 8: "MISSA, relying solely on global
map data, fails to recognize and subsequently avoid these obstructions"; §4.5). The path is
driven segment by segment: it turns in place towards the next vertex, drives to it with a small heading
correction, and brakes to a stop at every vertex where the path turns (and at the goal); every
command stays in the dynamic window. It never looks
at the distance field or the movers, and its guidance (``optplan/papers.py``) does not re-plan
when a sensed obstacle blocks the path.
"""
from __future__ import annotations

import math
import time

import numpy as np

from ..checks import number
from ..world.robot import Command, RobotSpec, RobotState
from .base import LocalContext
from .window import dynamic_window


class PathFollower:
    """The global path driven vertex by vertex, blind to obstacles (see the module docstring).

    Args:
        robot, dt: the robot and the control period (s).
        reached: metres; a vertex this close counts as reached.
        aligned: radians; a heading error beyond this is turned away in place before driving on.
        gain: rad/s per radian of heading error while driving (and turning, up to ``w_max``).
    """

    name = "follow"

    def __init__(self, robot: RobotSpec, dt: float, reached: float = 0.03, aligned: float = 0.05,
                 gain: float = 3.0) -> None:
        self.robot, self.dt = robot, number(minimum=0.0, strict_minimum=True)("dt", dt)
        self.reached = number(minimum=0.0, strict_minimum=True)("reached", reached)
        self.aligned = number(minimum=0.0, maximum=math.pi, strict_minimum=True)("aligned", aligned)
        self.gain = number(minimum=0.0, strict_minimum=True)("gain", gain)
        self._next = 1
        self._path: np.ndarray | None = None

    def reset(self, state: RobotState, global_path: np.ndarray) -> None:
        self._next, self._path = 1, None

    def _passed(self, path: np.ndarray, here: np.ndarray) -> bool:
        """The next vertex is reached: the robot is within ``reached`` of it, or has come
        within ``reached`` of it along the segment that leads to it (a few centimetres off
        the segment sideways, it would never come closer)."""
        a, b = path[self._next - 1], path[self._next]
        ab = b - a
        L = float(np.hypot(*ab))
        if np.hypot(*(b - here)) <= self.reached or L < 1e-12:
            return True
        return float(np.dot(here - a, ab)) / L >= L - self.reached

    def _straight_on(self, path: np.ndarray) -> float:
        """Metres the path runs on straight past the next vertex (through vertices where it
        turns by at most ``aligned``) before a turn or its end."""
        run, k = 0.0, self._next
        while k < len(path) - 1:
            a, b = path[k] - path[k - 1], path[k + 1] - path[k]
            if abs(math.remainder(math.atan2(b[1], b[0]) - math.atan2(a[1], a[0]), 2 * math.pi)) > self.aligned:
                break
            run += float(np.hypot(*b))
            k += 1
        return run

    def command(self, ctx: LocalContext) -> Command:
        t0 = time.perf_counter()
        st, r = ctx.state, self.robot
        path = np.asarray(ctx.global_path, float).reshape(-1, 2)
        if self._path is None or self._path.shape != path.shape or not np.array_equal(self._path, path):
            self._path, self._next = path, 1   # a new path (the navigator re-planned): start it over
        here = np.array([st.x, st.y])
        while self._next < len(path) - 1 and self._passed(path, here):
            self._next += 1
        target = path[min(self._next, len(path) - 1)]
        d = float(np.hypot(*(target - here)))
        alpha = math.remainder(math.atan2(target[1] - st.y, target[0] - st.x) - st.theta, 2 * math.pi)
        win = dynamic_window(r, st, self.dt)
        w = max(-r.w_max, min(r.w_max, self.gain * alpha)) if d > 1e-9 else 0.0
        if abs(alpha) > self.aligned or d <= 1e-9:
            v = 0.0
        else:   # brake to a stop at the next vertex where the path turns (or at its end)
            v = min(r.v_max, math.sqrt(2.0 * r.a_max * (d + self._straight_on(path))), d / self.dt + r.a_max * self.dt)
        v, w, vy = win.clip(v, w, 0.0)
        return Command(v=v, w=w, vy=vy, info={"planner": self.name, "mode": "follow", "status": "followed",
                                              "vertex": int(self._next),
                                              "solve_ms": (time.perf_counter() - t0) * 1e3})
