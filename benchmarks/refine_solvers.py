"""Refinement timings, and IPOPT vs SLSQP vs the QP corridor smoother on one problem.

    python benchmarks/refine_solvers.py            # all tables
    python benchmarks/refine_solvers.py --quick    # fewer repetitions

1. Circle worlds (yang2023 env 1-2), N <= 100. *build*: constructing both IPOPT
   instances of a size (once per N, K). *cold*: a solve from the resampled seed
   with the structure cached (median). *warm*: replanning after the start moved
   0.05-0.5 m along the path, warm-started from the previous solution and its
   multipliers (median). Goals: 30 ms cold, 15 ms warm.
2. Grid maps once the interpolant is cached: cold and warm per-solve NLP times
   with 1 (default) and 2 constrained samples inside each segment, and the QP
   polish on its own; goal 150 ms per solve.
3. The same circle-world problem solved by IPOPT (casadi), scipy SLSQP (fixed
   neighbour sets, as the NLP), and by the QP corridor smoother (OSQP and cvxpy):
   time and objective ``J`` side by side; goal IPOPT >= 20x faster than SLSQP.
   The QP's feasible set is a convex corridor inside the NLP's, so its one-solve
   ``J`` is at least the NLP's local optimum around the same seed; the full
   smoother rebuilds the corridor in rounds (and may add seed vertices, so its N
   and hence J differ slightly).
4. IPOPT options: total iterations over 9 cold solves (why ``mu_strategy='adaptive'``).
5. QP corridor smoother (``refine='qp'``) per map: time, rounds, length.

Wall-clock figures depend on machine load; run it on a quiet machine. The CPU
columns (this process's CPU time) are less sensitive to other processes.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

import optplan as op
from optplan.solvers.nlp import smoothing
from optplan.solvers.nlp.smoothing import smooth_path
from optplan.solvers.qp import build_corridor, corridor_program, smooth_path_qp
from optplan.solvers.qp.corridor import sample_for_corridor
from optplan.world.papermaps import paper_map

REPS = 7


def seed_for(world, s, g):
    if hasattr(world, "occ"):
        return op.plan(world, s, g, algorithm="astar").path
    return op.plan(world, s, g, algorithm="pso", seed=0, pop=30, iters=60).path


def timed(fn, reps, cpu: bool = False):
    """Last result and median wall time (and median CPU time of this process with ``cpu``)."""
    out, ts, cs = None, [], []
    for _ in range(reps):
        t, c = time.perf_counter(), time.process_time()
        out = fn()
        ts.append(time.perf_counter() - t)
        cs.append(time.process_time() - c)
    return (out, float(np.median(ts)), float(np.median(cs))) if cpu else (out, float(np.median(ts)))


def moved_starts(path: np.ndarray, n: int) -> list[np.ndarray]:
    """Starts 0.05 .. 0.5 m along a path (a robot that advanced a little)."""
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))])
    return [np.array([np.interp(d, s, path[:, 0]), np.interp(d, s, path[:, 1])]) for d in np.linspace(0.05, 0.5, n)]


def warm_times(world, seed, first, reps, **kw):
    """Median time and iterations of warm-started re-solves after the start moved; failures counted."""
    ts, its, fails = [], [], 0
    for start in moved_starts(first.path, reps):
        moved = np.vstack([start, seed[1:]])
        t = time.perf_counter()
        r = smooth_path(world, moved, warm_start=first, **kw)
        ts.append(time.perf_counter() - t)
        its.append(r.iterations)
        fails += not (r.success and not r.message)
    return float(np.median(ts)), int(np.median(its)), fails


def circle_timings(reps: int) -> None:
    print("## 1. CasADi/IPOPT on circle worlds\n")
    print("| map | seed | N | build [s] | cold median [s] | cold CPU [s] | cold its | warm median [s] | warm its "
          "| warm not clean | rounds | length [m] | optimum [m] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name in ("yang2023_env1", "yang2023_env2"):
        world, s, g = paper_map(name)
        opt = op.shortest_path(world, s, g, method="visibility")
        for label, seed in (("pso", seed_for(world, s, g)), ("visibility", opt.path)):
            n = smoothing.default_points(seed, 0.25)
            smoothing.clear_solver_cache()
            t = time.perf_counter()
            smoothing.circle_nlp(n, min(2, len(world.circles)), 0.5)
            build = time.perf_counter() - t
            first, cold, cold_cpu = timed(lambda: smooth_path(world, seed), reps, cpu=True)
            warm, warm_its, fails = warm_times(world, seed, first, reps)
            print(f"| {name} | {label} | {n} | {build:.3f} | {cold:.4f} | {cold_cpu:.4f} | {first.iterations} | {warm:.4f} | {warm_its} "
                  f"| {fails}/{reps} | {first.rounds} | {op.path_metrics(world, first.path).length:.3f} | {opt.length:.3f} |")
    print("\ngoals: circle worlds 0.030 s cold / 0.015 s warm (median, N <= 100)\n")


def grid_timings(reps: int) -> None:
    print("## 2. CasADi/IPOPT on grid maps (interpolant cached)\n")
    print("NLP times without the QP polish; the polish (on by default on grids) is timed on its own.\n")
    print("| map | N | samples/segment | first call [s] | cold median [s] | cold CPU [s] | warm median [s] | warm not clean "
          "| polish [s] | NLP length [m] | polished [m] | optimum [m] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name in ("chen2025_20", "hou2024_env2", "li2023_30", "hou2024_base50", "li2023_90"):
        world, s, g = paper_map(name)
        seed = seed_for(world, s, g)
        opt = op.shortest_path(world, s, g, method="visibility").length
        for S in (1, 2):
            t = time.perf_counter()
            smooth_path(world, seed, grid_samples=S, polish=False)
            first_call = time.perf_counter() - t
            first, cold, cold_cpu = timed(lambda: smooth_path(world, seed, grid_samples=S, polish=False), reps, cpu=True)
            warm, _, fails = warm_times(world, seed, first, reps, grid_samples=S, polish=False)
            polished, t_polish = timed(lambda: smooth_path_qp(world, first.path, n_points=len(first.path)), 3)
            status = "" if first.success and not first.message else " (cold: " + first.message[:60] + ")"
            print(f"| {name} | {len(first.path)} | {S} | {first_call:.3f} | {cold:.4f}{status} | {cold_cpu:.4f} | {warm:.4f} | {fails}/{reps} "
                  f"| {t_polish:.4f} | {op.path_metrics(world, first.path).length:.3f} "
                  f"| {op.path_metrics(world, polished.path).length:.3f} | {opt:.3f} |")
    print("\ngoal: grids 0.150 s per solve once the interpolant is cached (first call includes the distance field)\n")


def same_problem(n: int = 40, K: int = 3) -> None:
    from scipy.optimize import minimize

    world, s, g = paper_map("yang2023_env1")
    X0 = sample_for_corridor(world, seed_for(world, s, g), n)
    N = len(X0)
    Q = smoothing._query_points(X0)
    idx = smoothing.nearest_circles(world, Q, K)
    C = world.circles[idx, :2]
    R = world.radii[idx] + 1e-3
    ends = np.stack([X0[0], X0[-1]])
    w = 0.5
    nlp = smoothing.circle_nlp(N, K, w)
    lbx, ubx = smoothing._box_bounds(world, N, 0.0)
    p = np.concatenate([ends.ravel(), C[..., 0].ravel(order="F"), C[..., 1].ravel(order="F"), R.ravel(order="F")])
    args = dict(x0=smoothing._pack(X0), p=p, lbx=lbx, ubx=ubx, lbg=0.0, ubg=np.inf)
    nlp["cold"](**args)  # build and warm the caches
    sol, t_ipopt = timed(lambda: nlp["cold"](**args), 3)

    def objective(z):
        return smoothing.smoothing_objective(smoothing._unpack(z, ends), w)

    def constraints(z):
        q = smoothing._query_points(smoothing._unpack(z, ends))
        return (((q[:, None, :] - C) ** 2).sum(axis=2) - R ** 2).ravel()

    t = time.perf_counter()
    res = minimize(objective, smoothing._pack(X0), method="SLSQP", constraints=[{"type": "ineq", "fun": constraints}],
                   bounds=list(zip(lbx, ubx)), options={"maxiter": 500})
    t_slsqp = time.perf_counter() - t
    corridor = build_corridor(world, X0)
    rows = []
    for backend in ("osqp", "cvxpy"):
        prog = corridor_program(corridor.n_points, corridor.k_slots, w, backend)
        prog.solve(corridor)  # set-up / canonicalisation happens once
        qp, t_qp = timed(lambda: prog.solve(corridor), 3)
        full, t_full = timed(lambda: smooth_path_qp(world, X0, backend=backend, n_points=N), 3)
        rows.append((backend, qp, t_qp, full, t_full))
    print(f"## 3. The same problem (yang2023_env1, N = {N}, K = {K} circles per sample, J = sum|d|^2 + {w} sum|dd|^2)\n")
    print("| solver | feasible set | time [s] | objective J | status |")
    print("|---|---|---|---|---|")
    print(f"| IPOPT (casadi nlpsol, exact Hessian) | NLP, fixed neighbours | {t_ipopt:.4f} | {objective(np.asarray(sol['x']).ravel()):.6f} "
          f"| {nlp['cold'].stats()['return_status']} |")
    print(f"| SLSQP (scipy, finite-difference gradients) | NLP, fixed neighbours | {t_slsqp:.4f} | {res.fun:.6f} | {res.message} |")
    for backend, qp, t_qp, full, t_full in rows:
        print(f"| QP corridor, {backend} (one solve) | corridor around the seed | {t_qp:.4f} | {qp.objective:.6f} | {qp.status} |")
        print(f"| QP corridor, {backend} (smooth_path_qp, {full.rounds} rounds, N = {len(full.path)}) | corridors, rebuilt | {t_full:.4f} "
              f"| {full.objective:.6f} | {'valid' if full.success else full.message} |")
    print(f"\nIPOPT speed-up over SLSQP {t_slsqp / t_ipopt:.1f}x (goal >= 20x)\n")


def ipopt_options(reps: int) -> None:
    variants = {
        "adaptive (default)": {},
        "monotone": {"mu_strategy": "monotone"},
        "monotone, mu_init 1e-2": {"mu_strategy": "monotone", "mu_init": 1e-2},
        "monotone, mu_init 1e-3": {"mu_strategy": "monotone", "mu_init": 1e-3},
        "adaptive, no NLP scaling": {"nlp_scaling_method": "none"},
        "adaptive, L-BFGS Hessian": {"hessian_approximation": "limited-memory", "max_iter": 100},
    }
    cases = []
    for name in ("yang2023_env1", "yang2023_env2"):
        world, s, g = paper_map(name)
        cases += [(world, op.plan(world, s, g, algorithm=a, seed=k, pop=30, iters=60).path) for k, a in enumerate(("pso", "ipso"))]
        cases.append((world, op.shortest_path(world, s, g, method="visibility").path))
    for name in ("chen2025_20", "li2023_30", "hou2024_env2"):
        world, s, g = paper_map(name)
        cases.append((world, seed_for(world, s, g)))
    print(f"## 4. IPOPT options, cold solves of {len(cases)} problems (6 circle-world seeds, 3 A* grid seeds)\n")
    print("| options | total iterations | failures | median time per solve [s] |")
    print("|---|---|---|---|")
    saved = dict(smoothing.IPOPT_OPTIONS)
    try:
        for label, extra in variants.items():
            smoothing.IPOPT_OPTIONS.clear()
            smoothing.IPOPT_OPTIONS.update({**saved, **extra})
            smoothing.clear_solver_cache(*[w for w, _ in cases])
            its, fails, ts = 0, 0, []
            for world, seed in cases:
                smooth_path(world, seed)  # build
                r, t = timed(lambda: smooth_path(world, seed), 1 if "L-BFGS" in label else max(1, reps // 3))
                its += r.iterations
                fails += not (r.success and not r.message)
                ts.append(t)
            print(f"| {label} | {its} | {fails} | {np.median(ts):.4f} |")
    finally:
        smoothing.IPOPT_OPTIONS.clear()
        smoothing.IPOPT_OPTIONS.update(saved)
        smoothing.clear_solver_cache(*[w for w, _ in cases])
    print("\nfailures: the first attempt did not end valid (retried or fell back). Linear solver: MUMPS, the only one "
          "bundled with the casadi wheel (HSL ma27/ma57 are not available). Warm starts use monotone mu with "
          "mu_init 1e-6 (1e-4 and 1e-3 took 2-4x the iterations on the same cases).\n")


def qp_timings(reps: int) -> None:
    print("## 5. QP corridor smoother (refine='qp', OSQP) per map\n")
    print("| map | seed | N | median [s] | rounds | seed length [m] | refined [m] | optimum [m] |")
    print("|---|---|---|---|---|---|---|---|")
    for name in ("yang2023_env1", "yang2023_env2", "chen2025_20", "hou2024_env2", "li2023_30", "hou2024_base50", "li2023_90"):
        world, s, g = paper_map(name)
        seed = seed_for(world, s, g)
        opt = op.shortest_path(world, s, g, method="visibility").length
        smooth_path_qp(world, seed)
        r, t = timed(lambda: smooth_path_qp(world, seed), reps)
        print(f"| {name} | {'A*' if hasattr(world, 'occ') else 'pso'} | {len(r.path)} | {t:.4f} | {r.rounds} "
              f"| {op.path_metrics(world, seed).length:.3f} | {op.path_metrics(world, r.path).length:.3f} | {opt:.3f} |")
    print()


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="3 repetitions instead of 7")
    ap.add_argument("--part", choices=["all", "circles", "grids", "same", "options", "qp"], default="all")
    a = ap.parse_args(argv)
    reps = 3 if a.quick else REPS
    parts = {"circles": lambda: circle_timings(reps), "grids": lambda: grid_timings(reps), "same": same_problem,
             "options": lambda: ipopt_options(reps), "qp": lambda: qp_timings(reps)}
    for key, fn in parts.items():
        if a.part in ("all", key):
            fn()


if __name__ == "__main__":
    main()
