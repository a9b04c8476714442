"""Could any robot have avoided the mover it met? (issue 28, yang2023's fusion experiment)

For every run of a local preset that touches a moving obstacle, the robot's recorded state a
second before the mover set off, when it set off and half a second later is searched from:
every plan of five 0.6 s pieces, each with the linear and the angular acceleration at -max,
0 or +max (9^5 = 59,049 plans, then 3 s holding the last speeds), driven with the robot's
limits against the mover's true future motion (which no planner knows) and the true static
map. A plan avoids the contact when it keeps clear of every mover and static obstacle for
the 6 s. Zero plans from the moment the mover sets off: no controller with the robot's
limits could have avoided it after seeing it move.

    python benchmarks/mover_avoidability.py --seeds 0-9 [--plain-ends] [--cache DIR] [--workers 2]

``--plain-ends`` draws the movers without ``random_dynamic.ends_unseen`` (a mover may stand
in view beside the path and set off when the robot is near), as the scenario was before.
One line per run that touched a mover, then a summary.
"""
from __future__ import annotations

import argparse
import itertools
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace

import numpy as np

from paper_local_rates import EXPERIMENTS, global_plan

PIECE, PIECES, HOLD = 0.6, 5, 3.0  # s


def avoiding_plans(env, robot, state: np.ndarray, t0: float, dt: float) -> int:
    """How many of the 9^PIECES acceleration plans from ``state`` ``(x, y, theta, v, w)`` at
    ``t0`` keep clear of every mover and static obstacle for ``PIECES * PIECE + HOLD`` s."""
    choice = np.array(list(itertools.product((-1, 0, 1), (-1, 0, 1))), dtype=float)
    plans = np.array(list(itertools.product(range(len(choice)), repeat=PIECES)))
    acc, ang = choice[plans, 0] * robot.a_max, choice[plans, 1] * robot.alpha_max
    x, y, th, v, w = (np.full(len(plans), float(s)) for s in state)
    per = int(round(PIECE / dt))
    steps = PIECES * per + int(round(HOLD / dt))
    clear = np.ones(len(plans), dtype=bool)
    points = np.empty((len(plans), steps, 2))
    for k in range(steps):
        if k < PIECES * per:
            v = np.clip(v + acc[:, k // per] * dt, max(robot.v_min, 0.0), robot.v_max)
            w = np.clip(w + ang[:, k // per] * dt, -robot.w_max, robot.w_max)
        x, y, th = x + v * np.cos(th) * dt, y + v * np.sin(th) * dt, th + w * dt
        m = env.movers(round(t0 + (k + 1) * dt, 10))
        gap = np.hypot(x[:, None] - m[None, :, 0], y[:, None] - m[None, :, 1]) - m[None, :, 4] - robot.radius
        clear &= (gap > 0).all(axis=1)
        points[:, k, 0], points[:, k, 1] = x, y
    rows = np.flatnonzero(clear)
    if not len(rows):
        return 0
    static = np.asarray(env.true_clearance(points[rows].reshape(-1, 2))).reshape(len(rows), steps)
    return int(((static - robot.radius) > 0).all(axis=1).sum())


def one_seed(job) -> tuple | None:
    from optplan.sim.closed_loop import realized_scenario, scenario_for, simulate
    from optplan.sim.environment import SimEnvironment

    preset, name, planner, gopts, seed, cache, plain = job
    sc = scenario_for(name)
    if plain:
        sc = replace(sc, random_dynamic={**sc.random_dynamic, "ends_unseen": False})
    plan = global_plan(name, planner, gopts, seed, cache)
    run = simulate(sc, global_planner=planner, local_planner=preset, seed=seed, global_plan=plan,
                   mover_motion="once")
    world = realized_scenario(sc, seed, plan, "once")
    env = SimEnvironment(world)
    traj = run.trajectory
    if not world.dynamic:
        return None
    for row in traj:
        m = env.movers(row[0])
        gap = np.hypot(m[:, 0] - row[1], m[:, 1] - row[2]) - m[:, 4] - world.robot.radius
        if gap.min() < 0:
            contact, mover = float(row[0]), int(np.argmin(gap))
            break
    else:
        return None
    ob = world.dynamic[mover]
    launch = ob.delay if ob.phase == 0.0 else 0.0
    counts = []
    for t0 in (launch - 1.0, launch, launch + 0.5):
        k = int(round(t0 / sc.dt))
        counts.append(avoiding_plans(env, world.robot, traj[k, 1:6], k * sc.dt, sc.dt)
                      if 0 <= k * sc.dt < contact else None)
    return seed, contact, launch, counts


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", default="0-9", help="first-last (inclusive)")
    ap.add_argument("--paper", default="yang2023", choices=sorted(EXPERIMENTS))
    ap.add_argument("--plain-ends", action="store_true", help="movers drawn without ends_unseen")
    ap.add_argument("--cache", default=None, help="directory for the global plans")
    ap.add_argument("--workers", type=int, default=1)
    a = ap.parse_args(argv)
    preset, scenarios, planner, gopts = EXPERIMENTS[a.paper]
    lo, hi = (int(x) for x in a.seeds.split("-"))
    jobs = [(preset, sc, planner, gopts, s, a.cache, a.plain_ends) for sc in scenarios for s in range(lo, hi + 1)]
    n_plans = 9 ** PIECES
    touched = unavoidable = 0
    print(f"{preset}, {', '.join(scenarios)}, seeds {a.seeds}, movers once"
          f"{' (plain ends)' if a.plain_ends else ' (ends as the scenario draws them)'}")
    print(f"| seed | contact [s] | mover set off [s] | plans avoiding from 1 s before / at set-off / 0.5 s after "
          f"(of {n_plans}) |")
    print("|---|---|---|---|")
    with ProcessPoolExecutor(a.workers) as ex:
        for out in ex.map(one_seed, jobs):
            if out is None:
                continue
            seed, contact, launch, counts = out
            touched += 1
            unavoidable += counts[1] == 0
            print(f"| {seed} | {contact:.1f} | {launch:.1f} | "
                  f"{' / '.join('-' if c is None else str(c) for c in counts)} |", flush=True)
    print(f"{touched} of {len(jobs)} runs touched a mover; in {unavoidable} of them no plan avoided it "
          f"from the moment the mover set off")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
