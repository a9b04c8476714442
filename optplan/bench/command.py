"""``optplan bench`` and ``optplan reproduce`` (hooked into ``optplan.cli``)."""
from __future__ import annotations

import argparse
import os
import signal
import sys
from contextlib import contextmanager
from pathlib import Path

from ..errors import ParameterError
from .runner import EXECUTORS_HELP

PAPERS = ("hou2024", "yang2023", "yuan2021", "li2023", "chen2025")

BENCH_EPILOG = """examples:
  optplan bench chen2025_paths --quick --db results.sqlite          # a shipped spec, reduced
  optplan bench my_spec.yaml --workers 8 --csv runs.csv --plots figs/
  optplan bench my_spec.yaml --executor dask://10.0.0.5:8786 --db results.sqlite
  optplan bench programs_example --db programs.sqlite                # kind program: one program, many solvers
Rerunning the same command skips the runs already in --db (resume after an interruption).
Spec format: optplan/data/specs/README.md"""

REPRODUCE_EPILOG = """examples:
  optplan reproduce chen2025 --quick
  optplan reproduce hou2024 --runs 10 --workers 2 --db hou2024.sqlite   # resumable
Shipped specs: optplan/data/specs/PAPER_*.yaml"""


def _common_run_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--executor", default="local", metavar="EXEC",
                   help=f"where runs execute: {EXECUTORS_HELP} (default local: a process pool)")
    p.add_argument("--workers", type=int, default=None, metavar="N",
                   help="worker processes for local/dask-local (default: CPU count, 1 with --quick; 1 runs in "
                        "this process)")
    p.add_argument("--runs", type=int, default=None, metavar="N", help="seeds per (target, algorithm), overriding "
                   "the spec")
    p.add_argument("--quick", action="store_true", help="apply the spec's quick overrides (few runs, short budgets)")
    p.add_argument("--format", choices=["markdown", "latex"], default="markdown", help="table format")
    p.add_argument("--plots", metavar="DIR", help="write box plots, convergence curves and path overlays here")
    p.add_argument("--csv", metavar="OUT.csv", help="export the runs of the spec(s) to a CSV file")
    p.add_argument("--export-ompl", metavar="DIR", help="write the runs as OMPL benchmark logs (one per experiment "
                   "and target) into DIR, for ompl_benchmark_statistics.py and Planner Arena")
    p.add_argument("--retry-failed", action="store_true", help="rerun runs stored as failed (default: keep them)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")


def add_bench_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``optplan bench``."""
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = BENCH_EPILOG
    parser.add_argument("spec", help="experiment spec YAML file, or the name of a shipped spec")
    parser.add_argument("--db", default="results.sqlite", metavar="FILE",
                        help="SQLite results database (default results.sqlite; ':memory:' keeps nothing)")
    parser.add_argument("--layout", default=None, help="table layout (default: the spec's 'report', else summary)")
    parser.add_argument("--summary-only", action="store_true", help="print the tables of what --db holds, run nothing")
    _common_run_arguments(parser)


def add_reproduce_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``optplan reproduce``."""
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = REPRODUCE_EPILOG
    parser.add_argument("paper", choices=PAPERS, help="which paper's experiments to run")
    parser.add_argument("--part", default=None, help="only this part (e.g. global, local, functions, paths)")
    parser.add_argument("--db", default=":memory:", metavar="FILE",
                        help="keep results in this SQLite file and resume from it (default: in memory, fresh)")
    _common_run_arguments(parser)


@contextmanager
def _sigterm_as_interrupt():
    """SIGTERM stops like Ctrl-C: pending runs are cancelled, stored runs stay."""
    def handler(signum, frame):
        raise KeyboardInterrupt

    try:
        old = signal.signal(signal.SIGTERM, handler)
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, old)


def _check_workers(workers) -> None:
    if workers is not None and workers < 1:
        raise ParameterError(f"--workers must be a positive integer, got {workers}")
    if workers is not None and workers > 4 * (os.cpu_count() or 1):
        print(f"optplan: note: {workers} workers on {os.cpu_count()} CPUs", file=sys.stderr)


def run_spec(spec, store, args, label: str = ""):
    """Run the missing runs of ``spec`` into ``store``; returns the :class:`RunReport`."""
    from .runner import run_records

    return run_records(spec.expand(), store, executor=args.executor, workers=args.workers,
                       progress=not args.no_progress, retry_failed=args.retry_failed, label=label)


def _tables(spec, store, args, layout: str | None = None) -> str:
    from .reports import render_report
    from .summary import load_results

    plots = Path(args.plots) if args.plots else None
    return render_report(load_results(spec, store), fmt=args.format, plots_dir=plots, layout=layout)


def _export_ompl(store, args, keys) -> None:
    if getattr(args, "export_ompl", None):
        from .ompl import export_ompl

        files = export_ompl(store, args.export_ompl, keys)
        print(f"wrote {len(files)} OMPL benchmark log(s) to {args.export_ompl} (Planner Arena: "
              f"ompl_benchmark_statistics.py {args.export_ompl}/*.log -d benchmark.db)", file=sys.stderr)


def run_bench(args) -> int:
    """``optplan bench``: run a spec into the database, print its tables; exit 1 if runs failed."""
    from .spec import load_spec
    from .store import ResultStore

    _check_workers(args.workers)
    spec = load_spec(args.spec, quick=args.quick, runs=args.runs)
    store = ResultStore(args.db)
    try:
        failed = 0
        if not args.summary_only:
            with _sigterm_as_interrupt():
                try:
                    rep = run_spec(spec, store, args, label=spec.name)
                except KeyboardInterrupt:
                    print(f"optplan: interrupted; {store.count()} runs are stored in {args.db}; rerun the same "
                          f"command to finish the rest", file=sys.stderr)
                    raise
            print(f"{spec.name}: {rep.describe()}; database {args.db}", file=sys.stderr)
            failed = rep.failed
        print(_tables(spec, store, args, args.layout).rstrip("\n"))
        if args.csv:
            n = store.to_csv(args.csv, [r.key for r in spec.expand()])
            print(f"wrote {n} rows to {args.csv}", file=sys.stderr)
        _export_ompl(store, args, [r.key for r in spec.expand()])
        if failed:
            print(f"optplan: {failed} run(s) failed; their messages are in the 'error' column of {args.db} "
                  f"(--retry-failed runs them again)", file=sys.stderr)
        return 1 if failed else 0
    finally:
        store.close()


def run_reproduce(args) -> int:
    """``optplan reproduce PAPER``: run the paper's shipped specs and print its tables in its layout."""
    from .spec import load_spec, shipped_specs
    from .store import ResultStore

    _check_workers(args.workers)
    names = shipped_specs(args.paper)
    if not names:
        raise ParameterError(f"no shipped specs for {args.paper} in optplan/data/specs")
    specs = sorted((load_spec(n, quick=args.quick, runs=args.runs) for n in names), key=lambda s: (s.order, s.name))
    if args.quick and args.workers is None and args.executor == "local":
        args.workers = 1  # a quick grid takes seconds; starting worker processes would cost more than it saves
    parts = sorted({s.part for s in specs if s.part})
    if args.part is not None:
        if args.part not in parts:
            raise ParameterError(f"{args.paper} has no part {args.part!r}; its parts: {', '.join(parts)}")
        specs = [s for s in specs if s.part == args.part]
    store = ResultStore(args.db)
    failed = 0
    keys: list[str] = []
    try:
        for spec in specs:
            with _sigterm_as_interrupt():
                try:
                    rep = run_spec(spec, store, args, label=spec.name)
                except KeyboardInterrupt:
                    if args.db != ":memory:":
                        print(f"optplan: interrupted; rerun with --db {args.db} to resume", file=sys.stderr)
                    raise
            print(f"{spec.name}: {rep.describe()}", file=sys.stderr)
            failed += rep.failed
            keys += [r.key for r in spec.expand()]
            print(_tables(spec, store, args), flush=True)
        if args.csv:
            n = store.to_csv(args.csv, keys)
            print(f"wrote {n} rows to {args.csv}", file=sys.stderr)
        _export_ompl(store, args, keys)
        if failed:
            print(f"optplan: {failed} run(s) failed (see the 'failed' counts in the tables)", file=sys.stderr)
        return 1 if failed else 0
    finally:
        store.close()


def reproduce(paper: str, part: str | None = None, *, quick: bool = False, runs: int | None = None,
              workers: int | None = None, db: str = ":memory:", plots: str | None = None,
              progress: bool = True) -> int:
    """``optplan reproduce PAPER [--part PART]`` from Python (what the example scripts call, so
    both print the same tables, claims included); returns the command's exit status."""
    if paper not in PAPERS:
        raise ParameterError(f"unknown paper {paper!r}; known: {', '.join(PAPERS)}")
    args = argparse.Namespace(paper=paper, part=part, quick=quick, runs=runs, workers=workers, db=db,
                              executor="local", format="markdown", plots=plots, csv=None, retry_failed=False,
                              no_progress=not progress)
    return run_reproduce(args)
