"""Graph-search baselines: A*, Dijkstra and the exact any-angle optimum.

``shortest_path(world, start, goal, method=...)`` returns a validated
:class:`PlanResult`. On a :class:`CircleWorld`, ``visibility`` is the exact
tangent-graph optimum among the circles.
"""
from __future__ import annotations

import time

import numpy as np

from ...errors import ParameterError, UnknownAlgorithmError
from ...results import PlanResult
from ...world.queries import check_start_goal
from ..result import make_plan_result
from ..tangent_graph import plan_tangent
from .astar import grid_search, octile
from .visibility import convex_corners, visibility_path

METHODS = ("astar", "dijkstra", "visibility")

__all__ = ["METHODS", "convex_corners", "grid_search", "octile", "shortest_path", "visibility_path"]


def shortest_path(world, start, goal, method: str = "astar", *, corner_cutting: bool = False,
                  points: str = "centres", clearance: float = 0.0) -> PlanResult:
    """Shortest path by graph search.

    Args:
        world: a GridMap (or a CircleWorld for ``method="visibility"``).
        start, goal: ``(x, y)`` in metres; on grids they are snapped to their cells'
            centres (or, with ``points="corners"``, to the nearest lattice vertex).
        method: ``"astar"`` / ``"dijkstra"`` (8-connected cell centres, octile
            optimum) or ``"visibility"`` (exact any-angle optimum).
        corner_cutting: allow diagonal moves past a blocked side cell (A*/Dijkstra only).
        points: ``"centres"`` or ``"corners"`` (visibility only).
        clearance: metres. A*/Dijkstra keep only moves whose straight segment keeps
            it (exact rule); ``visibility`` searches the map inflated cell-wise by it
            (conservative: the result is feasible but may be longer than necessary).

    Raises:
        InfeasibleQueryError: start/goal outside the map, blocked, equal, or unreachable.
        UnknownAlgorithmError: unknown ``method``.
    """
    if method not in METHODS:
        raise UnknownAlgorithmError(f"unknown graph method {method!r}; known: {', '.join(METHODS)}")
    t0 = time.perf_counter()
    if not hasattr(world, "occ"):
        if method != "visibility":
            raise ParameterError(f"method {method!r} needs a grid map; use 'visibility' on circle worlds")
        return plan_tangent(world, start, goal, clearance)
    s, g = check_start_goal(world, start, goal, clearance)
    if method == "visibility":
        search_world = world.inflate(clearance) if clearance > 0 else world
        if points == "centres":
            # both points must sit in free cells for the centre convention
            for p, what in ((s, "start"), (g, "goal")):
                search_world.check_query_point(world.cell_center(world.cell_of(p)), f"{what} cell centre")
        path, length = visibility_path(search_world, s, g, points)
        return make_plan_result(world, path, method, time.perf_counter() - t0, clearance=clearance)
    cs, cg = world.cell_of(s), world.cell_of(g)
    for c, what in ((cs, "start"), (cg, "goal")):
        centre = world.cell_center(c)
        if not (world.in_map(c) and bool(world.is_free(centre, clearance)) and not world.occ[c[1], c[0]]):
            from ...errors import InfeasibleQueryError

            raise InfeasibleQueryError(f"the {what} cell (ix={c[0]}, iy={c[1]}) is blocked"
                                       + (f" or its centre is closer than {clearance:g} m to an obstacle" if clearance else ""))
    cells, _, expanded = grid_search(world, cs, cg, heuristic=method == "astar", corner_cutting=corner_cutting,
                                     clearance=clearance)
    path = world.cell_center(cells)
    return make_plan_result(world, path, method, time.perf_counter() - t0, clearance=clearance,
                            message=f"{expanded} cells expanded" + (" (corner cutting)" if corner_cutting else ""))
