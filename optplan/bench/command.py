"""What ``optplan bench`` and ``optplan reproduce`` do (their arguments are defined by the
command line, :mod:`optplan.cli`), and :func:`reproduce`, the same from Python."""
from __future__ import annotations

import logging
import os
import signal
import sys
from contextlib import contextmanager
from pathlib import Path
from types import SimpleNamespace

from ..errors import ParameterError

PAPERS = ("hou2024", "yang2023", "yuan2021", "li2023", "chen2025")
log = logging.getLogger(__name__)

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
        log.warning(f"optplan: note: {workers} workers on {os.cpu_count()} CPUs")


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
        log.info(f"wrote {len(files)} OMPL benchmark log(s) to {args.export_ompl} (Planner Arena: "
                 f"ompl_benchmark_statistics.py {Path(args.export_ompl) / '*.log'} -d benchmark.db)")


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
                    # the command line prints this once, after 'interrupted'
                    raise KeyboardInterrupt(f"{store.count()} runs are stored in {args.db}; rerun the same "
                                            f"command to finish the rest") from None
            log.info(f"{spec.name}: {rep.describe()}; database {args.db}")
            failed = rep.failed
        print(_tables(spec, store, args, args.layout).rstrip("\n"))
        if args.csv:
            n = store.to_csv(args.csv, [r.key for r in spec.expand()])
            log.info(f"wrote {n} rows to {args.csv}")
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
                        raise KeyboardInterrupt(f"rerun with --db {args.db} to resume") from None
                    raise
            log.info(f"{spec.name}: {rep.describe()}")
            failed += rep.failed
            keys += [r.key for r in spec.expand()]
            print(_tables(spec, store, args), flush=True)
        if args.csv:
            n = store.to_csv(args.csv, keys)
            log.info(f"wrote {n} rows to {args.csv}")
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
    args = SimpleNamespace(paper=paper, part=part, quick=quick, runs=runs, workers=workers, db=db,
                              executor="local", format="markdown", plots=plots, csv=None, retry_failed=False,
                              no_progress=not progress)
    return run_reproduce(args)
