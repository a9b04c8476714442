"""li2023's TGA and IGA on the paper's cell-sequence chromosome against the column chromosome (issue 28).

Runs ``ga`` and ``iga`` with ``encoding="cells"`` (li2023 §3.1, a general cell sequence) and
``encoding="columns"`` (one cell per column) at li2023's protocol (population 50, 200
generations) and prints, per map, feasible runs, mean length, the gap to A* and the mean time.
A column chromosome that cannot represent any path on a map counts as infeasible.

Development maps are the shipped stand-ins (li2023_30/60/90); held-out maps are drawn here
with the shipped recipe (:func:`optplan.worldgen.papermaps.block_grid`, density 0.22, blocks up
to size/7.5 cells) from seeds never used while developing (9100 + k), start and goal at
opposite corners, as ``benchmarks/paper_protocol_feasibility.py`` does.

    python benchmarks/li2023_cells.py [--runs 5] [--heldout 2] [--sizes 30,60,90]
"""
from __future__ import annotations

import argparse

import numpy as np

import optplan as op
from optplan.world.grid import GridMap
from optplan.world.papermaps import paper_map
from optplan.worldgen.papermaps import block_grid

ROWS = [("ga", "cells"), ("iga", "cells"), ("ga", "columns"), ("iga", "columns")]
MAX_BLOCK = {30: 4, 60: 6, 90: 8}   # the shipped li2023 recipes (optplan/worldgen/papermaps.py)


def maps(sizes: list[int], heldout: int):
    for n in sizes:
        w, s, g = paper_map(f"li2023_{n}")
        yield "dev", f"li2023_{n}", w, s, g
    for n in sizes:
        for j in range(heldout):
            occ = block_grid(n, 0.22, MAX_BLOCK[n], seed=9100 + j)
            yield "held-out", f"heldout{n}_{9100 + j}", GridMap(occ), np.array([0.5, 0.5]), np.array([n - 0.5] * 2)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--heldout", type=int, default=2, help="held-out maps per size")
    ap.add_argument("--sizes", default="30,60,90")
    args = ap.parse_args(argv)
    print("| set | map | A* [m] | algorithm | chromosome | feasible | mean length [m] | vs A* [%] | mean time [s] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for kind, name, w, s, g in maps([int(x) for x in args.sizes.split(",")], args.heldout):
        astar = op.shortest_path(w, s, g, method="astar").length
        for algo, enc in ROWS:
            lengths, times, ok = [], [], 0
            for seed in range(args.runs):
                try:
                    r = op.plan(w, s, g, algorithm=algo, encoding=enc, seed=seed, pop=50, iters=200)
                except op.InfeasibleQueryError:
                    continue
                times.append(r.runtime_s)
                if r.feasible:
                    ok += 1
                    lengths.append(r.length)
            L = np.mean(lengths) if lengths else np.nan
            t = f"{np.mean(times):.2f}" if times else "-"
            print(f"| {kind} | {name} | {astar:.2f} | {algo} | {enc} | {ok}/{args.runs} | {L:.2f} | "
                  f"{100 * (L / astar - 1):+.1f} | {t} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
