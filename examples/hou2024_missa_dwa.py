"""Reproduce hou2024 (MISSA-DWA) with optplan.

--part global: Tables 2-3 analog on the stand-ins for environment models 1 and 2
(hou2024_env1/env2): ACO, IACO (reconstructed from the one-sentence summary of
Zheng et al. [19], docs/fidelity/hou2024.md), SSA and MISSA, 50 runs, Table 1
settings (60 individuals, 300 iterations; ACO and IACO alpha 2, beta 6, rho 0.1,
Q 5) under the paper's protocol (penalised fitness, own initialisation including
MISSA's chaotic eq 9, fitness of the pruned path), then SSA and MISSA under the
feasibility-rule protocol (-fair rows): min/mean length, total rotation angle and
time, the gap to the exact any-angle optimum, the rank-sum p-value against SSA,
and the paper's claims judged. It runs the shipped spec hou2024_global, exactly as
``optplan reproduce hou2024 --part global`` does.

    python examples/hou2024_missa_dwa.py --part global [--runs 50] [--quick]

--part local: Table 4 analog (0-3 random unknown obstacles, scenarios
hou2024_table4_0..3) and the four dynamic environments of §4.5
(hou2024_dynamic1..4), every local planner preset on the same MISSA global path
per seed (60 sparrows; --iters, default 300), with success, collisions, timeouts,
time and path length. --gif FILE writes an animation of MISSA-DWA in dynamic
environment 1 (seed 0).

    python examples/hou2024_missa_dwa.py --part local [--runs 20] [--quick] [--gif run.gif]
"""
from __future__ import annotations

import argparse

from optplan.bench.command import reproduce


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["global", "local"], default="global")
    ap.add_argument("--runs", type=int, default=50)
    ap.add_argument("--quick", action="store_true", help="one map, 3 runs, 60 iterations")
    ap.add_argument("--iters", type=int, default=None, help="iterations of the global planner")
    ap.add_argument("--movers", choices=["once", "shuttle"], default="once",
                    help="--part local: random movers cross the path once, from an origin, as the paper draws "
                         "them (default), or shuttle across it for the whole run (harder)")
    ap.add_argument("--gif", metavar="FILE.gif", help="--part local: also write an animation of one run")
    args = ap.parse_args(argv)
    if args.part == "local":
        return part_local(args)
    return reproduce("hou2024", "global", quick=args.quick, runs=None if args.quick else args.runs, workers=1)


def part_local(args) -> int:
    from optplan.sim.experiments import paper_local
    from optplan.viz.animate import write_run_gif

    if args.quick:
        paper_local("hou2024 Table 4 analog (quick smoke test: 1 random obstacle, A* global path)",
                    ["hou2024_table4_1"], 1,
                    planners=["dwa", "missa-dwa"])
    else:
        runs = args.runs if args.runs != 50 else 20
        gopts = {"encoding": "paper", "pop": 60, "iters": args.iters or 300}
        paper_local("hou2024 Table 4 analog: random unknown obstacles (MISSA global path)",
                    [f"hou2024_table4_{k}" for k in range(4)], runs, global_planner="missa", global_options=gopts)
        paper_local(f"hou2024 §4.5 analog: dynamic environments 1-4 (MISSA global path; movers {args.movers})",
                    [f"hou2024_dynamic{k}" for k in range(1, 5)], runs, global_planner="missa", global_options=gopts,
                    mover_motion=args.movers)
    if args.gif:
        print(write_run_gif("hou2024_dynamic1", "missa-dwa", args.gif, global_planner="astar" if args.quick else "missa",
                        global_options=None if args.quick else {"pop": 60, "iters": args.iters or 300}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
