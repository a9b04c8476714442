"""li2023's GA loop (:func:`~optplan.solvers.gridpath.ga_path.evolve`) on the general encoding.

IGA's improvements (li2023 §4: the variance-checked start, the tanh-adaptive selection,
crossover and mutation probabilities of eq 4, the elite count of eq 5, the regeneration
operator and the stop after 50 generations without improvement) act on the population, not on
the chromosome. Here the chromosome is the general encoding's: ``m`` via points, each snapped
to a roadmap node and joined by geodesic legs
(:class:`~optplan.formulations.encodings.GeneralPath`), so every path class of the map is
reachable and every chromosome decodes to a collision-free path. The operators:

* start: one random corridor per chromosome (``GeneralPath.sample_corridors``);
* one-point crossover between via points (a via point is one gene of two coordinates);
* mutation: one via point moved onto a random node the start reaches (li2023's mutation
  redraws one gene among the free ones);
* similarity for the regeneration: the Euclidean distance of the via points, in cells (the
  regeneration itself never fires: no decoded path collides).

``op.plan(..., algorithm="iga")`` plans with it by default; ``encoding="paper"`` (or
``"columns"`` / ``"cells"``) gives li2023's grid chromosomes.
"""
from __future__ import annotations

import time

import numpy as np

from ...formulations.encodings import GeneralPath
from ...formulations.problem import PathProblem
from ...rng import as_generator
from ..archive import ARCHIVE_EVERY
from ..result import check_alternatives
from .ga_path import GAParams, check_budget, evolve, ga_result


class ViaChromosomes:
    """The general encoding's via points as a chromosome (the ``ops`` of ``evolve``)."""

    def __init__(self, problem: PathProblem, rng: np.random.Generator) -> None:
        self.problem, self.rng = problem, rng
        self.encoding: GeneralPath = problem.encoding
        self.m = self.encoding.m
        self.cell = float(getattr(problem.encoding.world, "resolution", 1.0))

    def sample(self, k: int) -> np.ndarray:
        return self.encoding.sample_corridors(k, self.rng)

    def evaluate(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return self.problem.evaluate(X)

    def canonical(self, X: np.ndarray) -> np.ndarray:
        return np.asarray(X, float)

    def crossover(self, X: np.ndarray, pc: np.ndarray) -> np.ndarray:
        """One-point crossover of consecutive pairs between via points; pair (2i, 2i+1) crosses
        with the mean of their ``pc``."""
        n = len(X)
        V = np.asarray(X, float).reshape(n, self.m, 2)
        out = V.copy()
        if self.m < 2:
            return out.reshape(n, -1)
        half = n // 2
        a, b = np.arange(0, 2 * half, 2), np.arange(1, 2 * half, 2)
        go = self.rng.random(half) < 0.5 * (pc[a] + pc[b])
        cut = self.rng.integers(1, self.m, size=half)
        swap = (np.arange(self.m)[None, :] >= cut[:, None]) & go[:, None]
        out[a] = np.where(swap[..., None], V[b], V[a])
        out[b] = np.where(swap[..., None], V[a], V[b])
        return out.reshape(n, -1)

    def mutate(self, X: np.ndarray, pm: np.ndarray) -> np.ndarray:
        """Each chromosome mutates with its ``pm``: one via point moves onto a random node the
        start reaches."""
        n = len(X)
        out = np.asarray(X, float).reshape(n, self.m, 2).copy()
        who = np.nonzero(self.rng.random(n) < pm)[0]
        if who.size:
            enc = self.encoding
            j = self.rng.integers(0, self.m, size=who.size)
            node = enc.reachable[self.rng.integers(len(enc.reachable), size=who.size)]
            out[who, j] = enc.points[node]
        return out.reshape(n, -1)

    def similarity(self, fresh: np.ndarray, best: np.ndarray) -> np.ndarray:
        return np.linalg.norm(fresh - best, axis=1) / self.cell


def plan_via_ga(world, start, goal, *, improved: bool, seed=0, pop: int = 50, iters: int | None = 200,
                clearance: float = 0.0, preset: str = "li2023", postprocess: str | None = None,
                max_evals: int | None = None, waypoints: int = 3, alternatives: int = 0,
                alternative_separation: float | None = None, **params):
    """``op.plan(..., algorithm="iga")`` (and ``"ga"`` with ``encoding="general"`` through
    :func:`~optplan.solvers.paths.plan_path`'s vector GA): li2023's GA loop on the general
    encoding's via points. Options as :func:`optplan.solvers.gridpath.ga_path.plan_ga`, plus
    ``waypoints`` (the number of via points)."""
    t0 = time.perf_counter()
    check_budget(pop, iters, max_evals)
    s = world.check_query_point(start, "start", clearance)
    g = world.check_query_point(goal, "goal", clearance)
    p = GAParams(improved=improved, **params)
    name = "iga" if improved else "ga"
    problem = PathProblem(GeneralPath(world, s, g, m=waypoints, clearance=clearance), preset, clearance=clearance)
    rng = as_generator(seed)
    ops = ViaChromosomes(problem, rng)
    count, separation = check_alternatives(alternatives, alternative_separation)
    snapshots = [] if count else None
    spreads: list = []
    x, fbest, history, nfev, gens = evolve(ops, rng, pop=pop, iters=iters, params=p, max_evals=max_evals,
                                           snapshots=snapshots, archive_every=ARCHIVE_EVERY, spreads=spreads)
    result = ga_result(world, problem.encoding, x, name, improved, postprocess, clearance, t0, history=history,
                       nfev=nfev, seed=seed, message=f"{gens} generations on the general encoding's via points",
                       snapshots=snapshots, count=count, separation=separation, spreads=spreads)
    result.encoding = "general"
    return result

