"""Global planning on generated maps (issue 26): the general encoding, the refinement's own job,
and the fused pipeline, each gap split into the class gap and the in-class gap.

    python benchmarks/general_planning.py --part encoding [--split dev|heldout|fresh] [--runs 5]
    python benchmarks/general_planning.py --part refine   [--split dev|heldout|fresh]
    python benchmarks/general_planning.py --part fused    [--split dev|heldout|fresh]
    python benchmarks/general_planning.py --part defaults [--split defaults]

Maps come from :func:`optplan.worldgen.maps.generate_map`. ``dev`` seeds (0-99) are the ones
the code was developed on; ``heldout`` seeds (7000+) were not looked at before measuring;
``fresh`` seeds (9000+) were kept back after a held-out failure had been diagnosed.

* ``encoding``: every metaheuristic with ``encoding="general"`` and 15,000 evaluations on
  rooms, mazes, random 15-30 % and warehouse maps (20-64 cells): share of feasible runs and
  best-of-``runs`` gap to the exact optimum per (map, algorithm), from the default start
  (random corridors) and, in the last columns, from the algorithm's own start (``init="own"``).
* ``refine``: seeds from the paper encodings (missa, msiar-gwo, pso; their default encodings)
  on random 20x20 maps with 20 % blocked cells, refined with ``refine="casadi"`` and
  ``tube_radius=0``: share of runs within 1 % of the *seed's* class optimum.
* ``fused``: msiar-gwo, missa, pso with ``encoding="general"`` + ``refine="casadi"``, same
  budget (15,000 evaluations), on random 20x20 maps with 20 % blocked cells: share within 1 %
  of the exact optimum, and for comparison the paper encodings + casadi.
* ``defaults`` (issue 43): what a new user gets, ``op.plan(grid, s, g, algorithm=X)`` with no
  option but the seed (default budget, default encoding), for every metaheuristic and the
  path GAs, on random (20 %), rooms and maze grids of 20-48 cells at the ``defaults`` seeds
  (7700+, drawn after the default was chosen): best-of-``runs`` gap to the exact optimum,
  and the share of ``refine="casadi"`` runs within 1 % of it (goals: <= 1 % and >= 95 %).

Every row reports the class gap (corridor chosen by the global stage) and the in-class gap
(shape) separately (:func:`optplan.solvers.gaps.class_gaps`). Timings are not reported here.
"""
from __future__ import annotations

import argparse

import numpy as np

import optplan as op
from optplan.solvers.gaps import class_gaps
from optplan.solvers.refine import refine_result
from optplan.worldgen.maps import generate_map, map_query

ALGORITHMS = ["ssa", "missa", "pso", "ipso", "ba", "iba", "ga", "gwo", "msiar-gwo", "woa", "aro", "dbo", "igwo"]
FUSED = ["msiar-gwo", "missa", "pso"]
SEED_BASE = {"dev": 0, "heldout": 7000, "fresh": 9000, "defaults": 7700}
DEFAULT_PLANNERS = ALGORITHMS + ["iga"]


def encoding_maps(split: str) -> list:
    """(label, grid, start, goal) for the encoding figure."""
    b = SEED_BASE[split]
    specs = [("rooms", 32, {}), ("maze", 33, {}), ("random", 20, {"density": 0.15}),
             ("random", 32, {"density": 0.25}), ("random", 24, {"density": 0.30}), ("warehouse", 64, {}),
             ("rooms", 48, {}), ("random", 64, {"density": 0.20})]
    out = []
    for k, (kind, n, kw) in enumerate(specs):
        grid = generate_map(kind, n, seed=b + k, **kw)
        s, g = map_query(grid, seed=b + k)
        out.append((grid.name + (f"-{int(100 * kw['density'])}%" if kw else ""), grid, s, g))
    return out


def random20_maps(split: str, count: int) -> list:
    b = SEED_BASE[split] + 50
    out = []
    for k in range(count):
        grid = generate_map("random", 20, seed=b + k, density=0.20)
        s, g = map_query(grid, seed=b + k)
        out.append((grid.name, grid, s, g))
    return out


def part_encoding(split: str, runs: int, evals: int) -> None:
    print(f"general encoding, {evals} evaluations, {runs} runs per (map, algorithm), split {split}\n")
    print("| map | algorithm | feasible | best gap % | median gap % | median class gap % | median in-class gap % "
          "| optimal class | init='own': feasible | init='own': best gap % |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    worst, all_feasible = 0.0, True
    for label, grid, s, g in encoding_maps(split):
        exact = op.shortest_path(grid, s, g, method="visibility")
        for algo in ALGORITHMS:
            rows = []
            for seed in range(runs):
                r = op.plan(grid, s, g, algorithm=algo, encoding="general", max_evals=evals, seed=seed)
                rows.append((r.feasible, class_gaps(grid, s, g, r.path, exact)))
            feas = sum(f for f, _ in rows)
            gaps = np.array([d["gap"] if f else np.inf for f, d in rows])
            cg = np.array([d["class_gap"] if f else np.nan for f, d in rows])
            ig = np.array([d["in_class_gap"] if f else np.nan for f, d in rows])
            opt = sum(bool(d["optimal_class"]) for f, d in rows if f)
            worst = max(worst, gaps.min())
            all_feasible &= feas == runs
            # the same runs from the algorithm's own random start instead of random corridors
            own = [op.plan(grid, s, g, algorithm=algo, encoding="general", max_evals=evals, seed=seed, init="own")
                   for seed in range(runs)]
            own_gap = min((r.length / exact.length - 1) if r.feasible else np.inf for r in own)
            print(f"| {label} | {algo} | {feas}/{runs} | {100 * gaps.min():.2f} | {100 * np.median(gaps):.2f} | "
                  f"{100 * np.nanmedian(cg):.2f} | {100 * np.nanmedian(ig):.2f} | {opt}/{runs} | "
                  f"{sum(r.feasible for r in own)}/{runs} | {100 * own_gap:.2f} |", flush=True)
    print(f"\nall runs feasible: {all_feasible}; worst best-of-{runs} gap: {100 * worst:.2f} % (goal <= 3 %)")


def part_refine(split: str, maps: int, runs: int, evals: int) -> None:
    print(f"refine='casadi', tube_radius=0, seeds from the paper encodings ({evals} evaluations), "
          f"{maps} random 20x20 maps (20 %), {runs} seeds each, split {split}\n")
    print("| planner | runs | seed feasible | within 1 % of seed's class optimum | median refined / class optimum - 1 % "
          "| seed in-class gap % (median) |")
    print("|---|---|---|---|---|---|")
    total_in = total = 0
    for algo in FUSED:
        ok = n = feas = 0
        ratio, seed_in = [], []
        for label, grid, s, g in random20_maps(split, maps):
            exact = op.shortest_path(grid, s, g, method="visibility")
            for seed in range(runs):
                pure = op.plan(grid, s, g, algorithm=algo, encoding="paper", max_evals=evals, seed=seed)
                n += 1
                if not pure.feasible:
                    continue
                feas += 1
                before = class_gaps(grid, s, g, pure.path, exact)
                ref = refine_result(grid, pure, method="casadi", tube_radius=0.0, starts=1)
                q = ref.length / before["class_length"] - 1 if ref.feasible else np.inf
                ratio.append(q)
                seed_in.append(before["in_class_gap"])
                ok += q <= 0.01
        total_in += ok
        total += feas
        print(f"| {algo} | {n} | {feas} | {ok}/{feas} | {100 * np.median(ratio):.3f} | "
              f"{100 * np.median(seed_in):.2f} |", flush=True)
    print(f"\nwithin 1 % of the seed's class optimum: {total_in}/{total} = {100 * total_in / max(total, 1):.1f} % "
          "(goal >= 95 %)")


def part_fused(split: str, maps: int, runs: int, evals: int) -> None:
    print(f"fused pipeline (planner + refine='casadi'), {evals} evaluations, {maps} random 20x20 maps (20 %), "
          f"{runs} seeds each, split {split}\n")
    print("| planner | encoding | runs | within 1 % of optimum | optimal class | median class gap % "
          "| median in-class gap % |")
    print("|---|---|---|---|---|---|---|")
    summary = {}
    for encoding in ("general", "paper"):
        for algo in FUSED:
            within = opt = n = 0
            cg, ig = [], []
            for label, grid, s, g in random20_maps(split, maps):
                exact = op.shortest_path(grid, s, g, method="visibility")
                for seed in range(runs):
                    r = op.plan(grid, s, g, algorithm=algo, max_evals=evals, seed=seed, refine="casadi",
                                encoding=encoding)
                    n += 1
                    d = class_gaps(grid, s, g, r.path, exact)
                    if d["gap"] is None:
                        continue
                    within += d["gap"] <= 0.01
                    opt += bool(d["optimal_class"])
                    cg.append(d["class_gap"])
                    ig.append(d["in_class_gap"])
            summary[(encoding, algo)] = (within, n)
            print(f"| {algo} | {encoding} | {n} | {within}/{n} | {opt}/{n} | {100 * np.median(cg):.2f} | "
                  f"{100 * np.median(ig):.2f} |", flush=True)
    w = sum(summary[("general", a)][0] for a in FUSED)
    n = sum(summary[("general", a)][1] for a in FUSED)
    print(f"\ngeneral encoding + casadi within 1 % of the exact optimum: {w}/{n} = {100 * w / max(n, 1):.1f} % "
          "(goal >= 90 %)")


def default_maps(split: str) -> list:
    """(label, grid, start, goal) for the defaults figure: random, rooms and maze grids."""
    b = SEED_BASE[split]
    specs = [("random", 20, {"density": 0.20}), ("random", 32, {"density": 0.20}), ("rooms", 24, {}),
             ("rooms", 40, {}), ("maze", 25, {}), ("maze", 41, {}), ("random", 48, {"density": 0.20})]
    out = []
    for k, (kind, n, kw) in enumerate(specs):
        grid = generate_map(kind, n, seed=b + k, **kw)
        s, g = map_query(grid, seed=b + k)
        out.append((f"{kind}{n}-s{b + k}", grid, s, g))
    return out


def part_defaults(split: str, runs: int, planners=None) -> None:
    print(f"defaults: op.plan(grid, s, g, algorithm=X, seed=k) and the same with refine='casadi', "
          f"{runs} seeds per (map, planner), split {split}\n")
    print("| planner | encoding used | runs | feasible | worst best-of-5 gap % | median gap % "
          "| casadi within 1 % | casadi median gap % |")
    print("|---|---|---|---|---|---|---|---|")
    maps = [(label, grid, s, g, op.shortest_path(grid, s, g, method="visibility").length)
            for label, grid, s, g in default_maps(split)]
    worst_all, within_all, n_all = 0.0, 0, 0
    for algo in planners or DEFAULT_PLANNERS:
        feas = n = within = 0
        best, gaps, rgaps, used = [], [], [], set()
        for label, grid, s, g, exact in maps:
            mine = []
            for seed in range(runs):
                r = op.plan(grid, s, g, algorithm=algo, seed=seed)
                ref = op.plan(grid, s, g, algorithm=algo, seed=seed, refine="casadi")
                used.add(r.encoding or "-")
                n += 1
                feas += r.feasible
                gap = r.length / exact - 1 if r.feasible else np.inf
                rgap = ref.length / exact - 1 if ref.feasible else np.inf
                mine.append(gap)
                gaps.append(gap)
                rgaps.append(rgap)
                within += rgap <= 0.01
            best.append(min(mine))
        worst_all = max(worst_all, max(best))
        within_all += within
        n_all += n
        print(f"| {algo} | {', '.join(sorted(used))} | {n} | {feas}/{n} | {100 * max(best):.2f} | "
              f"{100 * np.median(gaps):.2f} | {within}/{n} | {100 * np.median(rgaps):.2f} |", flush=True)
    print(f"\nworst best-of-{runs} gap over every planner and map: {100 * worst_all:.2f} % (goal <= 1 %); "
          f"refine='casadi' within 1 %: {within_all}/{n_all} = {100 * within_all / max(n_all, 1):.1f} % (goal >= 95 %)")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", choices=["encoding", "refine", "fused", "defaults"], required=True)
    ap.add_argument("--split", choices=sorted(SEED_BASE), default="heldout")
    ap.add_argument("--runs", type=int, default=None, help="seeds per (map, algorithm) (encoding and defaults 5, "
                    "others 3)")
    ap.add_argument("--maps", type=int, default=10, help="random 20x20 maps for refine / fused (default 10)")
    ap.add_argument("--evals", type=int, default=15000, help="evaluation budget per run (default 15000)")
    ap.add_argument("--planners", nargs="+", default=None, help="defaults part: only these planners")
    a = ap.parse_args(argv)
    if a.part == "encoding":
        part_encoding(a.split, a.runs or 5, a.evals)
    elif a.part == "defaults":
        part_defaults(a.split if a.split != "heldout" else "defaults", a.runs or 5, a.planners)
    elif a.part == "refine":
        part_refine(a.split, a.maps, a.runs or 3, a.evals)
    else:
        part_fused(a.split, a.maps, a.runs or 3, a.evals)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
