"""Pictures of a stored experiment: box plots, convergence curves, path overlays (PNG, no screen needed).

The convergence curves are :func:`optplan.viz.convergence.plot_convergence`
(median and inter-quartile band) and the overlays :func:`optplan.viz.plots.plot_paths`;
this module picks the data out of the results database.
"""
from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from ..bench.summary import ExperimentResults


def _safe(name: str) -> str:
    return re.sub(r"[^0-9A-Za-z_.+-]", "_", name)


# units of the metrics the runs store (a metric not listed has none, e.g. a count or a cost)
METRIC_UNITS = {"length": "m", "path_length": "m", "time_s": "s", "runtime_s": "s", "wall_s": "s",
                "min_clearance": "m", "turn_angle_deg": "deg", "max_abs_accel": "m/s^2", "mean_step_ms": "ms",
                "max_abs_jerk": "m/s^3"}


def metric_label(metric: str) -> str:
    """An axis label for a stored metric, with its unit where it has one: ``length [m]``."""
    unit = METRIC_UNITS.get(metric)
    return f"{metric} [{unit}]" if unit else metric


def box_plot(groups: Mapping[str, Sequence[float]], filename: str | Path | None = None, title: str = "",
             ylabel: str = "", reference_line: float | None = None):
    """One box per group (median, quartiles, 1.5 IQR whiskers, outliers) with the runs jittered on top;
    empty groups are shown by name with no box. ``reference_line`` draws e.g. the exact optimum.
    Returns the Figure, after writing it as a PNG to ``filename`` when one is given."""
    from .plots import finish_figure, new_figure

    names = list(groups)
    fig, ax = new_figure((max(4.0, 0.9 * len(names) + 2), 4.2))
    data = [np.asarray(groups[n], float) for n in names]
    pos = [i + 1 for i, d in enumerate(data) if len(d)]
    if pos:
        ax.boxplot([d for d in data if len(d)], positions=pos, widths=0.55, showfliers=True)
    rng = np.random.default_rng(0)  # jitter only; fixed so the picture is reproducible
    for i, d in enumerate(data):
        if len(d):
            ax.plot(i + 1 + rng.uniform(-0.12, 0.12, len(d)), d, ".", alpha=0.5, ms=4)
    if reference_line is not None:
        ax.axhline(reference_line, ls="--", lw=1, color="0.4", label="exact optimum")
        ax.legend(fontsize=7)
    ax.set_xticks(range(1, len(names) + 1))
    ax.set_xticklabels(names, rotation=30, ha="right", fontsize=8)
    ax.set_xlim(0.4, len(names) + 0.6)
    ax.set_ylabel(ylabel)
    return finish_figure(fig, filename, title)


def experiment_plots(res: ExperimentResults, out_dir: str | Path, metric: str | None = None) -> list[Path]:
    """Per target: a box plot of ``metric`` (successful runs), convergence curves (when runs have a
    history) and an overlay of each group's best path (plan, program) or last trajectory (simulate)."""
    from .convergence import plot_convergence

    out_dir = Path(out_dir)
    spec = res.spec
    metric = metric or spec.metric
    files: list[Path] = []
    for t in spec.targets:
        groups = res.groups(t.name)
        names = {g: res.group_name(*g) for g in groups}
        ref_line = None
        if spec.kind == "plan" and metric == "length":
            from ..bench.summary import exact_optimum_of

            ref_line = exact_optimum_of(t.spec, float(spec.params.get("clearance", 0.0) or 0.0))
        vals = {names[g]: res.values(recs, metric) for g, recs in groups.items()}
        if any(len(v) for v in vals.values()):
            files.append(out_dir / f"{_safe(spec.name)}_{_safe(t.name)}_box.png")
            box_plot(vals, files[-1], title=f"{t.name}: {metric}", ylabel=metric_label(metric),
                     reference_line=ref_line)
        histories, paths, finals = {}, {}, {}
        from ..bench.kinds import get_kind

        final_metric = get_kind(spec.kind).final_metric
        for g, recs in groups.items():
            ok = [r for r in recs if res.successful(r)] or [r for r in recs if r.key in res.rows
                                                             and res.rows[r.key]["status"] == "ok"]
            tr = res.traces([r.key for r in ok])
            hs = [np.asarray([np.nan if h is None else h for h in tr[r.key]["history"]], float)
                  for r in ok if len(tr.get(r.key, {}).get("history", [])) > 1]
            hs = [h for h in hs if np.isfinite(h).all()]
            if hs:
                histories[names[g]] = hs
                if final_metric:  # what pruning / refinement made of the search's best
                    finals[names[g]] = res.values(ok, final_metric, successful_only=False)
            if ok and spec.kind in ("plan", "simulate", "program"):
                best = min(ok, key=lambda r: float(res.rows[r.key].get(metric) or np.inf))
                trace = tr.get(best.key, {})
                if spec.kind in ("plan", "program") and trace.get("path"):
                    paths[names[g]] = np.asarray(trace["path"], float)
                elif trace.get("trajectory"):
                    paths[names[g]] = np.asarray(trace["trajectory"], float)[:, 1:3]
        if histories:
            # a path search's fitness is no error to a known optimum: a linear axis, with the
            # value after post-processing marked past the curve (so runs that share a search
            # but not a refinement do not draw one curve)
            files.append(out_dir / f"{_safe(spec.name)}_{_safe(t.name)}_convergence.png")
            plot_convergence(histories, files[-1], title=f"{t.name}: best value per iteration", log=False,
                             finals=finals or None,
                             reference=(ref_line, "exact optimum") if ref_line is not None else None,
                             ylabel=(f"best fitness during the search; marks: final {final_metric}"
                                     if final_metric else None))
        if paths:
            world = _world_of(spec.kind, t.spec)
            if world is not None:
                from .plots import plot_paths

                files.append(out_dir / f"{_safe(spec.name)}_{_safe(t.name)}_paths.png")
                ends = _query_of(spec.kind, t.spec)  # a trajectory ends where the robot stopped
                plot_paths(world, paths, files[-1], title=f"{t.name}: best run of each", start=ends[0],
                           goal=ends[1])
    return files


def _query_of(kind: str, target_spec: Mapping) -> tuple:
    """``(start, goal)`` of a target (``(None, None)`` when it has none to draw)."""
    try:
        if kind in ("plan", "program"):
            from ..bench.runner import plan_target

            _, s, g = plan_target(json.dumps(dict(target_spec), sort_keys=True))
            return s, g
        from ..world.scenario import load_scenario

        sc = load_scenario(target_spec["scenario"])
        return sc.start[:2], sc.goal
    except Exception:  # nothing to mark: plot_paths falls back to the paths' ends
        return None, None


def _world_of(kind: str, target_spec: Mapping):
    if kind in ("plan", "program"):
        from ..bench.runner import plan_target

        return plan_target(json.dumps(dict(target_spec), sort_keys=True))[0]
    try:
        from ..world.scenario import load_scenario

        sc = load_scenario(target_spec["scenario"])
    except Exception:  # no scenario layer or no drawable map: skip the overlay, keep the other plots
        return None
    return getattr(sc, "grid", None) or getattr(sc, "world", None) or getattr(sc, "map", None)


def function_convergence_plots(res: ExperimentResults, out_dir: str | Path) -> list[Path]:
    """chen2025 Figs 3-14 analog: convergence curves of every algorithm on each benchmark
    function (``convergence_F<n>[ _unshifted].png``, so shifted and unshifted runs can share a
    folder)."""
    from .convergence import plot_convergence

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    files = []
    for t in res.spec.targets:
        h = {}
        for (label, _, _), recs in res.groups(t.name).items():
            tr = res.traces([r.key for r in recs if r.key in res.rows])
            h[label] = [np.asarray(tr[k]["history"], float) for k in tr if "history" in tr[k]]
        if not h or not all(len(v) for v in h.values()):
            continue
        shifted = bool(t.spec.get("shifted"))
        f = out_dir / f"convergence_{t.name}{'' if shifted else '_unshifted'}.png"
        plot_convergence(h, f, title=f"{t.name} ({'shifted where applicable' if shifted else 'unshifted'})",
                         log=t.name not in ("F8", "F17", "F18"))
        files.append(f)
    return files


def write_figures(res: ExperimentResults, out_dir: str | Path) -> list[str]:
    """Every figure of a report into ``out_dir``; returns the lines the report prints about them."""
    if res.spec.kind == "optimize":
        files = function_convergence_plots(res, out_dir)
        return [f"convergence plots in {out_dir}/"] if files else []
    files = experiment_plots(res, out_dir)
    return [f"plots: {len(files)} files in {out_dir}/"] if files else []
