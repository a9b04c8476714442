"""Global planner timings on the paper maps, and on generated 256x256 city maps.

    python benchmarks/global_speed.py [--repeats 5]     # paper maps, then the cold-start city table
    python benchmarks/global_speed.py --scale-only      # the cold-start city table only
    python benchmarks/global_speed.py --city [--repeats 3]   # general encoding on a city map

``--city`` (issue 26): one metaheuristic run with the general encoding and 15,000 evaluations
on a 256x256 city-like map (``worldgen.maps.generate_map("city", 256)``), goal at most 5 s,
next to A* and the exact visibility planner. The map's roadmap (corners, visible edges,
all-pairs geodesics) is built once per map: its time is reported as its own column and is
not part of a run's time.

Goals (issue 4): a hou2024-style MISSA run (pop 60 x 300 iterations on 20x20)
at most 0.1 s median; IGA on 90x90 at most 0.3 s median (the papers report
0.99 s and 2.24 s in MATLAB). Per-map tables (segment lookups, distance field)
are built once per map; the first, cold run is reported separately. Timings are
wall-clock: on a shared machine compare runs made in the same minute.

Scale table (issues 26 and 30): a seeded 256x256 city map (``optplan.worldgen.city``;
no Moving AI city map is shipped), one query between free cells near opposite
corners and one ~60 m long. Each case runs in a fresh child process (cold: nothing
cached, modules imported), which reports its wall time and the growth of its peak
resident memory (VmHWM). Rows: a cold ``refine="casadi"`` of the A* path (the
set-up the issue measured at 521 s) and a warm one; a metaheuristic run of 15,000
evaluations (msiar-gwo, pop 30, column nodes, including every per-map set-up: 147 s
and 14 GB in the issue); A* and the exact any-angle search. The anchors are run in
the same invocation on a 64x64 city map, where the old set-ups still finish: the
CasADi interpolant fit over the whole field (what the refinement built before) and
the full per-map segment tables (``ColumnNodes.segment_tables``).
"""
from __future__ import annotations

import time

import numpy as np

import optplan as op
from optplan.formulations.encodings import clear_shared_tables
from optplan.world.papermaps import paper_map

CASES = [
    ("missa", "hou2024_env1", dict(encoding="paper", pop=60, iters=300), 0.1),
    ("ssa", "hou2024_env1", dict(encoding="paper", pop=60, iters=300), None),
    ("aco", "hou2024_env1", dict(pop=60, iters=300), None),
    ("iga", "li2023_90", dict(encoding="paper", pop=50, iters=200), 0.3),
    ("ga", "li2023_90", dict(encoding="paper", pop=50, iters=200), None),
    ("msiar-gwo", "chen2025_40", dict(encoding="paper", pop=30, iters=500), None),
    ("ipso", "yang2023_env1", dict(encoding="paper", pop=50, iters=300), None),
]


# --------------------------------------------------------------------- scale table
def _peak_kib() -> tuple[int, int]:
    """``(VmRSS, VmHWM)`` of this process in KiB (Linux)."""
    out = {}
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(("VmRSS:", "VmHWM:")):
                out[line.split(":")[0]] = int(line.split()[1])
    return out.get("VmRSS", 0), out.get("VmHWM", 0)


def _city_queries(grid):
    """Free cell centres near opposite corners (largest component), and a pair ~60 m apart."""
    from scipy.ndimage import label

    lab, _ = label(~grid.occ)
    iy, ix = np.nonzero(lab > 0)
    big = np.argmax(np.bincount(lab[iy, ix]))
    keep = lab[iy, ix] == big
    iy, ix = iy[keep], ix[keep]
    a, b = np.argmin(ix + iy), np.argmax(ix + iy)
    far = grid.cell_center((ix[a], iy[a])), grid.cell_center((ix[b], iy[b]))
    m = grid.width // 2
    c = np.argmin(np.abs(ix - m + 20) + np.abs(iy - m + 20))
    d = np.argmin(np.abs(ix - m - 20) + np.abs(iy - m - 25))
    return {"far": far, "60 m": (grid.cell_center((ix[c], iy[c])), grid.cell_center((ix[d], iy[d])))}


def _scale_case(case: str, size: int, query: str, conn, city_seed: int = 0) -> None:
    """One case in a fresh (spawned) process: ``(seconds, peak growth in bytes, note)``."""
    import optplan as op
    from optplan.worldgen.city import city_map

    grid = city_map(size, seed=city_seed)
    s, g = _city_queries(grid)[query]
    rss0, _ = _peak_kib()
    t0 = time.perf_counter()
    note = ""
    if case == "refine cold" or case == "refine warm":
        from optplan.solvers.refine import refine_path

        seed = op.shortest_path(grid, s, g, method="astar").path
        rss0, _ = _peak_kib()
        t0 = time.perf_counter()
        r = refine_path(grid, seed, "casadi")
        if case == "refine warm":
            t0 = time.perf_counter()
            r = refine_path(grid, seed, "casadi")
        L = float(np.hypot(*np.diff(r.path, axis=0).T).sum())
        note = f"{'valid' if r.success else 'seed kept'}, {L:.1f} m (seed {float(np.hypot(*np.diff(seed, axis=0).T).sum()):.1f} m)"
        if not r.success:
            note += f": {r.message[:70]}"
    elif case == "msiar-gwo 15,000 evals":
        r = op.plan(grid, s, g, algorithm="msiar-gwo", seed=0, pop=30, iters=500, max_evals=15000)
        note = f"{r.nfev} evaluations, feasible {r.feasible}, {r.length:.1f} m"
    elif case in ("astar", "visibility"):
        r = op.shortest_path(grid, s, g, method=case)
        note = f"{r.length:.4f} m, feasible {r.feasible}"
    elif case == "old: casadi interpolant fit":
        import casadi as ca

        from optplan.world.fields import grid_distance_field

        f = grid_distance_field(grid, 4)
        t0 = time.perf_counter()
        ca.interpolant("sdf", "bspline", [f.xs, f.ys], f.values.ravel())
        note = f"{f.values.size} lattice points (the field itself not timed)"
    elif case == "old: full segment tables":
        from optplan.formulations.encodings import ColumnNodes

        enc = ColumnNodes(grid, np.asarray(s), np.asarray(g))
        enc.segment_tables(0.0)
        note = f"{(enc.dim - 1) * grid.height ** 2 + 2 * grid.height} segments (no penetration table)"
    _, peak = _peak_kib()
    conn.send((time.perf_counter() - t0, (peak - rss0) * 1024, note))


SCALE_CASES = [  # (case, map size, query)
    ("refine cold", 256, "60 m"), ("refine warm", 256, "60 m"), ("refine cold", 256, "far"),
    ("msiar-gwo 15,000 evals", 256, "far"), ("astar", 256, "far"), ("visibility", 256, "far"),
    ("old: casadi interpolant fit", 64, "far"), ("refine cold", 64, "far"),
    ("old: full segment tables", 64, "far"), ("msiar-gwo 15,000 evals", 64, "far"),
]


def scale_table(timeout: float = 600.0, city_seed: int = 0) -> None:
    """The cold-start table on the city maps (each case a fresh spawned process)."""
    import multiprocessing as mp

    print(f"\n## Cold starts on a seeded city map (optplan.worldgen.city, seed {city_seed})\n")
    print("each case in a fresh process; memory = growth of its peak resident set over the start of the timed part. "
          "Anchors from issue 30 on a 256x256 city map: cold refine 521 s; segment tables 147 s and 14 GB. "
          "Times on a shared 2-core machine: compare rows of one run\n")
    print("| case | map | query | time [s] | peak memory growth [MB] | result |")
    print("|---|---|---|---|---|---|")
    ctx = mp.get_context("spawn")
    for case, size, query in SCALE_CASES:
        here, there = ctx.Pipe(duplex=False)
        proc = ctx.Process(target=_scale_case, args=(case, size, query, there, city_seed))
        proc.start()
        if here.poll(timeout):
            t, peak, note = here.recv()
            print(f"| {case} | {size}x{size} | {query} | {t:.2f} | {peak / 2 ** 20:.0f} | {note} |", flush=True)
        else:
            print(f"| {case} | {size}x{size} | {query} | > {timeout:g} (stopped) | - | - |", flush=True)
        proc.kill()
        proc.join()


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


CITY_ALGORITHMS = ("msiar-gwo", "missa", "pso")


def city_general_speed(repeats: int = 3, seed: int = 7001, evals: int = 15000) -> None:
    """Print the 256x256 city table: roadmap build, metaheuristic runs, A*, exact planner."""
    from optplan.world.roadmap import Roadmap
    from optplan.worldgen.maps import generate_map, map_query

    grid = generate_map("city", 256, seed=seed)
    s, g = map_query(grid, seed=seed)
    t = time.perf_counter()
    rm = Roadmap.of(grid)
    rm.dist  # the all-pairs tables the general encoding reads are part of the once-per-map build
    build = time.perf_counter() - t
    exact = op.shortest_path(grid, s, g, method="visibility")
    astar = op.shortest_path(grid, s, g, method="astar")
    print(f"{grid.name}: {grid.occ.mean():.0%} blocked, roadmap {len(rm.nodes)} nodes / {len(rm.edges)} edges "
          f"built once in {build:.2f} s\n")
    print("| planner | budget | median run [s] | goal [s] | median length [m] | exact optimum [m] |")
    print("|---|---|---|---|---|---|")
    print(f"| astar | - | {astar.runtime_s:.3f} | - | {astar.length:.3f} | {exact.length:.3f} |")
    print(f"| visibility (exact) | - | {exact.runtime_s:.3f} | - | {exact.length:.3f} | {exact.length:.3f} |")
    for algo in CITY_ALGORITHMS:
        times, lengths = [], []
        for k in range(repeats):
            t = time.perf_counter()
            r = op.plan(grid, s, g, algorithm=algo, encoding="general", max_evals=evals, seed=k)
            times.append(time.perf_counter() - t)
            lengths.append(r.length if r.feasible else np.nan)
        print(f"| {algo} (general) | {evals} evaluations | {np.median(times):.3f} | 5 | {np.nanmedian(lengths):.3f} | "
              f"{exact.length:.3f} |", flush=True)


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=5, help="warm runs per case (default 5)")
    ap.add_argument("--city", action="store_true", help="the 256x256 city table (general encoding) only")
    ap.add_argument("--scale-only", action="store_true", help="only the city-map cold-start table")
    ap.add_argument("--city-seed", type=int, default=0, help="seed of the city maps (0 was developed on; default 0)")
    args = ap.parse_args()
    if args.city:
        city_general_speed(max(args.repeats, 1))
    else:
        if not args.scale_only:
            main(max(args.repeats, 1))
        scale_table(city_seed=args.city_seed)
