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
directly when that segment is free; it is then the shortest path. Between
equally short paths through different end cells, the one through the cell the
point belongs to (``cell_of``, the half-open convention that the search used to
snap to) is taken.

The neighbour structure comes from the map's cached move table
(:func:`optplan.solvers.gridpath.moves.move_table`): one byte of allowed
directions per cell for the scalar A* loop, a CSR matrix for scipy's compiled
Dijkstra. Nothing is converted per query.
"""
from __future__ import annotations

import heapq
import math
from array import array
from dataclasses import dataclass

import numpy as np

from ...errors import InfeasibleQueryError
from ..gridpath.moves import WINDOW_CELLS, move_table
from ...world.derived import DerivedStore

_DERIVED = DerivedStore("solvers.graph.astar")  # this module's data derived from worlds

SQRT2 = math.sqrt(2.0)
CLOSED = -math.inf


def octile(dx: float, dy: float) -> float:
    """Octile distance (li2023 eq 12) between cells ``dx``, ``dy`` apart, in cells."""
    dx, dy = abs(dx), abs(dy)
    return max(dx, dy) + (SQRT2 - 1.0) * min(dx, dy)


def _unreachable(corner_cutting: bool) -> InfeasibleQueryError:
    return InfeasibleQueryError(
        "the goal is unreachable from the start on the 8-connected grid"
        + ("" if corner_cutting else " (diagonal moves need both side cells free)")
        + "; check the map or choose another goal")


# cost (cells) added to the joins of the end cells other than the one the point belongs to
# (its cell_of, the half-open convention): it only breaks exact ties, as distinct path
# lengths on this grid differ by far more
TIE = 1e-9


class _TouchedOctile(dict):
    """The heuristic of a big map, computed for the cells the search touches (the same
    float operations as the octile window), so memory follows the search, not the map."""

    def __init__(self, width: int, ax: int, ay: int, slack: float, virtual_goal: int):
        super().__init__({virtual_goal: 0.0})
        self.width, self.ax, self.ay, self.slack = width, ax, ay, slack

    def __missing__(self, c: int) -> float:
        dy, dx = divmod(c, self.width)
        dx, dy = abs(dx - self.ax), abs(dy - self.ay)
        v = (dx + dy) + (SQRT2 - 2.0) * min(dx, dy)
        if self.slack > 0:
            v = max(v - self.slack, 0.0)
        self[c] = v
        return v


def astar_cells(table, sources, targets, source_bias=None, target_bias=None):
    """A*: shortest move sequence from any of ``sources`` to any of ``targets`` (flat cell indices).

    Source ``k`` starts at distance ``source_bias[k]`` (default 0) and reaching target ``k``
    costs ``target_bias[k]`` more (a virtual goal behind the targets; with one target the
    search stops when it is expanded). The heuristic is the octile distance to the first
    target less the largest octile distance between targets (clipped at 0): consistent,
    and 0 at every target. Heap entries are ``(f, g, cell)`` (ties: the shallower, then
    the lower index, first) and a move must improve a distance by more than 1e-12: with
    one source and one target this is the cell sequence the search has always returned.

    Returns ``(flat_cells, cost_in_cells, expanded)`` (a list of flat indices; the cost
    includes the biases), or ``None`` when no target is reached.
    """
    W, n = table.width, table.width * table.height
    masks, moves = table.masks, table.moves_by_mask
    targets = [int(t) for t in targets]
    single = len(targets) == 1
    ay, ax = divmod(targets[0], W)
    slack = 0.0 if single else max(octile(t % W - ax, t // W - ay) for t in targets)
    if n <= WINDOW_CELLS:
        # the heuristic of every cell: a slice of the table's octile window (the same float
        # operations as the scalar formula), copied into an array('d'), not n Python floats
        Ht = table.height
        h = table.octile_window[Ht - 1 - ay:2 * Ht - 1 - ay, W - 1 - ax:2 * W - 1 - ax]
        if slack > 0:
            h = np.maximum(h - slack, 0.0)
        H = array("d", h.tobytes())
        H.append(0.0)  # the virtual goal, flat index n
    else:
        H = _TouchedOctile(W, ax, ay, slack, n)
    # dist[c] is -1 once c is expanded (closed): no heap entry matches it. bar[c] is
    # dist[c] - 1e-12, the value a move must beat (-inf once closed: nothing beats it),
    # kept next to dist so that the test of every move is one comparison
    dist = [math.inf] * (n + 1)
    bar = [math.inf] * (n + 1)
    parent = [-1] * (n + 1)
    goal = bytearray(n + 1)
    biases = target_bias if target_bias is not None else [0.0] * len(targets)
    extra = {targets[0]: biases[0]} if single else dict(zip(targets, biases))
    for t in targets:
        goal[t] = 1
    goal[n] = 1
    heap = []
    for s, b in zip(sources, source_bias if source_bias is not None else [0.0] * len(sources)):
        s = int(s)
        dist[s] = float(b)
        bar[s] = dist[s] - 1e-12
        heap.append((H[s] + dist[s], dist[s], s))
    if len(heap) > 1:
        heapq.heapify(heap)
    pop, push, pushpop = heapq.heappop, heapq.heappush, heapq.heappushpop
    reached, cost, closed = -1, math.inf, 0
    # an expansion's last new entry waits and goes in with the next pop (one sift instead of
    # two): the heap's keys are distinct, so the entries come out in the same order
    pending = None
    while True:
        if pending is not None:
            _, d, c = pushpop(heap, pending)
            pending = None
        elif heap:
            _, d, c = pop(heap)
        else:
            break
        if d != dist[c]:
            continue  # closed, or a stale entry
        if goal[c]:
            if c == n:  # the virtual goal: its parent is the best target
                reached, cost = parent[n], d
                break
            if single:
                reached, cost = c, d + extra[c]
                break
            dist[c], bar[c] = -1.0, CLOSED
            closed += 1
            nd = d + extra[c]  # a path on through one target to another is longer than stopping
            if nd < dist[n]:
                dist[n], parent[n] = nd, c
                push(heap, (nd, nd, n))
            continue
        dist[c], bar[c] = -1.0, CLOSED
        closed += 1
        for off, w in moves[masks[c]]:
            t = c + off
            nd = d + w
            if nd < bar[t]:
                dist[t], bar[t] = nd, nd - 1e-12
                parent[t] = c
                if pending is not None:
                    push(heap, pending)
                pending = (nd + H[t], nd, t)
    if reached < 0:
        return None
    expanded = closed + int(single)   # a single target is expanded, not closed
    cells = [reached]
    append = cells.append
    c = parent[reached]
    while c >= 0:
        append(c)
        c = parent[c]
    cells.reverse()
    return cells, cost, expanded


def dijkstra_cells(table, sources, targets, source_bias=None, target_bias=None):
    """As :func:`astar_cells`, with scipy's compiled Dijkstra (a whole shortest-path tree
    from the sources, ``min_only``, which has no source bias: ties between source cells go
    to scipy). ``expanded`` is the number of cells reached."""
    from scipy.sparse.csgraph import dijkstra

    dist, pred, _ = dijkstra(table.csr, directed=True, indices=np.asarray(sources, dtype=np.int64),
                             return_predecessors=True, min_only=True)
    targets = np.asarray(targets, dtype=np.int64)
    bias = np.zeros(len(targets)) if target_bias is None else np.asarray(target_bias, float)
    best = targets[np.argmin(dist[targets] + bias)]
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
    return table.xy(np.asarray(flat, dtype=np.int64)), float(length), expanded


def _closure_cells(W: int, H: int, q) -> list[int]:
    """Flat indices of the ``W x H`` map's cells whose closed square holds the point ``q``
    (grid units): 1, or 2 on a cell edge, or up to 4 on a corner; free or not."""
    x, y = q
    fx, fy = math.floor(x), math.floor(y)
    return [iy * W + ix for iy in ((fy - 1, fy) if y == fy else (fy,)) if 0 <= iy < H
            for ix in ((fx - 1, fx) if x == fx else (fx,)) if 0 <= ix < W]


def _occupancy_bytes(grid) -> bytes:
    """One byte per cell by flat index, 1 = blocked (cached on the map): indexing ``bytes``
    gives a Python int, where indexing the boolean array builds a numpy scalar."""
    occ = _DERIVED.of(grid).get("occupancy_bytes")
    if occ is None:
        occ = _DERIVED.of(grid)["occupancy_bytes"] = grid.occ.reshape(-1).astype(np.uint8).tobytes()
    return occ


def _end_cells(grid, q: tuple[float, float], clearance: float) -> tuple[list[int], float, list[float]]:
    """The cells the point ``q`` (grid units) is joined to (flat indices), the join length
    (cells, the same for all) and each join's tie bias (0 for the cell that holds ``q``
    under the half-open convention, ``cell_of``; :data:`TIE` for the others).

    A cell qualifies when it is free, its centre keeps the clearance and the segment
    from the point to its centre is free under the exact rule. Without clearance that
    segment lies in the closed free cell and ends inside it, so the rule holds and is
    not evaluated."""
    W, H = grid.width, grid.height
    occ = _occupancy_bytes(grid)
    cells = [c for c in _closure_cells(W, H, q) if not occ[c]]
    if cells and clearance > 0:
        centres = grid.cell_center(np.array([(c % W, c // W) for c in cells]))
        p = grid.to_world(np.asarray(q, float))
        ok = grid.segments_free(np.broadcast_to(p, centres.shape), centres, clearance)
        ok &= grid.is_free(centres, clearance)
        cells = [c for c, k in zip(cells, ok.tolist()) if k]
    if not cells:
        return cells, 0.0, []
    own = min(max(math.floor(q[1]), 0), H - 1) * W + min(max(math.floor(q[0]), 0), W - 1)
    join = math.hypot(q[0] - (cells[0] % W + 0.5), q[1] - (cells[0] // W + 0.5))
    return cells, join, [0.0 if c == own else TIE for c in cells]


def cell_centres(grid) -> np.ndarray:
    """``(width * height, 2)`` centres of the cells in metres, by flat index (cached on the map)."""
    C = _DERIVED.of(grid).get("cell_centres")
    if C is None:
        iy, ix = np.divmod(np.arange(grid.width * grid.height), grid.width)
        C = grid.cell_center(np.stack([ix, iy], axis=1))
        C.setflags(write=False)
        _DERIVED.of(grid)["cell_centres"] = C
    return C


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
    s, g = np.asarray(start, float), np.asarray(goal, float)
    return search_between(grid, float(s[0]), float(s[1]), float(g[0]), float(g[1]), method=method,
                          corner_cutting=corner_cutting, clearance=clearance)[0]


def search_between(grid, sx: float, sy: float, gx: float, gy: float, *, method: str = "astar",
                   corner_cutting: bool = False, clearance: float = 0.0, ends=None):
    """:func:`cell_path` between ``(sx, sy)`` and ``(gx, gy)`` (metres, Python floats);
    ``ends``: the two points in grid units when the caller has them (``GridMap.point_to_grid``).

    Returns ``(CellPath, cells, ends)``: ``cells`` the flat indices of the path's cells in
    order (an int64 array; ``None`` for the direct segment), ``ends`` the two points in grid
    units. What ``shortest_path`` needs to check the path in cell units
    (:func:`optplan.world.geometry.centre_moves_free`) without converting it back."""
    table = move_table(grid, corner_cutting, clearance)
    res = grid.resolution
    # the per-query arithmetic on Python floats: numpy scalars cost more than the small searches
    qs, qg = ends if ends is not None else (grid.point_to_grid(sx, sy), grid.point_to_grid(gx, gy))
    joins = []
    for (px, py), q, what in (((sx, sy), qs, "start"), ((gx, gy), qg, "goal")):
        cells, join, bias = _end_cells(grid, q, clearance)
        if not cells:
            raise InfeasibleQueryError(
                f"the {what} ({px:g}, {py:g}) joins no free cell centre by a free segment"
                + (f" whose centre keeps the clearance {clearance:g} m" if clearance else "")
                + "; A*/Dijkstra run over cell centres: move the point or use method='visibility'")
        joins.append((cells, join, bias))
    (sc, sj, bs), (gc, gj, bg) = joins
    if clearance > 0:  # the cells a point shares with the other, whether or not its centre keeps the clearance
        occ, W, H = _occupancy_bytes(grid), grid.width, grid.height
        shared = ({c for c in _closure_cells(W, H, qs) if not occ[c]}
                  & {c for c in _closure_cells(W, H, qg) if not occ[c]})
    else:
        shared = set(sc) & set(gc)
    # in one closed free cell the straight segment is free without clearance (the cell is convex)
    if shared and (clearance == 0 or bool(grid.segments_free((sx, sy), (gx, gy), clearance))):
        return CellPath(np.array([[sx, sy], [gx, gy]]), math.hypot(gx - sx, gy - sy), 0, True), None, (qs, qg)
    search = astar_cells if method == "astar" else dijkstra_cells
    found = search(table, sc, gc, bs, bg)
    if found is None:
        raise _unreachable(corner_cutting)
    flat, cost, expanded = found
    cost -= bs[sc.index(flat[0])] + bg[gc.index(flat[-1])]
    # an end at a cell centre is that centre: no repeated point
    first, last = int(sj != 0), int(gj != 0)
    flat = np.asarray(flat, dtype=np.int64)
    P = np.empty((len(flat) + first + last, 2))
    if table.width * table.height <= WINDOW_CELLS:
        cell_centres(grid).take(flat, axis=0, out=P[first:len(P) - last])
    else:  # the centres of the path's cells only: a big map's table of all centres is 16 bytes a cell
        P[first:len(P) - last] = grid.cell_center(table.xy(flat))
    if first:
        P[0] = sx, sy
    if last:
        P[-1] = gx, gy
    return CellPath(P, (sj + cost + gj) * res, expanded), flat, (qs, qg)
