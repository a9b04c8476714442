"""One budget for every population loop (the engine, ACO, the path GAs).

A :class:`Budget` says when a loop stops and how far along it is, so that every loop
means the same thing by ``iters``, ``max_evals``, ``stagnation`` and ``target``
(termination as an object, in the manner of pymoo):

* ``iterations``: at most that many iterations (generations, colonies) after the
  initial population;
* ``evaluations``: at most that many objective evaluations (rows, paths, ant walks),
  exactly: a batch larger than what is left is cut (:meth:`Budget.allowed`) and the
  rows beyond it count as not evaluated;
* ``stagnation``: stop after that many iterations without a new best;
* ``target``: stop once the best feasible value is at or below it.

``progress(it, nfev)`` is the spent fraction ``t / T`` in [0, 1] that schedule-driven
rules (GWO's ``a``, PSO's inertia, ...) read; ``horizon(pop)`` is the ``T`` in
iterations they plan for.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..checks import integer, number
from ..errors import ParameterError


class BudgetExhausted(Exception):
    """Raised inside a step when no evaluations are left; the loop stops cleanly."""


@dataclass(frozen=True)
class Budget:
    """When a population loop stops; see the module docstring. At least one of
    ``iterations`` and ``evaluations`` must be given (an unbounded run never ends)."""

    iterations: int | None = None
    evaluations: int | None = None
    stagnation: int | None = None
    target: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "iterations", integer(0, optional=True)("iters", self.iterations))
        object.__setattr__(self, "evaluations", integer(1, optional=True)("max_evals", self.evaluations))
        object.__setattr__(self, "stagnation", integer(1, optional=True)("stagnation", self.stagnation))
        object.__setattr__(self, "target", number(optional=True)("target", self.target))
        if self.iterations is None and self.evaluations is None:
            raise ParameterError("give iters or max_evals (or both): an unbounded run never ends")

    def horizon(self, pop: int) -> int:
        """Iterations the schedule-driven rules plan for: ``iterations`` when given, else
        the iterations the evaluation budget affords at one evaluation per individual
        (after the initial population), at least 1."""
        if self.iterations is not None:
            return max(self.iterations, 1)
        return max(math.ceil(self.evaluations / pop) - 1, 1)

    def progress(self, it: int, nfev: int) -> float:
        """``t / T`` in [0, 1]: the larger spent fraction of iterations and evaluations."""
        if self.evaluations is None:
            return min(it / max(self.iterations, 1), 1.0)
        spent = nfev / self.evaluations
        if self.iterations is not None:
            spent = max(spent, it / max(self.iterations, 1))
        return float(min(max(spent, 0.0), 1.0))

    def evaluations_left(self, nfev: int) -> float:
        """Evaluations still allowed (``inf`` without an evaluation budget)."""
        return math.inf if self.evaluations is None else self.evaluations - nfev

    def allowed(self, n: int, nfev: int) -> int:
        """How many of ``n`` rows may still be evaluated; raises :class:`BudgetExhausted`
        when none may."""
        left = self.evaluations_left(nfev)
        if left <= 0:
            raise BudgetExhausted
        return n if n <= left else int(left)

    def spent(self, it: int, nfev: int) -> tuple[str, str] | None:
        """``(status, message)`` when the evaluation or iteration limit is reached after
        iteration ``it`` (the evaluation budget named first), else ``None``."""
        if self.evaluations is not None and nfev >= self.evaluations:
            return "max_evals", f"evaluation budget of {self.evaluations} spent"
        if self.iterations is not None and it >= self.iterations:
            return "max_iters", "iteration budget spent"
        return None

    def converged(self, since_improvement: int, best: float, best_feasible: bool = True) -> tuple[str, str] | None:
        """``(status, message)`` when the target is reached or the run stagnates, else ``None``.

        ``since_improvement``: iterations since the best last improved; ``best``: the best
        value so far; ``best_feasible``: whether that best satisfies the constraints.
        """
        if self.target is not None and best_feasible and best <= self.target:
            return "target", f"reached the target value {self.target:g}"
        if self.stagnation is not None and since_improvement >= self.stagnation:
            return "stagnation", f"no improvement in {self.stagnation} iterations"
        return None

    def stop(self, it: int, nfev: int, since_improvement: int = 0, best: float = math.inf,
             best_feasible: bool = True) -> tuple[str, str] | None:
        """:meth:`converged`, then :meth:`spent`: why the loop stops after iteration ``it``,
        or ``None`` to go on. Statuses: ``target``, ``stagnation``, ``max_evals``, ``max_iters``."""
        return self.converged(since_improvement, best, best_feasible) or self.spent(it, nfev)
