"""Exact geometry shared by every solver: the segment rule and ``validate_path``.

The rule (DESIGN.md, "Conventions"): a segment is free when it does not enter the
interior of any blocked cell (after inflating the blocked cells by the requested
clearance) and does not pass through a point where two blocked cells meet only
diagonally. The outside of the map is blocked, so segments must stay inside it.
A segment may run along an edge between a free and a blocked cell, but not along
an edge between two blocked cells.

Exactness: coordinates are converted to grid units. When every coordinate of a
query is a multiple of half a cell (cell centres and cell corners, which is what
graph search and the grid encodings produce), the test runs in int64 arithmetic
on doubled coordinates and is exact. Other coordinates use the same formulas in
float64, so decisions within ~1e-12 cells of a cell boundary follow rounding; the
test then errs on the blocked side near double corners (a path that passes
within 1e-9 cells of one is rejected).

With ``clearance > 0`` a segment must additionally keep a Euclidean distance of at
least ``clearance`` metres from every blocked cell and from the map border.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..checks import metres
from ..errors import ParameterError
from .derived import DerivedStore

_DERIVED = DerivedStore("world.geometry")  # this module's data derived from worlds

_VERTEX_EPS = 1e-9  # float mode: how close to a lattice vertex counts as "through it"
_INT_LIMIT = 1 << 24  # doubled coordinates beyond this fall back to float mode
# cells of segment length (|dx| + |dy| + 2 per segment) that one block of the segment rule
# visits: its work arrays hold about that many entries (~10 int64 arrays)
SPAN_BUDGET = 1_000_000


# --------------------------------------------------------------------------- helpers
def _as_points(points) -> np.ndarray:
    p = np.asarray(points, dtype=float)
    if p.shape[-1:] != (2,):
        raise ParameterError(f"points must have shape (..., 2), got {p.shape}")
    return p


def _check_clearance(clearance: float) -> float:
    return metres("clearance", clearance)


def _clamp(x, lo, hi):
    """``np.clip(x, lo, hi)`` as two ufuncs: np.clip's Python dispatch (a dtype-limits
    lookup on every call) cost a fifth of a small map's ``shortest_path``."""
    return np.minimum(np.maximum(x, lo), hi)


def _doubled_ints(*arrays: np.ndarray) -> tuple[np.ndarray, ...] | None:
    """Return ``2 * a`` as int64 for every array if all are exact half-integers, else None."""
    out = []
    for a in arrays:
        d = 2.0 * a
        if a.size and (np.abs(d).max() >= _INT_LIMIT or not np.array_equal(d, np.round(d))):
            return None
        out.append(d.astype(np.int64))
    return tuple(out)


def _expand(counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For counts ``[2, 0, 3]`` return owners ``[0,0,2,2,2]`` and offsets ``[0,1,0,1,2]``."""
    counts = np.maximum(counts, 0)
    owner = np.repeat(np.arange(counts.size), counts)
    starts = np.cumsum(counts) - counts
    offset = np.arange(owner.size) - starts[owner]
    return owner, offset


def _blocks(weights: np.ndarray, budget: float):
    """Consecutive ``(first, last)`` slices of items whose weights add up to at most
    ``budget`` (an item heavier than that forms a block of its own): the work arrays of
    one block then stay within a fixed size, whatever the number of items."""
    ends = np.cumsum(weights, dtype=float)
    first = 0
    while first < len(ends):
        base = ends[first - 1] if first else 0.0
        last = max(int(np.searchsorted(ends, base + budget, side="right")), first + 1)
        yield first, last
        first = last


def _floor_div(n, d, integer: bool):
    return n // d if integer else np.floor(n / d)


def _ceil_div(n, d, integer: bool):
    return -((-n) // d) if integer else np.ceil(n / d)


# ------------------------------------------------------------------ grid: points
def points_free(grid, points, clearance: float = 0.0) -> np.ndarray:
    """Whether points are free on ``grid`` (see :meth:`GridMap.is_free`)."""
    c = _check_clearance(clearance)
    p = _as_points(points)
    shape = p.shape[:-1]
    g = grid.to_grid(p.reshape(-1, 2))
    if c > 0:
        return (grid_clearance(grid, p.reshape(-1, 2)) >= c).reshape(shape)
    inside = (g[:, 0] >= 0) & (g[:, 0] <= grid.width) & (g[:, 1] >= 0) & (g[:, 1] <= grid.height)
    ok = np.isfinite(g).all(axis=1) & inside
    gx = np.where(ok, g[:, 0], 0.0)
    gy = np.where(ok, g[:, 1], 0.0)
    fx, fy = np.floor(gx), np.floor(gy)
    # a point on a grid line belongs to the closure of the cells on both sides
    xs = np.stack([fx, np.where(gx == fx, fx - 1, fx)], axis=1).astype(np.int64)
    ys = np.stack([fy, np.where(gy == fy, fy - 1, fy)], axis=1).astype(np.int64)
    pad = grid.padded
    any_free = np.zeros(len(g), dtype=bool)
    for i in range(2):
        for j in range(2):
            any_free |= ~pad[_clamp(ys[:, j] + 1, 0, grid.height + 1), _clamp(xs[:, i] + 1, 0, grid.width + 1)]
    return (ok & any_free).reshape(shape)


# --------------------------------------------------------------- grid: segments
def _column_prefix(occ_pad: np.ndarray) -> np.ndarray:
    """``cum[c, j] = number of blocked cells in padded column c below padded row j``."""
    return np.concatenate([np.zeros((occ_pad.shape[1], 1), np.int64),
                           np.cumsum(occ_pad.T, axis=1, dtype=np.int64)], axis=1)


def _segments_free_grid_units(occ_pad: np.ndarray, col_cum: np.ndarray, a: np.ndarray, b: np.ndarray, scale,
                              integer: bool) -> np.ndarray:
    """Core of the rule for segments with ``b.x != a.x`` (sorted so that a.x < b.x).

    ``occ_pad`` is the occupancy with a blocked one-cell frame and ``col_cum`` its
    column prefix sums (:func:`_column_prefix`); ``a``, ``b`` are in
    grid units times ``scale`` (1 for float mode, 2 for integer mode).
    Returns a boolean array: no blocked interior is entered, no edge between two
    blocked cells is followed, no double corner is passed through.
    """
    n = len(a)
    ok = np.ones(n, dtype=bool)
    if n == 0:
        return ok
    S = scale
    x0, y0, x1, y1 = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
    dx, dy = x1 - x0, y1 - y0  # dx > 0
    H, W = occ_pad.shape[0] - 2, occ_pad.shape[1] - 2

    def num(xv, seg):  # y(x) * dx, exact in integer mode
        return y0[seg] * dx[seg] + (xv - x0[seg]) * dy[seg]

    # ---- cells whose open interior the segment crosses, column by column
    k_first = _floor_div(x0, S, integer)
    k_last = _ceil_div(x1, S, integer) - 1
    seg, off = _expand((k_last - k_first + 1).astype(np.int64))
    k = k_first[seg] + off
    xa = np.maximum(x0[seg], k * S)
    xb = np.minimum(x1[seg], (k + 1) * S)
    if integer:
        na, nb = num(xa, seg), num(xb, seg)
        den = dx[seg] * S
    else:
        # float mode: a stretch that ends at the segment's end point takes that point's own
        # y, so a segment that stops exactly on a grid line is not pushed over it by rounding
        # (y0 * dx + (x1 - x0) * dy) / dx != y1 in floating point
        na = np.where(xa == x0[seg], y0[seg], y0[seg] + (xa - x0[seg]) * (dy[seg] / dx[seg]))
        nb = np.where(xb == x1[seg], y1[seg], y0[seg] + (xb - x0[seg]) * (dy[seg] / dx[seg]))
        den = np.ones_like(na)
    nlo, nhi = np.minimum(na, nb), np.maximum(na, nb)
    sloped = dy[seg] != 0
    if np.any(sloped):
        s_seg, s_k, s_lo, s_hi, s_den = seg[sloped], k[sloped], nlo[sloped], nhi[sloped], den[sloped]
        j_first = _clamp(_floor_div(s_lo, s_den, integer).astype(np.int64), -1, H)
        j_last = _clamp((_ceil_div(s_hi, s_den, integer) - 1).astype(np.int64), -1, H)
        # the rows crossed in one column form a run: count its blocked cells with
        # per-column prefix sums instead of visiting every cell
        col = _clamp(s_k.astype(np.int64) + 1, 0, W + 1)
        hit = (col_cum[col, j_last + 2] - col_cum[col, j_first + 1]) > 0
        ok[s_seg[hit]] = False
    flat = ~sloped
    if np.any(flat):
        f_seg, f_k = seg[flat], k[flat].astype(np.int64)
        yv = y0[f_seg]
        on_line = (yv % S) == 0
        row = _floor_div(yv, S, integer).astype(np.int64)
        # inside a row: that cell must be free; on a grid line: not both neighbours blocked
        bad = np.where(on_line, _blocked_at(occ_pad, f_k, row - 1) & _blocked_at(occ_pad, f_k, row),
                       _blocked_at(occ_pad, f_k, row))
        ok[f_seg[bad]] = False

    # ---- lattice vertices strictly inside the segment: no double corners
    v_first = _floor_div(x0, S, integer) + 1
    v_last = _ceil_div(x1, S, integer) - 1
    seg, off = _expand((v_last - v_first + 1).astype(np.int64))
    if seg.size:
        X = (v_first[seg] + off) * S
        nv = num(X, seg)
        den = dx[seg] * S
        if integer:
            on_vertex = (nv % den) == 0
            Y = nv // den
        else:
            q = nv / den
            Y = np.round(q)
            on_vertex = np.abs(q - Y) <= _VERTEX_EPS
        seg, X, Y = seg[on_vertex], (X[on_vertex] // S if integer else X[on_vertex] / S), Y[on_vertex]
        ok[seg[_double_corner(occ_pad, X.astype(np.int64), Y.astype(np.int64))]] = False
    return ok


def _blocked_at(occ_pad: np.ndarray, ix, iy) -> np.ndarray:
    """Whether cells ``(ix, iy)`` of the map padded into ``occ_pad`` are blocked (outside: yes)."""
    H, W = occ_pad.shape[0] - 2, occ_pad.shape[1] - 2
    return occ_pad[_clamp(iy + 1, 0, H + 1), _clamp(ix + 1, 0, W + 1)]


def _double_corner(occ_pad: np.ndarray, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Whether lattice vertices ``(X, Y)`` (integers, grid units of ``occ_pad``'s map) are
    points where two blocked cells meet only diagonally (the frame counts as blocked)."""
    bl, br = _blocked_at(occ_pad, X - 1, Y - 1), _blocked_at(occ_pad, X, Y - 1)
    tl, tr = _blocked_at(occ_pad, X - 1, Y), _blocked_at(occ_pad, X, Y)
    return (bl & tr & ~br & ~tl) | (br & tl & ~bl & ~tr)


def double_corner_points(grid, points) -> np.ndarray:
    """Whether points (metres) lie exactly on a lattice vertex where two blocked cells meet
    only diagonally: a path that has such a point as an inner vertex passes through it."""
    g = grid.to_grid(_as_points(points).reshape(-1, 2))
    on = np.isfinite(g).all(axis=1) & np.all(g == np.round(g), axis=1)
    out = np.zeros(len(g), dtype=bool)
    if np.any(on):
        v = g[on].astype(np.int64)
        out[on] = _double_corner(grid.padded, v[:, 0], v[:, 1])
    return out


def _cached_transpose(grid) -> np.ndarray:
    cache = _DERIVED.of(grid)
    if "padded_T" not in cache:
        cache["padded_T"] = np.ascontiguousarray(grid.padded.T)
    return cache["padded_T"]


def _cached_prefix(grid, transposed: bool) -> np.ndarray:
    key = "col_prefix_T" if transposed else "col_prefix"
    cache = _DERIVED.of(grid)
    if key not in cache:
        cache[key] = _column_prefix(_cached_transpose(grid) if transposed else grid.padded)
    return cache[key]


def _segments_rule(grid, ga: np.ndarray, gb: np.ndarray) -> np.ndarray:
    """Apply the clearance-0 rule to segments given in grid units."""
    n = len(ga)
    ok = np.ones(n, dtype=bool)
    ints = _doubled_ints(ga, gb)
    integer = ints is not None
    if integer:
        a, b, S = ints[0], ints[1], 2
    else:
        a, b, S = ga, gb, 1.0
    vertical = a[:, 0] == b[:, 0]
    same = vertical & (a[:, 1] == b[:, 1])
    if np.any(same):
        ok[same] = points_free(grid, grid.to_world(ga[same]))
    # non-vertical: order endpoints by x
    nv = ~vertical
    if np.any(nv):
        swap = a[nv, 0] > b[nv, 0]
        aa = np.where(swap[:, None], b[nv], a[nv])
        bb = np.where(swap[:, None], a[nv], b[nv])
        ok[nv] = _segments_free_grid_units(grid.padded, _cached_prefix(grid, False), aa, bb, S, integer)
    # vertical: the same rule on the transposed map
    v = vertical & ~same
    if np.any(v):
        at, bt = a[v][:, ::-1], b[v][:, ::-1]
        swap = at[:, 0] > bt[:, 0]
        aa = np.where(swap[:, None], bt, at)
        bb = np.where(swap[:, None], at, bt)
        ok[v] = _segments_free_grid_units(_cached_transpose(grid), _cached_prefix(grid, True), aa, bb, S, integer)
    return ok


def _segment_box_distance(a: np.ndarray, b: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Distance between segments ``a->b`` and closed boxes ``[lo, hi]`` that do not
    overlap (checked by the caller): the minimum over segment endpoints to box and
    box corners to segment."""
    def point_box(p):
        d = np.maximum(np.maximum(lo - p, p - hi), 0.0)
        return np.hypot(d[:, 0], d[:, 1])

    def point_seg(p):
        ab = b - a
        L2 = np.einsum("ij,ij->i", ab, ab)
        t = np.where(L2 > 0, np.einsum("ij,ij->i", p - a, ab) / np.where(L2 > 0, L2, 1.0), 0.0)
        t = _clamp(t, 0.0, 1.0)
        q = a + t[:, None] * ab
        return np.hypot(p[:, 0] - q[:, 0], p[:, 1] - q[:, 1])

    d = np.minimum(point_box(a), point_box(b))
    for cx, cy in ((lo[:, 0], lo[:, 1]), (hi[:, 0], lo[:, 1]), (lo[:, 0], hi[:, 1]), (hi[:, 0], hi[:, 1])):
        d = np.minimum(d, point_seg(np.stack([cx, cy], axis=1)))
    return d


def _blocked_cells_near(grid, ga: np.ndarray, gb: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Blocked cells that may lie within ``r[i]`` (grid units) of segment ``ga[i] -> gb[i]``.

    Returns ``(owner, lo)``: the segment index and lower-left corner (grid units) of
    each candidate cell. Enumerated per column of the segment thickened by ``r``: the
    rows it can reach there, so every cell within ``r`` is listed (and a few more)."""
    xmin = np.minimum(ga[:, 0], gb[:, 0]) - r
    xmax = np.maximum(ga[:, 0], gb[:, 0]) + r
    k0 = np.floor(xmin).astype(np.int64)
    k1 = np.ceil(xmax).astype(np.int64) - 1
    seg, off = _expand(k1 - k0 + 1)
    k = k0[seg] + off
    a, b, rs = ga[seg], gb[seg], r[seg]
    dxs = b[:, 0] - a[:, 0]
    # y-range of the segment over x in [k - r, k + 1 + r]
    xl = _clamp(k - rs, np.minimum(a[:, 0], b[:, 0]), np.maximum(a[:, 0], b[:, 0]))
    xr = _clamp(k + 1 + rs, np.minimum(a[:, 0], b[:, 0]), np.maximum(a[:, 0], b[:, 0]))
    safe = np.where(dxs != 0, dxs, 1.0)
    ya = np.where(dxs != 0, a[:, 1] + (xl - a[:, 0]) * (b[:, 1] - a[:, 1]) / safe, np.minimum(a[:, 1], b[:, 1]))
    yb = np.where(dxs != 0, a[:, 1] + (xr - a[:, 0]) * (b[:, 1] - a[:, 1]) / safe, np.maximum(a[:, 1], b[:, 1]))
    j0 = np.floor(np.minimum(ya, yb) - rs).astype(np.int64)
    j1 = np.ceil(np.maximum(ya, yb) + rs).astype(np.int64) - 1
    # rows outside the map hold no blocked cell (the border is measured separately)
    j0, j1 = np.maximum(j0, 0), np.minimum(j1, grid.height - 1)
    own, joff = _expand(j1 - j0 + 1)
    cx, cy = k[own], j0[own] + joff
    inside = (cx >= 0) & (cx < grid.width)
    cand = np.zeros(len(cx), dtype=bool)
    cand[inside] = grid.occ[cy[inside], cx[inside]]
    lo = np.stack([cx[cand], cy[cand]], axis=1).astype(float)
    return seg[own][cand], lo


def _segments_clear_grid_units(grid, ga: np.ndarray, gb: np.ndarray, r: float) -> np.ndarray:
    """Segments (grid units) keep distance >= r (grid units) from blocked cells and border."""
    n = len(ga)
    ok = np.ones(n, dtype=bool)
    lo_b, hi_b = np.array([r, r]), np.array([grid.width - r, grid.height - r])
    ok &= np.all((ga >= lo_b) & (ga <= hi_b) & (gb >= lo_b) & (gb <= hi_b), axis=1)
    sidx, lo = _blocked_cells_near(grid, ga, gb, np.full(n, float(r)))
    if sidx.size:
        d = _segment_box_distance(ga[sidx], gb[sidx], lo, lo + 1.0)
        ok[sidx[~(d >= r * (1 - 1e-12))]] = False
    return ok


def segments_clearance(grid, a, b, *, free=None) -> np.ndarray:
    """Exact smallest distance (metres) from each segment ``a[i] -> b[i]`` to the blocked
    cells and the map border of ``grid``.

    A segment that satisfies the clearance-0 rule gets its exact Euclidean distance
    (segment to unit squares, and to the border, which is closest at an end point). A
    segment that breaks the rule gets a value <= 0: minus the deepest penetration
    among its end points and its samples every 1/20 cell (a crossing has no single
    depth). Shape ``(n, 2)`` in, ``(n,)`` out.

    ``free``: the verdict of ``segments_free(grid, a, b)`` (clearance 0, the same ``a``
    and ``b``) when the caller already has it (:func:`validate_path_segments`); it is
    then not computed again. Without it the rule runs here.
    """
    A, B = np.broadcast_arrays(_as_points(a), _as_points(b))
    A, B = A.reshape(-1, 2), B.reshape(-1, 2)
    n = len(A)
    out = np.zeros(n)
    if n == 0:
        return out
    ga, gb = grid.to_grid(A), grid.to_grid(B)
    if free is None:
        free = segments_free(grid, A, B)
    else:
        free = np.asarray(free, dtype=bool).reshape(-1)
        if free.shape != (n,):
            raise ParameterError(f"free must hold one verdict per segment ({n}), got shape {free.shape}")
    # the border is closest at an end point (distance to it is linear along a segment)
    border = np.minimum.reduce([ga[:, 0], ga[:, 1], grid.width - ga[:, 0], grid.height - ga[:, 1],
                                gb[:, 0], gb[:, 1], grid.width - gb[:, 0], grid.height - gb[:, 1]])
    ok = np.nonzero(free)[0]
    if ok.size:
        near = _distance_to_cells(_DERIVED.of(grid), "tree_blocked", lambda: _boundary_cells(grid.occ),
                                  ga[ok], gb[ok])
        out[ok] = np.maximum(np.minimum(near, border[ok]), 0.0)
    bad = np.nonzero(~free)[0]
    if bad.size:
        out[bad] = _crossing_depth(grid, ga[bad], gb[bad])
    return out * grid.resolution


def _crossing_depth(grid, ga: np.ndarray, gb: np.ndarray) -> np.ndarray:
    """Minus the deepest penetration (grid units, <= 0) among the end points of segments
    that break the rule and their samples every 1/20 cell, in blocks of bounded size."""
    seg = gb - ga
    counts = np.maximum(np.ceil(np.hypot(seg[:, 0], seg[:, 1]) * 20).astype(np.int64), 1) + 1
    depth = np.full(len(ga), np.inf)
    for first, last in _blocks(counts, 20 * PIECE_BLOCK):
        owner, off = _expand(counts[first:last])
        owner += first
        t = off / (counts[owner] - 1)
        pts = grid.to_world(ga[owner] + t[:, None] * seg[owner])
        np.minimum.at(depth, owner, grid_clearance(grid, pts) / grid.resolution)
    return np.minimum(depth, 0.0)


def segments_free(grid, a, b, clearance: float = 0.0) -> np.ndarray:
    """Exact segment rule for many segments at once on a :class:`GridMap`.

    Args:
        grid: the map.
        a, b: arrays of shape ``(n, 2)`` (or ``(2,)``) of segment end points in metres.
        clearance: required distance to blocked cells and the map border, metres.

    Returns:
        Boolean array of shape ``(n,)`` (a scalar bool array for single segments).
    """
    c = _check_clearance(clearance)
    A, B = _as_points(a), _as_points(b)
    A, B = np.broadcast_arrays(A, B)
    shape = A.shape[:-1]
    A, B = A.reshape(-1, 2), B.reshape(-1, 2)
    ga, gb = grid.to_grid(A), grid.to_grid(B)
    finite = np.isfinite(ga).all(axis=1) & np.isfinite(gb).all(axis=1)
    inside = finite & np.all((ga >= 0) & (gb >= 0), axis=1)
    inside &= (ga[:, 0] <= grid.width) & (gb[:, 0] <= grid.width)
    inside &= (ga[:, 1] <= grid.height) & (gb[:, 1] <= grid.height)
    ok = inside.copy()
    idx = np.nonzero(inside)[0]
    r = c / grid.resolution
    # the rule's work arrays hold about |dx| + |dy| + 2 entries per segment (and the
    # clearance band (2r + 2) times that): blocks of bounded span keep memory bounded
    d = np.abs(gb[idx] - ga[idx])
    span = d.sum(axis=1) + 2.0 + (4.0 * r * (1.0 + d.max(axis=1)) if r > 0 else 0.0)
    for first, last in _blocks(span, SPAN_BUDGET):
        part = idx[first:last]
        free = _segments_rule(grid, ga[part], gb[part])
        if r > 0 and np.any(free):
            free[free] = _segments_clear_grid_units(grid, ga[part[free]], gb[part[free]], r)
        ok[part] = free
    return ok.reshape(shape)


# --------------------------------------------------------------- grid: clearance
def _boundary_cells(mask: np.ndarray) -> np.ndarray:
    """Cells of ``mask`` with a 4-neighbour outside ``mask`` (inside the map)."""
    m = np.pad(mask, 1, constant_values=False)
    core = m[1:-1, 1:-1]
    edge = core & ~(m[:-2, 1:-1] & m[2:, 1:-1] & m[1:-1, :-2] & m[1:-1, 2:])
    # the frame does not count as "other": only real free/blocked neighbours matter
    iy, ix = np.nonzero(edge)
    return np.stack([ix, iy], axis=1)


# pieces of a segment measured at once by the exact distance: each piece is at most
# 2 * PIECE_HALF cells long, and one block holds at most PIECE_BLOCK pieces, so memory grows
# with the path's length and never with the map's area
PIECE_HALF = 1.0
PIECE_BLOCK = 1 << 15


def _distance_to_cells(tree_cache: dict, key: str, cells_fn, a: np.ndarray, b: np.ndarray | None = None) -> np.ndarray:
    """Exact distance (grid units) from points ``a`` (or segments ``a -> b``) to the union
    of the unit squares whose lower-left corners ``cells_fn()`` lists.

    A segment is cut into pieces no longer than ``2 * PIECE_HALF`` cells. For each piece,
    the squares nearest to its midpoint are read from a k-d tree of their centres, ``k``
    doubling until no unread square can be nearer: a square whose centre is ``D`` from the
    midpoint is at least ``D - sqrt(1/2) - half`` from the piece. The segment's value is its
    pieces' minimum. A segment must not enter a square's interior (the caller checks the
    segment rule first; a touch gives 0)."""
    from scipy.spatial import cKDTree

    if key not in tree_cache:
        cells = cells_fn()
        tree_cache[key] = (cKDTree(cells + 0.5) if len(cells) else None, cells)
    tree, cells = tree_cache[key]
    b = a if b is None else b
    out = np.full(len(a), np.inf)
    if tree is None or len(a) == 0:
        return out
    seg = b - a
    counts = np.maximum(np.ceil(np.hypot(seg[:, 0], seg[:, 1]) / (2 * PIECE_HALF)), 1).astype(np.int64)
    for first, last in _blocks(counts, PIECE_BLOCK):
        owner, off = _expand(counts[first:last])
        owner += first
        n = counts[owner].astype(float)
        pa = a[owner] + (off / n)[:, None] * seg[owner]
        pb = a[owner] + ((off + 1) / n)[:, None] * seg[owner]
        mid, half = 0.5 * (pa + pb), 0.5 * np.hypot(pb[:, 0] - pa[:, 0], pb[:, 1] - pa[:, 1])
        piece = np.full(len(owner), np.inf)
        todo = np.arange(len(owner))
        k = min(8, len(cells))
        while todo.size:
            dist, idx = tree.query(mid[todo], k=k)
            dist, idx = dist.reshape(len(todo), -1), idx.reshape(len(todo), -1)
            lo = cells[idx.ravel()].astype(float)
            rep = np.repeat(todo, idx.shape[1])
            d = _segment_box_distance(pa[rep], pb[rep], lo, lo + 1.0).reshape(len(todo), -1).min(axis=1)
            piece[todo] = d
            done = (dist[:, -1] - np.sqrt(0.5) - half[todo] > d) | (k >= len(cells))
            todo = todo[~done]
            k = min(2 * k, len(cells))
        np.minimum.at(out, owner, piece)
    return out


def grid_clearance(grid, points) -> np.ndarray:
    """Signed distance (metres) from points to blocked cells and the map border."""
    p = _as_points(points)
    shape = p.shape[:-1]
    g = grid.to_grid(p.reshape(-1, 2))
    border = np.minimum.reduce([g[:, 0], g[:, 1], grid.width - g[:, 0], grid.height - g[:, 1]])
    cache = _DERIVED.of(grid)
    to_blocked = _distance_to_cells(cache, "tree_blocked", lambda: _boundary_cells(grid.occ), g)
    d = np.minimum(to_blocked, border)
    # inside an obstacle (interior of a blocked cell) or outside the map: negative depth
    inside_map = (g[:, 0] >= 0) & (g[:, 0] <= grid.width) & (g[:, 1] >= 0) & (g[:, 1] <= grid.height)
    in_blocked = ~points_free(grid, p.reshape(-1, 2)) & inside_map
    if np.any(in_blocked):
        depth = _distance_to_cells(cache, "tree_free", lambda: _boundary_cells(~grid.occ), g[in_blocked])
        d[in_blocked] = -depth
    outside = ~inside_map & (border < 0)
    d[outside] = border[outside]
    return (d * grid.resolution).reshape(shape)


# ------------------------------------------------------------------ validate_path
@dataclass
class PathCheck:
    """Outcome of :func:`validate_path`; truthy when the path is valid.

    Attributes:
        ok: every point and every segment satisfies the rule.
        bad_segments: indices ``i`` of segments ``path[i] -> path[i+1]`` that fail.
        bad_points: indices of points that are not free.
        reason: empty when ``ok``, otherwise a sentence naming the first problem.
    """

    ok: bool
    bad_segments: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    bad_points: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    reason: str = ""

    def __bool__(self) -> bool:
        return self.ok


def validate_path(world, path, clearance: float = 0.0) -> PathCheck:
    """The one exact collision test every returned path goes through.

    Args:
        world: a :class:`GridMap` or :class:`CircleWorld`.
        path: ``(N, 2)`` points in metres, start first, goal last (``N >= 1``).
        clearance: required distance to obstacles and map border, metres.

    Returns:
        A :class:`PathCheck` (truthy when valid) naming the failing segments.
    """
    return validate_path_segments(world, path, clearance)[0]


def validate_path_segments(world, path, clearance: float = 0.0) -> tuple[PathCheck, np.ndarray | None]:
    """:func:`validate_path` (the same test, the same :class:`PathCheck`) and the verdict of
    the segment rule on each segment ``path[i] -> path[i + 1]`` that it computed on the way
    (``world.segments_free(path[:-1], path[1:], clearance)``; ``None`` when the path was
    refused before the segments were looked at). With ``clearance == 0`` that verdict is
    what :func:`segments_clearance` (``free=``) and the exact clearance metric need, so a
    result's check and its clearance share one pass of the rule."""
    from .queries import check_world

    check_world(world)
    c = _check_clearance(clearance)
    try:
        P = np.asarray(path, dtype=float)
    except (TypeError, ValueError):
        return PathCheck(False, reason=f"a path must be an (N, 2) array of numbers, got {type(path).__name__}"), None
    if P.ndim != 2 or P.shape[1] != 2 or len(P) == 0:
        return PathCheck(False, reason=f"a path must be an (N, 2) array with N >= 1, got shape {P.shape}"), None
    if not np.all(np.isfinite(P)):
        bad = np.nonzero(~np.isfinite(P).all(axis=1))[0]
        return PathCheck(False, bad_points=bad, reason=f"path has non-finite coordinates at point {bad[0]}"), None
    pts_ok = np.asarray(world.is_free(P, c), dtype=bool)
    if getattr(world, "is_grid", False) and len(P) > 2:
        # an inner vertex on a diagonal meeting of two blocked cells is passed through
        # (DESIGN.md), so joined legs are judged like one straight segment through it
        pts_ok[1:-1] &= ~double_corner_points(world, P[1:-1])
    seg_ok = np.asarray(world.segments_free(P[:-1], P[1:], c), dtype=bool) if len(P) > 1 else np.ones(0, bool)
    bad_pts = np.nonzero(~pts_ok)[0]
    bad_segs = np.nonzero(~seg_ok)[0]
    if bad_pts.size:
        i = bad_pts[0]
        if getattr(world, "is_grid", False) and 0 < i < len(P) - 1 and double_corner_points(world, P[i])[0]:
            reason = (f"point {i} ({P[i, 0]:.6g}, {P[i, 1]:.6g}) is a point where two blocked cells meet "
                      "diagonally; a point robot cannot pass it")
        else:
            reason = (f"point {i} ({P[i, 0]:.6g}, {P[i, 1]:.6g}) is not free"
                      + (f" with clearance {c:g} m" if c else ""))
    elif bad_segs.size:
        i = bad_segs[0]
        reason = (f"segment {i} ({P[i, 0]:.6g}, {P[i, 1]:.6g}) -> ({P[i + 1, 0]:.6g}, {P[i + 1, 1]:.6g}) "
                  "collides" + (f" or comes closer than {c:g} m to an obstacle" if c else ""))
    else:
        reason = ""
    return PathCheck(not reason, bad_segs, bad_pts, reason), seg_ok


# ------------------------------------------------- the rule on cell paths, in cell units
# Graph search returns paths through cell centres. For those the rule needs no segment
# geometry: the checks below give its verdicts (clearance 0) from cell lookups, exactly, for a
# few microseconds instead of the general rule's fixed cost of a few hundred
# (tests/test_shortest_path_speed_43.py compares them with the general rule).
def padded_bytes(grid) -> bytes:
    """``grid.padded`` as one byte per cell, row after row (1 = blocked; the frame is
    blocked), cached on the map: indexing ``bytes`` gives a Python int."""
    cache = _DERIVED.of(grid)
    out = cache.get("padded_bytes")
    if out is None:
        out = cache["padded_bytes"] = grid.padded.astype(np.uint8).tobytes()
    return out


def grid_point_free(grid, gx: float, gy: float) -> bool:
    """:func:`points_free` (clearance 0) of one point given in grid units (``GridMap.
    point_to_grid``) on Python floats: inside the map and in the closure of a free cell."""
    W, H = grid.width, grid.height
    if not (0.0 <= gx <= W and 0.0 <= gy <= H):   # also False for NaN
        return False
    fx, fy = math.floor(gx), math.floor(gy)
    pad, Wp = padded_bytes(grid), W + 2
    # a point on a grid line belongs to the closure of the cells on both sides
    for iy in {fy, fy - 1 if gy == fy else fy}:
        for ix in {fx, fx - 1 if gx == fx else fx}:
            if not pad[min(max(iy + 1, 0), H + 1) * Wp + min(max(ix + 1, 0), W + 1)]:
                return True
    return False


def in_free_cell(grid, gx: float, gy: float, cell: int) -> bool:
    """Whether the point ``(gx, gy)`` (grid units) lies in the closed square of the free
    cell with flat index ``cell`` (``iy * width + ix``).

    Then the segment from the point to any other point of that closed square (its centre,
    the other end of a path inside the cell) satisfies the rule: the square is convex and
    free, so the segment enters no blocked interior; it meets the square's boundary, which
    is made of edges between this free cell and another, only at its ends or along one
    edge, and an edge of a square holds no lattice vertex strictly inside it."""
    iy, ix = divmod(int(cell), grid.width)
    return (0 <= iy < grid.height and ix <= gx <= ix + 1 and iy <= gy <= iy + 1
            and not padded_bytes(grid)[(iy + 1) * (grid.width + 2) + ix + 1])


# the 8 unit moves (dx, dy) whose centre-to-centre segments centre_moves_free decides
_UNIT_MOVES = ((1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1))


def _unit_move_masks(grid) -> np.ndarray:
    """``(width * height,)`` uint8, cached on the map: bit ``k`` of entry ``c`` is the rule's
    verdict on the segment from the centre of cell ``c`` to the centre of its neighbour
    ``_UNIT_MOVES[k]`` (see :func:`centre_moves_free`)."""
    cache = _DERIVED.of(grid)
    out = cache.get("unit_move_masks")
    if out is None:
        H, W = grid.height, grid.width
        free = ~grid.padded          # free[iy + 1, ix + 1]; the frame (outside) is blocked

        def at(dx: int, dy: int) -> np.ndarray:
            return free[1 + dy:H + 1 + dy, 1 + dx:W + 1 + dx]

        out = np.zeros((H, W), dtype=np.uint8)
        for k, (dx, dy) in enumerate(_UNIT_MOVES):
            ok = at(0, 0) & at(dx, dy)
            if dx and dy:   # not both side cells blocked (they would meet only diagonally)
                ok &= at(dx, 0) | at(0, dy)
            out |= ok.astype(np.uint8) << k
        out = cache["unit_move_masks"] = out.reshape(-1)
    return out


def _unit_move_bits(width: int) -> np.ndarray:
    """``bits[d + width + 2]``: the bit of the unit move whose flat step is ``d`` (``dx + dy *
    width``), 0 for any other step (both ends of the table stand for every step beyond)."""
    bits = np.zeros(2 * width + 5, dtype=np.uint8)
    for k, (dx, dy) in enumerate(_UNIT_MOVES):
        bits[dx + dy * width + width + 2] = 1 << k
    return bits


def centre_moves_free(grid, cells) -> np.ndarray:
    """The rule (clearance 0) on the segments between the centres of consecutive cells of
    ``cells`` (flat indices ``iy * width + ix``), from cell lookups: one verdict a segment.

    A segment between the centres of two 8-adjacent cells lies in the union of their closed
    squares and crosses no edge lengthwise; a diagonal one passes through the one lattice
    vertex the four cells around it share. So it is free exactly when both cells are free
    and, for a diagonal, the two side cells are not both blocked (they would meet only
    diagonally at that vertex): one bit of a per-map table (:func:`_unit_move_masks`). Cells
    that are not 8-adjacent get ``False`` (not decided here: a caller then runs the general
    rule). A flat step of a unit move can also join two cells that are not neighbours (across
    the map's side), and on maps 1 or 2 cells wide two moves can share a flat step: the bit
    read is then that of a neighbour outside the map, 0, never a wrong ``True``."""
    W, n = grid.width, grid.width * grid.height
    f = np.asarray(cells, dtype=np.int64)
    if f.size < 2:
        return np.ones(0, dtype=bool)
    if f.astype(np.uint64).max() >= n:   # a negative index wraps to a huge one
        return np.zeros(f.size - 1, dtype=bool)
    cache = _DERIVED.of(grid)
    bits = cache.get("unit_move_bits")
    if bits is None:
        bits = cache["unit_move_bits"] = _unit_move_bits(W)
    step = _clamp(f[1:] - f[:-1] + (W + 2), 0, 2 * W + 4)
    return (_unit_move_masks(grid)[f[:-1]] & bits[step]) != 0


def convex_corners(grid) -> tuple[np.ndarray, np.ndarray]:
    """Lattice vertices (grid units) with exactly one blocked cell around them (the map's
    outside counts as blocked), and the quadrant ``(sx, sy)`` (each +-1) in which that
    blocked cell lies: the only points where a shortest path under the segment rule bends."""
    pad = grid.padded  # padded[iy + 1, ix + 1]
    # the four cells around vertex (X, Y): (X-1, Y-1), (X, Y-1), (X-1, Y), (X, Y)
    bl, br = pad[:-1, :-1], pad[:-1, 1:]
    tl, tr = pad[1:, :-1], pad[1:, 1:]
    count = bl.astype(np.int8) + br + tl + tr
    Y, X = np.nonzero(count == 1)
    sx = np.where(br[Y, X] | tr[Y, X], 1, -1)
    sy = np.where(tl[Y, X] | tr[Y, X], 1, -1)
    return np.stack([X, Y], axis=1).astype(float), np.stack([sx, sy], axis=1)


def wrap_angle(theta):
    """Angle(s) in radians wrapped to ``[-pi, pi)``."""
    return (np.asarray(theta, dtype=float) + np.pi) % (2 * np.pi) - np.pi
