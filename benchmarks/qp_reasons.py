"""Why qp-dwa's QP result is or is not commanded (issue 30 item 6): the ``info["qp"]`` of every
step where the QP stage was reached, counted over clutter worlds and the shipped dynamic
scenarios, with the share used / active (active = the QP ran: neither "inactive" nor
"path sample"), and how many of the used results differ from the sampled command by more than
``CHANGED`` (a solved QP whose optimum is the sample itself is "used" but changes nothing).

    python benchmarks/qp_reasons.py --clutter-seeds 0:10 --dynamic-seed 0
    python benchmarks/qp_reasons.py --family clutter-movers --clutter-seeds 0:10 --dynamic-seed -1 \
        --params '{"qp_passes": 3}'
"""
from __future__ import annotations

import argparse
import json
from collections import Counter

from optplan.local.qp_dwa import qp_outcome
from optplan.sim.closed_loop import scenario_for, simulate
from optplan.sim.experiments import plan_global
from optplan.worldgen.clutter import family_options

CHANGED = 1e-3  # m/s or rad/s
DYNAMIC = ["hou2024_dynamic1", "hou2024_dynamic2", "hou2024_dynamic3", "hou2024_dynamic4", "li2023_exp2_2",
           "li2023_exp2_3", "li2023_exp2_4", "li2023_exp2_5", "yang2023_idwa_crossing", "yang2023_fusion"]


def reasons(scenario, seed: int, global_plan=None, params: dict | None = None) -> tuple[Counter, Counter, str]:
    """One qp-dwa run: counts of ``info["qp"]``, counts of the outcomes (``qp_outcome``, plus
    ``"changed"``: used results that moved the command by more than ``CHANGED``), its status."""
    statuses: Counter = Counter()
    outcomes: Counter = Counter()

    def count(t, state, info):
        step = info["command"].info
        outcome = qp_outcome(step)
        if outcome is not None:
            statuses[step["qp"]] += 1
            outcomes[outcome] += 1
            if outcome == "used" and step.get("qp_change", 0.0) > CHANGED:
                outcomes["changed"] += 1

    opts = {"planner_params": params} if params else {}
    res = simulate(scenario, global_planner="astar", local_planner="qp-dwa", seed=seed, global_plan=global_plan,
                   progress=count, **opts)
    return statuses, outcomes, res.status


def table(title: str, statuses: Counter, outcomes: Counter) -> str:
    used, changed = outcomes["used"], outcomes["changed"]
    total = used + outcomes["fallback"]  # the steps where the QP ran
    lines = [f"{title}: QP used in {used} of {total} active steps ({100 * used / max(total, 1):.1f} %); "
             f"it changed the command by more than {CHANGED:g} in {changed} ({100 * changed / max(total, 1):.1f} % "
             "of active steps)",
             "| info[\"qp\"] | steps |", "|---|---|"]
    lines += [f"| {k} | {v} |" for k, v in statuses.most_common()]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--clutter-seeds", default="0:10", help="A:B, or empty for none")
    ap.add_argument("--family", default="clutter", choices=("clutter", "clutter-movers"),
                    help="the generated worlds of --clutter-seeds")
    ap.add_argument("--params", default="", help="JSON planner_params for qp-dwa on top of the family's")
    ap.add_argument("--dynamic-seed", type=int, default=0, help="-1 for none")
    a = ap.parse_args(argv)
    extra = json.loads(a.params) if a.params else {}
    if a.clutter_seeds:
        lo, hi = (int(x) for x in a.clutter_seeds.split(":"))
        statuses: Counter = Counter()
        outcomes: Counter = Counter()
        fam = family_options(a.family)
        params = extra
        for seed in range(lo, hi):
            sc = scenario_for(a.family, seed)
            gp = plan_global(sc, "astar", None, seed, fam.get("global_options"))
            st, oc, status = reasons(sc, seed, gp, params)
            statuses += st
            outcomes += oc
            print(f"{a.family} {seed}: {status}", flush=True)
        print(table(f"{a.family} seeds {lo}..{hi - 1}", statuses, outcomes))
    if a.dynamic_seed >= 0:
        statuses, outcomes = Counter(), Counter()
        for name in DYNAMIC:
            st, oc, status = reasons(name, a.dynamic_seed, params=extra or None)
            statuses += st
            outcomes += oc
            print(f"{name} {a.dynamic_seed}: {status}", flush=True)
        print(table(f"dynamic scenarios seed {a.dynamic_seed}", statuses, outcomes))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
