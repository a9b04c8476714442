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
from ..world.roadmap import Roadmap, ray_crossings
from .result import make_plan_result


class _ClassSearch:
    """A* over (node, signature) on one roadmap for one start and goal."""

    def __init__(self, roadmap: Roadmap, start: np.ndarray, goal: np.ndarray) -> None:
        self.rm, self.s, self.g = roadmap, np.asarray(start, float), np.asarray(goal, float)
        M = len(roadmap.nodes)
        self.M = M
        self.points = np.vstack([roadmap.nodes, self.s[None], self.g[None]]) if M else np.stack([self.s, self.g])
        # adjacency: roadmap edges, plus start and goal joined to every node they see (and each other)
        A, B = roadmap.edges[:, 0], roadmap.edges[:, 1]
        ends = []
        for e in (M, M + 1):
            seen = np.nonzero(roadmap.visible(np.broadcast_to(self.points[e], (M, 2)), roadmap.nodes))[0] if M else []
            ends.append(np.stack([np.full(len(seen), e), seen], axis=1))
        if roadmap.visible(self.s[None], self.g[None])[0]:
            ends.append(np.array([[M, M + 1]]))
        E = np.vstack([np.stack([A, B], axis=1)] + [x.reshape(-1, 2) for x in ends]).astype(np.int64)
        src = np.concatenate([E[:, 0], E[:, 1]])
        dst = np.concatenate([E[:, 1], E[:, 0]])
        order = np.argsort(src, kind="stable")
        self.nbr = dst[order]
        self.ptr = np.searchsorted(src[order], np.arange(M + 3))
        self._cross: dict[int, np.ndarray] = {}

    def neighbours(self, u: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Neighbour indices, edge lengths and edge signatures ``(deg, K)`` of node ``u``."""
        v = self.nbr[self.ptr[u]:self.ptr[u + 1]]
        if u not in self._cross:
            P = self.points
            self._cross[u] = ray_crossings(np.broadcast_to(P[u], (len(v), 2)), P[v], self.rm.rays)
        return v, np.hypot(*(self.points[v] - self.points[u]).T), self._cross[u]

    def run(self, target: np.ndarray, bound: float) -> tuple[list[int], float] | None:
        """Shortest node sequence from start to goal with signature ``target`` and length at most
        ``bound``; ``None`` when there is none."""
        s, g = self.M, self.M + 1
        heur = np.hypot(*(self.points - self.g).T)
        tol = 1e-9 * max(1.0, bound)
        K = len(target)
        zero = np.zeros(K, dtype=np.int64)
        key0 = (s, zero.tobytes())
        best = {key0: 0.0}
        parent = {key0: None}
        sig_of = {key0: zero}
        heap = [(heur[s], 0.0, s, key0[1])]
        tkey = target.astype(np.int64).tobytes()
        while heap:
            f, cost, u, sk = heapq.heappop(heap)
            key = (u, sk)
            if cost > best.get(key, np.inf) + tol:
                continue
            if u == g and sk == tkey:
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
            sig = sig_of[key]
            for j in np.nonzero(ok)[0]:  # one search node at a time: A* is sequential by nature
                ns = sig + X[j]
                nk = (int(v[j]), ns.tobytes())
                if nc[j] < best.get(nk, np.inf) - tol:
                    best[nk] = nc[j]
                    parent[nk] = key
                    sig_of[nk] = ns
                    heapq.heappush(heap, (nc[j] + heur[v[j]], nc[j], int(v[j]), nk[1]))
        return None


def class_shortest_path(world, start, goal, homotopy, clearance: float = 0.0) -> tuple[np.ndarray, float, str]:
    """Shortest path from ``start`` to ``goal`` with the h-signature of the path ``homotopy``.

    Returns ``(path, length, message)``. The path never is longer than ``homotopy`` (the seed
    itself is returned when nothing shorter exists in the class).

    Raises:
        ParameterError: ``homotopy`` is not an ``(N, 2)`` path from start to goal that passes
            the exact collision test.
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
    rm = Roadmap.of(world, clearance)
    target = rm.signature(P)
    seed_len = float(path_length(P[None])[0])
    found = _ClassSearch(rm, s, g).run(target, seed_len)
    if found is None:
        return P.copy(), seed_len, "no roadmap path in the class is shorter than the seed; the seed is returned"
    seq, length = found
    pts = np.vstack([rm.nodes, s[None], g[None]])[seq]
    pts[0], pts[-1] = s, g
    return pts, float(length), f"shortest path of h-signature {target.tolist()} ({len(rm.rays)} components)"


def homotopy_shortest_path(world, start, goal, homotopy, clearance: float = 0.0):
    """``op.shortest_path(world, start, goal, method="visibility", homotopy=path)``: a validated
    :class:`PlanResult` holding the shortest path in ``homotopy``'s h-signature class."""
    t0 = time.perf_counter()
    s, g = check_start_goal(world, start, goal, clearance)
    path, length, msg = class_shortest_path(world, s, g, homotopy, clearance)
    return make_plan_result(world, path, "visibility", time.perf_counter() - t0, clearance=clearance, message=msg)
