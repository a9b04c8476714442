"""The shortest path in a homotopy class: same h-signature as a given path, exactly shortest.

Bhattacharya, Kumar and Likhachev (2012, "Topological constraints in search-based robot path
planning", §IV) search a graph whose states are (vertex, h-signature so far): an edge adds
its own signature (the signed crossings of one ray per obstacle component), and the goal is
reached only in the state whose signature is the target's. Here the graph is the world's
:class:`~optplan.world.roadmap.Roadmap` (convex corners joined by taut visible edges on
grids; circumscribed polygons on circle worlds) plus start and goal, and the search is A*
with the Euclidean heuristic, pruned by the seed path's own length (the class optimum is
never longer than a member of the class, so nothing longer is ever needed and the search is
finite).

Exactness on grids: a shortest path in a homology class is locally shortest (any local
shortening stays in the class), so it bends only at convex corners and every edge is tangent
at both ends: it is a path of the roadmap, and A* over (vertex, signature) finds the
shortest one. On circle worlds the arcs are replaced by the sides of the circumscribed
polygons (at most ``1/cos(pi/ring) - 1`` longer than the true arcs).
"""
from __future__ import annotations

import heapq
import time

import numpy as np

from ..errors import ParameterError
from ..world.geometry import validate_path
from ..world.metrics import path_length
from ..world.queries import check_start_goal
from ..world.roadmap import (ROADMAP_CORNERS, Roadmap, component_rays, corner_count, h_signature,
                              ray_crossings)
from .result import make_plan_result


# states (node, signature) the class search may hold before it gives up with a ParameterError
# (a few seconds of search)
MAX_STATES = 200_000
SIGNATURE_HASH_SEED = 20120901   # fixed: the same words on every run


class _RoadmapNeighbours:
    """The roadmap's edges plus start and goal joined to every node they see (and each other):
    node ``M`` is the start, ``M + 1`` the goal."""

    def __init__(self, roadmap: Roadmap, start: np.ndarray, goal: np.ndarray) -> None:
        M = len(roadmap.nodes)
        self.points = np.vstack([roadmap.nodes, start[None], goal[None]]) if M else np.stack([start, goal])
        self.start, self.goal = M, M + 1
        A, B = roadmap.edges[:, 0], roadmap.edges[:, 1]
        ends = []
        for e in (M, M + 1):
            seen = np.nonzero(roadmap.visible(np.broadcast_to(self.points[e], (M, 2)), roadmap.nodes))[0] if M else []
            ends.append(np.stack([np.full(len(seen), e), seen], axis=1))
        if roadmap.visible(start[None], goal[None])[0]:
            ends.append(np.array([[M, M + 1]]))
        E = np.vstack([np.stack([A, B], axis=1)] + [x.reshape(-1, 2) for x in ends]).astype(np.int64)
        src = np.concatenate([E[:, 0], E[:, 1]])
        dst = np.concatenate([E[:, 1], E[:, 0]])
        order = np.argsort(src, kind="stable")
        self.nbr = dst[order]
        self.ptr = np.searchsorted(src[order], np.arange(M + 3))

    def __call__(self, u: int) -> tuple[np.ndarray, np.ndarray]:
        v = self.nbr[self.ptr[u]:self.ptr[u + 1]]
        return v, np.hypot(*(self.points[v] - self.points[u]).T)


class _ClassSearch:
    """A* over (node, signature) for one start and goal: ``graph(u)`` gives the neighbours of
    node ``u`` and the edge lengths, ``graph.points`` the node positions, ``graph.start`` and
    ``graph.goal`` the end nodes; ``rays`` the h-signature's ray origins."""

    def __init__(self, graph, rays: np.ndarray) -> None:
        self.graph, self.rays = graph, rays
        self.points = graph.points
        self._cross: dict[int, np.ndarray] = {}
        # a signature is kept as two 64-bit linear hashes (sum of count x random word per
        # component, wrapping): a state costs a few words, however many components there are,
        # and two different signatures share both words with probability ~2^-128
        self.words = np.random.default_rng(SIGNATURE_HASH_SEED).integers(0, 2 ** 63, size=(len(rays), 2),
                                                                        dtype=np.uint64)

    def hash(self, X: np.ndarray) -> np.ndarray:
        """The two hash words ``(n, 2)`` of signatures or crossings ``X`` ``(n, K)``."""
        with np.errstate(over="ignore"):
            return np.asarray(X).astype(np.int64).astype(np.uint64) @ self.words

    def neighbours(self, u: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Neighbour indices, edge lengths and the hash words of each edge's crossings ``(deg, 2)``."""
        v, w = self.graph(u)
        if u not in self._cross:
            P = self.points
            self._cross[u] = self.hash(ray_crossings(np.broadcast_to(P[u], (len(v), 2)), P[v], self.rays))
        return v, w, self._cross[u]

    def run(self, target: np.ndarray, bound: float) -> tuple[list[int], float] | None:
        """Shortest node sequence from start to goal with signature ``target`` and length at most
        ``bound``; ``None`` when there is none."""
        s, g = self.graph.start, self.graph.goal
        heur = np.hypot(*(self.points - self.points[g]).T)
        tol = 1e-9 * max(1.0, bound)
        th = self.hash(np.asarray(target)[None])[0]
        tkey = (int(th[0]), int(th[1]))
        key0 = (s, 0, 0)
        best = {key0: 0.0}
        parent = {key0: None}
        heap = [(heur[s], 0.0, key0)]
        mask = (1 << 64) - 1
        while heap:
            f, cost, key = heapq.heappop(heap)
            if cost > best.get(key, np.inf) + tol:
                continue
            u, h1, h2 = key
            if u == g and (h1, h2) == tkey:
                seq = [u]
                k = parent[key]
                while k is not None:
                    seq.append(k[0])
                    k = parent[k]
                return seq[::-1], cost
            v, w, X = self.neighbours(u)
            nc = cost + w
            ok = nc + heur[v] <= bound + tol
            if not ok.any():
                continue
            if len(best) > MAX_STATES:
                raise ParameterError(
                    f"the shortest path in this h-signature class needs more than {MAX_STATES} search states "
                    f"(node, signature over {len(self.rays)} obstacle components) within the seed's length: too "
                    "many classes this close to the seed on this map; pass a shorter seed or a smaller crop")
            for j in np.nonzero(ok)[0]:  # one search node at a time: A* is sequential by nature
                nk = (int(v[j]), (h1 + int(X[j, 0])) & mask, (h2 + int(X[j, 1])) & mask)
                if nc[j] < best.get(nk, np.inf) - tol:
                    best[nk] = nc[j]
                    parent[nk] = key
                    heapq.heappush(heap, (nc[j] + heur[v[j]], nc[j], nk))
        return None


def class_shortest_path(world, start, goal, homotopy, clearance: float = 0.0) -> tuple[np.ndarray, float, str]:
    """Shortest path from ``start`` to ``goal`` with the h-signature of the path ``homotopy``.

    Returns ``(path, length, message)``. The path never is longer than ``homotopy`` (the seed
    itself is returned when nothing shorter exists in the class).

    Raises:
        ParameterError: ``homotopy`` is not an ``(N, 2)`` path from start to goal that passes
            the exact collision test, or the search would need more than :data:`MAX_STATES`
            states: on large cluttered maps the classes shorter than a long detour are too
            many to search.
    """
    P = np.asarray(homotopy, dtype=float)
    if P.ndim != 2 or P.shape[1] != 2 or len(P) < 2 or not np.all(np.isfinite(P)):
        raise ParameterError(f"homotopy must be an (N, 2) path of finite points with N >= 2, got shape {P.shape}")
    s, g = np.asarray(start, float), np.asarray(goal, float)
    if not (np.allclose(P[0], s) and np.allclose(P[-1], g)):
        raise ParameterError("homotopy path must start at start and end at goal (its class is defined between "
                             "those two points)")
    check = validate_path(world, P, clearance)
    if not check.ok:
        raise ParameterError(f"homotopy path is not collision-free ({check.reason}); its h-signature class is "
                             "defined only for feasible paths: pass a feasible path")
    rays = component_rays(world, clearance)
    target = h_signature(world, P, clearance)
    seed_len = float(path_length(P[None])[0])
    if world.is_grid and corner_count(world, clearance) > ROADMAP_CORNERS:
        # a large map: no roadmap of every edge, the edges of the corners the search visits
        from .graph.visibility import CornerNeighbours

        graph = CornerNeighbours(world, s, g, clearance, bound=seed_len * (1 + 1e-9))
        graph.start, graph.goal = 0, 1
    else:
        graph = _RoadmapNeighbours(Roadmap.of(world, clearance), s, g)
    found = _ClassSearch(graph, rays).run(target, seed_len)
    if found is None:
        return P.copy(), seed_len, "no roadmap path in the class is shorter than the seed; the seed is returned"
    seq, length = found
    pts = graph.points[seq].copy()
    pts[0], pts[-1] = s, g
    return pts, float(length), f"shortest path of h-signature {target.tolist()} ({len(rays)} components)"


def homotopy_shortest_path(world, start, goal, homotopy, clearance: float = 0.0):
    """``op.shortest_path(world, start, goal, method="visibility", homotopy=path)``: a validated
    :class:`PlanResult` holding the shortest path in ``homotopy``'s h-signature class."""
    t0 = time.perf_counter()
    s, g = check_start_goal(world, start, goal, clearance)
    path, length, msg = class_shortest_path(world, s, g, homotopy, clearance)
    return make_plan_result(world, path, "visibility", time.perf_counter() - t0, clearance=clearance, message=msg)
