"""The built-in program solvers, registered by name on import.

Every registered metaheuristic (``ssa``, ``missa``, ``pso``, ``gwo``, ``msiar-gwo``, ...),
``ipopt``, ``slsqp``, ``osqp``, ``cvxpy``, and chains of them (a list of names).
A new solver is one :class:`~optplan.formulations.program.ProgramSolver` subclass
and one :func:`~optplan.formulations.program.register_solver` call.
"""
from __future__ import annotations

from functools import partial

from ...formulations.program import SOLVERS, get_solver, register_solver, solver_names
from ..metaheuristics import algorithm_names
from .chain import ChainSolver
from .gradient import IpoptSolver, SlsqpSolver
from .quadratic import CvxpySolver, OsqpSolver
from .swarm import SwarmSolver

for _name in algorithm_names():
    register_solver(_name, partial(SwarmSolver, _name))
for _cls in (IpoptSolver, SlsqpSolver, OsqpSolver, CvxpySolver):
    register_solver(_cls.name, _cls)
register_solver("chain", ChainSolver)


def show_options(solver) -> str:
    """The options of a program solver (name, default, meaning), one per line."""
    return get_solver(solver).show_options()


__all__ = ["SOLVERS", "get_solver", "solver_names", "show_options", "SwarmSolver", "IpoptSolver", "SlsqpSolver",
           "OsqpSolver", "CvxpySolver", "ChainSolver"]
