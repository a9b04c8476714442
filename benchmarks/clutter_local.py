"""Local planners in seeded BARN-style clutter (issue 27): success, collisions, timeouts,
stuck runs, mean time, BARN score and the QP share of qp-dwa, per preset.

Every world is ``op.simulate("clutter", seed=N)`` (or ``"clutter-movers"``: two movers,
r 0.15 m, 0.2-0.4 m/s, 1.5-3 m tracks across the path), the robot of issue 27 (r 0.2 m,
v_max 0.5, w_max 90 deg/s, a_max 1, alpha_max 180 deg/s^2, 2.5 m sensor, dt 0.1), A*
global path, goal within 1 m in 100 s. For one world the global plan is made once and
shared by every planner.

``--nav own`` runs each preset with its paper's navigation policy (subgoal strategy and
reaction to blocked paths, ``PRESET_DEFAULTS``); ``--nav shared`` runs every preset under
qp-dwa's navigation layer (key points, exact re-plan, the same stuck recovery), so the
local planner's share and the navigation layer's share of a lead are both visible.

Runs are appended to ``--out`` (JSON lines) as they finish and skipped when already
there, so a long measurement can be stopped and resumed; the table is printed from the
file. Development seeds were 0-49; report held-out seeds (e.g. ``--seeds 1000:1300``).

    python benchmarks/clutter_local.py --family clutter --seeds 1000:1300 --planners qp-dwa \\
        --out /tmp/clutter.jsonl --workers 2
"""
from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

import numpy as np

SHARED_NAV = {"subgoals": "key_points", "on_blocked": "replan"}  # qp-dwa's policy (PRESET_DEFAULTS)


def run_world(task: tuple[str, int, tuple[str, ...], str, dict]) -> list[dict]:
    """Every planner on one generated world: one row per run."""
    from optplan.sim.closed_loop import scenario_for, simulate
    from optplan.sim.experiments import barn_score, optimal_time, plan_global
    from optplan.solvers.graph import shortest_path
    from optplan.local.qp_dwa import qp_outcome
    from optplan.worldgen.clutter import family_options

    family, seed, planners, nav, qp_params = task
    sc = scenario_for(family, seed)
    gp = plan_global(sc, "astar", None, seed, family_options(family).get("global_options"))
    # OT: the shortest route the footprint has, whatever the global planner preferred
    ot = optimal_time(shortest_path(sc.world, sc.start[:2], sc.goal, method="astar", clearance=sc.robot.radius),
                      sc.robot)
    rows = []
    for planner in planners:
        qp: dict[str, int] = {}
        reasons: dict[str, int] = {}

        def count(t, state, info, qp=qp, reasons=reasons):
            key = qp_outcome(info["command"].info)
            if key is not None:
                qp[key] = qp.get(key, 0) + 1
                status = info["command"].info["qp"]
                reasons[status] = reasons.get(status, 0) + 1

        opts = dict(SHARED_NAV) if nav == "shared" else {}
        # each preset's defaults (qp-dwa's clutter mechanisms apply where its path is tight)
        params = qp_params if planner == "qp-dwa" else {}
        if params:
            opts["planner_params"] = params
        res = simulate(sc, global_planner="astar", local_planner=planner, seed=seed, global_plan=gp, progress=count,
                       **opts)
        rows.append({"family": family, "seed": seed, "planner": planner, "nav": nav, "status": res.status,
                     "reached": res.reached, "collisions": res.collisions, "time_s": res.time_s,
                     "path_length": res.path_length, "min_clearance": res.min_clearance,
                     "max_abs_accel": res.max_abs_accel, "max_abs_ang_accel": res.max_abs_ang_accel,
                     "mean_step_ms": res.mean_step_ms, "ot": ot, "barn": barn_score(res, ot), "replans": res.replans,
                     "qp_used": qp.get("used", 0), "qp_fallback": qp.get("fallback", 0),
                     "qp_not_run": qp.get("not run", 0), "qp_reasons": reasons, "a_max": sc.robot.a_max,
                     "alpha_max": sc.robot.alpha_max})
    return rows


def table(rows: list[dict]) -> str:
    """Markdown table: one row per family, navigation policy and planner."""
    out = ["| worlds | nav | local planner | runs | success [%] | with collision | timeouts | stuck | "
           "mean time [s] | BARN score | QP used / active | accel limits held |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    keys = sorted({(r["family"], r["nav"], r["planner"]) for r in rows})
    for fam, nav, planner in keys:
        rs = [r for r in rows if (r["family"], r["nav"], r["planner"]) == (fam, nav, planner)]
        ok = [r for r in rs if r["reached"] and r["collisions"] == 0]
        n = len(rs)
        used = sum(r["qp_used"] for r in rs)
        active = used + sum(r["qp_fallback"] for r in rs)
        share = f"{100 * used / active:.1f} % of {active}" if active else "-"
        held = sum(r["max_abs_accel"] <= r["a_max"] * (1 + 1e-6) and r["max_abs_ang_accel"] <= r["alpha_max"] * (1 + 1e-6)
                   for r in rs)
        t = np.mean([r["time_s"] for r in ok]) if ok else float("nan")
        out.append(f"| {fam} | {nav} | {planner} | {n} | {100 * len(ok) / n:.1f} | "
                   f"{sum(r['collisions'] > 0 for r in rs)} | {sum(r['status'] == 'timeout' for r in rs)} | "
                   f"{sum(r['status'] == 'stuck' for r in rs)} | {t:.1f} | {np.mean([r['barn'] for r in rs]):.3f} | "
                   f"{share} | {held}/{n} |")
    out += ["", "success = goal reached within 1 m in 100 s with no collision; mean time over successful runs; "
                "BARN score = mean of 1{success} OT / clip(time, 2 OT, 8 OT), OT = A* path length / v_max "
                "(at most 0.5); QP used = steps whose QP result was commanded, of the steps where the QP ran "
                "(not \"inactive\" or \"path sample\")."]
    return "\n".join(out)


def reason_table(rows: list[dict]) -> str:
    """Markdown table of qp-dwa's ``info["qp"]`` (why its QP result was or was not commanded)
    summed over the runs that recorded it; empty when none did."""
    total: dict[str, int] = {}
    for r in rows:
        for k, v in r.get("qp_reasons", {}).items():
            total[k] = total.get(k, 0) + v
    if not total:
        return ""
    out = ["| qp-dwa info[\"qp\"] | steps |", "|---|---|"]
    out += [f"| {k} | {v} |" for k, v in sorted(total.items(), key=lambda kv: -kv[1])]
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--family", default="clutter", help="clutter, clutter-movers or both")
    ap.add_argument("--seeds", default="1000:1300", help="A:B (seeds A..B-1)")
    ap.add_argument("--planners", default="qp-dwa,dwa,missa-dwa,idwa,ba-dwa,iga-dwa")
    ap.add_argument("--nav", default="own", choices=("own", "shared", "both"))
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--out", default="", help="JSON lines file to append to / resume from")
    ap.add_argument("--table-only", action="store_true", help="print the table of --out and exit")
    ap.add_argument("--qp-dwa-params", default="", help="JSON planner_params for qp-dwa, e.g. issue 27's "
                    '\'{"qp_committed": true, "continuation_check": true, "path_progress": {"within_travel": true}}\'')
    a = ap.parse_args(argv)
    lo, hi = (int(x) for x in a.seeds.split(":"))
    families = ["clutter", "clutter-movers"] if a.family == "both" else [a.family]
    navs = ["own", "shared"] if a.nav == "both" else [a.nav]
    planners = tuple(p.strip() for p in a.planners.split(",") if p.strip())
    rows: list[dict] = []
    path = Path(a.out) if a.out else None
    if path is not None and path.exists():
        rows = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    if not a.table_only:
        done = {(r["family"], r["seed"], r["planner"], r["nav"]) for r in rows}
        tasks = []
        for fam in families:
            for nav in navs:
                for seed in range(lo, hi):
                    todo = tuple(p for p in planners if (fam, seed, p, nav) not in done)
                    if todo:
                        tasks.append((fam, seed, todo, nav, json.loads(a.qp_dwa_params or "{}")))
        sink = path.open("a") if path is not None else None
        if a.workers > 1:
            import multiprocessing as mp

            pool = mp.get_context("fork").Pool(a.workers)
            results = pool.imap_unordered(run_world, tasks)
        else:
            pool, results = None, map(run_world, tasks)
        for k, new in enumerate(results):
            rows += new
            if sink is not None:
                sink.write("".join(json.dumps(r) + "\n" for r in new))
                sink.flush()
            print(f"\r{k + 1}/{len(tasks)} worlds", end="", file=sys.stderr, flush=True)
        print(file=sys.stderr)
        if pool is not None:
            pool.close()
    wanted = [r for r in rows if r["family"] in families and lo <= r["seed"] < hi and r["planner"] in planners
              and r["nav"] in navs]
    print(f"seeds {lo}..{hi - 1}; {os.cpu_count()} CPUs (shared: times are simulated seconds, not wall clock)")
    print(table(wanted))
    reasons = reason_table([r for r in wanted if r["planner"] == "qp-dwa"])
    if reasons:
        print("\n" + reasons)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
