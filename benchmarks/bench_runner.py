"""Benchmark runner overheads: executors, parallel speed-up and the SQLite writer.

Prints one table: for each executor, the wall time of a grid of short runs and of a grid of
longer runs, the summed in-run time (``runtime_s`` is the solver's own clock) and the overhead
per run; and the time to write one result row (one transaction each, WAL).

    python benchmarks/bench_runner.py [--workers 2] [--runs 40] [--long-iters 2000] [--no-dask]

Wall times depend on what else the machine is doing; compare rows of one invocation.
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from optplan.bench.runner import execute_run, run_records, warm_up
from optplan.bench.spec import load_spec
from optplan.bench.store import ResultStore


def grid(runs: int, iters: int):
    return load_spec({"name": f"overhead_{iters}", "kind": "plan", "maps": ["chen2025_30"],
                      "algorithms": ["gwo"], "params": {"pop": 30, "iters": iters}, "runs": runs}).expand()


def timed(records, executor: str, workers: int) -> tuple[float, float]:
    with tempfile.TemporaryDirectory() as tmp:
        store = ResultStore(Path(tmp) / "r.sqlite")
        t0 = time.perf_counter()
        run_records(records, store, executor=executor, workers=workers, progress=False)
        wall = time.perf_counter() - t0
        inside = sum(r["runtime_s"] or 0.0 for r in store.rows().values())
        store.close()
    return wall, inside


def write_cost(n: int = 300) -> float:
    rec = grid(1, 20)[0]
    outcome = execute_run(rec.to_dict())
    with tempfile.TemporaryDirectory() as tmp:
        store = ResultStore(Path(tmp) / "w.sqlite")
        d = rec.to_dict()
        t0 = time.perf_counter()
        for k in range(n):
            store.write({**d, "key": f"k{k}"}, outcome)
        dt = (time.perf_counter() - t0) / n
        store.close()
    return dt


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--runs", type=int, default=40)
    ap.add_argument("--long-iters", type=int, default=2000, help="iterations of the long runs (default 2000)")
    ap.add_argument("--no-dask", action="store_true")
    args = ap.parse_args(argv)
    warm_up()
    execute_run(grid(1, 5)[0].to_dict())  # map tables and imports, once, outside the timings
    short, long = grid(args.runs, 20), grid(args.runs, args.long_iters)
    executors = [("in-process (workers 1)", "local", 1), (f"process pool ({args.workers})", "local", args.workers)]
    if not args.no_dask:
        executors.append((f"dask LocalCluster ({args.workers} processes)", "dask-local", args.workers))
    print(f"## Runner overheads ({args.runs} runs of gwo on chen2025_30, pop 30; 20 and {args.long_iters} "
          f"iterations)\n")
    print("| executor | start-up [s] | short grid wall [s] | overhead per run [ms] | long grid wall [s] | "
          "long in-run [s] | speed-up vs in-process |")
    print("|---|---|---|---|---|---|---|")
    base = None
    for name, ex, w in executors:
        startup, _ = timed(grid(w, 1), ex, w)  # one trivial run per worker: process start and imports
        ws, ins = timed(short, ex, w)
        wl, inl = timed(long, ex, w)
        base = base or wl
        per_run = 1000 * (ws - (startup if w > 1 or ex != "local" else 0.0) - ins / w) / args.runs
        print(f"| {name} | {startup:.2f} | {ws:.2f} | {per_run:.1f} | {wl:.2f} | {inl:.2f} | {base / wl:.2f} |")
    print(f"\nSQLite write of one run (own transaction, WAL, history + path): {1000 * write_cost():.2f} ms")
    print("overhead per run = (short wall - start-up - in-run time / workers) / runs; in-run = the solvers' own "
          "runtime_s, summed")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
