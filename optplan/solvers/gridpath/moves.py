"""The 8-connected move table of a grid, with the no-corner-cutting rule.

``neighbours[c, k]`` is the flat index of the k-th neighbour of flat cell ``c``
(``iy * width + ix``) or ``-1`` when that move is not allowed: the target is
blocked or outside, or (without corner cutting) the move is diagonal and one
of the two side cells is blocked. ``step_length[k]`` is 1 or sqrt(2) cells.

The table is built once per map (and per corner-cutting rule and clearance) and
cached on the map. Graph search reads two forms of it that are derived once per
table, never per query: :attr:`MoveTable.masks` (one byte of allowed directions
per cell, with :attr:`MoveTable.moves_by_mask` listing the ``(flat offset,
step)`` pairs of each of the 256 bytes), for the scalar A* loop, and
:attr:`MoveTable.csr`, the sparse adjacency matrix for scipy's compiled searches.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from ...world.derived import DerivedStore

_DERIVED = DerivedStore("solvers.gridpath.moves")  # this module's data derived from worlds

OFFSETS = np.array([(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1)], dtype=np.int64)
STEP = np.hypot(OFFSETS[:, 0], OFFSETS[:, 1])


@dataclass(frozen=True)
class MoveTable:
    width: int
    height: int
    neighbours: np.ndarray   # (n_cells, 8) int64, -1 = no move
    step_length: np.ndarray  # (8,) cells

    def xy(self, flat) -> np.ndarray:
        """Flat indices -> integer cells ``(ix, iy)``."""
        flat = np.asarray(flat)
        return np.stack([flat % self.width, flat // self.width], axis=-1)

    @cached_property
    def masks(self) -> bytes:
        """Byte ``c``: bit ``k`` set when move ``k`` out of flat cell ``c`` is allowed
        (one byte per cell; indexing ``bytes`` gives a Python int without conversion)."""
        bits = (self.neighbours >= 0).astype(np.uint8) << np.arange(8, dtype=np.uint8)
        return np.bitwise_or.reduce(bits, axis=1).astype(np.uint8).tobytes()

    @cached_property
    def moves_by_mask(self) -> tuple[tuple[tuple[int, float], ...], ...]:
        """For each of the 256 masks, the allowed moves as ``(flat offset, step in cells)``.

        Allowed moves never leave the map, so ``c + offset`` is the target cell."""
        moves = [(int(dx + dy * self.width), float(w)) for (dx, dy), w in zip(OFFSETS.tolist(), self.step_length)]
        return tuple(tuple(moves[k] for k in range(8) if m >> k & 1) for m in range(256))

    @cached_property
    def octile_window(self) -> np.ndarray:
        """``(2 height - 1, 2 width - 1)`` octile distances (li2023 eq 12) from the middle
        entry, in cells: the heuristic towards goal cell ``(ax, ay)`` of every cell is the
        window ``[height - 1 - ay :][: height, width - 1 - ax :][:, : width]``, one slice
        per query. Written ``(dx + dy) + (sqrt 2 - 2) min(dx, dy)``, as the A* loop wrote it."""
        dx = np.abs(np.arange(-(self.width - 1), self.width))[None, :]
        dy = np.abs(np.arange(-(self.height - 1), self.height))[:, None]
        return (dx + dy) + (np.sqrt(2.0) - 2.0) * np.minimum(dx, dy)

    @cached_property
    def csr(self):
        """``(n_cells, n_cells)`` scipy CSR matrix of the allowed moves, weights in cells."""
        from scipy.sparse import csr_matrix

        src, k = np.nonzero(self.neighbours >= 0)
        n = self.width * self.height
        return csr_matrix((self.step_length[k], (src, self.neighbours[src, k])), shape=(n, n))


def move_table(grid, corner_cutting: bool = False, clearance: float = 0.0) -> MoveTable:
    """Build (and cache on the grid) the move table.

    With ``clearance > 0`` a move is kept only when both cell centres are at least
    ``clearance`` metres from obstacles and the map border and the straight move
    keeps that distance too (the exact segment rule), so graph search with a
    clearance does not have to block whole cells.
    """
    key = ("moves", bool(corner_cutting), float(clearance))
    cache = _DERIVED.of(grid)
    if key in cache:
        return cache[key]
    H, W = grid.height, grid.width
    pad = grid.padded  # blocked frame: padded[iy + 1, ix + 1]
    iy, ix = np.mgrid[0:H, 0:W]
    ix, iy = ix.ravel(), iy.ravel()
    nb = np.full((H * W, 8), -1, dtype=np.int64)
    free_here = ~grid.occ.ravel()
    for k, (dx, dy) in enumerate(OFFSETS):
        tx, ty = ix + dx, iy + dy
        ok = free_here & ~pad[ty + 1, tx + 1]
        if dx and dy and not corner_cutting:
            ok &= ~pad[iy + 1, tx + 1] & ~pad[ty + 1, ix + 1]
        nb[ok, k] = (ty * W + tx)[ok]
    if clearance > 0:
        src, k = np.nonzero(nb >= 0)
        a = grid.cell_center(np.stack([src % W, src // W], axis=1))
        dst = nb[src, k]
        b = grid.cell_center(np.stack([dst % W, dst // W], axis=1))
        ok = grid.is_free(a, clearance) & grid.is_free(b, clearance) & grid.segments_free(a, b, clearance)
        nb[src[~ok], k[~ok]] = -1
    table = MoveTable(W, H, nb, STEP.copy())
    cache[key] = table
    return table
