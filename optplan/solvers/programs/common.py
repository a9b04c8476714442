"""Pieces every program solver shares: start vectors, result assembly, the ranking rule."""
from __future__ import annotations

import time

import numpy as np

from ...checks import anything
from ...errors import ParameterError
from ...formulations.program import Option
from ...results import ProgramResult

INIT_OPTION = Option(None, anything, "a start: a ProgramResult, an (N, 2) path or a decision vector")


def start_vector(program, variables, init) -> np.ndarray | None:
    """The decision vector of ``variables`` that a start ``init`` stands for (``None``: none given).

    A result of the same program with the same variables hands over its ``x``
    exactly; any other result or path is fitted (``variables.from_path``)."""
    if init is None:
        return None
    if isinstance(init, ProgramResult):
        x = np.asarray(init.x, float).reshape(-1)
        if init.variables == variables.name and x.size == variables.dim:
            return np.clip(x, variables.lower, variables.upper)
        return variables.from_path(np.asarray(init.path, float))
    a = np.asarray(init, dtype=float)
    if a.ndim == 1 and a.size == variables.dim:
        return np.clip(a, variables.lower, variables.upper)
    if a.ndim == 2 and a.shape[1] == 2 and len(a) >= 2:
        return variables.from_path(a)
    raise ParameterError(f"init must be a ProgramResult, an (N, 2) path or a vector of {variables.dim} numbers, "
                         f"got an array of shape {a.shape}")


def straight_start(program, variables) -> np.ndarray:
    """The variables' fit of the straight start-goal segment (a deterministic default start)."""
    return variables.from_path(np.stack([program.start, program.goal]))


def result_of(program, variables, x, solver: str, status: str, message: str, nfev: int, t0: float,
              seed=None, history=None, notes=()) -> ProgramResult:
    """Decode ``x``, judge the path by the program, and say what failed when it is infeasible."""
    x = np.asarray(x, float).reshape(-1)
    path = variables.decode(x[None])[0]
    cost, viol, feasible = program.judge(path)
    words = [m for m in (message, *notes) if m]
    if not feasible:
        bad = [f"{k} (violation {v:.3g})" for k, v in viol.items() if v > 0]
        words.append("infeasible: " + (", ".join(bad) if bad else "the exact collision test rejects the path"))
    return ProgramResult(solver=solver, cost=cost, feasible=feasible, path=path, x=x, violations=viol,
                         status=status, message="; ".join(words), nfev=int(nfev),
                         runtime_s=time.perf_counter() - t0,
                         seed=int(seed) if isinstance(seed, (int, np.integer)) and not isinstance(seed, bool) else None,
                         history=np.asarray(history if history is not None else np.zeros(0), float),
                         variables=variables.name)


def total_violation(r: ProgramResult) -> float:
    """Sum of a result's constraint violations (0 when every constraint holds)."""
    return float(sum(r.violations.values())) if r.violations else 0.0


def better(a: ProgramResult, b: ProgramResult) -> bool:
    """Is ``a`` strictly better than ``b``: feasible first, then less violation, then lower cost."""
    ka = (not a.feasible, total_violation(a), a.cost)
    kb = (not b.feasible, total_violation(b), b.cost)
    return ka < kb
