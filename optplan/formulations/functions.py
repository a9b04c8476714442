"""Benchmark functions F1-F18 of chen2025 Tables 1-3, vectorised, with shifted versions.

Each function maps ``X`` of shape ``(n, d)`` to ``(n,)``. ``get_function(name,
shifted=True)`` moves the optimum of F1-F13 away from the origin (or from the
all-ones point of F5) by a fixed offset drawn from a seed of its own, inside 80 %
of the bounds: origin-centred functions flatter algorithms that are drawn to
zero (GWO's ``C * X_leader`` is one), so honest comparisons use the shifted ones.
F14-F18 have fixed dimensions and optima away from the origin; they are never
shifted. F7's noise is drawn from a generator owned by the function object
(seeded), so a run is reproducible.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..errors import UnknownAlgorithmError

SHIFT_SEED = 20250101  # the offsets' own stream: never the stream of an algorithm's seed


def _u(x, a, k, m):
    return np.where(x > a, k * (x - a) ** m, 0.0) + np.where(x < -a, k * (-x - a) ** m, 0.0)


def f1(X):
    """Sphere: sum of x_i^2; minimum 0 at the origin. ``X``: ``(n, d)``; returns ``(n,)``."""
    return np.einsum("ij,ij->i", X, X)


def f2(X):
    """Schwefel 2.22: sum |x_i| + prod |x_i|; minimum 0 at the origin. ``X``: ``(n, d)``; returns ``(n,)``."""
    A = np.abs(X)
    return A.sum(1) + A.prod(1)


def f3(X):
    """Schwefel 1.2: sum over i of (x_1 + ... + x_i)^2; minimum 0 at the origin. ``X``: ``(n, d)``; returns ``(n,)``."""
    return (np.cumsum(X, axis=1) ** 2).sum(1)


def f4(X):
    """Schwefel 2.21: max |x_i|; minimum 0 at the origin. ``X``: ``(n, d)``; returns ``(n,)``."""
    return np.abs(X).max(1)


def f5(X):
    """Rosenbrock: sum 100 (x_{i+1} - x_i^2)^2 + (x_i - 1)^2; minimum 0 at all ones. ``X``: ``(n, d)``; returns ``(n,)``."""
    return (100 * (X[:, 1:] - X[:, :-1] ** 2) ** 2 + (X[:, :-1] - 1) ** 2).sum(1)


def f6(X):
    """Step: sum floor(x_i + 0.5)^2; minimum 0 on the cube around the origin. ``X``: ``(n, d)``; returns ``(n,)``."""
    return (np.floor(X + 0.5) ** 2).sum(1)


def make_f7(seed: int = 7):
    """Quartic with noise: sum i x_i^4 + U[0, 1); the noise comes from a generator seeded
    with ``seed`` and owned by the returned function, so runs repeat exactly."""
    rng = np.random.default_rng(seed)

    def f7(X):
        i = np.arange(1, X.shape[1] + 1)
        return (i * X ** 4).sum(1) + rng.random(len(X))

    return f7


def f8(X):
    """Schwefel 2.26: -sum x_i sin(sqrt|x_i|); minimum about -418.98 d at x_i = 420.97. ``X``: ``(n, d)``; returns ``(n,)``."""
    return -(X * np.sin(np.sqrt(np.abs(X)))).sum(1)


def f9(X):
    """Rastrigin: sum x_i^2 - 10 cos(2 pi x_i) + 10; minimum 0 at the origin. ``X``: ``(n, d)``; returns ``(n,)``."""
    return (X ** 2 - 10 * np.cos(2 * np.pi * X) + 10).sum(1)


def f10(X):
    """Ackley; minimum 0 at the origin. ``X``: ``(n, d)``; returns ``(n,)``."""
    d = X.shape[1]
    return (-20 * np.exp(-0.2 * np.sqrt((X ** 2).sum(1) / d)) - np.exp(np.cos(2 * np.pi * X).sum(1) / d)
            + 20 + np.e)


def f11(X):
    """Griewank: sum x_i^2 / 4000 - prod cos(x_i / sqrt i) + 1; minimum 0 at the origin. ``X``: ``(n, d)``; returns ``(n,)``."""
    i = np.sqrt(np.arange(1, X.shape[1] + 1))
    return (X ** 2).sum(1) / 4000 - np.cos(X / i).prod(1) + 1


def f12(X):
    """Penalised 1 (Levy-type with the u penalty, a = 10); minimum 0 at x_i = -1. ``X``: ``(n, d)``; returns ``(n,)``."""
    d = X.shape[1]
    y = 1 + (X + 1) / 4
    body = (10 * np.sin(np.pi * y[:, 0]) ** 2
            + ((y[:, :-1] - 1) ** 2 * (1 + 10 * np.sin(np.pi * y[:, 1:]) ** 2)).sum(1)
            + (y[:, -1] - 1) ** 2)
    return np.pi / d * body + _u(X, 10, 100, 4).sum(1)


def f13(X):
    """Penalised 2 (u penalty, a = 5); minimum 0 at x_i = 1. ``X``: ``(n, d)``; returns ``(n,)``."""
    body = (np.sin(3 * np.pi * X[:, 0]) ** 2
            + ((X[:, :-1] - 1) ** 2 * (1 + np.sin(3 * np.pi * X[:, 1:]) ** 2)).sum(1)
            + (X[:, -1] - 1) ** 2 * (1 + np.sin(2 * np.pi * X[:, -1]) ** 2))
    return 0.1 * body + _u(X, 5, 100, 4).sum(1)


_KOW_A = np.array([0.1957, 0.1947, 0.1735, 0.16, 0.0844, 0.0627, 0.0456, 0.0342, 0.0323, 0.0235, 0.0246])
_KOW_B = 1 / np.array([0.25, 0.5, 1, 2, 4, 6, 8, 10, 12, 14, 16])


def f14(X):
    """Kowalik (4-d least squares fit); minimum about 3.075e-4. ``X``: ``(n, d)``; returns ``(n,)``."""
    x1, x2, x3, x4 = (X[:, k:k + 1] for k in range(4))
    b = _KOW_B[None, :]
    model = x1 * (b ** 2 + b * x2) / (b ** 2 + b * x3 + x4)
    return ((_KOW_A[None, :] - model) ** 2).sum(1)


def f15(X):
    """Branin (2-d); minimum about 0.398 at three points. ``X``: ``(n, d)``; returns ``(n,)``."""
    x1, x2 = X[:, 0], X[:, 1]
    return (x2 - 5.1 / (4 * np.pi ** 2) * x1 ** 2 + 5 / np.pi * x1 - 6) ** 2 + 10 * (1 - 1 / (8 * np.pi)) * np.cos(x1) + 10


def f16(X):
    """Goldstein-Price (2-d); minimum 3 at (0, -1). ``X``: ``(n, d)``; returns ``(n,)``."""
    x1, x2 = X[:, 0], X[:, 1]
    a = 1 + (x1 + x2 + 1) ** 2 * (19 - 14 * x1 + 3 * x1 ** 2 - 14 * x2 + 6 * x1 * x2 + 3 * x2 ** 2)
    b = 30 + (2 * x1 - 3 * x2) ** 2 * (18 - 32 * x1 + 12 * x1 ** 2 + 48 * x2 - 36 * x1 * x2 + 27 * x2 ** 2)
    return a * b


_H6_A = np.array([[10, 3, 17, 3.5, 1.7, 8], [0.05, 10, 17, 0.1, 8, 14], [3, 3.5, 1.7, 10, 17, 8], [17, 8, 0.05, 10, 0.1, 14]])
_H6_C = np.array([1, 1.2, 3, 3.2])
_H6_P = 1e-4 * np.array([[1312, 1696, 5569, 124, 8283, 5886], [2329, 4135, 8307, 3736, 1004, 9991],
                         [2348, 1451, 3522, 2883, 3047, 6650], [4047, 8828, 8732, 5743, 1091, 381]])


def f17(X):
    """Hartmann 6-d; minimum about -3.322. ``X``: ``(n, d)``; returns ``(n,)``."""
    inner = (_H6_A[None] * (X[:, None, :] - _H6_P[None]) ** 2).sum(2)
    return -(_H6_C[None] * np.exp(-inner)).sum(1)


_SH_A = np.array([[4, 4, 4, 4], [1, 1, 1, 1], [8, 8, 8, 8], [6, 6, 6, 6], [3, 7, 3, 7], [2, 9, 2, 9], [5, 5, 3, 3],
                  [8, 1, 8, 1], [6, 2, 6, 2], [7, 3.6, 7, 3.6]], dtype=float)
_SH_C = np.array([0.1, 0.2, 0.2, 0.4, 0.4, 0.6, 0.3, 0.7, 0.5, 0.5])


def f18(X):
    """Shekel with ten maxima (4-d); minimum about -10.536. ``X``: ``(n, d)``; returns ``(n,)``."""
    diff = X[:, None, :] - _SH_A[None]
    return -(1 / ((diff ** 2).sum(2) + _SH_C[None])).sum(1)


@dataclass
class BenchmarkFunction:
    """A benchmark function with its box, dimension and known optimum."""

    name: str
    f: Callable
    lower: float
    upper: float
    dim: int
    f_opt: float
    x_opt: np.ndarray | None = None
    shifted: bool = False
    shift: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def __call__(self, X: np.ndarray) -> np.ndarray:
        return self.f(np.asarray(X, dtype=float))

    @property
    def bounds(self) -> np.ndarray:
        return np.tile([self.lower, self.upper], (self.dim, 1)).astype(float)


# name: (function or factory, lower, upper, default dim, f_opt, x_opt builder (dim -> point) or None)
_TABLE = {
    "F1": (f1, -100, 100, 30, 0.0, lambda d: np.zeros(d)),
    "F2": (f2, -10, 10, 30, 0.0, lambda d: np.zeros(d)),
    "F3": (f3, -100, 100, 30, 0.0, lambda d: np.zeros(d)),
    "F4": (f4, -100, 100, 30, 0.0, lambda d: np.zeros(d)),
    "F5": (f5, -30, 30, 30, 0.0, lambda d: np.ones(d)),
    "F6": (f6, -100, 100, 30, 0.0, lambda d: np.zeros(d)),
    "F7": (None, -1.28, 1.28, 30, 0.0, lambda d: np.zeros(d)),
    "F8": (f8, -500, 500, 30, None, lambda d: np.full(d, 420.968746)),
    "F9": (f9, -5.12, 5.12, 30, 0.0, lambda d: np.zeros(d)),
    "F10": (f10, -32, 32, 30, 0.0, lambda d: np.zeros(d)),
    "F11": (f11, -600, 600, 30, 0.0, lambda d: np.zeros(d)),
    "F12": (f12, -50, 50, 30, 0.0, lambda d: -np.ones(d)),
    "F13": (f13, -50, 50, 30, 0.0, lambda d: np.ones(d)),
    "F14": (f14, -5, 5, 4, 0.0003074859878, None),
    "F15": (f15, -5, 5, 2, 0.39788735772973816, None),
    "F16": (f16, -2, 2, 2, 3.0, None),
    "F17": (f17, 0, 1, 6, -3.3223680114155, None),
    "F18": (f18, 0, 10, 4, -10.536409816692, None),
}
FIXED_DIM = ("F14", "F15", "F16", "F17", "F18")
NAMES = tuple(_TABLE)


def get_function(name: str, shifted: bool = False, dim: int | None = None, seed: int = 7) -> BenchmarkFunction:
    """F1-F18 by name; ``shifted`` moves F1-F13's optimum by a fixed offset."""
    key = name.upper()
    if key not in _TABLE:
        raise UnknownAlgorithmError(f"unknown benchmark function {name!r}; known: {', '.join(NAMES)}")
    fn, lo, hi, d0, f_opt, xopt = _TABLE[key]
    d = d0 if key in FIXED_DIM or dim is None else int(dim)
    base = make_f7(seed) if key == "F7" else fn
    if f_opt is None:  # F8: -418.9829 per dimension
        f_opt = -418.9828872724338 * d
    x_opt = xopt(d) if xopt is not None else None
    if not shifted or key in FIXED_DIM:
        return BenchmarkFunction(key, base, lo, hi, d, f_opt, x_opt)
    # offsets from their own stream; the shifted optimum stays inside 80 % of the box
    rng = np.random.default_rng([SHIFT_SEED, int(key[1:]), d])
    span = 0.8 * (hi - lo) / 2
    target = rng.uniform(-span, span, d) + (lo + hi) / 2
    if key == "F8":  # keep F8's optimum inside the box: shift only a little
        target = np.clip(x_opt + rng.uniform(-0.1, 0.1, d) * (hi - lo) / 2, lo + 1, hi - 1)
    shift = target - x_opt

    def shifted_f(X, _f=base, _s=shift):
        return _f(X - _s)

    return BenchmarkFunction(key, shifted_f, lo, hi, d, f_opt, target, True, shift)
