"""Experiments at scale (DESIGN.md layer 7).

* :mod:`~optplan.bench.spec` — YAML experiment specs, expanded into keyed, seeded runs;
* :mod:`~optplan.bench.runner` — runs them in a local process pool or on Dask, storing each result;
* :mod:`~optplan.bench.store` — the SQLite results database (one row per run, resume by key);
* :mod:`~optplan.bench.summary`, :mod:`~optplan.bench.stats`, :mod:`~optplan.bench.tables` —
  grouping, min/mean/max/std, Wilcoxon rank-sum with +/=/-, markdown and LaTeX tables;
* :mod:`~optplan.bench.reports` — the papers' table layouts (figures: :mod:`optplan.viz.experiment_plots`);
* :mod:`~optplan.bench.global_runs` — the in-process loops of the example scripts;
* :mod:`~optplan.bench.command` — ``optplan bench`` and ``optplan reproduce``.

The names below are imported lazily so that ``import optplan.bench`` stays light.
"""
from __future__ import annotations

from ..lazy import lazy_exports

_LAZY = {
    "load_spec": "optplan.bench.spec",
    "ExperimentSpec": "optplan.bench.spec",
    "RunRecord": "optplan.bench.spec",
    "run_records": "optplan.bench.runner",
    "ResultStore": "optplan.bench.store",
    "load_results": "optplan.bench.summary",
    "render_report": "optplan.bench.reports",
    "run_experiment": "optplan.bench.experiment",
}

__getattr__, __dir__, __all__ = lazy_exports("optplan.bench", _LAZY, globals())
