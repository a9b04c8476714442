"""The exact any-angle search at scale (issue 43, item 3): ``method="visibility"`` on large grids.

    python benchmarks/exact_search_scale.py                      # table: random, rooms, maze; 64-512
    python benchmarks/exact_search_scale.py --old-up-to 256      # also time the old search up to 256
    python benchmarks/exact_search_scale.py --check              # exactness: new vs old, held-out seeds

The table: maps from :func:`optplan.worldgen.maps.generate_map` (``random`` with 20 % blocked
cells, ``rooms``, ``maze``) on held-out seeds (7000, 7001, ...; ``--seeds``), one query per
map (:func:`optplan.worldgen.maps.map_query`: two far-apart cell centres; ``--query corners``:
the free cell centres nearest to two opposite map corners). Columns:

* ``corners``: the graph's nodes (convex obstacle corners);
* ``new s``: ``visibility_path`` (the search, its upper bound and set-up), cold;
* ``api s``: the whole ``op.shortest_path(..., method="visibility")`` call (path validated, metrics);
* ``old s``: the reference search that looks at every corner on every expansion
  (``visibility_path(..., search="scan")``, the code before this change), where the size is at
  most ``--old-up-to`` (it takes minutes on 512 x 512 maps);
* ``length``: the optimum in cells; ``equal``: old and new lengths within 1e-9 relative;
  ``valid``: the API's path passes ``validate_path``.

``--check``: the new search against the old one on held-out seeds 7000-7039, random / rooms /
maze maps of 32-128 cells, three queries per map (far-apart cell centres, two random points
inside free cells, two lattice points or edge midpoints of free cells), and with a clearance of
0.3 cells on the maps up to 64 cells: every length equal to 1e-9 relative (unreachable in both
or in neither), every path valid under ``validate_path``; also counts identical paths.
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

import optplan as op
from optplan.solvers.graph.visibility import corner_nodes, visibility_path
from optplan.worldgen.maps import generate_map, map_query

KINDS = ("random", "rooms", "maze")
SIZES = (64, 128, 256, 512)
HELD_OUT = 7000


def corner_query(grid):
    """Free cell centres nearest to the bottom-left and the top-right map corners (metres)."""
    free = np.argwhere(~grid.occ)[:, ::-1]  # (ix, iy)
    a = free[np.argmin(free.sum(axis=1))]
    b = free[np.argmax(free.sum(axis=1))]
    return grid.to_world(a + 0.5), grid.to_world(b + 0.5)


def timed(fn):
    t0 = time.perf_counter()
    try:
        out = fn()
    except op.InfeasibleQueryError:
        out = None
    return out, time.perf_counter() - t0


def table(sizes, kinds, seeds, old_up_to: int, query: str) -> None:
    print("| map | size | seed | corners | new s | api s | old s | length (cells) | equal | valid |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n in sizes:
        for kind in kinds:
            for seed in range(HELD_OUT, HELD_OUT + seeds):
                grid = generate_map(kind, n, seed=seed)
                s, g = map_query(grid, seed=seed) if query == "far" else corner_query(grid)
                corners = len(corner_nodes(grid)[0])
                new, t_new = timed(lambda: visibility_path(grid, s, g))
                grid = generate_map(kind, n, seed=seed)  # cold again: nothing derived kept
                api, t_api = timed(lambda: op.shortest_path(grid, s, g, method="visibility"))
                old, t_old = (None, None)
                if n <= old_up_to:
                    old, t_old = timed(lambda: visibility_path(grid, s, g, search="scan"))
                length = "unreachable" if new is None else f"{new[1] / grid.resolution:.6f}"
                if n > old_up_to:
                    equal = "-"
                elif (new is None) != (old is None):
                    equal = "NO"
                else:
                    equal = "yes" if new is None or abs(new[1] - old[1]) <= 1e-9 * old[1] else "NO"
                valid = "-" if api is None else ("yes" if op.validate_path(grid, api.path) else "NO")
                told = "-" if t_old is None else f"{t_old:.2f}"
                print(f"| {kind} | {n} | {seed} | {corners} | {t_new:.2f} | {t_api:.2f} | {told} | {length} | "
                      f"{equal} | {valid} |", flush=True)


def _queries(grid, rng, seed):
    """Three queries: far-apart centres, random inner points, lattice / edge points of free cells."""
    out = [map_query(grid, seed=seed)]
    free = np.argwhere(~grid.occ)[:, ::-1].astype(float)
    for mode in ("inside", "lattice"):
        for _ in range(20):
            a, b = free[rng.choice(len(free), 2, replace=False)]
            off = rng.uniform(0.02, 0.98, (2, 2)) if mode == "inside" else rng.choice([0.0, 0.5, 1.0], (2, 2))
            p, q = grid.to_world(a + off[0]), grid.to_world(b + off[1])
            if grid.is_free(p) and grid.is_free(q) and not np.array_equal(p, q):
                out.append((p, q))
                break
    return out


def check(seeds: range, sizes=(32, 48, 64, 96, 128), clearance_cells: float = 0.3) -> int:
    rng = np.random.default_rng(43)
    stats = dict(queries=0, equal=0, identical=0, unreachable=0, valid=0, bad=[], worst=0.0, t_new=0.0, t_old=0.0)
    for seed in seeds:
        for k, kind in enumerate(KINDS):
            n = sizes[(seed + k) % len(sizes)]
            grid = generate_map(kind, n, seed=seed)
            cases = [(p, q, 0.0) for p, q in _queries(grid, rng, seed)]
            if n <= 64:
                p, q = map_query(grid, seed=seed)
                cases.append((p, q, clearance_cells * grid.resolution))
            for p, q, c in cases:
                stats["queries"] += 1
                old, t_old = timed(lambda: visibility_path(grid, p, q, clearance=c, search="scan"))
                new, t_new = timed(lambda: visibility_path(grid, p, q, clearance=c))
                stats["t_old"] += t_old
                stats["t_new"] += t_new
                tag = (kind, n, seed, tuple(p), tuple(q), c)
                if (old is None) != (new is None):
                    stats["bad"].append(("reachability differs", tag))
                    continue
                if old is None:
                    stats["equal"] += 1
                    stats["unreachable"] += 1
                    stats["valid"] += 1
                    continue
                rel = abs(new[1] - old[1]) / max(old[1], 1e-300)
                stats["worst"] = max(stats["worst"], rel)
                if rel <= 1e-9:
                    stats["equal"] += 1
                else:
                    stats["bad"].append((f"length {new[1]!r} vs old {old[1]!r}", tag))
                stats["identical"] += bool(np.array_equal(new[0], old[0]))
                if op.validate_path(grid, new[0], c):
                    stats["valid"] += 1
                else:
                    stats["bad"].append(("invalid path", tag))
    print(f"queries: {stats['queries']} (of which unreachable in both: {stats['unreachable']}; "
          f"with clearance {clearance_cells} cells: the maps up to 64 cells)")
    print(f"lengths equal to 1e-9 relative: {stats['equal']}/{stats['queries']} (largest relative difference "
          f"{stats['worst']:.2e}); paths identical: {stats['identical']}/{stats['queries'] - stats['unreachable']}")
    print(f"paths valid (validate_path): {stats['valid']}/{stats['queries']}")
    print(f"time: old {stats['t_old']:.1f} s, new {stats['t_new']:.1f} s in all")
    for what, tag in stats["bad"]:
        print("MISMATCH", what, tag)
    return 1 if stats["bad"] else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=list(SIZES))
    ap.add_argument("--kinds", nargs="+", default=list(KINDS), choices=KINDS)
    ap.add_argument("--seeds", type=int, default=1, help="maps per kind and size (seeds 7000, 7001, ...)")
    ap.add_argument("--old-up-to", type=int, default=128, help="time the old search up to this size (default 128)")
    ap.add_argument("--query", choices=("far", "corners"), default="far")
    ap.add_argument("--check", action="store_true", help="exactness check instead of the table")
    ap.add_argument("--check-seeds", type=int, nargs=2, default=(7000, 7040), metavar=("FIRST", "STOP"))
    a = ap.parse_args(argv)
    if a.check:
        return check(range(*a.check_seeds))
    table(a.sizes, a.kinds, a.seeds, a.old_up_to, a.query)
    return 0


if __name__ == "__main__":
    sys.exit(main())
