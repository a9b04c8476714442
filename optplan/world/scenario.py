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
  the polygon already driven at ``t = 0``; ``delay`` (s, default 0) is how long the mover
  waits where it stands at ``t = 0`` before it drives. Waypoints that are all one point make
  a mover that stands there.
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
* ``random_dynamic: {count, radius, speed: [lo, hi], length: [lo, hi], keep_away, motion}``:
  ``count`` obstacles drawn from the seed, each driving along a straight
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
  then has to cross them together. ``motion: shuttle`` (default) drives each segment back
  and forth for the whole run, from a random phase; ``motion: once`` drives it once, from one
  end to the other, where the mover then stands (an end as far from the path as start and goal
  must be; drawn when both are), timed to cross the reference path
  when a robot driving that path from the start at a speed drawn between 30 % and 100 % of
  its ``v_max`` would get there (it waits at its first end until it must set off; a mover
  that would have had to start before ``t = 0`` starts part-way). This is how hou2024 §4.5 and
  li2023 §6.2 draw their movers: an origin and a path. ``ends_unseen: true`` (default false;
  ``motion: once`` only) lengthens both ends of the track, along it, until a robot on the
  reference path cannot sense a mover standing there (the disc beyond ``sensor_range`` +
  0.5 m of every path point): the robot only ever sees it drive, as a mover in the papers'
  uniform motion. A track whose longer ends are not free is drawn again. Without it a mover
  may stand beside the path in view and set off 0.2-1.6 s before the robot passes (or stop
  in its way): a jump in velocity that no prediction can foresee, and that a robot with the
  papers' accelerations cannot avoid once it sees it.

* Draws no map can hold are refused when the file is read: more random obstacles than
  the map has cells (at most 10,000) or blocks wider than the map, and more random
  movers than discs of their radius fit apart in the map (at most 1,000).

* ``timing_jitter``: seconds (default 0). Each moving obstacle of the file is advanced
  along its motion by a time drawn uniformly from ``[0, timing_jitter]`` with the
  run's seed, so seeded runs of a fixed scenario meet the movers at different moments.
* ``planner_params: {qp-dwa: {...}, mpc: {...}}``: options per local planner, as
  ``op.simulate(..., planner_params=...)`` takes them for that planner (the caller's win).
* ``global_options: {pop: 40, clearance: 0.3, ...}``: ``op.plan`` options of the global
  planner (the caller's ``global_options`` win). Both are checked where they are used,
  with the same named errors as in Python.

This module reads and checks the file (the :class:`Scenario` it builds is in
:mod:`optplan.world.scenario_model`, the movers in :mod:`optplan.world.movers`, the value
checks in :mod:`optplan.world.file_values`); the seed-dependent parts are realised by
:func:`optplan.worldgen.scenarios.realize` (``op.simulate`` calls it with its ``seed``
and its initial global path), so the same scenario file, seed and global path always
give the same world. Drawing them needs a planner, which this layer may not import.
Malformed files raise :class:`ScenarioError` naming the key and what to write instead.
"""
from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import MapFormatError, OptplanError, ScenarioError, named_with_hints
from .file_values import file_mapping, file_number, file_points, file_range, file_vector
from .movers import BORDER_MODES, DynamicObstacle
from .robot import FILE_KEYS, RobotSpec
from .scenario_model import MAX_RANDOM_MOVERS, MAX_RANDOM_OBSTACLES, Scenario, circle_distance, static_clearance, validate

# the public names of the scenario modules, importable from here as before the split
__all__ = ["BORDER_MODES", "MAX_RANDOM_MOVERS", "MAX_RANDOM_OBSTACLES", "REQUIRED", "SCENARIOS_DIR", "TOP_KEYS",
           "DynamicObstacle", "Scenario", "circle_distance", "load_scenario", "scenario_from_dict", "scenario_names",
           "static_clearance", "validate"]

SCENARIOS_DIR = Path(__file__).resolve().parent.parent / "data" / "scenarios"

TOP_KEYS = ("map", "resolution", "robot", "start", "goal", "sensor_range", "dt", "time_limit",
            "unknown_obstacles", "dynamic_obstacles", "name", "description", "goal_tolerance",
            "random_obstacles", "random_dynamic", "timing_jitter", "planner_params", "global_options")
REQUIRED = ("map", "start", "goal")


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
        item = file_mapping(item, key, ("cells", "circle"))
        if len(item) != 1:
            raise ScenarioError(f"{key} must have exactly one of 'cells' or 'circle'")
        if "cells" in item:
            pts = file_points(item["cells"], f"{key}.cells")
            if not np.all(pts == np.round(pts)):
                raise ScenarioError(f"{key}.cells must be integer cell indices [ix, iy]")
            huge = np.any(np.abs(pts) > 2 ** 31, axis=1)  # would overflow the integer cast below
            if huge.any():
                raise ScenarioError(f"{key}.cells: cell {pts[np.argmax(huge)].tolist()} is outside any map")
            cells.append(pts.astype(np.int64))
        else:
            c = file_vector(item["circle"], f"{key}.circle", (3,))
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
        item = file_mapping(item, key, ("radius", "waypoints", "speed", "loop", "phase", "delay", "start", "velocity",
                                            "at_border"))
        if "radius" not in item:
            raise ScenarioError(f"{key} is missing 'radius' (metres)")
        radius = file_number(item["radius"], f"{key}.radius", positive=True)
        if "waypoints" in item:
            extra = {"start", "velocity", "at_border"} & set(item)
            if extra:
                raise ScenarioError(f"{key} mixes waypoints with {sorted(extra)}; use waypoints+speed or start+velocity")
            if "speed" not in item:
                raise ScenarioError(f"{key} has waypoints but no 'speed' (m/s)")
            loop = item.get("loop", True)
            if not isinstance(loop, bool):
                raise ScenarioError(f"{key}.loop must be true or false, got {loop!r}")
            out.append(DynamicObstacle(radius, waypoints=file_points(item["waypoints"], f"{key}.waypoints"),
                                       speed=file_number(item["speed"], f"{key}.speed", non_negative=True), loop=loop,
                                       phase=file_number(item.get("phase", 0.0), f"{key}.phase", non_negative=True),
                                       delay=file_number(item.get("delay", 0.0), f"{key}.delay", non_negative=True)))
        elif "start" in item:
            extra = {"speed", "loop", "phase", "delay"} & set(item)
            if extra:
                raise ScenarioError(f"{key} mixes start/velocity with {sorted(extra)}")
            if "velocity" not in item:
                raise ScenarioError(f"{key} has a start but no 'velocity' [vx, vy] (m/s)")
            mode = item.get("at_border", "bounce")
            if mode not in BORDER_MODES:
                raise ScenarioError(f"{key}.at_border must be one of {', '.join(BORDER_MODES)}, got {mode!r}")
            out.append(DynamicObstacle(radius, start=file_vector(item["start"], f"{key}.start"),
                                       velocity=file_vector(item["velocity"], f"{key}.velocity"), at_border=mode))
        else:
            raise ScenarioError(f"{key} needs 'waypoints' + 'speed' or 'start' + 'velocity'")
    return out


MOVER_MOTIONS = ("shuttle", "once")  # random_dynamic.motion


def _read_random(spec, key: str, allowed: dict[str, Any]) -> dict | None:
    if spec is None:
        return None
    spec = dict(file_mapping(spec, key, tuple(allowed)))
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
        if k == "motion":
            if v not in MOVER_MOTIONS:
                raise ScenarioError(f"{key}.motion must be one of {', '.join(MOVER_MOTIONS)}, got {v!r}")
            continue
        if k == "ends_unseen":
            if not isinstance(v, bool):
                raise ScenarioError(f"{key}.ends_unseen must be true or false, got {v!r}")
            continue
        if isinstance(allowed[k], tuple):
            out[k] = file_range(v, f"{key}.{k}")
        else:
            out[k] = file_number(v, f"{key}.{k}", positive=k in ("size", "radius"), non_negative=True)
    return out


def scenario_from_dict(data: dict, base_dir: str | os.PathLike | None = None, source: str = "") -> Scenario:
    """Build a :class:`Scenario` from the parsed YAML mapping (``base_dir`` resolves a relative map path)."""
    if not isinstance(data, dict):
        raise ScenarioError(f"a scenario must be a mapping of keys ({', '.join(REQUIRED)} required), got {type(data).__name__}")
    unknown = sorted(set(map(str, data)) - set(TOP_KEYS))
    if unknown:
        raise ScenarioError(f"unknown scenario key(s) {named_with_hints(unknown, TOP_KEYS)}; known: {', '.join(TOP_KEYS)}")
    missing = [k for k in REQUIRED if k not in data]
    if missing:
        raise ScenarioError(f"scenario is missing required key(s) {missing}; see DESIGN.md 'Scenario YAML'")
    res = data.get("resolution")
    if res is not None:
        res = file_number(res, "resolution", positive=True)
    world = _read_map(data["map"], res, Path(base_dir) if base_dir is not None else None)
    robot_spec = data.get("robot", {}) or {}
    if not isinstance(robot_spec, dict):
        raise ScenarioError(f"robot must be a mapping with keys {', '.join(FILE_KEYS)}, got {robot_spec!r}")
    bad = sorted(set(map(str, robot_spec)) - set(FILE_KEYS))
    if bad:
        raise ScenarioError(f"unknown robot key(s) {named_with_hints(bad, FILE_KEYS)}; known: {', '.join(FILE_KEYS)}")
    for k, v in robot_spec.items():
        if k == "model" or (k == "jerk_max" and v is None):
            continue
        file_number(v, f"robot.{k}")
    try:
        robot = RobotSpec.from_dict(robot_spec)
    except OptplanError as exc:
        raise ScenarioError(f"robot: {exc}") from None
    start = file_vector(data["start"], "start", (2, 3))
    if len(start) == 3:
        start[2] = math.radians(start[2])
    goal = file_vector(data["goal"], "goal")
    cells, circles = _read_unknown(data.get("unknown_obstacles"), world)
    kwargs = {}
    for key in ("sensor_range", "dt", "time_limit", "goal_tolerance"):
        if key in data:
            kwargs[key] = file_number(data[key], key, positive=True)
    if "timing_jitter" in data:
        kwargs["timing_jitter"] = file_number(data["timing_jitter"], "timing_jitter", non_negative=True)
    for key in ("name", "description"):
        if key in data:
            if not isinstance(data[key], str):
                raise ScenarioError(f"{key} must be text, got {data[key]!r}")
            kwargs[key] = data[key].strip()
    random_obstacles = _read_random(data.get("random_obstacles"), "random_obstacles",
                                    {"count": 0, "size": 1.0, "keep_away": 2.0})
    random_dynamic = _read_random(data.get("random_dynamic"), "random_dynamic",
                                  {"count": 0, "radius": 0.3, "speed": (0.3, 0.6), "length": (3.0, 8.0),
                                   "keep_away": 3.0, "motion": "shuttle", "ends_unseen": False})
    kwargs["planner_params"] = _read_options(data.get("planner_params"), "planner_params", per_planner=True)
    kwargs["global_options"] = _read_options(data.get("global_options"), "global_options")
    return Scenario(world, robot, start, goal, unknown_cells=cells, unknown_circles=circles,
                    dynamic=_read_movers(data.get("dynamic_obstacles")), random_obstacles=random_obstacles,
                    random_dynamic=random_dynamic, source=source, **kwargs)


def _read_options(value, key: str, per_planner: bool = False) -> dict:
    """``planner_params: {qp-dwa: {...}, mpc: {...}}`` (options per local planner) or
    ``global_options: {pop: 30, ...}``: plain mappings of plain YAML data; what each option
    means is checked where it is used (``make_local_planner``, ``op.plan``), with the same
    named errors as in Python."""
    import json

    if value is None:
        return {}
    if not isinstance(value, dict) or not all(isinstance(k, str) for k in value):
        raise ScenarioError(f"{key} must be a mapping of {'local planner names to mappings' if per_planner else 'options'}"
                            f", got {value!r:.80}")
    if per_planner:
        for name, params in value.items():
            if not isinstance(params, dict) or not all(isinstance(k, str) for k in params):
                raise ScenarioError(f"{key}.{name} must be a mapping of the planner's options, got {params!r:.80}")
    try:
        json.dumps(value, allow_nan=False)
    except (TypeError, ValueError):
        raise ScenarioError(f"{key} must hold plain YAML data (numbers, text, lists, mappings; no .nan)") from None
    return {k: dict(v) if isinstance(v, dict) else v for k, v in value.items()}


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
    if os.path.lexists(p) and not p.is_file():
        from .files import regular_file

        regular_file(p, "scenario file", ScenarioError)   # says what it is (a FIFO, a device, a folder)
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
