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
from .engine import Algorithm, Problem, pooled_archive, real_values, run, run_batched

# registry: name -> class (filled from the family modules)
ALGORITHMS: dict[str, type[Algorithm]] = {}


def register(cls: type[Algorithm]) -> type[Algorithm]:
    """Class decorator: make an :class:`Algorithm` subclass available by its ``name``."""
    ALGORITHMS[cls.name] = cls
    return cls


def _load_families() -> None:
    from . import bat, dbo, ga, gwo, gwo_variants, pso, pso_variants, random_search, ssa, woa_aro

    for mod in (random_search, gwo, gwo_variants, pso, pso_variants, ssa, bat, woa_aro, dbo, ga):
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


BOUNDS_FORMS = ("a (d, 2) array or list of (lower, upper) rows, scipy.optimize.Bounds(lb, ub), "
                "a tuple (lb, ub) of two length-d arrays (d != 2), or one (lower, upper) pair with dim=d")


def _bounds(bounds, dim: int | None) -> tuple[np.ndarray, np.ndarray]:
    """``(lower, upper)`` arrays from any of :data:`BOUNDS_FORMS`."""
    if hasattr(bounds, "lb") and hasattr(bounds, "ub"):          # scipy.optimize.Bounds
        lb = float_array("bounds.lb", bounds.lb).reshape(-1)
        ub = float_array("bounds.ub", bounds.ub).reshape(-1)
        if lb.size == 1 and dim is not None:
            lb, ub = np.full(dim, lb[0]), np.full(dim, ub[0])
        if lb.shape != ub.shape:
            raise ParameterError(f"bounds.lb and bounds.ub differ in length: {lb.size} and {ub.size}")
        b = np.stack([lb, ub], axis=1)
    else:
        b = float_array("bounds", bounds, BOUNDS_FORMS)
        if isinstance(bounds, tuple) and b.ndim == 2 and b.shape[0] == 2 and b.shape[1] != 2:
            b = b.T                                              # (lb, ub), as scipy's least_squares takes
    if b.ndim == 1 and b.size == 2 and dim is not None:
        b = np.tile(b, (dim, 1))
    if b.ndim != 2 or b.shape[1] != 2 or b.shape[0] == 0:
        raise ParameterError(f"bounds must be {BOUNDS_FORMS}; got shape {b.shape}")
    if dim is not None and b.shape[0] != dim:
        raise ParameterError(f"bounds have {b.shape[0]} rows but dim={dim}")
    lo, hi = b[:, 0].copy(), b[:, 1].copy()
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        raise ParameterError("bounds must be finite numbers (a metaheuristic samples the whole box)")
    if np.any(lo >= hi):
        j = int(np.argmax(lo >= hi))
        raise ParameterError(f"lower bound must be below upper bound; dimension {j} has {lo[j]} >= {hi[j]}")
    with np.errstate(over="ignore"):
        span = hi - lo
    if not np.all(np.isfinite(span)) or np.any(np.abs(lo) > 1e300) or np.any(np.abs(hi) > 1e300):
        j = int(np.argmax(~np.isfinite(span) | (np.abs(lo) > 1e300) | (np.abs(hi) > 1e300)))
        raise ParameterError(f"bounds of dimension {j}, [{lo[j]:g}, {hi[j]:g}], are too wide for float64 "
                             "arithmetic (their span overflows); scale the variable")
    return lo, hi


class _Vectorised:
    """The objective as a batched call: ``f`` itself when it is batched (``f(X)`` of ``(n, d)``
    rows gives ``(n,)`` values), or a per-row loop around it when it takes one point of
    shape ``(d,)`` and returns one number, as scipy.optimize's objectives do (slower: one
    Python call per row). Told apart on the first batch the run evaluates, so no call is
    made that the run does not count; only when the batch is square (``n == d``, where a
    function of one point indexing ``x[0]`` gets a row of the right length) is its first
    row also evaluated alone to check."""

    def __init__(self, f: Callable) -> None:
        self.f, self.mode = f, None

    def __call__(self, X: np.ndarray):
        if self.mode == "batched":
            return self.f(X)
        if self.mode == "rows":
            return self._rows(X)
        try:
            out, error = self.f(X), None
        except Exception as exc:  # noqa: BLE001 - a function of one point may fail on rows
            out, error = None, exc
        if error is None and (isinstance(out, tuple) or (np.shape(out) in ((len(X),), (len(X), 1))
                                                         and self._consistent(X, out))):
            self.mode = "batched"
            return out
        if error is None:
            real_values(out, "values")      # strings or objects: say so, whatever the shape
        try:
            rows = self._rows(X)
        except Exception:  # noqa: BLE001 - neither reading works: report the batched call's problem
            if error is not None:
                raise error
            self.mode = "batched"
            return out                       # the shape check then names what came back
        self.mode = "rows"
        return rows

    def _consistent(self, X: np.ndarray, out) -> bool:
        if X.ndim != 2 or X.shape[0] != X.shape[1] or len(X) < 2:
            return True
        try:
            alone = np.asarray(self.f(X[:1].copy()))
        except Exception:  # noqa: BLE001
            return False
        return alone.size == 1 and bool(np.allclose(np.asarray(out).reshape(-1)[:1].astype(complex),
                                                    alone.reshape(-1).astype(complex), equal_nan=True))

    def _rows(self, X: np.ndarray):
        values = [self.f(x) for x in X]
        if values and isinstance(values[0], tuple):
            return np.array([v[0] for v in values]), np.array([v[1] for v in values])
        out = [np.asarray(v) for v in values]
        if any(v.size != 1 for v in out):
            bad = next(v for v in out if v.size != 1)
            raise ParameterError(f"the objective returned shape {bad.shape} for one point of shape ({X.shape[1]},); "
                                 "return one number per point, or (n,) values for (n, d) rows")
        return np.array([v.reshape(()) for v in out]) if out else np.zeros(0)


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
        if not np.all(np.isfinite(init)):
            raise ParameterError("init holds NaN or infinite values; give finite points inside the bounds")
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
    f = _Vectorised(f)
    if seeds is not None:
        return _optimize_seeds(cls, f, lo, hi, pop, budget, seeds, init=init, repair=repair, callback=callback,
                               progress=progress, archive_every=archive_every, params=params)
    algo = cls(**params)
    t0 = time.perf_counter()
    state, hist, hist_nfev, status, message, nit = run(
        algo, Problem(f, lo, hi, repair), pop=pop, seed=seed, init=init, callback=callback, progress=progress,
        archive_every=archive_every, budget=budget)
    best_f, best_v = float(state.best_f), float(state.best_v)
    return OptimizeResult(
        x=state.best_x, f=best_f, history=hist, history_nfev=hist_nfev, nfev=state.nfev, nit=nit,
        runtime_s=time.perf_counter() - t0, status=status, message=message + _no_answer(best_f, best_v),
        algorithm=cls.name, seed=int(seed) if isinstance(seed, (int, np.integer)) else None,
        archive=pooled_archive(state.snapshots) if archive_every else None, success=_success(best_f, best_v))


def _success(best_f: float, best_v: float) -> bool:
    return bool(np.isfinite(best_f) and best_v == 0)


def _no_answer(best_f: float, best_v: float) -> str:
    """What a run without an answer adds to its message (nothing for one with an answer)."""
    if not np.isfinite(best_f):
        return "; no point gave a finite objective value (every value was NaN or infinite): the run has no answer"
    return ""


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
            note += "; the objective returned NaN or -inf for some points (treated as +inf)"
        best_f, best_v = float(state.best_f[r]), float(state.best_v[r])
        if best_v > 0 and np.isfinite(best_v):
            note += f"; no feasible point found (least violation {best_v:.3g})"
        results.append(OptimizeResult(
            x=state.best_x[r].copy(), f=best_f, history=hist[:, r].copy(), history_nfev=hist_nfev.copy(),
            nfev=state.nfev, nit=nit, runtime_s=runtime, status=status, message=note + _no_answer(best_f, best_v),
            algorithm=cls.name, seed=int(s) if isinstance(s, (int, np.integer)) else None, archive=None,
            success=_success(best_f, best_v)))
    return results
