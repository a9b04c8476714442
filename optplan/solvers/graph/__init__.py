"""Graph-search baselines: A*, Dijkstra and the exact any-angle optimum.

``shortest_path(world, start, goal, method=...)`` returns a validated
:class:`PlanResult` whose path starts at ``start`` and ends at ``goal`` exactly.
On a :class:`CircleWorld`, ``visibility`` is the exact tangent-graph optimum
among the circles.
"""
from __future__ import annotations

import math
import time

import numpy as np

from ...checks import boolean, choice
from ...errors import ParameterError, UnknownAlgorithmError
from ...results import PlanResult
from ...world.geometry import centre_moves_free, convex_corners, grid_point_free, in_free_cell
from ...world.grid import GridMap
from ...world.queries import check_start_goal, check_world
from ..capabilities import PlannerCapabilities
from ..result import make_plan_result
from ..tangent_graph import plan_tangent
from .astar import CellPath, cell_path, grid_search, octile, search_between
from .visibility import POINT_MODES, visibility_path

METHODS = ("astar", "dijkstra", "visibility")
CAPABILITIES = {
    "astar": PlannerCapabilities("astar", "graph", grid_only="A* searches the grid's cell graph",
                                 stochastic=False, exact=True),
    "dijkstra": PlannerCapabilities("dijkstra", "graph", grid_only="Dijkstra searches the grid's cell graph",
                                    stochastic=False, exact=True),
    "visibility": PlannerCapabilities("visibility", "graph", stochastic=False, exact=True),
}

__all__ = ["METHODS", "CellPath", "cell_path", "convex_corners", "grid_search", "octile", "shortest_path", "visibility_path"]


def shortest_path(world, start, goal, method: str = "astar", *, corner_cutting: bool = False,
                  points: str = "exact", clearance: float = 0.0, homotopy=None) -> PlanResult:
    """Shortest path by graph search.

    Args:
        world: a GridMap (or a CircleWorld for ``method="visibility"``).
        start, goal: ``(x, y)`` in metres. The path starts at ``start`` and ends at
            ``goal`` exactly, wherever they lie in their cells (a free cell corner or
            the map border included).
        method: ``"astar"`` (a scalar A* loop) / ``"dijkstra"`` (scipy's compiled
            Dijkstra): the octile optimum over the 8-connected cell centres, the ends
            joined to the centres of the cells they lie in (:func:`cell_path`); or
            ``"visibility"``: the exact any-angle optimum between the two points
            (:func:`visibility_path`).
        corner_cutting: allow diagonal moves past a blocked side cell (A*/Dijkstra only).
        points: ``"exact"`` (default), or ``"centres"`` / ``"corners"`` to check that
            start and goal are cell centres / lattice vertices (visibility only;
            a ParameterError otherwise). Points are never moved.
        clearance: metres. A*/Dijkstra keep only moves and end joins whose straight
            segment keeps it (exact rule); ``visibility`` searches the corners of the
            blocked cells grown by it as squares, every edge checked by the exact rule
            with the clearance (conservative: the result is feasible but may be a little
            longer than necessary, see :func:`visibility_path`).
        homotopy: an ``(N, 2)`` feasible path from start to goal (``method="visibility"``
            only): return the exact shortest path with the same h-signature (the same
            winding about every obstacle component that does not touch the border;
            :mod:`optplan.solvers.homotopy`), never longer than ``homotopy``.

    Raises:
        InfeasibleQueryError: start/goal outside the map, blocked, equal, or unreachable
            (for A*/Dijkstra also: an end that joins no free cell centre).
        UnknownAlgorithmError: unknown ``method``.
    """
    check_world(world)
    corner_cutting = boolean("corner_cutting", corner_cutting)
    choice(*POINT_MODES)("points", points)
    if method not in METHODS:
        raise UnknownAlgorithmError(f"unknown graph method {method!r}; known: {', '.join(METHODS)}")
    t0 = time.perf_counter()
    if homotopy is not None:
        if method != "visibility":
            raise ParameterError(f"homotopy= needs method='visibility' (the class search runs on the visibility "
                                 f"roadmap), got method={method!r}")
        from ..homotopy import homotopy_shortest_path

        return homotopy_shortest_path(world, start, goal, homotopy, clearance)
    if not world.is_grid:
        if method != "visibility":
            raise ParameterError(f"method {method!r} needs a grid map; use 'visibility' on circle worlds")
        return plan_tangent(world, start, goal, clearance)
    # the common query (a plain GridMap, no clearance, two plain points) skips the numpy
    # checks whose fixed cost was most of a small map's call; anything else takes the full path
    if method != "visibility" and type(world) is GridMap and type(clearance) in (float, int) and clearance == 0:
        ends = _plain_ends(world, start, goal)
        if ends is not None:
            return _cell_search(world, *ends, method, corner_cutting, t0)
    s, g = check_start_goal(world, start, goal, clearance)
    if method == "visibility":
        path, length = visibility_path(world, s, g, points, clearance=clearance)
        return make_plan_result(world, path, method, time.perf_counter() - t0, clearance=clearance,
                                defer_clearance=True, message=f"exact any-angle optimum {length:.9f} m" if clearance == 0 else
                                "shortest path over the corners of the obstacles grown by the clearance as squares")
    found = cell_path(world, s, g, method=method, corner_cutting=corner_cutting, clearance=clearance)
    how = ("start and goal share a free cell: the straight segment" if found.direct else
           f"{found.expanded} cells expanded" if method == "astar" else f"{found.expanded} cells reached")
    return make_plan_result(world, found.path, method, time.perf_counter() - t0, clearance=clearance,
                            defer_clearance=True, message=how + (" (corner cutting)" if corner_cutting else ""))


def _plain_point(grid, point):
    """``((x, y), (gx, gy))``: ``point`` as two Python floats and in grid units, when it is a
    plain pair of numbers (a tuple, a list or a float array) at a free point of the map: what
    ``check_query_point`` accepts, with the same numbers. ``None`` for anything else: the
    full check then decides (and raises)."""
    if type(point) is np.ndarray:
        if point.shape != (2,) or point.dtype != np.float64:
            return None
        x, y = point.tolist()
    elif type(point) in (tuple, list) and len(point) == 2:
        x, y = point
        # ints beyond 2**53 and bools take the full check (their float conversion is its business)
        if not all(isinstance(v, float) or (type(v) is int and -2**53 <= v <= 2**53) for v in (x, y)):
            return None
        x, y = float(x), float(y)
    else:
        return None
    xmin, ymin, xmax, ymax = grid.bounds
    if not (xmin <= x <= xmax and ymin <= y <= ymax):   # also refuses NaN (inf is outside)
        return None
    q = grid.point_to_grid(x, y)
    if not grid_point_free(grid, *q):
        return None
    return (x, y), q


def _plain_ends(grid, start, goal):
    """``(sx, sy, gx, gy, (qs, qg))`` (metres, then grid units) when start and goal both pass
    :func:`_plain_point` and differ; ``None`` otherwise (``check_start_goal`` then runs)."""
    s = _plain_point(grid, start)
    g = _plain_point(grid, goal) if s is not None else None
    if g is None or s[0] == g[0]:
        return None
    return s[0][0], s[0][1], g[0][0], g[0][1], (s[1], g[1])


def _cell_search(grid, sx, sy, gx, gy, q, method, corner_cutting, t0) -> PlanResult:
    """A*/Dijkstra without clearance between checked points: the search, then the result.

    The returned path still goes through the exact rule, in cell units, without trusting the
    search: its inner points are the centres of ``cells`` (``search_between`` takes them from
    the map's table of centres) and each inner segment joins the centres of two consecutive
    cells, which :func:`~optplan.world.geometry.centre_moves_free` judges from cell lookups
    (the general rule's verdicts for a few microseconds instead of a few hundred); each end
    lies in the closed square of the free cell whose centre it joins, or both ends in one
    free cell (:func:`~optplan.world.geometry.in_free_cell`: such a segment is free); the ends
    passed the query's point check and centres are no lattice vertices. When anything is not
    shown free that way (corner cutting can pass between two blocked cells), the general
    check (``make_plan_result``) judges the path, as before; the turn metrics and
    ``min_clearance`` are computed on their first read."""
    found, cells, (qs, qg) = search_between(grid, sx, sy, gx, gy, method=method, corner_cutting=corner_cutting,
                                            ends=q)
    runtime = time.perf_counter() - t0
    how = ("start and goal share a free cell: the straight segment" if found.direct else
           f"{found.expanded} cells expanded" if method == "astar" else f"{found.expanded} cells reached")
    if corner_cutting:
        how += " (corner cutting)"
    P = found.path
    if cells is None:   # the straight segment: both ends in one closed free cell?
        x, y = qs
        around = [(iy, ix) for iy in {math.floor(y), math.floor(y) - (y == math.floor(y))}
                  for ix in {math.floor(x), math.floor(x) - (x == math.floor(x))}
                  if 0 <= ix < grid.width and 0 <= iy < grid.height]
        free = any(in_free_cell(grid, *qs, c) and in_free_cell(grid, *qg, c)
                   for c in (iy * grid.width + ix for iy, ix in around))
    else:
        free = (in_free_cell(grid, *qs, cells[0]) and in_free_cell(grid, *qg, cells[-1])
                and bool(centre_moves_free(grid, cells).all()))
    return make_plan_result(grid, P, method, runtime, defer_clearance=True, message=how, proven_free=free)
