"""A* and Dijkstra on the 8-connected grid of cell centres.

Moves go to the 8 neighbouring cells; a diagonal move is allowed only when both
side cells are free (no corner cutting), unless ``corner_cutting=True`` (the
convention of the public ACO demos, where only the target must be free).
Costs are 1 and sqrt(2) cells times the resolution. A* uses the octile distance
(li2023 eq 12), which is admissible and consistent on this graph, so both
searches return the same optimal length.
"""
from __future__ import annotations

import heapq
import math

import numpy as np

from ...errors import InfeasibleQueryError
from ..gridpath.moves import move_table

SQRT2 = math.sqrt(2.0)


def octile(dx: float, dy: float) -> float:
    """Octile distance (li2023 eq 12) between cells ``dx``, ``dy`` apart, in cells."""
    dx, dy = abs(dx), abs(dy)
    return max(dx, dy) + (SQRT2 - 1.0) * min(dx, dy)


def grid_search(grid, start_cell, goal_cell, *, heuristic: bool = True, corner_cutting: bool = False,
                clearance: float = 0.0):
    """Optimal 8-connected cell path from ``start_cell`` to ``goal_cell`` (integer ``(ix, iy)``).

    Returns ``(cells, length_in_cells, expanded)``; raises InfeasibleQueryError when
    the goal cannot be reached.
    """
    table = move_table(grid, corner_cutting, clearance)
    W = grid.width
    nb = table.neighbours.tolist()           # Python lists: the loop below is scalar by nature
    step = table.step_length.tolist()
    s = int(start_cell[1]) * W + int(start_cell[0])
    g = int(goal_cell[1]) * W + int(goal_cell[0])
    gx, gy = g % W, g // W
    n_cells = grid.width * grid.height
    dist = [math.inf] * n_cells
    parent = [-1] * n_cells
    closed = bytearray(n_cells)
    dist[s] = 0.0

    def h(c: int) -> float:
        if not heuristic:
            return 0.0
        dx, dy = abs(c % W - gx), abs(c // W - gy)
        return (dx + dy) + (SQRT2 - 2.0) * (dx if dx < dy else dy)

    heap = [(h(s), 0.0, s)]
    expanded = 0
    while heap:
        _, d, c = heapq.heappop(heap)
        if closed[c]:
            continue
        closed[c] = 1
        expanded += 1
        if c == g:
            break
        for k, t in enumerate(nb[c]):
            if t < 0 or closed[t]:
                continue
            nd = d + step[k]
            if nd < dist[t] - 1e-12:
                dist[t] = nd
                parent[t] = c
                heapq.heappush(heap, (nd + h(t), nd, t))
    if not closed[g]:
        raise InfeasibleQueryError(
            "the goal is unreachable from the start on the 8-connected grid"
            + ("" if corner_cutting else " (diagonal moves need both side cells free)")
            + "; check the map or choose another goal")
    cells = [g]
    while cells[-1] != s:
        cells.append(parent[cells[-1]])
    cells.reverse()
    flat = np.asarray(cells, dtype=np.int64)
    return np.stack([flat % W, flat // W], axis=1), float(dist[g]), expanded
