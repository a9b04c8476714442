"""Engine speed: pop 30 x 500 iterations on the 30-d sphere, per algorithm.

    python benchmarks/engine_speed.py

Prints wall time (median of 5 runs) and the framework overhead per evaluation:
(wall time - time spent inside the objective) / evaluations. Goal (issue 3):
GWO under 0.03 s and under 2 us per evaluation. If mealpy is installed, its GWO runs
on the same problem for comparison. mealpy is not one of optplan's extras: it pins an
older numpy, which breaks cvxpy, so install it in a venv of its own::

    python3 -m venv /tmp/mealpy-venv && . /tmp/mealpy-venv/bin/activate
    pip install -e . mealpy && python benchmarks/engine_speed.py
"""
from __future__ import annotations

import time

import numpy as np

import optplan as op
from optplan.solvers.metaheuristics import algorithm_names

REPEATS = 5


def timed_sphere():
    spent = [0.0]

    def f(X):
        t = time.perf_counter()
        out = np.einsum("ij,ij->i", X, X)
        spent[0] += time.perf_counter() - t
        return out

    return f, spent


def measure(algo: str):
    walls, overheads, nfev = [], [], 0
    for k in range(REPEATS):
        f, spent = timed_sphere()
        t = time.perf_counter()
        r = op.optimize(f, [(-100, 100)] * 30, algorithm=algo, pop=30, iters=500, seed=k)
        wall = time.perf_counter() - t
        walls.append(wall)
        overheads.append((wall - spent[0]) / r.nfev * 1e6)
        nfev = r.nfev
    return float(np.median(walls)), float(np.median(overheads)), nfev


def mealpy_gwo():
    try:
        from mealpy import FloatVar, GWO
    except ImportError:
        return None
    problem = {"obj_func": lambda x: float(np.dot(x, x)), "bounds": FloatVar(lb=(-100.0,) * 30, ub=(100.0,) * 30),
               "minmax": "min", "log_to": None}
    t = time.perf_counter()
    GWO.OriginalGWO(epoch=500, pop_size=30).solve(problem, seed=0)
    wall = time.perf_counter() - t
    return wall, wall / 15000 * 1e6


def main() -> None:
    print(f"sphere 30-d, pop 30, 500 iterations; median of {REPEATS} runs\n")
    print("| algorithm | wall [s] | overhead [us/eval] | evaluations |")
    print("|---|---|---|---|")
    for algo in algorithm_names():
        w, o, n = measure(algo)
        print(f"| {algo} | {w:.4f} | {o:.2f} | {n} |")
    m = mealpy_gwo()
    if m is not None:
        print(f"| mealpy GWO (reference) | {m[0]:.4f} | {m[1]:.2f} (incl. objective) | 15000 |")
    else:
        print("\nmealpy is not installed; to compare, run this in a venv of its own with "
              "'pip install -e . mealpy' (it downgrades numpy, so keep it out of optplan's venv)")
    print("\ngoal: gwo under 0.03 s and under 2 us/eval of overhead")


if __name__ == "__main__":
    main()
