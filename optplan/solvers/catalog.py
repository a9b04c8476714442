"""Which keyword options each global planner and refinement takes, checked in one place.

``op.plan`` forwards its extra keywords through several levels (the planner's entry,
the optimiser, the algorithm's own parameters; the refinement, its tube and its
smoother). The accepted names are read from those functions' signatures and the
algorithms' parameter tables, so they cannot drift from the code, and an option the
chosen planner does not take is a ParameterError that names it, lists what the
planner takes and says which planners or refinements do take it — before any work
is done, never a raw ``TypeError`` or a silently ignored keyword.
"""
from __future__ import annotations

import dataclasses
import inspect
from typing import Callable, Iterable

from ..errors import ParameterError, UnknownAlgorithmError, named_with_hints

# keywords op.plan passes itself: never user options of the planner's entry point
PLAN_OWN = frozenset({"world", "grid", "start", "goal", "algorithm", "seed", "pop", "iters", "clearance",
                      "improved", "ants", "params"})
# optimise() keywords that plan_path sets itself
OPTIMIZE_SET_BY_PLANNER = frozenset({"f", "bounds", "dim", "init", "repair", "archive_every"})
REFINE_OWN = frozenset({"world", "path", "seed_path", "seed", "smoother", "radius", "clearance", "method",
                        "result", "warm_start"})
REFINE_CONTROL = frozenset({"tube_radius", "starts", "if_worse"})


def keyword_names(fn: Callable, exclude: Iterable[str] = ()) -> set[str]:
    """Names of ``fn``'s named parameters (no ``*args``/``**kwargs``), minus ``exclude``."""
    skip = set(exclude)
    return {p.name for p in inspect.signature(fn).parameters.values()
            if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD) and p.name not in skip}


def planner_capabilities(name: str):
    """The :class:`~optplan.solvers.capabilities.PlannerCapabilities` that ``name`` declares
    (an UnknownAlgorithmError for an unknown planner)."""
    from .graph import CAPABILITIES as GRAPH
    from .gridpath.aco import CAPABILITIES as ACO
    from .gridpath.ga_path import CAPABILITIES as CELL_GA
    from .gridpath.iaco import CAPABILITIES as IACO

    declared = {**GRAPH, ACO.name: ACO, IACO.name: IACO, **CELL_GA}
    if name in declared:
        return declared[name]
    from .metaheuristics import ALGORITHMS

    if name in ALGORITHMS:
        return ALGORITHMS[name].capabilities()
    raise UnknownAlgorithmError(f"unknown path planner {name!r}")


def runs_on(name: str, world) -> bool:
    """Whether the global planner ``name`` runs on ``world``, as it declares (names that are
    not global planners, e.g. local planners, run anywhere: True)."""
    try:
        caps = planner_capabilities(name)
    except UnknownAlgorithmError:
        return True
    return caps.runs_on(world)


def planner_kind(name: str, world, encoding=None) -> str:
    """``graph``, ``aco``, ``cell-ga`` (the grid GAs on their own chromosome) or ``swarm``: the
    kind the planner declares (:mod:`optplan.solvers.capabilities`), except that ``ga`` runs on
    li2023's cell chromosome when a grid plan asks for it (``encoding`` ``paper``, ``columns``
    or ``cells``); it is a swarm otherwise."""
    kind = planner_capabilities(name).kind
    # ga's default is the general encoding (a swarm); "paper", "columns", "cells": li2023's chromosome
    if name == "ga" and world.is_grid and encoding in ("paper", "columns", "cells"):
        return "cell-ga"
    return kind


def planner_options(name: str, world, encoding=None) -> set[str]:
    """Every keyword ``op.plan(..., algorithm=name, **options)`` accepts on ``world``."""
    kind = planner_kind(name, world, encoding)
    if kind == "graph":
        from .graph import shortest_path

        return keyword_names(shortest_path, PLAN_OWN | {"method"})
    if kind == "aco":
        from .gridpath.aco import aco_path, plan_aco
        from .gridpath.iaco import plan_iaco

        entry = plan_iaco if name == "iaco" else plan_aco
        # postprocess: applied by paths.plan_path to the colony's cell path
        return keyword_names(entry, PLAN_OWN) | keyword_names(aco_path, PLAN_OWN) | {"postprocess"}
    if kind == "cell-ga":
        from .gridpath.ga_path import GAParams, plan_ga

        fields = {f.name for f in dataclasses.fields(GAParams)} - {"improved"}
        own = keyword_names(plan_ga, PLAN_OWN) | fields | {"encoding"}   # "columns" and "cells" are its own
        if name == "iga" and encoding in (None, "general"):
            from .gridpath.via_ga import plan_via_ga

            own |= keyword_names(plan_via_ga, PLAN_OWN)   # the via points' count
        return own
    from .metaheuristics import get_algorithm, optimize
    from .paths import plan_path

    own = set(get_algorithm(name).defaults())
    return keyword_names(plan_path, PLAN_OWN) | keyword_names(optimize, PLAN_OWN | OPTIMIZE_SET_BY_PLANNER) | own


def refine_options(method: str) -> set[str]:
    """Every key ``refine_options`` accepts with ``refine=method``."""
    from .refine import smoother_for
    from .tube import refine_in_tube

    return set(REFINE_CONTROL) | keyword_names(refine_in_tube, REFINE_OWN) | keyword_names(smoother_for(method),
                                                                                              REFINE_OWN)


def _takers(option: str, world, names: Iterable[str]) -> list[str]:
    out = []
    for other in names:
        try:
            if option in planner_options(other, world):
                out.append(other)
        except (ImportError, KeyError, ParameterError):   # a planner missing here takes nothing
            continue
    return out


def check_plan_options(name: str, world, params: dict, planner_names: Iterable[str],
                       caller_params: Iterable[str] = ()) -> None:
    """Raise a ParameterError for a keyword the planner ``name`` does not take on ``world``
    (``caller_params``, the caller's own keywords, are only offered as spellings meant)."""
    accepted = planner_options(name, world, params.get("encoding"))
    unknown = sorted(set(params) - accepted)
    if not unknown:
        return
    names = list(planner_names)
    where = []
    from .refine import METHODS

    for opt in unknown:
        takers = _takers(opt, world, names)
        refiners = [m for m in METHODS if opt in refine_options(m)]
        if takers:
            shown = ", ".join(takers[:6]) + (f" and {len(takers) - 6} more" if len(takers) > 6 else "")
            where.append(f"{opt!r} is an option of {shown}")
        elif refiners:
            where.append(f"{opt!r} is a refinement option: pass it as refine_options={{{opt!r}: ...}} with "
                         f"refine={refiners[0]!r}")
        else:
            where.append(f"no planner takes {named_with_hints([opt], [*accepted, *caller_params])}")
    kind = planner_kind(name, world, params.get("encoding"))
    raise ParameterError(f"{name} ({kind} planner) has no option {', '.join(map(repr, unknown))}; "
                         f"{'; '.join(where)}. {name} takes: {', '.join(sorted(accepted)) or 'none'}")


def check_refine_options(method: str, options: dict) -> None:
    """Raise a ParameterError for a ``refine_options`` key that ``refine=method`` does not take."""
    accepted = refine_options(method)
    unknown = sorted(set(options) - accepted)
    if not unknown:
        return
    from .refine import METHODS

    hint = [f"{o!r} is an option of refine={other!r}" for other in METHODS if other != method
            for o in unknown if o in refine_options(other)]
    raise ParameterError(f"refine={method!r} has no option {named_with_hints(unknown, accepted)}"
                         f"{' (' + '; '.join(hint) + ')' if hint else ''}; its refine_options are: "
                         f"{', '.join(sorted(accepted))}")
