"""Sampled signed-distance fields for fast, smooth clearance queries in hot paths.

``validate_path`` and ``GridMap.clearance`` are exact but not cheap enough to call
for every sample of every individual at every iteration. Objective terms and the
CasADi refinement instead use a signed distance field sampled on a lattice
``subdiv`` times finer than the map and interpolated bilinearly; it is exact at
the lattice points (the exact ``grid_clearance``, found by a distance transform) and its error in
between is bounded by the lattice spacing. Decisions about feasibility are never
taken on it: results are always re-checked with the exact rule.

The refinement's cubic spline of the field (:func:`distance_spline`) is fitted whole on
small maps and chunk by chunk near the paths that read it on large ones
(:class:`ChunkFiller`), so a cold refinement's set-up grows with the path, not the map.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from .derived import DerivedStore

_DERIVED = DerivedStore("world.fields")  # this module's data derived from worlds


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
        # the arithmetic of (1-ty)((1-tx) v00 + tx v10) + ty((1-tx) v01 + tx v11), done in place
        # (a rollout batch is 24,000 points: fresh temporaries cost more than the arithmetic)
        fx = np.asarray(p[..., 0] - self.xs[0])  # 0-d for a single point: still writable
        fx /= h
        np.clip(fx, 0.0, len(self.xs) - 1.000001, out=fx)
        fy = np.asarray(p[..., 1] - self.ys[0])
        fy /= h
        np.clip(fy, 0.0, len(self.ys) - 1.000001, out=fy)
        k = fy.astype(np.int64)
        ix = fx.astype(np.int64)
        fx -= ix  # tx
        fy -= k   # ty
        tx, ty = fx, fy
        v = self.values.ravel()  # flat gathers: cheaper than 2-d fancy indexing, same values
        nx = self.values.shape[1]
        k *= nx
        k += ix
        lower = v[k]
        lower *= 1 - tx
        right = v[k + 1]
        right *= tx
        lower += right
        upper = v[k + nx]
        upper *= 1 - tx
        right = v[k + (nx + 1)]
        right *= tx
        upper += right
        lower *= 1 - ty
        upper *= ty
        lower += upper
        return lower[()]  # a scalar for a single point, as before


def check_field_memory(grid, subdiv: int = 4) -> None:
    """Refuse, before any work, a map whose sampled field cannot fit the memory budget: the
    lattice's coordinates, covers, transform indices and distances take ~120 bytes a lattice
    point while it is built (a 2000 x 2000 map at 4 points a cell: 7.7 GB)."""
    from ..checks import memory_budget

    memory_budget(f"the sampled distance field of a {grid.width} x {grid.height} map ({subdiv} points a cell; "
                  "penetration terms and the casadi smoother use it)",
                  120.0 * (grid.width * subdiv + 1) * (grid.height * subdiv + 1),
                  "plan without penetration terms (astar, visibility, encoding='general'), or on a crop of the map")


def grid_distance_field(grid, subdiv: int = 4) -> DistanceField:
    """The signed distance field of a GridMap on a lattice of ``subdiv`` points per cell
    (cached on the map); the values are :func:`lattice_clearance`'s."""
    key = ("sdf", int(subdiv))
    cached = _DERIVED.of(grid).get(key)
    if cached is not None:
        return cached
    check_field_memory(grid, subdiv)
    xmin, ymin, xmax, ymax = grid.bounds
    xs = np.linspace(xmin, xmax, grid.width * subdiv + 1)
    ys = np.linspace(ymin, ymax, grid.height * subdiv + 1)
    field = DistanceField(xs, ys, lattice_clearance(grid, xs, ys, int(subdiv)))
    _DERIVED.of(grid)[key] = field
    return field


def _closed_cover(occ: np.ndarray, subdiv: int) -> np.ndarray:
    """``cover[j, i]``: the lattice point ``(i, j) / subdiv`` (grid units) lies in the closed
    square of some cell marked in ``occ``. Point ``i`` is in the closure of the cells
    ``floor(i / subdiv)`` and ``ceil(i / subdiv) - 1`` along its axis (one cell off the
    grid lines, two on them)."""
    H, W = occ.shape
    i = np.arange(W * subdiv + 1)
    j = np.arange(H * subdiv + 1)
    cx = [np.clip(i // subdiv, 0, W - 1), np.clip(-(-i // subdiv) - 1, 0, W - 1)]
    cy = [np.clip(j // subdiv, 0, H - 1), np.clip(-(-j // subdiv) - 1, 0, H - 1)]
    cover = np.zeros((len(j), len(i)), dtype=bool)
    for a in cy:
        rows = occ[a]
        for b in cx:
            cover |= rows[:, b]
    return cover


def _nearest_in_cover(cover: np.ndarray, g: np.ndarray, subdiv: int) -> np.ndarray:
    """Distance (grid units) from every lattice point (grid coordinates ``g``, shape
    ``(ny, nx, 2)``) to the nearest lattice point of ``cover``; ``inf`` without any.

    The union of closed unit squares with corners on the lattice is nearest to a lattice
    point at a lattice point (clamping a lattice point to such a square gives one), so
    this is the exact distance to the squares. The Euclidean distance transform finds
    that point; the distance is measured from ``g`` as ``grid_clearance`` measures it."""
    from scipy.ndimage import distance_transform_edt

    if not cover.any():
        return np.full(cover.shape, np.inf)
    iy, ix = distance_transform_edt(~cover, return_distances=False, return_indices=True)
    return np.hypot(ix / subdiv - g[..., 0], iy / subdiv - g[..., 1])


def lattice_clearance(grid, xs: np.ndarray, ys: np.ndarray, subdiv: int) -> np.ndarray:
    """``grid.clearance`` (signed distance, metres) at the lattice ``xs`` x ``ys``
    (``values[iy, ix]``, ``subdiv`` points per cell, from the map's bounds), in time
    linear in the number of lattice points.

    It follows ``geometry.grid_clearance`` step by step (the same grid coordinates, the
    free test on the lattice, the same border and sign rules) but finds the nearest blocked
    (free) square of every point with one distance transform instead of a tree query
    per point: a 256x256 map's 4-per-cell lattice is a million points."""
    X, Y = np.meshgrid(xs, ys)
    p = np.stack([X, Y], axis=-1)
    g = grid.to_grid(p)
    border = np.minimum.reduce([g[..., 0], g[..., 1], grid.width - g[..., 0], grid.height - g[..., 1]])
    d = np.minimum(_nearest_in_cover(_closed_cover(grid.occ, subdiv), g, subdiv), border)
    inside_map = (g[..., 0] >= 0) & (g[..., 0] <= grid.width) & (g[..., 1] >= 0) & (g[..., 1] <= grid.height)
    # a point is free when it lies in the closure of a free cell (``points_free``); on the
    # lattice that is the free cells' closed cover
    free_cover = _closed_cover(~grid.occ, subdiv)
    in_blocked = ~free_cover & inside_map
    if np.any(in_blocked):
        depth = _nearest_in_cover(free_cover, g, subdiv)
        d[in_blocked] = -depth[in_blocked]
    outside = ~inside_map & (border < 0)
    d[outside] = border[outside]
    return d * grid.resolution


def _not_a_knot_system(n: int) -> np.ndarray:
    """Banded form (``scipy.linalg.solve_banded`` with ``(4, 4)``) of the ``(n + 2)``-square
    system whose solution gives the uniform cubic B-spline coefficients of the not-a-knot
    interpolant through ``n >= 5`` equally spaced values (padded with a zero at each end):
    row 0 and row ``n + 1`` ask for a continuous third derivative at the second and the
    second-to-last lattice point (the 4th difference of five coefficients is 0), rows
    ``1..n`` for ``(c[i] + 4 c[i+1] + c[i+2]) / 6 = v[i]``."""
    ab = np.zeros((9, n + 2))
    full = np.zeros((n + 2, n + 2))
    full[0, :5] = (1.0, -4.0, 6.0, -4.0, 1.0)
    full[-1, -5:] = (1.0, -4.0, 6.0, -4.0, 1.0)
    i = np.arange(n)
    full[i + 1, i] = full[i + 1, i + 2] = 1.0 / 6.0
    full[i + 1, i + 1] = 4.0 / 6.0
    for r, c in zip(*np.nonzero(full)):
        ab[4 + r - c, c] = full[r, c]
    return ab


def _uniform_coefficients(values: np.ndarray, axis: int) -> np.ndarray:
    """Coefficients along ``axis`` (``n`` values -> ``n + 2`` coefficients) of the uniform
    cubic B-spline that is the not-a-knot interpolant of ``values`` along that axis."""
    from scipy.linalg import solve_banded

    v = np.moveaxis(values, axis, 0)
    n = v.shape[0]
    rhs = np.zeros((n + 2,) + v.shape[1:])
    rhs[1:-1] = v
    return np.moveaxis(solve_banded((4, 4), _not_a_knot_system(n), rhs.reshape(n + 2, -1)).reshape(rhs.shape), 0, axis)


def _cubic_weights(t, m):
    """The four uniform cubic B-spline weights at the offsets ``t`` in ``[0, 1)`` of an
    interval (``m``: numpy or casadi, the operations are the same)."""
    s = 1 - t
    return (s * s * s / 6, (3 * t * t * t - 6 * t * t + 4) / 6, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6,
            t * t * t / 6)


# lattice squares per side of a strip tile (DistanceSpline.strip); a tile's block holds the
# (TILE + 3)^2 coefficients its squares read
TILE = 8


@dataclass(frozen=True)
class DistanceSpline:
    """The cubic not-a-knot spline through a :class:`DistanceField` (the function CasADi's
    ``interpolant('bspline')`` builds from the same data), as a uniform cubic B-spline.

    ``coeffs[jy, jx]`` (``(ny + 2, nx + 2)``) weigh the B-splines centred one lattice step
    before the lattice point ``(jx, jy)``; a value at ``(x, y)`` reads the 4 x 4
    coefficients of its lattice square. For CasADi the coefficients near a path are handed
    over as numbers (:meth:`strip`, a parameter of the NLP) and read by index
    (:meth:`symbolic`), so neither the NLP, nor its derivatives, nor its set-up grow with
    the map: a CasADi B-spline over the whole lattice took minutes to fit and seconds to
    differentiate on a 256x256 map.
    """

    x0: float
    y0: float
    h: float
    coeffs: np.ndarray
    # large maps: fills the coefficient chunks a read needs (ChunkFiller); None = all computed
    filler: "ChunkFiller | None" = None

    @property
    def tiles(self) -> tuple[int, int]:
        """Strip tiles along y and x: :data:`TILE` lattice squares a side."""
        ny, nx = self.coeffs.shape[0] - 3, self.coeffs.shape[1] - 3   # lattice squares
        return -(-ny // TILE), -(-nx // TILE)

    def _cells(self, qx, qy, m):
        ny, nx = self.coeffs.shape[0] - 3, self.coeffs.shape[1] - 3
        u, v = (qx - self.x0) / self.h, (qy - self.y0) / self.h
        # the lattice square of the point; outside the lattice, the edge square's cubic
        ix = m.fmin(m.fmax(m.floor(u), 0), nx - 1)
        iy = m.fmin(m.fmax(m.floor(v), 0), ny - 1)
        return ix, iy, u - ix, v - iy

    def __call__(self, points) -> np.ndarray:
        """Values at points ``(..., 2)`` (numpy)."""
        p = np.asarray(points, dtype=float)
        ix, iy, tx, ty = self._cells(p[..., 0], p[..., 1], _NumpyOps)
        ix, iy = ix.astype(np.int64), iy.astype(np.int64)
        if self.filler is not None:
            self.filler.ensure(iy.ravel() // TILE, ix.ravel() // TILE)
        wx, wy = _cubic_weights(tx, np), _cubic_weights(ty, np)
        C = self.coeffs
        return sum(wy[b] * sum(wx[a] * C[iy + b, ix + a] for a in range(4)) for b in range(4))

    def strip(self, path, radius: float, capacity: int | None = None) -> tuple[np.ndarray, int]:
        """The numbers :meth:`symbolic` reads for points within ``radius`` metres of the
        polyline ``path``: ``(parameters, blocks)``.

        ``parameters`` is one vector: for every tile (row-major over :attr:`tiles`) the
        offset of its block, then the blocks, each the ``(TILE + 3)^2`` coefficients of
        one tile that comes within ``radius`` of the path, and first a block whose
        coefficients are all ``radius`` (a B-spline with equal coefficients is that
        constant), which every other tile points to: away from the strip the distance
        reads as ``radius``, so the strip must hold every point the solver may reach.
        ``capacity`` pads to that many blocks (the NLP's parameter has a fixed size);
        ``blocks`` is the number needed (the capacity must be at least that)."""
        nty, ntx = self.tiles
        P = np.asarray(path, dtype=float).reshape(-1, 2)
        # tiles within radius of the path: sample the path at a quarter tile and take the
        # tiles whose box comes within radius + half a tile diagonal of a sample
        tile_m = TILE * self.h
        seg = np.diff(P, axis=0)
        L = np.hypot(seg[:, 0], seg[:, 1])
        k = np.maximum(np.ceil(L / (0.25 * tile_m)).astype(int), 1)
        own = np.repeat(np.arange(len(seg)), k)
        t = (np.arange(own.size) - np.repeat(np.cumsum(k) - k, k)) / np.repeat(k, k)
        S = np.vstack([P[own] + t[:, None] * seg[own], P[-1:]]) if len(seg) else P
        cx = self.x0 + (np.arange(ntx) + 0.5) * tile_m
        cy = self.y0 + (np.arange(nty) + 0.5) * tile_m
        reach = radius + 0.75 * tile_m
        near = np.zeros((nty, ntx), dtype=bool)
        for a in range(0, len(S), 256):
            q = S[a:a + 256]
            dx = np.abs(q[:, 0, None] - cx[None, :]) <= reach          # (m, ntx)
            dy = np.abs(q[:, 1, None] - cy[None, :]) <= reach          # (m, nty)
            near |= (dy[:, :, None] & dx[:, None, :]).any(axis=0)
        ty, tx = np.nonzero(near)
        if self.filler is not None:
            self.filler.ensure(ty, tx)
        blocks = len(ty) + 1
        cap = blocks if capacity is None else int(capacity)
        if cap < blocks:
            raise ValueError(f"strip needs {blocks} blocks, capacity {cap}")
        side = TILE + 3
        C = np.pad(self.coeffs, ((0, TILE), (0, TILE)))
        store = np.full((cap, side, side), float(radius))
        rows = ty[:, None] * TILE + np.arange(side)[None, :]
        cols = tx[:, None] * TILE + np.arange(side)[None, :]
        store[1:blocks] = C[rows[:, :, None], cols[:, None, :]]
        table = np.zeros(nty * ntx)
        table[ty * ntx + tx] = np.arange(1, blocks) * side * side
        return np.concatenate([table, store.ravel()]), blocks

    def symbolic(self, qx, qy, params):
        """Values at the CasADi column vectors ``qx``, ``qy`` (same length), a column,
        reading the coefficients from ``params`` (:meth:`strip`'s vector, symbolic). The
        tile and the lattice square enter as indices (no derivative), the weights as
        polynomials; inside the strip this is the spline, exactly."""
        import casadi as ca

        nty, ntx = self.tiles
        side = TILE + 3
        ix, iy, tx, ty = self._cells(qx, qy, ca)
        jx, jy = ca.floor(ix / TILE), ca.floor(iy / TILE)
        base = params[jy * ntx + jx] + nty * ntx + (iy - jy * TILE) * side + (ix - jx * TILE)
        wx, wy = _cubic_weights(tx, ca), _cubic_weights(ty, ca)
        return sum(wy[b] * sum(wx[a] * params[base + (b * side + a)] for a in range(4)) for b in range(4))


class _NumpyOps:
    """The three functions :meth:`DistanceSpline._cells` needs, numpy's."""

    fmin, fmax, floor = staticmethod(np.fmin), staticmethod(np.fmax), staticmethod(np.floor)


# lattices with more points than this (maps above about 128 x 128 cells at 4 points per cell)
# get their spline chunk by chunk, only where a path reads it (ChunkFiller); smaller ones
# are fitted whole, once, which costs less than 0.1 s and is shared by every later call
LOCAL_POINTS = 1 << 18
# a chunk is CHUNK_TILES x CHUNK_TILES strip tiles of coefficients
CHUNK_TILES = 8
# lattice points beyond a chunk that its fit reads: the cubic B-spline interpolant's
# dependence on a value decays as (2 - sqrt 3)^k = 0.27^k, so a chunk's coefficients are the
# whole-map fit's to about 2e-6 of the field's variation
FIT_MARGIN = 10
# a chunk's distances are exact up to this many cells and capped there (its crop of the map
# reaches that far): a local smoother needs the distance near obstacles, and the required
# clearance (plus the NLP's cushion) must stay below it
REACH_CELLS = 4


class ChunkFiller:
    """Computes a large map's :class:`DistanceSpline` coefficients chunk by chunk.

    A chunk's coefficients come from the not-a-knot fit of the exact lattice distances
    (:func:`lattice_clearance`, capped at :data:`REACH_CELLS` cells) on the chunk grown by
    :data:`FIT_MARGIN` lattice points, on a crop of the map grown by the reach. Each chunk
    depends on the map only (not on which path asked first), so results do not depend on the
    order of calls; the work is proportional to the area near the paths, not to the map.
    """

    def __init__(self, grid, subdiv: int, coeffs: np.ndarray) -> None:
        self.grid, self.subdiv, self.coeffs = grid, int(subdiv), coeffs
        self.size = CHUNK_TILES * TILE                      # coefficient rows / columns per chunk
        ny, nx = coeffs.shape
        self.done = np.zeros((-(-ny // self.size), -(-nx // self.size)), dtype=bool)

    def ensure(self, ty: np.ndarray, tx: np.ndarray) -> None:
        """Compute every chunk that the tiles ``(ty, tx)`` read (a tile reads ``TILE + 3``
        coefficients a side, so it can reach into the next chunk)."""
        ty, tx = np.asarray(ty, np.int64).ravel(), np.asarray(tx, np.int64).ravel()
        if not len(ty):
            return
        last = np.array(self.done.shape) - 1
        lo_y, hi_y = np.minimum(ty * TILE // self.size, last[0]), np.minimum((ty * TILE + TILE + 2) // self.size, last[0])
        lo_x, hi_x = np.minimum(tx * TILE // self.size, last[1]), np.minimum((tx * TILE + TILE + 2) // self.size, last[1])
        need = np.zeros_like(self.done)
        for cy in (lo_y, hi_y):
            for cx in (lo_x, hi_x):
                need[cy, cx] = True
        for a, b in zip(*np.nonzero(need & ~self.done)):  # a loop over chunks (few), each vectorised
            self._fill(int(a), int(b))
            self.done[a, b] = True

    def _fill(self, a: int, b: int) -> None:
        grid, m, S = self.grid, self.subdiv, self.size
        ny, nx = self.coeffs.shape
        r0, r1 = a * S, min((a + 1) * S, ny)
        c0, c1 = b * S, min((b + 1) * S, nx)
        # lattice points the fit reads (coefficient j belongs to lattice point j - 1)
        ya, yb = max(r0 - 1 - FIT_MARGIN, 0), min(r1 - 1 + FIT_MARGIN, ny - 2)
        xa, xb = max(c0 - 1 - FIT_MARGIN, 0), min(c1 - 1 + FIT_MARGIN, nx - 2)
        # the crop of cells whose lattice covers those points, grown by the reach
        R = REACH_CELLS
        gy0, gy1 = max(ya // m - R, 0), min(-(-yb // m) + R, grid.height)
        gx0, gx1 = max(xa // m - R, 0), min(-(-xb // m) + R, grid.width)
        from .grid import GridMap

        h = grid.resolution
        crop = GridMap(grid.occ[gy0:gy1, gx0:gx1], h, (grid.origin[0] + gx0 * h, grid.origin[1] + gy0 * h))
        xmin, ymin, xmax, ymax = crop.bounds
        xs = np.linspace(xmin, xmax, crop.width * m + 1)
        ys = np.linspace(ymin, ymax, crop.height * m + 1)
        v = lattice_clearance(crop, xs, ys, m)[ya - gy0 * m:yb - gy0 * m, xa - gx0 * m:xb - gx0 * m]
        v = np.clip(v, -R * h, R * h)  # beyond the reach the crop cannot tell
        c = _uniform_coefficients(_uniform_coefficients(v, 1), 0)       # window coefficient k = global ya + k
        self.coeffs[r0:r1, c0:c1] = c[r0 - ya:r1 - ya, c0 - xa:c1 - xa]


def distance_spline(grid, subdiv: int = 4) -> DistanceSpline:
    """The :class:`DistanceSpline` of the grid's :func:`grid_distance_field` (cached on the
    map). Its coefficients come from banded solves, one axis at a time: time linear in
    the lattice. Lattices above :data:`LOCAL_POINTS` points are fitted chunk by chunk as
    paths read them (:class:`ChunkFiller`): the set-up of a refinement is then local to
    its path, not to the map."""
    key = ("sdf_spline", int(subdiv))
    spline = _DERIVED.of(grid).get(key)
    if spline is None:
        nyp, nxp = grid.height * subdiv + 1, grid.width * subdiv + 1
        xmin, ymin, xmax, ymax = grid.bounds
        if nyp * nxp <= LOCAL_POINTS:
            f = grid_distance_field(grid, subdiv)
            coeffs = _uniform_coefficients(_uniform_coefficients(f.values, 1), 0)
            spline = DistanceSpline(float(f.xs[0]), float(f.ys[0]), f.spacing, coeffs)
        else:
            coeffs = np.zeros((nyp + 2, nxp + 2))
            h = float(np.linspace(xmin, xmax, nxp)[1] - xmin)
            spline = DistanceSpline(float(xmin), float(ymin), h, coeffs, ChunkFiller(grid, subdiv, coeffs))
        _DERIVED.of(grid)[key] = spline
    return spline


def distance_function(world, subdiv: int = 4):
    """A vectorised ``points -> signed distance`` callable for any world: the sampled
    field for grids, the analytic distance for circle worlds."""
    if world.is_grid:
        return grid_distance_field(world, subdiv)
    return world.clearance
