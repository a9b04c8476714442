"""Exact shortest path among circular obstacles (the optimum for circle worlds).

In a plane with disc obstacles, a shortest path is made of straight segments
tangent to the discs and arcs along their boundaries. The tangent graph holds
start, goal and every tangent point: edges are free tangent segments (start or
goal to a disc, and the up to four common tangents of two discs) and free arcs
between consecutive tangent points on one disc. Dijkstra on it gives the exact
optimum; the returned polyline follows arcs on a circumscribed polygon (just
outside the disc), so it validates and is longer than the optimum only by the
polygon's excess, reported separately.
"""
from __future__ import annotations

import time

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from ..errors import InfeasibleQueryError, ParameterError
from ..world.queries import check_start_goal
from .result import make_plan_result
from ..world.derived import DerivedStore

_DERIVED = DerivedStore("solvers.tangent_graph")  # this module's data derived from worlds

_EPS = 1e-9
# memory bounds: segment-circle distances evaluated per block, and the largest tangent graph
PAIR_BLOCK = 4_000_000
PAIR_CHUNK = 100_000  # circle pairs whose tangents are built and checked at once
MAX_GRAPH_BYTES = 4 * 2**30
BYTES_PER_TANGENT = 200  # two nodes (x, y, circle, angle), an edge (u, v, w) and its CSR copy, an arc edge
# the cheap pass of _segments_clear: circles nearest to these points along each segment
PREFILTER_K = 3
PREFILTER_T = (0.5, 0.3, 0.7, 0.15, 0.85)


def _point_tangents(p: np.ndarray, C: np.ndarray, R: np.ndarray):
    """Tangent points from point p to every circle: two per circle, (m, 2, 2) and circle ids."""
    d = C - p
    dist = np.hypot(d[:, 0], d[:, 1])
    ok = dist > R + _EPS
    base = np.arctan2(-d[:, 1], -d[:, 0])  # direction from centre to p
    half = np.arccos(np.clip(R / np.where(ok, dist, 1.0), -1, 1))
    angs = np.stack([base + half, base - half], axis=1)
    pts = C[:, None, :] + R[:, None, None] * np.stack([np.cos(angs), np.sin(angs)], axis=-1)
    ids = np.repeat(np.arange(len(C))[:, None], 2, axis=1)
    return pts[ok].reshape(-1, 2), ids[ok].ravel(), angs[ok].ravel()


def _common_tangents(C: np.ndarray, R: np.ndarray, I: np.ndarray, J: np.ndarray):
    """The common tangent segments of the circle pairs ``(I[k], J[k])``:
    ``(a_pts, b_pts, i, j, ang_i, ang_j)``."""
    out = []
    d = C[J] - C[I]
    dist = np.hypot(d[:, 0], d[:, 1])
    phi = np.arctan2(d[:, 1], d[:, 0])
    for sign_j in (1.0, -1.0):  # +1: outer tangents, -1: inner (crossing) tangents
        c = (R[I] - sign_j * R[J]) / np.where(dist > 0, dist, 1.0)
        ok = (np.abs(c) <= 1 - 1e-12) & (dist > 0)
        for side in (1.0, -1.0):
            ang_i = phi + side * np.arccos(np.clip(c, -1, 1))
            ang_j = ang_i if sign_j > 0 else ang_i + np.pi
            pa = C[I] + R[I, None] * np.stack([np.cos(ang_i), np.sin(ang_i)], 1)
            pb = C[J] + R[J, None] * np.stack([np.cos(ang_j), np.sin(ang_j)], 1)
            out.append((pa[ok], pb[ok], I[ok], J[ok], ang_i[ok], ang_j[ok]))
    return [np.concatenate(z) for z in zip(*out)]


def _covered_intervals(C: np.ndarray, R: np.ndarray, i: int):
    """Angular intervals (centre, half-width) of circle i's boundary lying inside other circles."""
    d = C - C[i]
    dist = np.hypot(d[:, 0], d[:, 1])
    hit = (dist < R[i] + R - _EPS) & (np.arange(len(C)) != i)
    centre = np.arctan2(d[hit, 1], d[hit, 0])
    cosw = (R[i] ** 2 + dist[hit] ** 2 - R[hit] ** 2) / (2 * R[i] * np.maximum(dist[hit], 1e-300))
    half = np.where(cosw <= -1, np.pi, np.arccos(np.clip(cosw, -1, 1)))
    # circle i entirely inside another: fully covered
    return centre, half


def _segments_clear(world, A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Tangent segments touch their own circles exactly; allow a tiny tolerance.

    Exact, in bounded memory: a cheap pass first tests each segment against the
    ``PREFILTER_K`` circles nearest to each of a few points along it (a segment any
    of them cuts is blocked), then the segments left are tested against every
    circle in blocks of at most ``PAIR_BLOCK`` segment-circle pairs."""
    n = len(A)
    if n == 0:
        return np.zeros(0, bool)
    xmin, ymin, xmax, ymax = world.bounds
    ok = np.ones(n, dtype=bool)
    for P in (A, B):
        ok &= (P[:, 0] >= xmin - 1e-12) & (P[:, 0] <= xmax + 1e-12) & (P[:, 1] >= ymin - 1e-12) & (P[:, 1] <= ymax + 1e-12)
    C, R = world.circles[:, :2], world.radii
    m = len(C)
    if m == 0:
        return ok
    if m > PREFILTER_K:
        tree = _circle_tree(world)
        k = PREFILTER_K
        for t in PREFILTER_T:
            idx = np.nonzero(ok)[0]
            if len(idx) == 0:
                break
            _, near = tree.query(A[idx] + t * (B[idx] - A[idx]), k=k)
            d = _segment_point_distances(A[idx], B[idx], C[near])
            ok[idx[np.any(d < R[near] - 1e-7, axis=1)]] = False
    idx = np.nonzero(ok)[0]
    step = max(1, PAIR_BLOCK // m)
    for lo in range(0, len(idx), step):
        sel = idx[lo:lo + step]
        ok[sel] = np.all(world.segment_distances(A[sel], B[sel]) >= R - 1e-7, axis=1)
    return ok


def _segment_point_distances(A: np.ndarray, B: np.ndarray, Q: np.ndarray) -> np.ndarray:
    """Distance from segment ``A[i] -> B[i]`` to each point ``Q[i, j]``, shape ``(n, k)``."""
    D = (B - A)[:, None, :]
    q = Q - A[:, None, :]
    L2 = np.maximum(np.einsum("nkj,nkj->nk", D, D), 1e-300)
    t = np.clip(np.einsum("nkj,nkj->nk", q, D) / L2, 0.0, 1.0)
    e = q - t[..., None] * D
    return np.sqrt(np.einsum("nkj,nkj->nk", e, e))


def _circle_tree(world):
    from scipy.spatial import cKDTree

    tree = _DERIVED.of(world).get("circle_tree")
    if tree is None:
        tree = _DERIVED.of(world)["circle_tree"] = cKDTree(world.circles[:, :2])
    return tree


def tangent_graph_bytes(n_circles: int) -> int:
    """Bytes the tangent graph of ``n_circles`` circles can need when every tangent is free:
    ``2 n (n - 1)`` common tangents and ``4 n`` from start and goal, each two nodes and an
    edge, plus an arc edge per node (:data:`BYTES_PER_TANGENT` each)."""
    n = int(n_circles)
    return (2 * n * (n - 1) + 4 * n + 1) * BYTES_PER_TANGENT


def check_tangent_graph_size(n_circles: int) -> None:
    """ParameterError when :func:`tangent_graph_bytes` exceeds :data:`MAX_GRAPH_BYTES`."""
    need = tangent_graph_bytes(n_circles)
    if need > MAX_GRAPH_BYTES:
        n_max = int(np.sqrt(MAX_GRAPH_BYTES / (2 * BYTES_PER_TANGENT))) + 2
        while tangent_graph_bytes(n_max) > MAX_GRAPH_BYTES:
            n_max -= 1
        raise ParameterError(
            f"the exact tangent graph of {n_circles:,} circles can hold {2 * n_circles * (n_circles - 1):,} "
            f"common tangents ({need / 2**30:.3g} GiB when all are free), above the bound of "
            f"{MAX_GRAPH_BYTES / 2**30:.3g} GiB (MAX_GRAPH_BYTES), i.e. at most {n_max:,} circles; "
            "plan on a raster of the world (a GridMap) or with a metaheuristic instead")


def _pair_chunks(n: int, budget: int):
    """Circle pairs ``(I, J)``, ``I < J``, in blocks of about ``budget`` pairs (rows of the
    upper triangle), so the pairs are never all in memory at once."""
    i = 0
    while i < n - 1:
        rows, count = [], 0
        while i < n - 1 and (not rows or count + (n - 1 - i) <= budget):
            rows.append(i)
            count += n - 1 - i
            i += 1
        I = np.concatenate([np.full(n - 1 - r, r) for r in rows])
        J = np.concatenate([np.arange(r + 1, n) for r in rows])
        yield I, J


def _arcs(world, circle_of: np.ndarray, angle_of: np.ndarray):
    """Free arcs between consecutive tangent points on each circle: ``(u, v, length)``
    arrays, counter-clockwise from ``u`` to ``v``."""
    C, R = world.circles[:, :2], world.radii
    xmin, ymin, xmax, ymax = world.bounds
    on_disc = circle_of >= 0
    order = np.lexsort((angle_of[on_disc], circle_of[on_disc]))
    nodes = np.nonzero(on_disc)[0][order]
    circ = circle_of[nodes]
    U, V, L = [], [], []
    starts = np.r_[0, np.nonzero(np.diff(circ))[0] + 1, len(nodes)]
    for a, b in zip(starts[:-1], starts[1:]):
        if b - a < 2:
            continue
        i = int(circ[a])
        u = nodes[a:b]
        v = np.roll(u, -1)
        a0, a1 = angle_of[u], angle_of[v]
        span = (a1 - a0) % (2 * np.pi)
        ok = np.ones(len(u), dtype=bool)
        centre, half = _covered_intervals(C, R, i)
        if len(centre):  # the arc meets a covered interval [c - h, c + h]
            st = (centre[None, :] - half[None, :] - a0[:, None]) % (2 * np.pi)
            ok &= ~np.any((st < span[:, None] - _EPS) | (st + 2 * half[None, :] > 2 * np.pi - _EPS), axis=1)
        cx, cy = C[i]
        if not (cx - R[i] >= xmin and cx + R[i] <= xmax and cy - R[i] >= ymin and cy + R[i] <= ymax):
            for k in np.nonzero(ok)[0]:  # a disc across the border: sample its arcs
                t = a0[k] + np.linspace(0, span[k], max(3, int(span[k] * 32)))
                px, py = cx + R[i] * np.cos(t), cy + R[i] * np.sin(t)
                ok[k] = bool(np.all((px >= xmin) & (px <= xmax) & (py >= ymin) & (py <= ymax)))
        U.append(u[ok])
        V.append(v[ok])
        L.append(R[i] * span[ok])
    if not U:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
    return np.concatenate(U), np.concatenate(V), np.concatenate(L)


# slacks over the straight distance tried in turn by tangent_shortest_path: the graph is built
# only where a path that short can pass, and a path found within the slack is the optimum
BOUND_SLACKS = (1.005, 1.03, 1.15, 1.6)


def tangent_shortest_path(world, start, goal, arc_step_deg: float = 2.0):
    """Exact optimum length and a validating polyline for a CircleWorld.

    Only free tangent segments make nodes (a tangent point no free segment reaches is
    passed along its arc anyway), so the graph holds what can be on a path.
    Memory: tangents are generated and checked in blocks of :data:`PAIR_BLOCK` circle
    pairs, and a world whose graph could exceed :data:`MAX_GRAPH_BYTES` is refused
    before anything is built (:func:`check_tangent_graph_size`).

    Bounded search, exact: with a bound ``U`` on the length, a point ``x`` of a path
    no longer than ``U`` has ``|s - x| + |x - g| <= U``, so only circles that reach into
    that ellipse and tangents whose ends (and length) fit in it are built
    (:func:`_tangent_graph`). If the graph holds a path of length ``<= U``, its optimum
    is the optimum; otherwise the bound grows (:data:`BOUND_SLACKS` times the straight
    distance, then none). A corner-to-corner query among 400 circles builds a few
    percent of the tangents.

    Returns ``(length, polyline)``; raises InfeasibleQueryError when the goal is unreachable,
    ParameterError when the world has too many circles for the bound.
    """
    s, g = np.asarray(start, float), np.asarray(goal, float)
    check_tangent_graph_size(len(world.circles))
    straight = float(np.hypot(*(g - s)))
    for bound in [straight * k + 1e-9 for k in BOUND_SLACKS] + [np.inf]:
        found = _tangent_graph(world, s, g, bound, arc_step_deg)
        if found is not None and found[0] <= bound:
            return found
    raise InfeasibleQueryError("the goal is unreachable: circles (grown by the safety distance) separate it from the start")


def _tangent_graph(world, s: np.ndarray, g: np.ndarray, bound: float, arc_step_deg: float):
    """Dijkstra on the tangent graph restricted to the ellipse ``|s - x| + |x - g| <= bound``
    (every circle and tangent when ``bound`` is infinite): ``(length, polyline)``, or
    ``None`` when that graph does not join start and goal."""
    C, R = world.circles[:, :2], world.radii
    n = len(C)
    focal = np.hypot(*(C - s).T) + np.hypot(*(C - g).T) - 2 * R
    kept = np.nonzero(focal <= bound)[0]   # circles with a boundary point inside the ellipse

    def fits(a, b, length):
        """Tangents ``a -> b`` (of that length) a path within the bound can use."""
        return np.hypot(*(a - s).T) + length + np.hypot(*(b - g).T) <= bound

    xy, circ, ang = [np.stack([s, g])], [np.array([-1, -1])], [np.zeros(2)]
    EU, EV, EW = [], [], []
    count = 2

    def add(P, ids, angs):
        nonlocal count
        xy.append(P)
        circ.append(np.asarray(ids, np.int64))
        ang.append(np.asarray(angs, float))
        idx = count + np.arange(len(P))
        count += len(P)
        return idx

    if _segments_clear(world, s[None], g[None])[0]:
        EU.append([0]), EV.append([1]), EW.append([float(np.hypot(*(g - s)))])
    for k, p in enumerate((s, g)):
        P, ids, angs = _point_tangents(p, C[kept], R[kept])
        ids = kept[ids]
        dist_p = np.hypot(*(P - p).T)
        # a tangent from the start ends at x with |s - x| + |x - g| <= bound; from the goal alike
        ok = dist_p + np.hypot(*(P - (g if k == 0 else s)).T) <= bound
        ok[ok] = _segments_clear(world, np.broadcast_to(p, P[ok].shape), P[ok])
        idx = add(P[ok], ids[ok], angs[ok])
        EU.append(np.full(len(idx), k)), EV.append(idx), EW.append(np.hypot(*(P[ok] - p).T))
    if len(kept) > 1:
        for I, J in _pair_chunks(len(kept), PAIR_CHUNK):
            pa, pb, i, j, ai, aj = _common_tangents(C, R, kept[I], kept[J])
            # either direction: the path may run a -> b or b -> a
            length = np.hypot(*(pb - pa).T)
            ok = fits(pa, pb, length) | fits(pb, pa, length)
            ok[ok] = _segments_clear(world, pa[ok], pb[ok])
            ia = add(pa[ok], i[ok], ai[ok])
            ib = add(pb[ok], j[ok], aj[ok])
            EU.append(ia), EV.append(ib), EW.append(np.hypot(*(pb[ok] - pa[ok]).T))
    nodes = np.concatenate(xy)
    circle_of = np.concatenate(circ)
    angle_of = np.concatenate(ang) % (2 * np.pi)
    au, av, al = _arcs(world, circle_of, angle_of)
    u = np.concatenate([np.concatenate(EU).astype(np.int64), au])
    v = np.concatenate([np.concatenate(EV).astype(np.int64), av])
    w = np.concatenate([np.concatenate(EW).astype(float), al])
    graph = coo_matrix((w, (u, v)), shape=(count, count)).tocsr()
    dist, pred = dijkstra(graph, directed=False, indices=0, return_predecessors=True)
    if not np.isfinite(dist[1]):
        return None
    chain = [1]
    while chain[-1] != 0:
        chain.append(int(pred[chain[-1]]))
    chain = chain[::-1]
    pts = [nodes[chain[0]]]
    for a, b in zip(chain[:-1], chain[1:]):
        if circle_of[a] >= 0 and circle_of[a] == circle_of[b]:  # tangents join two circles: this is an arc
            i = circle_of[a]
            a0, a1 = angle_of[a], angle_of[b]
            # arc edges were stored counter-clockwise from the earlier-sorted node;
            # walking the chain backwards means going clockwise
            span = (a1 - a0) % (2 * np.pi)
            if abs(R[i] * span - abs(dist[b] - dist[a])) > 1e-9:
                span = -((a0 - a1) % (2 * np.pi))
            steps = max(1, int(np.ceil(abs(np.degrees(span)) / arc_step_deg)))
            delta = span / steps
            rout = R[i] / np.cos(delta / 2) + 1e-9  # circumscribed polygon stays outside the disc
            mids = a0 + delta * (np.arange(steps) + 0.5)
            pts.extend(C[i] + rout * np.stack([np.cos(mids), np.sin(mids)], 1))
        pts.append(nodes[b])
    poly = np.array(pts, dtype=float)
    # tangent points lie exactly on their circle: nudge them outwards so rounding
    # cannot put them a hair inside. Only ever outwards: the circumscribed-polygon
    # vertices of a short arc sit less than 1e-7 outside, and pulling them in to
    # R + 1e-9 would let the chord between their neighbours cut the disc.
    if n:
        near_idx = _circle_tree(world).query_ball_point(poly, r=float(R.max()) + 1e-9)
        for k, cands in enumerate(near_idx):
            for i in cands:
                d = poly[k] - C[i]
                dc = float(np.hypot(*d))
                if R[i] - 1e-7 < dc < R[i] + 1e-9:
                    poly[k] = C[i] + d / dc * (R[i] + 1e-9)
    return float(dist[1]), poly


def plan_tangent(world, start, goal, clearance: float = 0.0):
    """``shortest_path(circle_world, ..., method="visibility")``: exact optimum among circles."""
    t0 = time.perf_counter()
    s, g = check_start_goal(world, start, goal, clearance)
    if clearance > 0:
        from ..world.circles import CircleWorld

        world_c = CircleWorld(world.bounds, world.circles, world.safety + clearance, world.name)
    else:
        world_c = world
    length, poly = tangent_shortest_path(world_c, s, g)
    res = make_plan_result(world, poly, "visibility", time.perf_counter() - t0, clearance=clearance,
                           message=f"exact optimum {length:.9f} m; polyline follows arcs from outside")
    res.length = length if res.feasible else res.length
    return res
