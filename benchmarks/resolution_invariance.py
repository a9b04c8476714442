"""Resolution and origin invariance of the exact geometry (issue 48, figure 1 and 2).

The same occupancy grid is planned at resolution 1 with origin (0, 0) and again at
resolutions 0.05 (ROS map_server's default), 0.1 and 0.37 with shifted origins. Every
answer must be the same: reachable or not, the path's validity, and its length divided by
the resolution (to 1e-9 relative). Queries put their end points inside cells, on cell edges
and on cell corners, on rooms, maze, random and city maps drawn for this script.

Counted per resolution, against the resolution-1 answer:

* ``differ``: a different verdict or a length off by more than 1e-9 relative;
* ``false unreachable``: ``visibility`` says unreachable where A* (at any resolution) found a path;
* ``roadmap errors``: the general encoding's roadmap raises where visibility finds a path;
* ``bad valid``: ``validate_path`` accepts a path that the exact rational check of
  ``benchmarks/independent_check.py`` rejects (shares no code with optplan's rule).

    python benchmarks/resolution_invariance.py                 # 1,200 queries, seeds 1000..
    python benchmarks/resolution_invariance.py --seed0 0 --maps 4 --queries 10   # quick
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

import optplan as op
from optplan.errors import InfeasibleQueryError
from optplan.worldgen.maps import generate_map

sys.path.insert(0, str(Path(__file__).resolve().parent))
from independent_check import grid_path_collides  # noqa: E402  (exact rational check, no optplan geometry)

RESOLUTIONS = ((0.05, (-10.0, -10.0)), (0.1, (3.3, -2.7)), (0.37, (-0.123, 5.55)))
KINDS = ("rooms", "maze", "random", "city")
POINT_KINDS = ("interior", "edge", "corner")


def _endpoint(rng: np.random.Generator, occ: np.ndarray, kind: str) -> np.ndarray:
    """A point (grid units) in or on a free cell: inside it, on one of its edges, or at a corner."""
    iy, ix = np.argwhere(~occ)[rng.integers(int((~occ).sum()))]
    p = np.array([ix, iy], float)
    if kind == "interior":
        return p + rng.uniform(0.05, 0.95, 2)
    if kind == "edge":
        side = rng.integers(4)
        t = rng.uniform(0.05, 0.95)
        return p + [(t, 0.0), (t, 1.0), (0.0, t), (1.0, t)][side]
    return p + rng.integers(0, 2, 2)


def _answer(fn):
    try:
        res = fn()
    except InfeasibleQueryError as exc:
        return ("none", str(exc).split(":")[0])
    return ("path", res)


def run(seed0: int, n_maps: int, n_queries: int, size: int, general: bool) -> dict:
    rows = {name: dict(queries=0, differ=0, false_unreachable=0, roadmap_errors=0, bad_valid=0, examples=[])
            for name in ["1.0"] + [f"{r:g}" for r, _ in RESOLUTIONS]}
    for m in range(n_maps):
        kind = KINDS[m % len(KINDS)]
        seed = seed0 + m
        base = generate_map(kind, size, seed)
        rng = np.random.default_rng(seed)
        grids = [("1.0", base)] + [(f"{r:g}", op.GridMap(base.occ, r, o)) for r, o in RESOLUTIONS]
        for q in range(n_queries):
            ks, kg = rng.choice(POINT_KINDS, 2)
            s, g = _endpoint(rng, base.occ, ks), _endpoint(rng, base.occ, kg)
            answers = {}
            for name, grid in grids:
                res = grid.resolution
                S, G = grid.to_world(s), grid.to_world(g)
                row = rows[name]
                row["queries"] += 1
                astar = _answer(lambda: op.shortest_path(grid, S, G, method="astar"))
                vis = _answer(lambda: op.shortest_path(grid, S, G, method="visibility"))
                summary = []
                for tag, a in (("astar", astar), ("visibility", vis)):
                    if a[0] == "none":
                        summary.append((tag, "none", a[1]))
                        continue
                    path = np.asarray(a[1].path)
                    ok = bool(op.validate_path(grid, path))
                    if ok and grid_path_collides(grid.occ, res, grid.origin, path):
                        row["bad_valid"] += 1
                    summary.append((tag, "path", round(a[1].length / res, 6), ok))
                if vis[0] == "none" and astar[0] == "path":
                    row["false_unreachable"] += 1
                    row["examples"].append((kind, seed, s.tolist(), g.tolist(), "visibility unreachable"))
                if general and vis[0] == "path":
                    try:
                        op.plan(grid, S, G, algorithm="pso", encoding="general", max_evals=300, iters=None,
                                pop=10, seed=0)
                    except InfeasibleQueryError as exc:
                        row["roadmap_errors"] += 1
                        row["examples"].append((kind, seed, s.tolist(), g.tolist(), f"general: {exc}"))
                    except Exception as exc:  # an internal error is a roadmap error too
                        row["roadmap_errors"] += 1
                        row["examples"].append((kind, seed, s.tolist(), g.tolist(), f"general: {exc!r}"))
                answers[name] = summary
            ref = answers["1.0"]
            for name, summ in answers.items():
                if name == "1.0":
                    continue
                same = len(summ) == len(ref) and all(
                    a[:2] == b[:2] and (a[1] != "path" or (abs(a[2] - b[2]) <= 1e-9 * max(1.0, b[2]) + 1e-6
                                                         and a[3] == b[3]))
                    for a, b in zip(summ, ref))
                if not same:
                    rows[name]["differ"] += 1
                    rows[name]["examples"].append((kind, seed, s.tolist(), g.tolist(), f"{summ} vs {ref}"))
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed0", type=int, default=1000, help="first map seed (1000.. were not used in development)")
    ap.add_argument("--maps", type=int, default=40)
    ap.add_argument("--queries", type=int, default=30, help="queries per map")
    ap.add_argument("--size", type=int, default=32)
    ap.add_argument("--general", action="store_true", help="also build the general encoding's roadmap per query")
    ap.add_argument("--examples", type=int, default=3, help="failing queries printed per resolution")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    rows = run(args.seed0, args.maps, args.queries, args.size, args.general)
    print(f"{args.maps} maps ({', '.join(KINDS)}), {args.size}x{args.size}, {args.queries} queries each, "
          f"seeds {args.seed0}..{args.seed0 + args.maps - 1}, {time.perf_counter() - t0:.0f} s")
    print(f"{'resolution':>10} {'queries':>8} {'differ':>7} {'false unreach.':>15} {'roadmap err.':>13} {'bad valid':>10}")
    for name, r in rows.items():
        print(f"{name:>10} {r['queries']:>8} {r['differ']:>7} {r['false_unreachable']:>15} "
              f"{r['roadmap_errors'] if args.general else '-':>13} {r['bad_valid']:>10}")
    for name, r in rows.items():
        for ex in r["examples"][: args.examples]:
            print(f"  {name}: {ex}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
