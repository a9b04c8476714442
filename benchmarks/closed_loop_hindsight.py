"""Which closed-loop runs were avoidable in hindsight (issue 6 reference figure).

    python benchmarks/closed_loop_hindsight.py [SCENARIO ...] [--seeds 0 50] [--margin 0.0]
        [--workers 2] [--db dynamic.sqlite]

For every scenario and seed the world the run met is rebuilt (A* global path, random
obstacles and movers of the seed, as in ``benchmarks/dynamic_qp_dwa.yaml``), and
``optplan.sim.hindsight.hindsight_profile`` searches, with the movers' whole future
known, for a forward speed profile along the A* path of the true map (unknown obstacles
included) that reaches the goal without contact. The table gives per scenario how many
runs have such a profile and its mean earliest arrival.

With ``--db`` (a results database of ``optplan bench``) the closed-loop planners' runs
of the same scenarios and seeds are set next to it: their successes, their failures
that were avoidable in hindsight, and their mean time over successful runs against the
hindsight arrival of the same runs (the hindsight profile skips the turns at the
path's corners, so part of that ratio is not lost time). Without scenario names the ten
dynamic scenarios of ``benchmarks/dynamic_qp_dwa.yaml`` are used.

"Not avoidable" means only that no forward profile along that one path exists; a
planner may still succeed by leaving the path (``optplan/sim/hindsight.py``).
"""
from __future__ import annotations

import argparse
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import yaml

from optplan.nav.navigator import Navigator
from optplan.sim.closed_loop import realized_scenario
from optplan.sim.experiments import plan_global
from optplan.sim.hindsight import hindsight_profile
from optplan.world.scenario import load_scenario

SPEC = Path(__file__).with_name("dynamic_qp_dwa.yaml")


def one(job: tuple[str, int, float]) -> tuple[str, int, bool, float | None]:
    name, seed, margin = job
    sc = load_scenario(name)
    world = realized_scenario(sc, seed, plan_global(sc, "astar", None, seed))
    nav = Navigator(world.true_world(), world.robot, world.start[:2], world.goal)
    nav.plan_initial()
    prof = hindsight_profile(world, nav.path, margin=margin)
    return name, seed, prof.feasible, prof.time_s


def planner_rows(db: str, names: list[str], seeds: range) -> dict[str, dict[tuple[str, int], dict]]:
    """``{local planner: {(scenario, seed): row}}`` of the closed-loop runs stored in ``db``."""
    from optplan.bench.store import ResultStore

    out: dict[str, dict[tuple[str, int], dict]] = {}
    for row in ResultStore(db).rows().values():
        if row["kind"] != "simulate" or row["status"] != "ok" or row["target"] not in names:
            continue
        if int(row["seed"]) in seeds:
            out.setdefault(row["local_planner"], {})[(row["target"], int(row["seed"]))] = row
    return dict(sorted(out.items()))


def avoidable_failures(rows: dict, runs: list, found: dict) -> int:
    """How many of ``runs`` the planner of ``rows`` failed although a hindsight profile exists."""
    return sum(1 for r in runs if r in rows and not int(rows[r]["success"]) and found[r][0])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenarios", nargs="*", help="scenario names or files (default: those of dynamic_qp_dwa.yaml)")
    ap.add_argument("--seeds", nargs=2, type=int, default=(0, 50), metavar=("FIRST", "STOP"))
    ap.add_argument("--margin", type=float, default=0.0, help="extra clearance demanded from every mover, m")
    ap.add_argument("--workers", type=int, default=2, help="processes (1: in this process)")
    ap.add_argument("--db", help="results database of `optplan bench` to compare against")
    args = ap.parse_args(argv)
    names = args.scenarios or yaml.safe_load(SPEC.read_text())["scenarios"]
    seeds = range(*args.seeds)
    jobs = [(n, s, args.margin) for n in names for s in seeds]
    t0 = time.perf_counter()
    found = {}
    pool = ProcessPoolExecutor(max_workers=args.workers) if args.workers > 1 else None
    try:
        results = pool.map(one, jobs, chunksize=1) if pool else map(one, jobs)
        for i, (name, seed, ok, t) in enumerate(results, 1):
            found[(name, seed)] = (ok, t)
            print(f"\r  {i}/{len(jobs)} runs searched", end="", file=sys.stderr, flush=True)
    finally:
        if pool:
            pool.shutdown()
    print(f"\n  {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    planners = planner_rows(args.db, names, seeds) if args.db else {}

    head = "| scenario | runs | avoidable in hindsight | mean earliest arrival [s] |"
    rule = "|---|---|---|---|"
    for p in planners:
        head += f" {p}: avoidable failures |"
        rule += "---|"
    print(f"Hindsight profiles along the true map's A* path (margin {args.margin:g} m, seeds "
          f"{seeds.start}-{seeds.stop - 1})\n\n{head}\n{rule}")
    for name in names:
        runs = [r for r in found if r[0] == name]
        ok = [r for r in runs if found[r][0]]
        arrival = f"{np.mean([found[r][1] for r in ok]):.1f}" if ok else "-"
        cells = [str(avoidable_failures(rows, runs, found)) for rows in planners.values()]
        print(f"| {name} | {len(runs)} | {len(ok)} | {arrival} |" + "".join(f" {c} |" for c in cells))
    ok = [r for r in found if found[r][0]]
    arrival = f"{np.mean([found[r][1] for r in ok]):.1f}" if ok else "-"
    cells = [str(avoidable_failures(rows, list(found), found)) for rows in planners.values()]
    print(f"| **all** | {len(found)} | {len(ok)} | {arrival} |" + "".join(f" {c} |" for c in cells))
    if planners:
        print(f"\n| local planner | runs | success | failures | avoidable in hindsight | mean time / hindsight "
              f"arrival (successful runs) |\n|---|---|---|---|---|---|")
        for p, rows in planners.items():
            mine = [r for r in found if r in rows]
            won = [r for r in mine if int(rows[r]["success"])]
            lost = [r for r in mine if r not in won]
            both = [r for r in won if found[r][0]]
            ratio = f"{np.mean([float(rows[r]['time_s']) / found[r][1] for r in both]):.2f}" if both else "-"
            print(f"| {p} | {len(mine)} | {len(won)} | {len(lost)} | {avoidable_failures(rows, mine, found)} | {ratio} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
