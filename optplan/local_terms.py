"""Terms and constraints of window programs (``from optplan import local_terms as LT``).

Each is written once, with a batched numpy view (sampling) and a symbolic CasADi view
(``mpc``); see :mod:`optplan.formulations.local_program` and ``op.LocalProgram``.

Terms: :func:`goal_distance`, :func:`goal_heading`, :func:`path_distance`, :func:`speed`,
:func:`smoothness`, :func:`obstacle_cost`, :func:`stop_cost`, and your own :func:`custom` ``fn(Z, U, m)``.
Constraints: ``clearance() >= d``, :func:`can_stop` and :func:`stop_clear`.
"""
from __future__ import annotations

from .formulations.local_program import (
    can_stop,
    clearance,
    custom,
    default_local_program,
    goal_distance,
    goal_heading,
    obstacle_cost,
    path_distance,
    smoothness,
    speed,
    stop_clear,
    stop_cost,
)

__all__ = ["can_stop", "clearance", "custom", "default_local_program", "goal_distance", "goal_heading",
           "obstacle_cost", "path_distance", "smoothness", "speed", "stop_clear", "stop_cost"]
