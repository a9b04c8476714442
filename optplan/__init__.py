"""optplan: mobile-robot path planning as constrained programs.

The public API (see DESIGN.md) is re-exported here lazily, so ``import optplan``
stays fast and light layers do not pull in CasADi or OSQP.
"""
from __future__ import annotations

import importlib
from typing import Any

from .errors import (
    InfeasibleQueryError,
    MapFormatError,
    OptplanError,
    ParameterError,
    ScenarioError,
    UnknownAlgorithmError,
)
from .results import OptimizeResult, PlanResult, SimResult

__version__ = "0.1.0"

# public name -> module that defines it
_LAZY = {
    "GridMap": "optplan.world.grid",
    "CircleWorld": "optplan.world.circles",
    "load_map": "optplan.world.loaders",
    "save_map": "optplan.world.loaders",
    "load_scen": "optplan.world.loaders",
    "validate_path": "optplan.world.geometry",
    "path_metrics": "optplan.world.metrics",
    "shortest_path": "optplan.solvers.graph",
    "optimize": "optplan.solvers.metaheuristics",
    "plan": "optplan.planning",
    "algorithms": "optplan.registry",
    "RobotSpec": "optplan.world.robot",
    "Scenario": "optplan.world.scenario",
    "load_scenario": "optplan.world.scenario",
    "simulate": "optplan.sim",
}

__all__ = sorted(
    list(_LAZY)
    + [
        "OptplanError", "MapFormatError", "InfeasibleQueryError", "UnknownAlgorithmError",
        "ParameterError", "ScenarioError", "OptimizeResult", "PlanResult", "SimResult",
    ]
)


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'optplan' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return __all__
