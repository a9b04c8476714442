"""Terms of path programs (``from optplan import terms as T``).

Each term is written once and has a batched numpy view (swarms, reports) and a
symbolic CasADi view (IPOPT, SLSQP); see :mod:`optplan.formulations.expressions`.

Scalar terms: :func:`length`, :func:`squared_length` (quadratic), :func:`bending`
(quadratic), :func:`turn_count` and :func:`turn_cost` (no smooth form: gradient
solvers use a documented surrogate), :func:`start_heading`, :func:`goal_heading`.
Vector terms (reduce with ``.sum()``, ``.sumsq()``, ``.max()``, or compare
element-wise): :func:`turn_angles`, :func:`segment_lengths`, :func:`curvature`,
:func:`clearance`. Your own: :func:`custom`.
"""
from __future__ import annotations

from .formulations.expressions import (
    Constraint,
    Expr,
    bending,
    clearance,
    curvature,
    custom,
    goal_heading,
    length,
    segment_lengths,
    squared_length,
    start_heading,
    turn_angles,
    turn_cost,
    turn_count,
)

__all__ = ["Constraint", "Expr", "bending", "clearance", "curvature", "custom", "goal_heading", "length",
           "segment_lengths", "squared_length", "start_heading", "turn_angles", "turn_cost", "turn_count"]
