"""Hashes of closed-loop trajectories: one run per local preset on a scenario of its paper,
seeds 0 and 1, A* global path, the scenario's own time limit.

A refactoring of the local layer that must not change behaviour prints the same lines
before and after (compare with ``diff``).

    PYTHONPATH=$PWD python benchmarks/local_trajectory_hashes.py
    PYTHONPATH=$PWD python benchmarks/local_trajectory_hashes.py --as-program

``--as-program`` runs each preset as its named window program sampled by ``dwa`` (``qp-dwa``
for its own): ``local_planner="dwa", local_program=PRESET`` (issue 42). It prints the same
lines as the presets themselves.
"""
from __future__ import annotations

import argparse
import hashlib

import numpy as np

from optplan.sim.closed_loop import simulate

CASES = [("dwa", "li2023_exp1"), ("iga-dwa", "li2023_exp2_3"), ("idwa", "yang2023_idwa_crossing"),
         ("missa-dwa", "hou2024_dynamic1"), ("ba-dwa", "yuan2021_added_obstacles"), ("qp-dwa", "hou2024_dynamic4")]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--as-program", action="store_true",
                    help="run each preset as its named window program, sampled by dwa (qp-dwa for its own)")
    a = ap.parse_args()
    for planner, scenario in CASES:
        for seed in (0, 1):
            if a.as_program:
                solver = "qp-dwa" if planner == "qp-dwa" else "dwa"
                r = simulate(scenario, local_planner=solver, local_program=planner, seed=seed)
            else:
                r = simulate(scenario, local_planner=planner, seed=seed)
            traj = np.ascontiguousarray(r.trajectory, dtype=float)
            print(planner, scenario, seed, r.status, traj.shape, hashlib.sha256(traj.tobytes()).hexdigest()[:16],
                  flush=True)


if __name__ == "__main__":
    main()
