"""Scenarios: the known map, what the robot does not know yet, what moves, and the robot.

A scenario file (YAML) has the keys of DESIGN.md; angles are degrees in the file and
radians in memory, lengths metres, times seconds::

    map: maps/office.map          # path relative to this file (or absolute), a shipped map
                                  # name (optplan.world.maps.names()), or an inline list of 0/1 rows
    resolution: 1.0               # cell size for inline rows and plain 0/1 files
    robot: {model: unicycle, radius: 0.2, v_max: 1.0, w_max_deg: 30,
            a_max: 0.3, alpha_max_deg: 50, jerk_max: null}
    start: [0.5, 0.5, 45]         # x, y, heading in degrees (heading optional, default 0)
    goal: [19.5, 19.5]
    sensor_range: 3.0
    dt: 0.1
    time_limit: 300
    unknown_obstacles:            # not in the map the global planner sees
      - {cells: [[5, 6], [5, 7]]}
      - {circle: [12.0, 8.0, 0.5]}
    dynamic_obstacles:
      - {radius: 0.3, waypoints: [[3, 10], [15, 10]], speed: 0.5, loop: true}
      - {radius: 0.6, start: [20, 5], velocity: [-0.6, 0.0]}

Only ``map``, ``start`` and ``goal`` are required; the others default to
``resolution`` of the map, ``RobotSpec()``, ``sensor_range: 3``, ``dt: 0.1``,
``time_limit: 300`` and no obstacles.

Optional keys added by optplan (all validated like the rest):

* ``name``, ``description``: free text (``description`` says which paper experiment a
  shipped scenario stands in for and how it was made).
* ``goal_tolerance``: distance (m) from the goal centre that counts as reached (0.3).
* ``dynamic_obstacles[i].loop``: ``true`` (default) drives the waypoint polygon closed,
  back to the first waypoint and round again (two waypoints: back and forth);
  ``false`` stops at the last waypoint. ``phase`` (m, default 0) is the distance along
  the polygon already driven at ``t = 0``. Waypoints that are all one point make a mover
  that stands there.
* ``dynamic_obstacles[i].at_border`` for constant-velocity obstacles: ``bounce``
  (default; reflect off the map border shrunk by the obstacle radius), ``stop`` (halt
  where the disc first touches the border) or ``pass`` (leave the map). A bouncing disc
  that starts over the border drives on until it is inside, then bounces; ``bounce`` and
  ``stop`` need a disc no wider than the map (a wider one is refused when the file is read).
* ``random_obstacles: {count, size, keep_away}``: ``count`` unknown square blocks of
  ``size`` x ``size`` cells (circle worlds: discs of diameter ``size`` m), drawn from the
  run's seed on cells of the run's global path (the *reference path*: the path the
  robot is given, or the known map's shortest path when none is) at least ``keep_away`` m
  (default 2) from start and goal; draws that would leave the goal unreachable for
  the robot's footprint are redrawn. This is hou2024 §4.4 "random obstacles".
* ``random_dynamic: {count, radius, speed: [lo, hi], length: [lo, hi], keep_away}``:
  ``count`` obstacles drawn from the seed, each driving back and forth along a straight
  segment of the given length range that crosses the reference path (at
  least ``keep_away`` m, default 3, from start and goal) at a random angle of 60-120
  degrees, with a random phase; segments are kept free of known obstacles and the border
  by the obstacle radius (an end that is not is pulled towards the path in steps of 20 %,
  so tracks near walls end up shorter than the drawn length, down to the larger of 1 m
  and half the lower length bound: on the 11x11 map of li2023 Experiment II about two
  tracks in three are shorter than 2 m), away from start and goal, far enough from each other that two
  movers never touch (both radii + 0.1 m), and must cross the reference path once
  (not run along it), so a robot that cannot reverse can always wait outside one
  mover's sweep. Sweeps of different movers may overlap along the path; the robot
  then has to cross them together.

* Draws no map can hold are refused when the file is read: more random obstacles than
  the map has cells (at most 10,000) or blocks wider than the map, and more random
  movers than discs of their radius fit apart in the map (at most 1,000).

* ``timing_jitter``: seconds (default 0). Each moving obstacle of the file is advanced
  along its motion by a time drawn uniformly from ``[0, timing_jitter]`` with the
  run's seed, so seeded runs of a fixed scenario meet the movers at different moments.

This module reads and checks the file; the seed-dependent parts are realised by
:func:`optplan.worldgen.scenarios.realize` (``op.simulate`` calls it with its ``seed``
and its initial global path), so the same scenario file, seed and global path always
give the same world. Drawing them needs a planner, which this layer may not import.
Malformed files raise :class:`ScenarioError` naming the key and what to write instead.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import MapFormatError, OptplanError, ScenarioError
from .robot import FILE_KEYS, RobotSpec

SCENARIOS_DIR = Path(__file__).resolve().parent.parent / "data" / "scenarios"

TOP_KEYS = ("map", "resolution", "robot", "start", "goal", "sensor_range", "dt", "time_limit",
            "unknown_obstacles", "dynamic_obstacles", "name", "description", "goal_tolerance",
            "random_obstacles", "random_dynamic", "timing_jitter")
REQUIRED = ("map", "start", "goal")
BORDER_MODES = ("bounce", "stop", "pass")
# random draws larger than these are fills, not scenarios; refusing them keeps a hostile
# file from making the draw allocate without bound or retry for ever
MAX_RANDOM_OBSTACLES, MAX_RANDOM_MOVERS = 10_000, 1_000


# ----------------------------------------------------------------- value checks
def _where(ctx: str) -> str:
    return f"scenario {ctx}" if ctx else "scenario"


def _number(value, key: str, *, positive: bool = False, non_negative: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ScenarioError(f"{key} must be a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise ScenarioError(f"{key} must be a finite number, got {value!r}")
    if positive and v <= 0:
        raise ScenarioError(f"{key} must be > 0, got {value!r}")
    if non_negative and v < 0:
        raise ScenarioError(f"{key} must be >= 0, got {value!r}")
    return v


def _vector(value, key: str, lengths: tuple[int, ...] = (2,)) -> np.ndarray:
    if not isinstance(value, (list, tuple, np.ndarray)) or len(value) not in lengths:
        want = " or ".join(str(n) for n in lengths)
        raise ScenarioError(f"{key} must be a list of {want} numbers, got {value!r}")
    return np.array([_number(v, f"{key}[{i}]") for i, v in enumerate(value)], dtype=float)


def _points(value, key: str, min_len: int = 1) -> np.ndarray:
    if not isinstance(value, (list, tuple)) or len(value) < min_len:
        raise ScenarioError(f"{key} must be a list of at least {min_len} [x, y] pairs, got {value!r}")
    return np.array([_vector(p, f"{key}[{i}]") for i, p in enumerate(value)], dtype=float).reshape(-1, 2)


def _mapping(value, key: str, allowed: tuple[str, ...]) -> dict:
    if not isinstance(value, dict):
        raise ScenarioError(f"{key} must be a mapping with keys {', '.join(allowed)}, got {value!r}")
    unknown = sorted(set(map(str, value)) - set(allowed))
    if unknown:
        raise ScenarioError(f"unknown key(s) {unknown} in {key}; known: {', '.join(allowed)}")
    return value


def _range(value, key: str) -> tuple[float, float]:
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        v = _number(value, key, non_negative=True)
        return (v, v)
    lo, hi = _vector(value, key)
    if lo < 0 or hi < lo:
        raise ScenarioError(f"{key} must be [low, high] with 0 <= low <= high, got {value!r}")
    return (float(lo), float(hi))


# ------------------------------------------------------------- moving obstacles
@dataclass
class DynamicObstacle:
    """A disc that moves along a waypoint polygon or at a constant velocity.

    Attributes:
        radius: metres.
        waypoints: ``(k, 2)`` polygon (metres) for waypoint movers, else ``None``.
        speed: m/s along the polygon.
        loop: drive the polygon closed and repeat (``False``: stop at the last waypoint).
        phase: metres along the polygon already driven at ``t = 0``.
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
        s = self.phase + self.speed * t
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
            raise ScenarioError(_misfit_message("this mover", self.radius, bounds, self.at_border))
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


# ----------------------------------------------------------------------- scenario
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
        _number(getattr(sc, key), key, positive=True)
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
        _check_mover(ob, i, sc.bounds)
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


def _check_mover(ob: DynamicObstacle, i: int, bounds=None) -> None:
    key = f"dynamic_obstacles[{i}]"
    _number(ob.radius, f"{key}.radius", positive=True)
    if (ob.waypoints is None) == (ob.start is None):
        raise ScenarioError(f"{key} needs either waypoints (+ speed) or start (+ velocity)")
    if ob.waypoints is not None:
        _number(ob.speed, f"{key}.speed", non_negative=True)
        _number(ob.phase, f"{key}.phase", non_negative=True)
    else:
        if ob.velocity is None or np.shape(ob.velocity) != (2,) or not np.all(np.isfinite(ob.velocity)):
            raise ScenarioError(f"{key}.velocity must be [vx, vy] in m/s")
        if ob.at_border not in BORDER_MODES:
            raise ScenarioError(f"{key}.at_border must be one of {', '.join(BORDER_MODES)}, got {ob.at_border!r}")
        if bounds is not None and ob.at_border != "pass":
            xmin, ymin, xmax, ymax = bounds
            if 2 * ob.radius > min(xmax - xmin, ymax - ymin):
                raise ScenarioError(_misfit_message(key, ob.radius, bounds, ob.at_border))


def _misfit_message(key: str, radius: float, bounds, at_border: str) -> str:
    xmin, ymin, xmax, ymax = bounds
    return (f"{key} (radius {radius:g} m) is wider than the {xmax - xmin:g} x {ymax - ymin:g} m map, so it cannot "
            f"{at_border} at the border; use a radius of at most {min(xmax - xmin, ymax - ymin) / 2:g} m "
            f"or at_border: pass")


# --------------------------------------------------------------------- reading
def _read_map(spec, resolution, base_dir: Path | None):
    from .grid import GridMap
    from .loaders import load_map

    if isinstance(spec, list):
        try:
            rows = np.array(spec)
            if rows.ndim != 2 or not np.all(np.isin(rows, (0, 1))):
                raise ValueError
        except ValueError:
            raise ScenarioError("an inline map must be a list of equal-length rows of 0/1 values (top row first)") from None
        return GridMap.from_rows(rows.astype(bool), 1.0 if resolution is None else resolution, name="inline")
    if not isinstance(spec, (str, os.PathLike)):
        raise ScenarioError(f"map must be a file path, a shipped map name or a list of 0/1 rows, got {spec!r}")
    p = Path(spec)
    if not p.is_absolute() and base_dir is not None and (base_dir / p).exists():
        p = base_dir / p
    try:
        world = load_map(p if p.exists() else spec)
    except MapFormatError as exc:
        raise ScenarioError(f"map {spec!r}: {exc}") from None
    if resolution is not None and world.is_grid and resolution != world.resolution:
        if world.resolution != 1.0:
            raise ScenarioError(f"map {spec!r} has its own resolution {world.resolution:g} m; "
                                f"remove 'resolution: {resolution:g}' from the scenario or make them agree")
        world = GridMap(world.occ, resolution, world.origin, world.name)
    if resolution is not None and not world.is_grid:
        raise ScenarioError("'resolution' applies to grid maps only; remove it for a circle world")
    return world


def _read_unknown(items, world) -> tuple[np.ndarray, np.ndarray]:
    if items is None:
        return np.zeros((0, 2), np.int64), np.zeros((0, 3))
    if not isinstance(items, list):
        raise ScenarioError("unknown_obstacles must be a list of {cells: [[ix, iy], ...]} or {circle: [x, y, r]}")
    cells, circles = [], []
    for i, item in enumerate(items):
        key = f"unknown_obstacles[{i}]"
        item = _mapping(item, key, ("cells", "circle"))
        if len(item) != 1:
            raise ScenarioError(f"{key} must have exactly one of 'cells' or 'circle'")
        if "cells" in item:
            pts = _points(item["cells"], f"{key}.cells")
            if not np.all(pts == np.round(pts)):
                raise ScenarioError(f"{key}.cells must be integer cell indices [ix, iy]")
            huge = np.any(np.abs(pts) > 2 ** 31, axis=1)  # would overflow the integer cast below
            if huge.any():
                raise ScenarioError(f"{key}.cells: cell {pts[np.argmax(huge)].tolist()} is outside any map")
            cells.append(pts.astype(np.int64))
        else:
            c = _vector(item["circle"], f"{key}.circle", (3,))
            if c[2] <= 0:
                raise ScenarioError(f"{key}.circle radius must be > 0, got {c[2]:g}")
            circles.append(c)
    return (np.vstack(cells) if cells else np.zeros((0, 2), np.int64),
            np.vstack(circles) if circles else np.zeros((0, 3)))


def _read_movers(items) -> list[DynamicObstacle]:
    if items is None:
        return []
    if not isinstance(items, list):
        raise ScenarioError("dynamic_obstacles must be a list of mappings")
    out = []
    for i, item in enumerate(items):
        key = f"dynamic_obstacles[{i}]"
        item = _mapping(item, key, ("radius", "waypoints", "speed", "loop", "phase", "start", "velocity", "at_border"))
        if "radius" not in item:
            raise ScenarioError(f"{key} is missing 'radius' (metres)")
        radius = _number(item["radius"], f"{key}.radius", positive=True)
        if "waypoints" in item:
            extra = {"start", "velocity", "at_border"} & set(item)
            if extra:
                raise ScenarioError(f"{key} mixes waypoints with {sorted(extra)}; use waypoints+speed or start+velocity")
            if "speed" not in item:
                raise ScenarioError(f"{key} has waypoints but no 'speed' (m/s)")
            loop = item.get("loop", True)
            if not isinstance(loop, bool):
                raise ScenarioError(f"{key}.loop must be true or false, got {loop!r}")
            out.append(DynamicObstacle(radius, waypoints=_points(item["waypoints"], f"{key}.waypoints"),
                                       speed=_number(item["speed"], f"{key}.speed", non_negative=True), loop=loop,
                                       phase=_number(item.get("phase", 0.0), f"{key}.phase", non_negative=True)))
        elif "start" in item:
            extra = {"speed", "loop", "phase"} & set(item)
            if extra:
                raise ScenarioError(f"{key} mixes start/velocity with {sorted(extra)}")
            if "velocity" not in item:
                raise ScenarioError(f"{key} has a start but no 'velocity' [vx, vy] (m/s)")
            mode = item.get("at_border", "bounce")
            if mode not in BORDER_MODES:
                raise ScenarioError(f"{key}.at_border must be one of {', '.join(BORDER_MODES)}, got {mode!r}")
            out.append(DynamicObstacle(radius, start=_vector(item["start"], f"{key}.start"),
                                       velocity=_vector(item["velocity"], f"{key}.velocity"), at_border=mode))
        else:
            raise ScenarioError(f"{key} needs 'waypoints' + 'speed' or 'start' + 'velocity'")
    return out


def _read_random(spec, key: str, allowed: dict[str, Any]) -> dict | None:
    if spec is None:
        return None
    spec = dict(_mapping(spec, key, tuple(allowed)))
    if "count" not in spec:
        raise ScenarioError(f"{key} is missing 'count'")
    out = dict(allowed)
    out.update(spec)
    c = out["count"]
    if isinstance(c, bool) or not isinstance(c, int) or c < 0:
        raise ScenarioError(f"{key}.count must be a non-negative integer, got {c!r}")
    for k, v in out.items():
        if k == "count":
            continue
        if isinstance(allowed[k], tuple):
            out[k] = _range(v, f"{key}.{k}")
        else:
            out[k] = _number(v, f"{key}.{k}", positive=k in ("size", "radius"), non_negative=True)
    return out


def scenario_from_dict(data: dict, base_dir: str | os.PathLike | None = None, source: str = "") -> Scenario:
    """Build a :class:`Scenario` from the parsed YAML mapping (``base_dir`` resolves a relative map path)."""
    if not isinstance(data, dict):
        raise ScenarioError(f"a scenario must be a mapping of keys ({', '.join(REQUIRED)} required), got {type(data).__name__}")
    unknown = sorted(set(map(str, data)) - set(TOP_KEYS))
    if unknown:
        raise ScenarioError(f"unknown scenario key(s) {unknown}; known: {', '.join(TOP_KEYS)}")
    missing = [k for k in REQUIRED if k not in data]
    if missing:
        raise ScenarioError(f"scenario is missing required key(s) {missing}; see DESIGN.md 'Scenario YAML'")
    res = data.get("resolution")
    if res is not None:
        res = _number(res, "resolution", positive=True)
    world = _read_map(data["map"], res, Path(base_dir) if base_dir is not None else None)
    robot_spec = data.get("robot", {}) or {}
    if not isinstance(robot_spec, dict):
        raise ScenarioError(f"robot must be a mapping with keys {', '.join(FILE_KEYS)}, got {robot_spec!r}")
    bad = sorted(set(map(str, robot_spec)) - set(FILE_KEYS))
    if bad:
        raise ScenarioError(f"unknown robot key(s) {bad}; known: {', '.join(FILE_KEYS)}")
    for k, v in robot_spec.items():
        if k == "model" or (k == "jerk_max" and v is None):
            continue
        _number(v, f"robot.{k}")
    try:
        robot = RobotSpec.from_dict(robot_spec)
    except OptplanError as exc:
        raise ScenarioError(f"robot: {exc}") from None
    start = _vector(data["start"], "start", (2, 3))
    if len(start) == 3:
        start[2] = math.radians(start[2])
    goal = _vector(data["goal"], "goal")
    cells, circles = _read_unknown(data.get("unknown_obstacles"), world)
    kwargs = {}
    for key in ("sensor_range", "dt", "time_limit", "goal_tolerance"):
        if key in data:
            kwargs[key] = _number(data[key], key, positive=True)
    if "timing_jitter" in data:
        kwargs["timing_jitter"] = _number(data["timing_jitter"], "timing_jitter", non_negative=True)
    for key in ("name", "description"):
        if key in data:
            if not isinstance(data[key], str):
                raise ScenarioError(f"{key} must be text, got {data[key]!r}")
            kwargs[key] = data[key].strip()
    random_obstacles = _read_random(data.get("random_obstacles"), "random_obstacles",
                                    {"count": 0, "size": 1.0, "keep_away": 2.0})
    random_dynamic = _read_random(data.get("random_dynamic"), "random_dynamic",
                                  {"count": 0, "radius": 0.3, "speed": (0.3, 0.6), "length": (3.0, 8.0),
                                   "keep_away": 3.0})
    return Scenario(world, robot, start, goal, unknown_cells=cells, unknown_circles=circles,
                    dynamic=_read_movers(data.get("dynamic_obstacles")), random_obstacles=random_obstacles,
                    random_dynamic=random_dynamic, source=source, **kwargs)


def scenario_names() -> list[str]:
    """Names of the scenarios shipped in ``optplan/data/scenarios``."""
    if not SCENARIOS_DIR.is_dir():
        return []
    return sorted(p.stem for p in SCENARIOS_DIR.glob("*.yaml"))


def load_scenario(path_or_dict) -> Scenario:
    """Read a scenario from a YAML file, a shipped scenario name, or an already parsed mapping.

    Lengths in the file are metres, times seconds, speeds m/s, and angles degrees
    (``start`` heading, ``w_max_deg``, ``alpha_max_deg``); the returned :class:`Scenario`
    holds radians.

    Raises:
        ScenarioError: the file is missing or malformed (the message names the key).
    """
    if isinstance(path_or_dict, Scenario):
        return path_or_dict
    if isinstance(path_or_dict, dict):
        return scenario_from_dict(path_or_dict)
    if not isinstance(path_or_dict, (str, os.PathLike)):
        raise ScenarioError(f"load_scenario needs a file path, a shipped name or a dict, got {type(path_or_dict).__name__}")
    p = Path(path_or_dict)
    if not p.is_file():
        shipped = SCENARIOS_DIR / f"{p.name}" if p.suffix == ".yaml" else SCENARIOS_DIR / f"{p.name}.yaml"
        if not shipped.is_file():
            raise ScenarioError(f"scenario file {path_or_dict} does not exist "
                                f"(shipped scenarios: {', '.join(scenario_names()) or 'none'})")
        p = shipped
    from .loaders import read_yaml

    data = read_yaml(p, "scenario file", ScenarioError)  # bounded: size, alias expansion, one-line errors
    if data is None:
        raise ScenarioError(f"scenario file {p} is empty")
    sc = scenario_from_dict(data, base_dir=p.parent, source=str(p))
    if not sc.name:
        sc.name = p.stem
    return sc
