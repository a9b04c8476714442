"""A* and Dijkstra on the 8-connected grid of cell centres, from exact start and goal points.

Moves go to the 8 neighbouring cells; a diagonal move is allowed only when both
side cells are free (no corner cutting), unless ``corner_cutting=True`` (the
convention of the public ACO demos, where only the target must be free).
Costs are 1 and sqrt(2) cells times the resolution. A* uses the octile distance
(li2023 eq 12), which is admissible and consistent on this graph, so both
searches return the same optimal length.

Start and goal are points, not cells (:func:`cell_path`): each is joined to the
centres of the free cells whose closure holds it (one cell for a point inside a
cell, two on a cell edge, up to four on a corner) by a straight segment that the
exact rule (``segments_free``, with the clearance) accepts. All those centres
are equally far from the point (a shared edge is the perpendicular bisector of
the two centres), so the search is a multi-source, multi-target search with one
offset at each end. Two points in the closure of one free cell are also joined
directly when that segment is free; it is then the shortest path.

The neighbour structure comes from the map's cached move table
(:func:`optplan.solvers.gridpath.moves.move_table`): one byte of allowed
directions per cell for the scalar A* loop, a CSR matrix for scipy's compiled
Dijkstra. Nothing is converted per query.
"""
from __future__ import annotations

import heapq
import math
from dataclasses import dataclass

import numpy as np

from ...errors import InfeasibleQueryError
from ..gridpath.moves import move_table

SQRT2 = math.sqrt(2.0)


def octile(dx: float, dy: float) -> float:
    """Octile distance (li2023 eq 12) between cells ``dx``, ``dy`` apart, in cells."""
    dx, dy = abs(dx), abs(dy)
    return max(dx, dy) + (SQRT2 - 1.0) * min(dx, dy)


def _unreachable(corner_cutting: bool) -> InfeasibleQueryError:
    return InfeasibleQueryError(
        "the goal is unreachable from the start on the 8-connected grid"
        + ("" if corner_cutting else " (diagonal moves need both side cells free)")
        + "; check the map or choose another goal")


def astar_cells(table, sources, targets):
    """A*: shortest move sequence from any of ``sources`` to any of ``targets`` (flat cell indices).

    Every source starts at distance 0; the first target expanded is the nearest one.
    The heuristic is the octile distance to the first target less the largest octile
    distance between targets (clipped at 0): consistent, and 0 at every target. Heap
    entries are ``(f, g, cell)`` (ties: the shallower, then the lower index, first) and
    a move must improve a distance by more than 1e-12: with one source and one target
    this is the cell sequence the search has always returned.

    Returns ``(flat_cells, length_in_cells, expanded)``, or ``None`` when no target is
    reached.
    """
    W = table.width
    masks, moves = table.masks, table.moves_by_mask
    ay, ax = divmod(int(targets[0]), W)
    slack = max(octile(t % W - ax, t // W - ay) for t in targets)
    c2 = SQRT2 - 2.0
    n = W * table.height
    # dist[c] is -1 once c is expanded (closed): no move improves it, no heap entry matches it
    dist = [math.inf] * n
    parent = [-1] * n
    goal = set(int(t) for t in targets)
    heap = []
    for s in sources:
        s = int(s)
        dist[s] = 0.0
        y, x = divmod(s, W)
        heap.append((max(octile(x - ax, y - ay) - slack, 0.0), 0.0, s))
    heapq.heapify(heap)
    pop, push = heapq.heappop, heapq.heappush
    expanded, reached, length = 0, -1, math.inf
    while heap:
        _, d, c = pop(heap)
        if d != dist[c]:
            continue  # closed, or a stale entry
        dist[c] = -1.0
        expanded += 1
        if c in goal:
            reached, length = c, d
            break
        for off, w in moves[masks[c]]:
            t = c + off
            nd = d + w
            if nd < dist[t] - 1e-12:
                dist[t] = nd
                parent[t] = c
                y, x = divmod(t, W)
                dx = x - ax if x >= ax else ax - x
                dy = y - ay if y >= ay else ay - y
                h = dx + dy + c2 * (dx if dx < dy else dy) - slack
                push(heap, (nd + h if h > 0.0 else nd, nd, t))
    if reached < 0:
        return None
    cells = [reached]
    while (c := parent[cells[-1]]) >= 0:
        cells.append(c)
    cells.reverse()
    return np.asarray(cells, dtype=np.int64), length, expanded


def dijkstra_cells(table, sources, targets):
    """As :func:`astar_cells`, with scipy's compiled Dijkstra (a whole shortest-path tree
    from the sources, ``min_only``). ``expanded`` is the number of cells reached."""
    from scipy.sparse.csgraph import dijkstra

    dist, pred, _ = dijkstra(table.csr, directed=True, indices=np.asarray(sources, dtype=np.int64),
                             return_predecessors=True, min_only=True)
    targets = np.asarray(targets, dtype=np.int64)
    best = targets[np.argmin(dist[targets])]
    if not np.isfinite(dist[best]):
        return None
    cells = [int(best)]
    while pred[cells[-1]] >= 0:
        cells.append(int(pred[cells[-1]]))
    cells.reverse()
    return np.asarray(cells, dtype=np.int64), float(dist[best]), int(np.isfinite(dist).sum())


def grid_search(grid, start_cell, goal_cell, *, heuristic: bool = True, corner_cutting: bool = False,
                clearance: float = 0.0):
    """Optimal 8-connected cell path from ``start_cell`` to ``goal_cell`` (integer ``(ix, iy)``).

    Returns ``(cells, length_in_cells, expanded)``; raises InfeasibleQueryError when
    the goal cannot be reached.
    """
    table = move_table(grid, corner_cutting, clearance)
    W = grid.width
    s = int(start_cell[1]) * W + int(start_cell[0])
    g = int(goal_cell[1]) * W + int(goal_cell[0])
    out = astar_cells(table, [s], [g]) if heuristic else dijkstra_cells(table, [s], [g])
    if out is None:
        raise _unreachable(corner_cutting)
    flat, length, expanded = out
    return table.xy(flat), float(length), expanded


def _closure_cells(grid, p: np.ndarray) -> np.ndarray:
    """Integer cells ``(ix, iy)`` inside the map whose closed square holds ``p`` (1, 2 or 4)."""
    q = grid.to_grid(p)
    xs = {math.floor(q[0])} | ({int(q[0]) - 1} if q[0] == math.floor(q[0]) else set())
    ys = {math.floor(q[1])} | ({int(q[1]) - 1} if q[1] == math.floor(q[1]) else set())
    cells = np.array([(x, y) for y in sorted(ys) for x in sorted(xs)], dtype=np.int64)
    return cells[grid.in_map(cells)]


def _end_cells(grid, p: np.ndarray, clearance: float):
    """Flat indices of the cells the point ``p`` is joined to, and the join length (cells).

    A cell qualifies when it is free, its centre keeps the clearance and the segment
    from ``p`` to its centre is free under the exact rule. Without clearance that
    segment lies in the closed free cell and ends inside it, so the rule holds and is
    not evaluated."""
    cells = _closure_cells(grid, p)
    cells = cells[~grid.occ[cells[:, 1], cells[:, 0]]]
    if len(cells) and clearance > 0:
        centres = grid.cell_center(cells)
        ok = grid.segments_free(np.broadcast_to(p, centres.shape), centres, clearance)
        cells = cells[ok & grid.is_free(centres, clearance)]
    join = float(np.hypot(*(grid.to_grid(p) - (cells[0] + 0.5)))) if len(cells) else 0.0
    return _flat(grid, cells), join


@dataclass
class CellPath:
    """A path through cell centres between two exact points (:func:`cell_path`).

    Attributes:
        path: ``(N, 2)`` metres: ``start``, the cell centres, ``goal`` (no repeated point).
        length: metres (the joins plus the moves).
        expanded: cells expanded (A*) or reached (Dijkstra); 0 for a direct segment.
        direct: start and goal share a free cell and the straight segment is free.
    """

    path: np.ndarray
    length: float
    expanded: int
    direct: bool = False


def cell_path(grid, start, goal, *, method: str = "astar", corner_cutting: bool = False,
              clearance: float = 0.0) -> CellPath:
    """Shortest path from the point ``start`` to the point ``goal`` (metres) over the cell centres.

    ``method``: ``"astar"`` (the scalar loop with the octile heuristic) or ``"dijkstra"``
    (scipy's compiled Dijkstra). Both give the optimal length of the same graph.

    Raises:
        InfeasibleQueryError: an end joins no cell centre (with the clearance), or the
            goal is unreachable.
    """
    table = move_table(grid, corner_cutting, clearance)
    s, g = np.asarray(start, float), np.asarray(goal, float)
    ends = []
    for p, what in ((s, "start"), (g, "goal")):
        cells, join = _end_cells(grid, p, clearance)
        if len(cells) == 0:
            raise InfeasibleQueryError(
                f"the {what} ({p[0]:g}, {p[1]:g}) joins no free cell centre by a free segment"
                + (f" whose centre keeps the clearance {clearance:g} m" if clearance else "")
                + "; A*/Dijkstra run over cell centres: move the point or use method='visibility'")
        ends.append((cells, join))
    (sc, sj), (gc, gj) = ends
    shared = set(_flat(grid, _closure_cells(grid, s)).tolist()) & set(_flat(grid, _closure_cells(grid, g)).tolist())
    # in one closed free cell the straight segment is free without clearance (the cell is convex)
    if any(not grid.occ.flat[c] for c in shared) and (clearance == 0 or bool(grid.segments_free(s, g, clearance))):
        return CellPath(np.stack([s, g]), float(np.hypot(*(g - s))), 0, True)
    found = astar_cells(table, sc, gc) if method == "astar" else dijkstra_cells(table, sc, gc)
    if found is None:
        raise _unreachable(corner_cutting)
    flat, moves, expanded = found
    centres = grid.cell_center(table.xy(flat))
    P = np.vstack([s, centres, g])
    keep = np.ones(len(P), dtype=bool)
    keep[1:] = np.any(P[1:] != P[:-1], axis=1)  # an end at a cell centre is that centre
    return CellPath(P[keep], (sj + moves + gj) * grid.resolution, expanded)


def _flat(grid, cells: np.ndarray) -> np.ndarray:
    return cells[:, 1] * grid.width + cells[:, 0]
