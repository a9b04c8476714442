"""Reproduce hou2024 (MISSA-DWA) with optplan.

--part global: Tables 2-3 analog on the stand-ins for environment models 1 and 2
(hou2024_env1/env2): ACO, SSA and MISSA (IACO is not implemented), 50 runs,
Table 1 settings (60 individuals, 300 iterations; ACO alpha 2, beta 6, rho 0.1,
Q 5): min/mean length, total rotation angle and time, plus what the paper lacks:
the gap to the exact any-angle optimum and the rank-sum p-value against SSA.

    python examples/hou2024_missa_dwa.py --part global [--runs 50] [--quick]
"""
from __future__ import annotations

import argparse

from optplan.bench.global_runs import paper_global


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["global", "local"], default="global")
    ap.add_argument("--runs", type=int, default=50)
    ap.add_argument("--quick", action="store_true", help="one map, 3 runs, 60 iterations")
    args = ap.parse_args(argv)
    if args.part == "local":
        print("the local part (Table 4, dynamic environments) is not available yet")
        return 2
    maps = ["hou2024_env1"] if args.quick else ["hou2024_env1", "hou2024_env2"]
    runs = 3 if args.quick else args.runs
    iters = 60 if args.quick else 300
    paper_global("hou2024 Tables 2-3 analog: ACO, SSA, MISSA (pop 60)", maps, ["aco", "ssa", "missa"], runs,
                 reference="ssa", pop=60, iters=iters)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
