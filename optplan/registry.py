"""Names of every registered solver and local planner (``op.algorithms()``)."""
from __future__ import annotations

import importlib

GRAPH_METHODS = ("astar", "dijkstra", "visibility")

# layer modules that expose ``algorithm_names()``; missing ones are skipped so a
# partial install (or a layer not built yet) still lists what exists
_PROVIDERS = (
    "optplan.solvers.metaheuristics",
    "optplan.solvers.paths",
    "optplan.local",
)


def algorithms() -> list[str]:
    """Sorted names usable as ``algorithm=`` (global planners) or ``local_planner=``."""
    names = set(GRAPH_METHODS)
    for mod in _PROVIDERS:
        try:
            m = importlib.import_module(mod)
        except ImportError:
            continue
        fn = getattr(m, "algorithm_names", None)  # a layer under construction may lack it
        if fn is not None:
            names.update(fn())
    return sorted(names)
