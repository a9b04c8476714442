"""What the tube stage of ``refine="casadi"`` buys, per tube radius.

For each paper map: the paper's own global planner (seeds ``0 .. runs-1``) and,
on grids, A*, give the seeds; each seed is refined by ``refine_path(...,
"casadi", tube_radius=R)`` for several radii ``R``, given as multiples of the
map's widest obstacle (:func:`optplan.solvers.tube.obstacle_width`, the unit of
the default radius; ``0`` = purely local). Printed per map and radius: the share
of refinements within 1 % of the exact any-angle optimum that pass
``validate_path``, and the median refinement time (tube search + both
smoothings). The last row counts the maps that reach issue 5's figure
(>= 90 %) at each radius.

    python benchmarks/refine_tube.py [--runs 10] [--maps NAME ...] [--widths 0 1 1.5 2 3] [--iters N] [--pop N]

Wall-clock times depend on machine load; run it on a quiet machine.
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from optplan.bench.global_runs import PAPER_BUDGET, PAPER_PLANNER, exact_optimum
from optplan.planning import plan
from optplan.solvers.refine import refine_path
from optplan.solvers.tube import DEFAULT_WIDTHS, obstacle_width
from optplan.world.geometry import validate_path
from optplan.world.metrics import path_length
from optplan.world.papermaps import maps_of, paper_map



def seeds_for(world, s, g, planner: str, runs: int, iters: int, pop: int) -> list[np.ndarray]:
    """Feasible paths of the paper's planner (seeds 0..runs-1) and, on grids, A*."""
    results = [plan(world, s, g, algorithm=planner, seed=k, pop=pop, iters=iters) for k in range(runs)]
    if hasattr(world, "occ"):
        results.append(plan(world, s, g, algorithm="astar"))
    return [r.path for r in results if r.feasible]


def sweep_map(world, opt: float, seeds, radii) -> list[tuple[int, float]]:
    """Per radius: (refinements within 1 % that validate, median time in seconds)."""
    refine_path(world, seeds[0], "casadi", tube_radius=max(radii))  # build interpolant and solvers untimed
    out = []
    for R in radii:
        good, times = 0, []
        for seed in seeds:
            t = time.perf_counter()
            r = refine_path(world, seed, "casadi", tube_radius=R)
            times.append(time.perf_counter() - t)
            good += bool(r.success and validate_path(world, r.path) and path_length(r.path) <= 1.01 * opt)
        out.append((good, float(np.median(times))))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=10, help="seeded runs of each paper's planner per map")
    ap.add_argument("--maps", nargs="+", metavar="NAME", help="only these paper maps (default: all)")
    ap.add_argument("--widths", nargs="+", type=float, default=[0, 1, 1.5, 2, 3], metavar="K",
                    help="tube radii in widths of the widest obstacle (0 = purely local; default "
                         f"0 1 1.5 2 3; the refine='casadi' default is {DEFAULT_WIDTHS:g})")
    ap.add_argument("--iters", type=int, default=None, help="planner iterations (default: each paper's own)")
    ap.add_argument("--pop", type=int, default=None, help="population (default: each paper's own)")
    args = ap.parse_args(argv)
    widths = sorted(set(args.widths))
    rows, reached = [], np.zeros(len(widths), int)
    for paper, planner in PAPER_PLANNER.items():
        pop, iters = args.pop or PAPER_BUDGET[paper][0], args.iters or PAPER_BUDGET[paper][1]
        for name in maps_of(paper):
            if args.maps and name not in args.maps:
                continue
            world, s, g = paper_map(name)
            opt = exact_optimum(world, s, g)
            unit = obstacle_width(world)
            seeds = seeds_for(world, s, g, planner, args.runs, iters, pop)
            stats = sweep_map(world, opt, seeds, [k * unit for k in widths])
            n = len(seeds)
            reached += np.array([good >= 0.9 * n for good, _ in stats])
            rows.append([name, f"{pop} x {iters}", f"{unit:.2f}", str(n)]
                        + [f"{good}/{n} ({100 * good / n:.0f} %)" for good, _ in stats]
                        + [f"{1e3 * t:.0f}" for _, t in stats])
            print(f"  {name}: done", file=sys.stderr, flush=True)
    header = (["map", "pop x iters", "widest obstacle [m]", "seeds"] + [f"within 1 %, R = {k:g} w" for k in widths]
              + [f"median ms, R = {k:g} w" for k in widths])
    print(f"## Tube radius sweep (refine='casadi'; R in widths w of the widest obstacle; {args.runs} runs of each "
          f"paper's planner at its paper's population and iterations, + A* on grids)\n")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for r in rows:
        print("| " + " | ".join(r) + " |")
    print("| maps with >= 90 % | | | | " + " | ".join(f"{m}/{len(rows)}" for m in reached) + " |" + " |" * len(widths))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
