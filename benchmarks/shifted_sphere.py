"""How far below random search each algorithm ends on the shifted 30-d sphere.

    python benchmarks/shifted_sphere.py [--runs 10]

Budget 15,000 evaluations, pop 30; the ratio is the median of random search
divided by the algorithm's median (issue 3 asks for at least 1000x). Also
prints the F15/F16 hit counts of the improved variants (20 runs, 1e-3).
"""
from __future__ import annotations

import argparse

import numpy as np

import optplan as op
from optplan.formulations.functions import get_function
from optplan.solvers.metaheuristics import algorithm_names


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=10)
    args = ap.parse_args()
    F = get_function("F1", shifted=True)

    def med(algo):
        return float(np.median([op.optimize(F, F.bounds, algorithm=algo, pop=30, iters=None, max_evals=15000,
                                            seed=s).f for s in range(args.runs)]))

    rnd = med("random")
    print(f"shifted sphere 30-d, 15,000 evaluations, {args.runs} runs; random search median {rnd:.4g}\n")
    print("| algorithm | median | ratio to random | >= 1000x |")
    print("|---|---|---|---|")
    for a in algorithm_names():
        if a == "random":
            continue
        m = med(a)
        print(f"| {a} | {m:.4g} | {rnd / m:.3g} | {'yes' if rnd / m >= 1000 else 'NO'} |")
    print("\n| function | algorithm | runs within 1e-3 of the optimum (of 20) |")
    print("|---|---|---|")
    for fn in ("F15", "F16"):
        G = get_function(fn)
        for a in ("missa", "ipso", "iba", "msiar-gwo"):
            hits = sum(abs(op.optimize(G, G.bounds, algorithm=a, pop=30, iters=500, seed=s).f - G.f_opt) < 1e-3
                       for s in range(20))
            print(f"| {fn} | {a} | {hits} |")


if __name__ == "__main__":
    main()
