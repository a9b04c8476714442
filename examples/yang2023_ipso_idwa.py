"""Reproduce yang2023 (IPSO-IDWA) with optplan.

--part global: Tables 1-3 analog on the circle-world stand-ins for environments
1 and 2 ((0,0)->(10,10) and (0,0)->(15,15)): PSO vs IPSO, IPSO1 (partly reconstructed)
and IPSO2 (a reconstruction; docs/fidelity/yang2023.md), spline paths through 3 handle points
(eq 3-4), population 150, 500 iterations (the Table 3 settings), 20 runs. Table 3
analog: the median converged length and the iteration at which each run reached
it. Lengths stand next to the exact optimum (tangent graph); the paper's claims
are judged at the end. It runs the shipped spec yang2023_global, exactly as
``optplan reproduce yang2023 --part global`` does.

    python examples/yang2023_ipso_idwa.py --part global [--runs 20] [--quick]

--part local: §7.2 analog (DWA vs IDWA against two crossing movers, scenario
yang2023_idwa_crossing, movers shifted in time per seed) and §7.3 analog (the
IPSO-IDWA fusion on the 25x25 dynamic map, yang2023_fusion, IPSO global path with
50 particles; --iters, default 300), every local planner preset, honest
success/collision/timeout counts. --gif FILE animates IDWA in the crossing test.

    python examples/yang2023_ipso_idwa.py --part local [--runs 20] [--quick] [--gif run.gif]
"""
from __future__ import annotations

import argparse

from optplan.bench.command import reproduce


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["global", "local"], default="global")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--quick", action="store_true", help="one environment, 3 runs, 40 iterations")
    ap.add_argument("--iters", type=int, default=None, help="--part local: iterations of the global planner")
    ap.add_argument("--movers", choices=["once", "shuttle"], default="once",
                    help="--part local: the fusion map's random movers cross the path once, from an origin, as "
                         "the paper draws them (default), or shuttle across it for the whole run (harder)")
    ap.add_argument("--gif", metavar="FILE.gif", help="--part local: also write an animation of one run")
    args = ap.parse_args(argv)
    if args.part == "local":
        return part_local(args)
    return reproduce("yang2023", "global", quick=args.quick, runs=None if args.quick or args.runs == 20 else args.runs,
                     workers=1)


def part_local(args) -> int:
    from optplan.sim.experiments import paper_local
    from optplan.viz.animate import write_run_gif

    if args.quick:
        paper_local("yang2023 §7.2 analog (quick smoke test): DWA vs IDWA, two crossing movers", ["yang2023_idwa_crossing"], 1,
                    planners=["dwa", "idwa"])
    else:
        paper_local("yang2023 §7.2 analog: DWA vs IDWA, two crossing movers (radius 0.6 m, 0.6 m/s)",
                    ["yang2023_idwa_crossing"], args.runs)
        paper_local(f"yang2023 §7.3 analog: fusion on the 25x25 dynamic map (IPSO global path; movers {args.movers})",
                    ["yang2023_fusion"], args.runs, global_planner="ipso",
                    global_options={"encoding": "paper", "pop": 50, "iters": args.iters or 300}, mover_motion=args.movers)
    if args.gif:
        print(write_run_gif("yang2023_idwa_crossing", "idwa", args.gif))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
