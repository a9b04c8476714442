"""Seeded city-like grid maps: rectangular blocks of buildings between streets.

Moving AI's city maps (Sturtevant 2012) are not shipped with the project, so the
speed benchmarks and their tests use maps of the same kind made here: a street
grid with irregular spacing, every block filled with a few buildings separated
by alleys, some blocks left open as squares, and a little clutter. The streets
keep the map connected; start and goal go on free cells near opposite corners.
"""
from __future__ import annotations

import numpy as np

from ..world.grid import GridMap


def city_map(size: int = 256, seed: int = 0, street: tuple[int, int] = (2, 5), block: tuple[int, int] = (12, 28),
             open_share: float = 0.1, clutter: float = 0.002) -> GridMap:
    """A ``size`` x ``size`` city-like :class:`GridMap` (the same seed gives the same map).

    Args:
        size: cells per side.
        seed: random seed.
        street: smallest and largest street width (cells).
        block: smallest and largest block side (cells) between streets.
        open_share: share of blocks left free (squares, parks).
        clutter: share of single blocked cells scattered in the streets.
    """
    rng = np.random.default_rng(seed)
    occ = np.zeros((size, size), dtype=bool)

    def cuts() -> list[tuple[int, int]]:
        """``(lo, hi)`` spans of blocks along one axis, streets between them."""
        spans, pos = [], int(rng.integers(street[0], street[1] + 1))
        while pos < size - street[0]:
            side = int(rng.integers(block[0], block[1] + 1))
            hi = min(pos + side, size - street[0])
            if hi - pos >= 3:
                spans.append((pos, hi))
            pos = hi + int(rng.integers(street[0], street[1] + 1))
        return spans

    for x0, x1 in cuts():
        for y0, y1 in cuts():
            if rng.random() < open_share:
                continue
            # split the block into buildings by one-cell alleys, sometimes
            xs = [x0, x1]
            ys = [y0, y1]
            if x1 - x0 > 10 and rng.random() < 0.5:
                xs.insert(1, int(rng.integers(x0 + 4, x1 - 4)))
            if y1 - y0 > 10 and rng.random() < 0.5:
                ys.insert(1, int(rng.integers(y0 + 4, y1 - 4)))
            for a, b in zip(xs[:-1], xs[1:]):
                for c, d in zip(ys[:-1], ys[1:]):
                    occ[c:d - (d != y1), a:b - (b != x1)] = True
    occ |= rng.random((size, size)) < clutter
    occ[:2, :2] = False
    occ[-2:, -2:] = False
    return GridMap(occ)
