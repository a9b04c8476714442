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
