"""idwa's brake sample and held period (``brake_sample``, ``reaction`` 0.1 s): how often a
robot that starts on an admissible arc later slides into a static obstacle, with both and with
neither (Fox's plain test on the plain grid).

    python benchmarks/brake_sample.py [--presets idwa,dwa,iga-dwa,ba-dwa] [--starts 500] [--seed 1]
        [--map yang2023_fusion25]

Fox's admissibility asks that the robot can stop on a sample's arc. The arc the robot
drives, braked (the window's slowest speed at the same curvature), is rarely on the sample
grid, so a robot whose chosen arc was admissible can find every sample of the next window
inadmissible. Random starts (position at least 0.4 m clear, heading, speed 0.3-1.0 m/s, yaw
rate +-0.6 rad/s, a random goal; ``--seed``: 0 was used to develop the option, others are
held out) on a shipped paper map (``--map``; default the map of yang2023's fusion
experiment) with the fusion experiment's robot (a_max 0.2 m/s^2), no movers; only starts whose first step is an admissible sample count. Each
runs 4 s (40 steps); a hit is a footprint overlapping an obstacle (distance field). Prints,
per preset, hits with neither / with both, and the starts that hit with both only.
"""
from __future__ import annotations

import argparse

import numpy as np

from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.sim.kinematics import step_pose
from optplan.world.fields import distance_function
from optplan.world.papermaps import paper_map
from optplan.world.robot import RobotState
from optplan.world.scenario import load_scenario

STEPS, DT = 40, 0.1


def run(preset: str, brake: bool, robot, field, start: RobotState, goal: np.ndarray) -> tuple[bool, bool]:
    """``(first step was an admissible sample, the footprint hit an obstacle)``."""
    planner = make_local_planner(preset, robot, DT, brake_sample=brake, reaction=DT if brake else 0.0)
    path = np.array([[start.x, start.y], goal])
    planner.reset(start, path)
    st, first = start, None
    for _ in range(STEPS):
        ctx = LocalContext(state=st, subgoal=goal, goal=goal, global_path=path, static_distance=field,
                           dynamic=np.zeros((0, 5)), dt=DT)
        cmd = planner.command(ctx)
        first = cmd.info["mode"] == "sample" if first is None else first
        x, y, th = step_pose(robot.model, st.x, st.y, st.theta, cmd.v, cmd.w, DT)
        st = RobotState(float(x), float(y), float(th), cmd.v, cmd.w)
        if float(field(np.array([st.x, st.y]))) < robot.radius:
            return first, True
    return first, False


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--presets", default="idwa,dwa,iga-dwa,ba-dwa")
    ap.add_argument("--starts", type=int, default=500)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--map", default="yang2023_fusion25", help="a shipped paper map (optplan/data/maps)")
    a = ap.parse_args(argv)
    sc = load_scenario("yang2023_fusion")  # its robot
    grid = paper_map(a.map)[0]
    field = distance_function(grid)
    x0, y0, x1, y1 = grid.bounds
    rng = np.random.default_rng(a.seed)
    starts = []
    while len(starts) < a.starts:
        p = rng.uniform((x0, y0), (x1, y1))
        if float(field(p)) < 0.4:
            continue
        starts.append((RobotState(p[0], p[1], rng.uniform(-np.pi, np.pi), rng.uniform(0.3, 1.0), rng.uniform(-0.6, 0.6)),
                       rng.uniform((x0, y0), (x1, y1))))
    print(f"{a.starts} random starts (seed {a.seed}) on {a.map}, {sc.name}'s robot, {STEPS} steps each\n")
    print("| preset | starts with an admissible first step | hits, plain | hits, brake sample + held period | hit with them only |")
    print("|---|---|---|---|---|")
    for preset in a.presets.split(","):
        counted = without = with_ = only_with = 0
        for st, goal in starts:
            first, hit_without = run(preset, False, sc.robot, field, st, goal)
            if not first:
                continue
            _, hit_with = run(preset, True, sc.robot, field, st, goal)
            counted += 1
            without += hit_without
            with_ += hit_with
            only_with += hit_with and not hit_without
        print(f"| {preset} | {counted} | {without} | {with_} | {only_with} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
