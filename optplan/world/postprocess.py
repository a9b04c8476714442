"""Path post-processing used by several papers.

* :func:`remove_collinear` — the "three points on one line" pass (li2023 §4.4 step 1).
* :func:`key_points` — li2023 §4.4 step 2: from the current key point, connect to
  the following turning points one by one; the point before the first blocked
  connection is a key point and becomes the new anchor.
* :func:`prune_direct` — chen2025 §4.3.1 direct-connection test: from each kept node,
  jump straight to the farthest later node it can see, dropping the nodes between.
* :func:`spline_resample` — yang2023 eq 3-4: a cubic spline through the waypoints,
  sampled densely, whose polyline length is the spline path length.

All visibility decisions use the one exact rule ``world.segments_free``.
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError


def _as_path(path) -> np.ndarray:
    P = np.asarray(path, dtype=float)
    if P.ndim != 2 or P.shape[1] != 2:
        raise ParameterError(f"a path must be an (N, 2) array, got shape {P.shape}")
    return P


def remove_duplicates(path) -> np.ndarray:
    """Drop consecutive repeated points."""
    P = _as_path(path)
    if len(P) < 2:
        return P.copy()
    keep = np.ones(len(P), dtype=bool)
    keep[1:] = np.any(np.diff(P, axis=0) != 0, axis=1)
    return P[keep]


def remove_collinear(path, tol: float = 1e-9) -> np.ndarray:
    """Remove interior points lying on the straight line through their neighbours
    and between them (li2023 §4.4 step 1). Only start, turning points and goal remain.

    ``tol`` bounds ``|cross| / (|u| |v|)`` (the sine of the turn) for "collinear".
    """
    P = remove_duplicates(path)
    if len(P) < 3:
        return P
    # one pass suffices: removing a straight-through point leaves the headings unchanged
    u = P[1:-1] - P[:-2]
    v = P[2:] - P[1:-1]
    cross = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    dot = np.einsum("ij,ij->i", u, v)
    norm = np.hypot(u[:, 0], u[:, 1]) * np.hypot(v[:, 0], v[:, 1])
    straight = (np.abs(cross) <= tol * norm) & (dot > 0)
    keep = np.concatenate([[True], ~straight, [True]])
    return P[keep]


def _walk(world, P: np.ndarray, clearance: float, next_from) -> np.ndarray:
    """Keep ``P[0]``, then repeatedly the point ``next_from(later, free, anchor)`` chooses
    from the indices after the anchor and whether each is visible from it (one batched query
    per anchor); never fewer than one step forward."""
    n = len(P)
    if n < 3:
        return P
    kept, anchor = [0], 0
    while anchor < n - 1:
        later = np.arange(anchor + 1, n)
        free = np.asarray(world.segments_free(np.repeat(P[anchor:anchor + 1], len(later), 0), P[later], clearance))
        anchor = max(int(next_from(later, free, anchor)), anchor + 1)
        kept.append(anchor)
    return P[kept]


def _before_first_blocked(later: np.ndarray, free: np.ndarray, anchor: int) -> int:
    blocked = np.flatnonzero(~free)
    # when the next point itself is not visible the walk keeps it: the path is invalid there
    return later[blocked[0]] - 1 if blocked.size else later[-1]


def _farthest_visible(later: np.ndarray, free: np.ndarray, anchor: int) -> int:
    return later[free].max(initial=anchor)


def key_points(world, path, clearance: float = 0.0) -> np.ndarray:
    """Key turning points of a path (li2023 §4.4).

    After :func:`remove_collinear`, start from ``P1`` and test ``P1 P3``, ``P1 P4``, ...
    in order; at the first blocked connection ``P1 Pm``, ``P(m-1)`` is a key point
    and becomes the new anchor. The returned path keeps start and goal.
    """
    return _walk(world, remove_collinear(path), clearance, _before_first_blocked)


def prune_direct(world, path, clearance: float = 0.0) -> np.ndarray:
    """Direct-connection pruning (chen2025 §4.3.1): from each kept node, connect to
    the farthest later node with a free straight segment and drop those between."""
    return _walk(world, remove_duplicates(path), clearance, _farthest_visible)


def spline_resample(waypoints, n_points: int = 100, parametrisation: str = "uniform") -> np.ndarray:
    """Cubic spline through ``waypoints`` sampled at ``n_points`` (yang2023 eq 3-4).

    Args:
        waypoints: ``(m, 2)`` points, start first, goal last (``m >= 2``).
        n_points: samples along the whole curve, ends included.
        parametrisation: ``"uniform"`` (knots equally spaced in [0, 1], as the
            common PSO path demos do) or ``"chord"`` (knots at cumulative chord length).

    Returns:
        ``(n_points, 2)`` polyline; its length approximates the spline length of eq 4.
    """
    from scipy.interpolate import CubicSpline

    W = remove_duplicates(waypoints)
    if n_points < 2:
        raise ParameterError(f"n_points must be >= 2, got {n_points}")
    if len(W) == 1:
        return np.repeat(W, n_points, axis=0)
    if parametrisation == "uniform":
        t = np.linspace(0.0, 1.0, len(W))
    elif parametrisation == "chord":
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(W, axis=0).T))])
        t = s / s[-1]
    else:
        raise ParameterError(f"parametrisation must be 'uniform' or 'chord', got {parametrisation!r}")
    if len(W) == 2:
        tt = np.linspace(0.0, 1.0, n_points)[:, None]
        return W[0] + tt * (W[1] - W[0])
    bc = "not-a-knot" if len(W) > 3 else "natural"
    spline = CubicSpline(t, W, axis=0, bc_type=bc)
    return spline(np.linspace(0.0, 1.0, n_points))
