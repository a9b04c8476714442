"""Seeded grid maps of the kinds users bring: rooms, mazes, random clutter, warehouses, cities.

``generate_map(kind, size, seed)`` returns a :class:`GridMap` and ``map_query(grid, seed)``
a start and goal (cell centres in the largest free region, far apart). Same arguments,
same map. These maps are drawn here, not taken from public benchmark suites, so results
measured on seeds that were not used while developing are held-out figures.

Kinds:

* ``rooms``: a grid of rooms separated by walls with one or two door gaps per wall.
* ``maze``: a perfect maze (randomised depth-first carving) with corridors ``corridor``
  cells wide, plus a few extra openings so that several corridors lead to the goal.
* ``random``: every cell blocked with probability ``density`` (0.15-0.30 typical).
* ``warehouse``: rows of shelf blocks with aisles and cross-aisles, a few shelves missing.
* ``city``: rectangular buildings of random size on a street grid, some blocks merged
  (like the Moving AI city crops, drawn anew).
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..rng import as_generator
from ..world.grid import GridMap

MAP_KINDS = ("rooms", "maze", "random", "warehouse", "city")


def _rooms(n: int, rng: np.random.Generator) -> np.ndarray:
    occ = np.zeros((n, n), bool)
    room = int(rng.integers(5, 9))
    walls = list(range(room, n - 2, room))
    for w in walls:
        occ[w, :] = True
        occ[:, w] = True
    bounds = [0] + walls + [n]
    # doors: every wall piece between two crossings gets one or two gaps of 1-2 cells
    for w in walls:
        for a, b in zip(bounds[:-1], bounds[1:]):
            lo, hi = a + 1, b - 1
            if hi - lo < 2:
                continue
            for _ in range(int(rng.integers(1, 3))):
                c = int(rng.integers(lo, hi - 1))
                width = int(rng.integers(1, 3))
                if rng.random() < 0.85:
                    occ[w, c:c + width] = False
                if rng.random() < 0.85:
                    occ[c:c + width, w] = False
    return occ


def _maze(n: int, rng: np.random.Generator, corridor: int = 1) -> np.ndarray:
    step = corridor + 1
    m = (n - 1) // step
    occ = np.ones((n, n), bool)
    seen = np.zeros((m, m), bool)
    stack = [(0, 0)]
    seen[0, 0] = True

    def carve(cx, cy):
        occ[1 + cy * step:1 + cy * step + corridor, 1 + cx * step:1 + cx * step + corridor] = False

    carve(0, 0)
    while stack:  # map generation, not a hot path
        cx, cy = stack[-1]
        nbrs = [(cx + dx, cy + dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
                if 0 <= cx + dx < m and 0 <= cy + dy < m and not seen[cy + dy, cx + dx]]
        if not nbrs:
            stack.pop()
            continue
        nx, ny = nbrs[int(rng.integers(len(nbrs)))]
        seen[ny, nx] = True
        carve(nx, ny)
        x0, x1 = sorted((1 + cx * step, 1 + nx * step))
        y0, y1 = sorted((1 + cy * step, 1 + ny * step))
        occ[y0:y1 + corridor, x0:x1 + corridor] = False
        stack.append((nx, ny))
    # extra openings: knock out interior wall cells so the maze has loops (corridor choices)
    walls = np.argwhere(occ[1:-1, 1:-1]) + 1
    k = max(1, len(walls) // 25)
    for iy, ix in walls[rng.choice(len(walls), size=min(k, len(walls)), replace=False)]:
        occ[iy, ix] = False
    occ[0, :] = occ[-1, :] = occ[:, 0] = occ[:, -1] = False
    return occ


def _random(n: int, rng: np.random.Generator, density: float) -> np.ndarray:
    return rng.random((n, n)) < density


def _warehouse(n: int, rng: np.random.Generator) -> np.ndarray:
    occ = np.zeros((n, n), bool)
    shelf_len = int(rng.integers(4, 9))
    aisle = int(rng.integers(1, 3))
    cross = shelf_len + int(rng.integers(2, 4))
    for y in range(2, n - 2, 2 + aisle):        # a double shelf row, then an aisle
        for x0 in range(2, n - 2, cross):
            if rng.random() < 0.1:
                continue                         # a missing shelf block
            occ[y:y + 2, x0:min(x0 + shelf_len, n - 2)] = True
    return occ


def _city(n: int, rng: np.random.Generator) -> np.ndarray:
    occ = np.zeros((n, n), bool)
    y = int(rng.integers(1, 4))
    while y < n - 3:
        h = int(rng.integers(max(3, n // 40), max(5, n // 10)))
        x = int(rng.integers(1, 4))
        while x < n - 3:
            w = int(rng.integers(max(3, n // 40), max(5, n // 10)))
            if rng.random() < 0.85:
                # a building slightly smaller than its block, sometimes L-shaped
                occ[y:min(y + h, n - 1), x:min(x + w, n - 1)] = True
                if rng.random() < 0.3:
                    occ[y:y + h // 2, x:x + w // 2] = False
            x += w + int(rng.integers(2, max(3, n // 32) + 2))
        y += h + int(rng.integers(2, max(3, n // 32) + 2))
    return occ


def generate_map(kind: str, size: int = 32, seed=0, *, density: float = 0.2, corridor: int = 1) -> GridMap:
    """A seeded ``size x size`` grid map of ``kind`` (one of :data:`MAP_KINDS`).

    Args:
        kind: ``rooms``, ``maze``, ``random``, ``warehouse`` or ``city``.
        size: cells per side (8-1024).
        seed: int or Generator; the same seed gives the same map.
        density: blocked share for ``random``.
        corridor: corridor width in cells for ``maze``.

    Raises:
        ParameterError: unknown kind, size out of range, density outside ``[0, 0.6]``.
    """
    if kind not in MAP_KINDS:
        raise ParameterError(f"map kind must be one of {', '.join(MAP_KINDS)}, got {kind!r}")
    if not isinstance(size, (int, np.integer)) or not 8 <= size <= 1024:
        raise ParameterError(f"size must be an integer number of cells in [8, 1024], got {size!r}")
    if not 0.0 <= float(density) <= 0.6:
        raise ParameterError(f"density must be a blocked share in [0, 0.6], got {density!r}")
    rng = as_generator(seed)
    n = int(size)
    if kind == "rooms":
        occ = _rooms(n, rng)
    elif kind == "maze":
        occ = _maze(n, rng, int(corridor))
    elif kind == "random":
        occ = _random(n, rng, float(density))
    elif kind == "warehouse":
        occ = _warehouse(n, rng)
    else:
        occ = _city(n, rng)
    label = f"{kind}{n}-s{seed}" if isinstance(seed, (int, np.integer)) else f"{kind}{n}"
    return GridMap(occ, name=label)


def map_query(grid: GridMap, seed=0, min_separation: float = 0.6) -> tuple[np.ndarray, np.ndarray]:
    """A start and goal (cell centres, metres) in the largest 8-connected free region, at least
    ``min_separation`` times the map diagonal apart when possible (else the farthest pair drawn)."""
    from scipy import ndimage

    rng = as_generator(seed)
    lab, n = ndimage.label(~grid.occ, np.ones((3, 3), bool))
    if n == 0:
        raise ParameterError(f"map {grid.name!r} has no free cell")
    sizes = np.bincount(lab.ravel())[1:]
    iy, ix = np.nonzero(lab == 1 + int(sizes.argmax()))
    cells = np.stack([ix, iy], axis=1)
    diag = np.hypot(*grid.occ.shape)
    best = None
    for _ in range(64):
        a, b = cells[rng.integers(len(cells), size=2)]
        d = np.hypot(*(a - b))
        if best is None or d > best[0]:
            best = (d, a, b)
        if d >= min_separation * diag:
            break
    _, a, b = best
    return grid.to_world(a + 0.5), grid.to_world(b + 0.5)
