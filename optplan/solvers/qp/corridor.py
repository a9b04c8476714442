"""Safe corridors around a path: one free convex region per path piece.

A *piece* is the segment between two consecutive path points ``p_i -> p_{i+1}``.
For every piece of a collision-free path we build a convex region ``C_i`` that
contains the piece and no obstacle (with the clearance):

* grid maps: an axis-aligned box. It starts as the bounding box of the piece and
  grows outward one cell line at a time (all pieces at once) while the box,
  widened by the clearance on every side, still covers no blocked cell and stays
  inside the map; a summed-area table answers each "any blocked cell in this
  rectangle?" in O(1). Widening by the clearance in the max-norm is conservative,
  because Euclidean distance is at least max-norm distance.
* circle worlds: a trust box (the piece's bounding box widened by ``delta``,
  clipped to the map border minus the clearance) intersected with one half-plane
  per nearby circle. The half-plane of circle ``(c, R)`` is tangent to the
  circle grown by the clearance and has the unit normal ``n = (q - c)/|q - c|``,
  ``q`` the point of the piece closest to ``c``. Since ``q`` is the projection of
  ``c`` on the convex piece, every point ``x`` of the piece has
  ``n.(x - c) >= |q - c| >= R + clearance``, so the piece lies in the half-plane
  and the grown disc lies outside it. Only the ``K`` circles nearest to the
  piece's bounding box get a half-plane; ``delta`` is chosen so that every other
  circle stays out of the trust box (``delta * sqrt 2`` below its gap), so the
  region is free of *all* circles, not just the selected ones.

Why the smoothed path is then collision-free: the smoother constrains *both*
ends of piece ``i`` into ``C_i``; a point ``p_j`` is shared by pieces ``j-1`` and
``j`` and so must lie in ``C_{j-1} ∩ C_j``. Consecutive regions overlap because
both contain the seed point ``s_j``, so the constraints are satisfiable (the seed
itself is feasible). By convexity the whole new piece ``p_i -> p_{i+1}`` lies in
``C_i``, which is free, so every segment of the result is free by construction;
``validate_path`` confirms it exactly afterwards. A piece whose region cannot be
built (a grid piece whose bounding box, widened by the clearance, touches a
blocked cell even after splitting; more than ``K`` circles at its bounding box)
is *pinned*: both ends keep their seed positions, so it stays the valid seed
piece.

Regions are shrunk by a small ``cushion`` (metres) so that a solver that meets
its constraints only to about 1e-7 cannot place a point exactly on an obstacle
corner or a grown circle.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from ...world.derived import DerivedStore

_DERIVED = DerivedStore("solvers.qp.corridor")  # this module's data derived from worlds


@dataclass
class Corridor:
    """Convex regions of the pieces of ``points``, in the form the QP needs.

    Attributes:
        points: ``(N, 2)`` path points (metres) the regions were built around.
        lo, hi: ``(N, 2)`` box bounds of each point: the intersection of the boxes
            of the (one or two) pieces it belongs to; equal for fixed points
            (start, goal and the ends of pinned pieces).
        normals: ``(N-1, K, 2)`` half-plane normals of each piece (zero rows unused).
        offsets: ``(N-1, K)`` right-hand sides: both ends of piece ``i`` satisfy
            ``normals[i, k] . p >= offsets[i, k]`` (``-inf`` for unused slots).
        pinned: ``(N-1,)`` pieces whose ends are held at the seed.
    """

    points: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    normals: np.ndarray
    offsets: np.ndarray
    pinned: np.ndarray

    @property
    def n_points(self) -> int:
        return len(self.points)

    @property
    def k_slots(self) -> int:
        return self.normals.shape[1]


# ----------------------------------------------------------------- path points
def arc_positions(path: np.ndarray) -> np.ndarray:
    """Cumulative arc length at each vertex of a polyline, metres."""
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))])


def points_at(path: np.ndarray, s: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Points at arc lengths ``t`` along ``path`` (vertex arc lengths ``s``)."""
    return np.stack([np.interp(t, s, path[:, 0]), np.interp(t, s, path[:, 1])], axis=1)


def sample_for_corridor(world, path: np.ndarray, n: int, clearance: float = 0.0) -> np.ndarray:
    """``n`` points spread evenly by arc length along a valid ``path``, plus the
    path's own vertices wherever an even piece would cut a corner into an obstacle.

    Every piece of the result then lies on a (valid) seed segment or is itself
    checked free, so the corridor can be built around it.
    """
    P = np.asarray(path, dtype=float)
    s = arc_positions(P)
    if s[-1] == 0:
        return P[[0, -1]]
    t = np.linspace(0.0, s[-1], max(n, 2))
    X = points_at(P, s, t)
    X[0], X[-1] = P[0], P[-1]
    bad = ~np.asarray(world.segments_free(X[:-1], X[1:], clearance), dtype=bool)
    if bad.any():
        inner = s[1:-1]
        piece = np.clip(np.searchsorted(t, inner, side="right") - 1, 0, len(t) - 2)
        add = inner[bad[piece] & (inner > t[piece] + 1e-9 * s[-1]) & (inner < t[piece + 1] - 1e-9 * s[-1])]
        t = np.union1d(t, add)
        X = points_at(P, s, t)
        X[0], X[-1] = P[0], P[-1]
    return X


def _insert_on_pieces(points: np.ndarray, owner: np.ndarray, fractions: np.ndarray) -> np.ndarray:
    """Insert a point at fraction ``fractions[k]`` (0 < f < 1) of piece ``owner[k]``."""
    if not len(owner):
        return points
    new = points[owner] + fractions[:, None] * (points[owner + 1] - points[owner])
    order = np.argsort(np.concatenate([np.arange(len(points), dtype=float), owner + fractions]), kind="stable")
    return np.vstack([points, new])[order]


def grid_line_fractions(ga: np.ndarray, gb: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where segments ``ga[i] -> gb[i]`` (grid units) cross cell lines: ``(segment index, fraction)``.

    Between two consecutive crossings a segment stays inside one closed cell,
    which is free when the segment is, so its bounding box is free.
    """
    owners, fracs = [], []
    for axis in (0, 1):
        a, b = ga[:, axis], gb[:, axis]
        first = np.floor(np.minimum(a, b)) + 1
        count = np.maximum(np.ceil(np.maximum(a, b)) - first, 0).astype(np.int64)
        count[a == b] = 0
        seg = np.repeat(np.arange(len(a)), count)
        k = first[seg] + (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count))
        owners.append(seg)
        fracs.append((k - a[seg]) / (b[seg] - a[seg]))
    seg, f = np.concatenate(owners), np.concatenate(fracs)
    keep = (f > 1e-12) & (f < 1 - 1e-12)
    seg, f = seg[keep], f[keep]
    order = np.lexsort((f, seg))
    seg, f = seg[order], f[order]
    distinct = np.concatenate([[True], (np.diff(seg) != 0) | (np.diff(f) > 1e-12)]) if len(f) else np.zeros(0, bool)
    return seg[distinct], f[distinct]


# ----------------------------------------------------------------------- grids
class _BlockedCounter:
    """O(1) count of blocked cells in a cell rectangle; outside the map is blocked."""

    def __init__(self, grid) -> None:
        self.w, self.h = grid.width, grid.height
        padded = np.pad(grid.occ, 1, constant_values=True).astype(np.int64)
        self.table = np.zeros((padded.shape[0] + 1, padded.shape[1] + 1), dtype=np.int64)
        self.table[1:, 1:] = padded.cumsum(0).cumsum(1)

    def count(self, ix0, iy0, ix1, iy1) -> np.ndarray:
        """Blocked cells with ``ix0 <= ix <= ix1``, ``iy0 <= iy <= iy1`` (empty ranges count 0)."""
        empty = (ix1 < ix0) | (iy1 < iy0)
        x0 = np.clip(ix0, -1, self.w) + 1
        x1 = np.clip(ix1, -1, self.w) + 2
        y0 = np.clip(iy0, -1, self.h) + 1
        y1 = np.clip(iy1, -1, self.h) + 2
        T = self.table
        c = T[y1, x1] - T[y0, x1] - T[y1, x0] + T[y0, x0]
        return np.where(empty, 0, c)

    def box_free(self, E: np.ndarray) -> np.ndarray:
        """Whether the open interior of each box ``(x0, y0, x1, y1)`` (grid units) covers no blocked cell."""
        ix0 = np.floor(E[:, 0]).astype(np.int64)
        iy0 = np.floor(E[:, 1]).astype(np.int64)
        ix1 = np.ceil(E[:, 2]).astype(np.int64) - 1
        iy1 = np.ceil(E[:, 3]).astype(np.int64) - 1
        return self.count(ix0, iy0, ix1, iy1) == 0


def _counter(grid) -> _BlockedCounter:
    c = _DERIVED.of(grid).get("qp_blocked_counter")
    if c is None:
        c = _DERIVED.of(grid)["qp_blocked_counter"] = _BlockedCounter(grid)
    return c


def grid_boxes(grid, points: np.ndarray, clearance: float, max_cells: int, split: bool = True):
    """Free boxes of the pieces of ``points`` on a grid map.

    Returns ``(points, boxes, pinned)``: the points (with extra points where a
    piece's bounding box was not free and splitting it at cell lines helped),
    ``(N-1, 4)`` boxes ``(x0, y0, x1, y1)`` in metres, and the pinned pieces.
    """
    counter = _counter(grid)
    r = clearance / grid.resolution
    for _ in range(2):
        g = grid.to_grid(points)
        E = np.hstack([np.minimum(g[:-1], g[1:]) - r, np.maximum(g[:-1], g[1:]) + r])
        ok = counter.box_free(E)
        if ok.all() or not split:
            break
        bad = np.nonzero(~ok)[0]
        split = False  # one splitting pass; pieces still failing are pinned
        owner, fractions = grid_line_fractions(g[bad], g[bad + 1])
        points = _insert_on_pieces(points, bad[owner], fractions)
        # a crossing computed in floating point lands up to an ulp off its cell line, which
        # the exact rule can see as entering the neighbouring cell: put it on the line
        gp = grid.to_grid(points)
        line = np.round(gp)
        points = grid.to_world(np.where(np.abs(gp - line) < 1e-9, line, gp))
    pinned = ~ok
    # grow every free box outward, one cell line per side and step, all pieces at once
    for _ in range(max_cells):
        for side in range(4):
            cand = E.copy()
            cand[:, side] = np.floor(E[:, side]) + 1 if side >= 2 else np.ceil(E[:, side]) - 1
            take = ok & counter.box_free(cand)
            E[take] = cand[take]
    B = E + np.array([r, r, -r, -r])
    lo = grid.to_world(B[:, :2])
    hi = grid.to_world(B[:, 2:])
    return points, np.hstack([lo, hi]), pinned


# ---------------------------------------------------------------------- circles
def _closest_on_segments(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Closest point of each segment ``a[i] -> b[i]`` to each centre ``c[i, k]``: ``(n, k, 2)``."""
    ab = (b - a)[:, None, :]
    L2 = np.einsum("ikj,ikj->ik", ab, ab)
    t = np.einsum("ikj,ikj->ik", c - a[:, None, :], ab) / np.where(L2 > 0, L2, 1.0)
    return a[:, None, :] + np.clip(t, 0.0, 1.0)[..., None] * ab


def circle_regions(world, points: np.ndarray, clearance: float, k: int, max_step: float):
    """Trust boxes and tangent half-planes of the pieces of ``points`` in a circle world.

    Returns ``(boxes (N-1, 4), normals (N-1, K, 2), offsets (N-1, K), pinned (N-1,))`` with
    ``K = min(k, number of circles)``.
    """
    a, b = points[:-1], points[1:]
    n = len(a)
    bb_lo, bb_hi = np.minimum(a, b), np.maximum(a, b)
    xmin, ymin, xmax, ymax = world.bounds
    border_lo = np.array([xmin, ymin]) + clearance
    border_hi = np.array([xmax, ymax]) - clearance
    m = len(world.circles)
    kk = min(k, m)
    normals = np.zeros((n, kk, 2))
    offsets = np.full((n, kk), -np.inf)
    delta = np.full(n, float(max_step))
    pinned = np.zeros(n, dtype=bool)
    if kk:
        centres, grown = world.circles[:, :2], world.radii + clearance
        # distance of every centre to every piece's bounding box, minus the grown radius
        out = np.maximum(bb_lo[:, None, :] - centres[None], 0) + np.maximum(centres[None] - bb_hi[:, None, :], 0)
        gap = np.hypot(out[..., 0], out[..., 1]) - grown[None, :]
        order = np.argsort(gap, axis=1)
        near = order[:, :kk]
        if m > kk:
            next_gap = np.take_along_axis(gap, order[:, kk:kk + 1], axis=1)[:, 0]
            delta = np.minimum(delta, next_gap / np.sqrt(2.0))
            pinned = next_gap <= 0  # more than k circles reach the bounding box itself
            delta = np.maximum(delta, 0.0)
        c = centres[near]
        q = _closest_on_segments(a, b, c)
        v = q - c
        dist = np.hypot(v[..., 0], v[..., 1])
        normals[:] = v / np.where(dist > 0, dist, 1.0)[..., None]
        offsets[:] = np.einsum("ikj,ikj->ik", normals, c) + grown[near]
    lo = np.maximum(bb_lo - delta[:, None], border_lo)
    hi = np.minimum(bb_hi + delta[:, None], border_hi)
    return np.hstack([lo, hi]), normals, offsets, pinned


# ----------------------------------------------------------------------- build
def assemble(points: np.ndarray, boxes: np.ndarray, normals: np.ndarray, offsets: np.ndarray,
             pinned: np.ndarray, cushion: float) -> Corridor:
    """Per-point bounds from per-piece regions, shrunk by ``cushion``; ends and pinned pieces fixed."""
    N = len(points)
    mid = (boxes[:, :2] + boxes[:, 2:]) / 2
    boxes = boxes + np.array([cushion, cushion, -cushion, -cushion])
    # a box thinner than twice the cushion collapses to its mid-line, which is still inside it
    thin = boxes[:, 2:] < boxes[:, :2]
    boxes[:, :2] = np.where(thin, mid, boxes[:, :2])
    boxes[:, 2:] = np.where(thin, mid, boxes[:, 2:])
    lo = np.full((N, 2), -np.inf)
    hi = np.full((N, 2), np.inf)
    lo[:-1] = np.maximum(lo[:-1], boxes[:, :2])
    lo[1:] = np.maximum(lo[1:], boxes[:, :2])
    hi[:-1] = np.minimum(hi[:-1], boxes[:, 2:])
    hi[1:] = np.minimum(hi[1:], boxes[:, 2:])
    offsets = np.where(np.isfinite(offsets), offsets + cushion, offsets)
    fixed = np.zeros(N, dtype=bool)
    fixed[[0, -1]] = True
    fixed[:-1] |= pinned
    fixed[1:] |= pinned
    lo[fixed] = hi[fixed] = points[fixed]
    normals = normals.copy()
    # fixed points meet their half-planes by construction (they are seed points); never let the cushion cut them off
    for e in (0, 1):
        idx = np.nonzero(fixed[e:N - 1 + e])[0]
        if len(idx):
            val = np.einsum("ikj,ij->ik", normals[idx], points[idx + e])
            offsets[idx] = np.minimum(offsets[idx], val)
    offsets[pinned] = -np.inf
    normals[pinned] = 0.0
    return Corridor(points, lo, hi, normals, offsets, pinned)


def build_corridor(world, points: np.ndarray, clearance: float = 0.0, *, k: int = 6, max_cells: int = 3,
                   max_step: float = 1.0, cushion: float = 1e-5, split: bool = True) -> Corridor:
    """The corridor of a collision-free polyline ``points`` (see the module docstring).

    Args:
        world: GridMap or CircleWorld.
        points: ``(N, 2)`` path points, metres; the polyline must be valid.
        clearance: required distance to obstacles, metres.
        k: half-plane slots per piece (circle worlds).
        max_cells: how many cell lines a grid box may grow on each side.
        max_step: trust-box half-width around a piece (circle worlds), metres.
        cushion: regions shrink by this much, metres.
        split: on grids, split pieces whose bounding box is not free at cell lines.
    """
    P = np.asarray(points, dtype=float)
    if world.is_grid:
        P, boxes, pinned = grid_boxes(world, P, clearance, max_cells, split)
        normals = np.zeros((len(P) - 1, 0, 2))
        offsets = np.zeros((len(P) - 1, 0))
        return assemble(P, boxes, normals, offsets, pinned, cushion * world.resolution)
    boxes, normals, offsets, pinned = circle_regions(world, P, clearance, k, max_step)
    return assemble(P, boxes, normals, offsets, pinned, cushion)
