"""Sampled signed-distance fields for fast, smooth clearance queries in hot paths.

``validate_path`` and ``GridMap.clearance`` are exact but not cheap enough to call
for every sample of every individual at every iteration. Objective terms and the
CasADi refinement instead use a signed distance field sampled on a lattice
``subdiv`` times finer than the map and interpolated bilinearly; it is exact at
the lattice points (computed with the exact ``grid_clearance``) and its error in
between is bounded by the lattice spacing. Decisions about feasibility are never
taken on it: results are always re-checked with the exact rule.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class DistanceField:
    """Signed distance (metres) sampled at ``xs`` x ``ys`` (``values[iy, ix]``)."""

    xs: np.ndarray
    ys: np.ndarray
    values: np.ndarray

    @property
    def spacing(self) -> float:
        return float(self.xs[1] - self.xs[0])

    def __call__(self, points) -> np.ndarray:
        """Bilinear interpolation at points ``(..., 2)``; clamped outside the lattice."""
        p = np.asarray(points, dtype=float)
        h = self.spacing
        fx = np.clip((p[..., 0] - self.xs[0]) / h, 0.0, len(self.xs) - 1.000001)
        fy = np.clip((p[..., 1] - self.ys[0]) / h, 0.0, len(self.ys) - 1.000001)
        ix, iy = fx.astype(np.int64), fy.astype(np.int64)
        tx, ty = fx - ix, fy - iy
        v = self.values
        return ((1 - ty) * ((1 - tx) * v[iy, ix] + tx * v[iy, ix + 1])
                + ty * ((1 - tx) * v[iy + 1, ix] + tx * v[iy + 1, ix + 1]))


def grid_distance_field(grid, subdiv: int = 4) -> DistanceField:
    """The signed distance field of a GridMap on a lattice of ``subdiv`` points per cell
    (cached on the map)."""
    key = ("sdf", int(subdiv))
    cached = grid._cache.get(key)
    if cached is not None:
        return cached
    xmin, ymin, xmax, ymax = grid.bounds
    n_x = grid.width * subdiv + 1
    n_y = grid.height * subdiv + 1
    xs = np.linspace(xmin, xmax, n_x)
    ys = np.linspace(ymin, ymax, n_y)
    X, Y = np.meshgrid(xs, ys)
    values = grid.clearance(np.stack([X, Y], axis=-1).reshape(-1, 2)).reshape(n_y, n_x)
    field = DistanceField(xs, ys, values)
    grid._cache[key] = field
    return field


def distance_function(world, subdiv: int = 4):
    """A vectorised ``points -> signed distance`` callable for any world: the sampled
    field for grids, the analytic distance for circle worlds."""
    if hasattr(world, "occ"):
        return grid_distance_field(world, subdiv)
    return world.clearance
