"""Reproduce chen2025 (MSIAR-GWO) with optplan.

--part functions: Tables 4-7 analog. F1-F18 (F1-F13 shifted, see
optplan.formulations.functions), 20 runs x 500 iterations x population 30, for
MSIAR-GWO and the baselines optplan has (GWO, ARO, DBO, WOA, IGWO; AGWO and
RSMGWO are not implemented). Prints best/mean/worst/std tables, the Wilcoxon
rank-sum table with the +/=/- tally against MSIAR-GWO, and saves convergence
plots in --out.

--part paths: Tables 8-11 analog on the stand-in maps chen2025_20/30/40: the
same algorithms (20 runs, population 30, 500 iterations), each length next to
the exact any-angle optimum, and A* vs MSIAR-GWO (Table 8).

    python examples/chen2025_msiar_gwo.py --part functions [--runs 20] [--iters 500] [--quick]
    python examples/chen2025_msiar_gwo.py --part paths [--runs 20] [--quick]
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

import optplan as op
from optplan.bench.global_runs import exact_optimum, global_table, run_many
from optplan.bench.stats import summary_table, wilcoxon_table
from optplan.formulations.functions import NAMES, get_function
from optplan.viz.convergence import plot_convergence
from optplan.world.papermaps import paper_map

ALGORITHMS = ("msiar-gwo", "gwo", "aro", "dbo", "woa", "igwo")
MISSING = ("agwo", "rsmgwo")


def part_functions(runs: int, iters: int, functions, out: Path) -> None:
    results, histories = {}, {}
    for k, name in enumerate(functions, 1):
        F = get_function(name, shifted=True)
        results[name], histories[name] = {}, {}
        for algo in ALGORITHMS:
            rs = [op.optimize(F, F.bounds, algorithm=algo, pop=30, iters=iters, seed=s) for s in range(runs)]
            results[name][algo] = [r.f for r in rs]
            histories[name][algo] = [r.history for r in rs]
        print(f"\r  {k}/{len(functions)} functions", end="", file=sys.stderr, flush=True)
        plot_convergence(histories[name], out / f"convergence_{name}.png", title=f"{name} (shifted where applicable)",
                         log=name not in ("F8", "F17", "F18"))
    print(file=sys.stderr)
    print(f"## chen2025 Tables 4-6 analog ({runs} runs x {iters} iterations x pop 30; F1-F13 shifted)\n")
    print(summary_table(results))
    print("\nknown optima: " + ", ".join(f"{n}={get_function(n).f_opt:.6g}" for n in functions))
    print(f"\n## chen2025 Table 7 analog: Wilcoxon rank-sum p-values of msiar-gwo against each algorithm\n")
    print(wilcoxon_table(results, "msiar-gwo"))
    print(f"\n(+: msiar-gwo significantly better at alpha 0.05, -: significantly worse, =: no difference)")
    print(f"not implemented: {', '.join(MISSING)}; convergence plots in {out}/")


def part_paths(runs: int, iters: int, maps) -> None:
    print(f"## chen2025 Tables 9-11 analog ({runs} runs, pop 30, {iters} iterations; feasibility rule, "
          "collision-free random starts)\n")
    astar_rows = []
    for name in maps:
        world, s, g = paper_map(name)
        opt = exact_optimum(world, s, g)
        sets = [run_many(world, s, g, a, runs, pop=30, iters=iters) for a in ALGORITHMS]
        print(f"### {name}\n")
        print(global_table(sets, opt, reference="msiar-gwo"))
        print()
        a = op.plan(world, s, g, algorithm="astar")
        best = min((r for r in sets[0].feasible), key=lambda r: r.length, default=None)
        astar_rows.append((name, a.length, best.length if best else float("nan"), opt))
    print("## chen2025 Table 8 analog: A* vs MSIAR-GWO (best of runs)\n")
    print("| map | A* (8-connected) [m] | MSIAR-GWO best [m] | exact any-angle optimum [m] |")
    print("|---|---|---|---|")
    for name, la, lm, opt in astar_rows:
        print(f"| {name} | {la:.4f} | {lm:.4f} | {opt:.4f} |")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["functions", "paths"], default="functions")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--iters", type=int, default=500)
    ap.add_argument("--quick", action="store_true", help="3 runs, short budgets, a few functions/one map")
    ap.add_argument("--out", default="out/chen2025", help="folder for plots")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.part == "functions":
        funcs = ("F1", "F9", "F15", "F16") if args.quick else NAMES
        part_functions(3 if args.quick else args.runs, 50 if args.quick else args.iters, funcs, out)
    else:
        maps = ("chen2025_20",) if args.quick else ("chen2025_20", "chen2025_30", "chen2025_40")
        part_paths(3 if args.quick else args.runs, 60 if args.quick else args.iters, maps)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
