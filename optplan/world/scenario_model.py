"""The :class:`Scenario` of a closed-loop run and its checks: the known map, what the robot
does not know yet, what moves, the robot, and the true static world they make.

The file format is read by :mod:`optplan.world.scenario`; the seed-dependent parts are
realised by :func:`optplan.worldgen.scenarios.realize`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ScenarioError
from .file_values import file_number
from .movers import DynamicObstacle, check_mover
from .robot import RobotSpec

# random draws larger than these are fills, not scenarios; refusing them keeps a hostile
# file from making the draw allocate without bound or retry for ever
MAX_RANDOM_OBSTACLES, MAX_RANDOM_MOVERS = 10_000, 1_000


@dataclass
class Scenario:
    """Everything a closed-loop run needs (see the module docstring for the file format).

    Attributes:
        world: the known map (GridMap or CircleWorld) the global planner sees.
        robot: footprint and limits.
        start: ``(3,)`` pose ``(x, y, theta)`` in metres and radians.
        goal: ``(2,)`` metres.
        sensor_range: distance (m) within which unknown obstacles and movers are sensed.
        dt: control and simulation period, seconds.
        time_limit: seconds of simulated time before a run counts as a timeout.
        unknown_cells: ``(m, 2)`` integer cells ``(ix, iy)`` blocked but missing from ``world``.
        unknown_circles: ``(k, 3)`` discs ``(x, y, r)`` missing from ``world``.
        dynamic: moving obstacles.
        goal_tolerance: metres.
        name, description: free text.
        random_obstacles, random_dynamic: seed-dependent parts (``None`` when absent);
            :func:`optplan.worldgen.scenarios.realize` turns them into unknown and moving obstacles.
        timing_jitter: seconds; ``realize`` advances each mover by a random time up to this.
        source: the file it was read from, if any.
        planner_params: options per local planner name (``{"qp-dwa": {...}}``), laid under
            the caller's ``planner_params`` by ``op.simulate``.
        global_options: ``op.plan`` options of the global planner, under the caller's.
    """

    world: Any
    robot: RobotSpec
    start: np.ndarray
    goal: np.ndarray
    sensor_range: float = 3.0
    dt: float = 0.1
    time_limit: float = 300.0
    unknown_cells: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int64))
    unknown_circles: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    dynamic: list[DynamicObstacle] = field(default_factory=list)
    goal_tolerance: float = 0.3
    name: str = ""
    description: str = ""
    random_obstacles: dict | None = None
    random_dynamic: dict | None = None
    timing_jitter: float = 0.0
    source: str = ""
    planner_params: dict = field(default_factory=dict)
    global_options: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.start = np.asarray(self.start, dtype=float).reshape(-1)
        if self.start.shape == (2,):
            self.start = np.append(self.start, 0.0)
        self.goal = np.asarray(self.goal, dtype=float).reshape(-1)
        self.unknown_cells = np.asarray(self.unknown_cells, dtype=np.int64).reshape(-1, 2)
        self.unknown_circles = np.asarray(self.unknown_circles, dtype=float).reshape(-1, 3)
        validate(self)

    @property
    def is_grid(self) -> bool:
        return self.world.is_grid

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        return tuple(float(b) for b in self.world.bounds)

    def true_world(self):
        """The static world as it really is: the known map plus the unknown cells (grids)
        or discs (circle worlds, without the planning safety margin). Unknown discs on a
        grid are not included; see :func:`static_clearance`."""
        return _true_world(self)


# ------------------------------------------------------------------ true world
def _true_world(sc: Scenario):
    from .circles import CircleWorld

    if sc.is_grid:
        if not len(sc.unknown_cells):
            return sc.world
        from .grid import GridMap

        occ = sc.world.occ.copy()
        occ[sc.unknown_cells[:, 1], sc.unknown_cells[:, 0]] = True
        return GridMap(occ, sc.world.resolution, sc.world.origin, f"{sc.world.name}+unknown")
    circles = np.vstack([sc.world.circles, sc.unknown_circles]) if len(sc.unknown_circles) else sc.world.circles
    return CircleWorld(sc.world.bounds, circles, 0.0, sc.world.name)


def circle_distance(points, circles) -> np.ndarray:
    """Signed distance (m) from points ``(..., 2)`` to the nearest of ``circles`` ``(k, 3)``
    (``inf`` when there are none)."""
    p = np.asarray(points, dtype=float)
    c = np.asarray(circles, dtype=float).reshape(-1, 3)
    if not len(c):
        return np.full(p.shape[:-1], np.inf)
    d = np.hypot(p[..., None, 0] - c[:, 0], p[..., None, 1] - c[:, 1]) - c[:, 2]
    return d.min(axis=-1)


def static_clearance(sc: Scenario, points) -> np.ndarray:
    """Exact signed distance (m) from points to the true static world (known map,
    unknown cells and unknown discs, and the map border)."""
    d = np.asarray(sc.true_world().clearance(points), dtype=float)
    if sc.is_grid and len(sc.unknown_circles):
        d = np.minimum(d, circle_distance(points, sc.unknown_circles))
    return d


# ------------------------------------------------------------------ validation
def validate(sc: Scenario) -> None:
    """Check a scenario's values and geometry, raising ScenarioError with the fix."""
    if not hasattr(sc.world, "bounds") or not hasattr(sc.world, "segments_free"):
        raise ScenarioError(f"scenario world must be a GridMap or CircleWorld, got {type(sc.world).__name__}")
    if not isinstance(sc.robot, RobotSpec):
        raise ScenarioError(f"scenario robot must be a RobotSpec, got {type(sc.robot).__name__}")
    if sc.start.shape != (3,) or not np.all(np.isfinite(sc.start)):
        raise ScenarioError(f"start must be [x, y] or [x, y, heading_deg] with finite numbers, got {sc.start!r}")
    if sc.goal.shape != (2,) or not np.all(np.isfinite(sc.goal)):
        raise ScenarioError(f"goal must be [x, y] with finite numbers, got {sc.goal!r}")
    for key in ("sensor_range", "dt", "time_limit", "goal_tolerance"):
        file_number(getattr(sc, key), key, positive=True)
    if sc.dt > sc.time_limit:
        raise ScenarioError(f"dt ({sc.dt:g} s) must not exceed time_limit ({sc.time_limit:g} s)")
    if sc.time_limit / sc.dt > 10_000_000:
        raise ScenarioError(f"time_limit / dt = {sc.time_limit / sc.dt:.3g} steps is too many; raise dt or lower time_limit")
    xmin, ymin, xmax, ymax = sc.bounds
    if len(sc.unknown_cells):
        if not sc.is_grid:
            raise ScenarioError("unknown_obstacles 'cells' need a grid map; on a circle world use {circle: [x, y, r]}")
        bad = ~sc.world.in_map(sc.unknown_cells)
        if np.any(bad):
            c = sc.unknown_cells[np.argmax(bad)]
            raise ScenarioError(f"unknown obstacle cell {c.tolist()} is outside the {sc.world.width}x{sc.world.height} map")
    if len(sc.unknown_circles) and (not np.all(np.isfinite(sc.unknown_circles)) or np.any(sc.unknown_circles[:, 2] <= 0)):
        raise ScenarioError("unknown obstacle circles must be [x, y, r] with finite centre and r > 0")
    r = sc.robot.radius
    for what, p in (("start", sc.start[:2]), ("goal", sc.goal)):
        if not (xmin <= p[0] <= xmax and ymin <= p[1] <= ymax):
            raise ScenarioError(f"{what} ({p[0]:g}, {p[1]:g}) is outside the map bounds "
                                f"x in [{xmin:g}, {xmax:g}], y in [{ymin:g}, {ymax:g}]")
        known = float(sc.world.clearance(p))
        if known < r:
            raise ScenarioError(f"{what} ({p[0]:g}, {p[1]:g}) is blocked or closer than the robot radius {r:g} m "
                                f"to an obstacle of the map (clearance {known:.3g} m); move it into free space")
        true = float(static_clearance(sc, p))
        if true < r:
            raise ScenarioError(f"an unknown obstacle overlaps the robot at the {what} ({p[0]:g}, {p[1]:g}) "
                                f"(clearance {true:.3g} m < radius {r:g} m); move the obstacle or the {what}")
    _check_random_draws(sc)
    for i, ob in enumerate(sc.dynamic):
        check_mover(ob, i, sc.bounds)
        pos, _ = ob.state(0.0, sc.bounds)
        gap = float(np.hypot(*(pos - sc.start[:2]))) - ob.radius - r
        if gap < 0:
            raise ScenarioError(f"dynamic obstacle {i} at ({pos[0]:g}, {pos[1]:g}) overlaps the robot's start "
                                f"(gap {gap:.3g} m); move it away by at least {-gap:.3g} m")


def _check_random_draws(sc: Scenario) -> None:
    """Refuse random obstacles and movers that no map of this size can hold."""
    xmin, ymin, xmax, ymax = sc.bounds
    span, area = max(xmax - xmin, ymax - ymin), (xmax - xmin) * (ymax - ymin)
    blocks, movers = sc.random_obstacles or {}, sc.random_dynamic or {}
    if blocks.get("count", 0):
        count, size = blocks["count"], blocks["size"]
        limit, size_limit, unit = MAX_RANDOM_OBSTACLES, span, "m"
        if sc.is_grid:  # size in cells
            w, h = sc.world.width, sc.world.height
            limit, size_limit, unit = min(limit, w * h), max(w, h), "cells"
        if count > limit:
            raise ScenarioError(f"random_obstacles.count ({count}) is more than this map can take (at most {limit})")
        if size > size_limit:
            raise ScenarioError(f"random_obstacles.size ({size:g} {unit}) is larger than the map ({size_limit:g} {unit})")
    if movers.get("count", 0):
        count, radius = movers["count"], movers["radius"]
        if radius > span / 2:
            raise ScenarioError(f"random_dynamic.radius ({radius:g} m) is larger than half the map ({span / 2:g} m)")
        # movers never touch, so their discs alone must fit in the map
        limit = min(MAX_RANDOM_MOVERS, int(area / (math.pi * radius ** 2)))
        if count > limit:
            raise ScenarioError(f"random_dynamic.count ({count}) is more than {limit} discs of radius {radius:g} m "
                                f"that fit apart in this map; lower count or radius")
