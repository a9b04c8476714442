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


def _as_printed_section(spec, specs, store, args) -> str:
    """The table of the claims whose verdicts differ between ``spec`` and its ``as_printed`` spec, when
    this command ran both (``""`` otherwise)."""
    twin = next((s for s in specs if s.name == spec.as_printed), None)
    if twin is None:
        return ""
    from .claims import as_printed_table
    from .summary import load_results

    table = as_printed_table(load_results(spec, store), load_results(twin, store))
    if table is None:
        return ""
    return (f"\n## Verdicts that differ as printed ({twin.name}) and with our change ({spec.name})\n\n"
            f"{table.render(args.format)}\n")


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


def _reproduce_specs(paper: str, part: str | None, quick: bool, runs: int | None) -> list:
    """The shipped specs ``optplan reproduce PAPER [--part PART]`` runs, in its order."""
    from .spec import load_spec, shipped_specs

    names = shipped_specs(paper)
    if not names:
        raise ParameterError(f"no shipped specs for {paper} in optplan/data/specs")
    specs = sorted((load_spec(n, quick=quick, runs=runs) for n in names), key=lambda s: (s.order, s.name))
    parts = sorted({s.part for s in specs if s.part})
    if part is not None:
        if part not in parts:
            raise ParameterError(f"{paper} has no part {part!r}; its parts: {', '.join(parts)}")
        specs = [s for s in specs if s.part == part]
    return specs


def run_reproduce(args) -> int:
    """``optplan reproduce PAPER``: run the paper's shipped specs and print its tables in its layout;
    with ``--update-docs``, rewrite the docs' marked tables of those specs (:mod:`.doc_tables`)."""
    from .store import ResultStore

    _check_workers(args.workers)
    update = getattr(args, "update_docs", False)
    if update and args.format != "markdown":
        raise ParameterError("--update-docs writes the markdown tables; drop --format latex")
    specs = _reproduce_specs(args.paper, args.part, args.quick, args.runs)
    if args.quick and args.workers is None and args.executor == "local":
        args.workers = 1  # a quick grid takes seconds; starting worker processes would cost more than it saves
    store = ResultStore(args.db)
    failed = 0
    keys: list[str] = []
    printed: dict[str, str] = {}
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
            printed[spec.name] = _tables(spec, store, args)
            print(printed[spec.name], flush=True)
        for spec in specs:   # a spec with a twin at the paper's setting: the verdicts that differ
            text = _as_printed_section(spec, specs, store, args)
            if text:
                printed[spec.name] += text
                print(text, flush=True)
        if args.csv:
            n = store.to_csv(args.csv, keys)
            log.info(f"wrote {n} rows to {args.csv}")
        _export_ompl(store, args, keys)
        if update and failed:
            log.warning("--update-docs: runs failed, so the docs were left as they are")
        elif update:
            written, left = _update_docs(printed, specs)
            for b in written:
                log.info(f"updated {b.where()}")
            for b in left:
                log.info(f"left {b.where()}: its command ({b.command}) runs other runs")
            if not written:
                log.info("--update-docs: no marked table in the docs is printed by this command "
                         "(optplan/bench/doc_tables.py says how tables are marked)")
        if failed:
            print(f"optplan: {failed} run(s) failed (see the 'failed' counts in the tables)", file=sys.stderr)
        return 1 if failed else 0
    finally:
        store.close()


def _update_docs(printed: dict[str, str], specs: list) -> tuple[list, list]:
    """Rewrite the docs' marked tables (:mod:`.doc_tables`) of the specs just run whose command runs
    exactly these runs (the same run keys); returns the blocks written and those of the same specs
    left alone (their command runs other seeds or budgets)."""
    from .doc_tables import find_blocks, write_tables

    ran = {s.name: [r.key for r in s.expand()] for s in specs}
    chosen, left = [], []
    for b in find_blocks():
        if b.spec not in printed:
            continue
        theirs = {s.name: s for s in command_specs(b.command)}.get(b.spec)
        same = theirs is not None and [r.key for r in theirs.expand()] == ran[b.spec]
        (chosen if same else left).append(b)
    write_tables(chosen, printed, {s.name: s.seeds for s in specs})
    return chosen, left


def command_specs(command: str) -> list:
    """The specs a doc table's ``command`` runs (``optplan reproduce PAPER [--part P] [--runs N]
    [--quick]`` or ``optplan bench SPEC [--runs N] [--quick]``, see :mod:`.doc_tables`), loaded as
    the command loads them (so their ``seeds`` are the command's)."""
    from .doc_tables import parse_command
    from .spec import load_spec

    inv = parse_command(command)
    if inv.kind == "reproduce":
        return _reproduce_specs(inv.name, inv.part, inv.quick, inv.runs)
    return [load_spec(inv.name, quick=inv.quick, runs=inv.runs)]


def command_reports(command: str, spec_names, workers: int | None = 1) -> dict[str, tuple[str, list[int]]]:
    """What a doc table's ``command`` (``optplan reproduce ...`` / ``optplan bench ...``, see
    :mod:`.doc_tables`) prints now for each of ``spec_names``, run fresh in memory: ``{spec: (text,
    seeds)}``. Each spec's tables come from its own runs, so only the named specs are run."""
    from .store import ResultStore

    specs = {s.name: s for s in command_specs(command)}
    unknown = [n for n in spec_names if n not in specs]
    if unknown:
        raise ParameterError(f"{command!r} does not run {', '.join(unknown)}; it runs {', '.join(specs)}")
    args = SimpleNamespace(executor="local", workers=workers, no_progress=True, retry_failed=False,
                           format="markdown", plots=None)
    out = {}
    for name in dict.fromkeys(spec_names):
        store = ResultStore(":memory:")
        try:
            spec = specs[name]
            run_spec(spec, store, args, label=name)
            text = _tables(spec, store, args)
            twin = specs.get(spec.as_printed) if spec.as_printed else None
            if twin is not None:   # the command also prints the verdicts that differ from its twin's
                run_spec(twin, store, args, label=twin.name)
                text += _as_printed_section(spec, [twin], store, args)
            out[name] = (text, spec.seeds)
        finally:
            store.close()
    return out


def reproduce(paper: str, part: str | None = None, *, quick: bool = False, runs: int | None = None,
              workers: int | None = None, db: str = ":memory:", plots: str | None = None,
              progress: bool = True, update_docs: bool = False) -> int:
    """``optplan reproduce PAPER [--part PART]`` from Python (what the example scripts call, so
    both print the same tables, claims included); ``update_docs`` is ``--update-docs``; returns the
    command's exit status."""
    if paper not in PAPERS:
        raise ParameterError(f"unknown paper {paper!r}; known: {', '.join(PAPERS)}")
    args = SimpleNamespace(paper=paper, part=part, quick=quick, runs=runs, workers=workers, db=db,
                              executor="local", format="markdown", plots=plots, csv=None, retry_failed=False,
                              no_progress=not progress, update_docs=update_docs)
    return run_reproduce(args)
