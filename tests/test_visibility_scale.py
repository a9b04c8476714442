"""The fast exact any-angle search (issue 43): the same optimum as the search over every corner.

``visibility_path(..., search="tiled")`` (the default) prunes where it looks for visible
corners (corner tiles, shadows of near blocked cells, grid lines, taut regions) and computes
edges in batches; ``search="scan"`` is the reference that looks at every corner on every
expansion. These tests check the prunings one by one against the exact segment rule, and the
whole search against known optima, a brute-force any-angle optimum and the reference.
"""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.world import shadows as S
from optplan.solvers.graph import visibility as V
from optplan.solvers.graph.visibility import corner_nodes, visibility_path
from optplan.world.geometry import segments_free
from optplan.worldgen.maps import generate_map, map_query

from conftest import random_grid

SQ2 = float(np.sqrt(2.0))


def both(grid, s, g, **kw):
    """(new, old) results of visibility_path; None where the goal is unreachable."""
    out = []
    for search in ("tiled", "scan"):
        try:
            out.append(visibility_path(grid, s, g, search=search, **kw))
        except op.InfeasibleQueryError:
            out.append(None)
    return out


def brute_force(grid, s, g) -> float:
    """Dijkstra over the complete visibility graph of every free, non-double lattice vertex and
    the two ends (half-lattice ends: the rule is integer-exact on every pair)."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import dijkstra

    pad = grid.padded
    bl, br, tl, tr = pad[:-1, :-1], pad[:-1, 1:], pad[1:, :-1], pad[1:, 1:]
    double = (bl & tr & ~br & ~tl) | (br & tl & ~bl & ~tr)
    Y, X = np.nonzero(~double)
    Vx = np.stack([X, Y], axis=1).astype(float)
    Vx = Vx[grid.is_free(Vx)]
    P = np.vstack([s, g, Vx])
    I, J = np.triu_indices(len(P), 1)
    ok = segments_free(grid, P[I], P[J])
    W = np.zeros((len(P), len(P)))
    W[I[ok], J[ok]] = np.hypot(*(P[J[ok]] - P[I[ok]]).T)
    return float(dijkstra(csr_matrix(W), directed=False, indices=0)[1])


# ------------------------------------------------------------------ known optima
def test_single_block_is_passed_on_its_tangents():
    occ = np.zeros((9, 9), bool)
    occ[3:6, 3:6] = True
    grid = op.GridMap(occ)
    s, g = np.array([0.5, 4.5]), np.array([8.5, 4.5])
    best = 2 * np.hypot(2.5, 1.5) + 3.0  # (0.5, 4.5) -> (3, 6) -> (6, 6) -> (8.5, 4.5), or mirrored
    new, old = both(grid, s, g)
    assert new[1] == pytest.approx(best, rel=1e-12) and old[1] == pytest.approx(best, rel=1e-12)
    assert np.array_equal(new[0], old[0])
    assert op.validate_path(grid, new[0])
    # the path bends only at the block's corners
    assert {tuple(p) for p in new[0][1:-1]} in ({(3.0, 6.0), (6.0, 6.0)}, {(3.0, 3.0), (6.0, 3.0)})


def test_diagonal_pair_is_not_squeezed_through():
    # cells (2, 2) and (3, 3) blocked: they meet only at the lattice vertex (3, 3)
    occ = np.zeros((6, 6), bool)
    occ[2, 2] = occ[3, 3] = True
    grid = op.GridMap(occ)
    s, g = np.array([2.5, 3.5]), np.array([3.5, 2.5])
    assert not segments_free(grid, s, g)  # the straight segment passes the double corner
    new, old = both(grid, s, g)
    assert new[1] == pytest.approx(2.0 + SQ2, rel=1e-12)  # round one end of the pair
    assert old[1] == pytest.approx(new[1], rel=1e-12)
    assert op.validate_path(grid, new[0])
    assert not any(np.array_equal(p, [3.0, 3.0]) for p in new[0])


def test_a_far_pinhole_seen_through_clutter_near_the_start():
    # a wall at x = 20 with a one-cell hole at y = 10, clutter near the start that leaves a
    # narrow gap of directions: the optimum goes straight through the hole
    occ = np.zeros((21, 40), bool)
    occ[:, 20] = True
    occ[10, 20] = False
    occ[12, 3] = occ[8, 3] = occ[13, 5] = occ[7, 5] = True
    grid = op.GridMap(occ)
    s, g = np.array([1.5, 10.5]), np.array([38.5, 10.5])
    new, old = both(grid, s, g)
    assert new[1] == pytest.approx(37.0, rel=1e-12) and old[1] == pytest.approx(37.0, rel=1e-12)


def test_a_path_along_a_grid_line_between_offset_blocks():
    # blocks below and above the line y = 4 that never face each other across it: a path may
    # run along the line; one pair that does face each other closes it further on
    occ = np.zeros((8, 24), bool)
    occ[3, 4:7] = True     # below the line
    occ[4, 8:11] = True    # above it
    occ[3, 12:14] = True
    grid = op.GridMap(occ)
    s, g = np.array([2.0, 2.0]), np.array([16.0, 6.0])
    new, old = both(grid, s, g)
    assert new[1] == pytest.approx(old[1], rel=1e-12) == pytest.approx(brute_force(grid, s, g), rel=1e-12)
    occ[4, 12] = True      # now the edge from (12, 4) to (13, 4) has blocked cells on both sides
    grid = op.GridMap(occ)
    new, old = both(grid, s, g)
    assert new[1] == pytest.approx(old[1], rel=1e-12) == pytest.approx(brute_force(grid, s, g), rel=1e-12)
    assert op.validate_path(grid, new[0])


# ------------------------------------------------------------ against brute force
@pytest.mark.parametrize("seed", range(24))
def test_small_random_maps_match_the_brute_force_optimum(seed):
    """Ends at centres, edge midpoints and lattice vertices of free cells (so every pair is
    integer-exact in the brute force)."""
    rng = np.random.default_rng(4300 + seed)
    h, w = rng.integers(6, 14, 2)
    grid = random_grid(rng, h, w, rng.uniform(0.15, 0.35))
    free = np.argwhere(~grid.occ)[:, ::-1].astype(float)
    if len(free) < 2:
        return
    for _ in range(3):
        a, b = free[rng.choice(len(free), 2, replace=False)]
        s, g = a + rng.choice([0.0, 0.5, 1.0], 2), b + rng.choice([0.0, 0.5, 1.0], 2)
        if not (grid.is_free(s) and grid.is_free(g)) or np.array_equal(s, g):
            continue
        best = brute_force(grid, s, g)
        new, old = both(grid, s, g)
        if not np.isfinite(best):
            assert new is None and old is None
            continue
        assert new[1] == pytest.approx(best, rel=1e-12, abs=1e-12)
        assert old[1] == pytest.approx(best, rel=1e-12, abs=1e-12)
        assert op.validate_path(grid, new[0])


# ------------------------------------------------------------------- against scan
CASES = [("random", 40, 3), ("random", 64, 11), ("rooms", 48, 5), ("maze", 41, 2), ("random", 96, 7)]


@pytest.mark.parametrize("kind,n,seed", CASES)
def test_generated_maps_give_the_reference_path(kind, n, seed):
    grid = generate_map(kind, n, seed=seed)
    rng = np.random.default_rng(seed)
    queries = [map_query(grid, seed=seed)]
    free = np.argwhere(~grid.occ)[:, ::-1].astype(float)
    for off in ("inside", "lattice"):
        a, b = free[rng.choice(len(free), 2, replace=False)]
        d = rng.uniform(0.05, 0.95, (2, 2)) if off == "inside" else rng.choice([0.0, 0.5, 1.0], (2, 2))
        queries.append((a + d[0], b + d[1]))
    for s, g in queries:
        if not (grid.is_free(s) and grid.is_free(g)):
            continue
        new, old = both(grid, s, g)
        assert (new is None) == (old is None)
        if new is not None:
            assert new[1] == pytest.approx(old[1], rel=1e-12)
            assert np.array_equal(new[0], old[0])
            assert op.validate_path(grid, new[0])


@pytest.mark.parametrize("kind,n,seed", [("random", 32, 1), ("rooms", 40, 2), ("maze", 33, 4)])
def test_clearance_gives_the_reference_path(kind, n, seed):
    grid = generate_map(kind, n, seed=seed)
    s, g = map_query(grid, seed=seed)
    for c in (0.25, 0.5):
        new, old = both(grid, s, g, clearance=c)
        assert (new is None) == (old is None)
        if new is not None:
            assert new[1] == pytest.approx(old[1], rel=1e-12)
            assert op.validate_path(grid, new[0], c)


def test_unreachable_without_search_agrees_with_the_reference():
    # a walled-in pocket: A* over cells finds nothing, and neither does the full search
    occ = np.zeros((12, 12), bool)
    occ[3:9, 3] = occ[3:9, 8] = occ[3, 3:9] = occ[8, 3:9] = True
    grid = op.GridMap(occ)
    new, old = both(grid, np.array([5.5, 5.5]), np.array([0.5, 0.5]))
    assert new is None and old is None
    # a one-cell pocket whose only way out is a diagonal step through a double corner
    occ = np.zeros((7, 7), bool)
    occ[2:5, 2:5] = True
    occ[3, 3] = occ[4, 4] = False  # cells (3, 3) and (4, 4) meet only at the vertex (4, 4)
    grid = op.GridMap(occ)
    new, old = both(grid, np.array([3.5, 3.5]), np.array([0.5, 0.5]))
    assert new is None and old is None


def test_prunings_can_be_turned_down_without_changing_the_answer(monkeypatch):
    grid = generate_map("random", 48, seed=9)
    s, g = map_query(grid, seed=9)
    ref = visibility_path(grid, s, g, search="scan")
    for name, value in (("SHADOW_RADIUS", 1), ("QUADRANT_RADIUS", 2), ("TILE_MIN", 2), ("TILE_COUNT", 4)):
        with monkeypatch.context() as m:
            m.setattr(S, name, value)
            got = visibility_path(grid, s, g)
        assert got[1] == pytest.approx(ref[1], rel=1e-12), name
        assert np.array_equal(got[0], ref[0]), name
    with monkeypatch.context() as m:
        m.setattr(V, "TILED_SAMPLE_STEPS", np.zeros(0))
        m.setattr(V, "BATCH", 1)
        got = visibility_path(grid, s, g)
    assert np.array_equal(got[0], ref[0])


# ------------------------------------------------------------ the prunings alone
def _maps():
    rng = np.random.default_rng(77)
    for k in range(6):
        yield random_grid(rng, 20, 24, 0.15 + 0.04 * k)
    yield generate_map("maze", 21, seed=1)
    yield generate_map("rooms", 24, seed=3)


@pytest.mark.parametrize("grid", list(_maps()), ids=lambda g: f"{g.width}x{g.height}")
def test_shadows_and_grid_lines_hide_only_blocked_corners(grid):
    """Every corner that the wedges of near cells, or a grid line's blocked edges, say is
    hidden from a point is refused by the exact rule."""
    rng = np.random.default_rng(grid.width * 7 + int(grid.occ.sum()))
    C, Qc = corner_nodes(grid)
    free = np.argwhere(~grid.occ)[:, ::-1].astype(float)
    U = np.vstack([C[rng.choice(len(C), 12, replace=False)],
                   free[rng.choice(len(free), 6, replace=False)] + rng.uniform(0, 1, (6, 2))])
    quads = np.zeros((len(U), 2), np.int64)
    quads[:6] = rng.choice([-1, 1], (6, 2))  # half of the corners: a quadrant window, asked about it only
    sh = S.Shadows(grid.occ, U, quads)
    lines = S.GridLines(grid.padded)
    hidden_any = 0
    for k, u in enumerate(U):
        d = C - u
        keep = np.hypot(*d.T) > 0
        if quads[k].any():
            keep &= (quads[k][0] * d[:, 0] >= 0) & (quads[k][1] * d[:, 1] >= 0)
        Vk, dk = C[keep], d[keep]
        step = np.hypot(*dk.T)
        owner = np.full(len(Vk), k)
        theta = S.direction(dk)
        far = step > sh.reach[k] + S.DIST_SLACK
        hidden = np.zeros(len(Vk), bool)
        hidden[far] = sh.covers(owner[far], theta[far])
        hidden[~far] = sh.hides(owner[~far], theta[~far], step[~far])
        hidden |= lines.blocked(np.broadcast_to(u, Vk.shape), Vk)
        free_seg = segments_free(grid, np.broadcast_to(u, Vk.shape), Vk)
        assert not np.any(hidden & free_seg), (u, Vk[hidden & free_seg])
        hidden_any += int(hidden.sum())
    assert hidden_any > 0  # the test looks at something


def test_grid_lines_count_exactly():
    """Between lattice vertices on one grid line, the counts decide the rule exactly."""
    rng = np.random.default_rng(5)
    grid = random_grid(rng, 15, 17, 0.35)  # 17 columns, 15 rows
    lines = S.GridLines(grid.padded)
    A = np.stack([rng.integers(0, 18, 600), rng.integers(0, 16, 600)], axis=1).astype(float)
    B = A.copy()
    horiz = rng.random(600) < 0.5
    B[horiz, 0] = rng.integers(0, 18, int(horiz.sum()))
    B[~horiz, 1] = rng.integers(0, 16, int((~horiz).sum()))
    moving = np.any(A != B, axis=1)
    A, B = A[moving], B[moving]
    ok = segments_free(grid, A, B)
    assert np.array_equal(lines.blocked(A, B), ~ok)
    assert ok.any() and (~ok).any()


def tangent(d, q):
    """The line of ``d`` through a corner does not enter its blocked quadrant ``q`` nor the opposite."""
    s = np.sign(d)
    axis = (s[:, 0] == 0) | (s[:, 1] == 0)
    same = (s[:, 0] == q[..., 0]) & (s[:, 1] == q[..., 1])
    opposite = (s[:, 0] == -q[..., 0]) & (s[:, 1] == -q[..., 1])
    return axis | ~(same | opposite)


def taut(a, b, w):
    """The blocked cell (direction ``w``) lies inside the turn from ``a`` (back) to ``b`` (on)."""
    cab = a[0] * b[:, 1] - a[1] * b[:, 0]
    caw = a[0] * w[1] - a[1] * w[0]
    cwb = w[0] * b[:, 1] - w[1] * b[:, 0]
    inside = (np.sign(caw) == np.sign(cab)) & (np.sign(cwb) == np.sign(cab)) & (cab != 0)
    return inside | ((cab == 0) & (a @ b.T < 0))


@pytest.mark.parametrize("tile", [1, 6])
def test_tiles_list_every_visible_taut_corner(tile):
    """The tiles' candidates (with the ellipse, the taut region and the shadows) hold every
    corner that the full search would keep as an edge at that expansion; with one corner per
    tile every boundary case (a straight pass, a corner on the quadrant's edge) is its own tile."""
    grid = generate_map("random", 40, seed=21)
    C, Qc = corner_nodes(grid)
    rng = np.random.default_rng(tile)
    P = np.vstack([[0.5, 0.5], [39.5, 39.5], C])
    tiles = S.CornerTiles(C, first=2, lattice=True, tile=tile)
    checked = straight = 0
    for trial in range(300):
        u = int(rng.integers(2, len(P)))
        if trial % 2:
            a = P[int(rng.integers(0, len(P)))] - P[u]      # from some node
        else:
            a = -(P[int(rng.integers(2, len(P)))] - P[u])   # so that a corner lies straight on
        if not np.any(a) or not tangent(a[None], Qc[u - 2])[0]:
            continue  # the search only arrives along tangent lines
        turn, quadrant, n = S.taut_regions(a[None], Qc[u - 2][None])
        quadrant = np.where(turn[:, None], quadrant, 0)
        sh = S.Shadows(grid.occ, P[u][None], quadrant)
        budget = np.array([np.hypot(*(P[u] - P[1])) + rng.uniform(0, 30)])
        owner, J = tiles.candidates(P[u][None], P[1], budget, sh, turn, quadrant, n)
        on_row, on_col = tiles.lines_through(P[u][None])
        _, lj = tiles.on_lines(P[u][None], on_row, on_col)
        listed = set(J.tolist()) | set(lj.tolist())
        d = P[2:] - P[u]
        step = np.hypot(*d.T)
        # a tile left out holds only corners its shadows hide (off the grid lines through u)
        off_lines = ~((on_row[0] & (d[:, 1] == 0)) | (on_col[0] & (d[:, 0] == 0)))
        left = np.array(sorted(set(range(2, len(P))) - listed), dtype=np.int64)
        if not sh.empty and left.size:
            inside = (step[left - 2] + np.hypot(*(P[left] - P[1]).T) <= budget[0]) & off_lines[left - 2]
            if turn[0]:
                inside &= (quadrant[0, 0] * d[left - 2, 0] >= 0) & (quadrant[0, 1] * d[left - 2, 1] >= 0)
                inside &= n[0] @ d[left - 2].T >= 0
            k = left[inside] - 2
            hidden = (step[k] > sh.reach[0]) & sh.covers(np.zeros(len(k), np.int64), S.direction(d[k]))
            assert np.all(hidden), (P[u], C[k[~hidden]])
        want = (step + np.hypot(*(P[2:] - P[1]).T) <= budget[0]) & (step > 0)
        want &= tangent(d, Qc[u - 2]) & tangent(d, Qc) & taut(a, d, Qc[u - 2])
        want &= segments_free(grid, np.broadcast_to(P[u], d.shape), P[2:])
        missing = set((np.nonzero(want)[0] + 2).tolist()) - listed
        assert not missing, (P[u], P[sorted(missing)])
        checked += int(want.sum())
        straight += int((want & (a[0] * d[:, 1] - a[1] * d[:, 0] == 0)).sum())
    assert checked > 50 and straight > 5


def test_wedge_chains_never_bridge_a_gap():
    """A direction just past a wedge's end that no other wedge holds is open: no span across it
    is hidden, however narrow the gap (wedges that only touch leave one)."""
    rng = np.random.default_rng(8)
    gaps = 0
    for k in range(12):
        grid = random_grid(rng, 30, 30, 0.2 + 0.02 * k)
        U = np.vstack([corner_nodes(grid)[0][rng.choice(50, 4, replace=False)], rng.uniform(5, 25, (4, 2))])
        sh = S.Shadows(grid.occ, U, np.zeros((len(U), 2), np.int64))
        if sh.empty:
            continue
        owner = sh.cell_owner
        ends = sh.cell_lo + sh.cell_width  # each wedge's end, in (-pi, 3 pi)
        ends = np.where(ends >= S.TWO_PI, ends - S.TWO_PI, ends)
        open_ = ~sh.covers(owner, ends)
        o, e = owner[open_], ends[open_]
        gaps += len(e)
        for w in (1e-6, 1e-4, 1e-2):
            assert not np.any(sh.covers_spans(o, e - w, e + w))
        # and directions well inside a wedge are covered (the test sees something)
        mid = sh.cell_lo + 0.5 * sh.cell_width
        assert np.all(sh.covers(owner, np.where(mid >= S.TWO_PI, mid - S.TWO_PI, mid)))
    assert gaps > 20


def test_resolution_and_origin_do_not_change_the_answer():
    grid = generate_map("random", 48, seed=3)
    s, g = map_query(grid, seed=3)
    other = op.GridMap(grid.occ, resolution=0.37, origin=(-3.0, 2.0))
    s2, g2 = other.to_world(grid.to_grid(s)), other.to_world(grid.to_grid(g))
    path, length = visibility_path(other, s2, g2)
    ref_path, ref_length = visibility_path(grid, s, g, search="scan")
    assert length / 0.37 == pytest.approx(ref_length, rel=1e-12)
    assert np.allclose(other.to_grid(path), grid.to_grid(ref_path), atol=1e-9)
    assert op.validate_path(other, path)
