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

*Multi-start* (``starts=k``): a metaheuristic ends with a population, not only
its best path. With ``k > 1`` the refinement also starts from up to ``k - 1``
other paths of the planner's run (``PlanResult.alternatives``: valid paths of
the population snapshots, best first by the planner's own fitness, each outside
the tube of the best path and of the earlier ones) and keeps the shortest valid
refined path. Nothing is evaluated again and the planner's own result is
unchanged; the choice is by refined length only. ``op.plan`` asks the planner for
the alternatives. Defaults (:data:`DEFAULT_STARTS`): ``casadi`` 3, ``qp`` 1;
``starts=1`` is the single-start refinement exactly. More starts help where the
planner ended in a longer corridor but its population had held the shorter one
during the run, and cannot help where no individual came near the optimal
corridor (``python examples/refined_vs_pure.py --runs 10``; the figures are in
``docs/measurements.md``).

The refined path replaces the seed only when it passed the exact check;
otherwise the seed is returned with ``refined=False`` and the reason in
``message``. Extra keyword options reach the smoother (``smooth_path`` /
``smooth_path_qp``).
"""
from __future__ import annotations

import functools
from dataclasses import replace

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import ParameterError
from ..results import PlanResult
from .result import check_optional_metres, make_plan_result

@dataclass(frozen=True)
class RefineMethod:
    """One ``refine=`` method: its smoother (``load()`` imports it when first used), the tube
    radius it uses when none is given (``"default"`` = :func:`default_tube_radius`, else
    metres) and its refinement starts when none are given (the best path + starts - 1
    alternatives from the planner's population)."""

    name: str
    load: Callable[[], Callable]
    default_tube: float | str
    default_starts: int


def _casadi():
    from .nlp import smooth_path

    return in_seed_class(smooth_path)


def _qp():
    from .qp import smooth_path_qp

    return smooth_path_qp


# the registry of refinement methods: a new method is one entry here (and its smoother).
# casadi: 3 starts (docs/measurements.md), a tube of twice the widest obstacle; qp is the
# fast, purely local option: one start, no tube
REFINE_METHODS: dict[str, RefineMethod] = {m.name: m for m in (
    RefineMethod("casadi", _casadi, "default", 3),
    RefineMethod("qp", _qp, 0.0, 1),
)}
METHODS = tuple(REFINE_METHODS)
DEFAULT_TUBE = {m.name: m.default_tube for m in REFINE_METHODS.values()}
DEFAULT_STARTS = {m.name: m.default_starts for m in REFINE_METHODS.values()}
MAX_STARTS = 50


def check_tube_radius(tube_radius) -> float | None:
    """``tube_radius`` as a float (metres) or ``None`` (the method's default); a
    ParameterError for anything else than ``None`` or a finite number >= 0."""
    return check_optional_metres(tube_radius, "tube_radius (0 = purely local refinement)", "the default")


def check_starts(starts) -> int | None:
    """``starts`` as an int in ``1 .. MAX_STARTS`` or ``None`` (the method's default); a
    ParameterError for anything else."""
    if starts is None:
        return None
    if isinstance(starts, bool) or not isinstance(starts, (int, np.integer)) or not 1 <= starts <= MAX_STARTS:
        raise ParameterError(f"starts must be an integer from 1 to {MAX_STARTS} (1 = refine the planner's best path "
                             f"only), or None for the default, got {starts!r}")
    return int(starts)


def starts_for(method: str, starts=None) -> int:
    """Refinement starts a refinement uses: ``starts`` when given, else the method's default."""
    k = check_starts(starts)
    return k if k is not None else int(DEFAULT_STARTS.get(method, 1))


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


def smoother_for(method: str):
    """The smoothing function behind ``refine=method`` (``casadi``: IPOPT kept in the seed's
    class, :func:`in_seed_class`; ``qp``: the corridor QP)."""
    entry = REFINE_METHODS.get(method)
    if entry is None:
        raise ParameterError(f"refine must be one of {', '.join(map(repr, METHODS))}, got {method!r}")
    return entry.load()


def in_seed_class(smoother):
    """``smoother`` (the CasADi one) with the local contract enforced: the result keeps the
    h-signature of a collision-free seed.

    Why it is needed: IPOPT's first steps from a seed that is infeasible for the NLP's
    cushioned constraints (a taut seed touches corners) are long, nearly free steps of the
    path energy, and on cluttered maps they can carry points across a one-cell obstacle;
    the solve then converges on its far side, in another, often longer, class (issue 26:
    random20-s7050). The check is the signature of the result against the seed's
    (:func:`optplan.world.roadmap.h_signature`, no roadmap built); when they differ the
    correction is the corridor QP smoother (:func:`optplan.solvers.qp.smooth_path_qp`) from
    the seed, which cannot leave the seed's corridor. Its result replaces the NLP's only when
    it is valid and in the seed's class; otherwise the NLP's result stays, and the message
    says that it left the class.
    """
    @functools.wraps(smoother)
    def smooth(world, seed_path, clearance: float = 0.0, **options):
        out = smoother(world, seed_path, clearance, **options)
        if not out.success:
            return out
        from ..world.geometry import validate_path
        from ..world.roadmap import h_signature

        P = np.asarray(seed_path, float)
        target = h_signature(world, P, clearance)
        if np.array_equal(h_signature(world, out.path, clearance), target) or not validate_path(world, P, clearance):
            return out  # in class, or a colliding seed (it has no class to keep)
        from .qp import smooth_path_qp

        q = smooth_path_qp(world, P, clearance, **({"w_smooth": options["w_smooth"]} if "w_smooth" in options else {}))
        t = out.solve_time_s + q.solve_time_s
        if q.success and np.array_equal(h_signature(world, q.path, clearance), target):
            return replace(q, solve_time_s=t, iterations=out.iterations + q.iterations, rounds=out.rounds + q.rounds,
                           message="; ".join(m for m in ("the NLP left the seed's homotopy class; the corridor QP "
                                                         "from the seed kept it", q.message) if m))
        why = q.message if not q.success else "it left the class too"
        return replace(out, solve_time_s=t, message="; ".join(m for m in (out.message, "the result is not in the "
                       f"seed's homotopy class (the corridor QP correction failed: {why})") if m))

    return smooth


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
    smoother = smoother_for(method)
    radius = tube_radius_for(world, method, tube_radius)
    if radius == 0:
        return smoother(world, path, clearance, **options)
    from .tube import refine_in_tube

    return refine_in_tube(world, path, smoother, radius, clearance, **options)


def pick_starts(world, result: PlanResult, count: int, radius: float) -> list[np.ndarray]:
    """Up to ``count`` of ``result.alternatives`` (in their order) that leave the tube of
    radius ``radius`` around ``result.path`` and around every start picked before them;
    ``radius=0``: any that differ."""
    from .tube import Band

    if count <= 0 or not len(result.alternatives):
        return []
    bands = [Band(world, result.path, radius)]
    picked = []
    for alt in result.alternatives:
        P = np.asarray(alt, float).reshape(-1, 2)
        if len(P) < 2 or any(b.holds(P) for b in bands):
            continue
        picked.append(P)
        bands.append(Band(world, P, radius))
        if len(picked) == count:
            break
    return picked


def refine_result(world, result: PlanResult, method: str = "casadi", clearance: float = 0.0, seed=None,
                  tube_radius: float | None = None, starts: int | None = None, **options) -> PlanResult:
    """Refine ``result.path``; the algorithm name and seed stay the planner's.

    ``tube_radius`` (metres, ``None`` = the method's default, ``0`` = purely local)
    and ``options`` as in :func:`refine_path`. ``starts`` (``None`` = the method's
    default, :data:`DEFAULT_STARTS`): refine the best path and up to ``starts - 1``
    of ``result.alternatives`` (:func:`pick_starts`, with the same tube radius) and
    keep the shortest valid result; ``runtime_s`` adds every refinement. Without
    alternatives (graph search, or a result planned without them) it is the
    single-start refinement.
    """
    if not result.feasible or len(result.path) < 2:
        return replace(result, refined=False,
                       message=(result.message + "; " if result.message else "") + "not refined: the seed path is infeasible")
    k = starts_for(method, starts)
    others = pick_starts(world, result, k - 1, tube_radius_for(world, method, tube_radius)) if k > 1 else []
    out = refine_path(world, result.path, method, clearance, tube_radius=tube_radius, **options)
    if others:
        out = _shortest_of_starts(world, out, others, method, clearance, tube_radius, options)
    if not out.success:
        return replace(result, refined=False, runtime_s=result.runtime_s + out.solve_time_s,
                       message=(result.message + "; " if result.message else "") + f"refinement fell back to the seed: {out.message}")
    refined = make_plan_result(world, out.path, result.algorithm, result.runtime_s + out.solve_time_s,
                               clearance=clearance, history=result.history, seed=result.seed, nfev=result.nfev,
                               message="; ".join(m for m in (result.message, out.message) if m), refined=True)
    refined.alternatives = result.alternatives
    return refined


def _shortest_of_starts(world, own, others, method, clearance, tube_radius, options):
    """Refine each of ``others`` like the best path was (``own``); return the shortest
    successful ``SmoothResult`` with the total time and a message saying which start won."""
    from ..world.metrics import path_length

    rest = {k: v for k, v in options.items() if k != "warm_start"}  # a warm start belongs to the best path's solve
    outs = [own] + [refine_path(world, P, method, clearance, tube_radius=tube_radius, **rest) for P in others]
    lengths = [float(path_length(o.path)) if o.success else float("inf") for o in outs]
    i = int(np.argmin(lengths))
    total = sum(o.solve_time_s for o in outs)
    n = len(outs)
    if not np.isfinite(lengths[i]):
        return replace(own, solve_time_s=total, message=f"{own.message}; none of the {n} starts refined to a valid path")
    if i == 0:
        note = f"multi-start: the best path's refinement was the shortest of {n} starts"
    else:
        was = f"{lengths[0]:.4f} m" if np.isfinite(lengths[0]) else "failed"
        note = (f"multi-start: start {i + 1} of {n} (alternative {i} of the planner's population) refined shortest "
                f"({lengths[i]:.4f} m; the best path's refinement: {was})")
    return replace(outs[i], solve_time_s=total, message="; ".join(m for m in (note, outs[i].message) if m))
