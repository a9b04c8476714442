"""How often the papers' own global protocol finds a feasible path (issue 28).

The papers' protocol: their penalised fitness (``constraint="penalty"``), the algorithm's own
initialisation (``init="own"``; MISSA's chaotic map, hou2024 eq 9), one node per column,
their population and iterations, and the fitness scored on the path after the
direct-connection test (``fitness_on="pruned"``, chen2025 §4.3.1's order). For contrast,
``--nodes`` also runs the raw-node scoring that found 0-3 feasible runs of 10.

Development maps are the shipped ones; held-out maps are drawn here with the shipped recipe
(random blocks at the paper's density, :func:`optplan.worldgen.papermaps.block_grid`) from
seeds that were never used while developing (9000 + k), start and goal at opposite corners.

    python benchmarks/paper_protocol_feasibility.py [--runs 10] [--heldout 3] [--papers hou2024,yuan2021,chen2025]
"""
from __future__ import annotations

import argparse

import optplan as op
from optplan.bench.stats import wilson_interval
from optplan.world.grid import GridMap
from optplan.world.papermaps import paper_map
from optplan.worldgen.papermaps import block_grid

# paper -> (shipped maps, held-out recipe (size, density, max_block), algorithms, pop, iters)
PAPERS = {
    "hou2024": (["hou2024_env1", "hou2024_env2"], (20, 0.2, 3), ["missa", "ssa"], 60, 300),
    "yuan2021": (["yuan2021_25"], (25, 0.2, 3), ["iba", "ba"], 50, 100),
    "chen2025": (["chen2025_20", "chen2025_30", "chen2025_40"], (30, 0.2, 3), ["msiar-gwo", "gwo"], 30, 500),
}
PROTOCOL = {"constraint": "penalty", "init": "own", "encoding": "columns"}


def heldout_maps(size: int, density: float, max_block: int, k: int):
    """``k`` held-out grids with start and goal at opposite corner cells."""
    out = []
    for j in range(k):
        occ = block_grid(size, density, max_block, seed=9000 + j)
        out.append((f"heldout{size}_{9000 + j}", GridMap(occ), (0.5, 0.5), (size - 0.5, size - 0.5)))
    return out


def feasible_share(world, start, goal, algorithm: str, runs: int, pop: int, iters: int, fitness_on: str) -> int:
    """Feasible runs out of ``runs`` (seeds 0..runs-1)."""
    return sum(op.plan(world, start, goal, algorithm=algorithm, seed=s, pop=pop, iters=iters,
                       fitness_on=fitness_on, **PROTOCOL).feasible for s in range(runs))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=10)
    ap.add_argument("--heldout", type=int, default=3, help="held-out maps per paper")
    ap.add_argument("--papers", default="hou2024,yuan2021,chen2025")
    ap.add_argument("--nodes", action="store_true", help="also score the raw column nodes (the old protocol)")
    args = ap.parse_args(argv)
    modes = ["pruned", "nodes"] if args.nodes else ["pruned"]
    print("| paper | set | map | algorithm | scored on | feasible | 95 % interval [%] |")
    print("|---|---|---|---|---|---|---|")
    for paper in args.papers.split(","):
        shipped, recipe, algorithms, pop, iters = PAPERS[paper]
        worlds = [("development", name, *paper_map(name)) for name in shipped]
        worlds += [("held-out", *m) for m in heldout_maps(*recipe, args.heldout)]
        for which, name, world, s, g in worlds:
            for a in algorithms:
                for mode in modes:
                    k = feasible_share(world, s, g, a, args.runs, pop, iters, mode)
                    lo, hi = wilson_interval(k, args.runs)
                    print(f"| {paper} | {which} | {name} | {a} | {mode} | {k}/{args.runs} | "
                          f"{100 * lo:.0f}-{100 * hi:.0f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
