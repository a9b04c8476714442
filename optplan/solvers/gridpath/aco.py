"""Ant colony optimisation on the 8-connected grid graph (the hou2024 baseline).

All ants walk at once: at every step each live ant picks its next cell among
the allowed, not yet visited neighbours with probability proportional to
``tau^alpha * eta^beta`` (pheromone on the move, inverse distance of the target
to the goal). Ants that reach a dead end are dropped for that iteration. After
each iteration pheromone evaporates by ``rho`` and every successful ant adds
``Q / L`` to the moves it used. Defaults follow hou2024 Table 1: 60 ants, 300
iterations, alpha = 2, beta = 6, rho = 0.1, Q = 5.

Budget: one ant walk is one evaluation. The colony obeys the shared
:class:`~optplan.solvers.budget.Budget`: with ``max_evals`` the last iteration sends
out only the ants the budget has left, so ``nfev == max_evals`` exactly.
"""
from __future__ import annotations

import time

import numpy as np

from ...checks import integer, memory_budget
from ...errors import ParameterError
from ...rng import as_generator
from ..budget import Budget
from ..result import make_plan_result
from .moves import move_table
from ..capabilities import PlannerCapabilities

CAPABILITIES = PlannerCapabilities("aco", "aco", grid_only="ACO walks the grid's cell graph")


def aco_path(grid, start, goal, *, ants: int = 60, iters: int | None = 300, alpha: float = 2.0, beta: float = 6.0,
             rho: float = 0.1, q: float = 5.0, tau0: float = 1.0, corner_cutting: bool = False,
             seed=0, max_steps: int | None = None, callback=None, max_evals: int | None = None,
             goal_distance: np.ndarray | None = None, reward: float = 0.0, penalty: float = 0.0):
    """Run ACO; returns ``(best_path_in_metres, history_of_best_length, nfev)``.

    ``nfev`` counts ant walks (one path evaluation each, whether or not the ant
    arrives). ``iters`` caps the iterations and ``max_evals`` the walks, exactly (either
    may be ``None``, not both). The history holds the best length (metres) after each
    iteration (``inf`` while none found).

    Hooks for improved colonies (``iaco``; the defaults are plain ACO): ``goal_distance``
    replaces the straight-line distance of each flat cell to the goal in the heuristic;
    ``reward`` adds ``reward * Q / L`` more on the iteration-best walk and ``penalty`` takes
    that share of the pheromone off the moves of the iteration-worst walk.
    """
    ants = integer(1)("ants", ants)
    budget = Budget(iterations=iters, evaluations=max_evals)
    for name, v in (("alpha", alpha), ("beta", beta), ("q", q), ("tau0", tau0)):
        if not np.isfinite(v) or v < 0:
            raise ParameterError(f"{name} must be a finite number >= 0, got {v!r}")
    if not (0 < rho < 1):
        raise ParameterError(f"rho (evaporation) must be in (0, 1), got {rho!r}")
    if not (np.isfinite(reward) and reward >= 0) or not (0 <= penalty < 1):
        raise ParameterError(f"reward must be >= 0 and penalty in [0, 1), got {reward!r} and {penalty!r}")
    rng = as_generator(seed)
    table = move_table(grid, corner_cutting)
    W = grid.width
    s_cell, g_cell = grid.cell_of(start), grid.cell_of(goal)
    s, g = int(s_cell[1] * W + s_cell[0]), int(g_cell[1] * W + g_cell[0])
    n_cells = grid.width * grid.height
    max_steps = max_steps or n_cells
    # per cell: neighbours, pheromone and heuristic per move (8 x 24 bytes), and a visited
    # flag and a step per ant
    memory_budget(f"ACO with {ants} ants on {grid.width} x {grid.height} cells",
                  n_cells * (200.0 + ants * 9.0) + ants * max_steps * 8.0,
                  "use astar or visibility, or a metaheuristic (they keep no table per cell)")
    nb = table.neighbours
    valid = nb >= 0
    xy = table.xy(np.arange(n_cells)).astype(float)
    dist_goal = np.hypot(*(xy - xy[g]).T) if goal_distance is None else np.asarray(goal_distance, float)
    eta = 1.0 / np.maximum(dist_goal, 0.5)      # the goal itself gets the largest attraction
    eta_nb = np.where(valid, eta[np.where(valid, nb, 0)], 0.0) ** beta
    tau = np.full((n_cells, 8), float(tau0))
    best_len, best_cells = np.inf, None
    history = [np.inf]
    nfev = 0
    it = 0
    while budget.spent(it, nfev) is None:
        it += 1
        ants_now = budget.allowed(ants, nfev)   # the last colony may be cut to the budget
        rows = np.arange(ants_now)
        cur = np.full(ants_now, s, dtype=np.int64)
        alive = np.ones(ants_now, dtype=bool)
        done = np.zeros(ants_now, dtype=bool)
        visited = np.zeros((ants_now, n_cells), dtype=bool)
        visited[:, s] = True
        moves = np.full((ants_now, max_steps), -1, dtype=np.int64)  # chosen move index per step
        length = np.zeros(ants_now)
        for step in range(max_steps):
            walking = alive & ~done
            if not walking.any():
                break
            cand = nb[cur]                                        # (ants, 8)
            ok = (cand >= 0) & ~visited[rows[:, None], np.where(cand >= 0, cand, 0)]
            w = np.where(ok, (tau[cur] ** alpha) * eta_nb[cur], 0.0)
            w[~walking] = 0.0
            tot = w.sum(axis=1)
            stuck = walking & (tot <= 0)
            alive &= ~stuck
            walking &= ~stuck
            cum = np.cumsum(w, axis=1)
            r = rng.random(ants_now) * tot
            k = np.minimum((cum < r[:, None]).sum(axis=1), 7)
            k = np.where(walking, k, -1)
            idx = np.nonzero(walking)[0]
            nxt = cand[idx, k[idx]]
            moves[idx, step] = k[idx]
            length[idx] += table.step_length[k[idx]]
            cur[idx] = nxt
            visited[idx, nxt] = True
            done |= walking & (cur == g)
        success = np.nonzero(done)[0]
        nfev += ants_now
        # evaporation, then deposits Q / L along each successful walk
        tau *= 1.0 - rho
        if success.size:
            L = length[success]
            i_best = success[np.argmin(L)]
            if length[i_best] < best_len:
                best_len = float(length[i_best])
                best_cells = _replay(nb, s, moves[i_best])
            m = moves[success]
            steps = (m >= 0)
            cells = np.empty_like(m)
            cells[:, 0] = s
            # cell before each move: replay the walks in bulk
            for t in range(1, m.shape[1]):
                if not steps[:, t - 1].any():
                    break
                prev = cells[:, t - 1]
                cells[:, t] = np.where(steps[:, t - 1], nb[prev, np.maximum(m[:, t - 1], 0)], prev)
            sel = steps
            dep = np.broadcast_to((q / L)[:, None], m.shape)[sel]
            np.add.at(tau, (cells[sel], m[sel]), dep)
            if (reward or penalty) and success.size > 1:
                b, w = np.argmin(L), np.argmax(L)
                np.add.at(tau, (cells[b][sel[b]], m[b][sel[b]]), reward * q / L[b])
                tau[cells[w][sel[w]], m[w][sel[w]]] *= 1.0 - penalty
        history.append(best_len * grid.resolution)
        if callback is not None and callback(it, best_len) is False:
            break
    path = None if best_cells is None else grid.cell_center(table.xy(best_cells))
    if path is not None:
        path[0], path[-1] = np.asarray(start, float), np.asarray(goal, float)
    return path, np.asarray(history), nfev


def _replay(nb: np.ndarray, s: int, moves: np.ndarray) -> np.ndarray:
    cells = [s]
    for k in moves:
        if k < 0:
            break
        cells.append(int(nb[cells[-1], k]))
    return np.asarray(cells)


def plan_aco(grid, start, goal, *, seed=0, pop: int = 60, iters: int | None = 300, clearance: float = 0.0,
             max_evals: int | None = None, **params):
    """``op.plan(..., algorithm="aco")``: ACO on the grid graph; ``pop`` is the number of ants,
    ``max_evals`` caps the ant walks exactly."""
    t0 = time.perf_counter()
    s = grid.check_query_point(start, "start")
    g = grid.check_query_point(goal, "goal")
    if clearance > 0:
        raise ParameterError("aco plans on the cell graph; use clearance=0 (inflate the map with GridMap.inflate)")
    path, history, nfev = aco_path(grid, s, g, ants=pop, iters=iters, seed=seed, max_evals=max_evals, **params)
    msg = "" if path is not None else "no ant reached the goal; the goal may be unreachable or iters too small"
    return make_plan_result(grid, path, "aco", time.perf_counter() - t0, history=history,
                            seed=seed if isinstance(seed, int) else None, nfev=nfev, message=msg)
