"""Reproduce li2023 (IGA-IDWA) on optplan's stand-in maps.

--part global: Table 1 (traditional GA vs improved GA on 30x30, 60x60, 90x90:
length, running time, key points, reductions) and Table 2 (A* vs IGA), each with
the gap to the exact any-angle optimum that the paper does not report, and the
Wilcoxon rank-sum p-value of IGA's lengths against TGA's, and the paper's claims
judged. It runs the shipped spec li2023_global, exactly as
``optplan reproduce li2023 --part global`` does.

    python examples/li2023_iga_idwa.py --part global [--runs 20] [--quick]

--part local: Experiment I (11x11 map, static: traditional DWA vs the IGA-DWA
fusion and every other preset, li2023_exp1) and Experiment II (2-5 moving
obstacles, li2023_exp2_2..5) with the Figure 17 analog: mean path length of the
successful runs against the number of moving obstacles, per local planner. The
global path is IGA's (50 individuals; --iters, default 100). --gif FILE animates
IGA-DWA with 3 moving obstacles.

    python examples/li2023_iga_idwa.py --part local [--runs 20] [--quick] [--gif run.gif]
"""
from __future__ import annotations

import argparse

import numpy as np

from optplan.bench.command import reproduce


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["global", "local"], default="global")
    ap.add_argument("--runs", type=int, default=20, help="runs per algorithm and map (default 20)")
    ap.add_argument("--quick", action="store_true", help="one map, 3 runs, short budgets (for tests)")
    ap.add_argument("--iters", type=int, default=None, help="--part local: iterations of the global planner")
    ap.add_argument("--gif", metavar="FILE.gif", help="--part local: also write an animation of one run")
    args = ap.parse_args(argv)
    if args.part == "local":
        return part_local(args)
    return reproduce("li2023", "global", quick=args.quick, runs=None if args.quick or args.runs == 20 else args.runs,
                     workers=1)


def part_local(args) -> int:
    from optplan.sim.experiments import paper_local
    from optplan.viz.animate import write_run_gif

    if args.quick:
        paper_local("li2023 Experiment I analog (quick smoke test, 40 s limit): traditional DWA vs IGA-DWA, A* global path", ["li2023_exp1"], 1,
                    planners=["dwa", "iga-dwa"], time_limit=40)
    else:
        gopts = {"pop": 50, "iters": args.iters or 100}
        paper_local("li2023 Experiment I analog: static 11x11 map (IGA global path)", ["li2023_exp1"], args.runs,
                    global_planner="iga", global_options=gopts)
        movers = (2, 3, 4, 5)
        sets = paper_local("li2023 Experiment II analog: 2-5 moving obstacles (IGA global path)",
                           [f"li2023_exp2_{m}" for m in movers], args.runs, global_planner="iga", global_options=gopts)
        print("## li2023 Figure 17 analog: mean path length [m] of successful runs by number of moving obstacles\n")
        planners = list(dict.fromkeys(s.planner for s in sets))
        print("| local planner | " + " | ".join(f"{m} movers" for m in movers) + " |")
        print("|---|" + "---|" * len(movers))
        for p in planners:
            cells = []
            for m in movers:
                s = next(x for x in sets if x.planner == p and x.scenario == f"li2023_exp2_{m}")
                ok = s.successes
                cells.append(f"{np.mean([r.path_length for r in ok]):.2f} ({len(ok)}/{len(s.results)})" if ok
                             else f"- (0/{len(s.results)})")
            print(f"| {p} | " + " | ".join(cells) + " |")
        print("\n(successful runs / runs in brackets)")
    if args.gif:
        print(write_run_gif("li2023_exp2_3", "iga-dwa", args.gif, **({"time_limit": 20} if args.quick else {})))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
