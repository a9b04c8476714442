"""What the tube stage of ``refine="casadi"`` buys, per tube radius.

For each paper map: the paper's own global planner (seeds ``0 .. runs-1``) and,
on grids, A*, give the seeds; each seed is refined by ``refine_path(...,
"casadi", tube_radius=R)`` for several radii ``R``, given as multiples of the
map's widest obstacle (:func:`optplan.solvers.tube.obstacle_width`, the unit of
the default radius; ``0`` = purely local). Printed per map and radius: the share
of refinements within 1 % of the exact any-angle optimum that pass
``validate_path``, and the median refinement time (tube search + both
smoothings). The last row counts the maps that reach issue 5's figure
(>= 90 %) at each radius. The last columns give the shipped default,
``refine="casadi"`` as ``op.plan`` runs it: the default radius (2 widths) and
3 starts (the best path and up to 2 other paths of the planner's population
outside each other's tube, :func:`optplan.solvers.refine.refine_result`); its
time counts every start's refinement.

    python benchmarks/refine_tube.py [--runs 10] [--maps NAME ...] [--widths 0 1 1.5 2 3] [--iters N] [--pop N]
                                     [--starts K]

Wall-clock times depend on machine load; run it on a quiet machine.
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from optplan.bench.global_runs import PAPER_BUDGET, PAPER_PLANNER, exact_optimum
from optplan.planning import plan
from optplan.solvers.refine import refine_path, refine_result, starts_for, tube_radius_for
from optplan.solvers.tube import DEFAULT_WIDTHS, obstacle_width
from optplan.world.geometry import validate_path
from optplan.world.metrics import path_length
from optplan.world.papermaps import maps_of, paper_map



def seeds_for(world, s, g, planner: str, runs: int, iters: int, pop: int, starts: int | None = None) -> list:
    """Feasible results of the paper's planner (seeds 0..runs-1; with the alternatives
    a ``starts``-start refinement uses, which leave the path unchanged) and, on grids, A*."""
    k = starts_for("casadi", starts)
    ask = {"alternatives": k - 1, "alternative_separation": tube_radius_for(world, "casadi")} if k > 1 else {}
    results = [plan(world, s, g, algorithm=planner, seed=j, pop=pop, iters=iters, **ask) for j in range(runs)]
    if hasattr(world, "occ"):
        results.append(plan(world, s, g, algorithm="astar"))
    return [r for r in results if r.feasible]


def default_refinement(world, opt: float, results, starts: int | None = None) -> tuple[int, float]:
    """(refinements within 1 % that validate, median time in seconds) of ``refine_result``
    with the default radius and ``starts`` starts (None: the default)."""
    good, times = 0, []
    for res in results:
        r = refine_result(world, res, "casadi", starts=starts)
        times.append(r.runtime_s - res.runtime_s)
        good += bool(r.refined and r.feasible and r.length <= 1.01 * opt)
    return good, float(np.median(times))


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
    ap.add_argument("--starts", type=int, default=None, metavar="K",
                    help=f"starts of the default-refinement columns (default: refine='casadi''s, {starts_for('casadi')})")
    args = ap.parse_args(argv)
    widths = sorted(set(args.widths))
    k_starts = starts_for("casadi", args.starts)
    rows, reached, reached_default = [], np.zeros(len(widths), int), 0
    for paper, planner in PAPER_PLANNER.items():
        pop, iters = args.pop or PAPER_BUDGET[paper][0], args.iters or PAPER_BUDGET[paper][1]
        for name in maps_of(paper):
            if args.maps and name not in args.maps:
                continue
            world, s, g = paper_map(name)
            opt = exact_optimum(world, s, g)
            unit = obstacle_width(world)
            results = seeds_for(world, s, g, planner, args.runs, iters, pop, args.starts)
            seeds = [r.path for r in results]
            stats = sweep_map(world, opt, seeds, [k * unit for k in widths])
            n = len(seeds)
            reached += np.array([good >= 0.9 * n for good, _ in stats])
            dgood, dtime = default_refinement(world, opt, results, args.starts)
            reached_default += dgood >= 0.9 * n
            rows.append([name, f"{pop} x {iters}", f"{unit:.2f}", str(n)]
                        + [f"{good}/{n} ({100 * good / n:.0f} %)" for good, _ in stats]
                        + [f"{1e3 * t:.0f}" for _, t in stats]
                        + [f"{dgood}/{n} ({100 * dgood / n:.0f} %)", f"{1e3 * dtime:.0f}"])
            print(f"  {name}: done", file=sys.stderr, flush=True)
    header = (["map", "pop x iters", "widest obstacle [m]", "seeds"] + [f"within 1 %, R = {k:g} w" for k in widths]
              + [f"median ms, R = {k:g} w" for k in widths]
              + [f"within 1 %, default ({DEFAULT_WIDTHS:g} w, {k_starts} starts)",
                 f"median ms, default ({k_starts} starts)"])
    print(f"## Tube radius sweep (refine='casadi'; R in widths w of the widest obstacle; {args.runs} runs of each "
          f"paper's planner at its paper's population and iterations, + A* on grids)\n")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for r in rows:
        print("| " + " | ".join(r) + " |")
    print("| maps with >= 90 % | | | | " + " | ".join(f"{m}/{len(rows)}" for m in reached) + " |" + " |" * len(widths)
          + f" {reached_default}/{len(rows)} | |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
