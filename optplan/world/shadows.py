"""Spatial pruning for the exact any-angle search: corner tiles, shadows of near cells, grid lines.

The exact search (:mod:`optplan.solvers.graph.visibility`) expands corners and needs the
corners each one sees. Looking at every corner of the map on every expansion costs
``O(corners)`` numpy work per expansion, which dominated on large cluttered maps. The pieces
here restrict the look to corners that may be visible, for a batch of expanded points at once
(every array carries the index of its point, its *owner*), and never drop a corner that the
exact segment rule would accept:

* :class:`CornerTiles`: the corners bucketed in square tiles, the tiles in square blocks
  (each with its tight bounding box). A box whose nearest point is too far for the search's
  ellipse (``|v - u| + |v - goal| <= budget``), or that lies wholly outside the directions in
  which a taut path may leave a corner (:func:`taut_regions`), holds no candidate and is
  skipped; blocks first, then the tiles of the blocks kept.
* :class:`Shadows`: each blocked cell near an expanded point ``u`` hides an open wedge of
  directions. A ray from ``u`` whose direction lies strictly inside the wedge of a blocked
  unit square passes through that square's open interior, between the distances of its
  nearest and farthest corners; so a candidate ``v`` in such a direction and farther than the
  far corner enters a blocked interior: the rule refuses it, whatever the clearance. Wedges
  are shrunk by :data:`ANGLE_EPS` radians at both sides before use, so a direction that close
  to a side (rounding; rays along cell edges; rays between two cells that only touch) is never
  refused here; such candidates, like every candidate not refused, get the exact rule. A whole
  block or tile is skipped when it lies beyond every near cell and all its directions lie
  inside one chain of overlapping wedges.
* :class:`GridLines`: a segment along a grid line touches the cells on both sides without
  entering them, so no wedge hides it. Prefix sums per line count, exactly, the edges between
  two blocked cells it runs along and the double corners strictly inside it (the rule refuses
  it when one is there).

Everything here only removes candidates that the exact rule would refuse or that the search
would not look at (outside the ellipse, not taut), so the visibility graph the search sees,
and the optimum, are those of the search over every corner.
"""
from __future__ import annotations

import numpy as np

TWO_PI = 2.0 * np.pi
# radians a wedge is shrunk by at each side (a candidate this close to a side is kept): far
# above the float error of the angles (~1e-13 with the owner offsets below), and a segment
# refused by a wedge enters a blocked interior by ~1e-7 cells or more, far above the exact
# rule's float tolerance (~1e-12)
ANGLE_EPS = 1e-7
# Chebyshev radius (cells) of the window of cells whose wedges are computed around a point
# that may leave in any direction (start, goal), and around a corner, whose taut
# continuations lie in one quadrant (a quarter of the cells for a window twice as wide)
SHADOW_RADIUS = 8
QUADRANT_RADIUS = 16
# wedge angles of owner k are shifted by k * _OWNER_TURN so that one sorted array holds every
# owner's wedges apart (three copies of a turn span (-3 pi, 5 pi); queries lie in (-pi, 3 pi))
_OWNER_TURN = 8.0 * np.pi
# tiles: about this many on the map (the side at least TILE_MIN cells), grouped in blocks of
# BLOCK_TILES x BLOCK_TILES tiles (a hidden block skips all its tiles at once)
TILE_COUNT = 4096
TILE_MIN = 8
BLOCK_TILES = 4
# added to distance comparisons (grid units) so that rounding never drops a candidate
DIST_SLACK = 1e-9


def _wedges(cx: np.ndarray, cy: np.ndarray, px: np.ndarray, py: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Angular extent ``[lo, hi]`` (radians, ``lo`` in ``(-pi, 3 pi)``) of convex boxes seen from
    the origin: ``(cx, cy)`` a point inside each box (its centre), ``(px, py)`` its corners
    ``(m, 4)``. The origin must lie outside every closed box (the extent is then < pi)."""
    theta = np.arctan2(cy, cx) % TWO_PI
    rel = np.arctan2(cx[:, None] * py - cy[:, None] * px, cx[:, None] * px + cy[:, None] * py)
    return theta + rel.min(axis=1), theta + rel.max(axis=1)


def direction(d: np.ndarray) -> np.ndarray:
    """Angles in ``[0, 2 pi)`` of the rows of ``d``."""
    return np.arctan2(d[:, 1], d[:, 0]) % TWO_PI


def taut_regions(a: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where taut paths may go on from corners: ``a`` (rows) point back to the predecessors,
    ``w`` (rows of signs ``(qx, qy)``) to the corners' blocked cells. The turn must hold the
    cell (the direction ``b`` on the side of ``a`` that ``w`` is on, and on that side of ``w``)
    and the line of ``b`` must not enter the cell's quadrant or the opposite one; so ``b`` lies
    in the closed quadrant next to ``w`` on that side, and in the closed half-plane on that
    side of ``a`` (straight on, ``b = -a``, included).

    Returns ``(ok, quadrant, n)``: ``ok`` False where ``a`` is parallel to ``w`` or zero (no
    restriction), the quadrant's signs ``(sx, sy)`` and the half-plane's normal ``n``
    (``n . b >= 0``)."""
    side = np.sign(a[:, 0] * w[:, 1] - a[:, 1] * w[:, 0])
    quadrant = np.stack([-side * w[:, 1], side * w[:, 0]], axis=1).astype(np.int64)
    n = side[:, None] * np.stack([-a[:, 1], a[:, 0]], axis=1)
    return side != 0, quadrant, n


class Shadows:
    """The wedges hidden from points ``U`` (grid units) by the blocked cells of ``occ`` near
    them: within :data:`SHADOW_RADIUS` cells, or, for a point with a quadrant (``quadrant[k]``
    not ``(0, 0)``), within :data:`QUADRANT_RADIUS` cells in that closed quadrant only (the
    only directions then asked about: a ray in it meets only cells that reach into it).

    :attr:`reach` is, per point, the distance of the farthest corner of those cells: a point
    farther than that in a direction :meth:`covers` is hidden. :meth:`hides` judges nearer
    points cell by cell; :meth:`covers_spans` whole ranges of directions."""

    def __init__(self, occ: np.ndarray, U: np.ndarray, quadrant: np.ndarray) -> None:
        H, W = occ.shape
        B = len(U)
        ux, uy = U[:, 0], U[:, 1]
        fx, fy = np.floor(ux).astype(np.int64), np.floor(uy).astype(np.int64)
        cx, cy = np.ceil(ux).astype(np.int64), np.ceil(uy).astype(np.int64)
        sx, sy = quadrant[:, 0], quadrant[:, 1]
        r = np.where((sx != 0) | (sy != 0), QUADRANT_RADIUS, SHADOW_RADIUS)
        x0, x1 = np.maximum(fx - r, 0), np.minimum(fx + r + 1, W)
        y0, y1 = np.maximum(fy - r, 0), np.minimum(fy + r + 1, H)
        x0 = np.where(sx > 0, np.maximum(x0, cx - 1), x0)
        x1 = np.where(sx < 0, np.minimum(x1, fx + 1), x1)
        y0 = np.where(sy > 0, np.maximum(y0, cy - 1), y0)
        y1 = np.where(sy < 0, np.minimum(y1, fy + 1), y1)
        # full windows are 2 r + 1 cells wide, quadrant ones at most r + 2
        off = np.arange(max(2 * SHADOW_RADIUS + 1, QUADRANT_RADIUS + 2))
        ix = x0[:, None, None] + off[None, None, :]           # (B, 1, w)
        iy = y0[:, None, None] + off[None, :, None]           # (B, w, 1)
        inside = (ix < x1[:, None, None]) & (iy < y1[:, None, None])
        blocked = inside & occ[np.minimum(iy, H - 1), np.minimum(ix, W - 1)]
        owner, j, i = np.nonzero(blocked)
        ix = (x0[owner] + i).astype(float)
        iy = (y0[owner] + j).astype(float)
        # a cell whose closed square holds its point hides no wedge of its own (the point's own
        # obstacle: the tangent and taut rules and the exact rule deal with it)
        px0, py0 = ux[owner], uy[owner]
        away = (ix > px0) | (ix + 1 < px0) | (iy > py0) | (iy + 1 < py0)
        owner, ix, iy = owner[away], ix[away] - px0[away], iy[away] - py0[away]
        self.B = B
        self.reach = np.zeros(B)
        self.empty = True
        if owner.size == 0:
            return
        self.empty = False
        qx = np.stack([ix, ix + 1, ix, ix + 1], axis=1)
        qy = np.stack([iy, iy, iy + 1, iy + 1], axis=1)
        lo, hi = _wedges(ix + 0.5, iy + 0.5, qx, qy)
        lo, hi = lo + ANGLE_EPS, hi - ANGLE_EPS
        far = np.sqrt((qx * qx + qy * qy).max(axis=1))
        np.maximum.at(self.reach, owner, far)
        # cells by owner, for the cell by cell test (nonzero lists them by owner already)
        self.cell_owner, self.cell_lo, self.cell_width, self.cell_far = owner, lo, hi - lo, far + DIST_SLACK
        self.cell_start = np.searchsorted(owner, np.arange(B + 1))
        # the union of each owner's wedges over three turns, in one sorted array
        shift = owner * _OWNER_TURN
        lo3 = np.concatenate([lo - TWO_PI + shift, lo + shift, lo + TWO_PI + shift])
        hi3 = np.concatenate([hi - TWO_PI + shift, hi + shift, hi + TWO_PI + shift])
        order = np.argsort(lo3, kind="stable")
        lo3, hi3 = lo3[order], hi3[order]
        hi_max = np.maximum.accumulate(hi3)
        # chains of wedges that overlap on an interval (not merely touch): every direction
        # strictly between a chain's first lo and its largest hi is strictly inside a wedge
        # (owners never chain: their shifted ranges are apart)
        brk = np.empty(len(lo3), dtype=bool)
        brk[0] = True
        brk[1:] = lo3[1:] >= hi_max[:-1]
        end = np.maximum.reduceat(hi3, np.nonzero(brk)[0])
        self.lo, self.hi_max, self.end = lo3, hi_max, end[np.cumsum(brk) - 1]

    def covers(self, owner: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """Whether directions ``theta`` (radians in ``(-pi, 3 pi)``) from the points ``owner``
        lie strictly inside one of their wedges."""
        if self.empty or len(theta) == 0:
            return np.zeros(len(theta), dtype=bool)
        t = theta + owner * _OWNER_TURN
        i = np.searchsorted(self.lo, t, side="left") - 1
        ok = i >= 0
        ok[ok] = self.hi_max[i[ok]] > t[ok]
        return ok

    def covers_spans(self, owner: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Whether every direction of ``[a, b]`` (``a <= b``, radians in ``(-pi, 3 pi)``) from
        the points ``owner`` lies strictly inside one of their wedges."""
        if self.empty or len(a) == 0:
            return np.zeros(len(a), dtype=bool)
        shift = owner * _OWNER_TURN
        a, b = a + shift, b + shift
        i = np.searchsorted(self.lo, a, side="left") - 1
        ok = i >= 0
        k = i[ok]
        ok[ok] = (self.hi_max[k] > a[ok]) & (self.end[k] > b[ok])
        return ok

    def hides(self, owner: np.ndarray, theta: np.ndarray, dist: np.ndarray) -> np.ndarray:
        """Whether points at directions ``theta`` (radians) and distances ``dist`` from the
        points ``owner`` lie behind one of the owner's cells: strictly inside its wedge and
        farther than its far corner (cell by cell)."""
        out = np.zeros(len(theta), dtype=bool)
        if self.empty or len(theta) == 0:
            return out
        counts = self.cell_start[owner + 1] - self.cell_start[owner]
        pair = np.repeat(np.arange(len(theta)), counts)
        cell = np.repeat(self.cell_start[owner] - (np.cumsum(counts) - counts), counts) + np.arange(int(counts.sum()))
        rel = (theta[pair] - self.cell_lo[cell]) % TWO_PI
        hit = (rel > 0) & (rel < self.cell_width[cell]) & (dist[pair] > self.cell_far[cell])
        out[pair[hit]] = True
        return out


class CornerTiles:
    """Corners (grid units) bucketed in square tiles, the tiles grouped in square blocks, each
    tile and block with its tight bounding box; :meth:`candidates` lists, for a batch of
    points, the corners of the tiles that may hold an edge's other end: the blocks are
    judged first, then the tiles of the blocks kept. ``first`` is the node index of
    ``points[0]`` in the search's nodes.

    ``lattice``: every corner is a lattice vertex (no clearance). Then a ray from a point
    along a grid line through it touches the cells on both sides without entering them, so no
    wedge ever covers it: the corners on that line come from a row / column index instead
    (:meth:`on_lines`; the rule along a grid line is :class:`GridLines`' business), and a box
    across such a line is judged by its two parts off the line (a lattice corner off the line
    is at least one cell from it)."""

    def __init__(self, points: np.ndarray, first: int = 0, lattice: bool = False, tile: int | None = None,
                 block: int = BLOCK_TILES) -> None:
        pts = np.asarray(points, float).reshape(-1, 2)
        self.lattice = bool(lattice) and len(pts) > 0 and bool(np.all(pts == np.round(pts)))
        self.rows = self.cols = None
        self._goal_key = self._goal_dist = None
        self.first = int(first)
        if len(pts) == 0:
            self.nodes = np.zeros(0, dtype=np.int64)
            self.start = self.stop = self.tile_start = self.tile_stop = np.zeros(0, dtype=np.int64)
            self.lo = self.hi = self.block_lo = self.block_hi = np.zeros((0, 2))
            return
        if tile is None:
            span = float(np.max(pts.max(axis=0) - pts.min(axis=0))) + 1.0
            tile = max(TILE_MIN, int(np.ceil(span / np.sqrt(TILE_COUNT))))
        t = np.floor(pts / tile).astype(np.int64)
        t -= t.min(axis=0)
        c = t // max(int(block), 1)
        # corners ordered by block, then by tile: a block's tiles and a tile's corners are runs
        order = np.lexsort((t[:, 0], t[:, 1], c[:, 0], c[:, 1]))
        t, c = t[order], c[order]
        self.nodes = first + order
        P = pts[order]
        new_tile = np.r_[True, np.any(t[1:] != t[:-1], axis=1)]
        self.start = np.nonzero(new_tile)[0]
        self.stop = np.r_[self.start[1:], len(P)]
        self.lo = np.minimum.reduceat(P, self.start, axis=0)
        self.hi = np.maximum.reduceat(P, self.start, axis=0)
        tc = c[self.start]
        new_block = np.r_[True, np.any(tc[1:] != tc[:-1], axis=1)]
        self.tile_start = np.nonzero(new_block)[0]
        self.tile_stop = np.r_[self.tile_start[1:], len(self.start)]
        self.block_lo = np.minimum.reduceat(self.lo, self.tile_start, axis=0)
        self.block_hi = np.maximum.reduceat(self.hi, self.tile_start, axis=0)
        if self.lattice:
            self.rows = _LineIndex(pts[:, 1].astype(np.int64), first)
            self.cols = _LineIndex(pts[:, 0].astype(np.int64), first)

    def lines_through(self, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Whether points ``U`` lie on a horizontal / a vertical grid line (lattice mode only)."""
        if not self.lattice:
            no = np.zeros(len(U), dtype=bool)
            return no, no
        return U[:, 1] == np.floor(U[:, 1]), U[:, 0] == np.floor(U[:, 0])

    def on_lines(self, U: np.ndarray, on_row: np.ndarray, on_col: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(owner, node)`` of the corners on the grid lines through points ``U`` (lattice mode)."""
        owners, nodes = [], []
        for index, on, axis in ((self.rows, on_row, 1), (self.cols, on_col, 0)):
            k = np.nonzero(on)[0]
            if k.size == 0:
                continue
            o, nd = index.at(U[k, axis].astype(np.int64))
            owners.append(k[o])
            nodes.append(nd)
        if not owners:
            return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
        return np.concatenate(owners), np.concatenate(nodes)

    @staticmethod
    def _box_distance(lo: np.ndarray, hi: np.ndarray, p: np.ndarray) -> np.ndarray:
        dx = np.maximum(np.maximum(lo[:, 0] - p[:, 0], p[:, 0] - hi[:, 0]), 0.0)
        dy = np.maximum(np.maximum(lo[:, 1] - p[:, 1], p[:, 1] - hi[:, 1]), 0.0)
        return np.sqrt(dx * dx + dy * dy)

    def _goal_distance(self, goal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        key = (float(goal[0]), float(goal[1]))
        if self._goal_key != key:
            g = np.asarray(goal, float)[None, :]
            self._goal_key = key
            self._goal_dist = (self._box_distance(self.block_lo, self.block_hi, g),
                               self._box_distance(self.lo, self.hi, g))
        return self._goal_dist

    def candidates(self, U: np.ndarray, goal: np.ndarray, budget: np.ndarray, shadows: Shadows,
                   turn: np.ndarray, quadrant: np.ndarray, n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(owner, node)`` of the corners in the tiles that may hold, for point ``U[k]``, a
        corner ``v`` with ``|v - U[k]| + |v - goal| <= budget[k]`` (``inf``: no limit) and that
        the shadows of ``U[k]`` do not wholly hide. Where ``turn[k]``, only corners in the
        closed quadrant ``quadrant[k]`` from ``U[k]`` and in the closed half-plane
        ``n[k] . (v - U[k]) >= 0`` are wanted (:func:`taut_regions`). In lattice mode the
        corners on the grid lines through ``U[k]`` may be missing (:meth:`on_lines`)."""
        none = np.zeros(0, dtype=np.int64)
        if len(self.start) == 0:
            return none, none
        g_block, g_tile = self._goal_distance(goal)
        # every (point, block), then the tiles of the blocks kept
        owner = np.repeat(np.arange(len(U)), len(self.tile_start))
        box = np.tile(np.arange(len(self.tile_start)), len(U))
        k = self._keep(U, owner, self.block_lo[box], self.block_hi[box], g_block[box], budget, shadows,
                       turn, quadrant, n)
        owner, box = owner[k], box[k]
        counts = self.tile_stop[box] - self.tile_start[box]
        tile = np.repeat(self.tile_start[box] - (np.cumsum(counts) - counts), counts) + np.arange(int(counts.sum()))
        owner = np.repeat(owner, counts)
        k = self._keep(U, owner, self.lo[tile], self.hi[tile], g_tile[tile], budget, shadows, turn, quadrant, n)
        owner, tile = owner[k], tile[k]
        counts = self.stop[tile] - self.start[tile]
        total = int(counts.sum())
        if total == 0:
            return none, none
        # the members of each kept tile, in order: its start repeated, plus an offset
        row = np.repeat(self.start[tile] - (np.cumsum(counts) - counts), counts) + np.arange(total)
        return np.repeat(owner, counts), self.nodes[row]

    def _keep(self, U, owner, lo, hi, to_goal, budget, shadows, turn, quadrant, n) -> np.ndarray:
        """Indices of the boxes ``[lo, hi]`` (one per entry, for point ``U[owner]``) that may
        hold a wanted corner (see :meth:`candidates`)."""
        u = U[owner]
        ux, uy = u[:, 0], u[:, 1]
        keep = ~turn[owner]
        t = np.nonzero(~keep)[0]
        if t.size:
            # the closed quadrant and the closed half-plane of a turn
            q, nn = quadrant[owner[t]], n[owner[t]]
            L, H = lo[t], hi[t]
            m = np.where(q[:, 0] > 0, H[:, 0] >= ux[t], L[:, 0] <= ux[t])
            m &= np.where(q[:, 1] > 0, H[:, 1] >= uy[t], L[:, 1] <= uy[t])
            fx = np.where(nn[:, 0] > 0, H[:, 0], L[:, 0]) - ux[t]
            fy = np.where(nn[:, 1] > 0, H[:, 1], L[:, 1]) - uy[t]
            m &= nn[:, 0] * fx + nn[:, 1] * fy >= \
                -1e-9 * (np.abs(nn[:, 0]) + np.abs(nn[:, 1])) * (np.abs(fx) + np.abs(fy) + 1.0)
            keep[t] = m
        k = np.nonzero(keep)[0]
        du = self._box_distance(lo[k], hi[k], u[k])
        b = budget[owner[k]]
        fin = np.isfinite(b)
        if fin.any():
            m = ~fin
            m[fin] = du[fin] + to_goal[k[fin]] <= b[fin] * (1 + 1e-12) + 1e-6
            k, du = k[m], du[m]
        if not shadows.empty and k.size:
            f = np.nonzero(du > shadows.reach[owner[k]] + DIST_SLACK)[0]
            if f.size:
                hidden = self._hidden(U, owner[k[f]], lo[k[f]], hi[k[f]], shadows)
                m = np.ones(len(k), dtype=bool)
                m[f[hidden]] = False
                k = k[m]
        return k

    def _hidden(self, U: np.ndarray, owner: np.ndarray, lo: np.ndarray, hi: np.ndarray, shadows: Shadows) -> np.ndarray:
        """Whether boxes (each beyond its point's reach) are wholly hidden from their points:
        the parts of the boxes off the grid lines through the point (the whole box outside
        lattice mode)."""
        u = U[owner]
        alo, ahi = lo.copy(), hi.copy()   # box A, the part below / left of a line through u
        blo, bhi = lo.copy(), hi.copy()   # box B, the part above / right of it, if any
        split = np.zeros(len(owner), dtype=bool)
        on_row, on_col = self.lines_through(u)
        for axis, on in ((0, on_col), (1, on_row)):
            c = u[:, axis]
            across = on & (lo[:, axis] <= c) & (hi[:, axis] >= c)
            ahi[across, axis] = c[across] - 1.0
            blo[across, axis] = c[across] + 1.0
            split |= across
        ok = np.ones(len(owner), dtype=bool)
        for L, H, use in ((alo, ahi, None), (blo, bhi, split)):
            present = np.all(L <= H, axis=1)
            if use is not None:
                present &= use
            j = np.nonzero(present)[0]
            if j.size == 0:
                continue
            L, H, v = L[j], H[j], u[j]
            c = 0.5 * (L + H) - v
            Lx, Ly = L[:, 0:1] - v[:, 0:1], L[:, 1:2] - v[:, 1:2]
            Hx, Hy = H[:, 0:1] - v[:, 0:1], H[:, 1:2] - v[:, 1:2]
            a, b = _wedges(c[:, 0], c[:, 1], np.concatenate([Lx, Hx, Lx, Hx], axis=1),
                           np.concatenate([Ly, Ly, Hy, Hy], axis=1))
            ok[j] &= shadows.covers_spans(owner[j], a, b)
        return ok


class _LineIndex:
    """Node indices of the corners grouped by one integer coordinate (a row or a column)."""

    def __init__(self, key: np.ndarray, first: int) -> None:
        order = np.argsort(key, kind="stable")
        self.nodes = first + order
        self.key = key[order]

    def at(self, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(k, node)`` of the corners whose coordinate is ``values[k]``."""
        a = np.searchsorted(self.key, values, side="left")
        b = np.searchsorted(self.key, values, side="right")
        counts = b - a
        total = int(counts.sum())
        k = np.repeat(np.arange(len(values)), counts)
        row = np.repeat(a - (np.cumsum(counts) - counts), counts) + np.arange(total)
        return k, self.nodes[row]


class GridLines:
    """Segments that run along a grid line (both ends on one horizontal or vertical lattice
    line): exact counts, by prefix sums per line, of the unit edges between two blocked cells
    they run along and of the double corners strictly inside them. Such a segment enters no
    cell interior, so no wedge hides it; the rule refuses it when a count is not 0
    (:meth:`blocked` counts only the edges it covers whole, so it never refuses a free one).
    The map's outside counts as blocked, as in the rule.

    A line's prefix sums are computed the first time a segment on it is asked about; the
    tables are allocated whole but untouched pages take no memory, so what a search uses
    grows with the lines it meets, not with the map's area."""

    def __init__(self, padded: np.ndarray) -> None:
        self.pad = padded  # padded[iy + 1, ix + 1]
        H, W = padded.shape[0] - 2, padded.shape[1] - 2
        self.H, self.W = H, W
        # row Y: edge x lies between cells (x, Y - 1) and (x, Y); vertex x is (x, Y)
        self.edge_h = np.zeros((H + 1, W + 1), np.int32)
        self.double_h = np.zeros((H + 1, W + 2), np.int32)
        # column X: edge y lies between cells (X - 1, y) and (X, y); vertex y is (X, y)
        self.edge_v = np.zeros((W + 1, H + 1), np.int32)
        self.double_v = np.zeros((W + 1, H + 2), np.int32)
        self.done_h = np.zeros(H + 1, dtype=bool)
        self.done_v = np.zeros(W + 1, dtype=bool)

    @staticmethod
    def _double(bl, br, tl, tr):
        return (bl & tr & ~br & ~tl) | (br & tl & ~bl & ~tr)

    def _rows(self, Y: np.ndarray) -> None:
        Y = np.unique(Y[~self.done_h[Y]])
        if Y.size == 0:
            return
        pad = self.pad
        below, above = pad[Y], pad[Y + 1]                      # (m, W + 2)
        self.edge_h[Y, 1:] = np.cumsum(below[:, 1:-1] & above[:, 1:-1], axis=1)
        self.double_h[Y, 1:] = np.cumsum(self._double(below[:, :-1], below[:, 1:], above[:, :-1], above[:, 1:]), axis=1)
        self.done_h[Y] = True

    def _cols(self, X: np.ndarray) -> None:
        X = np.unique(X[~self.done_v[X]])
        if X.size == 0:
            return
        pad = self.pad
        left, right = pad[:, X].T, pad[:, X + 1].T             # (m, H + 2)
        self.edge_v[X, 1:] = np.cumsum(left[:, 1:-1] & right[:, 1:-1], axis=1)
        self.double_v[X, 1:] = np.cumsum(self._double(left[:, :-1], right[:, :-1], left[:, 1:], right[:, 1:]), axis=1)
        self.done_v[X] = True

    def blocked(self, A: np.ndarray, V: np.ndarray) -> np.ndarray:
        """Whether the segments ``A[i] -> V[i]`` (grid units, inside the map) lie on one grid
        line and run along an edge between two blocked cells or through a double corner (then
        the rule refuses them)."""
        out = np.zeros(len(V), dtype=bool)
        for along, across, top in ((0, 1, self.H), (1, 0, self.W)):
            on = A[:, across]
            k = np.nonzero((V[:, across] == on) & (on == np.floor(on)) & (on >= 0) & (on <= top))[0]
            if k.size == 0:
                continue
            line = on[k].astype(np.int64)
            lo = np.minimum(V[k, along], A[k, along])
            hi = np.maximum(V[k, along], A[k, along])
            e0, e1 = np.ceil(lo).astype(np.int64), np.floor(hi).astype(np.int64)
            d0, d1 = np.floor(lo).astype(np.int64) + 1, np.ceil(hi).astype(np.int64)
            e1 = np.maximum(e1, e0)
            d1 = np.maximum(d1, d0)
            if along == 0:
                self._rows(line)
                edge, double = self.edge_h, self.double_h
            else:
                self._cols(line)
                edge, double = self.edge_v, self.double_v
            n_edge = edge[line, e1] - edge[line, e0]
            n_double = double[line, d1] - double[line, d0]
            out[k] = (n_edge > 0) | (n_double > 0)
        return out
