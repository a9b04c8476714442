"""What every local planner sees and returns: the contract between ``optplan.local``
and the closed loop in ``optplan.nav`` / ``optplan.sim``.

Each control period the loop builds a :class:`LocalContext` and calls
``planner.command(ctx)``; the planner returns a :class:`Command`. Planners may keep
state between calls (previous command, Ruckig's acceleration, warm starts);
``reset`` clears it at the start of a run.

A planner may also declare capabilities the loop uses when present, by subclassing
(or ``register``-ing with) the capability's class: :class:`MoverSweepSource`.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Callable, Protocol

import numpy as np

from ..world.robot import Command, RobotSpec, RobotState

# (..., 2) points in metres -> (...) signed distance in metres from the robot *centre*
# to the nearest static obstacle (known map + unknown obstacles sensed so far);
# negative inside obstacles. The robot radius is not subtracted.
DistanceFn = Callable[[np.ndarray], np.ndarray]
# (n, 2), (n, 2) segment ends in metres, clearance in metres -> (n,) bool: the exact segment rule
SegmentsFreeFn = Callable[[np.ndarray, np.ndarray, float], np.ndarray]


@dataclass
class LocalContext:
    """Everything a local planner may use at one control step.

    Attributes:
        state: current robot state.
        subgoal: current target point ``(2,)`` chosen by the navigation layer, metres.
        goal: final goal ``(2,)``, metres.
        global_path: ``(N, 2)`` global path being followed (after refinement), metres.
        static_distance: vectorised signed distance to static obstacles (see ``DistanceFn``).
        dynamic: ``(k, 5)`` rows ``(x, y, vx, vy, radius)`` of moving obstacles the robot
            currently senses (positions now, velocities as measured), metres and m/s.
        dt: control period, seconds.
        t: simulation time, seconds.
        static_points: optional ``(m, 2)`` centres of sensed static obstacle cells or
            circles near the robot, for terms that reason about individual obstacles.
        bounds: ``(xmin, ymin, xmax, ymax)`` of the world, metres.
        distance_error: how much ``static_distance`` may overestimate the true distance, m
            (an interpolated field near convex corners); ``None``: not known.
        segments_free: the exact segment rule of DESIGN.md on the static world known now
            (``segments_free(a, b, clearance) -> (n,) bool`` for segments ``a[i] -> b[i]``,
            ``(n, 2)`` metres); ``None``: not given. Slower than ``static_distance`` per
            query, but exact where the field errs (a gap a centimetre wider than the robot).
    """

    state: RobotState
    subgoal: np.ndarray
    goal: np.ndarray
    global_path: np.ndarray
    static_distance: DistanceFn
    dynamic: np.ndarray
    dt: float
    t: float = 0.0
    static_points: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    bounds: tuple[float, float, float, float] | None = None
    distance_error: float | None = None
    segments_free: SegmentsFreeFn | None = None


class LocalPlanner(Protocol):
    """What the closed loop calls. Construct with ``make_local_planner(name, robot, dt, **params)``."""

    name: str
    robot: RobotSpec

    def reset(self, state: RobotState, global_path: np.ndarray) -> None:
        """Forget the previous run (called once before the first ``command``)."""

    def command(self, ctx: LocalContext) -> Command:
        """The velocity command for the next control period."""


class MoverSweepSource(ABC):
    """Capability: knows stretches that moving obstacles sweep back and forth.

    The closed loop hands them to the navigation layer, which plans round them when the
    robot is stuck or its path crosses one (``Navigator.on_sweeps``). Every
    ``DWAPlanner`` declares it; presets without a mechanism that learns sweeps (only
    ``qp-dwa``'s sweep gate does) report none. A planner of one's own declares it by
    subclassing this class or with ``MoverSweepSource.register(PlannerClass)``.
    """

    @abstractmethod
    def mover_sweeps(self) -> np.ndarray:
        """``(n, 5)`` rows ``(x0, y0, x1, y1, r)``, metres: a disc of radius ``r`` is known to
        drive back and forth between ``(x0, y0)`` and ``(x1, y1)``."""
