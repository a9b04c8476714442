"""The 8-connected move table of a grid, with the no-corner-cutting rule.

``allowed[c]`` holds one bit per move out of flat cell ``c`` (``iy * width + ix``):
bit ``k`` (direction ``OFFSETS[k]``) is set when the move is allowed, i.e. the target
is free and inside and (without corner cutting) a diagonal move has both side
cells free. ``neighbours[c, k]`` (built on demand) is the target's flat index or
``-1``. ``step_length[k]`` is 1 or sqrt(2) cells.

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

from ...checks import memory_budget
from ...world.derived import DerivedStore

_DERIVED = DerivedStore("solvers.gridpath.moves")  # this module's data derived from worlds

OFFSETS = np.array([(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1)], dtype=np.int64)
STEP = np.hypot(OFFSETS[:, 0], OFFSETS[:, 1])


# maps with more cells than this get the A* heuristic computed per touched cell instead of
# a slice of a precomputed octile window (4 doubles per cell, 512 MB at 4000 x 4000)
WINDOW_CELLS = 1 << 21


@dataclass(frozen=True)
class MoveTable:
    width: int
    height: int
    allowed: np.ndarray      # (n_cells,) uint8: bit k set when move k out of the cell is allowed
    step_length: np.ndarray  # (8,) cells

    def xy(self, flat) -> np.ndarray:
        """Flat indices -> integer cells ``(ix, iy)``."""
        flat = np.asarray(flat)
        return np.stack([flat % self.width, flat // self.width], axis=-1)

    @cached_property
    def masks(self) -> bytes:
        """Byte ``c``: bit ``k`` set when move ``k`` out of flat cell ``c`` is allowed
        (one byte per cell; indexing ``bytes`` gives a Python int without conversion)."""
        return self.allowed.tobytes()

    @cached_property
    def neighbours(self) -> np.ndarray:
        """``(n_cells, 8)`` int64: the flat index of the k-th neighbour, ``-1`` when that move
        is not allowed (8 int64 per cell: for the population methods on small maps)."""
        n = self.width * self.height
        flat = np.arange(n, dtype=np.int64)
        nb = np.full((n, 8), -1, dtype=np.int64)
        for k, (dx, dy) in enumerate(OFFSETS.tolist()):
            ok = (self.allowed >> k) & 1 == 1
            nb[ok, k] = flat[ok] + dx + dy * self.width
        return nb

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
        per query. Written ``(dx + dy) + (sqrt 2 - 2) min(dx, dy)``, as the A* loop wrote it.
        Only maps of at most :data:`WINDOW_CELLS` cells use it."""
        dx = np.abs(np.arange(-(self.width - 1), self.width))[None, :]
        dy = np.abs(np.arange(-(self.height - 1), self.height))[:, None]
        return (dx + dy) + (np.sqrt(2.0) - 2.0) * np.minimum(dx, dy)

    @cached_property
    def csr(self):
        """``(n_cells, n_cells)`` scipy CSR matrix of the allowed moves, weights in cells."""
        from scipy.sparse import csr_matrix

        n = self.width * self.height
        # the (n, 8) neighbour table and the matrix's indices and weights: ~100 bytes a cell
        memory_budget(f"the sparse move matrix of a {self.width} x {self.height} map (Dijkstra, ACO, the cell GA)",
                      100.0 * n, "use method='astar', which keeps one byte a cell")
        nb = self.neighbours
        src, k = np.nonzero(nb >= 0)
        return csr_matrix((self.step_length[k], (src, nb[src, k])), shape=(n, n))


def move_table(grid, corner_cutting: bool = False, clearance: float = 0.0) -> MoveTable:
    """Build (and cache on the grid) the move table.

    With ``clearance > 0`` a move is kept only when both cell centres are at least
    ``clearance`` metres from obstacles and the map border and the straight move
    keeps that distance too (the exact segment rule), so graph search with a
    clearance does not have to block whole cells. One byte per cell: a 4000 x 4000
    map's table is 16 MB.
    """
    key = ("moves", bool(corner_cutting), float(clearance))
    cache = _DERIVED.of(grid)
    if key in cache:
        return cache[key]
    H, W = grid.height, grid.width
    free = ~grid.padded  # free[iy + 1, ix + 1]; the frame is blocked

    def free_at(dx: int, dy: int) -> np.ndarray:
        """Whether the cell ``(ix + dx, iy + dy)`` is free, for every cell ``(ix, iy)``."""
        return free[1 + dy:H + 1 + dy, 1 + dx:W + 1 + dx]

    allowed = np.zeros((H, W), dtype=np.uint8)
    here = free_at(0, 0)
    for k, (dx, dy) in enumerate(OFFSETS.tolist()):
        ok = here & free_at(dx, dy)
        if dx and dy and not corner_cutting:
            ok &= free_at(dx, 0) & free_at(0, dy)
        allowed |= ok.astype(np.uint8) << k
    allowed = allowed.reshape(-1)
    if clearance > 0:
        for k, (dx, dy) in enumerate(OFFSETS.tolist()):
            src = np.nonzero((allowed >> k) & 1)[0]
            a = grid.cell_center(np.stack([src % W, src // W], axis=1))
            b = grid.cell_center(np.stack([src % W + dx, src // W + dy], axis=1))
            ok = grid.is_free(a, clearance) & grid.is_free(b, clearance) & grid.segments_free(a, b, clearance)
            allowed[src[~ok]] &= np.uint8(0xFF ^ (1 << k))
    table = MoveTable(W, H, allowed, STEP.copy())
    cache[key] = table
    return table
