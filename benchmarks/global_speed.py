"""Global planner timings on the paper maps.

    python benchmarks/global_speed.py [--repeats 5]

Goals (issue 4): a hou2024-style MISSA run (pop 60 x 300 iterations on 20x20)
at most 0.1 s median; IGA on 90x90 at most 0.3 s median (the papers report
0.99 s and 2.24 s in MATLAB). Per-map tables (segment lookups, distance field)
are built once per map; the first, cold run is reported separately. Timings are
wall-clock: on a shared machine compare runs made in the same minute.
"""
from __future__ import annotations

import time

import numpy as np

import optplan as op
from optplan.formulations.encodings import clear_shared_tables
from optplan.world.papermaps import paper_map

CASES = [
    ("missa", "hou2024_env1", dict(pop=60, iters=300), 0.1),
    ("ssa", "hou2024_env1", dict(pop=60, iters=300), None),
    ("aco", "hou2024_env1", dict(pop=60, iters=300), None),
    ("iga", "li2023_90", dict(pop=50, iters=200), 0.3),
    ("ga", "li2023_90", dict(pop=50, iters=200), None),
    ("msiar-gwo", "chen2025_40", dict(pop=30, iters=500), None),
    ("ipso", "yang2023_env1", dict(pop=50, iters=300), None),
]


def main(repeats: int = 5) -> None:
    print(f"median of {repeats} warm runs (seeds 1..{repeats}); cold = first run on a freshly loaded map\n")
    print("| algorithm | map | budget | cold [s] | median [s] | goal [s] | median length [m] | optimum [m] |")
    print("|---|---|---|---|---|---|---|---|")
    for algo, name, budget, goal in CASES:
        clear_shared_tables()  # cold really is cold: no tables from an earlier case on the same map
        world, s, g = paper_map(name)
        t = time.perf_counter()
        op.plan(world, s, g, algorithm=algo, seed=0, **budget)
        cold = time.perf_counter() - t
        times, lengths = [], []
        for seed in range(1, repeats + 1):
            r = op.plan(world, s, g, algorithm=algo, seed=seed, **budget)
            times.append(r.runtime_s)
            lengths.append(r.length if r.feasible else np.nan)
        opt = op.shortest_path(world, s, g, method="visibility").length
        b = f"pop {budget['pop']} x {budget['iters']}"
        print(f"| {algo} | {name} | {b} | {cold:.3f} | {np.median(times):.3f} | {goal if goal else '-'} | "
              f"{np.nanmedian(lengths):.3f} | {opt:.3f} |")


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=5, help="warm runs per case (default 5)")
    main(max(ap.parse_args().repeats, 1))
