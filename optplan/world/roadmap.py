"""A sparse roadmap of a world: geodesic distances between obstacle corners, and h-signatures.

One :class:`Roadmap` per world and clearance, built on first use and kept in the world's
own cache (``Roadmap.of(world, clearance)``), serves two things:

* the general path encoding (:mod:`optplan.formulations.encodings`): any path is a chain of
  geodesic legs between roadmap nodes, so a continuous vector of via points decodes to a
  collision-free path in any corridor of any map;
* the shortest path in a homotopy (h-signature) class (:mod:`optplan.solvers.homotopy`).

Nodes. On a grid they are the convex obstacle corners (lattice vertices with exactly one
blocked cell around them, the map outside counting as blocked), moved ``clearance`` away
from their blocked cell along both axes, as the exact visibility planner uses them
(``solvers/graph/visibility.py``); a shortest path under the segment rule bends only there.
On a circle world they are the vertices of a regular polygon circumscribed about every
grown circle (``ring`` per circle), so the edge between two neighbouring vertices only
touches the circle; lengths are then at most ``1/cos(pi/ring) - 1`` longer than around the
true arc.

Edges join nodes that see each other under the one exact segment rule
(``world.segments_free``). On grids an edge is kept only when its line is tangent to the
blocked cell at both ends (a taut path never cuts into the corner it wraps), which keeps
every locally shortest path.

H-signature (Bhattacharya, Kumar, Likhachev 2012, §III): every obstacle component that does
not touch the border gets a representative point and a ray from it straight up (distinct x,
so rays never meet). The signature of a path is the vector of signed crossings of each ray
(+1 crossing left to right). Two paths with the same ends have the same signature exactly
when they wind the same way about every such component (the same homology class).
"""
from __future__ import annotations

import numpy as np

from ..checks import memory_budget
from ..errors import ParameterError
from .geometry import convex_corners
from .derived import DerivedStore

_DERIVED = DerivedStore("world.roadmap")  # this module's data derived from worlds

# grid maps with more convex corners than this are "large": all-pairs tables over the corners
# (the general encoding) and a roadmap of every edge (the homotopy search) would grow as
# corners squared there, so their users build what a run visits instead
ROADMAP_CORNERS = 2000
# segments checked per segments_free call (bounds the work arrays of the exact rule)
EDGE_CHUNK = 20_000
# circle worlds: polygon vertices per grown circle
DEFAULT_RING = 32


def _grid_corners(grid, clearance: float) -> tuple[np.ndarray, np.ndarray]:
    """Convex corners in metres and their blocked quadrant ``(sx, sy)``."""
    corners, quad = convex_corners(grid)
    nodes = corners - quad * (clearance / grid.resolution)
    P = grid.to_world(nodes)
    keep = grid.is_free(P, clearance) if clearance > 0 else np.ones(len(P), bool)
    # nodes on the map border are never on a shortest path (nothing to wrap around)
    return P[keep], quad[keep]


def _circle_ring(world, clearance: float, ring: int) -> tuple[np.ndarray, np.ndarray]:
    """Vertices of the circumscribed polygons that are free, and their outward unit normals."""
    C = world.circles[:, :2]
    R = (world.circles[:, 2] + world.safety + clearance) / np.cos(np.pi / ring) * (1 + 1e-9)
    ang = 2 * np.pi * (np.arange(ring) + 0.5) / ring
    u = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    P = (C[:, None, :] + R[:, None, None] * u[None]).reshape(-1, 2)
    N = np.broadcast_to(u[None], (len(C), ring, 2)).reshape(-1, 2)
    keep = world.is_free(P, clearance)
    return P[keep], N[keep]


# node pairs whose tautness is tested at once (bounds the pair arrays)
PAIR_BLOCK = 2_000_000


def _components(world, clearance: float) -> np.ndarray:
    """Representative points ``(K, 2)`` of the obstacle components that do not touch the border."""
    if world.is_grid:
        from scipy import ndimage

        occ = world.occ
        if clearance > 0:  # cells closer than twice the clearance act as one obstacle
            grow = int(np.ceil(clearance / world.resolution))
            occ = ndimage.binary_dilation(occ, np.ones((2 * grow + 1,) * 2, bool))
        labels, n = ndimage.label(occ, np.ones((3, 3), bool))  # diagonal contact joins (segment rule)
        if n == 0:
            return np.zeros((0, 2))
        edge = np.unique(np.concatenate([labels[0], labels[-1], labels[:, 0], labels[:, -1]]))
        reps = []
        iy, ix = np.nonzero(labels)
        lab = labels[iy, ix]
        order = np.lexsort((iy, ix, lab))
        first = order[np.r_[0, np.nonzero(np.diff(lab[order]))[0] + 1]]
        for k in first:
            if lab[k] in edge:
                continue
            reps.append((ix[k] + 0.5, iy[k] + 0.5))
        pts = world.to_world(np.asarray(reps, float).reshape(-1, 2))
    else:
        c = world.circles
        if not len(c):
            return np.zeros((0, 2))
        R = c[:, 2] + world.safety + clearance
        D = np.hypot(*(c[:, None, :2] - c[None, :, :2]).transpose(2, 0, 1))
        from scipy.sparse.csgraph import connected_components

        n, lab = connected_components(D <= R[:, None] + R[None, :], directed=False)
        xmin, ymin, xmax, ymax = world.bounds
        touches = (c[:, 0] - R <= xmin + clearance) | (c[:, 0] + R >= xmax - clearance) | \
                  (c[:, 1] - R <= ymin + clearance) | (c[:, 1] + R >= ymax - clearance)
        bad = set(lab[touches].tolist())
        pts = np.asarray([c[np.nonzero(lab == k)[0][0], :2] for k in range(n) if k not in bad], float).reshape(-1, 2)
    # distinct abscissae, so that no two rays overlap
    span = world.bounds[2] - world.bounds[0]
    return pts + np.stack([(1 + np.arange(len(pts))) * 1e-7 * span, np.zeros(len(pts))], axis=1)


def component_rays(world, clearance: float = 0.0) -> np.ndarray:
    """Ray origins ``(K, 2)`` of the h-signature (one per obstacle component that does not touch
    the border, for ``clearance``), computed once per world and clearance and cached on it."""
    key = ("component_rays", float(clearance))
    rays = _DERIVED.of(world).get(key)
    if rays is None:
        rays = _DERIVED.of(world)[key] = _components(world, float(clearance))
    return rays


def h_signature(world, path: np.ndarray, clearance: float = 0.0) -> np.ndarray:
    """H-signature ``(K,)`` of a polyline without building a :class:`Roadmap` (the same rays):
    two paths between the same ends are in one class exactly when their signatures are equal."""
    rays = component_rays(world, clearance)
    P = np.asarray(path, float).reshape(-1, 2)
    if len(rays) == 0 or len(P) < 2:
        return np.zeros(len(rays), dtype=np.int64)
    return ray_crossings(P[:-1], P[1:], rays).sum(axis=0)


def ray_crossings(A: np.ndarray, B: np.ndarray, rays: np.ndarray) -> np.ndarray:
    """Signed crossings ``(n, K)`` of segments ``A[i] -> B[i]`` with the upward rays from ``rays``.

    +1 when the segment crosses a ray from left to right, -1 right to left, 0 otherwise; the
    ray's own abscissa counts as its right side, so a path that touches a ray and turns back
    does not cross it."""
    A, B = np.asarray(A, float).reshape(-1, 2), np.asarray(B, float).reshape(-1, 2)
    rx, ry = rays[None, :, 0], rays[None, :, 1]
    ax, ay, bx, by = A[:, :1], A[:, 1:], B[:, :1], B[:, 1:]
    right = (ax < rx) & (bx >= rx)
    left = (bx < rx) & (ax >= rx)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (rx - ax) / (bx - ax)
    y = ay + t * (by - ay)
    above = y > ry
    return (right & above).astype(np.int64) - (left & above)


def walk_legs(succ: np.ndarray, i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """Node sequences ``(n, L)`` of the shortest ways ``i[r] -> j[r]`` in a successor table,
    each padded with ``j[r]`` (vectorised over legs: one step of every leg at a time)."""
    cur = np.asarray(i, dtype=np.int64).ravel().copy()
    j = np.asarray(j, dtype=np.int64).ravel()
    seq = [cur.copy()]
    while np.any(cur != j):
        cur = succ[cur, j]
        if np.any(cur < 0):
            raise ParameterError("roadmap leg between unconnected nodes")
        seq.append(cur.copy())
    return np.stack(seq, axis=1)


# the local graph of large grid maps: free cell centres every STEINER_STEP cells; edges up to
# a radius (cells) that makes about LOCAL_PAIRS near pairs to check, within LOCAL_RADIUS
STEINER_STEP = 4
LOCAL_PAIRS = 1_500_000
LOCAL_RADIUS = (1.5 * STEINER_STEP, 8.0 * STEINER_STEP)


class LocalGraph:
    """The roadmap of grid maps too large for all-pairs geodesics over every corner: the convex
    corners (moved ``clearance`` away as in :class:`Roadmap`) and free cell centres on a lattice
    every :data:`STEINER_STEP` cells, joined by the visible segments up to ``radius`` cells
    long (tangent at corner ends, as :class:`Roadmap`'s edges are taut) and by the visible
    segments between consecutive nodes on one grid line, whatever their length (a straight
    passage with no corner inside has its corners at its two mouths, on one line). The
    default radius reads the map: as long as about :data:`LOCAL_PAIRS` near pairs allow for
    the density of nodes over the free cells (within :data:`LOCAL_RADIUS`), so sparse maps
    such as mazes get the long edges their corridors need and dense clutter stays cheap.

    It costs one pass over near pairs (no ``O(corners^2)`` work) and keeps the map's free space
    connected in practice; the users of it (the general encoding on large maps) widen
    ``radius`` when it does not join what they need. Shortest paths over it bend at lattice
    points as well as at corners, so they are a few per cent longer than the exact geodesics.

    Attributes:
        nodes: ``(N, 2)`` positions, metres; ``quadrants``: ``(N, 2)`` blocked quadrant of a
            corner, ``(0, 0)`` for a lattice point; ``lattice``: indices of the lattice points.
        edges: ``(E, 2)`` node pairs ``i < j``; ``weights``: their lengths, metres.
    """

    def __init__(self, grid, clearance: float = 0.0, radius: float | None = None) -> None:
        from scipy.spatial import cKDTree

        self.clearance = float(clearance)
        corners, quad = _grid_corners(grid, self.clearance)
        H, W = grid.occ.shape
        ys, xs = np.mgrid[STEINER_STEP // 2:H:STEINER_STEP, STEINER_STEP // 2:W:STEINER_STEP]
        centres = grid.to_world(np.stack([xs.ravel() + 0.5, ys.ravel() + 0.5], axis=1).astype(float))
        centres = centres[grid.is_free(centres, self.clearance)]
        self.nodes = np.vstack([corners, centres])
        if radius is None:
            # pairs within r: about N * density * pi r^2 / 2
            density = len(self.nodes) / max(float((~grid.occ).sum()), 1.0)
            r = np.sqrt(LOCAL_PAIRS / max(len(self.nodes) * density * np.pi / 2, 1e-9))
            radius = float(np.clip(r, *LOCAL_RADIUS))
        self.radius = float(radius)
        self.quadrants = np.vstack([quad, np.zeros((len(centres), 2), dtype=quad.dtype)])
        self.lattice = np.arange(len(corners), len(self.nodes))
        g = (self.nodes - np.asarray(grid.origin, float)) / grid.resolution   # grid units
        pairs = [cKDTree(g).query_pairs(self.radius, output_type="ndarray").reshape(-1, 2)]
        for axis in (0, 1):  # consecutive nodes along each grid line
            order = np.lexsort((g[:, 1 - axis], g[:, axis]))
            same = g[order[1:], axis] == g[order[:-1], axis]
            pairs.append(np.stack([order[:-1][same], order[1:][same]], axis=1))
        # a pair along a line within the radius is a near pair already
        line = np.concatenate(pairs[1:])
        far = np.hypot(*(g[line[:, 1]] - g[line[:, 0]]).T) > self.radius
        P = np.concatenate([pairs[0], line[far]]).astype(np.int64)
        d = g[P[:, 1]] - g[P[:, 0]]
        ok = tangent_at(d, self.quadrants[P[:, 0]]) & tangent_at(d, self.quadrants[P[:, 1]])
        P, d = P[ok], d[ok]
        ok = np.zeros(len(P), dtype=bool)
        for k in range(0, len(P), EDGE_CHUNK * 10):
            sl = slice(k, k + EDGE_CHUNK * 10)
            ok[sl] = grid.segments_free(self.nodes[P[sl, 0]], self.nodes[P[sl, 1]], self.clearance)
        self.edges = P[ok].astype(np.int64)
        self.weights = np.maximum(np.hypot(d[ok, 0], d[ok, 1]) * grid.resolution, 1e-12)
        self._rows: dict = {}

    def landmark_rows(self, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """About ``count`` landmarks (lattice points spread over the map: in each cell of a square
        binning, the point nearest the cell's centre) with their Dijkstra rows over the graph,
        ``(landmarks (K,), dist (K, N), pred (K, N))``, computed once per count."""
        got = self._rows.get(int(count))
        if got is None:
            from scipy.sparse import coo_matrix
            from scipy.sparse.csgraph import dijkstra

            N = len(self.nodes)
            P = self.nodes[self.lattice]
            marks = self.lattice[_spread(P, int(count))] if len(P) else np.zeros(0, dtype=np.int64)
            graph = coo_matrix((self.weights, (self.edges[:, 0], self.edges[:, 1])), shape=(N, N)).tocsr()
            graph = (graph + graph.T).tocsr()
            dist, pred = dijkstra(graph, directed=True, indices=marks, return_predecessors=True)
            got = self._rows[int(count)] = (marks, dist.reshape(len(marks), N), pred.reshape(len(marks), N))
        return got

    @classmethod
    def of(cls, grid, clearance: float = 0.0, radius: float | None = None) -> "LocalGraph":
        """The grid's local graph for ``clearance`` and ``radius``, built once and cached on it."""
        key = ("local_graph", float(clearance), None if radius is None else float(radius))
        lg = _DERIVED.of(grid).get(key)
        if lg is None:
            lg = _DERIVED.of(grid)[key] = cls(grid, clearance, radius)
        return lg


def _spread(P: np.ndarray, count: int) -> np.ndarray:
    """Indices of about ``count`` of the points ``P`` spread over their bounding box: in each
    cell of a square binning, the point nearest the cell's centre."""
    if len(P) <= count:
        return np.arange(len(P))
    lo, hi = P.min(axis=0), P.max(axis=0)
    side = float(np.sqrt(max(np.prod(hi - lo), 1e-12) / count))
    b = np.floor((P - lo) / side).astype(np.int64)
    d = np.hypot(*(P - (lo + (b + 0.5) * side)).T)
    key = b[:, 0] * (int(np.ceil((hi[1] - lo[1]) / side)) + 2) + b[:, 1]
    order = np.lexsort((d, key))
    first = np.r_[True, key[order][1:] != key[order][:-1]]
    return np.sort(order[first])


def corner_count(grid, clearance: float = 0.0) -> int:
    """Number of roadmap nodes (convex corners kept for ``clearance``) of a grid map."""
    return len(_grid_corners(grid, float(clearance))[0])


def unreachable_cells(grid, a, b) -> bool:
    """Whether points ``a`` and ``b`` (metres) lie in no common 4-connected region of free cells:
    then no free path joins them under the segment rule (two cells that only touch at a
    corner are joined only through a free cell beside that corner). A point on cell
    boundaries belongs to every free cell it touches."""
    from scipy import ndimage

    key = ("free_regions4",)
    lab = _DERIVED.of(grid).get(key)
    if lab is None:
        lab = _DERIVED.of(grid)[key] = ndimage.label(~grid.occ)[0]

    def regions(p):
        g = grid.to_grid(np.asarray(p, float)[None])[0]   # snapped onto grid lines: exact at any origin
        xs = {int(np.floor(g[0])), int(np.ceil(g[0])) - 1}
        ys = {int(np.floor(g[1])), int(np.ceil(g[1])) - 1}
        H, W = lab.shape
        return {int(lab[y, x]) for x in xs for y in ys if 0 <= x < W and 0 <= y < H} - {0}

    return not (regions(a) & regions(b))


def tangent_at(d: np.ndarray, quadrant: np.ndarray) -> np.ndarray:
    """The line of direction ``d`` through a corner with blocked quadrant ``quadrant`` only
    touches the corner's cell (nor enters the opposite quadrant); always true at a point with
    no quadrant ``(0, 0)``."""
    none = np.all(quadrant == 0, axis=1)
    return none | ((d[:, 0] * quadrant[:, 0]) * (d[:, 1] * quadrant[:, 1]) <= 0)


class Roadmap:
    """Nodes, visibility edges, all-pairs geodesic distances and h-signature rays of one world.

    Use :meth:`of` (cached on the world); the constructor always builds anew.

    Attributes:
        nodes: ``(M, 2)`` node positions, metres.
        edges: ``(E, 2)`` node index pairs that see each other (``i < j``).
        dist, succ: all-pairs geodesics and next hops (properties, built on first use).
        rays: ``(K, 2)`` representative points of the interior obstacle components.
    """

    def __init__(self, world, clearance: float = 0.0, ring: int = DEFAULT_RING) -> None:
        self.world, self.clearance = world, float(clearance)
        if world.is_grid:
            self.nodes, self.quadrants = _grid_corners(world, self.clearance)
            self.ring = None
        else:
            if ring < 4:
                raise ParameterError(f"ring must be >= 4 polygon vertices per circle, got {ring}")
            self.nodes, self.normals = _circle_ring(world, self.clearance, ring)
            self.quadrants, self.ring = None, int(ring)
        self.rays = component_rays(world, self.clearance)
        self.edges = self._visible_taut_edges()
        self._dist = self._succ = None
        self._tree = None

    @classmethod
    def of(cls, world, clearance: float = 0.0, ring: int | None = None) -> "Roadmap":
        """The world's roadmap for ``clearance`` (and ``ring`` on circle worlds, default
        :data:`DEFAULT_RING`), built once and kept in the world's cache."""
        ring = DEFAULT_RING if ring is None or world.is_grid else int(ring)
        key = ("roadmap", float(clearance), ring)
        rm = _DERIVED.of(world).get(key)
        if rm is None:
            rm = _DERIVED.of(world)[key] = cls(world, clearance, ring)
        return rm

    def _all_pairs(self) -> None:
        """All-pairs geodesics over the edges (only the general encoding needs them: built on
        first use, ``M x M`` floats and ints)."""
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import dijkstra

        M = len(self.nodes)
        if M == 0:
            self._dist, self._succ = np.zeros((0, 0)), np.zeros((0, 0), dtype=np.int64)
            return
        # distances, predecessors and next hops: ~28 bytes per node pair
        memory_budget(f"the general encoding's all-pairs geodesics over {M} obstacle corners", 28.0 * M * M,
                      "use encoding='columns' or 'waypoints', a graph planner (astar, visibility), "
                      "or a smaller crop of the map")
        w = np.hypot(*(self.nodes[self.edges[:, 1]] - self.nodes[self.edges[:, 0]]).T)
        # a zero-length edge would vanish from the sparse matrix: give it a tiny weight
        w = np.maximum(w, 1e-12)
        G = coo_matrix((w, (self.edges[:, 0], self.edges[:, 1])), shape=(M, M)).tocsr()
        self._dist, pred = dijkstra(G, directed=False, return_predecessors=True)
        # undirected: the node before i on the way from j is i's next node towards j
        succ = pred.T.astype(np.int64)
        np.fill_diagonal(succ, np.arange(M))
        self._succ = succ

    @property
    def dist(self) -> np.ndarray:
        """``(M, M)`` geodesic distance over the edges (``inf``: not connected)."""
        if self._dist is None:
            self._all_pairs()
        return self._dist

    @property
    def succ(self) -> np.ndarray:
        """``(M, M)`` next node after ``i`` on a shortest way from ``i`` to ``j``."""
        if self._succ is None:
            self._all_pairs()
        return self._succ

    def _visible_taut_edges(self) -> np.ndarray:
        """Pairs ``i < j`` whose line is taut at both ends and whose segment is free, built in
        blocks of rows so that memory stays bounded on large maps."""
        M = len(self.nodes)
        out = []
        rows = max(1, PAIR_BLOCK // max(M, 1))
        for a in range(0, M, rows):
            I = np.repeat(np.arange(a, min(a + rows, M)), M)
            J = np.tile(np.arange(M), min(a + rows, M) - a)
            up = J > I
            I, J = I[up], J[up]
            ok = self._taut(I, J)
            I, J = I[ok], J[ok]
            keep = self.visible(self.nodes[I], self.nodes[J])
            out.append(np.stack([I[keep], J[keep]], axis=1))
        return np.concatenate(out) if out else np.zeros((0, 2), dtype=np.int64)

    def _taut(self, I: np.ndarray, J: np.ndarray) -> np.ndarray:
        """Whether the line through nodes ``I`` and ``J`` misses the obstacle each one wraps."""
        d = self.nodes[J] - self.nodes[I]
        if self.quadrants is not None:
            qi, qj = self.quadrants[I], self.quadrants[J]
            # the line misses the inside of the blocked quadrant at both ends
            ok = (d[:, 0] * qi[:, 0]) * (d[:, 1] * qi[:, 1]) <= 0
            return ok & ((d[:, 0] * qj[:, 0]) * (d[:, 1] * qj[:, 1]) <= 0)
        # polygon vertex: the line stays outside the vertex's interior angle (pi - 2 pi / ring)
        # when its direction is within sin(pi / ring) of the tangent
        lim = np.sin(np.pi / self.ring) * (1 + 1e-9)
        L = np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300)
        ci = np.abs((d * self.normals[I]).sum(axis=1)) / L
        cj = np.abs((d * self.normals[J]).sum(axis=1)) / L
        return (ci <= lim) & (cj <= lim)

    def visible(self, A: np.ndarray, B: np.ndarray) -> np.ndarray:
        """Exact segment rule for many segments, in chunks."""
        out = np.zeros(len(A), dtype=bool)
        for k in range(0, len(A), EDGE_CHUNK):
            out[k:k + EDGE_CHUNK] = self.world.segments_free(A[k:k + EDGE_CHUNK], B[k:k + EDGE_CHUNK], self.clearance)
        return out

    def nearest(self, P: np.ndarray) -> np.ndarray:
        """Index of the nearest node to each point ``(..., 2)`` (Euclidean, not geodesic)."""
        if self._tree is None:
            from scipy.spatial import cKDTree

            self._tree = cKDTree(self.nodes)
        P = np.asarray(P, float)
        return self._tree.query(P.reshape(-1, 2))[1].reshape(P.shape[:-1])

    def attach(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Geodesic distance from point ``p`` to every node ``(M,)`` and the node it enters the
        roadmap by on that way ``(M,)`` (``-1``: unreachable)."""
        p = np.asarray(p, float)
        M = len(self.nodes)
        if M == 0:
            return np.zeros(0), np.zeros(0, dtype=np.int64)
        seen = np.nonzero(self.visible(np.broadcast_to(p, (M, 2)), self.nodes))[0]
        if seen.size == 0:
            return np.full(M, np.inf), np.full(M, -1, dtype=np.int64)
        hop = np.hypot(*(self.nodes[seen] - p).T)
        total = hop[:, None] + self.dist[seen]
        k = total.argmin(axis=0)
        d = total[k, np.arange(M)]
        return d, np.where(np.isfinite(d), seen[k], -1)

    def leg_nodes(self, i: np.ndarray, j: np.ndarray) -> np.ndarray:
        """Node sequences of the shortest ways ``i[r] -> j[r]`` (see :func:`walk_legs`)."""
        return walk_legs(self.succ, i, j)

    def signature(self, path: np.ndarray) -> np.ndarray:
        """H-signature of a polyline: signed crossings of every component's ray, ``(K,)``."""
        P = np.asarray(path, float)
        if len(self.rays) == 0 or len(P) < 2:
            return np.zeros(len(self.rays), dtype=np.int64)
        return ray_crossings(P[:-1], P[1:], self.rays).sum(axis=0)
