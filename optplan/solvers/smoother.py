"""What every path smoother shares: its result type, arc-length resampling, the number of
points a path gets, and the check that refuses a seed no smoother can refine.

The CasADi smoother (:mod:`optplan.solvers.nlp`) and the QP corridor smoother
(:mod:`optplan.solvers.qp`) both use these; keeping them here means the QP smoother does
not import the NLP one (which calls the QP smoother to polish its result).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import math

import numpy as np

from ..world.polyline import resample_path


@dataclass
class WarmStart:
    """A solved smoothing NLP's primal-dual point, to start a later solve of the same size
    (made and used by the CasADi smoother, :func:`optplan.solvers.nlp.smooth_path`).

    Attributes:
        points: ``(N, 2)`` solution, metres.
        lam_x: multipliers of the variable bounds.
        lam_g: multipliers of the clearance constraints.
        neighbours: ``(2N-3, K)`` circle indices of each query point (circle worlds), else None.
        key: which NLP produced it; a warm start from another NLP is ignored.
    """

    points: np.ndarray
    lam_x: np.ndarray
    lam_g: np.ndarray
    neighbours: np.ndarray | None
    key: tuple


@dataclass
class SmoothResult:
    """Outcome of a smoother (:func:`optplan.solvers.nlp.smooth_path`, :func:`optplan.solvers.qp.smooth_path_qp`).

    Attributes:
        path: the refined path when ``success``, otherwise the seed unchanged, ``(N, 2)`` metres.
        success: the refined path passed ``validate_path``.
        message: empty on a first-try success, otherwise what happened (the reason for a fallback).
        solve_time_s: wall time of the whole call, seconds.
        iterations: solver iterations (IPOPT iterations / OSQP ADMM iterations, summed over rounds).
        objective: the smoothing objective ``J`` of ``path`` (NaN when not computed).
        rounds: solves made (neighbour-reassignment rounds / corridor rounds, over all attempts).
        warm: primal-dual point for warm-starting a later call (CasADi smoother only).
    """

    path: np.ndarray
    success: bool
    message: str
    solve_time_s: float
    iterations: int = 0
    objective: float = float("nan")
    rounds: int = 0
    warm: WarmStart | None = field(default=None, repr=False)


def resample(path: np.ndarray, n: int) -> np.ndarray:
    """``n`` points equally spaced by arc length along a polyline (ends kept)."""
    return resample_path(path, n)


# a long path gets enough points that no segment spans more than this many spacings
# (8 x a quarter cell = 2 cells on grids): with a fixed cap, a corner-to-corner path on a
# 256x256 map had 4-cell segments that cut the corners of its streets and failed
MAX_SEGMENT_SPACINGS = 8


def default_points(path: np.ndarray, spacing: float) -> int:
    """Number of points for a path: about one per ``spacing`` metres, rounded up to
    a multiple of 10 (so paths of similar length share one built NLP), at least 20.

    The cap is 100 points (the solve time grows with them) unless the path is so long
    that 100 points would make segments longer than ``MAX_SEGMENT_SPACINGS`` spacings;
    then it gets one point per that length instead, so the cap grows with the path,
    not with the map."""
    L = float(np.hypot(*np.diff(np.asarray(path, float), axis=0).T).sum())
    cap = max(100, 10 * math.ceil((L / (MAX_SEGMENT_SPACINGS * spacing) + 1) / 10))
    return int(np.clip(10 * np.ceil((L / spacing + 1) / 10), 20, cap))


def check_seed_ends(world, seed_path, clearance: float) -> tuple[np.ndarray, SmoothResult | None]:
    """The seed as an ``(M, 2)`` array, and a failed :class:`SmoothResult` saying why when it
    cannot be refined at all (bad shape, or start/goal not ``clearance`` metres clear);
    shared by every smoother so they refuse the same inputs with the same words."""
    P = np.asarray(seed_path, dtype=float)
    if P.ndim != 2 or P.shape[1] != 2 or len(P) < 2:
        return P, SmoothResult(P, False, "the seed must be an (M, 2) path with at least two points", 0.0)
    for p, what in ((P[0], "start"), (P[-1], "goal")):
        if not bool(world.is_free(p, clearance)):
            return P, SmoothResult(P, False, f"the {what} is not {clearance:g} m clear of obstacles", 0.0)
    return P, None
