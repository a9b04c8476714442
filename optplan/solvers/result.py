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
from ..results import PlanResult, defer_fields
from ..world.geometry import validate_path_segments
from ..world.metrics import TURN_TOL_DEG, min_clearance, path_length, path_metrics, turn_angles_deg


def make_plan_result(world, path, algorithm: str, runtime_s: float, *, clearance: float = 0.0,
                     history=None, seed=None, nfev: int = 0, message: str = "", refined: bool = False,
                     defer_clearance: bool = False, proven_free: bool = False) -> PlanResult:
    """Validate ``path`` exactly and package it with its metrics.

    An empty or invalid path yields ``feasible=False`` and a message that says why. The exact
    check's segment verdicts (without clearance) also serve the exact clearance metric, so
    the segment rule runs once. ``defer_clearance``: ``min_clearance`` (a distance query over
    every segment, most of the cost for graph search) and the turn metrics are computed on
    their first read (:func:`~optplan.results.defer_fields`), from a copy of the path: the same
    values. ``proven_free``: the caller has shown every point and segment free at clearance 0
    by the rule's own verdicts in cell units (graph search:
    :func:`~optplan.world.geometry.centre_moves_free` and ``in_free_cell``), so the rule is
    not run a second time.
    """
    P = np.asarray(path, dtype=float).reshape(-1, 2) if path is not None else np.zeros((0, 2))
    history = np.asarray(history if history is not None else [], float)
    if len(P) == 0:
        return PlanResult(algorithm, P, False, float("inf"), float("nan"), 0, float("nan"), runtime_s,
                          history, refined, seed, message or "no path found", nfev)
    if proven_free and float(clearance) == 0.0:
        ok, reason, seg_ok = True, "", np.ones(len(P) - 1, dtype=bool)
    else:
        check, seg_ok = validate_path_segments(world, P, clearance)
        ok, reason = bool(check), check.reason
    msg = message
    if not ok:
        msg = (msg + "; " if msg else "") + f"infeasible: {reason}"
    # a check with a clearance ran the rule at that clearance: the metric then runs its own pass
    free = seg_ok if seg_ok is not None and float(clearance) == 0.0 else None
    if defer_clearance:
        res = PlanResult(algorithm, P, ok, float(path_length(P)), 0.0, 0, float("nan"), runtime_s,
                         history, refined, seed, msg, nfev)
        kept = P.copy()   # the result's path may be edited in place before a value is read
        later = {"min_clearance": lambda: min_clearance(world, kept, free=free)}
        if len(P) > 2:
            turns = []    # turn_angles_deg once for both turn fields

            def angles():
                if not turns:
                    turns.append(turn_angles_deg(kept))
                return turns[0]

            later.update(turn_angle_deg=lambda: float(angles().sum(axis=-1)),
                         n_turns=lambda: int((angles() > TURN_TOL_DEG).sum(axis=-1)))
        return defer_fields(res, **later)
    m = path_metrics(None, P)   # everything but the clearance, which needs the world
    res = PlanResult(algorithm, P, ok, m.length, m.turn_angle_deg, m.n_turns, float("nan"), runtime_s,
                     history, refined, seed, msg, nfev)
    res.min_clearance = min_clearance(world, P, free=free)
    return res


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
