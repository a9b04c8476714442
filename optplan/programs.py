"""Programs with the built-in solvers registered (``op.PathProgram`` and friends).

The model lives in :mod:`optplan.formulations.program`, the solvers in
:mod:`optplan.solvers.programs`; importing this module joins them, so
``op.PathProgram(...).solve("ipopt")`` finds every built-in solver.
"""
from __future__ import annotations

from .formulations.paper_programs import fitness_expression, paper_program, smoothing_program
from .formulations.program import PathProgram, ProgramSolver, register_solver
from .formulations.variables import (BSpline, CellSequence, ColumnNodes, GeneralVias, Points, SplineThrough, Variables,
                                      Waypoints)
from .solvers.programs import get_solver, show_options, solver_names

__all__ = ["PathProgram", "ProgramSolver", "register_solver", "Variables", "Waypoints", "Points", "BSpline",
           "ColumnNodes", "CellSequence", "GeneralVias", "SplineThrough", "paper_program", "smoothing_program", "fitness_expression", "get_solver",
           "show_options", "solver_names"]
