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

Modes: ``points="centres"`` puts start and goal at the centres of their cells
(what the metaheuristics produce); ``points="corners"`` takes them as lattice
vertices (the Anya / GPPC benchmark convention).
"""
from __future__ import annotations

import numpy as np
from ...errors import InfeasibleQueryError
from ...world.geometry import segments_free

_CHUNK = 200_000  # candidate pairs checked per call, to bound memory


def convex_corners(grid) -> tuple[np.ndarray, np.ndarray]:
    """Lattice vertices (grid units) with exactly one blocked cell around them, and the
    quadrant ``(sx, sy)`` (each +-1) in which that blocked cell lies."""
    pad = grid.padded  # padded[iy + 1, ix + 1]
    # the four cells around vertex (X, Y): (X-1, Y-1), (X, Y-1), (X-1, Y), (X, Y)
    bl, br = pad[:-1, :-1], pad[:-1, 1:]
    tl, tr = pad[1:, :-1], pad[1:, 1:]
    count = bl.astype(np.int8) + br + tl + tr
    Y, X = np.nonzero(count == 1)
    sx = np.where(br[Y, X] | tr[Y, X], 1, -1)
    sy = np.where(tl[Y, X] | tr[Y, X], 1, -1)
    return np.stack([X, Y], axis=1).astype(float), np.stack([sx, sy], axis=1)


def _tangent(d: np.ndarray, quadrant: np.ndarray) -> np.ndarray:
    """The line through a corner with direction ``d`` does not enter the open blocked
    quadrant (nor, extended, the opposite one that mirrors it): it only touches."""
    s = np.sign(d)
    axis = (s[:, 0] == 0) | (s[:, 1] == 0)
    same = (s[:, 0] == quadrant[:, 0]) & (s[:, 1] == quadrant[:, 1])
    opposite = (s[:, 0] == -quadrant[:, 0]) & (s[:, 1] == -quadrant[:, 1])
    return axis | ~(same | opposite)


def _visible_pairs(grid, P: np.ndarray, I: np.ndarray, J: np.ndarray) -> np.ndarray:
    ok = np.zeros(len(I), dtype=bool)
    for a in range(0, len(I), _CHUNK):
        b = a + _CHUNK
        ok[a:b] = segments_free(grid, grid.to_world(P[I[a:b]]), grid.to_world(P[J[a:b]]))
    return ok


def _astar_over_corners(grid, P: np.ndarray, Q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A* from node 0 to node 1 over the corner visibility graph with lazy edges.

    Edges out of a node are generated only when it is expanded: every open node
    whose line from it is tangent at both ends (quadrant ``(0, 0)`` = any direction)
    and whose tentative cost can still improve is checked in one vectorised
    ``segments_free`` call. The Euclidean heuristic is consistent, so the first
    time the goal is expanded its distance is optimal.
    """
    import heapq

    n = len(P)
    dist = np.full(n, np.inf)
    pred = np.full(n, -1, dtype=np.int64)
    closed = np.zeros(n, dtype=bool)
    h = np.hypot(*(P - P[1]).T)
    dist[0] = 0.0
    heap = [(h[0], 0)]
    anydir = np.all(Q == 0, axis=1)
    while heap:
        _, u = heapq.heappop(heap)
        if closed[u]:
            continue
        closed[u] = True
        if u == 1:
            break
        d = P - P[u]
        step = np.hypot(d[:, 0], d[:, 1])
        cand = ~closed & (dist[u] + step < dist)
        if not anydir[u]:
            cand &= _tangent(d, np.broadcast_to(Q[u], d.shape))
        cand &= anydir | _tangent(d, Q)
        J = np.nonzero(cand)[0]
        if J.size == 0:
            continue
        vis = _visible_pairs(grid, P, np.full(J.size, u), J)
        J = J[vis]
        nd = dist[u] + step[J]
        better = nd < dist[J]
        J, nd = J[better], nd[better]
        dist[J] = nd
        pred[J] = u
        for j, v in zip(J.tolist(), (nd + h[J]).tolist()):
            heapq.heappush(heap, (v, j))
    return dist, pred


def visibility_path(grid, start, goal, points: str = "centres"):
    """Exact any-angle shortest path between two points given in world metres.

    In centre mode the points are moved to the centres of their cells; in corner
    mode they must be lattice vertices (rounded to the nearest one). Returns
    ``(path_in_metres, length_in_metres)``; raises InfeasibleQueryError if the goal
    cannot be reached.
    """
    gs, gg = grid.to_grid(start), grid.to_grid(goal)
    if points == "centres":
        gs, gg = np.floor(gs) + 0.5, np.floor(gg) + 0.5
    elif points == "corners":
        gs, gg = np.round(gs), np.round(gg)
    else:
        from ...errors import ParameterError

        raise ParameterError(f"points must be 'centres' or 'corners', got {points!r}")
    corners, quad = convex_corners(grid)
    if segments_free(grid, grid.to_world(gs), grid.to_world(gg)):
        path = grid.to_world(np.stack([gs, gg]))
        return path, float(np.hypot(*(gg - gs))) * grid.resolution
    # node 0 = start, 1 = goal, 2.. = convex corners; the end points take any direction
    P = np.vstack([gs, gg, corners])
    Q = np.vstack([[0, 0], [0, 0], quad])
    dist, pred = _astar_over_corners(grid, P, Q)
    if not np.isfinite(dist[1]):
        raise InfeasibleQueryError("the goal is unreachable from the start (no free any-angle path); "
                                   "check the map or choose another goal")
    chain = [1]
    while chain[-1] != 0:
        chain.append(int(pred[chain[-1]]))
    path = grid.to_world(P[chain[::-1]])
    return path, float(dist[1]) * grid.resolution
