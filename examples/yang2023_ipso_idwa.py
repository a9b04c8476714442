"""Reproduce yang2023 (IPSO-IDWA) with optplan.

--part global: Tables 1-3 analog on the circle-world stand-ins for environments
1 and 2 ((0,0)->(10,10) and (0,0)->(15,15)): PSO vs IPSO (IPSO1/IPSO2 are not
implemented), spline paths through 3 handle points (eq 3-4), population 50, 300
iterations (§7.1), 20 runs. Table 3 analog: the median converged length and the
iteration at which each run reached it. Lengths stand next to the exact optimum
(tangent graph).

    python examples/yang2023_ipso_idwa.py --part global [--runs 20] [--quick]
"""
from __future__ import annotations

import argparse

import numpy as np

from optplan.bench.global_runs import convergence_iteration, paper_global


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["global", "local"], default="global")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--quick", action="store_true", help="one environment, 3 runs, 40 iterations")
    args = ap.parse_args(argv)
    if args.part == "local":
        print("the local part (§7.2-7.3, IDWA) is not available yet")
        return 2
    maps = ["yang2023_env1"] if args.quick else ["yang2023_env1", "yang2023_env2"]
    runs = 3 if args.quick else args.runs
    iters = 40 if args.quick else 300
    out = paper_global("yang2023 Tables 1-2 analog: PSO vs IPSO (pop 50, spline through 3 handles)", maps,
                       ["pso", "ipso"], runs, reference="pso", pop=50, iters=iters)
    print("## yang2023 Table 3 analog: convergence\n")
    print("| environment | algorithm | median converged fitness | median convergence iteration |")
    print("|---|---|---|---|")
    for name, sets in out.items():
        for s in sets:
            fin = [r.history[-1] for r in s.results]
            its = [convergence_iteration(r.history) for r in s.results]
            print(f"| {name} | {s.algorithm} | {np.median(fin):.4f} | {np.median(its):.0f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
