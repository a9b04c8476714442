"""Polyline geometry every layer uses: arc-length resampling, densifying, point-segment
distances. Written once here; the exact collision rule lives in ``geometry.py``."""
from __future__ import annotations

import numpy as np


def resample_path(path: np.ndarray, n: int) -> np.ndarray:
    """``n`` points equally spaced by arc length along a polyline (ends kept)."""
    P = np.asarray(path, dtype=float)
    seg = np.hypot(*np.diff(P, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    if s[-1] == 0:
        return np.repeat(P[:1], n, axis=0)
    t = np.linspace(0.0, s[-1], n)
    return np.stack([np.interp(t, s, P[:, 0]), np.interp(t, s, P[:, 1])], axis=1)


def densify(polyline: np.ndarray, step: float) -> np.ndarray:
    """Points along a polyline no more than ``step`` apart (its vertices included)."""
    P = np.asarray(polyline, float)
    seg = np.hypot(*np.diff(P, axis=0).T)
    k = np.maximum(np.ceil(seg / step).astype(int), 1)
    owner = np.repeat(np.arange(len(seg)), k)
    frac = (np.arange(k.sum()) - np.repeat(np.cumsum(k) - k, k)) / np.repeat(k, k)
    return np.vstack([P[owner] + frac[:, None] * (P[owner + 1] - P[owner]), P[-1:]])


def point_segment_distances(points: np.ndarray, a, b) -> np.ndarray:
    """Distance (m) from each point ``(n, 2)`` to the one segment ``a``-``b``."""
    q = np.asarray(points, float).reshape(-1, 2)
    a, b = np.asarray(a, float), np.asarray(b, float)
    ab = b - a
    t = np.clip((q - a) @ ab / max(float(ab @ ab), 1e-12), 0.0, 1.0)
    return np.hypot(*(q - (a + t[:, None] * ab)).T)


def segment_point_distances(path: np.ndarray, points: np.ndarray) -> np.ndarray:
    """``(S, V)`` distances from every segment of a path ``(S + 1, 2)`` to every point ``(V, 2)``."""
    P = np.asarray(path, float)
    a, u = P[:-1, None, :], (P[1:] - P[:-1])[:, None, :]
    q = np.asarray(points, float)[None]
    t = np.clip(((q - a) * u).sum(-1) / np.maximum((u * u).sum(-1), 1e-12), 0, 1)
    e = q - a - t[..., None] * u
    return np.hypot(e[..., 0], e[..., 1])


def repeats_to_end(P: np.ndarray, goal: np.ndarray) -> np.ndarray:
    """Paths ``P`` ``(n, N, 2)`` ending at ``goal`` with every repeated point dropped and the
    paths padded back to ``N`` points with copies of the goal: zero-length segments only at
    the end, where they change no term (a repeat inside a path would hide its turn from
    the turn terms, which measure the angle between consecutive segments)."""
    n = len(P)
    # keep a point when it differs from the previous one, move the rest to the end
    keep = np.ones(P.shape[:2], bool)
    keep[:, 1:] = np.any(P[:, 1:] != P[:, :-1], axis=2)
    keep[:, -1] = True
    order = np.argsort(~keep, axis=1, kind="stable")
    P = np.take_along_axis(P, order[..., None], axis=1)
    count = keep.sum(axis=1)
    tail = np.arange(P.shape[1])[None, :] >= count[:, None]
    P[tail] = np.broadcast_to(goal, (n, P.shape[1], 2))[tail]
    # the goal kept last: the sorted goal point is the last kept one already
    return P
