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


def algorithms() -> list[str]:
    """Sorted names usable as ``algorithm=`` (global planners) or ``local_planner=``."""
    names = set(GRAPH_METHODS)
    for mod in _PROVIDERS:
        names.update(importlib.import_module(mod).algorithm_names())
    return sorted(names)
