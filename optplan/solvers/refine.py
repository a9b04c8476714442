"""Refinement stage of ``op.plan(..., refine=...)``: polish a planner's path.

``casadi`` smooths and shortens the path with IPOPT under clearance constraints
(:mod:`optplan.solvers.nlp`); on grids the result is finished by one corridor
pass of the QP smoother, which removes the NLP's sampling cushion. The NLP is
not tied to a corridor around the seed and can also repair a slightly colliding
seed. ``qp`` solves a sequence of convex QPs inside a safe corridor around the
path (:mod:`optplan.solvers.qp`, OSQP): it needs a collision-free seed, stays in
its homotopy class and is the faster of the two. Both are local: neither moves
a path to the other side of an obstacle. The refined path replaces the seed
only when it passed the exact check; otherwise the seed is returned with
``refined=False`` and the reason in ``message``. Extra keyword options reach
the smoother (``smooth_path`` / ``smooth_path_qp``).
"""
from __future__ import annotations

from dataclasses import replace

from ..errors import ParameterError
from ..results import PlanResult
from .result import make_plan_result

METHODS = ("casadi", "qp")


def refine_path(world, path, method: str = "casadi", clearance: float = 0.0, **options):
    """Refine a raw ``(N, 2)`` path; returns the solver's result object."""
    if method == "casadi":
        from .nlp import smooth_path

        return smooth_path(world, path, clearance, **options)
    if method == "qp":
        from .qp import smooth_path_qp

        return smooth_path_qp(world, path, clearance, **options)
    raise ParameterError(f"refine must be 'casadi' or 'qp', got {method!r}")


def refine_result(world, result: PlanResult, method: str = "casadi", clearance: float = 0.0, seed=None,
                  **options) -> PlanResult:
    """Refine ``result.path``; the algorithm name and seed stay the planner's."""
    if not result.feasible or len(result.path) < 2:
        return replace(result, refined=False,
                       message=(result.message + "; " if result.message else "") + "not refined: the seed path is infeasible")
    out = refine_path(world, result.path, method, clearance, **options)
    if not out.success:
        return replace(result, refined=False, runtime_s=result.runtime_s + out.solve_time_s,
                       message=(result.message + "; " if result.message else "") + f"refinement fell back to the seed: {out.message}")
    refined = make_plan_result(world, out.path, result.algorithm, result.runtime_s + out.solve_time_s,
                               clearance=clearance, history=result.history, seed=result.seed, nfev=result.nfev,
                               message=result.message, refined=True)
    return refined
