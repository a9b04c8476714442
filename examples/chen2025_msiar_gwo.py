"""Reproduce chen2025 (MSIAR-GWO) with optplan.

--part functions: Tables 4-7 analog. F1-F18, 20 runs x 500 iterations x population
30, for MSIAR-GWO and the baselines optplan has (GWO, ARO, DBO, WOA, IGWO; AGWO and
RSMGWO are not implemented: docs/fidelity/chen2025.md). Run twice: F1-F13 shifted off
the origin (the headline; see optplan.formulations.functions) and unshifted, as the
paper prints them. Prints best/mean/worst/std tables, the Wilcoxon rank-sum table
with the +/=/- tally against MSIAR-GWO, and saves convergence plots in --out.

--part paths: Tables 8-11 analog on the stand-in maps chen2025_20/30/40: the same
algorithms (20 runs, population 30, 500 iterations) under the paper's protocol (eq 32
scored on the pruned path, own initialisation), then MSIAR-GWO and GWO under the
feasibility-rule protocol (-fair rows); each length next to the exact any-angle
optimum, A* vs MSIAR-GWO (Table 8), and the paper's claims judged.

Both parts run the shipped specs (chen2025_functions, chen2025_functions_unshifted,
chen2025_paths), exactly as ``optplan reproduce chen2025 --part PART`` does.

    python examples/chen2025_msiar_gwo.py --part functions [--runs 20] [--quick]
    python examples/chen2025_msiar_gwo.py --part paths [--runs 20] [--quick]
"""
from __future__ import annotations

import argparse
from pathlib import Path

from optplan.bench.command import reproduce


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["functions", "paths"], default="functions")
    ap.add_argument("--runs", type=int, default=None, help="runs per algorithm (default: the paper's 20)")
    ap.add_argument("--quick", action="store_true", help="3 runs, short budgets, a few functions/one map")
    ap.add_argument("--out", default="out/chen2025", help="folder for plots")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    return reproduce("chen2025", args.part, quick=args.quick, runs=args.runs, workers=1,
                     plots=str(out) if args.part == "functions" else None)


if __name__ == "__main__":
    raise SystemExit(main())
