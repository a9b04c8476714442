"""Checks of a planning query (start and goal) shared by every planner entry point."""
from __future__ import annotations

import numpy as np

from ..errors import InfeasibleQueryError, ParameterError


def check_world(world, what: str = "world"):
    """``world`` must be a map optplan can plan on (a GridMap, a CircleWorld, or an object
    with their query methods); a file name is refused with a hint to load it first."""
    needed = ("check_query_point", "is_free", "segments_free", "clearance")
    if not all(callable(getattr(world, m, None)) for m in needed):
        if isinstance(world, (str, bytes)) or hasattr(world, "__fspath__"):
            hint = " (load a map file with op.load_map first)"
        elif isinstance(world, (np.ndarray, list)):
            hint = " (an occupancy array, True = blocked, becomes a map with op.GridMap(occ, resolution=...))"
        else:
            hint = ""
        raise ParameterError(f"{what} must be an op.GridMap or op.CircleWorld, got {type(world).__name__}{hint}")
    return world


def as_point(point, what: str) -> np.ndarray:
    """``point`` as a length-2 float array, or InfeasibleQueryError naming it."""
    try:
        p = np.asarray(point, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        p = np.full(3, np.nan)
    if p.shape != (2,) or not np.all(np.isfinite(p)):
        raise InfeasibleQueryError(f"{what} must be two finite numbers (x, y) in metres, got {point!r}")
    return p


def check_start_goal(world, start, goal, clearance: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Validate ``start`` and ``goal`` (metres) on ``world`` and return them as arrays.

    Raises:
        InfeasibleQueryError: a point is not two finite numbers, lies outside the map or in
            an obstacle (or closer than ``clearance`` to one), or start and goal coincide.
    """
    check_world(world)
    s = world.check_query_point(as_point(start, "start"), "start", clearance)
    g = world.check_query_point(as_point(goal, "goal"), "goal", clearance)
    if np.array_equal(s, g):
        raise InfeasibleQueryError(f"start and goal are the same point ({s[0]:g}, {s[1]:g}); there is nothing to plan")
    return s, g


def grid_reachable(grid, start, goal) -> bool:
    """Whether a point robot (no clearance) can move from ``start`` to ``goal`` on ``grid``.

    Under the segment rule a path passes from a free cell to a 4-neighbour through their
    shared edge, and to a diagonal neighbour only past a third free cell (two blocked
    cells meeting at a corner close it), so the free cells the two points touch must lie
    in one 4-connected component. Linear in the map's size (a labelling pass)."""
    from scipy import ndimage

    def cells(p):
        gx, gy = grid.point_to_grid(float(p[0]), float(p[1]))
        xs = {int(np.floor(gx)), int(np.floor(gx)) - (gx == np.floor(gx))}
        ys = {int(np.floor(gy)), int(np.floor(gy)) - (gy == np.floor(gy))}
        return [(x, y) for x in xs for y in ys if 0 <= x < grid.width and 0 <= y < grid.height and not grid.occ[y, x]]

    a, b = cells(start), cells(goal)
    if not a or not b:
        return False
    labels, _ = ndimage.label(~grid.occ)
    return bool({labels[y, x] for x, y in a} & {labels[y, x] for x, y in b})
