"""Random steps and maps shared by several algorithms."""
from __future__ import annotations

from math import gamma, pi, sin

import numpy as np


def mantegna_sigma(beta: float = 1.5) -> float:
    """Scale of the numerator normal in Mantegna's Levy-stable step generator."""
    num = gamma(1 + beta) * sin(pi * beta / 2)
    den = gamma((1 + beta) / 2) * beta * 2 ** ((beta - 1) / 2)
    return (num / den) ** (1 / beta)


def levy(rng: np.random.Generator, shape, beta: float = 1.5, scale: float = 0.01) -> np.ndarray:
    """Levy-flight steps by Mantegna's method: ``scale * u / |v|^(1/beta)``, ``u ~ N(0, sigma^2)``,
    ``v ~ N(0, 1)`` (hou2024 eq 15-16 with scale 0.01; chen2025 eq 25-26 with scale 0.005)."""
    u = rng.normal(0.0, mantegna_sigma(beta), shape)
    v = rng.normal(0.0, 1.0, shape)
    return scale * u / np.abs(v) ** (1 / beta)


def logistic_tent(rng: np.random.Generator, shape, r: float = 3.9, burn_in: int = 20) -> np.ndarray:
    """Logistic-tent compound chaotic sequence in [0, 1) (hou2024 eq 9).

    ``x' = (r x (1 - x) + (4 - r) x / 2) mod 1`` for ``x < 0.5`` and
    ``x' = (r x (1 - x) + (4 - r)(1 - x) / 2) mod 1`` otherwise. Every element of
    ``shape`` is an independent orbit started from a random seed value, iterated
    ``burn_in`` times so the start value is forgotten.
    """
    x = rng.random(shape)
    for _ in range(burn_in):
        logistic = r * x * (1 - x)
        tent = np.where(x < 0.5, (4 - r) * x / 2, (4 - r) * (1 - x) / 2)
        x = np.mod(logistic + tent, 1.0)
    return x


def opposition(X: np.ndarray, lo: np.ndarray, hi: np.ndarray, k: np.ndarray | float = 1.0) -> np.ndarray:
    """Opposite points ``k * (lo + hi) - X`` (opposition-based learning; ``k`` random for elite OBL)."""
    return k * (lo + hi) - X


def sample_mask(rng: np.random.Generator, n: int, d: int, frac: np.ndarray) -> np.ndarray:
    """Boolean ``(n, d)`` masks choosing ``ceil(frac_i * d)`` random dimensions per row (ARO's ``c``)."""
    keys = rng.random((n, d))
    counts = np.maximum(np.ceil(np.asarray(frac) * d), 1).astype(int)
    order = np.argsort(keys, axis=1)
    ranks = np.empty_like(order)
    np.put_along_axis(ranks, order, np.arange(d)[None, :].repeat(n, 0), axis=1)
    return ranks < counts[:, None]


def running_operator(rng: np.random.Generator, t: int, T: int, n: int, d: int) -> np.ndarray:
    """ARO's running operator ``R = S * c`` (Wang 2022; chen2025 eq 10-13):
    ``S = (e - e^(((t - 1) / T)^2)) sin(2 pi r)`` and ``c`` a 0/1 mask of ``ceil(r' d)`` random dimensions."""
    S = (np.e - np.exp(((t - 1) / T) ** 2)) * np.sin(2 * np.pi * rng.random((n, 1)))
    return S * sample_mask(rng, n, d, rng.random(n))
