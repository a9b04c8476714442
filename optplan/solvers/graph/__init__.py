"""Graph-search baselines: A*, Dijkstra and the exact any-angle optimum.

``shortest_path(world, start, goal, method=...)`` returns a validated
:class:`PlanResult` whose path starts at ``start`` and ends at ``goal`` exactly.
On a :class:`CircleWorld`, ``visibility`` is the exact tangent-graph optimum
among the circles.
"""
from __future__ import annotations

import time

import numpy as np

from ...checks import boolean, choice
from ...errors import ParameterError, UnknownAlgorithmError
from ...results import PlanResult
from ...world.geometry import convex_corners
from ...world.queries import check_start_goal, check_world
from ..capabilities import PlannerCapabilities
from ..result import make_plan_result
from ..tangent_graph import plan_tangent
from .astar import CellPath, cell_path, grid_search, octile
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

