"""Occupancy grid maps.

Convention (DESIGN.md): ``occ[iy, ix]`` is ``True`` for a blocked cell, ``iy``
grows upwards, cell ``(ix, iy)`` covers ``[ix, ix+1) x [iy, iy+1)`` times the
resolution from ``origin`` (the bottom-left corner of the map). Everything
outside the map counts as blocked.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar
from functools import cached_property

import numpy as np

from ..errors import InfeasibleQueryError, MapFormatError, ParameterError


MAX_GRID_CELLS = 50_000_000  # about 7000 x 7000; the loaders refuse larger files before reading them
MAX_EXTENT_M = 1e9
# a grid coordinate within this many cells of a multiple of 1/2 (a grid line or a cell's
# mid-line) is snapped onto it where metres enter the grid (GridMap.to_grid): corners and
# centres computed in metres as ``origin + k * resolution`` come back exactly, so no exact
# test depends on the resolution or the origin (DESIGN.md, "Conventions")
SNAP_CELLS = 1e-9


def _finite(value, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ParameterError(f"{what} must be a finite number of metres, got {value!r}")
    v = float(value)
    if not np.isfinite(v):
        raise ParameterError(f"{what} must be a finite number of metres, got {value!r}")
    return v


@dataclass(eq=False)
class GridMap:
    """A 2-D occupancy grid.

    Args:
        occ: boolean (or 0/1) array of shape ``(height, width)``; ``occ[iy, ix]``
            is blocked, row 0 is the *bottom* row.
        resolution: cell side length in metres.
        origin: world coordinates ``(x, y)`` of the bottom-left map corner, metres.
        name: free text used in tables and plots.
    """

    occ: np.ndarray
    resolution: float = 1.0
    origin: tuple[float, float] = (0.0, 0.0)
    name: str = ""
    _cache: dict = field(default_factory=dict, repr=False)
    is_grid: ClassVar[bool] = True   # the World protocol (optplan.world.protocol)

    def __post_init__(self) -> None:
        try:
            occ = np.asarray(self.occ)
        except (TypeError, ValueError):
            raise MapFormatError("occupancy must be a rectangular 2-D array of 0/1 or booleans") from None
        if occ.ndim != 2 or occ.shape[0] == 0 or occ.shape[1] == 0:
            raise MapFormatError(f"occupancy must be a non-empty 2-D array, got shape {occ.shape}")
        if occ.size > MAX_GRID_CELLS:
            raise MapFormatError(f"a map of {occ.shape[0]} x {occ.shape[1]} cells exceeds the bound of "
                                 f"{MAX_GRID_CELLS} cells (a planner needs ~100 bytes per cell)")
        if occ.dtype != bool:
            if occ.dtype.kind not in "iuf" or not np.all(np.isin(occ, (0, 1))):
                raise MapFormatError("occupancy values must be 0 (free) or 1 (blocked)")
            occ = occ.astype(bool)
        # a copy: the map is read-only, the caller's array stays as it was
        self.occ = np.array(occ, dtype=bool, order="C", copy=True)
        self.occ.setflags(write=False)
        res = _finite(self.resolution, "resolution")
        if res <= 0:
            raise ParameterError(f"resolution must be a positive finite number of metres, got {self.resolution!r}")
        self.resolution = res
        try:
            ox, oy = (_finite(v, "origin") for v in self.origin)
        except (TypeError, ValueError):
            raise ParameterError(f"origin must be two finite numbers (x, y) in metres, got {self.origin!r}") from None
        self.origin = (ox, oy)
        # float64 keeps ~1e-6 m steps only below ~9e9 m: a larger world cannot be checked exactly
        extent = max(abs(ox), abs(oy)) + max(occ.shape) * res
        if extent > MAX_EXTENT_M:
            raise ParameterError(f"the map reaches {extent:.3g} m from (0, 0); the bound is {MAX_EXTENT_M:.0e} m "
                                 "(beyond it float64 coordinates lose micrometre precision); check resolution and origin")

    # ------------------------------------------------------------------ shape
    @classmethod
    def from_rows(cls, rows, resolution: float = 1.0, origin=(0.0, 0.0), name: str = "") -> "GridMap":
        """Build from rows written top row first (image convention, as in map files)."""
        try:
            arr = np.asarray(rows)
        except (TypeError, ValueError):
            arr = np.zeros(0)
        if arr.ndim != 2:
            raise MapFormatError("rows must form a 2-D 0/1 matrix with equal-length rows")
        return cls(arr[::-1].copy(), resolution, origin, name)

    def to_rows(self) -> np.ndarray:
        """0/1 ``uint8`` matrix with the top row first (the file convention)."""
        return self.occ[::-1].astype(np.uint8)

    @property
    def width(self) -> int:
        """Number of columns."""
        return int(self.occ.shape[1])

    @property
    def height(self) -> int:
        """Number of rows."""
        return int(self.occ.shape[0])

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` of the map in metres."""
        ox, oy = self.origin
        return (ox, oy, ox + self.width * self.resolution, oy + self.height * self.resolution)

    @cached_property
    def free_fraction(self) -> float:
        """Fraction of free cells."""
        return float(1.0 - self.occ.mean())

    # ----------------------------------------------------------- coordinates
    @cached_property
    def snap_tolerance(self) -> float:
        """Grid units within which :meth:`to_grid` snaps a coordinate to a multiple of 1/2:
        :data:`SNAP_CELLS`, or the rounding of metres far from (0, 0) (a UTM origin) where
        that is larger."""
        reach = max(abs(self.origin[0]), abs(self.origin[1])) + max(self.occ.shape) * self.resolution
        return max(SNAP_CELLS, 16.0 * np.finfo(float).eps * reach / self.resolution)

    def to_grid(self, points) -> np.ndarray:
        """World metres -> continuous grid units (cell ``(ix, iy)`` spans ``[ix, ix+1)``).

        The one place where metres enter the exact geometry: a coordinate within
        :attr:`snap_tolerance` of a grid line or a cell's mid-line is put on it, so a corner
        or a centre given in metres is the same lattice point at every resolution and origin.
        """
        g = (np.asarray(points, dtype=float) - np.asarray(self.origin)) / self.resolution
        half = np.round(2.0 * g) / 2.0
        return np.where(np.abs(g - half) <= self.snap_tolerance, half, g)

    def point_to_grid(self, x: float, y: float) -> tuple[float, float]:
        """:meth:`to_grid` of one point on Python floats (numpy scalars cost more than a
        small search): the same snapping, the same numbers."""
        tol = self.snap_tolerance
        out = []
        for v, o in ((x, self.origin[0]), (y, self.origin[1])):
            g = (float(v) - o) / self.resolution
            half = round(2.0 * g) / 2.0
            out.append(half if abs(g - half) <= tol else g)
        return out[0], out[1]

    def to_world(self, grid_points) -> np.ndarray:
        """Continuous grid units -> world metres."""
        g = np.asarray(grid_points, dtype=float)
        return g * self.resolution + np.asarray(self.origin)

    def cell_of(self, points) -> np.ndarray:
        """Integer cell indices ``(ix, iy)`` containing each point (may lie outside the map)."""
        return np.floor(self.to_grid(points)).astype(np.int64)

    def cell_center(self, cells) -> np.ndarray:
        """World coordinates of the centres of cells ``(ix, iy)``."""
        return self.to_world(np.asarray(cells, dtype=float) + 0.5)

    def in_map(self, cells) -> np.ndarray:
        """Whether integer cells ``(..., 2)`` lie inside the map."""
        c = np.asarray(cells)
        return (c[..., 0] >= 0) & (c[..., 0] < self.width) & (c[..., 1] >= 0) & (c[..., 1] < self.height)

    def blocked_cells(self, cells) -> np.ndarray:
        """Whether integer cells are blocked; cells outside the map are blocked."""
        c = np.asarray(cells, dtype=np.int64)
        inside = self.in_map(c)
        out = np.ones(c.shape[:-1], dtype=bool)
        out[inside] = self.occ[c[..., 1][inside], c[..., 0][inside]]
        return out

    @cached_property
    def padded(self) -> np.ndarray:
        """Occupancy with a one-cell blocked frame: ``padded[iy+1, ix+1] == occ[iy, ix]``."""
        return np.pad(self.occ, 1, constant_values=True)

    # ------------------------------------------------------------- queries
    def is_free(self, points, clearance: float = 0.0) -> np.ndarray:
        """Whether each point is at least ``clearance`` metres from every blocked cell.

        With ``clearance == 0`` a point is free when it is not in the interior of a
        blocked cell (points on the boundary between a free and a blocked cell are
        free; points inside the map only). Shape ``(..., 2)`` in, ``(...)`` out.
        """
        from .geometry import points_free

        return points_free(self, points, clearance)

    def clearance(self, points) -> np.ndarray:
        """Signed Euclidean distance (metres) from each point to the blocked region.

        Positive in free space, negative inside obstacles (depth to free space);
        the outside of the map counts as blocked.
        """
        from .geometry import grid_clearance

        return grid_clearance(self, points)

    def segments_free(self, a, b, clearance: float = 0.0) -> np.ndarray:
        """Exact segment rule of DESIGN.md for many segments ``a[i] -> b[i]`` at once."""
        from .geometry import segments_free

        return segments_free(self, a, b, clearance)

    def segments_clearance(self, a, b) -> np.ndarray:
        """Exact distance (metres) from each segment ``a[i] -> b[i]`` to blocked cells and
        the border (<= 0 for a segment that breaks the rule); see
        :func:`optplan.world.geometry.segments_clearance`."""
        from .geometry import segments_clearance

        return segments_clearance(self, a, b)

    def cells_touched_by_discs(self, discs) -> np.ndarray:
        """``(height, width)`` mask of the cells that any disc ``(x, y, r)`` (rows, metres)
        reaches into (square-to-disc distance below ``r``)."""
        d = np.asarray(discs, dtype=float).reshape(-1, 3)
        touched = np.zeros(self.occ.shape, dtype=bool)
        if not len(d):
            return touched
        iy, ix = np.mgrid[0:self.height, 0:self.width]
        lo = self.to_world(np.stack([ix, iy], -1).reshape(-1, 2).astype(float))
        res = self.resolution
        gap = np.stack([np.maximum(np.maximum(lo[:, None, k] - d[None, :, k], d[None, :, k] - lo[:, None, k] - res), 0.0)
                        for k in (0, 1)], -1)
        return np.any(np.hypot(gap[..., 0], gap[..., 1]) < d[None, :, 2], axis=1).reshape(self.occ.shape)

    def inflate(self, margin: float) -> "GridMap":
        """A new map whose blocked cells also include every cell closer than ``margin``
        metres (square-to-square distance) to a blocked cell or the map border.

        This is the conservative cell-level inflation used by graph search with a
        clearance; the exact continuous rule is ``segments_free(..., clearance)``.
        """
        margin = float(margin)
        if not np.isfinite(margin) or margin < 0:
            raise ParameterError(f"margin must be a finite number >= 0 metres, got {margin!r}")
        if margin == 0:
            return self
        r = margin / self.resolution
        k = int(np.ceil(r))
        # offsets (dx, dy) whose square-to-square gap max(|d|-1, 0) is < r
        d = np.arange(-k, k + 1)
        gx = np.maximum(np.abs(d)[None, :] - 1, 0)
        gy = np.maximum(np.abs(d)[:, None] - 1, 0)
        kernel = (gx**2 + gy**2) < r**2
        from scipy.ndimage import binary_dilation

        padded = np.pad(self.occ, k + 1, constant_values=True)
        grown = binary_dilation(padded, structure=kernel)[k + 1 : -k - 1, k + 1 : -k - 1]
        return GridMap(grown, self.resolution, self.origin, f"{self.name}+{margin:g}m")

    def check_query_point(self, point, what: str, clearance: float = 0.0) -> np.ndarray:
        """Validate a start/goal point, raising InfeasibleQueryError with a helpful message."""
        p = np.asarray(point, dtype=float).reshape(-1)
        if p.shape != (2,) or not np.all(np.isfinite(p)):
            raise InfeasibleQueryError(f"{what} must be two finite numbers (x, y) in metres, got {point!r}")
        xmin, ymin, xmax, ymax = self.bounds
        if not (xmin <= p[0] <= xmax and ymin <= p[1] <= ymax):
            raise InfeasibleQueryError(
                f"{what} ({p[0]:g}, {p[1]:g}) is outside the map, whose bounds are "
                f"x in [{xmin:g}, {xmax:g}], y in [{ymin:g}, {ymax:g}] metres"
            )
        if not bool(self.is_free(p, clearance)):
            cell = self.cell_of(p)
            raise InfeasibleQueryError(
                f"{what} ({p[0]:g}, {p[1]:g}) lies in blocked cell (ix={cell[0]}, iy={cell[1]})"
                + (f" or within clearance {clearance:g} m of an obstacle" if clearance > 0 else "")
                + "; pick a free point"
            )
        return p

    def __repr__(self) -> str:  # compact: the matrix can be large
        return (f"GridMap({self.width}x{self.height}, resolution={self.resolution:g}, "
                f"origin={self.origin}, free={self.free_fraction:.1%}, name={self.name!r})")
