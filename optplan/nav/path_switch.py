"""Path switch strategy with virtual points (yuan2021 §4.2).

Instead of re-planning the whole global path when a newly sensed obstacle blocks it,
yuan2021 keeps an undirected weighted graph over a few *virtual points* of the map
plus start and goal: each edge stores a collision-free path between two connected
points and its length. When the current path fails,

1. edges whose stored path is now blocked are dropped;
2. a virtual point that the obstacle sits on (or next to) is split into sub-virtual
   points around it, which inherit its connections with paths re-planned around the
   obstacle;
3. Dijkstra from the virtual point nearest the robot gives the shortest chain to the
   goal, and the chain of stored paths becomes the new global path (here: the best of
   the few nearest points, counting the way to reach it, see :meth:`route`).

The paper places its 8 virtual points by hand in a room map (its Figure 2). Here they
are chosen automatically and deterministically: farthest-point sampling over the free
cell centres (discs: free lattice points) that keep one cell (at least ``2 x clearance``)
from obstacles and the border,
seeded with start and goal; each point is connected to its ``k`` nearest neighbours by
the known map's shortest path (A* on grids, the tangent graph on circle worlds) with
the robot radius as clearance.
"""
from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from ..errors import OptplanError
from ..solvers.graph import shortest_path


def _path_length(P: np.ndarray) -> float:
    return float(np.hypot(*np.diff(P, axis=0).T).sum()) if len(P) > 1 else 0.0


def _connect(world, a: np.ndarray, b: np.ndarray, clearance: float) -> np.ndarray | None:
    """A collision-free path ``a -> b`` (ends exact) or ``None``."""
    if bool(world.segments_free(a, b, clearance)):
        return np.array([a, b])
    method = "astar" if world.is_grid else "visibility"
    try:
        res = shortest_path(world, a, b, method=method, clearance=clearance)
    except OptplanError:
        return None
    if not res.feasible or not len(res.path):
        return None
    P = np.vstack([a, res.path, b])
    keep = np.ones(len(P), bool)
    keep[1:] = np.any(np.diff(P, axis=0) != 0, axis=1)
    P = P[keep]
    if not np.all(world.segments_free(P[:-1], P[1:], clearance)):
        # the snapped ends (cell centres) do not connect straight to a and b
        return None
    return P


def _candidate_points(world, clearance: float) -> np.ndarray:
    if world.is_grid:
        iy, ix = np.nonzero(~world.occ)
        pts = world.cell_center(np.stack([ix, iy], axis=1))
    else:
        xmin, ymin, xmax, ymax = world.bounds
        step = max((xmax - xmin) / 40, (ymax - ymin) / 40)
        X, Y = np.meshgrid(np.arange(xmin + step / 2, xmax, step), np.arange(ymin + step / 2, ymax, step))
        pts = np.stack([X.ravel(), Y.ravel()], axis=1)
    # prefer open space (a free cell all round), as the paper's hand-placed points are
    clear = np.asarray(world.clearance(pts))
    roomy = pts[clear >= max(2 * clearance, getattr(world, "resolution", 0.5))]
    return roomy if len(roomy) >= 16 else pts[clear >= 2 * clearance]


class VirtualPointGraph:
    """The weighted graph of virtual points and stored paths (yuan2021 §4.2, Figure 2).

    Args:
        world: the known map (GridMap or CircleWorld).
        start, goal: metres; they are nodes 0 and 1.
        clearance: the robot radius, metres.
        n_virtual: virtual points besides start and goal (the paper uses 8).
        k_neighbours: connections tried per point.
    """

    def __init__(self, world, start, goal, clearance: float, n_virtual: int = 8, k_neighbours: int = 4):
        self.clearance = float(clearance)
        self.k = int(k_neighbours)
        self.nodes = [np.asarray(start, float), np.asarray(goal, float)]
        cand = _candidate_points(world, clearance)
        if len(cand):
            d = np.minimum(np.hypot(*(cand - self.nodes[0]).T), np.hypot(*(cand - self.nodes[1]).T))
            for _ in range(int(n_virtual)):
                i = int(np.argmax(d))
                if d[i] <= 0:
                    break
                self.nodes.append(cand[i].copy())
                d = np.minimum(d, np.hypot(*(cand - cand[i]).T))
        self.alive = [True] * len(self.nodes)
        self.edges: dict[tuple[int, int], np.ndarray] = {}
        for i in range(len(self.nodes)):
            self._link(world, i, self._nearest(i, self.k))

    # -------------------------------------------------------------------- building
    def _nearest(self, i: int, k: int, exclude=()) -> list[int]:
        P = np.array(self.nodes)
        d = np.hypot(*(P - P[i]).T)
        order = [j for j in np.argsort(d) if j != i and self.alive[j] and j not in exclude]
        return [int(j) for j in order[:k]]

    def _link(self, world, i: int, others) -> None:
        for j in others:
            key = (min(i, j), max(i, j))
            if key in self.edges:
                continue
            P = _connect(world, self.nodes[key[0]], self.nodes[key[1]], self.clearance)
            if P is not None:
                self.edges[key] = P

    # -------------------------------------------------------------------- updating
    def update(self, world) -> None:
        """Apply what is now known (``world`` = known map + sensed obstacles): drop blocked
        edges and split blocked virtual points into sub-virtual points."""
        c = self.clearance
        for key in [k for k, P in self.edges.items() if not np.all(world.segments_free(P[:-1], P[1:], c))]:
            del self.edges[key]
        res = getattr(world, "resolution", 1.0)
        for i in range(2, len(self.nodes)):
            if not self.alive[i] or float(world.clearance(self.nodes[i])) >= c:
                continue
            self.alive[i] = False
            neighbours = {j for key in list(self.edges) for j in key if i in key and j != i}
            neighbours |= set(self._nearest(i, self.k))
            for key in [k for k in self.edges if i in k]:
                del self.edges[key]
            for off in (np.array([1, 0]), np.array([-1, 0]), np.array([0, 1]), np.array([0, -1])):
                for step in (1, 2, 3):
                    p = self.nodes[i] + off * step * res
                    if float(world.clearance(p)) >= 2 * c:
                        self.nodes.append(p)
                        self.alive.append(True)
                        self._link(world, len(self.nodes) - 1, sorted(neighbours))
                        break

    # --------------------------------------------------------------------- routing
    def route(self, world, position, candidates: int = 4) -> np.ndarray | None:
        """Shortest chain of stored paths from a virtual point near ``position`` to the goal,
        as one path starting at ``position``; ``None`` when the graph has no route.

        yuan2021 starts Dijkstra at the virtual point nearest the robot. That point can lie
        behind the robot, so here the ``candidates`` nearest points that ``position`` connects
        to are all tried and the one with the shortest total (lead-in + chain) is kept.
        """
        n = len(self.nodes)
        if not self.edges:
            return None
        keys = list(self.edges)
        w = np.array([_path_length(self.edges[k]) for k in keys])
        I = np.array([k[0] for k in keys])
        J = np.array([k[1] for k in keys])
        G = coo_matrix((np.r_[w, w], (np.r_[I, J], np.r_[J, I])), shape=(n, n)).tocsr()
        # distances to the goal (node 1) from every node: one Dijkstra on the undirected graph
        dist, pred = dijkstra(G, indices=1, return_predecessors=True)
        P = np.array(self.nodes)
        order = [int(j) for j in np.argsort(np.hypot(*(P - np.asarray(position)).T)) if self.alive[j]]
        best = None
        for s in order[:candidates]:
            if not np.isfinite(dist[s]):
                continue
            lead = _connect(world, np.asarray(position, float), self.nodes[s], self.clearance)
            if lead is None:
                continue
            total = _path_length(lead) + dist[s]
            if best is None or total < best[0]:
                best = (total, s, lead)
        if best is None:
            return None
        _, s, lead = best
        chain = [s]
        while chain[-1] != 1:
            chain.append(int(pred[chain[-1]]))
        pieces = [lead]
        for a, b in zip(chain[:-1], chain[1:]):
            E = self.edges[(min(a, b), max(a, b))]
            pieces.append((E if a < b else E[::-1])[1:])
        self.last_chain = chain
        return np.vstack(pieces)
