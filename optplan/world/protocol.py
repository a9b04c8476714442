"""What every world offers the layers above it (``GridMap`` and ``CircleWorld`` both do).

Code above the world layer asks ``world.is_grid`` when it needs grid-only data
(``occ``, ``resolution``, cells) rather than probing attributes, and otherwise uses
only the members below, so a new kind of world is one class that implements them.
"""
from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np


@runtime_checkable
class World(Protocol):
    """The world protocol: bounds, exact free-space queries and query-point checks."""

    is_grid: bool
    name: str

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` in metres."""

    def is_free(self, points, clearance: float = 0.0) -> np.ndarray:
        """``(n,)`` True where a point is at least ``clearance`` from every obstacle."""

    def clearance(self, points) -> np.ndarray:
        """``(n,)`` distance of each point to the nearest obstacle (or border), metres."""

    def segments_free(self, a, b, clearance: float = 0.0) -> np.ndarray:
        """``(n,)`` True where segment ``a[i] -> b[i]`` keeps ``clearance`` (the exact rule)."""

    def check_query_point(self, point, what: str, clearance: float = 0.0) -> np.ndarray:
        """The point as a float array, or an InfeasibleQueryError saying why it cannot be used."""
