"""An improved ant colony (``iaco``), the second hou2024 baseline (Tables 2-3).

hou2024 compares MISSA with an "improved ant colony optimization (IACO)" without defining
it or citing its source next to the tables. Its introduction summarises one improved colony,
Zheng et al. [19]: the heuristic uses the actual shortest distance the ants can travel, and
reward and penalty rules update the pheromone. This module reconstructs that colony from
the summary (docs/fidelity/hou2024.md), on top of the plain colony of :mod:`.aco`:

* heuristic ``eta = 1 / d_geo``: ``d_geo`` is the shortest 8-connected grid distance from
  the cell to the goal (one Dijkstra search from the goal, no corner cutting) instead of the
  straight line, so walls no longer attract ants into dead ends;
* reward: the iteration-best walk deposits ``(1 + reward) Q / L`` (``reward`` = 1);
* penalty: the iteration-worst walk loses ``penalty`` (0.5) of the pheromone on its moves.

The reward and penalty sizes are our choice; the summary gives none.
"""
from __future__ import annotations

import time

import numpy as np

from ..result import make_plan_result
from .aco import aco_path
from .moves import move_table
from ..capabilities import PlannerCapabilities

CAPABILITIES = PlannerCapabilities("iaco", "aco", grid_only="IACO walks the grid's cell graph")


def geodesic_goal_distance(grid, goal_cell, corner_cutting: bool = False) -> np.ndarray:
    """Shortest 8-connected distance (cells) from every flat cell to ``goal_cell``; cells
    that cannot reach it get ``inf``."""
    from scipy.sparse.csgraph import dijkstra

    table = move_table(grid, corner_cutting)
    g = int(goal_cell[1] * grid.width + goal_cell[0])
    # distances *to* the goal: search the reversed graph from it (moves are symmetric here)
    return dijkstra(table.csr.T.tocsr(), indices=g)


def plan_iaco(grid, start, goal, *, seed=0, pop: int = 60, iters: int = 300, clearance: float = 0.0,
              reward: float = 1.0, penalty: float = 0.5, **params):
    """``op.plan(..., algorithm="iaco")``: the reconstructed improved colony; ``pop`` ants."""
    from ...errors import ParameterError

    t0 = time.perf_counter()
    s = grid.check_query_point(start, "start")
    g = grid.check_query_point(goal, "goal")
    if clearance > 0:
        raise ParameterError("iaco plans on the cell graph; use clearance=0 (inflate the map with GridMap.inflate)")
    d = geodesic_goal_distance(grid, grid.cell_of(g), params.get("corner_cutting", False))
    d = np.where(np.isfinite(d), d, 1e9)   # cells cut off from the goal: no attraction
    path, history, nfev = aco_path(grid, s, g, ants=pop, iters=iters, seed=seed, goal_distance=d, reward=reward,
                                   penalty=penalty, **params)
    msg = "" if path is not None else "no ant reached the goal; the goal may be unreachable or iters too small"
    return make_plan_result(grid, path, "iaco", time.perf_counter() - t0, history=history,
                            seed=seed if isinstance(seed, int) else None, nfev=nfev, message=msg)
