"""The general encoding on large maps (issue 43 item 3): cold and warm plans, memory, gap.

    python benchmarks/general_scale.py [--sizes 256 512] [--kinds city random maze rooms dao] [--seeds 2]

Each case runs in a fresh child process (nothing cached, modules imported before the clock
starts) and reports:

* ``cold``: ``op.plan(grid, s, g, algorithm="msiar-gwo", encoding="general", max_evals=3000)``,
  every per-map and per-query set-up included (the issue's target: <= 3 s on 256x256);
* ``warm``: the same query again with another seed (target <= 1 s), and ``new query``: another
  start and goal on the same map (the per-map graph kept, the per-query rows built);
* ``peak MB``: growth of the process's peak resident memory over the two plans (<= 1 GB);
* ``graph``: which leg tables the encoding used (``exact``: all-pairs over every corner;
  ``local``: the local graph and landmarks, :class:`optplan.formulations.encodings._LandmarkLegs`),
  with the number of convex corners;
* ``gap``: the cold plan's length over the exact any-angle optimum
  (``op.shortest_path(..., method="visibility")``, timed apart as ``exact s``).

Maps: seeded generated maps (``optplan.worldgen.maps.generate_map``; ``random`` has 20 %
blocked cells) at seeds 7300+ (held out: not used while the local graph was written, which
used seed 7100), and two Moving AI DAO maps shipped in ``benchmarks/data`` (den520d,
257x256, and brc202d, 481x530; Sturtevant 2012, Open Data Commons Attribution License),
queried at the same seeds.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

KINDS = ("city", "random", "maze", "rooms", "dao")
DAO = {256: "den520d.map", 512: "brc202d.map"}
SEED0 = 7300

CHILD = r"""
import json, sys, time
import numpy as np
import optplan as op
from optplan.worldgen.maps import generate_map, map_query

kind, n, seed, path = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]

def hwm():
    for line in open("/proc/self/status"):
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024.0

if kind == "dao":
    grid = op.load_map(path)
else:
    grid = generate_map(kind, n, seed=seed, **({"density": 0.2} if kind == "random" else {}))
s, g = map_query(grid, seed=seed)
from optplan.world.roadmap import corner_count
corners = corner_count(grid)
base = hwm()
out = {"corners": corners}
try:
    t = time.perf_counter()
    r = op.plan(grid, s, g, algorithm="msiar-gwo", encoding="general", max_evals=3000, seed=1)
    out["cold"] = time.perf_counter() - t
    t = time.perf_counter()
    op.plan(grid, s, g, algorithm="msiar-gwo", encoding="general", max_evals=3000, seed=2)
    out["warm"] = time.perf_counter() - t
    s2, g2 = map_query(grid, seed=seed + 1000)     # another query on the same map: per-map tables kept
    t = time.perf_counter()
    op.plan(grid, s2, g2, algorithm="msiar-gwo", encoding="general", max_evals=3000, seed=3)
    out["warm_new"] = time.perf_counter() - t
    out["peak"] = hwm() - base
    out["length"], out["feasible"] = float(r.length), bool(r.feasible)
    from optplan.formulations.encodings import _legs_of
    out["graph"] = "exact" if _legs_of(grid, s, g, 0.0).exact else "local"
    t = time.perf_counter()
    ex = op.shortest_path(grid, s, g, method="visibility")
    out["exact_s"] = time.perf_counter() - t
    out["exact"] = float(ex.length)
except op.errors.InfeasibleQueryError as e:
    out["error"] = "unreachable: " + str(e)[:60]
print(json.dumps(out))
"""


def run_case(kind: str, n: int, seed: int) -> dict:
    path = str(Path(__file__).parent / "data" / DAO.get(n, "")) if kind == "dao" else ""
    proc = subprocess.run([sys.executable, "-c", CHILD, kind, str(n), str(seed), path],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        return {"error": proc.stderr.strip().splitlines()[-1][:80]}
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", nargs="+", type=int, default=[256, 512])
    ap.add_argument("--kinds", nargs="+", default=list(KINDS), choices=KINDS)
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--seed0", type=int, default=SEED0)
    a = ap.parse_args(argv)
    print("| map | size | seed | corners | graph | cold s | warm s | new query s | peak MB | length | exact | gap % "
          "| exact s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n in a.sizes:
        for kind in a.kinds:
            if kind == "dao" and n not in DAO:
                continue
            for seed in range(a.seed0, a.seed0 + a.seeds):
                r = run_case(kind, n, seed)
                name = DAO[n] if kind == "dao" else kind
                if "error" in r:
                    print(f"| {name} | {n} | {seed} | {r.get('corners', '')} | - | {r['error']} | | | | | | | |", flush=True)
                    continue
                gap = 100.0 * (r["length"] / r["exact"] - 1.0)
                print(f"| {name} | {n} | {seed} | {r['corners']} | {r['graph']} | {r['cold']:.2f} | {r['warm']:.2f} | "
                      f"{r['warm_new']:.2f} | "
                      f"{r['peak']:.0f} | {r['length']:.2f} | {r['exact']:.2f} | {gap:.2f} | {r['exact_s']:.2f} |",
                      flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
