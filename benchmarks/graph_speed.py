"""Graph search timings: A*, Dijkstra and the exact visibility search.

    python benchmarks/graph_speed.py

Prints the median wall time of each method on the Moving AI maps (between the
scen row with the longest optimum) and on a seeded 64x64 map with 20 % random
obstacles, whose visibility time has a goal of 2 s (issue 2).
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

import optplan as op
from optplan.solvers.graph import shortest_path
from optplan.world.loaders import load_scen

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "movingai"
REPEATS = 5


def timed(fn, repeats: int = REPEATS):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return float(np.median(times)), out


def cases():
    for rel, scen in (("dao/arena.map", "dao/arena.map.scen"), ("dao/den312d.map", "dao/den312d.map.scen"),
                      ("mapf/room-32-32-4.map", "mapf/room-32-32-4-random-1.scen")):
        if (DATA / rel).exists():
            grid = op.load_map(DATA / rel)
            e = max(load_scen(DATA / scen), key=lambda r: r.optimal)
            yield Path(rel).stem, grid, e.start_world(), e.goal_world()
    for seed in range(20, 100):  # the first seed whose corners are connected
        rng = np.random.default_rng(seed)
        occ = rng.random((64, 64)) < 0.2
        occ[0, 0] = occ[-1, -1] = False
        grid = op.GridMap(occ)
        try:
            shortest_path(grid, (0.5, 0.5), (63.5, 63.5))
        except op.InfeasibleQueryError:
            continue
        grid._cache.clear()
        yield f"random64 (20 %, seed {seed})", grid, (0.5, 0.5), (63.5, 63.5)
        break


def main() -> None:
    print(f"median of {REPEATS} runs; caches cleared before the first\n")
    print("| map | size | method | median time [s] | length [m] | feasible |")
    print("|---|---|---|---|---|---|")
    for name, grid, s, g in cases():
        for method in ("astar", "dijkstra", "visibility"):
            grid._cache.clear()  # cold: no cached move tables or prefix sums
            t, r = timed(lambda: shortest_path(grid, s, g, method=method))
            print(f"| {name} | {grid.width}x{grid.height} | {method} | {t:.4f} | {r.length:.4f} | {r.feasible} |")
    print("\ngoal: visibility on random64 under 2 s")


if __name__ == "__main__":
    main()
