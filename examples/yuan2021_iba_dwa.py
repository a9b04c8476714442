"""Reproduce yuan2021 (IBA-DWA) with optplan.

--part global: Tables 1-2 analog on the 25x25 stand-in map, 50 individuals and
100 iterations (§5.1), the paper's protocol (penalised fitness, own
initialisation, fitness of the pruned path). Table 1: PSO, BA and IBA, 20 runs,
shortest collision-free path (mu = 0 in eq 13, preset ``yuan2021``), then BA and
IBA under the feasibility-rule protocol (-fair rows). Table 2: IBA with mu = 0
against IBA with mu = 0.1 (preset ``yuan2021-mu0.1``), 10 runs, with the corners
of each path. Each length is shown next to the exact any-angle optimum; the
paper's claims are judged at the end. It runs the shipped specs yuan2021_table1/2,
exactly as ``optplan reproduce yuan2021 --part global`` does.

    python examples/yuan2021_iba_dwa.py --part global [--runs 20] [--quick]

--part local: §5.2 analog (three unknown obstacles added on the global path,
yuan2021_added_obstacles) and §5.3 analog (a 3x3 unknown block that makes the
global path fail, yuan2021_path_switch), every local planner preset on the same
IBA global path per seed (50 bats; --iters, default 100). BA-DWA follows the
turning points and switches paths through the virtual-point graph (§4.2); the
table after the main one counts path switches and re-plans. --gif FILE animates
BA-DWA in the path switch scenario.

    python examples/yuan2021_iba_dwa.py --part local [--runs 20] [--quick] [--gif run.gif]
"""
from __future__ import annotations

import argparse

from optplan.bench.command import reproduce


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["global", "local"], default="global")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--quick", action="store_true", help="3 runs, 60 iterations")
    ap.add_argument("--iters", type=int, default=None, help="--part local: iterations of the global planner")
    ap.add_argument("--gif", metavar="FILE.gif", help="--part local: also write an animation of one run")
    args = ap.parse_args(argv)
    if args.part == "local":
        return part_local(args)
    return reproduce("yuan2021", "global", quick=args.quick, runs=None if args.quick or args.runs == 20 else args.runs,
                     workers=1)


def part_local(args) -> int:
    from optplan.sim.experiments import paper_local, path_switches
    from optplan.viz.animate import write_run_gif

    if args.quick:
        sets = paper_local("yuan2021 §5.3 analog (quick smoke test, 60 s limit): path switch, A* global path", ["yuan2021_path_switch"], 1,
                           planners=["dwa", "ba-dwa"], time_limit=60)
    else:
        gopts = {"pop": 50, "iters": args.iters or 100}
        paper_local("yuan2021 §5.2 analog: newly added obstacles (IBA global path)", ["yuan2021_added_obstacles"],
                    args.runs, global_planner="iba", global_options=gopts)
        sets = paper_local("yuan2021 §5.3 analog: path switch (IBA global path)", ["yuan2021_path_switch"],
                           args.runs, global_planner="iba", global_options=gopts)
    print("| local planner | runs | mean path switches | mean re-plans (incl. switches) |")
    print("|---|---|---|---|")
    for s in sets:
        if s.results:
            switches = [path_switches(r) for r in s.results]
            print(f"| {s.planner} | {len(s.results)} | {sum(switches) / len(s.results):.2f} | "
                  f"{sum(r.replans for r in s.results) / len(s.results):.2f} |")
    if args.gif:
        print(write_run_gif("yuan2021_path_switch", "ba-dwa", args.gif))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
