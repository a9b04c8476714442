"""Held-out program check (issue 24): one program, written once, on maps made here for it.

The program: length + 0.3 * sum of squared turn angles + 2 * a user term (exposure to a
"sensor" at the map centre), subject to clearance >= 0.1 m and every turn <= 75 degrees.
It is solved by three metaheuristics, IPOPT and SLSQP (both from the msiar-gwo result),
and the chain msiar-gwo > ipopt. For every result claimed feasible the script checks,
with code of its own (not the program's): the exact collision test at the clearance, every
turn angle, and that prog.evaluate(path) reproduces the reported cost. It prints one row
per (map, solver) and the share of chains in which IPOPT improved the metaheuristic seed.

Maps: random block grids (20x20 and 32x32, 15-25 % blocked) and circle worlds (10 m, 6-10
circles), drawn from seeds 1000+ that no development run used.

    python benchmarks/program_heldout.py [--maps 6] [--seeds 3] [--variables bspline|waypoints]
"""
from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

import optplan as op
from optplan import terms as T
from optplan.world.metrics import turn_angles_deg

LIMIT_DEG = 75.0
CLEARANCE = 0.1


def random_grid(seed: int, size: int, density: float) -> op.GridMap:
    """Rectangular blocks dropped at random, start and goal corners kept free and connected."""
    rng = np.random.default_rng(seed)
    while True:
        occ = np.zeros((size, size), bool)
        while occ.mean() < density:
            w, h = rng.integers(1, 4, size=2)
            x, y = rng.integers(0, size - w), rng.integers(0, size - h)
            occ[y:y + h, x:x + w] = True
        occ[:3, :3] = occ[-3:, -3:] = False
        grid = op.GridMap(occ)
        try:
            op.shortest_path(grid, (0.5, 0.5), (size - 0.5, size - 0.5), method="astar")
            return grid
        except op.OptplanError:
            seed += 7919
            rng = np.random.default_rng(seed)


def random_circles(seed: int) -> op.CircleWorld:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(6, 11))
    circles = []
    while len(circles) < n:
        c = rng.uniform(1.5, 8.5, 2)
        r = rng.uniform(0.4, 1.1)
        if np.hypot(*(c - 0.5)) > r + 0.6 and np.hypot(*(c - 9.5)) > r + 0.6:
            circles.append((c[0], c[1], r))
    return op.CircleWorld(bounds=(0, 0, 10, 10), circles=circles)


def program(world, variables: str):
    xmin, ymin, xmax, ymax = world.bounds
    start, goal = (xmin + 0.5, ymin + 0.5), (xmax - 0.5, ymax - 0.5)
    centre = np.array([(xmin + xmax) / 2, (ymin + ymax) / 2])
    scale = (xmax - xmin) / 4

    def exposure(P, m):
        d = (P - centre) / scale
        seg = m.norm(m.diff(P, axis=0), axis=1)
        near = m.exp(-m.sum(d * d, axis=1))
        return m.sum(seg * (near[1:] + near[:-1]) / 2)

    v = op.BSpline(ctrl=6, samples=60) if variables == "bspline" else op.Waypoints(6)
    prog = op.PathProgram(world, start, goal, variables=v, name="heldout")
    prog.minimize(T.length() + 0.3 * T.turn_angles().sumsq() + 2.0 * T.custom(exposure, name="exposure"))
    prog.subject_to(T.clearance() >= CLEARANCE)
    prog.subject_to(T.turn_angles() <= math.radians(LIMIT_DEG))
    return prog


def independent_check(prog, r) -> str:
    """'' when a result claimed feasible really is; otherwise what fails."""
    if not r.feasible:
        return ""
    P = np.asarray(r.path)
    fails = []
    if not (np.allclose(P[0], prog.start) and np.allclose(P[-1], prog.goal)):
        fails.append("ends")
    if not op.validate_path(prog.world, P, CLEARANCE):
        fails.append("collision/clearance")
    if np.any(turn_angles_deg(P[None])[0] > LIMIT_DEG + 1e-6):
        fails.append("turn")
    if abs(prog.evaluate(P)[0] - r.cost) > 1e-9 * max(1.0, abs(r.cost)):
        fails.append("cost")
    return ",".join(fails)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--maps", type=int, default=6, help="maps (half grids, half circle worlds)")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--max-evals", type=int, default=6000)
    ap.add_argument("--variables", choices=("bspline", "waypoints"), default="bspline")
    a = ap.parse_args(argv)
    worlds = []
    for i in range(a.maps):
        if i % 2 == 0:
            size = 20 if i % 4 == 0 else 32
            worlds.append((f"grid{size}_s{1000 + i}", random_grid(1000 + i, size, 0.15 + 0.05 * (i % 3))))
        else:
            worlds.append((f"circles_s{1000 + i}", random_circles(1000 + i)))
    swarms = ["msiar-gwo", "missa", "pso"]
    print(f"{'map':<18} {'solver':<16} {'feasible':>8} {'mean cost':>10} {'mean s':>7} {'bad claims':>10}")
    bad_total, chains, improved, worse_than_first, seeded, improved_seeded = 0, 0, 0, 0, 0, 0
    for label, world in worlds:
        prog = program(world, a.variables)
        rows = {}
        for seed in range(a.seeds):
            t0 = time.perf_counter()
            res = {n: prog.solve(n, max_evals=a.max_evals, seed=seed) for n in swarms}
            res["ipopt"] = prog.solve("ipopt", init=res["msiar-gwo"])
            res["slsqp"] = prog.solve("slsqp", init=res["msiar-gwo"])
            res["msiar-gwo>ipopt"] = prog.solve(["msiar-gwo", "ipopt"], max_evals=a.max_evals, seed=seed)
            ch = res["msiar-gwo>ipopt"]
            chains += 1
            first = ch.stages[0]
            better = bool(ch.stages[1]["accepted"] and ch.stages[1]["feasible"] and
                          (ch.cost < first["cost"] - 1e-9 or not first["feasible"]))
            improved += better
            seeded += bool(first["feasible"])
            improved_seeded += better and bool(first["feasible"])
            worse_than_first += bool(first["feasible"] and (not ch.feasible or ch.cost > first["cost"] + 1e-12))
            for n, r in res.items():
                bad = independent_check(prog, r)
                bad_total += bool(bad)
                rows.setdefault(n, []).append((r.feasible, r.cost, r.runtime_s, bad))
            print(f"  {label} seed {seed}: {time.perf_counter() - t0:.1f} s", file=sys.stderr)
        for n, rs in rows.items():
            ok = [c for f, c, _, _ in rs if f]
            print(f"{label:<18} {n:<16} {sum(f for f, *_ in rs):>4}/{len(rs):<3} "
                  f"{(np.mean(ok) if ok else float('nan')):>10.3f} {np.mean([t for _, _, t, _ in rs]):>7.2f} "
                  f"{sum(bool(b) for *_, b in rs):>10}")
    print()
    print(f"results claimed feasible that fail an independent check: {bad_total}")
    print(f"chains worse than their first stage: {worse_than_first} of {chains}")
    print(f"chains where ipopt improved the msiar-gwo seed (lower cost, or feasible from an infeasible seed): "
          f"{improved} of {chains} ({improved / max(chains, 1):.0%})")
    print(f"  of the chains whose seed was feasible: {improved_seeded} of {seeded} "
          f"({improved_seeded / max(seeded, 1):.0%})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
