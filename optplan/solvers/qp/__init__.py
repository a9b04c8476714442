"""Convex (QP) refinement: the corridor smoother, solved with OSQP or cvxpy.

``smooth_path_qp`` is what ``op.plan(..., refine="qp")`` runs; ``build_corridor``
and ``corridor_program`` expose the safe corridor and the QP for reuse.
"""
from .corridor import Corridor, build_corridor
from .program import CvxpyCorridorQP, OsqpCorridorQP, QPSolution, corridor_program, objective_value
from .smoothing import smooth_path_qp

__all__ = ["Corridor", "CvxpyCorridorQP", "OsqpCorridorQP", "QPSolution", "build_corridor", "corridor_program",
           "objective_value", "smooth_path_qp"]
