"""Path metrics, vectorised over a batch of paths.

Every function takes ``paths`` of shape ``(N, 2)`` or ``(..., N, 2)`` (metres) and
returns one value per path.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

TURN_TOL_DEG = 1e-6  # heading changes below this are numerical noise, not turns


def _segments(paths: np.ndarray) -> np.ndarray:
    return np.diff(np.asarray(paths, dtype=float), axis=-2)


def path_length(paths) -> np.ndarray:
    """Sum of segment lengths, metres."""
    d = _segments(paths)
    return np.hypot(d[..., 0], d[..., 1]).sum(axis=-1)


def turn_angles_deg(paths) -> np.ndarray:
    """Absolute heading change at each interior vertex, degrees, shape ``(..., N-2)``.

    Zero-length segments carry no heading: the change is measured between the
    neighbouring non-degenerate segments (a repeated point is not a turn).
    """
    d = _segments(paths)
    heading = np.arctan2(d[..., 1], d[..., 0])
    zero = (d[..., 0] == 0) & (d[..., 1] == 0)
    if np.any(zero):
        # carry the previous heading forward over repeated points; repeats before the first
        # real segment take that segment's heading (a repeated start is not a turn either)
        n = heading.shape[-1]
        ar = np.broadcast_to(np.arange(n), heading.shape)
        idx = np.maximum.accumulate(np.where(~zero, ar, -1), axis=-1)
        first = np.where(~zero, ar, n).min(axis=-1, keepdims=True)
        idx = np.where(idx < 0, np.minimum(first, n - 1), idx)
        heading = np.take_along_axis(heading, idx, axis=-1)
    turn = np.diff(heading, axis=-1)
    turn = (turn + np.pi) % (2 * np.pi) - np.pi
    return np.abs(np.degrees(turn))


def total_turn_deg(paths) -> np.ndarray:
    """Sum of absolute heading changes, degrees."""
    return turn_angles_deg(paths).sum(axis=-1)


def n_turns(paths, tol_deg: float = TURN_TOL_DEG) -> np.ndarray:
    """Number of interior vertices where the heading changes by more than ``tol_deg``."""
    return (turn_angles_deg(paths) > tol_deg).sum(axis=-1)


def max_curvature(paths) -> np.ndarray:
    """Largest discrete (Menger) curvature over consecutive point triples, 1/metres.

    For a triple (a, b, c) it is the inverse radius of the circle through them,
    ``4 * area / (|ab| |bc| |ca|)``; 0 for paths with fewer than three points.
    A repeated point gives no curvature (it is skipped).
    """
    p = np.asarray(paths, dtype=float)
    if p.shape[-2] < 3:
        return np.zeros(p.shape[:-2])
    a, b, c = p[..., :-2, :], p[..., 1:-1, :], p[..., 2:, :]
    ab, bc, ca = b - a, c - b, a - c
    cross = ab[..., 0] * bc[..., 1] - ab[..., 1] * bc[..., 0]
    denom = np.hypot(ab[..., 0], ab[..., 1]) * np.hypot(bc[..., 0], bc[..., 1]) * np.hypot(ca[..., 0], ca[..., 1])
    k = np.where(denom > 0, 2.0 * np.abs(cross) / np.where(denom > 0, denom, 1.0), 0.0)
    return k.max(axis=-1)


def min_clearance(world, path, samples_per_metre: float = 20.0, *, free=None) -> float:
    """Smallest clearance along a path (metres): the exact distance from its segments to
    the obstacles and the border when the world can measure it
    (``world.segments_clearance``: grids and circle worlds), <= 0 where the path enters
    an obstacle. Other worlds are sampled at vertices and ``samples_per_metre`` points
    per metre along every segment (an upper bound of the exact value).

    ``free`` (grids): the segment rule's verdict on ``path[i] -> path[i + 1]`` without
    clearance, as ``validate_path_segments(world, path)`` computed it; it is reused
    instead of running the rule again (the same value)."""
    P = np.asarray(path, dtype=float)
    if len(P) == 0:
        return float("nan")
    if len(P) == 1:
        return float(world.clearance(P).min())
    if free is not None and getattr(world, "is_grid", False):
        from .geometry import segments_clearance

        return float(segments_clearance(world, P[:-1], P[1:], free=free).min())
    if hasattr(world, "segments_clearance"):
        return float(world.segments_clearance(P[:-1], P[1:]).min())
    seg = np.diff(P, axis=0)
    lengths = np.hypot(seg[:, 0], seg[:, 1])
    counts = np.maximum(np.ceil(lengths * samples_per_metre).astype(int), 1)
    owner = np.repeat(np.arange(len(seg)), counts)
    t = (np.arange(owner.size) - np.repeat(np.cumsum(counts) - counts, counts)) / np.repeat(counts, counts)
    pts = np.vstack([P[owner] + t[:, None] * seg[owner], P[-1:]])
    return float(world.clearance(pts).min())


@dataclass(frozen=True)
class PathMetrics:
    """The metrics every result reports."""

    length: float
    turn_angle_deg: float
    n_turns: int
    min_clearance: float
    max_curvature: float


def path_metrics(world, path) -> PathMetrics:
    """All metrics of one ``(N, 2)`` path (metres, degrees, 1/metres)."""
    if world is not None:
        from .queries import check_world

        check_world(world)
    from ..checks import float_array

    P = float_array("path", path, "an (N, 2) array of points")
    if P.ndim != 2 or len(P) == 0:
        return PathMetrics(float("inf"), float("nan"), 0, float("nan"), float("nan"))
    return PathMetrics(
        float(path_length(P)),
        float(total_turn_deg(P)) if len(P) > 2 else 0.0,
        int(n_turns(P)) if len(P) > 2 else 0,
        min_clearance(world, P) if world is not None else float("nan"),
        float(max_curvature(P)),
    )
