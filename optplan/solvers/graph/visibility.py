"""Exact any-angle shortest paths on grids: a visibility graph over convex corners.

Under the segment rule of DESIGN.md a shortest path is a polyline whose inner
vertices are *convex obstacle corners*: lattice vertices where exactly one of
the four surrounding cells is blocked (the outside of the map counts as
blocked). Double corners are never on a path (the rule forbids passing through
them) and concave corners are never bent around. An edge between two corners is
kept only when its line is tangent to the blocked cell at both ends (a taut path
never cuts into the obstacle it wraps), and when ``segments_free`` — the one
exact rule, int64-exact for corners and cell centres — says it is free. A* with
the Euclidean heuristic over this graph, generating edges lazily as nodes are
expanded, gives the exact optimum.

Start and goal are used exactly as given: they are nodes 0 and 1 of the
graph, joined to any corner they see (a taut path may leave them in any
direction), so the length is the exact any-angle optimum between the requested
points. ``points="centres"`` / ``"corners"`` only check that the points follow
that convention (cell centres, as the metaheuristics produce; lattice vertices,
as the Anya / GPPC benchmarks use); nothing is moved.

Memory: ``segments_free`` checks its segments in blocks of bounded total length
(``geometry.SPAN_BUDGET`` cells), and the samples of the cheap rejection come in
blocks (:data:`SAMPLE_BUDGET`), so memory is linear in the number of corners; no
allocation grows with the product of the number of corners and the map size.

Speed: at an expanded corner only taut continuations are candidates (the
blocked cell inside the turn, :func:`_taut`), and candidates that a sample
shows to cross a blocked cell are dropped before the exact rule runs
(:func:`_surely_blocked`); both prunings keep the search exact. The default search
(:func:`_astar_tiled`) also looks for candidates only where one may be seen: corner tiles
inside the bound's ellipse and the turn's quadrant, beyond the wedges that near blocked
cells hide (:mod:`optplan.solvers.graph.shadows`), and computes the edges of the nodes at
the top of the heap in one vectorised batch. It finds the same edges as the reference
search over every corner (:func:`_astar_over_corners`, ``search="scan"``), so the same
path: its work per expansion grows with what the node may see, not with the map
(a 512 x 512 map with 20 % blocked cells: ~2 s instead of ~15 s).
"""
from __future__ import annotations

import heapq

import numpy as np

from ...errors import InfeasibleQueryError, ParameterError
from ...world.geometry import convex_corners, segments_free
from ...world.shadows import DIST_SLACK, CornerTiles, GridLines, Shadows, direction, taut_regions

POINT_MODES = ("exact", "centres", "corners")


def _tangent(d: np.ndarray, quadrant: np.ndarray) -> np.ndarray:
    """The line through a corner with direction ``d`` does not enter the open blocked
    quadrant (nor, extended, the opposite one that mirrors it): it only touches."""
    s = np.sign(d)
    axis = (s[:, 0] == 0) | (s[:, 1] == 0)
    same = (s[:, 0] == quadrant[:, 0]) & (s[:, 1] == quadrant[:, 1])
    opposite = (s[:, 0] == -quadrant[:, 0]) & (s[:, 1] == -quadrant[:, 1])
    return axis | ~(same | opposite)


class _EdgeRule:
    """The segment rule for the graph's edges, nodes 0 and 1 being start and goal.

    Without clearance, edges between corners are integer-exact; edges at an end point
    are checked by :meth:`end_segments_free`. With a clearance every edge is checked by
    the exact rule with that clearance (no node then lies on a cell boundary).
    """

    def __init__(self, grid, clearance: float = 0.0):
        self.grid, self.clearance = grid, float(clearance)

    def check(self, P: np.ndarray, u: int, J: np.ndarray) -> np.ndarray:
        """Visibility from node ``u`` to nodes ``J`` (grid units)."""
        ok = np.zeros(len(J), dtype=bool)
        at_end = (J < 2) | (u < 2)
        if self.clearance > 0:
            at_end[:] = False
        if (~at_end).any():
            A = self.grid.to_world(np.broadcast_to(P[u], (int((~at_end).sum()), 2)))
            ok[~at_end] = segments_free(self.grid, A, self.grid.to_world(P[J[~at_end]]), self.clearance)
        if at_end.any():
            sel = np.nonzero(at_end)[0]
            end = np.where(J[sel] < 2, J[sel], u)
            other = np.where(J[sel] < 2, u, J[sel])
            ok[sel] = self.end_segments_free(P[end], P[other])
        return ok

    def check_pairs(self, P: np.ndarray, I: np.ndarray, J: np.ndarray) -> np.ndarray:
        """Visibility from nodes ``I`` to nodes ``J`` (pairwise; :meth:`check` for many ``u``)."""
        ok = np.zeros(len(J), dtype=bool)
        at_end = (J < 2) | (I < 2)
        if self.clearance > 0:
            at_end[:] = False
        if (~at_end).any():
            k = ~at_end
            ok[k] = segments_free(self.grid, self.grid.to_world(P[I[k]]), self.grid.to_world(P[J[k]]), self.clearance)
        if at_end.any():
            sel = np.nonzero(at_end)[0]
            end = np.where(J[sel] < 2, J[sel], I[sel])
            other = np.where(J[sel] < 2, I[sel], J[sel])
            ok[sel] = self.end_segments_free(P[end], P[other])
        return ok

    def end_segments_free(self, E: np.ndarray, V: np.ndarray) -> np.ndarray:
        """The rule (no clearance) for segments from end points ``E`` to nodes ``V`` (grid units).

        A segment from a point off the half-cell lattice to a cell corner ends at the
        corner of a blocked cell, and the rule's float arithmetic may put the last
        1e-16 of it inside that cell. So a segment that reaches a lattice vertex ``v``
        off an axis is split where it is surely inside the cell next to ``v``: the piece
        from ``v`` lies in that open cell (it must be free), the rest is checked by the
        rule away from any cell boundary.
        """
        A, B = self.grid.to_world(E), self.grid.to_world(V)
        d = E - V
        split = np.all(V == np.round(V), axis=1) & np.all(d != 0, axis=1) & ~np.all(2 * E == np.round(2 * E), axis=1)
        ok = np.zeros(len(E), dtype=bool)
        if (~split).any():
            ok[~split] = segments_free(self.grid, A[~split], B[~split])
        if split.any():
            k = np.nonzero(split)[0]
            dk, vk = d[k], V[k]
            t = 0.5 * np.minimum(1.0, 1.0 / np.abs(dk).max(axis=1))   # half way to the first lattice line
            cell = (vk + np.where(dk > 0, 0, -1)).astype(np.int64)     # the cell next to v towards the end
            mid = self.grid.to_world(vk + t[:, None] * dk)
            ok[k] = ~self.grid.blocked_cells(cell) & segments_free(self.grid, A[k], mid)
        return ok


def corner_nodes(grid, clearance: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Graph nodes (grid units) and their blocked quadrants: the convex corners, or with a
    clearance ``c`` the corners of the blocked cells grown by ``c`` as squares (each convex
    corner moved ``c`` away from its blocked cell along both axes), kept where they keep
    ``c`` from every obstacle and the border."""
    corners, quad = convex_corners(grid)
    if clearance <= 0 or len(corners) == 0:
        return corners, quad
    nodes = corners - quad * (clearance / grid.resolution)
    keep = grid.is_free(grid.to_world(nodes), clearance)
    return nodes[keep], quad[keep]


def _taut(a: np.ndarray, b: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Whether the path ``p -> u -> v`` can be locally shortest at corner ``u``: the blocked
    cell (diagonal direction ``w`` from ``u``) lies inside the turn, between the rays back
    to ``p`` (``a = p - u``) and on to ``v`` (rows of ``b = v - u``); a straight pass is kept.

    Pruning the other edges at expansion is exact: if ``p -> u -> v`` bends the wrong
    way, cutting the corner is shorter, so ``v`` is reached more cheaply without ``u``,
    whichever of ``u``'s shortest predecessors is recorded (they all arrive at the same
    cost)."""
    a, w = np.asarray(a), np.asarray(w)  # (2,) for all rows of b, or one row per row of b
    cab = a[..., 0] * b[:, 1] - a[..., 1] * b[:, 0]
    caw = a[..., 0] * w[..., 1] - a[..., 1] * w[..., 0]
    cwb = w[..., 0] * b[:, 1] - w[..., 1] * b[:, 0]
    inside = (np.sign(caw) == np.sign(cab)) & (np.sign(cwb) == np.sign(cab)) & (cab != 0)
    straight = (cab == 0) & (a[..., 0] * b[:, 0] + a[..., 1] * b[:, 1] < 0)
    return inside | straight


# distances (cells) from the expanded node at which candidate segments are sampled: every
# half cell up to 8 cells, then sparser (clutter blocks most candidates near the node)
SAMPLE_STEPS = np.r_[np.arange(0.5, 8.01, 0.5), np.arange(9.0, 16.01, 1.0), 2.0 ** np.arange(4.5, 11.01, 0.5)]
SAMPLE_BUDGET = 1_000_000  # sample points per block
SAMPLE_STAGES = ((0.0, 3.0), (3.0, 8.5), (8.5, 32.0), (32.0, np.inf))
ONE_PASS_SAMPLES = 20_000  # up to this many samples in all, every step in one lookup


def _surely_blocked(grid, origin: np.ndarray, D: np.ndarray, length: np.ndarray,
                    steps: np.ndarray | None = None) -> np.ndarray:
    """A cheap, safe rejection: a point of the segment ``origin + t D`` (``0 < t < 1``;
    ``origin`` one point, or one per segment),
    at one of :data:`SAMPLE_STEPS` cells from ``origin``, lies inside a blocked cell at
    least 1e-6 cells from its border, so the segment enters a blocked interior whatever
    the rounding. Segments it does not reject still get the exact rule. The steps are
    tried in stages (near ones first, on every candidate; farther ones on the survivors),
    each stage one vectorised lookup, in blocks of :data:`SAMPLE_BUDGET` samples.
    ``steps``: other distances than :data:`SAMPLE_STEPS`, sampled in one pass."""
    out = np.zeros(len(D), dtype=bool)
    if steps is not None:
        k = np.nonzero(length > 1e-6)[0]
        if len(k) == 0:
            return out
        steps = steps[steps < length[k].max()]  # a step past every end samples nothing
        rows = max(1, SAMPLE_BUDGET // max(len(steps), 1))
        for a in range(0, len(k) if len(steps) else 0, rows):
            b = k[a:a + rows]
            out[b] = _sample_hits(grid, origin if origin.ndim == 1 else origin[b], D[b], length[b], steps)
        return out
    if len(D) * len(SAMPLE_STEPS) <= ONE_PASS_SAMPLES:
        # few candidates: one lookup of every step costs less than the stages' calls (a
        # step beyond a segment's end is masked off by t < 1, as in the stages; segments
        # of no length are skipped, as there)
        k = np.nonzero(length > 1e-6)[0]
        if len(k):
            out[k] = _sample_hits(grid, origin if origin.ndim == 1 else origin[k], D[k], length[k], SAMPLE_STEPS)
        return out
    live = np.arange(len(D))
    for lo, hi in SAMPLE_STAGES:
        S = SAMPLE_STEPS[(SAMPLE_STEPS >= lo) & (SAMPLE_STEPS < hi)]
        live = live[length[live] > lo + 1e-6] if len(live) else live
        if len(S) == 0 or len(live) == 0:
            continue
        step = max(1, SAMPLE_BUDGET // len(S))
        for a in range(0, len(live), step):
            k = live[a:a + step]
            out[k] = _sample_hits(grid, origin if origin.ndim == 1 else origin[k], D[k], length[k], S)
        live = live[~out[live]]
    return out


def _sample_hits(grid, origin, D, length, S) -> np.ndarray:
    t = S[None, :] / length[:, None]                      # (m, s); length > 0 here
    on = t < 1.0 - 1e-9
    ox, oy = (origin[0], origin[1]) if origin.ndim == 1 else (origin[:, 0:1], origin[:, 1:2])
    qx = ox + t * D[:, 0:1]
    qy = oy + t * D[:, 1:2]
    cx, cy = np.floor(qx), np.floor(qy)
    fx, fy = qx - cx, qy - cy
    deep = on & (fx > 1e-6) & (fx < 1 - 1e-6) & (fy > 1e-6) & (fy < 1 - 1e-6)
    pad = grid.padded  # padded[iy + 1, ix + 1]; samples lie in the map, clipping only guards rounding
    # two ufuncs, not np.clip: its Python wrapper costs more than the work on these blocks
    ix = np.minimum(np.maximum(cx.astype(np.int64) + 1, 0), grid.width + 1)
    iy = np.minimum(np.maximum(cy.astype(np.int64) + 1, 0), grid.height + 1)
    return np.any(deep & pad[iy, ix], axis=1)


def _search_start(P: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, list]:
    """The A* state over nodes ``P`` (``0`` the start, ``1`` the goal): distances, predecessors,
    closed flags, the Euclidean heuristic to the goal and the heap holding the start."""
    n = len(P)
    dist = np.full(n, np.inf)
    pred = np.full(n, -1, dtype=np.int64)
    closed = np.zeros(n, dtype=bool)
    h = np.hypot(*(P - P[1]).T)
    dist[0] = 0.0
    return dist, pred, closed, h, [(h[0], 0)]


def _astar_over_corners(rule: _EdgeRule, P: np.ndarray, Q: np.ndarray,
                        bound: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
    """A* from node 0 to node 1 over the corner visibility graph with lazy edges.

    Edges out of a node are generated only when it is expanded: every open node
    whose line from it is tangent at both ends (quadrant ``(0, 0)`` = any direction),
    that makes a taut turn at the expanded corner (:func:`_taut`) and whose tentative
    cost can still improve is a candidate; candidates that a few samples show to cut
    a blocked cell are dropped (:func:`_surely_blocked`) and the rest are checked in
    one vectorised ``segments_free`` call. The Euclidean heuristic is consistent, so
    the first time the goal is expanded its distance is optimal.

    ``bound`` (grid units): the length of a known path from start to goal; a node whose
    ``f = g + h`` exceeds it cannot be on a shortest path, so it is not made a candidate.
    """
    dist, pred, closed, h, heap = _search_start(P)
    anydir = np.all(Q == 0, axis=1)
    # the corners (nodes 2..) are sorted by x: with a bound, the candidates of a node lie in
    # the ellipse |v - u| + |v - goal| <= bound - dist[u], inside an x-range of the corners
    xs = P[2:, 0]
    assert np.all(xs[:-1] <= xs[1:]), "corners must be sorted by x"
    ends = np.array([0, 1])
    while heap:
        _, u = heapq.heappop(heap)
        if closed[u]:
            continue
        closed[u] = True
        if u == 1:
            break
        if np.isfinite(bound):
            a = 0.5 * (bound - dist[u]) * (1 + 1e-12) + 1e-9
            cx = 0.5 * (P[u, 0] + P[1, 0])
            lo, hi = 2 + np.searchsorted(xs, cx - a, "left"), 2 + np.searchsorted(xs, cx + a, "right")
        else:
            lo, hi = 2, len(P)
        idx = np.concatenate([ends, np.arange(lo, hi)])
        d = P[idx] - P[u]
        step = np.hypot(d[:, 0], d[:, 1])
        reach = dist[u] + step
        keep = ~closed[idx] & (reach < dist[idx]) & (reach + h[idx] <= bound * (1 + 1e-12) + 1e-9)
        J, d, step = idx[keep], d[keep], step[keep]
        if not anydir[u]:
            k = _tangent(d, np.broadcast_to(Q[u], d.shape))
            if pred[u] >= 0:
                k[k] = _taut(P[pred[u]] - P[u], d[k], Q[u])
            J, d, step = J[k], d[k], step[k]
        k = anydir[J] | _tangent(d, Q[J])
        k[k] = ~_surely_blocked(rule.grid, P[u], d[k], step[k])
        J, step = J[k], step[k]
        if J.size == 0:
            continue
        k = rule.check(P, u, J)
        J, nd = J[k], dist[u] + step[k]
        better = nd < dist[J]
        J, nd = J[better], nd[better]
        dist[J] = nd
        pred[J] = u
        for j, v in zip(J.tolist(), (nd + h[J]).tolist()):
            heapq.heappush(heap, (v, j))
    return dist, pred


# the sampled rejection of the batched search: every half cell to 64 cells (beyond its
# shadows' reach a candidate lies in a narrow gap between them, which clutter soon closes),
# then sparser
TILED_SAMPLE_STEPS = np.r_[np.arange(0.5, 64.01, 0.5), 2.0 ** np.arange(6.25, 12.01, 0.25)]
# nodes whose edges one batch computes: the expanded one and up to BATCH - 1 others from the
# top SPECULATE_SCAN entries of the heap (the next ones to be expanded, most likely)
BATCH = 24
SPECULATE_SCAN = 48


class _Visible:
    """The visibility part of :func:`_astar_tiled`: for a batch of nodes, the edges out of
    each that the search over every corner (:func:`_astar_over_corners`) would find when
    expanding it with the present distances and predecessors, computed in one vectorised pass.

    For each node the candidates come from the corner tiles that may hold one
    (:class:`~optplan.solvers.graph.shadows.CornerTiles`) and the corners on its grid lines;
    the filters of the full search follow (not closed, an improvement, inside the ellipse of
    the bound, tangent at both ends, taut at the node), then three safe rejections (a near
    blocked cell's wedge, :class:`~optplan.solvers.graph.shadows.Shadows`; an edge between
    two blocked cells along a grid line, :class:`~optplan.solvers.graph.shadows.GridLines`;
    a sample deep inside a blocked cell, :func:`_surely_blocked`) and the exact rule on the
    rest (:meth:`_EdgeRule.check_pairs`)."""

    def __init__(self, rule: _EdgeRule, P: np.ndarray, Q: np.ndarray, h: np.ndarray, bound: float) -> None:
        self.rule, self.P, self.Q, self.h, self.bound = rule, P, Q, h, bound
        self.anydir = np.all(Q == 0, axis=1)
        self.tiles = CornerTiles(P[2:], first=2, lattice=rule.clearance == 0)
        self.lines = GridLines(rule.grid.padded)
        self.limit = bound * (1 + 1e-12) + 1e-9

    def edges(self, U: np.ndarray, dist: np.ndarray, pred: np.ndarray,
              closed: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        """``(J, step)`` per node of ``U``: the nodes it sees that the full search would keep
        at its expansion now, and their distances (grid units)."""
        P, Q, h = self.P, self.Q, self.h
        B = len(U)
        Pu = P[U]
        du, pu = dist[U], pred[U]
        has = pu >= 0
        a = np.where(has[:, None], P[np.maximum(pu, 0)] - Pu, 0.0)
        turn, quadrant, n = taut_regions(a, Q[U])
        turn &= has & ~self.anydir[U]
        quadrant = np.where(turn[:, None], quadrant, 0)
        shadows = Shadows(self.rule.grid.occ, Pu, quadrant)
        budget = self.bound - du
        owner, J = self.tiles.candidates(Pu, P[1], budget, shadows, turn, quadrant, n)
        on_row, on_col = self.tiles.lines_through(Pu)
        if on_row.any() or on_col.any():
            # the corners on the grid lines through a node come from the line index, once
            off = ~((on_row[owner] & (P[J, 1] == Pu[owner, 1])) | (on_col[owner] & (P[J, 0] == Pu[owner, 0])))
            lo, lj = self.tiles.on_lines(Pu, on_row, on_col)
            owner, J = np.concatenate([owner[off], lo]), np.concatenate([J[off], lj])
        ar = np.arange(B)
        owner = np.concatenate([ar, ar, owner])
        J = np.concatenate([np.zeros(B, dtype=np.int64), np.ones(B, dtype=np.int64), J])
        d = P[J] - Pu[owner]
        step = np.hypot(d[:, 0], d[:, 1])
        reach = du[owner] + step
        k = np.nonzero(~closed[J] & (reach < dist[J]) & (reach + h[J] <= self.limit))[0]
        owner, J, d, step = owner[k], J[k], d[k], step[k]
        # tangent at the node and taut there, then tangent at the other end
        uo = U[owner]
        ok = self.anydir[uo] | _tangent(d, Q[uo])
        t = np.nonzero(ok & has[owner])[0]
        if t.size:
            ok[t] = self.anydir[uo[t]] | _taut(a[owner[t]], d[t], Q[uo[t]])
        ok &= self.anydir[J] | _tangent(d, Q[J])
        k = np.nonzero(ok)[0]
        owner, J, d, step = owner[k], J[k], d[k], step[k]
        if not shadows.empty and len(J):
            # beyond every near cell: the union of the wedges
            f = np.nonzero(step > shadows.reach[owner] + DIST_SLACK)[0]
            if f.size:
                k = np.ones(len(J), dtype=bool)
                k[f[shadows.covers(owner[f], direction(d[f]))]] = False
                owner, J, d, step = owner[k], J[k], d[k], step[k]
        k = np.nonzero(~self.lines.blocked(Pu[owner], P[J]))[0]
        owner, J, d, step = owner[k], J[k], d[k], step[k]
        k = np.nonzero(~_surely_blocked(self.rule.grid, Pu[owner], d, step, TILED_SAMPLE_STEPS))[0]
        owner, J, d, step = owner[k], J[k], d[k], step[k]
        if not shadows.empty and len(J):
            # nearer: cell by cell (what the samples missed: segments that clip a cell)
            f = np.nonzero(step <= shadows.reach[owner] + DIST_SLACK)[0]
            if f.size:
                k = np.ones(len(J), dtype=bool)
                k[f[shadows.hides(owner[f], direction(d[f]), step[f])]] = False
                owner, J, step = owner[k], J[k], step[k]
        if len(J):
            k = np.nonzero(self.rule.check_pairs(P, U[owner], J))[0]
            owner, J, step = owner[k], J[k], step[k]
        order = np.argsort(owner, kind="stable")
        owner, J, step = owner[order], J[order], step[order]
        cut = np.searchsorted(owner, np.arange(B + 1))
        return [(J[cut[i]:cut[i + 1]], step[cut[i]:cut[i + 1]]) for i in range(B)]


class CornerNeighbours:
    """The corner graph of a grid map (node 0 the start, 1 the goal, then the corners of
    :func:`corner_nodes`) with each node's edges found when first asked for, by the pruning
    of the tiled search (:class:`_Visible`): every node ``v`` that node ``u`` sees, the line
    tangent at both ends, with ``|u - v| + |v - goal| <= bound`` (metres; the ellipse of a
    search bounded by ``bound``, taken from ``u``). For searches whose states are not the
    corners themselves (the shortest path in a homotopy class): no edge of the whole graph
    is computed ahead, so large cluttered maps cost what the search visits."""

    def __init__(self, grid, start, goal, clearance: float = 0.0, bound: float = np.inf) -> None:
        self.grid = grid
        rule = _EdgeRule(grid, clearance)
        nodes, quad = corner_nodes(grid, rule.clearance)
        P = np.vstack([grid.to_grid(np.asarray(start, float)[None]), grid.to_grid(np.asarray(goal, float)[None]),
                       nodes])
        Q = np.vstack([[0, 0], [0, 0], quad]).astype(np.int64)
        self.points = grid.to_world(P)
        self.points[0], self.points[1] = start, goal
        self._vis = _Visible(rule, P, Q, np.hypot(*(P - P[1]).T), float(bound) / grid.resolution)
        self._dist = np.full(len(P), np.inf)
        self._pred = np.full(len(P), -1, dtype=np.int64)
        self._closed = np.zeros(len(P), dtype=bool)
        self._edges: dict[int, tuple[np.ndarray, np.ndarray]] = {}

    def __call__(self, u: int) -> tuple[np.ndarray, np.ndarray]:
        """Neighbours of node ``u`` and the edge lengths, metres."""
        got = self._edges.get(u)
        if got is None:
            self._dist[u] = 0.0
            J, step = self._vis.edges(np.array([u]), self._dist, self._pred, self._closed)[0]
            self._dist[u] = np.inf
            got = self._edges[u] = (J[J != u], step[J != u] * self.grid.resolution)
        return got


def _astar_tiled(rule: _EdgeRule, P: np.ndarray, Q: np.ndarray,
                 bound: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
    """The search of :func:`_astar_over_corners` (the same graph, the same order of
    expansions, the same distances and predecessors) with the edges of a node found by
    :class:`_Visible`, which looks only where a visible taut continuation may lie, and in
    batches: when a node is expanded, the edges of the nodes at the top of the heap are
    computed with its own, with their present distance and predecessor, and used when such
    a node is expanded with the same distance and predecessor (otherwise computed again).
    The filters that change as the search goes on (closed, an improvement) only tighten, so
    applying them again at the expansion gives the edges a computation then would give.

    Nodes ``0``/``1`` are start and goal, ``2..`` the corners (any order).
    """
    dist, pred, closed, h, heap = _search_start(P)
    vis = _Visible(rule, P, Q, h, bound)
    ahead: dict[int, tuple[int, float, np.ndarray, np.ndarray]] = {}
    while heap:
        _, u = heapq.heappop(heap)
        if closed[u]:
            continue
        closed[u] = True
        if u == 1:
            break
        got = ahead.pop(u, None)
        if got is not None and got[0] == pred[u] and got[1] == dist[u]:
            J, step = got[2], got[3]
        else:
            batch, seen = [u], {u}
            for _, v in heap[:SPECULATE_SCAN]:
                if len(batch) >= BATCH:
                    break
                if v in seen or v == 1 or closed[v]:
                    continue
                seen.add(v)
                old = ahead.get(v)
                if old is not None and old[0] == pred[v] and old[1] == dist[v]:
                    continue
                batch.append(v)
            U = np.asarray(batch, dtype=np.int64)
            found = vis.edges(U, dist, pred, closed)
            for v, (Jv, sv) in zip(batch[1:], found[1:]):
                ahead[v] = (int(pred[v]), float(dist[v]), Jv, sv)
            J, step = found[0]
        nd = dist[u] + step
        better = ~closed[J] & (nd < dist[J])
        J, nd = J[better], nd[better]
        dist[J] = nd
        pred[J] = u
        for j, v in zip(J.tolist(), (nd + h[J]).tolist()):
            heapq.heappush(heap, (v, j))
    return dist, pred


def _check_mode(grid, points: str, ends) -> None:
    if points not in POINT_MODES:
        raise ParameterError(f"points must be one of {', '.join(POINT_MODES)}, got {points!r}")
    if points == "exact":
        return
    for p, what in zip(ends, ("start", "goal")):
        q = grid.to_grid(p)
        snapped = np.floor(q) + 0.5 if points == "centres" else np.round(q)
        if not np.allclose(q, snapped, rtol=0.0, atol=1e-9):
            where = "the centre of a cell" if points == "centres" else "a lattice vertex (a cell corner)"
            raise ParameterError(
                f"points={points!r}: the {what} ({p[0]:g}, {p[1]:g}) is not {where}; start and goal are never "
                f"moved, so pass {tuple(float(v) for v in grid.to_world(snapped))} or points='exact'")


def _upper_bound(grid, s, g, clearance: float) -> float:
    """Length (grid units) of the A* path over cell centres after direct-connection
    pruning, a free any-angle path, so no shorter than the optimum without clearance;
    ``inf`` with a clearance (the corner graph of the grown cells can be longer than that
    path) or when A* finds none."""
    if clearance > 0:
        return np.inf
    from .astar import cell_path
    from ..gridpath.moves import WINDOW_CELLS

    from ...world.postprocess import prune_direct

    # scipy's compiled Dijkstra: the same optimal length as the scalar A* loop, 10x faster on
    # large maps; beyond WINDOW_CELLS its sparse matrix (~20 bytes a cell) is left to A*
    method = "dijkstra" if grid.width * grid.height <= WINDOW_CELLS else "astar"
    try:
        P = cell_path(grid, s, g, method=method).path
    except InfeasibleQueryError:
        return np.inf
    # direct-connection pruning keeps it free (the exact rule) and shortens it towards the
    # optimum: a tighter bound leaves fewer corners in the search's ellipse
    P = prune_direct(grid, P)
    return float(np.hypot(*np.diff(P, axis=0).T).sum()) / grid.resolution


SEARCHES = ("tiled", "scan")


def visibility_path(grid, start, goal, points: str = "exact", *, clearance: float = 0.0, search: str = "tiled"):
    """Shortest any-angle path between two points given in world metres.

    The path starts at ``start`` and ends at ``goal`` exactly. ``points`` ("exact",
    "centres" or "corners") only checks that the points follow that convention.

    Without clearance the length is the exact any-angle optimum. With ``clearance``
    (metres) the nodes are the corners of the blocked cells grown by it as squares
    (:func:`corner_nodes`) and every edge is checked by the exact rule with that
    clearance: the path keeps the clearance, and it is longer than the true optimum
    around discs of that radius by at most the corners' cut (and it can miss a
    passage that only a diagonal gap just wider than twice the clearance leaves).

    ``search``: ``"tiled"`` (default, :func:`_astar_tiled`) or ``"scan"``, the reference
    search that looks at every corner on every expansion (:func:`_astar_over_corners`, kept
    for checks and benchmarks): the same graph and the same optimum, the scan much slower on
    large maps.

    Returns ``(path_in_metres, length_in_metres)``; raises InfeasibleQueryError if the goal
    cannot be reached, ParameterError for a point off the requested convention.
    """
    if search not in SEARCHES:
        raise ParameterError(f"search must be one of {', '.join(SEARCHES)}, got {search!r}")
    s, g = np.asarray(start, float), np.asarray(goal, float)
    _check_mode(grid, points, (s, g))
    rule = _EdgeRule(grid, clearance)
    if bool(segments_free(grid, s, g, rule.clearance)):
        return np.stack([s, g]), float(np.hypot(*(g - s)))
    nodes, quad = corner_nodes(grid, rule.clearance)
    order = np.argsort(nodes[:, 0], kind="stable")
    nodes, quad = nodes[order], quad[order]
    # node 0 = start, 1 = goal, 2.. = corners; the end points take any direction
    P = np.vstack([grid.to_grid(s), grid.to_grid(g), nodes])
    Q = np.vstack([[0, 0], [0, 0], quad])
    bound = _upper_bound(grid, s, g, rule.clearance)
    if search == "scan":
        dist, pred = _astar_over_corners(rule, P, Q, bound)
    elif rule.clearance == 0 and not np.isfinite(bound):
        # without clearance A* over the cell centres finds a path whenever any free path
        # exists (a free path moves between free cells across a shared edge, or across a
        # shared corner where a third free cell joins them, as a double corner is never
        # passed; both are moves of the cell graph), so there is none: no search needed
        dist, pred = np.full(len(P), np.inf), np.full(len(P), -1, dtype=np.int64)
    else:
        dist, pred = _astar_tiled(rule, P, Q, bound)
    if not np.isfinite(dist[1]):
        raise InfeasibleQueryError(
            "the goal is unreachable from the start (no free any-angle path"
            + (f" over the corners of the obstacles grown by the clearance {clearance:g} m as squares; "
               "A* over cell centres may still find one" if rule.clearance > 0 else "")
            + "); check the map or choose another goal")
    chain = [1]
    while chain[-1] != 0:
        chain.append(int(pred[chain[-1]]))
    path = grid.to_world(P[chain[::-1]])
    path[0], path[-1] = s, g  # the very input values, not a round trip through grid units
    return path, float(dist[1]) * grid.resolution
