"""Objective terms and constraint measures over a population of decoded paths.

Each function takes ``paths`` of shape ``(n, N, 2)`` (metres) and returns ``(n,)``.
They are written once and shared by every solver; each paper's fitness is a
weighted combination of them (see :mod:`optplan.formulations.presets`).
"""
from __future__ import annotations

import numpy as np

from ..world.fields import distance_function
from ..world.metrics import n_turns, path_length, turn_angles_deg


def length(paths: np.ndarray) -> np.ndarray:
    """Path length in metres (yang2023 eq 2, yuan2021 eq 10, chen2025 eq 32 second term)."""
    return path_length(paths)


# Turn terms are functions of the absolute heading changes at the interior
# vertices (degrees, ``(n, N-2)``); the ``*_of_angles`` forms let encodings that
# tabulate segment headings skip decoding the paths.

def heading_changes_deg(heading: np.ndarray) -> np.ndarray:
    """Absolute change between consecutive segment headings (radians in), degrees out,
    wrapped to [0, 180] (the same rule as ``optplan.world.metrics.turn_angles_deg``)."""
    turn = np.diff(heading, axis=-1)
    turn = (turn + np.pi) % (2 * np.pi) - np.pi
    return np.abs(np.degrees(turn))


def turn_angle_of_angles(ang_deg: np.ndarray) -> np.ndarray:
    """Sum of absolute heading changes in radians (li2023 eq 2, theta)."""
    return np.radians(ang_deg).sum(axis=-1)


def turn_count_of_angles(ang_deg: np.ndarray, tol_deg: float = 1e-6) -> np.ndarray:
    """Number of turning points (li2023 eq 2, the partial-derivative symbol)."""
    return (ang_deg > tol_deg).sum(axis=-1).astype(float)


def turn_cost_of_angles(ang_deg: np.ndarray) -> np.ndarray:
    """yuan2021 eq 12: ``m1 * pi/4 + m2 * pi/2`` for m1 turns of up to 45 degrees and
    m2 sharper turns. On the 8-connected grid this is exactly the paper's count of
    45- and 90-degree turns; off the grid each turn is charged to its class."""
    small = (ang_deg > 1e-6) & (ang_deg <= 45.0 + 1e-9)
    sharp = ang_deg > 45.0 + 1e-9
    return small.sum(axis=-1) * (np.pi / 4) + sharp.sum(axis=-1) * (np.pi / 2)


def turn_angle(paths: np.ndarray) -> np.ndarray:
    """Sum of absolute heading changes in radians (li2023 eq 2, theta)."""
    return turn_angle_of_angles(turn_angles_deg(paths))


def turn_count(paths: np.ndarray, tol_deg: float = 1e-6) -> np.ndarray:
    """Number of turning points (li2023 eq 2, the partial-derivative symbol)."""
    return n_turns(paths, tol_deg).astype(float)


def turn_cost_quantised(paths: np.ndarray) -> np.ndarray:
    """yuan2021 eq 12 on decoded paths (see :func:`turn_cost_of_angles`)."""
    return turn_cost_of_angles(turn_angles_deg(paths))


def collisions(world, paths: np.ndarray, clearance: float = 0.0) -> np.ndarray:
    """Number of segments that fail the exact segment rule (yuan2021 eq 11 m_ob,
    chen2025 eq 32 O)."""
    P = np.asarray(paths, dtype=float)
    n, N = P.shape[:2]
    ok = world.segments_free(P[:, :-1].reshape(-1, 2), P[:, 1:].reshape(-1, 2), clearance)
    return (~np.asarray(ok).reshape(n, N - 1)).sum(axis=1).astype(float)


def penetration(world, paths: np.ndarray, clearance: float = 0.0, samples_per_segment: int = 8,
                distance=None) -> np.ndarray:
    """Integral along the path of how far it is inside the clearance zone, metres^2.

    ``sum over samples of max(0, clearance - sd(p)) * ds`` with ``sd`` the signed
    distance field (exact for circles, sampled for grids): zero for clear paths,
    growing smoothly with depth and length of the intrusion, so it guides search
    where a collision count is flat.
    """
    P = np.asarray(paths, dtype=float)
    sd = distance if distance is not None else distance_function(world)
    k = int(samples_per_segment)
    t = (np.arange(k) + 0.5) / k
    a, b = P[:, :-1, None, :], P[:, 1:, None, :]
    pts = a + t[None, None, :, None] * (b - a)              # (n, N-1, k, 2)
    depth = np.maximum(clearance - sd(pts), 0.0)
    seg = np.hypot(*(P[:, 1:] - P[:, :-1]).transpose(2, 0, 1))  # (n, N-1)
    return (depth.mean(axis=2) * seg).sum(axis=1)
