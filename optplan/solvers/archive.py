"""Population archives of the path planners, turned into alternative paths.

Shared by every planner that returns ``result.alternatives`` (the metaheuristics in
``paths.plan_path`` and the cell-sequence GAs in ``gridpath.ga_path``), so neither has
to import the other.
"""
from __future__ import annotations

import numpy as np

# iterations between the population snapshots that ``alternatives`` are drawn from
# (the final population alone often has lost the better corridor; docs/measurements.md)
ARCHIVE_EVERY = 10


def archive_alternatives(world, X, violation, encoding, finish, best_x, best_path, count: int,
                         separation: float | None, clearance: float = 0.0) -> list[np.ndarray]:
    """Decode a population archive (rows ``X`` best first, their ``violation``) lazily
    into up to ``count`` distinct valid paths (:func:`~optplan.solvers.tube.population_alternatives`):
    ``encoding.waypoints(row)`` then the planner's post-processing ``finish``.
    ``separation=None`` is the default tube radius of ``refine="casadi"``."""
    from .tube import default_tube_radius, population_alternatives

    if count <= 0 or X is None or len(X) == 0:
        return []
    sep = default_tube_radius(world) if separation is None else separation
    rows = X[np.asarray(violation) == 0]
    return population_alternatives(world, (encoding.waypoints(x) for x in rows), best_path, count, sep, clearance,
                                   finish=finish, best_raw=encoding.waypoints(best_x))
