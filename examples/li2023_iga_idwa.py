"""Reproduce li2023 (IGA-IDWA) on optplan's stand-in maps.

--part global: Table 1 (traditional GA vs improved GA on 30x30, 60x60, 90x90:
length, running time, key points, reductions) and Table 2 (A* vs IGA), each with
the gap to the exact any-angle optimum that the paper does not report, and the
Wilcoxon rank-sum p-value of IGA's lengths against TGA's.

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

from optplan.bench.global_runs import exact_optimum, global_table, run_many
from optplan.planning import plan
from optplan.world.papermaps import paper_map

MAPS = ("li2023_30", "li2023_60", "li2023_90")


def key_point_count(result) -> int:
    return max(len(result.path) - 2, 0)


def part_global(runs: int, quick: bool) -> None:
    maps = MAPS[:1] if quick else MAPS
    iters = 60 if quick else 200
    print("## li2023 Table 1 analog: traditional GA (ga) vs improved GA (iga)\n")
    print("| map | algorithm | mean length [m] | gap to optimum [%] | mean time [s] | mean key points | "
          "length reduction [%] | time reduction [%] | key point reduction [%] |")
    print("|---|---|---|---|---|---|---|---|---|")
    details = []
    for name in maps:
        world, s, g = paper_map(name)
        opt = exact_optimum(world, s, g)
        sets = {a: run_many(world, s, g, a, runs, pop=50, iters=iters) for a in ("ga", "iga")}
        stats = {}
        for a, rs in sets.items():
            L = rs.values("length")
            stats[a] = (L.mean() if len(L) else np.nan, np.mean([r.runtime_s for r in rs.results]),
                        np.mean([key_point_count(r) for r in rs.feasible]) if rs.feasible else np.nan)
        for a in ("ga", "iga"):
            Lm, tm, km = stats[a]
            red = ["", "", ""]
            if a == "iga":
                base = stats["ga"]
                red = [f"{100 * (1 - Lm / base[0]):.1f}", f"{100 * (1 - tm / base[1]):.1f}", f"{100 * (1 - km / base[2]):.1f}"]
            print(f"| {name} | {a} | {Lm:.3f} | {100 * (Lm / opt - 1):.2f} | {tm:.3f} | {km:.1f} | {' | '.join(red)} |")
        details.append((name, opt, list(sets.values())))
    print("\n## li2023 Table 2 analog: A* vs IGA\n")
    print("| map | A* length [m] | A* key points | A* time [s] | IGA mean length [m] | IGA key points | IGA time [s] | optimum [m] |")
    print("|---|---|---|---|---|---|---|---|")
    for name, opt, sets in details:
        world, s, g = paper_map(name)
        a = plan(world, s, g, algorithm="astar")
        from optplan.world.postprocess import remove_collinear

        ak = len(remove_collinear(a.path)) - 2
        iga = sets[1]
        print(f"| {name} | {a.length:.3f} | {ak} | {a.runtime_s:.4f} | {iga.values('length').mean():.3f} | "
              f"{np.mean([key_point_count(r) for r in iga.feasible]):.1f} | "
              f"{np.mean([r.runtime_s for r in iga.results]):.3f} | {opt:.3f} |")
    print("\n## Per-map detail (Wilcoxon rank-sum of lengths against ga)\n")
    for name, opt, sets in details:
        print(f"### {name}\n")
        print(global_table(sets, opt, reference="ga"))
        print()


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
    part_global(3 if args.quick else args.runs, args.quick)
    return 0


def part_local(args) -> int:
    from optplan.sim.experiments import paper_local
    from optplan.viz.animate import write_run_gif

    if args.quick:
        paper_local("li2023 Experiment I analog (quick): traditional DWA vs IGA-DWA, A* global path", ["li2023_exp1"], 1,
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
