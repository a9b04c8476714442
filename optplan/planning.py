"""``op.plan``: one entry point for every global planner (graph search and metaheuristics)."""
from __future__ import annotations

import inspect

import numpy as np

from .checks import metres, population_budget, seed_bound
from .errors import ParameterError, UnknownAlgorithmError
from .papers import paper_of_algorithm
from .registry import GRAPH_METHODS
from .results import PlanResult
from .world.queries import check_start_goal



def global_planner_names() -> list[str]:
    """Names ``op.plan`` takes as ``algorithm`` (graph search, metaheuristics, ACO, the path GAs)."""
    from .solvers.paths import algorithm_names

    return sorted(set(GRAPH_METHODS) | set(algorithm_names()))


def _checked_clearance(clearance) -> float:
    return metres("clearance", clearance)


def _checked_refine_options(options) -> dict:
    """``refine_options`` as a dict, its tube radius checked before any planning is done."""
    if options is None:
        return {}
    if not isinstance(options, dict):
        raise ParameterError(f"refine_options must be a dict of refinement options such as "
                             f"{{'tube_radius': 3.0}}, got {options!r}")
    taken = sorted({"method", "clearance", "seed"} & set(options))
    if taken:
        raise ParameterError(f"refine_options cannot set {', '.join(taken)}: use plan's own refine, clearance "
                             "and seed arguments")
    from .solvers.refine import check_starts, check_tube_radius

    check_tube_radius(options.get("tube_radius"))
    check_starts(options.get("starts"))
    return dict(options)


def _request_alternatives(world, refine: str, refine_options: dict, params: dict) -> None:
    """A multi-start refinement needs the planner's alternatives: ask for ``starts - 1``
    of them, distinct by the refinement's own tube radius (a caller's explicit
    ``alternatives`` / ``alternative_separation`` win)."""
    from .solvers.refine import starts_for, tube_radius_for

    k = starts_for(refine, refine_options.get("starts"))
    if k > 1:
        params.setdefault("alternatives", k - 1)
        params.setdefault("alternative_separation", tube_radius_for(world, refine, refine_options.get("tube_radius")))


def _judge_stages(world, start, goal, clearance, name, preset, before, after, refine, if_worse):
    """Record the planner's and the refinement's stage under the planner's own program (the paper
    fitness it optimised): a refinement that raises it is reported, or rejected with ``if_worse``."""
    from dataclasses import replace

    from .formulations.paper_programs import paper_program
    program_name = preset if isinstance(preset, str) else paper_of_algorithm(name)
    prog = paper_program(program_name, world, start, goal, clearance=clearance)

    def record(stage, solver, res):
        cost = prog.judge(res.path)[0] if len(res.path) >= 2 else float("inf")
        return {"stage": stage, "solver": solver, "program": program_name, "fitness": cost,
                "length": float(res.length), "feasible": bool(res.feasible)}

    first, second = record(1, name, before), record(2, refine, after)
    second.update(fitness_before=first["fitness"], length_before=first["length"],
                  worse=bool(after.refined and second["fitness"] > first["fitness"] + 1e-9))
    stages = [first, second]
    if not second["worse"]:
        return replace(after, stages=stages)
    note = (f"refine={refine} raised the {program_name} fitness the planner optimised from "
            f"{first['fitness']:.4g} to {second['fitness']:.4g} (length {first['length']:.4g} -> "
            f"{second['length']:.4g} m)")
    if if_worse == "reject":
        second["accepted"] = False
        return replace(before, stages=stages, message="; ".join(m for m in (before.message, note + "; the "
                       "planner's path is returned (refine_options if_worse='reject')") if m))
    second["accepted"] = True
    return replace(after, stages=stages, message="; ".join(m for m in (after.message, note + "; kept "
                   "(refine_options if_worse='reject' returns the planner's path)") if m))


def plan(world, start, goal, algorithm: str = "astar", refine: str | None = None, seed: int | None = 0,
         pop: int = 30, iters: int = 500, clearance: float = 0.0, refine_options: dict | None = None,
         **params) -> PlanResult:
    """Plan a global path from ``start`` to ``goal`` (metres) on ``world``.

    Args:
        world: a GridMap or CircleWorld.
        start, goal: ``(x, y)`` in metres.
        algorithm: a name from ``op.algorithms()`` (``astar``, ``visibility``, ``gwo``, ...).
        refine: ``None``/``"none"``, ``"casadi"`` or ``"qp"``.
        seed: seed of stochastic planners (ignored by graph search).
        pop, iters: population size and iterations of metaheuristics.
        clearance: required distance from obstacles, metres.
        refine_options: keyword options of the refinement (``refine_result``), e.g.
            ``{"tube_radius": 3.0}``: metres around the seed in which the refinement may
            move the path to the other side of an obstacle (``0``: purely local; default
            for ``casadi``: twice the widest obstacle, for ``qp``: 0), ``{"starts": k}``:
            also refine up to ``k - 1`` other distinct paths of a metaheuristic's
            population and keep the shortest (default ``casadi`` 3, ``qp`` 1; ``1`` =
            the best path only; see :mod:`optplan.solvers.refine`), ``{"if_worse":
            "reject"}``: return the planner's path when the refinement raises the
            planner's own fitness (default ``"keep"``: keep it and say so in
            ``message`` and ``stages``), or smoother options such as ``n_points``.
            Ignored without ``refine``.
        **params: extra keyword arguments for the chosen planner, e.g. ``encoding="general"``
            for a metaheuristic (every path class on every map; ``op.plan`` also falls back to
            it when the paper's encoding cannot represent a solution, and says so in
            ``result.encoding`` and ``message``; see :func:`optplan.solvers.paths.plan_path`),
            or ``encoding="cells"`` for ``ga``/``iga`` on a grid (li2023's own chromosome, a
            general cell sequence that may double back; ``"columns"``, one cell per column, is
            their default).

    Returns:
        A :class:`PlanResult`; ``feasible`` is the verdict of the exact ``validate_path``.

    Raises:
        InfeasibleQueryError: start/goal outside the map, blocked, equal, or unreachable.
        UnknownAlgorithmError: ``algorithm`` is not registered.
        ParameterError: a parameter is out of range, NaN or of the wrong type.
    """
    if not isinstance(algorithm, str):
        raise UnknownAlgorithmError(f"algorithm must be a name string, got {algorithm!r}")
    name = algorithm.lower()
    from .solvers.refine import METHODS as REFINE_METHODS

    if refine is not None and refine not in ("none", *REFINE_METHODS):
        raise ParameterError(f"refine must be one of none, {', '.join(REFINE_METHODS)}; got {refine!r}")
    refine_options = _checked_refine_options(refine_options)
    start, goal = check_start_goal(world, start, goal, _checked_clearance(clearance))
    if name not in GRAPH_METHODS:
        # one variable per column on grids (the default encoding), a few waypoints elsewhere
        dim = max(getattr(world, "width", 8), getattr(world, "height", 8)) * 2
        population_budget(pop, iters, params.get("max_evals"), dim)
    seed_bound("seed", seed)
    names = global_planner_names()
    if name not in names:
        raise UnknownAlgorithmError(f"unknown path planner {algorithm!r}; known: {', '.join(names)}")
    from .solvers.catalog import planner_capabilities

    caps = planner_capabilities(name)
    if not caps.runs_on(world):
        raise ParameterError(f"{name!r} needs a grid map ({caps.grid_only}); on a circle world use "
                             "'visibility' or a metaheuristic such as 'pso', 'ipso' or 'ga'")
    from .solvers.catalog import check_plan_options, check_refine_options

    check_plan_options(name, world, params, names, _PLAN_KEYWORDS)
    if refine not in (None, "none"):
        check_refine_options(refine, refine_options)
    if name in GRAPH_METHODS:
        from .solvers.graph import shortest_path

        result = shortest_path(world, start, goal, method=name, clearance=clearance, **params)
    else:
        from .solvers import paths

        if refine not in (None, "none"):
            _request_alternatives(world, refine, refine_options, params)
        result = paths.plan_path(world, start, goal, algorithm=name, seed=seed, pop=pop, iters=iters,
                                 clearance=clearance, **params)
    if refine not in (None, "none"):
        from .solvers.refine import refine_result

        if_worse = refine_options.pop("if_worse", "keep")
        if if_worse not in ("keep", "reject"):
            raise ParameterError(f"refine_options['if_worse'] must be 'keep' (report it) or 'reject' (return the "
                                 f"planner's path), got {if_worse!r}")
        seed_result = result
        result = refine_result(world, result, method=refine, clearance=clearance, seed=seed, **refine_options)
        result.encoding = seed_result.encoding  # the refinement keeps the planner's encoding on record
        result = _judge_stages(world, start, goal, clearance, name, params.get("preset"), seed_result, result,
                               refine, if_worse)
    if result.seed is None and name not in GRAPH_METHODS and isinstance(seed, (int, np.integer)):
        result.seed = int(seed)
    return result


# op.plan's own keywords: offered as the spelling meant when a planner option is unknown
_PLAN_KEYWORDS = tuple(inspect.signature(plan).parameters)[3:-1]


