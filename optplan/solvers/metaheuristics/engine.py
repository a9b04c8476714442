"""The one population loop shared by every metaheuristic.

An algorithm is a class with small named update rules; the engine owns
everything else: the budget (iterations and/or function evaluations), bounds,
the ranking rule, the best-so-far record, the history, stagnation and target
stops, callbacks, progress output and the random generator. That keeps every
algorithm module down to what its paper says.

Problems. ``optimize`` takes a batched objective ``f(X) -> (n,)``. It may also
return ``(f, violation)``; then individuals are ranked by the feasibility rule
(feasible beats infeasible, then lower violation, then lower ``f``), which is
what path formulations in feasibility mode use. A caller can pass an initial
population (``init=array``) or an initialiser (``init=callable(n, rng) -> X``),
and a ``repair`` hook applied to every population before it is evaluated (for
discrete encodings). Bounds are enforced by clipping.

Budgets. ``nfev`` counts rows passed to ``f``. The run obeys one
:class:`~optplan.solvers.budget.Budget` (iterations, evaluations, stagnation,
target), the same object ACO and the path GAs obey. With an evaluation budget the
run stops exactly when it is spent: a batch larger than what is left is cut, and
the rows that could not be evaluated are treated as infinitely bad.

Archive. With ``archive_every=k`` the engine keeps a copy of the population
(with its values) after the initial evaluation, every ``k`` iterations and at
the end (:attr:`State.snapshots`); :func:`pooled_archive` merges them into the
distinct points the run held, best first. Nothing extra is evaluated: a caller
(the path planners' multi-start refinement) uses them to look beyond the single
best point.
"""
from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ...errors import ParameterError, named_with_hints
from ...rng import as_generator
from ..budget import Budget, BudgetExhausted

__all__ = ["Algorithm", "Budget", "BudgetExhausted", "Problem", "State", "better", "pooled_archive", "rank", "run"]


@dataclass
class Problem:
    """A batched objective with box bounds."""

    f: Callable
    lower: np.ndarray
    upper: np.ndarray
    repair: Callable | None = None

    @property
    def dim(self) -> int:
        return int(self.lower.size)

    @property
    def span(self) -> np.ndarray:
        return self.upper - self.lower


def real_values(out, what: str) -> np.ndarray:
    """What the objective returned as a float array, or a ParameterError that says why not
    (complex values would lose their imaginary part, strings or objects are no values)."""
    a = out if isinstance(out, np.ndarray) else np.asarray(out)
    if a.dtype.kind in "biuf":
        return a.astype(float, copy=False)
    if a.dtype.kind == "c":
        raise ParameterError(f"the objective returned complex {what}; return real numbers (e.g. abs(z) or z.real)")
    try:
        return a.astype(float)
    except (TypeError, ValueError):
        raise ParameterError(f"the objective must return numbers, got {what} of type {a.dtype} "
                             f"({np.ravel(a)[:1].tolist()!r:.60})") from None


def objective_values(out, k: int) -> tuple[np.ndarray, np.ndarray]:
    """``(f, violation)``, shape ``(k,)`` each, from what ``f(X)`` returned for ``k`` rows:
    values, or a tuple ``(values, violations)``. A NaN violation counts as infinite."""
    if isinstance(out, tuple):
        fk = real_values(out[0], "values").reshape(-1)
        vk = real_values(out[1], "violations").reshape(-1)
        if math.isnan(np.add.reduce(vk)):          # one reduction instead of a mask on every call
            vk = np.where(np.isnan(vk), np.inf, vk)
    else:
        fk, vk = real_values(out, "values").reshape(-1), np.zeros(k)
    if fk.shape != (k,) or vk.shape != (k,):
        raise ParameterError(f"the objective must return shape ({k},) for {k} rows, got {fk.shape}")
    return fk, vk


def better(f1, v1, f2, v2) -> np.ndarray:
    """Feasibility rule: is (f1, v1) strictly better than (f2, v2)? (``v == 0`` is feasible)."""
    return (v1 < v2) | ((v1 == v2) & (f1 < f2))


def rank(f: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Indices from best to worst under the feasibility rule (stable); along the last
    axis, so ``(R, n)`` values of a batched run give one ranking per run."""
    return np.lexsort((f, v))


def pick(A: np.ndarray, order: np.ndarray) -> np.ndarray:
    """Rows ``order`` of a population array: ``A[order]`` for one run; for a batched run
    (``order`` of shape ``(R, k)``) the rows of each run's own ``order``."""
    if order.ndim == 1:
        return A[order]
    # plain fancy indexing: take_along_axis costs more in Python than the copy at these sizes
    return A[np.arange(len(order))[:, None], order]


def pooled_archive(snapshots) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The distinct rows of population snapshots ``[(X, f, v), ...]``, best first.

    Returns ``(X, f, v)`` with every row of ``X`` once (its first occurrence), ordered
    by the feasibility rule (:func:`rank`). Empty arrays when there is no snapshot.
    """
    snaps = [s for s in snapshots if len(s[0])]
    if not snaps:
        return np.empty((0, 0)), np.empty(0), np.empty(0)
    X = np.vstack([s[0] for s in snaps])
    f = np.concatenate([np.asarray(s[1], float) for s in snaps])
    v = np.concatenate([np.asarray(s[2], float) for s in snaps])
    _, first = np.unique(X, axis=0, return_index=True)
    first = np.sort(first)
    order = first[rank(f[first], v[first])]
    return X[order], f[order], v[order]


class State:
    """Everything a step may read or change. Algorithms keep their own memory
    (velocities, personal bests, loudness, ...) as attributes of their instance."""

    def __init__(self, problem: Problem, pop: int, iters: int | None, max_evals: int | None,
                 rng: np.random.Generator, budget: Budget | None = None):
        self.problem = problem
        self.pop = pop
        self.budget = budget if budget is not None else Budget(iterations=iters, evaluations=max_evals)
        self.iters = self.budget.iterations
        self.max_evals = self.budget.evaluations
        self.rng = rng
        self.lower, self.upper = problem.lower, problem.upper
        self.dim = problem.dim
        self.nfev = 0
        self.it = 0
        self.nan_seen = False
        self.X = np.empty((0, self.dim))
        self.F = np.empty(0)
        self.V = np.empty(0)
        self.best_x = np.full(self.dim, np.nan)
        self.best_f = np.inf
        self.best_v = np.inf
        self.snapshots: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []  # see run(archive_every=...)
        self._work: dict[str, np.ndarray] = {}

    def work(self, name: str, shape: tuple[int, ...]) -> np.ndarray:
        """A work array of ``shape`` kept for the whole run under ``name`` (contents undefined).

        Rules that rebuild a large temporary every iteration write into it instead: a
        fresh array of a batched run's size (hundreds of kB) is handed back to the
        system when freed, and touching its new pages again costs more than the
        arithmetic. Whatever is written there is overwritten by the next use."""
        buf = self._work.get(name)
        if buf is None or buf.shape != shape:
            buf = self._work[name] = np.empty(shape)
        return buf

    def snapshot(self) -> None:
        """Keep a copy of the current population and its values (the archive)."""
        self.snapshots.append((self.X.copy(), self.F.copy(), self.V.copy()))

    # ------------------------------------------------------------ budget
    @property
    def horizon(self) -> int:
        """Iterations the schedule-driven rules (a(t), w(t), ...) plan for (:meth:`Budget.horizon`)."""
        return self.budget.horizon(self.pop)

    @property
    def progress(self) -> float:
        """``t / T`` in [0, 1]: the fraction of the budget spent (:meth:`Budget.progress`)."""
        return self.budget.progress(self.it, self.nfev)

    @property
    def evals_left(self) -> float:
        """Evaluations still allowed (``inf`` without an evaluation budget)."""
        return self.budget.evaluations_left(self.nfev)

    # -------------------------------------------------------- evaluation
    def clip(self, X: np.ndarray) -> np.ndarray:
        # two ufuncs: np.clip's Python dispatch costs more than the work at these sizes
        return np.minimum(np.maximum(X, self.lower), self.upper)

    def evaluate(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Evaluate a batch (clipped and repaired first); returns ``(f, violation)``.

        Raises :class:`BudgetExhausted` when no evaluation is left at all.
        """
        n = len(X)
        k = self.budget.allowed(n, self.nfev)
        Xk = X if k == n else X[:k]
        fk, vk = objective_values(self.problem.f(Xk), k)
        if not math.isfinite(np.add.reduce(fk)) and not np.isfinite(fk).all():
            self.nan_seen |= bool(np.isnan(fk).any() or np.isneginf(fk).any())
            fk = np.where(np.isfinite(fk), fk, np.inf)
        self.nfev += k
        self._offer(Xk, fk, vk)
        if k == n:
            return fk, vk
        # the part beyond the budget was not evaluated: infinitely bad
        return np.concatenate([fk, np.full(n - k, np.inf)]), np.concatenate([vk, np.full(n - k, np.inf)])


    def _offer(self, X, f, v) -> None:
        i = int(f.argmin()) if not v.any() else int(rank(f, v)[0])
        if better(f[i], v[i], self.best_f, self.best_v):
            self.best_x, self.best_f, self.best_v = X[i].copy(), float(f[i]), float(v[i])

    def prepare(self, X: np.ndarray) -> np.ndarray:
        """Clip to the bounds and apply the problem's repair hook."""
        X = self.clip(X)
        if self.problem.repair is not None:
            X = self.clip(np.asarray(self.problem.repair(X), dtype=float))
        return X

    def eval_new(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``prepare`` then ``evaluate``: returns ``(X, f, v)``."""
        X = self.prepare(X)
        f, v = self.evaluate(X)
        return X, f, v

    def greedy(self, Xnew, Fnew, Vnew, idx=None) -> np.ndarray:
        """Replace population rows (all, or ``idx``) by the new ones where those are better."""
        if idx is None:
            win = better(Fnew, Vnew, self.F, self.V)
            self.X[win], self.F[win], self.V[win] = Xnew[win], Fnew[win], Vnew[win]
            return win
        idx = np.asarray(idx)
        win = better(Fnew, Vnew, self.F[idx], self.V[idx])
        rows = idx[win]
        self.X[rows], self.F[rows], self.V[rows] = Xnew[win], Fnew[win], Vnew[win]
        return win


class Algorithm:
    """Base class. Subclasses set ``name`` and implement ``step``; they may override
    ``initial_population`` and ``setup`` (memory after the first evaluation).

    ``BATCHABLE = True`` in a class's own body declares that its rules also work on a
    :class:`BatchState` (arrays with a leading run axis, draws from
    :class:`SeedGenerators`), so that ``optimize(..., seeds=...)`` runs all seeds as one
    population. It is not inherited (:meth:`batchable`): a subclass that changes the
    rules is run seed by seed until it declares it itself."""

    name = "base"
    min_pop = 2

    @classmethod
    def capabilities(cls):
        """What the planner can do (:class:`optplan.solvers.capabilities.PlannerCapabilities`):
        a metaheuristic runs on any world, depends on its seed and can offer other valid paths
        of its population."""
        from ..capabilities import PlannerCapabilities

        return PlannerCapabilities(cls.name, "swarm", stochastic=True, alternatives=True)

    @classmethod
    def batchable(cls) -> bool:
        """Whether this very class declares ``BATCHABLE = True``."""
        return bool(vars(cls).get("BATCHABLE", False))

    @classmethod
    def check_params(cls, params, caller_params=()) -> None:
        """Refuse a parameter the algorithm does not have (``caller_params``, the caller's own
        keywords, are only offered as the spelling meant)."""
        unknown = sorted(set(params) - set(cls.defaults()))
        if unknown:
            raise ParameterError(f"{cls.name} has no parameter(s) "
                                 f"{named_with_hints(unknown, [*cls.defaults(), *caller_params])}; "
                                 f"known: {sorted(cls.defaults())}")

    def __init__(self, **params) -> None:
        self.check_params(params)
        for k, v in {**self.defaults(), **params}.items():
            setattr(self, k, v)

    @classmethod
    def defaults(cls) -> dict:
        """Parameters and their paper defaults (class attributes in UPPER case are constants)."""
        out = {}
        for klass in reversed(cls.__mro__):
            for k, v in vars(klass).items():
                if not k.startswith("_") and not k.isupper() and k not in ("name", "min_pop") \
                        and not callable(v) and not isinstance(v, (property, classmethod, staticmethod)):
                    out[k] = v
        return out

    def initial_population(self, state: State, n: int) -> np.ndarray:
        """Uniform random points in the box."""
        return state.lower + state.rng.random((n, state.dim)) * (state.upper - state.lower)

    def setup(self, state: State) -> None:
        """Called once after the initial population is evaluated."""

    def step(self, state: State) -> None:  # pragma: no cover - abstract
        raise NotImplementedError


def run(algorithm: Algorithm, problem: Problem, *, pop: int, iters: int | None = None, max_evals: int | None = None,
        seed=0, init=None, callback=None, progress: bool = False, stagnation: int | None = None,
        target: float | None = None, archive_every: int | None = None, budget: Budget | None = None):
    """Run ``algorithm`` on ``problem``; returns ``(state, history, history_nfev, status, message, nit)``.

    The run obeys ``budget`` when given, else ``Budget(iters, max_evals, stagnation, target)``.
    ``archive_every``: keep population snapshots in ``state.snapshots`` (initial,
    every that many iterations, final); ``None`` keeps none.
    """
    if budget is None:
        budget = Budget(iterations=iters, evaluations=max_evals, stagnation=stagnation, target=target)
    rng = as_generator(seed)
    state = State(problem, pop, budget.iterations, budget.evaluations, rng, budget=budget)
    if init is None:
        X0 = algorithm.initial_population(state, pop)
    elif callable(init):
        X0 = np.asarray(init(pop, rng), dtype=float)
    else:
        X0 = np.asarray(init, dtype=float)
    if X0.shape != (pop, problem.dim):
        raise ParameterError(f"initial population must have shape ({pop}, {problem.dim}), got {X0.shape}")
    out = _loop(algorithm, state, X0, callback=callback, progress=progress, archive_every=archive_every)
    message = out[4]
    if state.nan_seen:
        message += "; the objective returned NaN or -inf for some points (treated as +inf)"
    if state.best_v > 0 and np.isfinite(state.best_v):
        message += f"; no feasible point found (least violation {state.best_v:.3g})"
    return out[:4] + (message, out[5])


def _loop(algorithm: Algorithm, state: State, X0: np.ndarray, *, callback=None, progress: bool = False,
          archive_every: int | None = None):
    """The population loop, written once for a single run (:class:`State`) and for R
    runs at once (:class:`BatchState`, whose best values are arrays; it is never given
    per-run controls: stagnation, target, callback, progress or archive)."""
    budget = state.budget
    batched = isinstance(state, BatchState)
    watch = budget.stagnation is not None or budget.target is not None   # never for a batch
    status, message = "max_iters", "iteration budget spent"
    history, history_nfev = [], []
    try:
        state.X, state.F, state.V = state.eval_new(X0)
        algorithm.setup(state)
    except BudgetExhausted:
        pass
    history.append(state.best_f.copy() if batched else state.best_f)
    history_nfev.append(state.nfev)
    if archive_every:
        state.snapshot()
    last_improvement, last_best = 0, state.best_f
    t_report = time.perf_counter()
    tty = bool(progress) and bool(getattr(sys.stderr, "isatty", lambda: False)())
    while True:
        why = budget.spent(state.it, state.nfev)
        if why is not None:
            status, message = why
            break
        state.it += 1
        try:
            algorithm.step(state)
        except BudgetExhausted:
            pass
        history.append(state.best_f.copy() if batched else state.best_f)
        history_nfev.append(state.nfev)
        if archive_every and state.it % archive_every == 0:
            state.snapshot()
        if progress and time.perf_counter() - t_report > (0.5 if tty else 10.0):
            # a terminal gets one line redrawn in place; a log file a new line every 10 s, not
            # a line of carriage returns
            t_report = time.perf_counter()
            line = f"{algorithm.name}: iteration {state.it}, evaluations {state.nfev}, best {state.best_f:.6g}"
            print(f"\r{line}" if tty else line, end="" if tty else "\n", file=sys.stderr, flush=True)
        if watch:
            if state.best_f < last_best:
                last_best, last_improvement = state.best_f, state.it
            why = budget.converged(state.it - last_improvement, state.best_f, state.best_v == 0)
            if why is not None:
                status, message = why
                break
        if callback is not None and callback(state) is False:
            status, message = "callback", "stopped by the callback"
            break
    if archive_every and state.it % archive_every != 0:
        state.snapshot()  # the final population
    if progress and tty:
        print(file=sys.stderr)
    return state, np.asarray(history), np.asarray(history_nfev, dtype=np.int64), status, message, state.it


# ------------------------------------------------------------------ batched independent runs
class SeedGenerators:
    """One ``numpy.random.Generator`` per seed behind one draw call.

    ``random(shape)``, ``normal`` and ``uniform`` draw ``shape`` from every seed's own
    generator, in seed order, and stack them on a leading run axis:
    ``random((2, 3, n, d))`` gives ``(R, 2, 3, n, d)``. Each seed's generator gives
    exactly the numbers of a single run's calls. Batchable rules index draws from the
    right (``r[..., 0, :, :, :]``) so that they read the same with and without the run axis.

    Read-ahead: a ``Generator.random`` call costs about as much as 1,500 of its numbers
    on top of them (``docs/measurements.md``), a fifth of the draw time at GWO's 5,400
    numbers per call. So ``random`` draws at least ``READ_AHEAD`` numbers per seed in
    one call and serves the next calls from them; a PCG64 stream gives the same doubles
    in one call of ``k n`` as in ``k`` calls of ``n``. ``random`` then returns a view that
    the next call may overwrite. Generators passed in as seeds are not read ahead (they
    are left where single runs would leave them), and ``normal``/``uniform`` are refused
    while read-ahead numbers are pending: they would come from the stream after those.
    """

    READ_AHEAD = 32768          # numbers per seed and call
    READ_AHEAD_TOTAL = 2 ** 21  # numbers for all seeds (16 MB): many seeds read ahead less

    def __init__(self, seeds) -> None:
        seeds = list(seeds)
        self.generators = [as_generator(s) for s in seeds]
        self.read_ahead = not any(isinstance(s, np.random.Generator) for s in seeds)
        self._ahead = np.empty((len(self.generators), 0))
        self._next = 0      # the first pending column of _ahead

    def __len__(self) -> int:
        return len(self.generators)

    def _draw(self, method: str, shape, *args) -> np.ndarray:
        if self._next < self._ahead.shape[1]:
            raise RuntimeError(f"SeedGenerators.{method} after random(): the streams' next numbers are already "
                               "read ahead; a batchable rule may only draw with random()")
        shape = tuple(shape) if isinstance(shape, (tuple, list)) else (int(shape),)
        out = np.empty((len(self.generators),) + shape)
        for g, o in zip(self.generators, out):
            if method == "random":
                g.random(out=o)
            else:
                o[...] = getattr(g, method)(*args, size=shape)
        return out

    def random(self, size=()) -> np.ndarray:
        """Uniform [0, 1) draws of ``size`` per seed: ``(R, *size)`` (a view of the
        read-ahead block, valid until the next call)."""
        if not self.read_ahead:
            return self._draw("random", size)
        shape = tuple(size) if isinstance(size, (tuple, list)) else (int(size),)
        m = math.prod(shape)
        if self._next + m > self._ahead.shape[1]:
            self._refill(m)
        block = self._ahead[:, self._next:self._next + m]
        self._next += m
        return block.reshape((len(self.generators),) + shape)

    def _refill(self, m: int) -> None:
        """Keep the pending numbers in front and draw the rest of a block of at least ``m``."""
        pending = self._ahead[:, self._next:]
        k = pending.shape[1]
        width = max(m, min(self.READ_AHEAD, self.READ_AHEAD_TOTAL // len(self.generators)))
        if self._ahead.shape[1] < width:
            block = np.empty((len(self.generators), width))
            block[:, :k] = pending
            self._ahead = block
        elif k:
            self._ahead[:, :k] = pending.copy()
        for g, row in zip(self.generators, self._ahead):
            g.random(out=row[k:])
        self._next = 0

    def normal(self, loc: float = 0.0, scale: float = 1.0, size=()) -> np.ndarray:
        """Normal draws (``Generator.normal``) per seed: ``(R, *size)``."""
        return self._draw("normal", size, loc, scale)

    def uniform(self, low: float = 0.0, high: float = 1.0, size=()) -> np.ndarray:
        """Uniform draws on ``[low, high)`` (``Generator.uniform``) per seed: ``(R, *size)``."""
        return self._draw("uniform", size, low, high)


class BatchState(State):
    """A :class:`State` holding R independent runs of one algorithm as one population.

    ``X`` is ``(R, n, d)``, ``F`` and ``V`` are ``(R, n)``, ``best_x`` is ``(R, d)`` and
    ``best_f``/``best_v`` are ``(R,)``; ``rng`` is a :class:`SeedGenerators`. Every run
    spends its evaluations in step with the others (the same algorithm on the same
    budget), so ``nfev`` and ``it`` are shared; the objective sees all ``R * n`` rows
    of an iteration in one call.
    """

    def __init__(self, problem: Problem, pop: int, rng: SeedGenerators, budget: Budget):
        super().__init__(problem, pop, budget.iterations, budget.evaluations, None, budget=budget)
        self.rng = rng
        R = len(rng)
        self.runs = R
        self.X = np.empty((R, 0, self.dim))
        self.F = np.empty((R, 0))
        self.V = np.empty((R, 0))
        self.best_x = np.full((R, self.dim), np.nan)
        self.best_f = np.full(R, np.inf)
        self.best_v = np.full(R, np.inf)
        self.nan_seen = np.zeros(R, dtype=bool)

    def snapshot(self) -> None:  # pragma: no cover - refused by optimize(seeds=...)
        raise ParameterError("archive_every is not available with seeds=...; run the seeds one by one")

    def prepare(self, X: np.ndarray) -> np.ndarray:
        """Clip to the bounds and apply the repair hook (on all ``R * n`` rows at once)."""
        X = self.clip(X)
        if self.problem.repair is not None:
            shape = X.shape
            X = self.clip(np.asarray(self.problem.repair(X.reshape(-1, self.dim)), dtype=float).reshape(shape))
        return X

    def evaluate(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Evaluate ``(R, n, d)`` rows in one objective call; returns ``(R, n)`` values and
        violations. The budget is per run: each run may evaluate ``allowed(n)`` rows."""
        R, n, d = X.shape
        k = self.budget.allowed(n, self.nfev)
        Xk = X if k == n else X[:, :k]
        fk, vk = objective_values(self.problem.f(Xk.reshape(R * k, d)), R * k)
        fk, vk = fk.reshape(R, k), vk.reshape(R, k)
        if not math.isfinite(np.add.reduce(fk, axis=None)) and not np.isfinite(fk).all():
            self.nan_seen = self.nan_seen | (np.isnan(fk) | np.isneginf(fk)).any(axis=1)   # per run
            fk = np.where(np.isfinite(fk), fk, np.inf)
        self.nfev += k
        self._offer(Xk, fk, vk)
        if k == n:
            return fk, vk
        pad = np.full((R, n - k), np.inf)
        return np.concatenate([fk, pad], axis=1), np.concatenate([vk, pad], axis=1)

    def _offer(self, X, f, v) -> None:
        # argmin is the first of lexsort's order when nothing is violated
        i = f.argmin(axis=1) if not v.any() else np.lexsort((f, v), axis=-1)[:, 0]
        rows = np.arange(len(f))
        fi, vi = f[rows, i], v[rows, i]
        win = better(fi, vi, self.best_f, self.best_v)
        self.best_x[win] = X[rows[win], i[win]]
        self.best_f[win], self.best_v[win] = fi[win], vi[win]

    def greedy(self, Xnew, Fnew, Vnew, idx=None) -> np.ndarray:
        """Replace rows of every run by the new ones where those are better (all rows only)."""
        if idx is not None:  # pragma: no cover - batchable algorithms use whole-population greedy
            raise ParameterError("greedy(idx=...) is not available in a batched run")
        win = better(Fnew, Vnew, self.F, self.V)
        # copyto with a mask: boolean-index assignment gathers and scatters the rows
        np.copyto(self.X, Xnew, where=win[..., None])
        np.copyto(self.F, Fnew, where=win)
        np.copyto(self.V, Vnew, where=win)
        return win


def run_batched(algorithm: Algorithm, problem: Problem, *, pop: int, seeds, budget: Budget, init=None):
    """Run ``algorithm`` once per seed, all seeds as one ``(R, pop, d)`` population.

    For algorithms with ``batchable = True`` (their rules are written for an optional
    leading run axis). Returns ``(state, history, history_nfev, status, message, nit)``
    with ``history`` of shape ``(iterations + 1, R)``; each run's numbers equal those of
    :func:`run` with its seed. Stagnation and target stops, callbacks and archives need
    per-run control and are refused (``optimize`` runs such seeds one by one).
    """
    if budget.stagnation is not None or budget.target is not None:
        raise ParameterError("a batched run stops every seed together: give no stagnation or target")
    rng = SeedGenerators(seeds)
    state = BatchState(problem, pop, rng, budget)
    R = len(rng)
    if init is None:
        X0 = algorithm.initial_population(state, pop)
    elif callable(init):
        X0 = np.stack([np.asarray(init(pop, g), dtype=float) for g in rng.generators])
    else:
        X0 = np.broadcast_to(np.asarray(init, dtype=float), (R, pop, problem.dim)).copy()
    if X0.shape != (R, pop, problem.dim):
        raise ParameterError(f"initial population must have shape ({pop}, {problem.dim}), got {X0.shape[1:]}")
    return _loop(algorithm, state, X0)
