"""Checks of a planning query (start and goal) shared by every planner entry point."""
from __future__ import annotations

import numpy as np

from ..errors import InfeasibleQueryError


def check_start_goal(world, start, goal, clearance: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Validate ``start`` and ``goal`` (metres) on ``world`` and return them as arrays.

    Raises:
        InfeasibleQueryError: a point is not two finite numbers, lies outside the map or in
            an obstacle (or closer than ``clearance`` to one), or start and goal coincide.
    """
    s = world.check_query_point(start, "start", clearance)
    g = world.check_query_point(goal, "goal", clearance)
    if np.array_equal(s, g):
        raise InfeasibleQueryError(f"start and goal are the same point ({s[0]:g}, {s[1]:g}); there is nothing to plan")
    return s, g
