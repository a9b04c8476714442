"""Speed of programs (issue 24): the cost of writing a term once, and IPOPT vs SLSQP.

1. Batched evaluation of a custom term (``T.custom(fn)``, evaluated through the batched
   namespace) against a hand-written numpy function of the same math, over 500 calls on a
   population of 30 paths (one swarm run of pop 30 x 500 iterations). Also the whole
   program (length + the custom term + the exact clearance constraint) against a
   hand-written objective doing the same.
2. IPOPT and SLSQP on the same program from the same start, in one run: the smoothing
   program (squared length + bending over n dense points, clearance >= 0.1 m) on paper
   maps, started from the A* path.

    python benchmarks/program_speed.py [--repeat 5] [--ipopt-runs 3] [--maps chen2025_20 ...]
"""
from __future__ import annotations

import argparse
import time

import numpy as np

import optplan as op
from optplan import terms as T
from optplan.formulations.terms import collisions
from optplan.world.papermaps import paper_map


def exposure(P, m):
    d = (P - np.array([10.0, 10.0])) / 5.0
    seg = m.norm(m.diff(P, axis=0), axis=1)
    near = m.exp(-m.sum(d * d, axis=1))
    return m.sum(seg * (near[1:] + near[:-1]) / 2)


def exposure_numpy(P):
    """The same math, written by hand for a population ``(n, N, 2)``."""
    d = (P - np.array([10.0, 10.0])) / 5.0
    dd = np.diff(P, axis=1)
    seg = np.sqrt((dd * dd).sum(axis=2))
    near = np.exp(-(d * d).sum(axis=2))
    return (seg * (near[:, 1:] + near[:, :-1]) / 2).sum(axis=1)


def best_of(fn, repeat):
    out = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t)
    return min(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--ipopt-runs", type=int, default=3, help="cold IPOPT solves per row (median)")
    ap.add_argument("--maps", nargs="+", default=["chen2025_20", "hou2024_env2", "li2023_30"])
    a = ap.parse_args(argv)
    world, s, g = paper_map("chen2025_20")
    prog = op.PathProgram(world, s, g, variables=op.Waypoints(6))
    term = T.custom(exposure, name="exposure")
    prog.minimize(T.length() + 2.0 * term)
    prog.subject_to(T.clearance() >= 0.1)
    v = prog.variables
    rng = np.random.default_rng(0)
    pops = [v.lower + rng.random((30, v.dim)) * (v.upper - v.lower) for _ in range(500)]
    paths = [v.decode(X) for X in pops]
    ctx = prog.ctx
    np.testing.assert_allclose(term.batch(paths[0], ctx), exposure_numpy(paths[0]), rtol=1e-12)

    t_custom = best_of(lambda: [term.batch(P, ctx) for P in paths], a.repeat)
    t_hand = best_of(lambda: [exposure_numpy(P) for P in paths], a.repeat)

    def hand_program(X):
        P = v.decode(X)
        dd = np.diff(P, axis=1)
        cost = np.sqrt((dd * dd).sum(axis=2)).sum(axis=1) + 2.0 * exposure_numpy(P)
        return cost, collisions(world, P, 0.1)

    t_prog = best_of(lambda: [prog.population(X) for X in pops], a.repeat)
    t_prog_hand = best_of(lambda: [hand_program(X) for X in pops], a.repeat)
    print("1. batched evaluation, 500 calls x pop 30 (best of", a.repeat, "runs)")
    print(f"{'what':<42} {'written once (s)':>16} {'hand numpy (s)':>15} {'ratio':>6}")
    print(f"{'custom term alone':<42} {t_custom:>16.4f} {t_hand:>15.4f} {t_custom / t_hand:>6.2f}")
    print(f"{'program: length + term + exact clearance':<42} {t_prog:>16.4f} {t_prog_hand:>15.4f} "
          f"{t_prog / t_prog_hand:>6.2f}")
    print()
    print("2. IPOPT vs SLSQP, smoothing program from the A* path (same program, same start).")
    print(f"   IPOPT: median of {a.ipopt_runs} cold solves, each on a new program instance (so each builds its "
          "CasADi problem); SLSQP: one solve.")
    print("   wall: seconds of wall time; cpu: seconds of this process's CPU time (robust to other load on the machine)")
    print(f"{'map':<16} {'n':>4} {'ipopt wall':>10} {'slsqp wall':>10} {'ratio':>6} {'ipopt cpu':>9} {'slsqp cpu':>9} "
          f"{'ratio':>6} {'ipopt cost':>11} {'slsqp cost':>11} {'both feasible':>13}")

    def timed(prog, solver, seed_path):
        c = time.process_time()
        r = prog.solve(solver, init=seed_path)
        return r, time.process_time() - c

    for name in a.maps:
        w, s2, g2 = paper_map(name)
        seed = op.plan(w, s2, g2, algorithm="astar")
        for n in (60, 120):
            runs = [timed(op.smoothing_program(w, s2, g2, n=n, clearance=0.1), "ipopt", seed.path)
                    for _ in range(a.ipopt_runs)]
            ri = runs[0][0]
            wall_i = float(np.median([r.runtime_s for r, _ in runs]))
            cpu_i = float(np.median([c for _, c in runs]))
            rs, cpu_s = timed(op.smoothing_program(w, s2, g2, n=n, clearance=0.1), "slsqp", seed.path)
            print(f"{name:<16} {n:>4} {wall_i:>10.2f} {rs.runtime_s:>10.2f} {rs.runtime_s / wall_i:>6.1f} "
                  f"{cpu_i:>9.2f} {cpu_s:>9.2f} {cpu_s / cpu_i:>6.1f} "
                  f"{ri.cost:>11.4f} {rs.cost:>11.4f} {str(ri.feasible and rs.feasible):>13}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
