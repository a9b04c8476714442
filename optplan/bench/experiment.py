"""One call from a spec to stored, summarised results (the Python side of ``optplan bench``)."""
from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping


def run_experiment(spec: str | Path | Mapping[str, Any], db: str | Path = ":memory:", executor: Any = "local",
                   workers: int | None = None, quick: bool = False, runs: int | None = None,
                   progress: bool = True, retry_failed: bool = False):
    """Run the missing runs of ``spec`` into the SQLite file ``db`` and return its results.

    Args:
        spec: a spec file, the name of a shipped spec, or a dict with the YAML keys.
        db: results database (``":memory:"`` keeps nothing; a file makes reruns resume).
        executor: ``"local"``, ``"dask://HOST:PORT"``, ``"dask-local"`` or a ``distributed.Client``.
        workers: processes for the local executors (default CPU count; 1 runs in this process).
        quick, runs: the spec's quick overrides / the number of seeds.
        progress: progress bar on stderr.
        retry_failed: run again the runs stored as failed.

    Returns:
        An :class:`~optplan.bench.summary.ExperimentResults` (``.rows`` per run key,
        ``.values(...)``, ``.run_sets(target)``); ``render_report(results)`` prints its tables.

    Example::

        from optplan.bench import run_experiment, render_report
        res = run_experiment("chen2025_paths", quick=True, workers=1)
        print(render_report(res))
    """
    from .runner import run_records
    from .spec import load_spec
    from .store import ResultStore
    from .summary import load_results

    s = load_spec(spec, quick=quick, runs=runs)
    store = ResultStore(db)
    run_records(s.expand(), store, executor=executor, workers=workers, progress=progress,
                retry_failed=retry_failed, label=s.name)
    return load_results(s, store)
