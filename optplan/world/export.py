"""Paths and trajectories written for other tools: CSV, JSON, GeoJSON and a ``nav_msgs/Path``-like YAML.

A *path* is an ``(N, 2)`` array of points in metres (start first). A *trajectory* is the
simulator's ``(T, 6)`` rows ``[t, x, y, theta, v, w]`` (seconds, metres, radians, m/s,
rad/s). Both are written as:

* ``.csv``: a header line, then one row per point (``x,y`` for a path; ``t,x,y,theta,v,w``
  for a trajectory), ``precision`` decimals (6 by default, a micrometre; ``precision=None``
  writes every digit, so a file read back gives the same numbers).
* ``.json``: ``{"frame_id", "columns", "points"}`` (a trajectory: ``"rows"``), numbers as
  Python's ``repr`` writes them, so a file read back gives the same numbers.
* ``.geojson``: one ``Feature`` whose geometry is the ``LineString`` of the points (a
  ``Point`` for a one-point path), in the map frame's metres; ``properties`` name the frame
  and say so (GeoJSON readers assume WGS84 degrees: give them the map frame as a local CRS),
  a trajectory's times and headings included.
* ``.yaml`` / ``.yml``: the fields of a ROS ``nav_msgs/Path`` message (``header`` with
  ``frame_id`` and ``stamp``, then ``poses``: ``geometry_msgs/PoseStamped`` with a
  position and a unit quaternion for the heading about z). A path has no time or heading
  of its own: each pose faces along the segment that leaves it (the last the one that
  arrives) and every stamp is 0; a trajectory's stamps are its times and its headings
  its ``theta``.
"""
from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from ..checks import file_path
from ..errors import ParameterError
from .files import written_whole

EXPORT_SUFFIXES = (".csv", ".yaml", ".yml", ".json", ".geojson")


def _checked_rows(rows, width: int, what: str) -> np.ndarray:
    try:
        a = np.asarray(rows, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"a {what} must be an array of numbers, got {type(rows).__name__}") from None
    if a.ndim != 2 or a.shape[1] != width or len(a) == 0:
        raise ParameterError(f"a {what} must be a non-empty array of {width} columns, got shape {a.shape}")
    if not np.isfinite(a).all():
        raise ParameterError(f"a {what} to export must hold finite numbers only")
    return a


def _check_frame(frame_id) -> None:
    if not isinstance(frame_id, str) or not frame_id.strip() or "\n" in frame_id:
        raise ParameterError(f"frame_id must be a one-line frame name such as 'map', got {frame_id!r:.60}")


def _target(file, kinds: str) -> Path:
    p = Path(file_path("file", file))
    if p.suffix.lower() not in EXPORT_SUFFIXES:
        raise ParameterError(f"cannot export {kinds} to {p.name}: use a .csv, .json, .geojson or .yaml file name")
    return p


def path_headings(path) -> np.ndarray:
    """Heading (radians) of each point of a path: the direction of the segment leaving it,
    the arriving one for the last point; a repeated point keeps the previous heading."""
    P = _checked_rows(path, 2, "path")
    if len(P) == 1:
        return np.zeros(1)
    d = np.diff(P, axis=0)
    moving = np.hypot(d[:, 0], d[:, 1]) > 0
    heading = np.arctan2(d[:, 1], d[:, 0])
    if moving.any():
        # carry the last real direction over repeated points (the first ones take the first)
        idx = np.maximum.accumulate(np.where(moving, np.arange(len(d)), -1))
        idx = np.where(idx < 0, np.argmax(moving), idx)
        heading = heading[idx]
    return np.append(heading, heading[-1])


def _write_csv(p: Path, header: str, rows: np.ndarray, precision: int | None = 6) -> Path:
    if precision is not None and (isinstance(precision, bool) or not isinstance(precision, int)
                                  or not 0 <= precision <= 17):
        raise ParameterError(f"precision must be a number of decimals in 0..17 or None (every digit), "
                             f"got {precision!r}")
    with written_whole(p) as tmp:
        np.savetxt(tmp, rows, delimiter=",", header=header, comments="",
                   fmt="%.17g" if precision is None else f"%.{precision}f")
    return p


def _write_json(p: Path, doc: dict) -> Path:
    import json

    with written_whole(p) as tmp:
        tmp.write_text(json.dumps(doc, allow_nan=False) + "\n")
    return p


def _geojson(xy: np.ndarray, frame_id: str, extra: dict) -> dict:
    coords = xy.tolist()
    geometry = {"type": "Point", "coordinates": coords[0]} if len(coords) == 1 else \
        {"type": "LineString", "coordinates": coords}
    return {"type": "Feature", "geometry": geometry,
            "properties": {"frame_id": frame_id, "units": "m",
                           "crs": f"the map frame {frame_id!r} in metres (not WGS84 degrees)", **extra}}


def _stamp(t: float) -> str:
    secs = math.floor(t)
    nsecs = min(int(round((t - secs) * 1e9)), 999_999_999)
    return f"{{secs: {secs}, nsecs: {nsecs}}}"


def _write_ros_path(p: Path, xy: np.ndarray, theta: np.ndarray, times: np.ndarray, frame_id: str) -> Path:
    if not isinstance(frame_id, str) or not frame_id or any(c in frame_id for c in ":{}[],#\n\"'"):
        raise ParameterError(f"frame_id must be a plain name such as 'map', got {frame_id!r}")
    qz, qw = np.sin(theta / 2.0), np.cos(theta / 2.0)
    lines = ["header:", "  seq: 0", f"  stamp: {_stamp(float(times[0]))}", f"  frame_id: {frame_id}", "poses:"]
    for i in range(len(xy)):  # one pose per point, written as text: the file is for other tools
        lines += [f"  - header: {{seq: {i}, stamp: {_stamp(float(times[i]))}, frame_id: {frame_id}}}",
                  "    pose:",
                  f"      position: {{x: {float(xy[i, 0])!r}, y: {float(xy[i, 1])!r}, z: 0.0}}",
                  f"      orientation: {{x: 0.0, y: 0.0, z: {float(qz[i])!r}, w: {float(qw[i])!r}}}"]
    with written_whole(p) as tmp:
        tmp.write_text("\n".join(lines) + "\n")
    return p


def export_path(path, file: str | os.PathLike, frame_id: str = "map", precision: int | None = 6) -> Path:
    """Write an ``(N, 2)`` path (metres) to ``file``: ``.csv`` (``x,y``, ``precision``
    decimals), ``.json`` (exact), ``.geojson`` (a LineString in the map frame) or ``.yaml``
    (a ``nav_msgs/Path``-like message in ``frame_id``). Returns the file written.

    Raises:
        ParameterError: not an (N, 2) finite array, or an unsupported file suffix.
    """
    p = _target(file, "a path")
    _check_frame(frame_id)
    P = _checked_rows(path, 2, "path")
    suffix = p.suffix.lower()
    if suffix == ".csv":
        return _write_csv(p, "x,y", P, precision)
    if suffix == ".json":
        return _write_json(p, {"frame_id": frame_id, "columns": ["x", "y"], "points": P.tolist()})
    if suffix == ".geojson":
        return _write_json(p, _geojson(P, frame_id, {"length_m": float(np.hypot(*np.diff(P, axis=0).T).sum())}))
    return _write_ros_path(p, P, path_headings(P), np.zeros(len(P)), frame_id)


def export_trajectory(trajectory, file: str | os.PathLike, frame_id: str = "map", precision: int | None = 6) -> Path:
    """Write a simulator trajectory (rows ``[t, x, y, theta, v, w]``) to ``file``: ``.csv``
    (all six columns, ``precision`` decimals), ``.json`` (exact rows), ``.geojson`` (the
    LineString of its positions, times and headings as properties) or ``.yaml`` (a
    ``nav_msgs/Path``-like message: stamps from ``t``, headings from ``theta``). Returns the
    file written.

    Raises:
        ParameterError: not a (T, 6) finite array, or an unsupported file suffix.
    """
    p = _target(file, "a trajectory")
    _check_frame(frame_id)
    T = _checked_rows(trajectory, 6, "trajectory")
    suffix = p.suffix.lower()
    if suffix == ".csv":
        return _write_csv(p, "t,x,y,theta,v,w", T, precision)
    if suffix == ".json":
        return _write_json(p, {"frame_id": frame_id, "columns": ["t", "x", "y", "theta", "v", "w"],
                               "rows": T.tolist()})
    if suffix == ".geojson":
        return _write_json(p, _geojson(T[:, 1:3], frame_id, {"t": T[:, 0].tolist(), "theta": T[:, 3].tolist()}))
    return _write_ros_path(p, T[:, 1:3], T[:, 3], T[:, 0], frame_id)


def read_path_csv(file: str | os.PathLike) -> np.ndarray:
    """Read back a path or trajectory CSV written by :func:`export_path` /
    :func:`export_trajectory` (the rows, without the header)."""
    return np.atleast_2d(np.loadtxt(Path(file), delimiter=",", skiprows=1))
