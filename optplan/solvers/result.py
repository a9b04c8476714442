"""Turning a solver's raw path into a checked :class:`PlanResult`.

Every planner ends here: the path is validated by the one exact rule
(``validate_path``) and its metrics are computed the same way for all. This
module imports only the world layer and the result types, so every solver
module can import it (the bands around paths that the refinement's multi-start
uses live with the tube, :mod:`optplan.solvers.tube`).
"""
from __future__ import annotations

import numpy as np

from ..checks import metres
from ..errors import ParameterError
from ..results import PlanResult
from ..world.geometry import validate_path
from ..world.metrics import path_metrics


def make_plan_result(world, path, algorithm: str, runtime_s: float, *, clearance: float = 0.0,
                     history=None, seed=None, nfev: int = 0, message: str = "", refined: bool = False) -> PlanResult:
    """Validate ``path`` exactly and package it with its metrics.

    An empty or invalid path yields ``feasible=False`` and a message that says why.
    """
    P = np.asarray(path, dtype=float).reshape(-1, 2) if path is not None else np.zeros((0, 2))
    if len(P) == 0:
        return PlanResult(algorithm, P, False, float("inf"), float("nan"), 0, float("nan"), runtime_s,
                          np.asarray(history if history is not None else [], float), refined, seed,
                          message or "no path found", nfev)
    check = validate_path(world, P, clearance)
    m = path_metrics(world, P)
    msg = message
    if not check:
        msg = (msg + "; " if msg else "") + f"infeasible: {check.reason}"
    return PlanResult(algorithm, P, bool(check), m.length, m.turn_angle_deg, m.n_turns, m.min_clearance, runtime_s,
                      np.asarray(history if history is not None else [], float), refined, seed, msg, nfev)


def check_optional_metres(value, name: str, meaning: str) -> float | None:
    """``value`` as a float (metres) or ``None`` (standing for ``meaning``); a ParameterError
    naming ``name`` otherwise (:func:`optplan.checks.metres`)."""
    return metres(name, value, none_means=meaning)


def check_alternatives(count, separation) -> tuple[int, float | None]:
    """``(count, separation)`` of a planner's ``alternatives`` request, checked: an
    integer >= 0 and ``None`` or a finite number >= 0 metres (ParameterError otherwise)."""
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 0:
        raise ParameterError(f"alternatives must be an integer >= 0 (how many other paths of the population "
                             f"to return), got {count!r}")
    return int(count), check_optional_metres(separation, "alternative_separation", "the default tube radius")
