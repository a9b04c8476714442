"""Bench results as OMPL benchmark logs, so Planner Arena (plannerarena.org) can plot them.

OMPL's ``ompl_benchmark_statistics.py`` reads a log per experiment (its grammar is in the
OMPL manual, "The benchmark logfile format") into the SQLite database that Planner Arena
opens. One log is written per (experiment, target): the target (a map, scenario or
function) is what OMPL calls the problem, and each planner configuration (the run's
``label``: algorithm, refinement, local planner) is one OMPL planner whose runs are the
seeds.

Each run reports OMPL's standard properties where optplan has them (``time``, ``solved``,
``solution length``, ``solution clearance``, ``correct solution``), then every other
numeric metric stored for the kind under its own name. A failed run is a run with
``solved = 0`` and empty measurements, as OMPL writes a planner that found nothing.
"""
from __future__ import annotations

import math
import os
import re
import socket
from collections import defaultdict
from pathlib import Path
from typing import Any, Iterable, Mapping

from ..errors import ParameterError
from ..world.files import written_whole

# OMPL's standard names: (property, type, function of a stored row)
_SOLVED = {
    "plan": lambda r: r.get("status") == "ok" and bool(r.get("feasible")),
    "program": lambda r: r.get("status") == "ok" and bool(r.get("feasible")),
    "simulate": lambda r: r.get("status") == "ok" and bool(r.get("reached")) and not r.get("collisions"),
    "optimize": lambda r: r.get("status") == "ok",
}
_STANDARD = (
    ("time", "REAL", lambda r: r.get("runtime_s") if r.get("runtime_s") is not None else r.get("wall_s")),
    ("solution length", "REAL", lambda r: r.get("length") if r.get("length") is not None else r.get("path_length")),
    ("solution clearance", "REAL", lambda r: r.get("min_clearance")),
    ("correct solution", "BOOLEAN", lambda r: r.get("feasible") if r.get("kind") in ("plan", "program") else
        (None if r.get("collisions") is None else r.get("collisions") == 0)),
)
# columns that are identity or bookkeeping, not measurements of the run
_NOT_MEASURED = {"key", "experiment", "kind", "target", "algorithm", "label", "refine", "local_planner", "status",
                 "error", "worker", "finished_at", "optplan_version", "params", "target_spec", "program",
                 "runtime_s", "wall_s", "length", "path_length", "min_clearance", "feasible", "seed", "code"}


def _safe_token(text: str) -> str:
    """OMPL reads host names and file stems as one token without white space."""
    return re.sub(r"[^0-9A-Za-z_.+-]+", "_", str(text)).strip("_") or "x"


def _one_line(text: Any) -> str:
    return " ".join(str(text).split())


def _value(v: Any, kind: str) -> str:
    if v is None:
        return ""
    if kind == "BOOLEAN":
        return "1" if bool(v) else "0"
    try:
        x = float(v)
    except (TypeError, ValueError):
        return ""
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf"
    return str(int(x)) if kind == "INTEGER" else repr(x)


def _extra_properties(rows: list[dict]) -> list[tuple[str, str, str]]:
    """``(column, OMPL name, type)`` of the numeric metrics beyond the standard ones."""
    out = []
    columns = sorted({c for r in rows for c in r} - _NOT_MEASURED)
    for col in columns:
        values = [r.get(col) for r in rows if r.get(col) is not None]
        if not values or not all(isinstance(v, (bool, int, float)) for v in values):
            continue  # text and JSON columns are not measurements
        kind = "INTEGER" if all(isinstance(v, (bool, int)) for v in values) else "REAL"
        if col.startswith("param_"):
            continue  # parameters are the planner's settings, written as common properties
        out.append((col, col.replace("_", " "), kind))
    return out


def ompl_log(experiment: str, target: str, rows: Iterable[Mapping[str, Any]], host: str | None = None) -> str:
    """The text of one OMPL benchmark log for the runs ``rows`` (``ResultStore`` rows of one
    experiment and target)."""
    from .. import __version__

    rows = [dict(r) for r in rows]
    if not rows:
        raise ParameterError(f"no stored runs for experiment {experiment!r} on {target!r}; nothing to export")
    kind = rows[0].get("kind") or "plan"
    solved = _SOLVED.get(kind, _SOLVED["optimize"])
    extra = _extra_properties(rows)
    props = [("solved", "BOOLEAN", solved)] + list(_STANDARD) + \
        [(name, typ, (lambda c: lambda r: r.get(c))(col)) for col, name, typ in extra]
    from .summary import pipeline_name

    # one OMPL planner per pipeline (algorithm x refine x local planner), named as the tables name it
    vary_refine = len({r.get("refine") for r in rows}) > 1
    vary_local = len({r.get("local_planner") for r in rows}) > 1
    by_planner: dict[str, list[dict]] = defaultdict(list)
    for r in sorted(rows, key=lambda r: (str(r.get("label") or r.get("algorithm")), str(r.get("refine")),
                                         str(r.get("local_planner")), r.get("seed") or 0)):
        name = pipeline_name(str(r.get("label") or r.get("algorithm") or "planner"), r.get("refine"),
                             r.get("local_planner"), vary_refine, vary_local)
        by_planner[_one_line(name)].append(r)
    times = [float(r["wall_s"]) for r in rows if isinstance(r.get("wall_s"), (int, float))]
    dates = sorted(str(r["finished_at"]) for r in rows if r.get("finished_at"))
    lines = [f"optplan version {__version__}",
             f"Experiment {_safe_token(experiment)}_{_safe_token(target)}",
             f"Running on {_safe_token(host or socket.gethostname())}",
             f"Starting at {dates[0] if dates else 'unknown'}",
             "<<<|", _one_line(f"optplan {kind} runs of experiment {experiment} on {target}"), "|>>>",
             "<<<|", _one_line(f"{os.cpu_count() or 1} CPUs"), "|>>>",
             "0 is the random seed",
             "0 seconds per run",
             "0 MB per run",
             f"{max(len(v) for v in by_planner.values())} runs per planner",
             f"{sum(times)!r} seconds spent to collect the data",
             f"{len(by_planner)} planners"]
    for planner, runs in by_planner.items():
        params = sorted({k for r in runs for k in r if k.startswith("param_") and r[k] is not None})
        lines.append(planner)
        lines.append(f"{len(params) + 1} common properties")
        lines.append(f"kind = {kind}")
        lines += [f"{k[len('param_'):]} = {_one_line(runs[0].get(k))}" for k in params]
        lines.append(f"{len(props) + 1} properties for each run")
        lines += [f"{name} {typ}" for name, typ, _ in props]
        lines.append("seed INTEGER")
        lines.append(f"{len(runs)} runs")
        for r in runs:
            ok = r.get("status") == "ok"
            cells = [_value(fn(r) if (ok or name == "solved") else None, typ) for name, typ, fn in props]
            cells.append(_value(r.get("seed"), "INTEGER"))
            lines.append("".join(f"{c}; " for c in cells))
        lines.append(".")
    return "\n".join(lines) + "\n"


def export_ompl(store, out_dir: str | os.PathLike, keys: Iterable[str] | None = None,
                host: str | None = None) -> list[Path]:
    """Write one OMPL benchmark log per (experiment, target) of the runs in ``store``
    (only ``keys`` when given) into ``out_dir``; returns the files written.

    Turn them into a Planner Arena database with OMPL's
    ``ompl_benchmark_statistics.py out_dir/*.log -d benchmark.db``.
    """
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ParameterError(f"--export-ompl {out} is a file; give a folder for the .log files")
    rows = store.rows(keys)
    if not rows:
        raise ParameterError("the results database holds no runs to export; run the spec first")
    groups: dict[tuple[str, str], list[dict]] = defaultdict(list)
    for r in rows.values():
        groups[(str(r.get("experiment")), str(r.get("target")))].append(r)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for (experiment, target), group in sorted(groups.items()):
        path = out / f"{_safe_token(experiment)}__{_safe_token(target)}.log"
        with written_whole(path, "OMPL log") as tmp:
            tmp.write_text(ompl_log(experiment, target, group, host))
        written.append(path)
    return written
