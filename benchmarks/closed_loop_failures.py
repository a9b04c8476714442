"""Why closed-loop runs fail: one line per failed run, then a count per kind (issue 6).

    python benchmarks/closed_loop_failures.py li2023_exp2_2 hou2024_dynamic4 [--seeds 0 12]
        [--planner qp-dwa] [--params '{"horizon": 4.0}']

For each scenario and seed (A* global path, as in ``benchmarks/dynamic_qp_dwa.yaml``) the
run is simulated; a run that did not reach the goal without collision is explained by its
first collision, replayed on the realised scenario:

* ``moving into mover``: the robot drove at >= ``--moving`` m/s into a mover;
* ``hit while slow``: the robot was slower than that and the mover ran into it;
* ``... after a turn-round``: the mover's velocity reversed within the last 2 s, which
  a constant-velocity prediction cannot foresee;
* ``static``: the footprint touched a static obstacle (with the planner's mode then);
* ``stalled``: no collision, but the goal was not reached (timeout or stuck).

The counts say which behaviour to work on; the per-run lines give the time to look at
with ``optplan simulate SCENARIO --seed N --gif``.
"""
from __future__ import annotations

import argparse
import json
import sys
from collections import Counter

import numpy as np

from optplan.sim.closed_loop import realized_scenario, simulate
from optplan.sim.environment import SimEnvironment
from optplan.sim.experiments import plan_global
from optplan.world.scenario import load_scenario


def first_collision(res, env: SimEnvironment, radius: float):
    """``(kind, index, mover)`` of the first period in collision: ``"mover"`` with the mover
    index, ``"static"`` with ``None``, or ``None`` when the run had none."""
    traj = res.trajectory
    static_hit, _ = env.static_check(traj[:, 1:3])
    first_static = int(np.argmax(static_hit)) if static_hit.any() else len(traj)
    for k in range(min(first_static, len(traj) - 1) + 1):
        m = env.movers(traj[k, 0])
        if len(m):
            gap = np.hypot(m[:, 0] - traj[k, 1], m[:, 1] - traj[k, 2]) - m[:, 4] - radius
            if gap.min() < 0:
                return "mover", k, int(np.argmin(gap))
    return ("static", first_static, None) if first_static < len(traj) else None


def explain(sc, seed: int, planner: str, params: dict, moving: float) -> tuple[str, str] | None:
    """``(kind, line)`` for a failed run, ``None`` for a success."""
    gp = plan_global(sc, "astar", None, seed)
    modes: list = []
    res = simulate(sc, global_planner="astar", local_planner=planner, seed=seed, global_plan=gp,
                   planner_params=params, progress=lambda t, s, info: modes.append(info["command"].info.get("mode")))
    if res.reached and res.collisions == 0:
        return None
    env = SimEnvironment(realized_scenario(sc, seed, gp))
    hit = first_collision(res, env, sc.robot.radius)
    head = f"{sc.name} seed {seed}: {res.status}, {res.collisions} period(s) in collision"
    if hit is None:
        return "stalled", head
    kind, k, j = hit
    t, v = res.trajectory[k, 0], res.trajectory[k, 4]
    mode = modes[k] if k < len(modes) else "?"
    if kind == "static":
        return "static", f"{head}; static at t={t:.1f} s, v={v:.2f} m/s, mode {mode}"
    now, before = env.movers(t)[j], env.movers(max(t - 2.0, 0.0))[j]
    turned = float(np.dot(now[2:4], before[2:4])) < 0
    kind = ("moving into mover" if v >= moving else "hit while slow") + (" after a turn-round" if turned else "")
    return kind, (f"{head}; mover {j} at t={t:.1f} s, robot v={v:.2f} m/s, mover speed {np.hypot(*now[2:4]):.2f} "
                  f"m/s, mode {mode}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenarios", nargs="+", help="shipped scenario names or files")
    ap.add_argument("--seeds", nargs=2, type=int, default=(0, 12), metavar=("FIRST", "STOP"))
    ap.add_argument("--planner", default="qp-dwa")
    ap.add_argument("--params", default="{}", help="JSON dict of local-planner parameters")
    ap.add_argument("--moving", type=float, default=0.3, help="m/s from which the robot counts as driving into a mover")
    args = ap.parse_args(argv)
    params = json.loads(args.params)
    counts: Counter = Counter()
    runs = 0
    for name in args.scenarios:
        sc = load_scenario(name)
        for seed in range(*args.seeds):
            runs += 1
            out = explain(sc, seed, args.planner, params, args.moving)
            if out is None:
                counts["success"] += 1
                continue
            counts[out[0]] += 1
            print(out[1], flush=True)
        print(f"  {name} done", file=sys.stderr)
    print(f"\n| outcome ({args.planner}, {runs} runs) | runs |\n|---|---|")
    for kind, n in counts.most_common():
        print(f"| {kind} | {n} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
