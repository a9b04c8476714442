"""Why qp-dwa's QP result is or is not commanded (issue 30 item 6): the ``info["qp"]`` of every
step where the QP stage was reached, counted over clutter worlds and the shipped dynamic
scenarios, with the share used / active (active = the QP ran: neither "inactive" nor
"path sample"), and how many of the used results differ from the sampled command by more than
``CHANGED`` (a solved QP whose optimum is the sample itself is "used" but changes nothing).

    python benchmarks/qp_reasons.py --clutter-seeds 0:10 --dynamic-seed 0
"""
from __future__ import annotations

import argparse
from collections import Counter

from optplan.sim.closed_loop import scenario_for, simulate
from optplan.sim.experiments import plan_global
from optplan.worldgen.clutter import family_options

CHANGED = 1e-3  # m/s or rad/s
DYNAMIC = ["hou2024_dynamic1", "hou2024_dynamic2", "hou2024_dynamic3", "hou2024_dynamic4", "li2023_exp2_2",
           "li2023_exp2_3", "li2023_exp2_4", "li2023_exp2_5", "yang2023_idwa_crossing", "yang2023_fusion"]


def reasons(scenario, seed: int, global_plan=None, params: dict | None = None) -> tuple[Counter, str]:
    """``info["qp"]`` counts of one qp-dwa run and its status."""
    seen: Counter = Counter()

    def count(t, state, info):
        status = info["command"].info.get("qp")
        if status is not None:
            seen[status] += 1
            if status == "solved" and info["command"].info.get("qp_change", 0.0) > CHANGED:
                seen["(of solved: changed the command)"] += 1

    opts = {"planner_params": params} if params else {}
    res = simulate(scenario, global_planner="astar", local_planner="qp-dwa", seed=seed, global_plan=global_plan,
                   progress=count, **opts)
    return seen, res.status


def table(title: str, seen: Counter) -> str:
    changed = seen.get("(of solved: changed the command)", 0)
    active = {k: v for k, v in seen.items() if k not in ("inactive", "path sample", "(of solved: changed the command)")}
    used = sum(v for k, v in active.items() if k.startswith("solved"))
    total = sum(active.values())
    lines = [f"{title}: QP used in {used} of {total} active steps ({100 * used / max(total, 1):.1f} %); "
             f"it changed the command by more than {CHANGED:g} in {changed} ({100 * changed / max(total, 1):.1f} % "
             "of active steps)",
             "| info[\"qp\"] | steps |", "|---|---|"]
    lines += [f"| {k} | {v} |" for k, v in seen.most_common()]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--clutter-seeds", default="0:10", help="A:B, or empty for none")
    ap.add_argument("--dynamic-seed", type=int, default=0, help="-1 for none")
    a = ap.parse_args(argv)
    if a.clutter_seeds:
        lo, hi = (int(x) for x in a.clutter_seeds.split(":"))
        total: Counter = Counter()
        fam = family_options("clutter")
        for seed in range(lo, hi):
            sc = scenario_for("clutter", seed)
            gp = plan_global(sc, "astar", None, seed, fam.get("global_options"))
            seen, status = reasons(sc, seed, gp, fam.get("local_params", {}).get("qp-dwa"))
            total += seen
            print(f"clutter {seed}: {status}", flush=True)
        print(table(f"clutter seeds {lo}..{hi - 1}", total))
    if a.dynamic_seed >= 0:
        total = Counter()
        for name in DYNAMIC:
            seen, status = reasons(name, a.dynamic_seed)
            total += seen
            print(f"{name} {a.dynamic_seed}: {status}", flush=True)
        print(table(f"dynamic scenarios seed {a.dynamic_seed}", total))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
