"""Seeding: every stochastic function accepts ``seed`` as an int, ``None`` or a Generator."""
from __future__ import annotations

import numpy as np

from .errors import ParameterError

SeedLike = "int | np.random.Generator | None"


def as_generator(seed: int | np.random.Generator | None) -> np.random.Generator:
    """Return a ``numpy.random.Generator`` for ``seed``.

    An existing Generator is passed through (so callers can share a stream);
    an int or ``None`` builds a fresh PCG64 generator.
    """
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is None:
        return np.random.default_rng()
    if isinstance(seed, (bool, float)) or not isinstance(seed, (int, np.integer)):
        raise ParameterError(f"seed must be an int, None or numpy.random.Generator, got {seed!r}")
    if seed < 0:
        raise ParameterError(f"seed must be non-negative, got {seed}")
    return np.random.default_rng(int(seed))
