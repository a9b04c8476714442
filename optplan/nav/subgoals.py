"""Subgoal selection: which point of the global path the local planner steers to next.

Every strategy is built once per run, told the global path with :meth:`reset` (again
after each re-plan) and asked each control period for the current subgoal with
:meth:`select`. All of them end at the goal.

* ``goal`` — no global guidance: the final goal is the only target (the "traditional
  DWA" the papers compare against).
* ``key_points`` — li2023 §4.4 (also hou2024 §3.2): remove collinear points, then keep
  only the turning points needed for line of sight (``world.postprocess.key_points``
  with the robot radius as clearance); each is a stage target.
* ``turning_points`` — yuan2021 §4.1 step 3: every turning point of the global path
  (collinear points removed) in turn.
* ``navigation_points`` — yang2023 §6: the path is divided into points ``ds`` apart; with
  the robot at point ``i`` the target is point ``i + n`` where ``n`` grows with the robot's
  speed, or point ``i + k n`` when a sensed moving obstacle is within the avoidance
  distance *and* the velocity-obstacle test (yang2023 eq 12-14) predicts a collision.

Stage targets (key / turning points) advance when the robot comes within
``switch_radius`` of them, when it has gone past them (beyond the perpendiculars at the
target of both the leg that ends there and the leg that starts there: a robot that swerved
round a mover and missed the target by more than ``switch_radius`` would otherwise be sent
back to it), and are skipped when a sensed obstacle leaves less than the robot radius
around them (yuan2021 §4.1 step 5).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import UnknownAlgorithmError
from ..world.postprocess import key_points, remove_collinear, remove_duplicates

STRATEGIES = ("goal", "key_points", "turning_points", "navigation_points")


def velocity_obstacle_hits(position: np.ndarray, velocity: np.ndarray, obstacles: np.ndarray,
                           robot_radius: float) -> np.ndarray:
    """Velocity-obstacle test (yang2023 eq 12-14) for each moving obstacle.

    The relative velocity ``V_r = v_robot - v_obstacle`` is kept constant; the robot
    is on a collision course when the ray ``P_r + V_r t`` (``t >= 0``) from the robot
    enters the obstacle disc grown by the robot radius.

    Args:
        position, velocity: robot centre (m) and world-frame velocity (m/s), ``(2,)``.
        obstacles: ``(k, 5)`` rows ``(x, y, vx, vy, radius)``.
        robot_radius: metres.

    Returns:
        Boolean ``(k,)``: True where the relative velocity lies in the collision cone.
    """
    ob = np.asarray(obstacles, dtype=float).reshape(-1, 5)
    rel_p = ob[:, :2] - np.asarray(position, float)          # obstacle seen from the robot
    rel_v = np.asarray(velocity, float) - ob[:, 2:4]         # robot's velocity relative to each obstacle
    vv = np.einsum("ij,ij->i", rel_v, rel_v)
    # time of closest approach along the ray (0 when not approaching)
    t_star = np.maximum(np.einsum("ij,ij->i", rel_p, rel_v) / np.where(vv > 0, vv, 1.0), 0.0)
    closest = rel_p - t_star[:, None] * rel_v
    return np.hypot(closest[:, 0], closest[:, 1]) < ob[:, 4] + robot_radius


class SubgoalStrategy:
    """Base class: a fixed sequence of stage targets visited in order."""

    name = "base"

    def __init__(self, robot_radius: float, switch_radius: float = 0.6):
        self.radius = float(robot_radius)
        self.switch_radius = float(switch_radius)
        self.targets = np.zeros((0, 2))
        self.origin = np.zeros(2)
        self.index = 0

    def stage_targets(self, path: np.ndarray, world) -> np.ndarray:
        """The targets of a path, start excluded, goal last."""
        raise NotImplementedError

    def reset(self, path: np.ndarray, world, goal: np.ndarray) -> None:
        """Adopt a new global path (start first, ``goal`` last)."""
        P = remove_duplicates(np.asarray(path, dtype=float))
        T = self.stage_targets(P, world) if len(P) >= 2 else np.zeros((0, 2))
        if not len(T) or np.hypot(*(T[-1] - goal)) > 1e-9:
            T = np.vstack([T, goal])
        self.targets = T
        self.origin = P[0] if len(P) else np.asarray(goal, dtype=float)
        self.index = 0

    def _passed(self, i: int, position: np.ndarray) -> bool:
        """Whether the robot is past stage target ``i`` (not the last): beyond the
        perpendicular at the target of the leg that ends there and of the leg after it."""
        T = self.targets
        before = T[i - 1] if i > 0 else self.origin
        offset = position - T[i]
        return bool(offset @ (T[i] - before) > 0 and offset @ (T[i + 1] - T[i]) > 0)

    def _blocked(self, point: np.ndarray, static_distance) -> bool:
        return static_distance is not None and float(static_distance(point)) < self.radius

    def select(self, position: np.ndarray, velocity: np.ndarray, dynamic: np.ndarray, static_distance=None) -> np.ndarray:
        """The current target ``(2,)``: advance past reached or obstructed stage targets."""
        last = len(self.targets) - 1
        while self.index < last and (np.hypot(*(self.targets[self.index] - position)) <= self.switch_radius
                                     or self._passed(self.index, position)
                                     or self._blocked(self.targets[self.index], static_distance)):
            self.index += 1
        return self.targets[self.index]

    def upcoming(self) -> np.ndarray:
        """Targets not yet reached (current first)."""
        return self.targets[self.index:]


class GoalOnly(SubgoalStrategy):
    """No global guidance: the final goal is the only target."""

    name = "goal"

    def stage_targets(self, path, world):
        return np.zeros((0, 2))


class KeyPoints(SubgoalStrategy):
    """Key points of the global path (li2023 §4.4; hou2024 §3.2)."""

    name = "key_points"

    def stage_targets(self, path, world):
        return key_points(world, path, clearance=self.radius)[1:]


class TurningPoints(SubgoalStrategy):
    """Every turning point of the global path (yuan2021 §4.1, step 3)."""

    name = "turning_points"

    def stage_targets(self, path, world):
        return remove_collinear(path)[1:]


class NavigationPoints(SubgoalStrategy):
    """Navigation points ``i + n`` / ``i + k n`` (yang2023 §6).

    Args:
        robot_radius: metres.
        spacing: distance ``ds`` between navigation points along the path, metres.
        lookahead_time: ``n`` covers the distance driven in this many seconds at the
            current speed (yang2023 §6 lets ``n`` grow with the robot's speed); 3 s (the
            prediction period) helps the yang2023 fusion but stalls idwa in a small room,
            see docs/fidelity/yang2023.md ...
        min_lookahead: ... but never less than this many metres ...
        w_max: ... nor than the diameter ``2 v / w_max`` of the tightest circle the robot
            can drive at its current speed ``v`` (rad/s; ``None``: no such bound). A point
            nearer than that can lie inside the circle, which the robot then orbits.
        avoid_distance: a moving obstacle closer than this (centre distance minus both
            radii, metres) is checked with the velocity obstacle.
    """

    name = "navigation_points"

    def __init__(self, robot_radius: float, switch_radius: float = 0.6, spacing: float = 0.25,
                 lookahead_time: float = 1.5, min_lookahead: float = 1.0, avoid_distance: float = 2.0,
                 w_max: float | None = None):
        super().__init__(robot_radius, switch_radius)
        self.spacing = float(spacing)
        self.lookahead_time = float(lookahead_time)
        self.min_lookahead = float(min_lookahead)
        self.avoid_distance = float(avoid_distance)
        self.w_max = None if w_max is None else float(w_max)
        self.last_k = 1

    def lookahead(self, speed: float) -> float:
        """Distance (m) along the path from the robot's point to its navigation point."""
        turning_diameter = 2.0 * speed / self.w_max if self.w_max else 0.0
        return max(speed * self.lookahead_time, self.min_lookahead, turning_diameter)

    def stage_targets(self, path, world):
        seg = np.diff(path, axis=0)
        n = np.maximum(np.ceil(np.hypot(seg[:, 0], seg[:, 1]) / self.spacing).astype(int), 1)
        pts = [path[i] + seg[i] * (np.arange(1, n[i] + 1)[:, None] / n[i]) for i in range(len(seg))]
        return np.vstack(pts)

    def select(self, position, velocity, dynamic, static_distance=None):
        T = self.targets
        last = len(T) - 1
        # robot's location i: nearest navigation point, searched forward only
        window = T[self.index:min(self.index + 80, last + 1)]
        i = self.index + int(np.argmin(np.hypot(window[:, 0] - position[0], window[:, 1] - position[1])))
        self.index = i
        speed = float(np.hypot(*velocity))
        n = max(math.ceil(self.lookahead(speed) / self.spacing), 1)
        k = 1
        if len(dynamic):
            gap = np.hypot(dynamic[:, 0] - position[0], dynamic[:, 1] - position[1]) - dynamic[:, 4] - self.radius
            near = gap < self.avoid_distance
            if np.any(near):
                hits = velocity_obstacle_hits(position, velocity, dynamic[near], self.radius)
                if np.any(hits):
                    # yang2023 ties k to the avoidance distance and the obstacle size; here the
                    # jump reaches past both: avoidance distance + obstacle diameter + robot radius
                    size = float(dynamic[near][hits, 4].max())
                    k = max(2, math.ceil((self.avoid_distance + 2 * size + self.radius) / (n * self.spacing)))
        self.last_k = k
        j = min(i + k * n, last)
        while j < last and self._blocked(T[j], static_distance):
            j += 1
        return T[j]


def make_strategy(name: str, robot_radius: float, w_max: float | None = None, **params) -> SubgoalStrategy:
    """A subgoal strategy by name (see ``STRATEGIES``); ``w_max`` (rad/s, the robot's) bounds
    the navigation points' lookahead (:class:`NavigationPoints`) and is unused by the others."""
    classes = {"goal": GoalOnly, "key_points": KeyPoints, "turning_points": TurningPoints,
               "navigation_points": NavigationPoints}
    if name not in classes:
        raise UnknownAlgorithmError(f"unknown subgoal strategy {name!r}; known: {', '.join(STRATEGIES)}")
    if classes[name] is NavigationPoints:
        params.setdefault("w_max", w_max)
    return classes[name](robot_radius, **params)
