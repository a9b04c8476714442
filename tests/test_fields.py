"""The sampled distance field and its spline: the same numbers as the exact clearance and
as CasADi's own B-spline interpolant, at a set-up cost that does not explode with the map."""
import numpy as np
import pytest

import optplan as op
from optplan.world.fields import TILE, distance_spline, grid_distance_field
from optplan.world.papermaps import paper_map
from optplan.worldgen.city import city_map


def _maps():
    yield paper_map("chen2025_20")[0]
    yield city_map(40, seed=3)
    # off-unit resolution and origin: grid coordinates are not exact multiples of the spacing
    yield op.GridMap(np.random.default_rng(3).random((17, 23)) < 0.3, resolution=0.05, origin=(-1.3, 2.1))


@pytest.mark.parametrize("subdiv", [4, 8])
def test_field_is_the_exact_clearance_at_the_lattice(subdiv):
    for grid in _maps():
        f = grid_distance_field(grid, subdiv)
        X, Y = np.meshgrid(f.xs, f.ys)
        exact = grid.clearance(np.stack([X, Y], axis=-1).reshape(-1, 2)).reshape(X.shape)
        assert f.values.shape == (grid.height * subdiv + 1, grid.width * subdiv + 1)
        np.testing.assert_allclose(f.values, exact, rtol=0, atol=1e-12)
        assert (f.values < 0).any() and (f.values > 0).any()


def test_field_of_a_map_without_obstacles_is_the_border_distance():
    grid = op.GridMap(np.zeros((3, 5), dtype=bool))
    f = grid_distance_field(grid, 2)
    X, Y = np.meshgrid(f.xs, f.ys)
    np.testing.assert_allclose(f.values, np.minimum.reduce([X, Y, 5 - X, 3 - Y]))


def test_spline_is_casadis_bspline_interpolant():
    ca = pytest.importorskip("casadi")
    for grid in _maps():
        f = grid_distance_field(grid, 4)
        ref = ca.interpolant("sdf", "bspline", [f.xs, f.ys], f.values.ravel())
        lo, hi = np.array(grid.bounds[:2]), np.array(grid.bounds[2:])
        Q = np.vstack([np.random.default_rng(0).uniform(lo, hi, (400, 2)), [lo, hi, [lo[0], hi[1]]]])
        np.testing.assert_allclose(distance_spline(grid)(Q), np.asarray(ref(Q.T)).ravel(), rtol=0, atol=1e-11)


def test_symbolic_strip_reads_the_spline_near_the_path_and_the_radius_away_from_it():
    ca = pytest.importorskip("casadi")
    grid = city_map(40, seed=3)
    sp = distance_spline(grid)
    path = np.array([[1.0, 1.0], [20.0, 4.0], [38.0, 39.0]])
    radius = 3.0
    params, blocks = sp.strip(path, radius)
    assert 1 < blocks < np.prod(sp.tiles)          # a strip, not the whole map
    rng = np.random.default_rng(1)
    t = rng.random(300)
    k = rng.integers(0, 2, 300)
    near = path[k] + t[:, None] * (path[k + 1] - path[k]) + rng.uniform(-radius, radius, (300, 2)) / 1.5
    near = np.clip(near, 0, 40)
    far = np.array([[38.0, 2.0], [2.0, 38.0]])   # more than radius + a tile from the path
    Q = np.vstack([near, far])
    qx, qy, p = ca.MX.sym("x", len(Q)), ca.MX.sym("y", len(Q)), ca.MX.sym("p", len(params))
    F = ca.Function("F", [qx, qy, p], [sp.symbolic(qx, qy, p)])
    got = np.asarray(F(Q[:, 0], Q[:, 1], params)).ravel()
    np.testing.assert_allclose(got[:-2], sp(near), rtol=0, atol=1e-12)
    np.testing.assert_array_equal(got[-2:], radius)
    # padding to a larger capacity changes nothing
    padded, _ = sp.strip(path, radius, blocks + 5)
    assert len(padded) == len(params) + 5 * (TILE + 3) ** 2
    p2 = ca.MX.sym("p", len(padded))
    F2 = ca.Function("F2", [qx, qy, p2], [sp.symbolic(qx, qy, p2)])
    np.testing.assert_array_equal(np.asarray(F2(Q[:, 0], Q[:, 1], padded)).ravel(), got)
    with pytest.raises(ValueError):
        sp.strip(path, radius, blocks - 1)


def _large_pair(monkeypatch, seed=5):
    """A map above LOCAL_POINTS (chunked spline) and a copy fitted whole (the reference)."""
    import optplan.world.fields as F

    big = city_map(160, seed=seed)
    assert (big.height * 4 + 1) * (big.width * 4 + 1) > F.LOCAL_POINTS
    ref_map = op.GridMap(big.occ.copy(), big.resolution, big.origin)
    monkeypatch.setattr(F, "LOCAL_POINTS", 1 << 40)
    ref = distance_spline(ref_map)
    monkeypatch.undo()
    return big, distance_spline(big), ref, ref_map


def test_chunked_spline_is_the_whole_fit_near_obstacles_and_local_to_the_path(monkeypatch):
    from optplan.world.fields import REACH_CELLS

    big, lazy, ref, ref_map = _large_pair(monkeypatch)
    assert lazy.filler is not None and ref.filler is None and not lazy.filler.done.any()
    # a short path: the strip fills only the chunks around it
    path = np.array([[30.5, 30.5], [45.5, 52.5]])
    params, blocks = lazy.strip(path, 6.0)
    assert 0 < lazy.filler.done.mean() < 0.2
    ref_params, ref_blocks = ref.strip(path, 6.0)
    assert blocks == ref_blocks
    # near obstacles (where the NLP's constraints act) the values are the whole-map fit's
    Q = np.random.default_rng(0).uniform([20, 20], [56, 63], size=(20000, 2))
    d = grid_distance_field(ref_map)(Q)
    near = np.abs(d) < (REACH_CELLS / 2) * big.resolution   # the cap's kink is felt only near the reach
    assert near.sum() > 1000
    np.testing.assert_allclose(lazy(Q)[near], ref(Q)[near], rtol=0, atol=1e-5)


def test_chunked_spline_does_not_depend_on_the_order_of_reads(monkeypatch):
    big, lazy, _, _ = _large_pair(monkeypatch)
    other = distance_spline(op.GridMap(big.occ.copy(), big.resolution, big.origin))
    a, b = np.array([[10.5, 10.5], [60.5, 20.5]]), np.array([[50.5, 15.5], [55.5, 80.5]])
    lazy.strip(a, 6.0), lazy.strip(b, 6.0)
    other.strip(b, 6.0), other.strip(a, 6.0)
    np.testing.assert_array_equal(lazy.filler.done, other.filler.done)
    np.testing.assert_array_equal(lazy.coeffs, other.coeffs)


def test_refinement_on_a_large_map_is_valid_and_fills_only_its_strip():
    from optplan.solvers.refine import refine_path

    big = city_map(160, seed=5)
    free = np.argwhere(~big.occ)                      # (iy, ix) of free cells
    pick = lambda x, y: free[np.argmin(np.abs(free - [y, x]).sum(axis=1))][::-1]
    s, g = big.cell_center(pick(20, 20)), big.cell_center(pick(60, 45))
    seed = op.shortest_path(big, s, g, method="astar").path
    out = refine_path(big, seed, "casadi", tube_radius=0.0)
    assert out.success and op.validate_path(big, out.path)
    assert distance_spline(big).filler.done.mean() < 0.5
