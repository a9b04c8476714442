"""Refinement timings and IPOPT vs SLSQP on the same smoothing problem.

    python benchmarks/refine_solvers.py

1. Circle worlds (yang2023 env 1-2), N <= 100: cold (first call, NLP built) and
   warm (structure reused) IPOPT times; goals 30 ms cold and 15 ms warm median.
2. Grid maps once the interpolant is cached: per-solve time; goal 150 ms.
3. The same circle-world problem (fixed neighbour sets) solved by IPOPT and by
   scipy.optimize SLSQP: time and objective side by side; goal IPOPT >= 20x faster.
The QP corridor smoother of issue 5 is not implemented yet, so it has no row.
"""
from __future__ import annotations

import time

import numpy as np

import optplan as op
from optplan.solvers.nlp import smoothing
from optplan.solvers.nlp.smoothing import resample, smooth_path
from optplan.world.papermaps import paper_map


def seed_for(world, s, g):
    if hasattr(world, "occ"):
        return op.plan(world, s, g, algorithm="astar").path
    return op.plan(world, s, g, algorithm="pso", seed=0, pop=30, iters=60).path


def timings() -> None:
    print("| map | N | cold [s] | warm median [s] | refined length [m] | optimum [m] |")
    print("|---|---|---|---|---|---|")
    for name in ("yang2023_env1", "yang2023_env2", "chen2025_20", "li2023_30", "hou2024_base50"):
        world, s, g = paper_map(name)
        seed = seed_for(world, s, g)
        smoothing._CACHE.clear()
        world._cache.clear()
        t = time.perf_counter()
        r = smooth_path(world, seed)
        cold = time.perf_counter() - t
        warm = []
        for _ in range(5):
            t = time.perf_counter()
            smooth_path(world, seed)
            warm.append(time.perf_counter() - t)
        opt = op.shortest_path(world, s, g, method="visibility").length
        n = smoothing.default_points(seed, 0.25 * (world.resolution if hasattr(world, "occ") else 1.0))
        L = op.path_metrics(world, r.path).length
        print(f"| {name} | {n} | {cold:.3f} | {np.median(warm):.3f} | {L:.3f} | {opt:.3f} |")
    print("\ngoals: circle worlds 0.030 s cold / 0.015 s warm; grids 0.150 s per solve (cached interpolant)")


def ipopt_vs_slsqp(N: int = 40, K: int = 3) -> None:
    from scipy.optimize import minimize

    world, s, g = paper_map("yang2023_env1")
    X0 = resample(seed_for(world, s, g), N)
    Q = np.vstack([X0, (X0[1:] + X0[:-1]) / 2])
    idx = smoothing._nearest(world, Q, K)
    C = np.hstack([world.circles[idx, 0], world.circles[idx, 1]])
    R = world.radii[idx] + 1e-3
    box = np.array(world.bounds, float)
    ends = np.stack([X0[0], X0[-1]])
    w = 0.5
    fn = smoothing._circle_solver(N, K, w)
    fn(X0, C, R, box, ends)  # build and warm
    t = time.perf_counter()
    Xi = np.array(fn(X0, C, R, box, ends))
    t_ipopt = time.perf_counter() - t

    def objective(z):
        X = np.vstack([ends[0], z.reshape(-1, 2), ends[1]])
        d = np.diff(X, axis=0)
        dd = X[2:] - 2 * X[1:-1] + X[:-2]
        return float((d ** 2).sum() + w * (dd ** 2).sum())

    def constraints(z):
        X = np.vstack([ends[0], z.reshape(-1, 2), ends[1]])
        P = np.vstack([X, (X[1:] + X[:-1]) / 2])
        dx = P[:, 0:1] - C[:, :K]
        dy = P[:, 1:2] - C[:, K:]
        return (dx ** 2 + dy ** 2 - R ** 2).ravel()

    t = time.perf_counter()
    sol = minimize(objective, X0[1:-1].ravel(), method="SLSQP", constraints=[{"type": "ineq", "fun": constraints}],
                   bounds=[(box[0], box[2]), (box[1], box[3])] * (N - 2), options={"maxiter": 500})
    t_slsqp = time.perf_counter() - t
    print(f"\n## same problem (N = {N}, K = {K} circles per sample), yang2023_env1\n")
    print("| solver | time [s] | objective | status |")
    print("|---|---|---|---|")
    print(f"| IPOPT (casadi, warm structure) | {t_ipopt:.4f} | {objective(Xi[1:-1].ravel()):.6f} | ok |")
    print(f"| SLSQP (scipy, numeric gradients) | {t_slsqp:.4f} | {sol.fun:.6f} | {sol.message} |")
    print(f"\nspeed-up {t_slsqp / t_ipopt:.1f}x (goal >= 20x)")


if __name__ == "__main__":
    timings()
    ipopt_vs_slsqp()
