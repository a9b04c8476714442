"""Engine speed and final quality against mealpy and niapy, anchors printed in the same run.

    python benchmarks/engine_speed.py [--runs 10] [--heldout] [--anchor-python PATH] [--no-anchors]
    python benchmarks/engine_speed.py --batched-only [--runs 5]     # table 3 alone, no anchors

Three tables (issue 30):

1. Speed: wall time per run at pop 30 x 500 iterations on the 30-d sphere, median
   of ``--runs`` runs, for every registered algorithm; mealpy's and niapy's GWO and
   PSO on the same problem, and the ratio (goal: at least 25x faster than mealpy).
2. Quality at equal evaluations: PSO, GWO, WOA and SSA on the shifted 30-d sphere
   (F1) and Rastrigin (F9) with pop 30 and 15,030 evaluations, median of ``--runs``
   seeds, against the anchors' same-named algorithms (goal: our median no worse, or
   a rank-sum p > 0.05). The anchors see the same shift vectors. The fixes were made
   looking at seeds 0-4 of the library's shifts (``get_function(..., shifted=True)``);
   ``--heldout`` draws other shift vectors (same rule: inside 80 % of the box) and
   seeds 1000, 1001, ... instead, and prints only this table.
3. Batched seeds: 20 seeds of GWO (pop 30 x 500 iterations, 30-d) through
   ``op.optimize(..., seeds=range(20))`` against one run (goal: at most 3x), next to
   the time the 20 seeds' own generators take to draw their numbers alone (results
   identical seed by seed need every seed's PCG64 stream) and that plus GWO's update
   arithmetic alone: two floors of the ratio. Wall and CPU time (the CPU time of this
   process is what a loaded machine disturbs least).

mealpy pins an older numpy, which breaks optplan's other dependencies, so the anchors
run in a virtual environment of their own: ``benchmarks/anchor_runs.py`` is executed
with that environment's Python (default ``/tmp/mealpy-venv``, created with
``pip install mealpy==3.0.3 niapy`` when absent). Timings on a shared machine are
inflated; the ratios are what to read.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from scipy.stats import ranksums

import optplan as op
from optplan.formulations.functions import get_function
from optplan.solvers.metaheuristics import algorithm_names
from optplan.solvers.budget import Budget
from optplan.solvers.metaheuristics.engine import BatchState, Problem, SeedGenerators
from optplan.solvers.metaheuristics.gwo import GWO

HERE = Path(__file__).resolve().parent
DEFAULT_VENV = Path("/tmp/mealpy-venv")
ANCHOR_PACKAGES = ("mealpy==3.0.3", "niapy")
POP, ITERS, EVALS = 30, 500, 15030
PROBLEMS = {"F1": "sphere", "F9": "rastrigin"}
# our algorithm -> the anchors' same-named algorithms
SAME_NAMED = {
    "pso": ("mealpy OriginalPSO", "mealpy LDW_PSO", "niapy ParticleSwarmAlgorithm"),
    "gwo": ("mealpy OriginalGWO", "niapy GreyWolfOptimizer"),
    "woa": ("mealpy OriginalWOA",),
    "ssa": ("mealpy OriginalSSA",),
}
HELDOUT_SHIFT_SEED, HELDOUT_FIRST_SEED = 20261202, 1000
SPEED_PAIRS = {"gwo": ("mealpy OriginalGWO", "niapy GreyWolfOptimizer"),
               "pso": ("mealpy OriginalPSO", "niapy ParticleSwarmAlgorithm")}


def anchor_python(venv: Path) -> Path | None:
    """The anchor environment's Python, created with mealpy and niapy when absent."""
    py = venv / "bin" / "python"
    probe = [str(py), "-c", "import mealpy, niapy"]
    if py.exists() and subprocess.run(probe, capture_output=True).returncode == 0:
        return py
    print(f"installing {', '.join(ANCHOR_PACKAGES)} into {venv} (kept out of optplan's environment) ...",
          file=sys.stderr)
    try:
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        subprocess.run([str(py), "-m", "pip", "install", "-q", *ANCHOR_PACKAGES], check=True)
    except (subprocess.CalledProcessError, OSError) as exc:
        print(f"could not set up the anchors: {exc}", file=sys.stderr)
        return None
    return py if subprocess.run(probe, capture_output=True).returncode == 0 else None


def shifted_problems(heldout: bool) -> dict:
    """``name -> (f, bounds, shift)``: the library's shifted F1/F9, or held-out shifts."""
    out = {}
    for k, name in enumerate(PROBLEMS):
        if not heldout:
            F = get_function(name, shifted=True)
            out[name] = (F, F.bounds, F.shift)
            continue
        base = get_function(name)                      # optimum at the origin
        lo, hi = base.bounds[0]
        shift = np.random.default_rng([HELDOUT_SHIFT_SEED, k]).uniform(0.8 * lo, 0.8 * hi, base.dim)
        out[name] = ((lambda X, _f=base, _s=shift: _f(X - _s)), base.bounds, shift)
    return out


def seeds_of(runs: int, heldout: bool) -> list[int]:
    return list(range(HELDOUT_FIRST_SEED, HELDOUT_FIRST_SEED + runs)) if heldout else list(range(runs))


def run_anchors(py: Path, runs: int, heldout: bool) -> dict:
    """Run ``anchor_runs.py`` in the anchor environment on the same shifted problems."""
    problems = {}
    for name, (_, bounds, shift) in shifted_problems(heldout).items():
        problems[name] = {"shift": np.asarray(shift).tolist(), "lower": float(bounds[0][0]),
                          "upper": float(bounds[0][1]), "kind": PROBLEMS[name]}
    job = {"problems": problems, "max_evals": EVALS, "pop": POP, "seeds": seeds_of(runs, heldout),
           "time_iters": ITERS, "time_repeats": 0 if heldout else max(3, min(runs, 5))}
    out = subprocess.run([str(py), str(HERE / "anchor_runs.py")], input=json.dumps(job), capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout)


def sphere(X: np.ndarray) -> np.ndarray:
    return np.einsum("ij,ij->i", X, X)


def time_ours(algo: str, runs: int) -> float:
    walls = []
    for k in range(runs):
        t = time.perf_counter()
        op.optimize(sphere, [(-100, 100)] * 30, algorithm=algo, pop=POP, iters=ITERS, seed=k)
        walls.append(time.perf_counter() - t)
    return float(np.median(walls))


def finals_ours(algo: str, problem: str, runs: int, heldout: bool) -> list[float]:
    f, bounds, _ = shifted_problems(heldout)[problem]
    return [op.optimize(f, bounds, algorithm=algo, pop=POP, iters=None, max_evals=EVALS, seed=s).f
            for s in seeds_of(runs, heldout)]


def speed_table(runs: int, anchors: dict | None, before: dict[str, float]) -> None:
    print(f"## Speed: 30-d sphere, pop {POP} x {ITERS} iterations, median wall time per run\n")
    print("| algorithm | optplan [s] | anchor | anchor [s] | optplan faster by |")
    print("|---|---|---|---|---|")
    for algo in algorithm_names():
        # the pair algorithms were also timed before the anchors ran: take the median of both sittings
        ours = time_ours(algo, runs) if algo not in before else float(np.median([before[algo], time_ours(algo, runs)]))
        pairs = SPEED_PAIRS.get(algo, ()) if anchors else ()
        if not pairs:
            print(f"| {algo} | {ours:.4f} | | | |")
        for name in pairs:
            t = float(np.median(anchors["time_s"][name]))
            print(f"| {algo} | {ours:.4f} | {name} | {t:.3f} | {t / ours:.1f}x {'(>= 25x)' if t / ours >= 25 else '(< 25x)'} |")
    print()


def quality_table(runs: int, anchors: dict | None, heldout: bool) -> None:
    which = "held-out shifts and seeds" if heldout else "development shifts and seeds"
    print(f"## Final value at {EVALS:,} evaluations, pop {POP}, shifted 30-d functions ({which}), "
          f"median of {runs} seeds\n")
    print("| function | optplan | median | anchor | anchor median | anchor evals | rank-sum p | no worse |")
    print("|---|---|---|---|---|---|---|---|")
    for problem in PROBLEMS:
        for algo, names in SAME_NAMED.items():
            ours = finals_ours(algo, problem, runs, heldout)
            m = float(np.median(ours))
            if not anchors:
                print(f"| {problem} | {algo} | {m:.4g} | | | | | |")
                continue
            for name in names:
                theirs = anchors["final"][name][problem]
                mt = float(np.median(theirs))
                p = float(ranksums(ours, theirs).pvalue)
                ok = m <= mt or p > 0.05
                evals = int(np.median(anchors["nfev"][name][problem]))
                print(f"| {problem} | {algo} | {m:.4g} | {name} | {mt:.4g} | {evals} | {p:.2g} | "
                      f"{'yes' if ok else 'NO'} |")
    print()


def draws_only(seeds: int) -> None:
    """What a batched GWO run cannot avoid: every seed's own generator drawing that
    seed's ``2 x 3 x pop x d`` numbers per iteration, drawn as the batch draws them
    (``SeedGenerators``, which reads each stream ahead in large blocks)."""
    rng = SeedGenerators(range(seeds))
    for _ in range(ITERS):
        rng.random((2, 3, POP, 30))


def update_only(seeds: int) -> None:
    """The draws plus GWO's own update arithmetic (eq 3-7: ``hunt`` and ``combine``) on
    the batch's arrays, with no objective, bounds, greedy step or leader bookkeeping."""
    state = BatchState(Problem(sphere, np.full(30, -100.0), np.full(30, 100.0)), POP,
                       SeedGenerators(range(seeds)), Budget(iterations=ITERS))
    state.X = np.random.default_rng(0).uniform(-100, 100, (seeds, POP, 30))
    gwo = GWO()
    gwo.leaders = state.X[:, :3].copy()
    for _ in range(ITERS):
        gwo.combine(state, gwo.hunt(state, 1.0))


def timed(fn) -> tuple[float, float]:
    """``(wall, cpu)`` seconds of one call: the CPU time of this process is what
    other jobs on a shared machine disturb least."""
    w, c = time.perf_counter(), time.process_time()
    fn()
    return time.perf_counter() - w, time.process_time() - c


def batched_table(repeats: int = 3) -> None:
    bounds, seeds = [(-100, 100)] * 30, range(20)
    jobs = {"one": lambda k: op.optimize(sphere, bounds, algorithm="gwo", pop=POP, iters=ITERS, seed=k),
            "batch": lambda k: op.optimize(sphere, bounds, algorithm="gwo", pop=POP, iters=ITERS, seeds=seeds),
            "draws": lambda k: draws_only(len(seeds)),
            "update": lambda k: update_only(len(seeds))}
    jobs["one"](0)                                                    # imports and first-call set-up
    walls, cpus = {name: [] for name in jobs}, {name: [] for name in jobs}
    for k in range(repeats):   # interleaved, so all four see the same machine load
        for name, job in jobs.items():
            w, c = timed(lambda: job(k))
            walls[name].append(w)
            cpus[name].append(c)
    numbers = len(seeds) * ITERS * 2 * 3 * POP * 30
    print(f"## Batched seeds: GWO, pop {POP} x {ITERS} iterations, 30-d sphere, median of {repeats}\n")
    print("Seed-by-seed identical results need every seed's own PCG64 numbers. 'draws alone' is the")
    print(f"time the 20 seeds' {numbers / 1e6:.0f} M numbers take to draw (no arithmetic), 'draws + update' adds")
    print("GWO's eq 3-7 arithmetic on the batch's arrays (no objective, bounds, greedy step or leader")
    print("bookkeeping); as multiples of one whole run they are floors of the ratio in one thread.\n")
    print("| clock | one run [s] | 20 seeds batched [s] | ratio | goal <= 3x | draws alone [s] | ns per number "
          "| floor: draws | floor: draws + update |")
    print("|---|---|---|---|---|---|---|---|---|")
    for clock, t in (("wall", walls), ("CPU", cpus)):
        a, b, c, u = (float(np.median(t[name])) for name in ("one", "batch", "draws", "update"))
        print(f"| {clock} | {a:.4f} | {b:.4f} | {b / a:.1f}x | {'yes' if b / a <= 3 else 'NO'} | {c:.4f} | "
              f"{c / numbers * 1e9:.2f} | {c / a:.1f}x | {u / a:.1f}x |")
    print()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=10, help="seeds per cell and timing repeats")
    ap.add_argument("--anchor-python", type=Path, default=None,
                    help="a Python with mealpy and niapy (default: the venv at /tmp/mealpy-venv)")
    ap.add_argument("--no-anchors", action="store_true", help="only optplan's numbers")
    ap.add_argument("--heldout", action="store_true", help="held-out shift vectors and seeds for the quality table")
    ap.add_argument("--batched-only", action="store_true", help="only the batched-seeds table")
    args = ap.parse_args()
    if args.batched_only:
        batched_table(max(args.runs, 3))
        return
    anchors = None
    before = {} if args.heldout else {algo: time_ours(algo, args.runs) for algo in SPEED_PAIRS}
    if not args.no_anchors:
        py = args.anchor_python or anchor_python(DEFAULT_VENV)
        if py is not None:
            print("running the anchors (mealpy, niapy) ...", file=sys.stderr)
            anchors = run_anchors(py, args.runs, args.heldout)
        else:
            print("anchors unavailable: only optplan's numbers are printed\n")
    if not args.heldout:
        speed_table(args.runs, anchors, before)
    quality_table(args.runs, anchors, args.heldout)
    if not args.heldout:
        batched_table()


if __name__ == "__main__":
    main()
