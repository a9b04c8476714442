"""Silent collisions and hidden obstacles, counted by code that shares nothing with optplan's
collision routines.

Two counts (issue 29):

* **silent collisions**: a planner reports ``feasible=True`` for a path that enters an
  obstacle deeper than 1e-9 cells (shallower touches come from rounding metres to cells in
  float64, which the collision rule's float mode documents; they are counted separately), leaves the map, follows an edge between two blocked cells or squeezes through a
  double corner, or does not start at the start and end at the goal exactly. Random grid maps
  (sizes, densities, resolutions, origins) and circle worlds with off-centre queries; each
  returned path is re-checked here in exact rational arithmetic (``fractions.Fraction``: every
  float is a rational, so no rounding decides anything once the points are in grid units).
* **hidden obstacles**: a closed-loop run reports ``collisions == 0`` although at some recorded
  step the robot's disc overlaps a blocked cell of the true map (known plus unknown cells) or a
  moving disc. Random scenarios whose movers drive at constant velocity and leave the map
  (``at_border: pass``), so their positions are ``start + velocity * t``, computed here.

Nothing here calls ``validate_path``, ``segments_free``, ``is_free``, ``clearance`` or the
simulator's collision check.

    python benchmarks/independent_check.py                      # 1000 queries, 100 scenarios (seeds 0..)
    python benchmarks/independent_check.py --seed0 50000        # held-out seeds
    python benchmarks/independent_check.py --queries 50 --scenarios 5
"""
from __future__ import annotations

import argparse
import time
from fractions import Fraction as Fr

import numpy as np

import optplan as op

GRID_PLANNERS = ("astar", "dijkstra", "visibility", "gwo", "pso")
CIRCLE_PLANNERS = ("visibility", "pso")


# ------------------------------------------------------------------ exact checks of one path
def _cell_blocked(occ: np.ndarray, ix: int, iy: int) -> bool:
    h, w = occ.shape
    return not (0 <= ix < w and 0 <= iy < h) or bool(occ[iy, ix])  # outside the map is blocked


def _enters_open_box(ax, ay, dx, dy, x0, y0, x1, y1) -> bool:
    """Whether the closed segment A + t D (t in [0, 1]) meets the open box (x0, x1) x (y0, y1)."""
    lo, hi = Fr(0), Fr(1)
    lo_open = hi_open = False
    for a, d, b0, b1 in ((ax, dx, x0, x1), (ay, dy, y0, y1)):
        if d == 0:
            if not b0 < a < b1:
                return False
            continue
        t0, t1 = (b0 - a) / d, (b1 - a) / d
        if t0 > t1:
            t0, t1 = t1, t0
        if t0 >= lo:
            lo, lo_open = t0, True
        if t1 <= hi:
            hi, hi_open = t1, True
    return lo < hi or (lo == hi and not lo_open and not hi_open)


DEPTH_EPS = Fr(1, 10 ** 9)  # cells: optplan's float mode decides within ~1e-12 cells by rounding


def grid_path_collides(occ: np.ndarray, res: float, origin, path, depth: Fr = Fr(0)) -> str:
    """The first rule a path breaks on a grid (empty when it breaks none), in exact arithmetic.

    ``depth`` > 0 only counts a blocked cell entered deeper than that (grid units): the
    cell's open square shrunk by ``depth`` on every side."""
    h, w = occ.shape
    # metres to grid units as the documented convention does, (x - origin) / resolution in
    # float64 (a decimal resolution such as 0.3 has no exact binary value), a value within
    # the snapping tolerance of a multiple of 1/2 put on it; from there on exact
    reach = max(abs(origin[0]), abs(origin[1])) + max(h, w) * res
    tol = max(1e-9, 16 * 2.0 ** -52 * reach / res)

    def snapped(v: float) -> Fr:
        near = Fr(round(2 * v), 2)
        return near if abs(Fr(v) - near) <= Fr(tol) else Fr(v)

    pts = [(snapped((float(x) - origin[0]) / res), snapped((float(y) - origin[1]) / res)) for x, y in path]
    for i, (x, y) in enumerate(pts):
        if not (0 <= x <= w and 0 <= y <= h):
            return f"point {i} outside the map"
    for i in range(len(pts) - 1):
        (ax, ay), (bx, by) = pts[i], pts[i + 1]
        dx, dy = bx - ax, by - ay
        kx0, kx1 = int(np.floor(float(min(ax, bx)))) - 1, int(np.ceil(float(max(ax, bx)))) + 1
        ky0, ky1 = int(np.floor(float(min(ay, by)))) - 1, int(np.ceil(float(max(ay, by)))) + 1
        for ix in range(max(kx0, 0), min(kx1, w)):
            for iy in range(max(ky0, 0), min(ky1, h)):
                if occ[iy, ix] and _enters_open_box(ax, ay, dx, dy, ix + depth, iy + depth, ix + 1 - depth,
                                                    iy + 1 - depth):
                    return f"segment {i} enters blocked cell ({ix}, {iy})"
        if dx == 0 and dy == 0:
            continue
        # lattice vertices strictly inside the segment: no double corner
        for vx in range(max(kx0, 0), min(kx1, w) + 1):
            for vy in range(max(ky0, 0), min(ky1, h) + 1):
                if (vx - ax) * dy != (vy - ay) * dx:
                    continue
                t = (vx - ax) / dx if dx != 0 else (vy - ay) / dy
                if not 0 < t < 1:
                    continue
                bl, br = _cell_blocked(occ, vx - 1, vy - 1), _cell_blocked(occ, vx, vy - 1)
                tl, tr = _cell_blocked(occ, vx - 1, vy), _cell_blocked(occ, vx, vy)
                if (bl and tr and not br and not tl) or (br and tl and not bl and not tr):
                    return f"segment {i} passes the double corner ({vx}, {vy})"
        # along a grid line: not between two blocked cells (the outside counts as blocked)
        if dy == 0 and ay.denominator == 1:
            j = int(ay)
            for k in range(max(int(np.floor(float(min(ax, bx)))), 0), min(int(np.ceil(float(max(ax, bx)))), w)):
                if min(max(ax, bx), k + 1) - max(min(ax, bx), k) > 0 and _cell_blocked(occ, k, j - 1) \
                        and _cell_blocked(occ, k, j):
                    return f"segment {i} runs between two blocked cells at y = {j}"
        if dx == 0 and ax.denominator == 1:
            j = int(ax)
            for k in range(max(int(np.floor(float(min(ay, by)))), 0), min(int(np.ceil(float(max(ay, by)))), h)):
                if min(max(ay, by), k + 1) - max(min(ay, by), k) > 0 and _cell_blocked(occ, j - 1, k) \
                        and _cell_blocked(occ, j, k):
                    return f"segment {i} runs between two blocked cells at x = {j}"
    return ""


def circle_path_collides(bounds, circles: np.ndarray, safety: float, path) -> str:
    """The first rule a path breaks in a circle world (inside a grown disc, or off the map)."""
    xmin, ymin, xmax, ymax = (Fr(float(b)) for b in bounds)
    pts = [(Fr(float(x)), Fr(float(y))) for x, y in path]
    for i, (x, y) in enumerate(pts):
        if not (xmin <= x <= xmax and ymin <= y <= ymax):
            return f"point {i} outside the bounds"
    discs = [(Fr(float(cx)), Fr(float(cy)), Fr(float(r)) + Fr(float(safety))) for cx, cy, r in circles]
    for i in range(len(pts) - 1):
        (ax, ay), (bx, by) = pts[i], pts[i + 1]
        dx, dy = bx - ax, by - ay
        L2 = dx * dx + dy * dy
        for cx, cy, R in discs:
            t = Fr(0) if L2 == 0 else min(max(((cx - ax) * dx + (cy - ay) * dy) / L2, Fr(0)), Fr(1))
            ex, ey = ax + t * dx - cx, ay + t * dy - cy
            if ex * ex + ey * ey < R * R:  # touching the grown circle is allowed
                return f"segment {i} enters the disc at ({float(cx):g}, {float(cy):g})"
    return ""


# ------------------------------------------------------------------ random queries
def _random_grid(rng):
    h, w = int(rng.integers(8, 31)), int(rng.integers(8, 31))
    occ = rng.random((h, w)) < rng.uniform(0.05, 0.35)
    res = float(rng.choice([1.0, 0.5, 0.25, 0.3]))
    origin = (float(rng.uniform(-5, 5)), float(rng.uniform(-5, 5))) if rng.random() < 0.5 else (0.0, 0.0)
    return occ, res, origin


def _free_point(rng, occ, res, origin):
    free = np.argwhere(~occ)
    iy, ix = free[rng.integers(len(free))]
    u = rng.random(2) if rng.random() < 0.7 else rng.integers(0, 3, 2) / 2  # off-centre, or centres/corners
    return (float(origin[0] + (ix + u[0]) * res), float(origin[1] + (iy + u[1]) * res))


def check_queries(n: int, seed0: int) -> dict:
    """Plan ``n`` random queries and count what the independent check finds."""
    out = {"queries": 0, "feasible": 0, "silent_collisions": 0, "touches_below_eps": 0, "wrong_ends": 0,
           "refused": 0, "examples": []}
    for q in range(n):
        rng = np.random.default_rng(seed0 + q)
        if rng.random() < 0.8:
            occ, res, origin = _random_grid(rng)
            if occ.all():
                continue
            world = op.GridMap(occ, res, origin)
            planner = GRID_PLANNERS[q % len(GRID_PLANNERS)]
            s, g = _free_point(rng, occ, res, origin), _free_point(rng, occ, res, origin)

            def verdict(path):
                exact = grid_path_collides(occ, res, origin, path)
                if exact and not grid_path_collides(occ, res, origin, path, DEPTH_EPS):
                    return "below-eps: " + exact
                return exact
        else:
            circles = np.column_stack([rng.uniform(0, 10, 8), rng.uniform(0, 10, 8), rng.uniform(0.2, 1.2, 8)])
            safety = float(rng.uniform(0, 0.3))
            world = op.CircleWorld((0, 0, 10, 10), circles, safety)
            planner = CIRCLE_PLANNERS[q % len(CIRCLE_PLANNERS)]
            s, g = tuple(rng.uniform(0, 10, 2)), tuple(rng.uniform(0, 10, 2))

            def verdict(path):
                return circle_path_collides((0, 0, 10, 10), circles, safety, path)
        try:
            res_ = op.plan(world, s, g, algorithm=planner, seed=q, pop=12, iters=30)
        except op.OptplanError:
            out["refused"] += 1  # start/goal blocked or unreachable: an honest answer
            continue
        out["queries"] += 1
        if not res_.feasible:
            continue
        out["feasible"] += 1
        P = np.asarray(res_.path, float)
        if not (np.array_equal(P[0], s) and np.array_equal(P[-1], g)):
            out["wrong_ends"] += 1
        why = verdict(P)
        if why.startswith("below-eps"):
            out["touches_below_eps"] += 1  # float rounding of the metre-to-cell conversion, not a collision
            why = ""
        if why:
            out["silent_collisions"] += 1
            if len(out["examples"]) < 5:
                out["examples"].append(f"query seed {seed0 + q} {planner}: {why}")
    return out


# ------------------------------------------------------------------ random scenarios
def _random_scenario(rng) -> dict:
    n = int(rng.integers(12, 21))
    occ = rng.random((n, n)) < 0.12
    occ[:2, :2] = False
    occ[-2:, -2:] = False
    unknown = [[int(x), int(y)] for x, y in rng.integers(2, n - 2, (3, 2)) if not occ[y, x]]
    movers = []
    for _ in range(int(rng.integers(1, 4))):
        p = rng.uniform(2, n - 2, 2)
        v = rng.uniform(-0.5, 0.5, 2)
        movers.append({"radius": float(rng.uniform(0.2, 0.5)), "start": p.tolist(), "velocity": v.tolist(),
                       "at_border": "pass"})
    return {"map": occ[::-1].astype(int).tolist(), "resolution": 1.0,
            "robot": {"model": "unicycle", "radius": 0.2, "v_max": 1.0, "w_max_deg": 60, "a_max": 0.5,
                      "alpha_max_deg": 90},
            "start": [0.5, 0.5, 45], "goal": [n - 0.5, n - 0.5], "sensor_range": 3.0, "dt": 0.1,
            "time_limit": 80, "unknown_obstacles": [{"cells": unknown}] if unknown else [],
            "dynamic_obstacles": movers}


def _overlaps(data: dict, traj: np.ndarray) -> str:
    """The first recorded step at which the robot disc overlaps the true static map or a mover."""
    occ = np.array(data["map"], bool)[::-1].copy()
    for x, y in (data["unknown_obstacles"][0]["cells"] if data["unknown_obstacles"] else []):
        occ[y, x] = True
    r = data["robot"]["radius"]
    blocked = np.argwhere(occ)  # (iy, ix)
    for t, x, y in traj[:, :3]:
        gap = np.maximum(np.maximum(blocked[:, ::-1] - [x, y], [x, y] - (blocked[:, ::-1] + 1.0)), 0.0)
        if len(blocked) and np.hypot(gap[:, 0], gap[:, 1]).min() < r - 1e-9:
            return f"t = {t:.2f} s: the robot overlaps a blocked cell at ({x:.3f}, {y:.3f})"
        for m in data["dynamic_obstacles"]:
            cx, cy = np.add(m["start"], np.multiply(m["velocity"], t))
            if np.hypot(x - cx, y - cy) < r + m["radius"] - 1e-9:
                return f"t = {t:.2f} s: the robot overlaps a mover at ({cx:.3f}, {cy:.3f})"
    return ""


def check_scenarios(n: int, seed0: int) -> dict:
    """Run ``n`` random closed loops and count the collisions the simulator did not report."""
    out = {"scenarios": 0, "reported_clean": 0, "hidden_obstacles": 0, "reported_collisions": 0, "refused": 0,
           "examples": []}
    for k in range(n):
        rng = np.random.default_rng(seed0 + k)
        data = _random_scenario(rng)
        try:
            sim = op.simulate(op.load_scenario(data), global_planner="astar", local_planner="dwa", seed=k)
        except op.OptplanError:
            out["refused"] += 1
            continue
        out["scenarios"] += 1
        if sim.collisions:
            out["reported_collisions"] += 1
            continue
        out["reported_clean"] += 1
        why = _overlaps(data, np.asarray(sim.trajectory, float))
        if why:
            out["hidden_obstacles"] += 1
            if len(out["examples"]) < 5:
                out["examples"].append(f"scenario seed {seed0 + k}: {why}")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--queries", type=int, default=1000)
    ap.add_argument("--scenarios", type=int, default=100)
    ap.add_argument("--seed0", type=int, default=0, help="first seed (development 0; held-out e.g. 50000)")
    args = ap.parse_args()
    t0 = time.perf_counter()
    q = check_queries(args.queries, args.seed0)
    print(f"queries: {q['queries']} planned ({q['refused']} refused as infeasible queries), {q['feasible']} "
          f"reported feasible; silent collisions {q['silent_collisions']} (deeper than 1e-9 cells), "
          f"touches below 1e-9 cells {q['touches_below_eps']}, wrong start/goal {q['wrong_ends']}")
    for e in q["examples"]:
        print("  ", e)
    s = check_scenarios(args.scenarios, args.seed0)
    print(f"scenarios: {s['scenarios']} run ({s['refused']} refused), {s['reported_clean']} reported collision-free, "
          f"{s['reported_collisions']} reported collisions; hidden obstacles {s['hidden_obstacles']}")
    for e in s["examples"]:
        print("  ", e)
    print(f"({time.perf_counter() - t0:.0f} s on a shared machine)")


if __name__ == "__main__":
    main()
