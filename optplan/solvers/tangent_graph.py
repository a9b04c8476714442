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

from ..errors import InfeasibleQueryError
from .result import make_plan_result
from ..world.queries import check_start_goal

_EPS = 1e-9


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


def _common_tangents(C: np.ndarray, R: np.ndarray):
    """All common tangent segments between circle pairs: (a_pts, b_pts, i, j, ang_i, ang_j)."""
    n = len(C)
    I, J = np.triu_indices(n, 1)
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


def _arc_free(world, i: int, a0: float, a1: float, cov) -> bool:
    """Counter-clockwise arc from a0 to a1 on circle i avoids other circles and the border."""
    span = (a1 - a0) % (2 * np.pi)
    centre, half = cov
    for c, h in zip(centre, half):
        # the arc meets the covered interval [c - h, c + h]
        start = (c - h - a0) % (2 * np.pi)
        if start < span - _EPS or (start + 2 * h) > 2 * np.pi - _EPS:
            return False
    C, R = world.circles[i, :2], world.radii[i]
    t = a0 + np.linspace(0, span, max(3, int(span * 32)))
    pts = C + R * np.stack([np.cos(t), np.sin(t)], 1)
    xmin, ymin, xmax, ymax = world.bounds
    return bool(np.all((pts[:, 0] >= xmin) & (pts[:, 0] <= xmax) & (pts[:, 1] >= ymin) & (pts[:, 1] <= ymax)))


def _segments_clear(world, A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Tangent segments touch their own circles exactly; allow a tiny tolerance."""
    if len(A) == 0:
        return np.zeros(0, bool)
    dist = world.segment_distances(A, B)
    ok = np.all(dist >= world.radii - 1e-7, axis=1)
    xmin, ymin, xmax, ymax = world.bounds
    for P in (A, B):
        ok &= (P[:, 0] >= xmin - 1e-12) & (P[:, 0] <= xmax + 1e-12) & (P[:, 1] >= ymin - 1e-12) & (P[:, 1] <= ymax + 1e-12)
    return ok


def tangent_shortest_path(world, start, goal, arc_step_deg: float = 2.0):
    """Exact optimum length and a validating polyline for a CircleWorld.

    Returns ``(length, polyline)``; raises InfeasibleQueryError when the goal is unreachable.
    """
    s, g = np.asarray(start, float), np.asarray(goal, float)
    C, R = world.circles[:, :2], world.radii
    nodes = [s, g]
    circle_of = [-1, -1]
    angle_of = [0.0, 0.0]
    edges = []  # (u, v, w)

    def add_nodes(P, ids, angs):
        base = len(nodes)
        nodes.extend(P)
        circle_of.extend(ids)
        angle_of.extend(angs)
        return base + np.arange(len(P))

    if _segments_clear(world, s[None], g[None])[0]:
        edges.append((0, 1, float(np.hypot(*(g - s)))))
    for k, p in enumerate((s, g)):
        P, ids, angs = _point_tangents(p, C, R)
        idx = add_nodes(P, ids, angs)
        ok = _segments_clear(world, np.repeat(p[None], len(P), 0), P)
        for u, q in zip(idx[ok], P[ok]):
            edges.append((k, int(u), float(np.hypot(*(q - p)))))
    if len(C) > 1:
        pa, pb, I, J, ai, aj = _common_tangents(C, R)
        ok = _segments_clear(world, pa, pb)
        ia = add_nodes(pa, I, ai)
        ib = add_nodes(pb, J, aj)
        L = np.hypot(*(pb - pa).T)
        for u, v, w in zip(ia[ok], ib[ok], L[ok]):
            edges.append((int(u), int(v), float(w)))
    circle_of = np.asarray(circle_of)
    angle_of = np.asarray(angle_of) % (2 * np.pi)
    for i in range(len(C)):
        on = np.nonzero(circle_of == i)[0]
        if len(on) < 2:
            continue
        order = on[np.argsort(angle_of[on])]
        cov = _covered_intervals(C, R, i)
        for u, v in zip(order, np.roll(order, -1)):
            if _arc_free(world, i, angle_of[u], angle_of[v], cov):
                span = (angle_of[v] - angle_of[u]) % (2 * np.pi)
                edges.append((int(u), int(v), float(R[i] * span)))
    e = np.array(edges, dtype=float).reshape(-1, 3)
    n = len(nodes)
    graph = coo_matrix((e[:, 2], (e[:, 0].astype(int), e[:, 1].astype(int))), shape=(n, n)).tocsr()
    dist, pred = dijkstra(graph, directed=False, indices=0, return_predecessors=True)
    if not np.isfinite(dist[1]):
        raise InfeasibleQueryError("the goal is unreachable: circles (grown by the safety distance) separate it from the start")
    chain = [1]
    while chain[-1] != 0:
        chain.append(int(pred[chain[-1]]))
    chain = chain[::-1]
    pts = [nodes[chain[0]]]
    for u, v in zip(chain[:-1], chain[1:]):
        if circle_of[u] >= 0 and circle_of[u] == circle_of[v]:
            i = circle_of[u]
            a0, a1 = angle_of[u], angle_of[v]
            # arc edges were stored counter-clockwise from the earlier-sorted node;
            # walking the chain backwards means going clockwise
            span = (a1 - a0) % (2 * np.pi)
            if abs(R[i] * span - max(graph[u, v], graph[v, u])) > 1e-9:
                span = -((a0 - a1) % (2 * np.pi))
            steps = max(1, int(np.ceil(abs(np.degrees(span)) / arc_step_deg)))
            delta = span / steps
            rout = R[i] / np.cos(delta / 2) + 1e-9  # circumscribed polygon stays outside the disc
            mids = a0 + delta * (np.arange(steps) + 0.5)
            pts.extend(C[i] + rout * np.stack([np.cos(mids), np.sin(mids)], 1))
        pts.append(nodes[v])
    poly = np.array(pts, dtype=float)
    # tangent points lie exactly on their circle: nudge them outwards so rounding
    # cannot put them a hair inside. Only ever outwards: the circumscribed-polygon
    # vertices of a short arc sit less than 1e-7 outside, and pulling them in to
    # R + 1e-9 would let the chord between their neighbours cut the disc.
    d = poly[:, None, :] - C[None, :, :]
    dist_c = np.hypot(d[..., 0], d[..., 1])
    near = (dist_c > R - 1e-7) & (dist_c < R + 1e-9)
    for k, i in zip(*np.nonzero(near)):
        poly[k] = C[i] + d[k, i] / dist_c[k, i] * (R[i] + 1e-9)
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
