"""Benchmark functions: known optima, shifts, fixed-dimension optima."""
from __future__ import annotations

import numpy as np
import pytest

from optplan.formulations.functions import FIXED_DIM, NAMES, get_function

KNOWN_POINTS = {
    "F15": np.array([np.pi, 2.275]),
    "F16": np.array([0.0, -1.0]),
    "F17": np.array([0.20169, 0.150011, 0.476874, 0.275332, 0.311652, 0.6573]),
    "F18": np.array([4.0, 4.0, 4.0, 4.0]),
    "F14": np.array([0.1928, 0.1908, 0.1231, 0.1358]),
}


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("shifted", [False, True])
def test_optimum_value_at_optimum_point(name, shifted):
    F = get_function(name, shifted=shifted)
    x = F.x_opt if F.x_opt is not None else KNOWN_POINTS[name]
    val = F(x[None])[0]
    tol = 1.0 if name == "F7" else 1e-3 if name in FIXED_DIM else 1e-9
    assert val == pytest.approx(F.f_opt, abs=tol)
    # nearby random points are not better (up to F7's noise)
    rng = np.random.default_rng(0)
    pts = np.clip(x + rng.normal(0, 0.05 * (F.upper - F.lower), (200, F.dim)), F.lower, F.upper)
    assert F(pts).min() >= F.f_opt - tol


def test_shift_moves_the_optimum_off_the_origin_inside_the_box():
    for name in NAMES:
        if name in FIXED_DIM:
            continue
        F0, F1 = get_function(name), get_function(name, shifted=True)
        assert not np.allclose(F1.x_opt, F0.x_opt)
        assert np.all((F1.x_opt > F1.lower) & (F1.x_opt < F1.upper))
        # origin is now clearly worse than the optimum (except for F8 whose optimum is not at 0)
        assert F1(np.zeros((1, F1.dim)))[0] > F1.f_opt


def test_shift_is_fixed_and_dimension_is_honoured():
    a, b = get_function("F9", shifted=True, dim=10), get_function("F9", shifted=True, dim=10)
    np.testing.assert_array_equal(a.shift, b.shift)
    assert a.dim == 10 and a.bounds.shape == (10, 2)
    assert get_function("F15", dim=10).dim == 2


def test_f7_noise_is_reproducible():
    a, b = get_function("F7", seed=3), get_function("F7", seed=3)
    X = np.zeros((5, 30))
    np.testing.assert_array_equal(a(X), b(X))
