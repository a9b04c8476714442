"""Names of every registered solver and local planner (``op.algorithms()``)."""
from __future__ import annotations

import importlib

GRAPH_METHODS = ("astar", "dijkstra", "visibility")

# layer modules that expose ``algorithm_names()`` (imported by name so this foundation
# module imports no layer above it; a failing import is a real error and is raised)
_PROVIDERS = (
    "optplan.solvers.metaheuristics",
    "optplan.solvers.paths",
    "optplan.local",
)
# modules that say which names run on which world (``runs_on(name, world)``), by name as above
_WORLD_CHECKS = ("optplan.solvers.catalog",)


def algorithms(world=None) -> list[str]:
    """Sorted names usable as ``algorithm=`` (global planners) or ``local_planner=``; with a
    ``world``, only those that run on it (the grid-only planners, as each declares in
    :mod:`optplan.solvers.capabilities`, are left out for a circle world)."""
    names = set(GRAPH_METHODS)
    for mod in _PROVIDERS:
        names.update(importlib.import_module(mod).algorithm_names())
    if world is not None:
        checks = [importlib.import_module(mod).runs_on for mod in _WORLD_CHECKS]
        names = {n for n in names if all(check(n, world) for check in checks)}
    return sorted(names)
