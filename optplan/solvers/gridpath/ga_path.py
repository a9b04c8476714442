"""Genetic algorithms on grid paths: the traditional GA (``ga``) and li2023's IGA (``iga``).

Chromosome: one free cell per grid column between start and goal (the cell's
sequence number ``N = x + n*y`` of li2023 eq 1 fixes the column, so a gene is the
row). Every operator keeps paths continuous in the sense of the exact segment
rule: one-point crossover swaps tails at a column, mutation redraws one gene
among the rows that keep both neighbouring moves free, and the initial
population is drawn among collision-free paths (a sampler over the column graph).

IGA (li2023 §4) adds, each as a small function below:

* variance-checked initialisation (§4.1): half the population random, half
  redrawn ``m`` chromosomes at a time until the fitness variance exceeds ``sigma1``;
* tanh-adaptive selection, crossover and mutation probabilities (eq 4) and an
  elite count that shrinks linearly (eq 5);
* the regeneration operator (§4.3): offspring that collide are replaced by fresh
  paths, redrawn while their mean distance to the best chromosome is <= ``sigma2``;
* termination after 50 generations without improvement (§4.5);
* key point extraction of the result (§4.4).

Eq 4 as printed grows every probability with ``f_i - f_avg``. For a cost to be
minimised we read it with the sign that protects good individuals: with
``z_i = (f_avg - f_i) / std(f)``, ``P_s = Ps_min + (Ps_max - Ps_min) * tanh(max(z_i, 0))``
and ``P_c``, ``P_m`` fall from their maxima by the same amount. The paper gives no
numbers for the bounds, ``k_e``, ``sigma1`` or ``sigma2``; the defaults below are ours.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ...checks import integer, number
from ...errors import ParameterError
from ...formulations.encodings import ColumnNodes
from ...formulations.problem import PathProblem
from ...formulations.segment_store import ColumnSegments, column_segments
from ...rng import as_generator
from ...world.postprocess import key_points, remove_collinear
from ..archive import ARCHIVE_EVERY, archive_alternatives
from ..budget import Budget
from ..metaheuristics.engine import pooled_archive
from ...results import PlanResult
from ..result import check_alternatives, make_plan_result
from ..capabilities import PlannerCapabilities

CAPABILITIES = {
    # ga is a vector GA over the general encoding (a swarm) unless asked for li2023's chromosome
    "ga": PlannerCapabilities("ga", "swarm", alternatives=True),
    "iga": PlannerCapabilities("iga", "cell-ga", grid_only="IGA evolves sequences of grid cells", alternatives=True),
}


@dataclass(frozen=True)
class GAParams:
    """Settings of the path GA; ``improved`` switches on the IGA mechanisms."""

    improved: bool = True
    pc: float = 0.8                  # traditional GA: fixed crossover probability
    pm: float = 0.2                  # traditional GA: fixed mutation probability
    ps_range: tuple[float, float] = (0.5, 1.0)
    pc_range: tuple[float, float] = (0.6, 0.9)
    pm_range: tuple[float, float] = (0.05, 0.3)
    k_e: float = 0.1                 # eq 5 elite retention factor, as a fraction of the population
    sigma1: float = 1.0              # §4.1 fitness variance threshold (metres^2)
    sigma2: float = 1.0              # §4.3 mean distance-to-best threshold (cells)
    redraw: int = 5                  # m chromosomes redrawn per diversity check
    stall: int = 50                  # §4.5 generations without improvement before stopping

    def __post_init__(self) -> None:
        share, positive = number(0.0, 1.0), number(0.0)
        for name in ("pc", "pm", "k_e"):
            share(name, getattr(self, name))
        for name in ("ps_range", "pc_range", "pm_range"):
            lo_hi = getattr(self, name)
            if not (isinstance(lo_hi, (tuple, list)) and len(lo_hi) == 2
                    and 0 <= share(name, lo_hi[0]) <= share(name, lo_hi[1])):
                raise ParameterError(f"{name} must be (low, high) with 0 <= low <= high <= 1, got {lo_hi!r}")
        positive("sigma1", self.sigma1)
        positive("sigma2", self.sigma2)
        integer(1)("redraw", self.redraw)
        integer(1)("stall", self.stall)


def adaptive_probabilities(f: np.ndarray, lo_hi: tuple[float, float], protect: bool) -> np.ndarray:
    """li2023 eq 4 for a minimised cost (see module docstring). ``protect=False`` gives
    the selection probability (rises for good individuals), ``True`` the crossover or
    mutation probability (falls for good individuals)."""
    lo, hi = lo_hi
    z = (f.mean() - f) / (f.std() + 1e-12)
    t = np.tanh(np.maximum(z, 0.0))
    return hi - (hi - lo) * t if protect else lo + (hi - lo) * t


def elite_count(t: int, t_max: int, k_e: float, pop: int) -> int:
    """li2023 eq 5: ``k_elite = (T_max - t) / T_max * k_e`` (here ``k_e`` is a share of ``pop``), at least 1."""
    return max(1, int(round((t_max - t) / max(t_max, 1) * k_e * pop)))


def _crossover(rows: np.ndarray, pc: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """One-point crossover of consecutive pairs; pair (2i, 2i+1) crosses with the mean of their pc."""
    n, d = rows.shape
    out = rows.copy()
    if d < 2:
        return out
    half = n // 2
    a, b = np.arange(0, 2 * half, 2), np.arange(1, 2 * half, 2)
    go = rng.random(half) < 0.5 * (pc[a] + pc[b])
    cut = rng.integers(1, d, size=half)
    tail = np.arange(d)[None, :] >= cut[:, None]
    swap = tail & go[:, None]
    out[a] = np.where(swap, rows[b], rows[a])
    out[b] = np.where(swap, rows[a], rows[b])
    return out


def _mutate(rows: np.ndarray, pm: np.ndarray, moves: ColumnSegments, rng: np.random.Generator) -> np.ndarray:
    """Redraw one gene per mutating individual among rows whose two moves stay free
    (``moves``: the map's segments, decided for the rows asked about)."""
    n, d = rows.shape
    out = rows.copy()
    who = np.nonzero(rng.random(n) < pm)[0]
    if who.size == 0:
        return out
    j = rng.integers(0, d, size=who.size)
    H = moves.H
    ok = np.ones((who.size, H), dtype=bool)
    has_prev = j > 0
    ok[~has_prev] &= moves.first_moves()[None, :]
    # one query per column: the moves out of the previous gene, and into the next one
    for col in np.unique(j[has_prev]):
        k = np.nonzero(has_prev & (j == col))[0]
        ok[k] &= moves.moves(int(col) - 1, rows[who[k], col - 1])
    has_next = j < d - 1
    for col in np.unique(j[has_next]):
        k = np.nonzero(has_next & (j == col))[0]
        ok[k] &= moves.moves_into(int(col), rows[who[k], col + 1])
    ok[~has_next] &= moves.last_moves()[None, :]
    any_ok = ok.any(axis=1)
    choice = np.argmax(ok * rng.random(ok.shape), axis=1)
    out[who[any_ok], j[any_ok]] = choice[any_ok]
    return out


def variance_checked(sample, evaluate, n: int, p: GAParams, rng) -> np.ndarray:
    """§4.1: redraw ``p.redraw`` random chromosomes until the fitness variance exceeds sigma1."""
    X = sample(n)
    f = evaluate(X)
    for _ in range(100):
        if f.var(ddof=1) > p.sigma1 if n > 1 else True:
            break
        k = rng.choice(n, size=min(p.redraw, n), replace=False)
        X[k] = sample(len(k))
        f[k] = evaluate(X[k])
    return X


def euclidean_to(fresh: np.ndarray, best: np.ndarray) -> np.ndarray:
    """li2023 §4.3's similarity of each chromosome to the best one: the Euclidean distance of
    their genes (rows of a column chromosome, in cells)."""
    return np.linalg.norm(fresh - best, axis=1)


def regenerate(X: np.ndarray, bad: np.ndarray, best: np.ndarray, sample, p: GAParams, rng,
               similarity=euclidean_to) -> np.ndarray:
    """§4.3: replace colliding offspring by fresh paths, diverse w.r.t. the best chromosome
    (``similarity(fresh, best)``: each fresh chromosome's distance to the best, in cells)."""
    idx = np.nonzero(bad)[0]
    if idx.size == 0:
        return X
    fresh = sample(idx.size)
    for _ in range(20):
        if similarity(fresh, best).mean() > p.sigma2:
            break
        k = rng.choice(idx.size, size=min(p.redraw, idx.size), replace=False)
        fresh[k] = sample(len(k))
    X = X.copy()
    X[idx] = fresh
    return X


class ColumnChromosomes:
    """The operators on the column chromosome (one row per column, genes at cell centres)."""

    def __init__(self, problem: PathProblem, rng: np.random.Generator) -> None:
        enc = problem.encoding
        if not isinstance(enc, ColumnNodes) or not enc.snap:
            raise ParameterError("the path GA works on snapped ColumnNodes encodings")
        self.problem, self.rng = problem, rng
        # the moves the operators may take, decided for the rows they ask about (not a table of
        # every segment of the map: (d - 1) H^2 of them)
        self.moves = column_segments(enc, problem.clearance)
        self.similarity = euclidean_to

    def sample(self, k: int) -> np.ndarray:
        return self.problem.encoding.sample_feasible(k, self.rng, self.problem.clearance)

    def evaluate(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return self.problem.evaluate(X)

    def canonical(self, X: np.ndarray) -> np.ndarray:
        return np.floor(X) + 0.5

    def crossover(self, X: np.ndarray, pc: np.ndarray) -> np.ndarray:
        return _crossover(np.floor(X).astype(np.int64), pc, self.rng) + 0.5

    def mutate(self, X: np.ndarray, pm: np.ndarray) -> np.ndarray:
        return _mutate(np.floor(X).astype(np.int64), pm, self.moves, self.rng) + 0.5


def check_budget(pop, iters, max_evals) -> None:
    """The path GAs' population and budget arguments (ParameterError when wrong)."""
    if isinstance(pop, bool) or not isinstance(pop, (int, np.integer)) or pop < 2:
        raise ParameterError(f"pop must be an integer >= 2, got {pop!r}")
    if iters is not None and (isinstance(iters, bool) or not isinstance(iters, (int, np.integer)) or iters < 0):
        raise ParameterError(f"iters must be an integer >= 0 or None, got {iters!r}")
    if max_evals is not None and (isinstance(max_evals, bool) or not isinstance(max_evals, (int, np.integer))
                                  or max_evals < pop):
        raise ParameterError(f"max_evals must be an integer >= pop ({pop}) or None, got {max_evals!r}")
    if iters is None and max_evals is None:
        raise ParameterError("give iters, max_evals or both; the GA needs a budget")


def ga_path(problem: PathProblem, *, pop: int = 50, iters: int | None = 200, seed=0, params: GAParams = GAParams(),
            callback=None, max_evals: int | None = None, snapshots: list | None = None, archive_every: int = 10,
            spreads: list | None = None):
    """Run the path GA on a column-node problem.

    ``iters`` caps the generations and ``max_evals`` the path evaluations (either may
    be ``None``, not both): the run obeys the shared :class:`~optplan.solvers.budget.Budget`,
    so ``nfev == max_evals`` exactly when the evaluations run out (a batch larger than
    what is left is cut; the rows beyond it count as infinitely bad). IGA's §4.5 stop
    after ``params.stall`` generations without improvement is the budget's stagnation.
    li2023 eq 5 grows the elite count with ``gen / T``; without an iteration cap ``T``
    is the number of generations the budget affords.

    ``snapshots``: when a list is given, ``(X, f)`` of the initial population, of every
    ``archive_every``-th generation and of the final one are appended to it (the
    archive ``plan_ga(..., alternatives=k)`` draws alternative paths from). ``spreads``: when a
    list is given, the standard deviation of the population's finite fitness values (0 with fewer
    than two; IGA scores a colliding chromosome as infinite) is appended for the initial
    population and every generation (li2023 Fig 14's diversity).

    Returns ``(best_x, best_f, history, nfev, generations)``.
    """
    check_budget(pop, iters, max_evals)
    rng = as_generator(seed)
    return evolve(ColumnChromosomes(problem, rng), rng, pop=pop, iters=iters, params=params, callback=callback,
                  max_evals=max_evals, snapshots=snapshots, archive_every=archive_every, spreads=spreads)


def fitness_spread(f: np.ndarray) -> float:
    """Standard deviation of a population's finite fitness values (0 with fewer than two)."""
    finite = f[np.isfinite(f)]
    return float(np.std(finite)) if len(finite) > 1 else 0.0


def evolve(ops, rng: np.random.Generator, *, pop: int, iters: int | None, params: GAParams, callback=None,
           max_evals: int | None = None, snapshots: list | None = None, archive_every: int = 10,
           spreads: list | None = None):
    """The GA loop of li2023 §4 (TGA when ``params.improved`` is false) over a chromosome's
    operators ``ops`` (``sample``, ``evaluate``, ``canonical``, ``crossover``, ``mutate``,
    ``similarity``; :class:`ColumnChromosomes`, :class:`~optplan.solvers.gridpath.cell_ga.CellChromosomes`).
    Arguments and result as :func:`ga_path`."""
    budget = Budget(iterations=iters, evaluations=max_evals, stagnation=params.stall if params.improved else None)
    horizon = iters if iters is not None else max(1, max_evals // pop - 1)  # T of li2023 eq 5
    nfev = 0
    sample = ops.sample

    def evaluate(X: np.ndarray) -> np.ndarray:
        nonlocal nfev
        n = len(X)
        k = min(n, int(min(budget.evaluations_left(nfev), n)))   # rows the budget still allows
        out = np.full(n, np.inf)
        if k > 0:
            nfev += k
            f, v = ops.evaluate(X[:k])
            out[:k] = np.where(v > 0, np.inf, f) if params.improved else f
        return out

    if params.improved:
        half = pop // 2
        X = np.vstack([sample(pop - half), variance_checked(sample, evaluate, half, params, rng)])
    else:
        X = sample(pop)
    f = evaluate(X)
    if snapshots is not None:
        snapshots.append((X.copy(), f.copy()))
    if spreads is not None:
        spreads.append(fitness_spread(f))
    best = int(np.argmin(f))
    best_x, best_f = X[best].copy(), float(f[best])
    history = [best_f]
    stalled = 0
    gen = 0
    while budget.spent(gen, nfev) is None:
        gen += 1
        rows = ops.canonical(X)
        finite = np.isfinite(f)
        fs = np.where(finite, f, f[finite].max() if finite.any() else 0.0)
        if params.improved:
            ps = adaptive_probabilities(fs, params.ps_range, protect=False)
            pc = adaptive_probabilities(fs, params.pc_range, protect=True)
            pm = adaptive_probabilities(fs, params.pm_range, protect=True)
            k_el = elite_count(min(gen, horizon), horizon, params.k_e, pop)
        else:
            ps = 1.0 / (fs - fs.min() + 1.0)     # roulette on inverse cost
            pc = np.full(pop, params.pc)
            pm = np.full(pop, params.pm)
            k_el = 1
        order = np.argsort(f, kind="stable")
        elites = rows[order[:k_el]]
        w = ps / ps.sum()
        parents = rng.choice(pop, size=pop - k_el, p=w)
        Xk = ops.mutate(ops.crossover(rows[parents], pc[parents]), pm[parents])
        fk = evaluate(Xk)
        if params.improved:
            bad = ~np.isfinite(fk)
            if bad.any():
                Xk = regenerate(Xk, bad, best_x, sample, params, rng, ops.similarity)
                fk[bad] = evaluate(Xk[bad])
        X = np.vstack([elites, Xk])
        f = np.concatenate([f[order[:k_el]], fk])
        i = int(np.argmin(f))
        if f[i] < best_f - 1e-12:
            best_x, best_f = X[i].copy(), float(f[i])
            stalled = 0
        else:
            stalled += 1
        history.append(best_f)
        if spreads is not None:
            spreads.append(fitness_spread(f))
        if snapshots is not None and gen % archive_every == 0:
            snapshots.append((X.copy(), f.copy()))
        if callback is not None and callback(gen, best_f) is False:
            break
        if budget.converged(stalled, best_f) is not None:   # IGA §4.5
            break
    if snapshots is not None and gen % archive_every != 0:
        snapshots.append((X.copy(), f.copy()))  # the final population
    return best_x, best_f, np.asarray(history), nfev, gen


def plan_ga(world, start, goal, *, improved: bool, seed=0, pop: int = 50, iters: int | None = 200, clearance: float = 0.0,
            preset: str = "li2023", postprocess: str | None = None, max_evals: int | None = None,
            alternatives: int = 0, alternative_separation: float | None = None, **params):
    """``op.plan(..., algorithm="ga" | "iga")`` on a grid map (li2023 §3-4).

    ``alternatives`` / ``alternative_separation``: other distinct paths of the run's
    population, as in :func:`optplan.solvers.paths.plan_path`.
    """
    t0 = time.perf_counter()
    s = world.check_query_point(start, "start", clearance)
    g = world.check_query_point(goal, "goal", clearance)
    problem = PathProblem(ColumnNodes(world, s, g), preset, clearance=clearance)
    name = "iga" if improved else "ga"
    if problem.encoding.dim == 0:
        return make_plan_result(world, np.stack([s, g]), name, time.perf_counter() - t0, clearance=clearance)
    p = GAParams(improved=improved, **params)
    count, separation = check_alternatives(alternatives, alternative_separation)
    snapshots = [] if count else None
    spreads: list = []
    x, fbest, history, nfev, gens = ga_path(problem, pop=pop, iters=iters, seed=seed, params=p, max_evals=max_evals,
                                            snapshots=snapshots, archive_every=ARCHIVE_EVERY, spreads=spreads)
    return ga_result(world, problem.encoding, x, name, improved, postprocess, clearance, t0, history=history,
                     nfev=nfev, seed=seed, message=f"{gens} generations", snapshots=snapshots, count=count,
                     separation=separation, spreads=spreads)


def ga_result(world, decoder, best, name: str, improved: bool, postprocess: str | None, clearance: float,
              t0: float, *, history, nfev: int, seed, message: str, snapshots: list | None, count: int,
              separation, spreads: list | None = None) -> PlanResult:
    """The result of a path GA run on either chromosome: the best one decoded
    (``decoder.waypoints``) and post-processed (IGA's key points, TGA's collinear points
    removed, unless ``postprocess`` says otherwise), with its alternatives from the population
    archive; every path is validated by the exact check on the way (``make_plan_result``,
    ``archive_alternatives``)."""
    mode = postprocess or ("keypoints" if improved else "collinear")

    def finish(raw):
        return key_points(world, raw, clearance) if mode == "keypoints" else remove_collinear(raw) if mode == "collinear" else raw

    path = finish(decoder.waypoints(best))
    others = []
    if count:
        # infinite cost = a colliding chromosome (IGA) or, on cells, no chain from start to goal
        X, _, V = pooled_archive([(X, f, np.where(np.isfinite(f), 0.0, np.inf)) for X, f in snapshots])
        others = archive_alternatives(world, X, V, decoder, finish, best, path, count, separation, clearance)
    result = make_plan_result(world, path, name, time.perf_counter() - t0, clearance=clearance, history=history,
                              seed=seed if isinstance(seed, int) else None, nfev=nfev, message=message)
    result.alternatives = others
    if spreads is not None:
        result.population_spread = np.asarray(spreads, float)
    return result
