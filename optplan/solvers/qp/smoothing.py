"""Convex corridor smoothing: refine a collision-free path with a sequence of QPs.

Each round builds the safe corridor of the current path
(:mod:`optplan.solvers.qp.corridor`: a free box per piece on grids, a trust box
and tangent half-planes per piece in circle worlds) and solves the convex QP of
:mod:`optplan.solvers.qp.program` inside it: squared first differences (length
surrogate) + ``w_smooth`` x squared second differences (smoothness), start and
goal fixed. The solution lies in the corridor, so it is collision-free by
construction and the next round's corridor can be built around it; rounds stop
when ``J`` improves by less than ``tol`` (relative) or after ``rounds``.

Unlike the CasADi smoother, this never leaves the seed's homotopy class and
needs a collision-free seed (it cannot repair a colliding one); each round is
a convex problem with a certificate, solved in milliseconds.

Status discipline, as in :func:`optplan.solvers.nlp.smooth_path`: the start and
goal clearance and the seed's validity are checked first; every round's result
goes through ``validate_path``; if the QP fails or the result is invalid the
call is retried once with twice the points and shrunken regions (smaller boxes,
a larger cushion); after that the seed comes back unchanged with the reason.
"""
from __future__ import annotations

import time

import numpy as np

from ...errors import ParameterError
from ...world.geometry import validate_path
from ..smoother import SmoothResult, check_seed_ends, default_points
from .corridor import build_corridor, sample_for_corridor
from .program import corridor_program, objective_value, osqp_settings


def smooth_path_qp(world, seed_path, clearance: float = 0.0, n_points: int | None = None, w_smooth: float = 0.5,
                   backend: str = "osqp", rounds: int = 6, tol: float = 1e-3, k_halfplanes: int = 6,
                   max_cells: int = 3, max_step: float | None = None, cushion: float = 1e-5,
                   osqp: dict | None = None) -> SmoothResult:
    """Smooth and shorten a collision-free ``seed_path`` inside its safe corridor.

    Args:
        world: GridMap or CircleWorld.
        seed_path: ``(M, 2)`` collision-free polyline, metres (start first, goal last).
        clearance: required distance to obstacles, metres.
        n_points: points spread evenly along the seed (plus the seed's vertices where an
            even piece would cut a corner, and on grids a few where a piece is split at cell lines). Default: about
            one per 0.25 m (circle worlds) or per quarter cell (grids), 20-100.
        w_smooth: weight of the squared second differences (same objective as the CasADi smoother).
        backend: ``"osqp"`` (the OSQP API, set up once per size, then updated and
            warm-started) or ``"cvxpy"`` (the same problem through cvxpy Parameters, solved by Clarabel).
        rounds: corridor rebuilds at most.
        tol: stop when a round improves ``J`` by less than this fraction.
        k_halfplanes: half-planes per piece (circle worlds).
        max_cells: cell lines a grid box may grow on each side.
        max_step: trust-box half-width around each piece in circle worlds, metres
            (default a tenth of the shorter side of the map).
        cushion: regions shrink by this much (metres; grid: times the resolution),
            a margin over the QP solver's constraint tolerance.
        osqp: OSQP settings of this call (e.g. ``{"max_iter": 2000}``), over the module's
            defaults ``OSQP_SETTINGS`` (osqp backend; through ``op.plan``:
            ``refine_options={"osqp": {...}}``).

    Returns:
        SmoothResult; ``success`` only when the result passed ``validate_path``.
    """
    t0 = time.perf_counter()
    osqp_settings(osqp)   # a bad settings dict is refused before any work
    if backend not in ("osqp", "cvxpy"):
        raise ParameterError(f"backend must be 'osqp' or 'cvxpy', got {backend!r}")
    if rounds < 1:
        raise ParameterError(f"rounds must be at least 1, got {rounds}")
    P, refused = check_seed_ends(world, seed_path, clearance)
    if refused is not None:
        return refused
    seed_check = validate_path(world, P, clearance)
    if not seed_check:
        return SmoothResult(P, False, f"the seed path is not collision-free ({seed_check.reason}); the corridor "
                            "smoother keeps a valid seed's homotopy class and cannot repair a colliding one "
                            "(use refine='casadi' or a feasible seed)", time.perf_counter() - t0)
    is_grid = world.is_grid
    scale = world.resolution if is_grid else 1.0
    N = n_points or default_points(P, 0.25 * scale)
    if max_step is None and not is_grid:
        xmin, ymin, xmax, ymax = world.bounds
        max_step = 0.1 * min(xmax - xmin, ymax - ymin)
    reasons = []
    solves = 0
    for attempt in range(2):
        shrink = attempt > 0
        opts = dict(k=k_halfplanes, max_cells=max(1, max_cells // 2) if shrink else max_cells,
                    max_step=(max_step or 0.0) / 2 if shrink else (max_step or 0.0),
                    cushion=cushion * 100 if shrink else cushion)
        X = sample_for_corridor(world, P, min(2 * N, 200) if shrink else N, clearance)
        best, best_J, iters, note = None, np.inf, 0, ""
        y = None
        for rnd in range(rounds):
            corridor = build_corridor(world, X, clearance, split=(rnd == 0), **opts)
            prog = corridor_program(corridor.n_points, corridor.k_slots, w_smooth, backend, osqp)
            sol = prog.solve(corridor) if backend == "cvxpy" else prog.solve(corridor, y0=y)
            iters += sol.iterations
            solves += 1
            if not sol.ok:
                note = f"round {rnd + 1}: QP status {sol.status}"
                break
            check = validate_path(world, sol.points, clearance)
            if not check:
                note = f"round {rnd + 1}: result invalid ({check.reason})"
                break
            X, y = sol.points, sol.dual
            improved = best_J - sol.objective
            best, best_J = X, sol.objective
            if improved < tol * sol.objective:
                break
        if best is not None:
            msg = "" if attempt == 0 else f"succeeded on retry ({reasons[0]})"
            if note:
                msg = (msg + "; " if msg else "") + f"kept the last valid round ({note})"
            return SmoothResult(best, True, msg, time.perf_counter() - t0, iters, best_J, solves)
        reasons.append(f"attempt {attempt + 1}: {note}")
    return SmoothResult(P, False, "; ".join(reasons), time.perf_counter() - t0, 0, objective_value(P, w_smooth), solves)
