"""optplan: mobile-robot path planning as constrained programs.

The public API (see DESIGN.md) is re-exported here lazily, so ``import optplan``
stays fast and light layers do not pull in CasADi or OSQP.
"""
from __future__ import annotations

from .errors import (
    InfeasibleQueryError,
    MapFormatError,
    OptplanError,
    ParameterError,
    ScenarioError,
    UnknownAlgorithmError,
)
from .lazy import lazy_exports
from .results import OptimizeResult, PlanResult, ProgramResult, SimResult

__version__ = "0.1.0"

# the 'optplan' logger: silent unless the program (or the optplan command, -v / -q) sets it up
import logging as _logging

_logging.getLogger("optplan").addHandler(_logging.NullHandler())

# public name -> module that defines it
_LAZY = {
    "GridMap": "optplan.world.grid",
    "CircleWorld": "optplan.world.circles",
    "load_map": "optplan.world.loaders",
    "save_map": "optplan.world.loaders",
    "load_scen": "optplan.world.loaders",
    "validate_path": "optplan.world.geometry",
    "export_path": "optplan.world.export",
    "export_trajectory": "optplan.world.export",
    "path_metrics": "optplan.world.metrics",
    "shortest_path": "optplan.solvers.graph",
    "optimize": "optplan.solvers.metaheuristics",
    "plan": "optplan.planning",
    "algorithms": "optplan.registry",
    "RobotSpec": "optplan.world.robot",
    "Scenario": "optplan.world.scenario",
    "load_scenario": "optplan.world.scenario",
    "simulate": "optplan.sim",
    "PathProgram": "optplan.programs",
    "LocalProgram": "optplan.formulations.local_program",
    "local_program": "optplan.local",
    "Waypoints": "optplan.programs",
    "Points": "optplan.programs",
    "BSpline": "optplan.programs",
    "ColumnNodes": "optplan.programs",
    "CellSequence": "optplan.programs",
    "GeneralVias": "optplan.programs",
    "SplineThrough": "optplan.programs",
    "paper_program": "optplan.programs",
    "smoothing_program": "optplan.programs",
    "show_options": "optplan.programs",
    "compare": "optplan.bench.compare",
    "plot_map": "optplan.viz.api",
    "plot_paths": "optplan.viz.api",
    "plot_run": "optplan.viz.api",
}

__getattr__, __dir__, __all__ = lazy_exports("optplan", _LAZY, globals(), eager=[
    "OptplanError", "MapFormatError", "InfeasibleQueryError", "UnknownAlgorithmError",
    "ParameterError", "ScenarioError", "OptimizeResult", "PlanResult", "ProgramResult", "SimResult",
])
