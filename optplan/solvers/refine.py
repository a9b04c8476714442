"""Refinement stage of ``op.plan(..., refine=...)``: polish a planner's path.

``casadi`` smooths and shortens the path with IPOPT under clearance constraints
(:mod:`optplan.solvers.nlp`); on grids the result is finished by one corridor
pass of the QP smoother, which removes the NLP's sampling cushion. The NLP is
not tied to a corridor around the seed and can also repair a slightly colliding
seed. ``qp`` solves a sequence of convex QPs inside a safe corridor around the
path (:mod:`optplan.solvers.qp`, OSQP): it needs a collision-free seed, stays in
its homotopy class and is the faster of the two.

Both smoothers are local: neither moves a path to the other side of an
obstacle. The *tube* stage (:mod:`optplan.solvers.tube`) lets the refinement do
that near the seed: the exact any-angle search, restricted to the points within
``tube_radius`` metres of the seed, gives a second seed, both are smoothed and
the shorter valid result is kept. A tube is a neighbourhood of the seed, not a
global re-plan (a tube as large as the map is the exact planner). Defaults:
``casadi`` uses twice the widest obstacle's width
(:func:`optplan.solvers.tube.default_tube_radius`); ``qp`` stays purely local
(``tube_radius=0``) unless given a radius; ``tube_radius=0`` gives the purely
local behaviour for both.

The refined path replaces the seed only when it passed the exact check;
otherwise the seed is returned with ``refined=False`` and the reason in
``message``. Extra keyword options reach the smoother (``smooth_path`` /
``smooth_path_qp``).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import ParameterError
from ..results import PlanResult
from .result import make_plan_result

METHODS = ("casadi", "qp")
# refine method -> tube radius when none is given: "default" = default_tube_radius(world)
DEFAULT_TUBE = {"casadi": "default", "qp": 0.0}


def check_tube_radius(tube_radius) -> float | None:
    """``tube_radius`` as a float (metres) or ``None`` (the method's default); a
    ParameterError for anything else than ``None`` or a finite number >= 0."""
    if tube_radius is None:
        return None
    try:
        r = float(tube_radius)
    except (TypeError, ValueError):
        r = float("nan")
    if isinstance(tube_radius, bool) or not np.isfinite(r) or r < 0:
        raise ParameterError(f"tube_radius must be a finite number >= 0 metres (0 = purely local refinement) "
                             f"or None for the default, got {tube_radius!r}")
    return r


def tube_radius_for(world, method: str, tube_radius=None) -> float:
    """The tube radius (metres) a refinement uses: ``tube_radius`` when given, else the
    method's default (``casadi``: twice the widest obstacle, ``qp``: 0)."""
    r = check_tube_radius(tube_radius)
    if r is not None:
        return r
    if DEFAULT_TUBE.get(method) == "default":
        from .tube import default_tube_radius

        return default_tube_radius(world)
    return float(DEFAULT_TUBE.get(method, 0.0))


def _smoother(method: str):
    if method == "casadi":
        from .nlp import smooth_path

        return smooth_path
    if method == "qp":
        from .qp import smooth_path_qp

        return smooth_path_qp
    raise ParameterError(f"refine must be 'casadi' or 'qp', got {method!r}")


def refine_path(world, path, method: str = "casadi", clearance: float = 0.0, tube_radius: float | None = None,
                **options):
    """Refine a raw ``(N, 2)`` path (metres); returns the smoother's ``SmoothResult``.

    Args:
        world: GridMap or CircleWorld.
        path: ``(N, 2)`` seed in metres.
        method: ``"casadi"`` or ``"qp"``.
        clearance: required distance to obstacles, metres.
        tube_radius: metres; ``0`` = purely local smoothing of the seed, ``None`` =
            the method's default (see the module docstring). A positive radius also
            smooths the shortest path within that distance of the seed and keeps
            the shorter valid result (:func:`optplan.solvers.tube.refine_in_tube`).
        **options: passed to the smoother.
    """
    smoother = _smoother(method)
    radius = tube_radius_for(world, method, tube_radius)
    if radius == 0:
        return smoother(world, path, clearance, **options)
    from .tube import refine_in_tube

    return refine_in_tube(world, path, smoother, radius, clearance, **options)


def refine_result(world, result: PlanResult, method: str = "casadi", clearance: float = 0.0, seed=None,
                  tube_radius: float | None = None, **options) -> PlanResult:
    """Refine ``result.path``; the algorithm name and seed stay the planner's.

    ``tube_radius`` (metres, ``None`` = the method's default, ``0`` = purely local)
    and ``options`` as in :func:`refine_path`.
    """
    if not result.feasible or len(result.path) < 2:
        return replace(result, refined=False,
                       message=(result.message + "; " if result.message else "") + "not refined: the seed path is infeasible")
    out = refine_path(world, result.path, method, clearance, tube_radius=tube_radius, **options)
    if not out.success:
        return replace(result, refined=False, runtime_s=result.runtime_s + out.solve_time_s,
                       message=(result.message + "; " if result.message else "") + f"refinement fell back to the seed: {out.message}")
    refined = make_plan_result(world, out.path, result.algorithm, result.runtime_s + out.solve_time_s,
                               clearance=clearance, history=result.history, seed=result.seed, nfev=result.nfev,
                               message="; ".join(m for m in (result.message, out.message) if m), refined=True)
    return refined
