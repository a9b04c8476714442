"""Anchor runs for ``engine_speed.py``: mealpy's and niapy's swarms on the same problems.

Not part of optplan and not imported by it: ``engine_speed.py`` runs this file with the
Python of a separate virtual environment that holds mealpy and niapy (mealpy pins an
older numpy, so it never goes into optplan's environment). It reads one JSON job from
stdin and writes one JSON object to stdout.

Job: ``{"problems": {name: {"shift": [...], "lower": l, "upper": u, "kind": "sphere" |
"rastrigin"}}, "max_evals": 15030, "pop": 30, "seeds": [...], "time_iters": 500,
"time_repeats": 3}``. Output: ``{"final": {anchor: {problem: [best per seed]}},
"nfev": {anchor: {problem: [evaluations per seed]}}, "time_s": {anchor: [seconds per
run at pop x time_iters on the unshifted sphere]}}``.

Equal evaluations: mealpy's iteration schedules (``a`` of GWO and WOA, the inertia of
LDW_PSO) plan for ``epoch`` iterations, so each mealpy run gets the number of epochs
its algorithm spends ``max_evals`` in (measured, since sparrow search spends more than
one evaluation per sparrow and epoch) and is cut at ``max_evals`` exactly. niapy's
schedules read the task's evaluation or iteration counters; its task gets both limits.
"""
from __future__ import annotations

import json
import sys
import time

import numpy as np


def objective(kind: str, shift: np.ndarray):
    if kind == "sphere":
        return lambda x: float(np.sum((np.asarray(x) - shift) ** 2))
    if kind == "rastrigin":
        def rastrigin(x):
            z = np.asarray(x) - shift
            return float(np.sum(z * z - 10 * np.cos(2 * np.pi * z) + 10))
        return rastrigin
    raise ValueError(kind)


def mealpy_models(pop: int):
    from mealpy import GWO, PSO, SSA, WOA

    return {
        "mealpy OriginalPSO": lambda epoch: PSO.OriginalPSO(epoch=epoch, pop_size=pop),
        "mealpy LDW_PSO": lambda epoch: PSO.LDW_PSO(epoch=epoch, pop_size=pop),
        "mealpy OriginalGWO": lambda epoch: GWO.OriginalGWO(epoch=epoch, pop_size=pop),
        "mealpy OriginalWOA": lambda epoch: WOA.OriginalWOA(epoch=epoch, pop_size=pop),
        "mealpy OriginalSSA": lambda epoch: SSA.OriginalSSA(epoch=epoch, pop_size=pop),
    }


def run_mealpy(make, f, lower, upper, dim, max_evals, pop, seed, epochs=None):
    from mealpy import FloatVar

    problem = {"obj_func": f, "bounds": FloatVar(lb=(lower,) * dim, ub=(upper,) * dim), "minmax": "min",
               "log_to": None}
    if epochs is None:
        probe = make(20)
        probe.solve(problem, seed=seed)
        per_epoch = (probe.nfe_counter - pop) / 20.0
        epochs = max(1, int(round((max_evals - pop) / per_epoch)))
    model = make(epochs)
    best = model.solve(problem, termination={"max_fe": max_evals}, seed=seed)
    return float(best.target.fitness), int(model.nfe_counter), epochs


def niapy_algorithms(pop: int):
    from niapy.algorithms.basic import GreyWolfOptimizer, ParticleSwarmAlgorithm

    return {
        # the setting (w 0.7, c1 = c2 = 1.5); niapy clamps velocities to +-1.5
        "niapy ParticleSwarmAlgorithm": lambda seed: ParticleSwarmAlgorithm(population_size=pop, c1=1.5, c2=1.5,
                                                                            w=0.7, seed=seed),
        "niapy GreyWolfOptimizer": lambda seed: GreyWolfOptimizer(population_size=pop, seed=seed),
    }


def run_niapy(make, f, lower, upper, dim, max_evals, max_iters, pop, seed):
    from niapy.problems import Problem
    from niapy.task import Task

    class Wrapped(Problem):
        def __init__(self):
            super().__init__(dimension=dim, lower=lower, upper=upper)

        def _evaluate(self, x):
            return f(x)

    task = Task(problem=Wrapped(), max_evals=max_evals, max_iters=max_iters)
    _, best_f = make(seed).run(task)
    return float(best_f), int(task.evals)


def main() -> None:
    job = json.load(sys.stdin)
    pop, max_evals, seeds = job["pop"], job["max_evals"], job["seeds"]
    final, nfev, times = {}, {}, {}
    models = mealpy_models(pop)
    algos = niapy_algorithms(pop)
    for pname, p in job["problems"].items():
        shift = np.asarray(p["shift"], float)
        f = objective(p["kind"], shift)
        dim, lo, hi = shift.size, float(p["lower"]), float(p["upper"])
        for name, make in models.items():
            epochs = None
            for s in seeds:
                val, n, epochs = run_mealpy(make, f, lo, hi, dim, max_evals, pop, s, epochs)
                final.setdefault(name, {}).setdefault(pname, []).append(val)
                nfev.setdefault(name, {}).setdefault(pname, []).append(n)
        for name, make in algos.items():
            for s in seeds:
                val, n = run_niapy(make, f, lo, hi, dim, max_evals, (max_evals - pop) // pop, pop, s)
                final.setdefault(name, {}).setdefault(pname, []).append(val)
                nfev.setdefault(name, {}).setdefault(pname, []).append(n)
    # speed: pop x time_iters on the plain 30-d sphere
    T, dim = job["time_iters"], 30
    sphere = objective("sphere", np.zeros(dim))
    for name in ("mealpy OriginalGWO", "mealpy OriginalPSO"):
        for k in range(job["time_repeats"]):
            t = time.perf_counter()
            run_mealpy(models[name], sphere, -100.0, 100.0, dim, pop * (T + 1), pop, k, epochs=T)
            times.setdefault(name, []).append(time.perf_counter() - t)
    for name in ("niapy GreyWolfOptimizer", "niapy ParticleSwarmAlgorithm"):
        for k in range(job["time_repeats"]):
            t = time.perf_counter()
            run_niapy(algos[name], sphere, -100.0, 100.0, dim, pop * (T + 1), T, pop, k)
            times.setdefault(name, []).append(time.perf_counter() - t)
    json.dump({"final": final, "nfev": nfev, "time_s": times}, sys.stdout)


if __name__ == "__main__":
    main()
