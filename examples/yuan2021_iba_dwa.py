"""Reproduce yuan2021 (IBA-DWA) with optplan.

--part global: Tables 1-2 analog on the 25x25 stand-in map: BA vs IBA, 20 runs.
Table 1 is the shortest collision-free path (mu = 0 in eq 13, preset
``yuan2021``); Table 2 adds the turning cost (mu = 1, preset ``yuan2021-smooth``)
and reports turns. Each length is shown next to the exact any-angle optimum.

    python examples/yuan2021_iba_dwa.py --part global [--runs 20] [--quick]
"""
from __future__ import annotations

import argparse

from optplan.bench.global_runs import paper_global


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["global", "local"], default="global")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--quick", action="store_true", help="3 runs, 60 iterations")
    args = ap.parse_args(argv)
    if args.part == "local":
        print("the local part (§5.2-5.3, added obstacles and path switch) is not available yet")
        return 2
    runs = 3 if args.quick else args.runs
    iters = 60 if args.quick else 300
    paper_global("yuan2021 Table 1 analog: shortest collision-free path (mu = 0)", ["yuan2021_25"], ["ba", "iba"],
                 runs, reference="ba", pop=50, iters=iters, preset="yuan2021")
    sets = paper_global("yuan2021 Table 2 analog: with the turning cost (mu = 1)", ["yuan2021_25"], ["ba", "iba"],
                        runs, reference="ba", pop=50, iters=iters, preset="yuan2021-smooth")
    for s in sets["yuan2021_25"]:
        turns = [r.n_turns for r in s.feasible]
        if turns:
            print(f"{s.algorithm}: turns min {min(turns)}, mean {sum(turns) / len(turns):.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
