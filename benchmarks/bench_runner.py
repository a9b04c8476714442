"""Benchmark runner overheads: executors, parallel speed-up and the SQLite writer.

Prints one table: for each executor, the wall time of a grid of short runs and of a grid of
longer runs, the summed in-run time (``runtime_s`` is the solver's own clock) and the overhead
per run; and the time to write one result row (one transaction each, WAL).

    python benchmarks/bench_runner.py [--workers 2] [--runs 40] [--no-dask]

Wall times depend on what else the machine is doing; compare rows of one invocation.
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from optplan.bench.runner import execute_run, run_records
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
    ap.add_argument("--no-dask", action="store_true")
    args = ap.parse_args(argv)
    short, long = grid(args.runs, 20), grid(args.runs, 400)
    executors = [("in-process (workers 1)", "local", 1), (f"process pool ({args.workers})", "local", args.workers)]
    if not args.no_dask:
        executors.append((f"dask LocalCluster ({args.workers} processes)", "dask-local", args.workers))
    print(f"## Runner overheads ({args.runs} runs of gwo on chen2025_30, pop 30; 20 and 400 iterations)\n")
    print("| executor | short grid wall [s] | in-run [s] | overhead per run [ms] | long grid wall [s] | in-run [s] | "
          "speed-up vs in-process |")
    print("|---|---|---|---|---|---|---|")
    base = None
    for name, ex, w in executors:
        ws, ins = timed(short, ex, w)
        wl, inl = timed(long, ex, w)
        base = base or wl
        print(f"| {name} | {ws:.2f} | {ins:.2f} | {1000 * (ws - ins / (w if w > 1 else 1)) / args.runs:.1f} | "
              f"{wl:.2f} | {inl:.2f} | {base / wl:.2f} |")
    print(f"\nSQLite write of one run (own transaction, WAL, history + path): {1000 * write_cost():.2f} ms")
    print("overhead per run = (wall - in-run time / workers) / runs; includes process start-up for the pools")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
