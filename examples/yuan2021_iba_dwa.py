"""Reproduce yuan2021 (IBA-DWA) with optplan.

--part global: Tables 1-2 analog on the 25x25 stand-in map: BA vs IBA, 20 runs,
50 bats and 100 iterations (§5.1; --iters changes it).
Table 1 is the shortest collision-free path (mu = 0 in eq 13, preset
``yuan2021``); Table 2 adds the turning cost (mu = 1, preset ``yuan2021-smooth``)
and reports turns. Each length is shown next to the exact any-angle optimum.

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

from optplan.bench.global_runs import paper_global


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["global", "local"], default="global")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--quick", action="store_true", help="3 runs, 60 iterations")
    ap.add_argument("--iters", type=int, default=None, help="iterations of the global planner")
    ap.add_argument("--gif", metavar="FILE.gif", help="--part local: also write an animation of one run")
    args = ap.parse_args(argv)
    if args.part == "local":
        return part_local(args)
    runs = 3 if args.quick else args.runs
    iters = 60 if args.quick else (args.iters or 100)  # §5.1: population 50, 100 iterations
    paper_global("yuan2021 Table 1 analog: shortest collision-free path (mu = 0)", ["yuan2021_25"], ["ba", "iba"],
                 runs, reference="ba", pop=50, iters=iters, preset="yuan2021")
    sets = paper_global("yuan2021 Table 2 analog: with the turning cost (mu = 1)", ["yuan2021_25"], ["ba", "iba"],
                        runs, reference="ba", pop=50, iters=iters, preset="yuan2021-smooth")
    for s in sets["yuan2021_25"]:
        turns = [r.n_turns for r in s.feasible]
        if turns:
            print(f"{s.algorithm}: turns min {min(turns)}, mean {sum(turns) / len(turns):.1f}")
    return 0


def part_local(args) -> int:
    from optplan.sim.experiments import paper_local, path_switches
    from optplan.viz.animate import write_run_gif

    if args.quick:
        sets = paper_local("yuan2021 §5.3 analog (quick): path switch, A* global path", ["yuan2021_path_switch"], 1,
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
