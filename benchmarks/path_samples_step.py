"""What qp-dwa's path-following samples cost per control step (issue 27).

    python benchmarks/path_samples_step.py [--contexts 100] [--rounds 5]

Contexts: states along the A* path of clutter world 0 (the robot on the path, heading
along it, at a seeded speed) with 10 movers 1-3 m away. The same contexts are timed with
``path_samples=()`` (arcs only) and with the preset's default, alternating the two planners
round by round; the median ``command()`` time of each and of ``rollout_tracking`` alone are
printed. Wall clock on whatever else the machine is doing: compare the two, not the numbers.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.local.rollout import rollout_tracking
from optplan.sim.closed_loop import scenario_for
from optplan.sim.environment import SimEnvironment
from optplan.sim.experiments import plan_global
from optplan.world.robot import RobotState
from optplan.worldgen.clutter import family_options


def contexts(n: int, seed: int = 0) -> list[LocalContext]:
    sc = scenario_for("clutter", 0)
    path = np.asarray(plan_global(sc, "astar", None, 0, family_options("clutter")["global_options"]).path)
    env = SimEnvironment(sc)
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        i = int(rng.integers(0, len(path) - 2))
        p, q = path[i], path[i + 1]
        theta = float(np.arctan2(*(q - p)[::-1]))
        st = RobotState(float(p[0]), float(p[1]), theta, float(rng.uniform(0, 0.5)), 0.0)
        ang = rng.uniform(-np.pi, np.pi, 10)
        at = p + rng.uniform(1.0, 3.0, (10, 1)) * np.c_[np.cos(ang), np.sin(ang)]
        movers = np.c_[at, rng.uniform(-0.3, 0.3, (10, 2)), np.full(10, 0.15)]
        out.append(LocalContext(state=st, subgoal=path[-1], goal=path[-1], global_path=path,
                                static_distance=env.static_distance, dynamic=movers, dt=sc.dt,
                                distance_error=env.distance_error))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--contexts", type=int, default=100)
    ap.add_argument("--rounds", type=int, default=5)
    a = ap.parse_args(argv)
    ctxs = contexts(a.contexts)
    robot = scenario_for("clutter", 0).robot
    planners = {"arcs only": make_local_planner("qp-dwa", robot, 0.1, path_samples=()),
                "arcs + path samples": make_local_planner("qp-dwa", robot, 0.1)}
    times: dict[str, list[float]] = {k: [] for k in planners}
    for _ in range(a.rounds):
        for name, planner in planners.items():
            for ctx in ctxs:
                planner.reset(ctx.state, ctx.global_path)
                t0 = time.perf_counter()
                planner.command(ctx)
                times[name].append((time.perf_counter() - t0) * 1e3)
    track = []
    o = planners["arcs + path samples"].options
    for ctx in ctxs:
        t0 = time.perf_counter()
        rollout_tracking(ctx.state, ctx.global_path, robot.v_max * np.asarray(o["path_samples"]),
                         np.asarray(o["path_look_aheads"]), 0.1, 30, robot, np.asarray(o["path_turn_first"]))
        track.append((time.perf_counter() - t0) * 1e3)
    for name, ms in times.items():
        print(f"{name:22s} command() median {np.median(ms):.2f} ms over {len(ms)} steps")
    print(f"{'rollout_tracking':22s} median {np.median(track):.2f} ms ({len(o['path_samples']) * len(o['path_look_aheads']) * len(o['path_turn_first'])} samples x 30 steps)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
