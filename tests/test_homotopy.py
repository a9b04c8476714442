"""The shortest path in an h-signature class (issue 26): exact, never longer than its seed,
and the same as brute-force enumeration on small maps."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.errors import ParameterError
from optplan.solvers.gaps import class_gaps
from optplan.world.roadmap import Roadmap
from optplan.worldgen.maps import generate_map, map_query


def small_map() -> op.GridMap:
    occ = np.zeros((8, 9), bool)
    occ[2:4, 2:4] = True      # two interior blocks and one touching the border
    occ[5, 5:7] = True
    occ[0:2, 7] = True
    return op.GridMap(occ)


def winding(path: np.ndarray, p: np.ndarray) -> float:
    """Total signed angle swept about ``p`` (radians), independent of the rays."""
    a = np.arctan2(path[:, 1] - p[1], path[:, 0] - p[0])
    d = np.diff(a)
    return float(((d + np.pi) % (2 * np.pi) - np.pi).sum())


def brute_force_classes(grid, s, g, bound):
    """Every simple path over all convex corners (no tautness pruning) with length <= bound,
    by depth-first enumeration; the shortest per h-signature."""
    rm = Roadmap.of(grid)
    pts = np.vstack([s, rm.nodes, g])
    n = len(pts)
    I, J = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    vis = grid.segments_free(pts[I.ravel()], pts[J.ravel()]).reshape(n, n)
    np.fill_diagonal(vis, False)
    W = np.hypot(*(pts[:, None] - pts[None]).transpose(2, 0, 1))
    h = np.hypot(*(pts - g).T)
    best: dict[tuple, tuple[float, list[int]]] = {}
    stack = [(0, 0.0, [0])]
    while stack:
        u, L, seq = stack.pop()
        if u == n - 1:
            key = tuple(rm.signature(pts[seq]))
            if key not in best or L < best[key][0]:
                best[key] = (L, seq)
            continue
        for v in np.nonzero(vis[u])[0]:
            if v in seq or L + W[u, v] + h[v] > bound:
                continue
            stack.append((int(v), L + W[u, v], seq + [int(v)]))
    return {k: (L, pts[seq]) for k, (L, seq) in best.items()}


def test_class_search_matches_brute_force_on_a_small_map():
    grid = small_map()
    s, g = np.array([0.5, 0.5]), np.array([8.5, 7.5])
    exact = op.shortest_path(grid, s, g, method="visibility").length
    classes = brute_force_classes(grid, s, g, 1.5 * exact)
    assert len(classes) >= 3          # the interior blocks split the paths into several classes
    for sig, (L, P) in classes.items():
        res = op.shortest_path(grid, s, g, method="visibility", homotopy=P)
        assert res.feasible
        assert res.length == pytest.approx(L, rel=1e-9, abs=1e-9)
        assert tuple(Roadmap.of(grid).signature(res.path)) == sig
    assert min(L for L, _ in classes.values()) == pytest.approx(exact, rel=1e-9)


def test_same_signature_means_same_winding_about_every_interior_component():
    grid = small_map()
    s, g = np.array([0.5, 0.5]), np.array([8.5, 7.5])
    exact = op.shortest_path(grid, s, g, method="visibility").length
    rm = Roadmap.of(grid)
    classes = brute_force_classes(grid, s, g, 1.5 * exact)
    paths = [P for _, P in classes.values()]
    for a in paths:
        for b in paths:
            loop = np.vstack([a, b[::-1]])
            same = np.array_equal(rm.signature(a), rm.signature(b))
            turns = [round(winding(loop, p) / (2 * np.pi)) for p in rm.rays]
            assert same == all(t == 0 for t in turns)


@pytest.mark.parametrize("kind,size,seed", [("random", 20, 11), ("rooms", 24, 12), ("maze", 21, 13)])
def test_class_optimum_of_the_optimum_is_the_optimum_and_never_longer_than_a_seed(kind, size, seed):
    grid = generate_map(kind, size, seed=seed, density=0.2)
    s, g = map_query(grid, seed=seed)
    best = op.shortest_path(grid, s, g, method="visibility")
    again = op.shortest_path(grid, s, g, method="visibility", homotopy=best.path)
    assert again.length == pytest.approx(best.length, rel=1e-9)
    astar = op.shortest_path(grid, s, g, method="astar")
    klass = op.shortest_path(grid, s, g, method="visibility", homotopy=astar.path)
    assert klass.feasible and best.length - 1e-9 <= klass.length <= astar.length + 1e-9
    gaps = class_gaps(grid, s, g, astar.path)
    assert gaps["gap"] == pytest.approx(gaps["class_gap"] + gaps["in_class_gap"], abs=1e-12)
    assert gaps["in_class_gap"] > 0   # the octile path is never taut


def test_circle_world_class_search():
    world = op.CircleWorld(bounds=(0, 0, 10, 10), circles=[(5, 5, 1.5), (2.5, 7, 0.8)])
    s, g = np.array([0.5, 5.0]), np.array([9.5, 5.0])
    above = np.array([s, [3.5, 6.0], [5, 7], [7.5, 6.5], g])
    below = np.array([s, [5, 3], g])
    up = op.shortest_path(world, s, g, method="visibility", homotopy=above)
    down = op.shortest_path(world, s, g, method="visibility", homotopy=below)
    assert up.feasible and down.feasible
    assert up.path[:, 1].max() > 6 and down.path[:, 1].min() < 4        # each stays on its side
    true = 2 * np.sqrt(4.5 ** 2 - 1.5 ** 2) + 1.5 * (np.pi - 2 * np.arccos(1.5 / 4.5))
    assert down.length == pytest.approx(true, rel=0.01)                 # polygon sides, not arcs


def test_homotopy_needs_a_feasible_path_and_the_visibility_method():
    grid = small_map()
    s, g = np.array([0.5, 0.5]), np.array([8.5, 7.5])
    with pytest.raises(ParameterError, match="not collision-free"):
        op.shortest_path(grid, s, g, method="visibility", homotopy=np.array([s, g]))
    with pytest.raises(ParameterError, match="method='visibility'"):
        op.shortest_path(grid, s, g, method="astar", homotopy=np.array([s, g]))
