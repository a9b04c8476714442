"""Swarm metaheuristics, one module per family, basic and improved variants side by side.

``optimize(f, bounds, algorithm=..., pop=..., iters=..., max_evals=..., seed=...)``
works on any batched objective ``f(X: (n, d)) -> (n,)`` (or ``(f, violation)``);
path formulations are solved through the same call.
"""
from __future__ import annotations

import inspect
import time
from typing import Callable

import numpy as np

from ...checks import float_array, function, integer
from ...checks import seed as checked_seed
from ...errors import ParameterError, UnknownAlgorithmError
from ...results import OptimizeResult
from ..budget import Budget
from .engine import Algorithm, Problem, pooled_archive, run, run_batched

# registry: name -> class (filled from the family modules)
ALGORITHMS: dict[str, type[Algorithm]] = {}


def register(cls: type[Algorithm]) -> type[Algorithm]:
    """Class decorator: make an :class:`Algorithm` subclass available by its ``name``."""
    ALGORITHMS[cls.name] = cls
    return cls


def _load_families() -> None:
    from . import bat, dbo, ga, gwo, pso, random_search, ssa, woa_aro

    for mod in (random_search, gwo, pso, ssa, bat, woa_aro, dbo, ga):
        for obj in vars(mod).values():
            if isinstance(obj, type) and issubclass(obj, Algorithm) and obj is not Algorithm \
                    and obj.__module__ == mod.__name__:
                register(obj)


_load_families()


def algorithm_names() -> list[str]:
    """Registered metaheuristic names."""
    return sorted(ALGORITHMS)


def get_algorithm(name: str) -> type[Algorithm]:
    """The algorithm class for ``name`` (case-insensitive)."""
    try:
        return ALGORITHMS[str(name).lower()]
    except KeyError:
        raise UnknownAlgorithmError(f"unknown algorithm {name!r}; known: {', '.join(algorithm_names())}") from None


def _positive_int(name: str, value, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ParameterError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def _bounds(bounds, dim: int | None) -> tuple[np.ndarray, np.ndarray]:
    b = float_array("bounds", bounds, "a (d, 2) array of (lower, upper) rows")
    if b.ndim == 1 and b.size == 2 and dim is not None:
        b = np.tile(b, (dim, 1))
    if b.ndim != 2 or b.shape[1] != 2 or b.shape[0] == 0:
        raise ParameterError(f"bounds must be a (d, 2) array of (lower, upper) rows, got shape {b.shape}")
    lo, hi = b[:, 0].copy(), b[:, 1].copy()
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        raise ParameterError("bounds must be finite numbers")
    if np.any(lo >= hi):
        j = int(np.argmax(lo >= hi))
        raise ParameterError(f"lower bound must be below upper bound; dimension {j} has {lo[j]} >= {hi[j]}")
    return lo, hi


def optimize(f: Callable, bounds, algorithm: str = "gwo", pop: int = 30, iters: int | None = 500,
             max_evals: int | None = None, seed=0, *, dim: int | None = None, init=None, repair=None,
             callback=None, progress: bool = False, stagnation: int | None = None, target: float | None = None,
             archive_every: int | None = None, budget: Budget | None = None, seeds=None,
             **params) -> OptimizeResult | list[OptimizeResult]:
    """Minimise a batched objective with a registered metaheuristic.

    With ``seeds`` (e.g. ``seeds=range(20)``) it makes one independent run per seed and
    returns a list of results, in seed order, each equal to ``optimize(..., seed=s)``
    number for number. Algorithms that declare ``BATCHABLE`` (``gwo``, ``pso``) run all
    seeds as one vectorised population of ``R x pop`` rows, so ``f`` sees ``R * pop``
    rows per call; the others (and runs with a callback, progress output, an archive,
    a stagnation or a target stop, or one Generator given twice) run the seeds one
    after the other. A batched
    result's ``runtime_s`` is the batch's wall time divided by ``R``.

    Args:
        f: ``f(X)`` for ``X`` of shape ``(n, d)`` returning ``(n,)`` values, or a tuple
            ``(values, violations)`` to rank by the feasibility rule.
        bounds: ``(d, 2)`` rows of (lower, upper); or one ``(lower, upper)`` pair with ``dim``.
        algorithm: a name from :func:`algorithm_names`.
        pop: population size.
        iters: iteration budget (``None``: only ``max_evals`` limits the run).
        max_evals: evaluation budget (rows passed to ``f``); the run stops exactly there.
        seed: int or ``numpy.random.Generator``; the same seed gives the same result.
        init: initial population ``(pop, d)`` or a callable ``(n, rng) -> X``.
        repair: callable applied to every population before evaluation.
        callback: ``callback(state)`` after each iteration; return ``False`` to stop.
        progress: print progress to stderr.
        stagnation: stop after this many iterations without improvement.
        target: stop once the best feasible value is ``<= target``.
        archive_every: keep the population every that many iterations (and the initial
            and final ones) and return their distinct points in ``result.archive``
            (best first); ``None`` (default) keeps nothing. Costs no evaluations.
        budget: a :class:`~optplan.solvers.budget.Budget` instead of ``iters``,
            ``max_evals``, ``stagnation`` and ``target`` (leave those at their defaults).
        seeds: an iterable of seeds for independent runs (then ``seed`` is not used);
            returns a list of results.
        **params: the algorithm's own parameters (see its class for defaults).
    """
    cls = get_algorithm(algorithm)
    cls.check_params(params, _OPTIMIZE_KEYWORDS)
    function()("f", f)
    repair, callback = function(optional=True)("repair", repair), function(optional=True)("callback", callback)
    if init is not None and not callable(init):
        init = float_array("init", init, "an initial population (pop, d) of numbers or a function (n, rng) -> X")
    pop = _positive_int("pop", pop, max(cls.min_pop, 1))
    if budget is None:
        budget = Budget(iterations=iters, evaluations=max_evals, stagnation=stagnation, target=target)
    elif not isinstance(budget, Budget):
        raise ParameterError(f"budget must be an optplan Budget, got {type(budget).__name__}")
    elif max_evals is not None or stagnation is not None or target is not None or iters not in (None, 500):
        raise ParameterError("give either budget=Budget(...) or iters/max_evals/stagnation/target, not both")
    if archive_every is not None:
        archive_every = _positive_int("archive_every", archive_every, 1)
    lo, hi = _bounds(bounds, integer(1, optional=True)("dim", dim))
    if seeds is not None:
        return _optimize_seeds(cls, f, lo, hi, pop, budget, seeds, init=init, repair=repair, callback=callback,
                               progress=progress, archive_every=archive_every, params=params)
    algo = cls(**params)
    t0 = time.perf_counter()
    state, hist, hist_nfev, status, message, nit = run(
        algo, Problem(f, lo, hi, repair), pop=pop, seed=seed, init=init, callback=callback, progress=progress,
        archive_every=archive_every, budget=budget)
    return OptimizeResult(
        x=state.best_x, f=float(state.best_f), history=hist, history_nfev=hist_nfev, nfev=state.nfev, nit=nit,
        runtime_s=time.perf_counter() - t0, status=status, message=message, algorithm=cls.name,
        seed=int(seed) if isinstance(seed, (int, np.integer)) else None,
        archive=pooled_archive(state.snapshots) if archive_every else None)


# optimize's own keywords: offered as the spelling meant when an algorithm parameter is unknown
_OPTIMIZE_KEYWORDS = tuple(inspect.signature(optimize).parameters)[:-1]


def _optimize_seeds(cls, f, lo, hi, pop, budget, seeds, *, init, repair, callback, progress, archive_every,
                    params) -> list[OptimizeResult]:
    """``optimize(..., seeds=...)``: one result per seed, batched when the algorithm allows."""
    if isinstance(seeds, (int, np.integer, np.random.Generator)) or not hasattr(seeds, "__iter__"):
        raise ParameterError(f"seeds must be an iterable of seeds such as range(20), got {seeds!r}")
    seeds = [checked_seed("seeds", s) for s in seeds]
    if not seeds:
        raise ParameterError("seeds is empty; give at least one seed")
    per_run_control = (callback is not None or progress or archive_every is not None
                       or budget.stagnation is not None or budget.target is not None)
    # one Generator given twice is one stream: separate runs take it in turn, run after run
    shared = [s for s in seeds if isinstance(s, np.random.Generator)]
    shared_stream = len({id(g) for g in shared}) < len(shared)
    if not cls.batchable() or per_run_control or shared_stream:
        bounds = np.stack([lo, hi], axis=1)
        return [optimize(f, bounds, algorithm=cls.name, pop=pop, iters=None, seed=s, init=init, repair=repair,
                         callback=callback, progress=progress, archive_every=archive_every, budget=budget,
                         **params) for s in seeds]
    t0 = time.perf_counter()
    state, hist, hist_nfev, status, message, nit = run_batched(
        cls(**params), Problem(f, lo, hi, repair), pop=pop, seeds=seeds, budget=budget, init=init)
    runtime = (time.perf_counter() - t0) / len(seeds)
    results = []
    for r, s in enumerate(seeds):
        note = message
        if state.nan_seen[r]:
            note += "; the objective returned NaN for some points (treated as +inf)"
        if state.best_v[r] > 0 and np.isfinite(state.best_v[r]):
            note += f"; no feasible point found (least violation {state.best_v[r]:.3g})"
        results.append(OptimizeResult(
            x=state.best_x[r].copy(), f=float(state.best_f[r]), history=hist[:, r].copy(), history_nfev=hist_nfev.copy(),
            nfev=state.nfev, nit=nit, runtime_s=runtime, status=status, message=note, algorithm=cls.name,
            seed=int(s) if isinstance(s, (int, np.integer)) else None, archive=None))
    return results
