"""A loop-based reference DWA in the common textbook structure.

    for v in window:
        for w in window:
            simulate the trajectory step by step
            compute its costs (collision check point by point, obstacle by obstacle)
    normalise, weight, pick the best

It implements the same method as the vectorised ``dwa`` preset (Fox et al. 1997 terms
heading / clearance / velocity, the dynamic window of hou2024 eq 20-21, admissibility
eq 22, constant-velocity prediction of movers, sum normalisation), written plainly so that
it can serve as a check of the vectorised core (same inputs, same choice) and as the
baseline of ``benchmarks/dwa_step.py``. As in common implementations the static-obstacle
distance is looked up once per trajectory (one call with its points); everything else is
plain Python.
"""
from __future__ import annotations

import math

import numpy as np

from ..world.geometry import wrap_angle
from ..world.robot import RobotSpec
from .base import LocalContext


def reference_dwa(robot: RobotSpec, ctx: LocalContext, *, n_v: int = 11, n_w: int = 21, horizon: float = 3.0,
                  rollout_dt: float | None = None, weights: tuple[float, float, float] = (2.0, 0.2, 0.2),
                  cap: float = 2.0, margin: float = 0.02) -> tuple[float, float, dict]:
    """The textbook DWA's command ``(v, w, info)`` for one control step (unicycle model).

    ``weights`` are those of heading, clearance and velocity; the other arguments mean what
    they mean for the ``dwa`` preset.
    """
    dt = ctx.dt
    rdt = rollout_dt or dt
    steps = max(1, int(round(horizon / rdt)))
    st = ctx.state
    R = robot.radius
    # dynamic window (eq 20-21)
    v_lo = min(max(robot.v_min, st.v - robot.a_max * dt), st.v + robot.a_max * dt)
    v_hi = min(max(robot.v_max, st.v - robot.a_max * dt), st.v + robot.a_max * dt)
    w_lo = min(max(-robot.w_max, st.w - robot.alpha_max * dt), st.w + robot.alpha_max * dt)
    w_hi = min(max(robot.w_max, st.w - robot.alpha_max * dt), st.w + robot.alpha_max * dt)
    gx, gy = float(ctx.subgoal[0]), float(ctx.subgoal[1])
    movers = [tuple(map(float, row)) for row in np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5)]
    # where the robot stands already closer than the margin, only getting closer counts
    static_now = float(np.asarray(ctx.static_distance(np.array([[st.x, st.y]]))).ravel()[0]) - R
    moving_now = math.inf
    for ox, oy, _, _, orad in movers:
        moving_now = min(moving_now, math.hypot(st.x - ox, st.y - oy) - orad - R)
    static_limit, moving_limit = min(margin, static_now), min(margin, moving_now)

    records = []  # (v, w, heading, clearance, velocity)
    for v in np.linspace(v_lo, v_hi, n_v):
        for w in np.linspace(w_lo, w_hi, n_w):
            v, w = float(v), float(w)
            x, y, th = st.x, st.y, st.theta
            traj = []
            for _ in range(steps):
                x += v * math.cos(th) * rdt
                y += v * math.sin(th) * rdt
                th += w * rdt
                traj.append((x, y, th))
            static = ctx.static_distance(np.array([(px, py) for px, py, _ in traj]))
            min_gap, first_hit, meets_mover = math.inf, None, False
            for k, (px, py, _) in enumerate(traj):
                t = (k + 1) * rdt
                gap = float(static[k]) - R
                if first_hit is None and gap < static_limit:
                    first_hit = k
                for ox, oy, ovx, ovy, orad in movers:
                    d = math.hypot(px - (ox + ovx * t), py - (oy + ovy * t)) - orad - R
                    if d < moving_limit:
                        meets_mover = True
                    if d < gap:
                        gap = d
                if gap < min_gap:
                    min_gap = gap
            free = math.inf if first_hit is None else first_hit * abs(v) * rdt
            if abs(v) > math.sqrt(2.0 * robot.a_max * free) + 1e-12:  # eq 22: cannot stop in time
                continue
            if meets_mover:  # a trajectory into a predicted mover is discarded
                continue
            heading = math.pi - abs(wrap_angle(math.atan2(gy - y, gx - x) - th))
            clearance = min(max(min_gap, 0.0), cap)
            records.append((v, w, heading, clearance, v))

    if not records:  # (the vectorised planner has finer fallbacks; the reference just brakes)
        return min(max(0.0, v_lo), v_hi), min(max(0.0, w_lo), w_hi), {"mode": "brake"}
    sums = [sum(abs(r[c]) for r in records) for c in (2, 3, 4)]
    best, best_score = None, -math.inf
    for r in records:
        score = 0.0
        for weight, value, total in zip(weights, r[2:], sums):
            if total > 0:
                score += weight * value / total
        if score > best_score:
            best, best_score = r, score
    return best[0], best[1], {"mode": "sample", "score": best_score, "n_candidates": len(records)}
