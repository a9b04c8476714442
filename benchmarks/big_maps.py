"""Peak memory and time of planning on big maps (issue 48, "memory proportional to the path").

Each case runs in a fresh Python process, so its peak resident memory (``ru_maxrss``,
interpreter and imports included, ~150 MB) is its own. Maps:

* ``empty``: every cell free, the query corner to corner (cell centres);
* ``building``: a ROS-style floor plan at 0.05 m (origin (-50, -50) m): rooms of 4-8 m
  behind 0.15 m walls with 0.9 m doors, a 2 m corridor every few rooms, written as a
  map_server ``.yaml`` + ``.pgm`` and read back with ``op.load_map``; the query joins two
  far rooms.

Methods: ``astar`` and ``visibility`` through ``op.plan`` (default metrics, so the exact
clearance of the path is computed), and one swarm (``gwo``, 300 evaluations, default encoding).
Issue 48's targets: A* on an empty 4000x4000 map <= 1 GB and <= 10 s; the 4000x4000 building
map loads, plans (astar, visibility) and validates in <= 2 GB.

    python benchmarks/big_maps.py                       # sizes 1000 2000 4000
    python benchmarks/big_maps.py --sizes 1000 --methods astar
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

CHILD = r"""
import json, resource, sys, time
import numpy as np
import optplan as op
sys.path.insert(0, {bench!r})
from big_maps import building, query
kind, n, method, folder = {kind!r}, {n}, {method!r}, {folder!r}
t0 = time.perf_counter()
if kind == "empty":
    grid = op.GridMap(np.zeros((n, n), bool))
else:
    grid = op.load_map(building(n, folder))
t_load = time.perf_counter() - t0
start, goal = query(grid, kind)
t1 = time.perf_counter()
opts = dict(max_evals=300, iters=None, pop=20, seed=0) if method not in ("astar", "visibility") else {{}}
res = op.plan(grid, start, goal, algorithm=method, **opts)
t_plan = time.perf_counter() - t1
ok = bool(op.validate_path(grid, res.path))
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
print(json.dumps(dict(load_s=t_load, plan_s=t_plan, peak_mb=peak, feasible=bool(res.feasible), valid=ok,
                      length=res.length, clearance=res.min_clearance)))
"""


def building(n: int, folder: str, resolution: float = 0.05, seed: int = 7) -> str:
    """Write a ROS-style ``n x n`` floor plan (map_server yaml + pgm) into ``folder``; its path."""
    rng = np.random.default_rng(seed)
    occ = np.zeros((n, n), bool)
    wall = max(1, round(0.15 / resolution))
    door = max(2, round(0.9 / resolution))
    corridor = max(3, round(2.0 / resolution))
    lines = []
    pos = 0
    while pos < n:
        lines.append(pos)
        pos += int(rng.integers(round(4 / resolution), round(8 / resolution)))
    for axis in (0, 1):
        for k, p in enumerate(lines):
            sl = slice(p, min(p + wall, n))
            if axis == 0:
                occ[sl, :] = True
            else:
                occ[:, sl] = True
    # doors in every wall piece between two crossings, and a corridor every third line
    for axis in (0, 1):
        for k, p in enumerate(lines):
            for a, b in zip(lines[:-1], lines[1:]):
                lo, hi = a + wall + 1, b - door - 1
                if hi <= lo:
                    continue
                c = int(rng.integers(lo, hi))
                if axis == 0:
                    occ[p:p + wall, c:c + door] = False
                else:
                    occ[c:c + door, p:p + wall] = False
            if k % 3 == 1:
                sl = slice(p + wall, min(p + wall + corridor, n))
                if axis == 0:
                    occ[sl, :] = False
                else:
                    occ[:, sl] = False
    occ[:, :wall] = occ[:, -wall:] = True
    occ[:wall, :] = occ[-wall:, :] = True
    folder = Path(folder)
    pgm = folder / f"building{n}.pgm"
    img = np.where(occ[::-1], 0, 254).astype(np.uint8)
    with open(pgm, "wb") as fh:
        fh.write(f"P5\n{n} {n}\n255\n".encode())
        fh.write(img.tobytes())
    yml = folder / f"building{n}.yaml"
    yml.write_text(f"image: {pgm.name}\nresolution: {resolution}\norigin: [-50.0, -50.0, 0.0]\n"
                   "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")
    return str(yml)


def query(grid, kind: str):
    """Corner to corner for the empty map; two far free cells (seeded) for the building."""
    if kind == "empty":
        return grid.to_world(np.array([0.5, 0.5])), grid.to_world(np.array([grid.width - 0.5, grid.height - 0.5]))
    free = np.argwhere(~grid.occ)
    rng = np.random.default_rng(0)
    best = None
    for _ in range(200):
        a, b = free[rng.integers(len(free), size=2)]
        d = np.abs(a - b).sum()
        if best is None or d > best[0]:
            best = (d, a, b)
    _, a, b = best
    return grid.to_world(a[::-1] + 0.5), grid.to_world(b[::-1] + 0.5)


def run_case(kind: str, n: int, method: str, folder: str, timeout: float) -> dict:
    code = CHILD.format(bench=str(Path(__file__).resolve().parent), kind=kind, n=n, method=method, folder=folder)
    t0 = time.perf_counter()
    try:
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(error=f"> {timeout:.0f} s")
    if out.returncode != 0:
        last = (out.stderr.strip().splitlines() or ["?"])[-1]
        return dict(error=last[:120], wall_s=time.perf_counter() - t0)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[1000, 2000, 4000])
    ap.add_argument("--kinds", nargs="+", default=["empty", "building"])
    ap.add_argument("--methods", nargs="+", default=["astar", "visibility", "gwo"])
    ap.add_argument("--timeout", type=float, default=300.0)
    args = ap.parse_args(argv)
    print(f"{'map':>9} {'cells':>6} {'method':>10} {'load s':>7} {'plan s':>7} {'peak MB':>8} "
          f"{'feasible':>8} {'valid':>6} {'length m':>10}")
    with tempfile.TemporaryDirectory() as folder:
        for kind in args.kinds:
            for n in args.sizes:
                for method in args.methods:
                    r = run_case(kind, n, method, folder, args.timeout)
                    if "error" in r:
                        print(f"{kind:>9} {n:>6} {method:>10}  failed: {r['error']}", flush=True)
                        continue
                    print(f"{kind:>9} {n:>6} {method:>10} {r['load_s']:>7.2f} {r['plan_s']:>7.2f} "
                          f"{r['peak_mb']:>8.0f} {str(r['feasible']):>8} {str(r['valid']):>6} "
                          f"{r['length']:>10.2f}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
