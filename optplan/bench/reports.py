"""The papers' table layouts, filled from stored runs.

Each shipped spec names its layout with ``report:``; the layouts print what the
example scripts in ``examples/`` print (the same helpers make the tables), so
``optplan reproduce PAPER`` and ``python examples/PAPER.py`` agree run for run.
A layout is ``layout(results, fmt) -> str``; figures are drawn by the viz layer
(:data:`FIGURE_WRITER`).
"""
from __future__ import annotations

import importlib

from pathlib import Path
from typing import Callable

import numpy as np

from .global_runs import convergence_iteration, global_table
from .stats import summary_table, wilcoxon_table
from .summary import ExperimentResults, exact_optimum_of, format_summary
from .tables import Table

# the module that draws a report's figures (viz layer; looked up by name, see docs/architecture.md)
FIGURE_WRITER = "optplan.viz.experiment_plots"


def _ref_label(res: ExperimentResults) -> str | None:
    ref = res.spec.reference
    return ref.get("algorithm") if isinstance(ref, dict) else ref


def _notes(res: ExperimentResults) -> list[str]:
    out = [res.spec.notes.strip()] if res.spec.notes.strip() else []
    if res.missing:
        out.append(f"({res.missing} of {len(res.records)} runs are not in the database; rerun to complete)")
    return out


def global_tables(res: ExperimentResults, fmt: str = "markdown", notes: bool = True) -> str:
    """One :func:`global_table` per map (hou2024 Tables 2-3, chen2025 Tables 9-11 layout)."""
    out = [f"## {res.spec.formatted_title()}\n"]
    for t in res.spec.targets:
        out.append(f"### {t.name}\n")
        out.append(global_table(res.run_sets(t.name), exact_optimum_of(t.spec), reference=_ref_label(res), fmt=fmt))
        out.append("")
    if notes:
        out += _notes(res)
    return "\n".join(out).rstrip("\n") + "\n"


def _tail(res: ExperimentResults) -> str:
    lines = _notes(res)
    return ("\n" + "\n".join(lines) + "\n") if lines else ""


def chen2025_paths(res: ExperimentResults, fmt: str = "markdown") -> str:
    """chen2025 Tables 9-11 (one table per map) and Table 8 (A* against the best MSIAR-GWO path)."""
    from ..planning import plan
    from .runner import plan_target
    import json

    text = global_tables(res, fmt, notes=False).rstrip("\n")
    ref = _ref_label(res) or res.spec.labels[0]
    table = Table(["map", "A* (8-connected) [m]", f"{ref.upper()} best [m]", "exact any-angle optimum [m]"],
                  caption="chen2025 Table 8 analog")
    for t in res.spec.targets:
        world, s, g = plan_target(json.dumps(dict(t.spec), sort_keys=True))
        astar = plan(world, s, g, algorithm="astar")
        sets = {rs.algorithm: rs for rs in res.run_sets(t.name)}
        best = min((r.length for r in sets[ref].feasible), default=float("nan")) if ref in sets else float("nan")
        table.rows.append([t.name, f"{astar.length:.4f}", f"{best:.4f}", f"{exact_optimum_of(t.spec):.4f}"])
    return (f"{text}\n\n## chen2025 Table 8 analog: A* vs {ref.upper()} (best of runs)\n\n"
            f"{table.render(fmt)}\n" + _tail(res))


def functions(res: ExperimentResults, fmt: str = "markdown") -> str:
    """chen2025 Tables 4-6 (best/mean/worst/std of F1-F18) and Table 7 (rank-sum p-values, +/=/-)."""
    from .runner import function_target
    import json

    spec = res.spec
    ref = _ref_label(res) or spec.labels[0]
    results, histories = {}, {}
    for t in spec.targets:
        results[t.name], histories[t.name] = {}, {}
        for (label, _, _), recs in res.groups(t.name).items():
            results[t.name][label] = list(res.values(recs, "f"))
            tr = res.traces([r.key for r in recs if r.key in res.rows])
            histories[t.name][label] = [np.asarray(tr[k]["history"], float) for k in tr if "history" in tr[k]]
    optima = {t.name: function_target(json.dumps(dict(t.spec), sort_keys=True)).f_opt for t in spec.targets}
    out = [f"## {spec.formatted_title()}\n", summary_table(results, fmt=fmt),
           "\nknown optima: " + ", ".join(f"{n}={v:.6g}" for n, v in optima.items()),
           f"\n## chen2025 Table 7 analog: Wilcoxon rank-sum p-values of {ref} against each algorithm\n",
           wilcoxon_table(results, ref, alpha=spec.alpha, fmt=fmt),
           f"\n(+: {ref} significantly better at alpha {spec.alpha}, -: significantly worse, =: no difference)"]
    out += _notes(res)
    return "\n".join(out) + "\n"


def yang2023_global(res: ExperimentResults, fmt: str = "markdown") -> str:
    """yang2023 Tables 1-2 (global tables) and Table 3 (median converged value and iteration)."""
    text = global_tables(res, fmt, notes=False).rstrip("\n")
    table = Table(["environment", "algorithm", "median converged fitness", "median convergence iteration"])
    for t in res.spec.targets:
        for s in res.run_sets(t.name):
            fin = [r.history[-1] for r in s.results if len(r.history)]
            its = [convergence_iteration(r.history) for r in s.results if len(r.history)]
            if fin:
                table.rows.append([t.name, s.algorithm, f"{np.median(fin):.4f}", f"{np.median(its):.0f}"])
    return f"{text}\n\n## yang2023 Table 3 analog: convergence\n\n{table.render(fmt)}\n" + _tail(res)


def yuan2021_turns(res: ExperimentResults, fmt: str = "markdown") -> str:
    """yuan2021 Table 2: the global table plus the number of turns of the feasible paths."""
    lines = [global_tables(res, fmt, notes=False).rstrip("\n"), ""]
    for t in res.spec.targets:
        for s in res.run_sets(t.name):
            turns = [r.n_turns for r in s.feasible]
            if turns:
                lines.append(f"{s.algorithm}: turns min {min(turns)}, mean {sum(turns) / len(turns):.1f}")
    return "\n".join(lines) + "\n" + _tail(res)


def li2023_global(res: ExperimentResults, fmt: str = "markdown") -> str:
    """li2023 Table 1 (TGA vs IGA: length, time, key points, reductions), Table 2 (A* vs IGA) and
    the per-map global tables."""
    import json

    from ..planning import plan
    from ..world.postprocess import remove_collinear
    from .runner import plan_target

    def key_points(r) -> int:
        return max(len(r.path) - 2, 0)

    labels = [a for a in res.spec.labels if a != "astar"] or res.spec.labels
    base, improved = (labels + labels)[:2] if len(labels) < 2 else labels[:2]
    # further (baseline, improved) pairs, e.g. the column chromosome next to the paper's
    pairs = [(base, improved)] + [tuple(labels[i:i + 2]) for i in range(2, len(labels) - 1, 2)]
    t1 = Table(["map", "algorithm", "mean length [m]", "gap to optimum [%]", "mean runtime [s]", "mean key points",
                "length reduction [%]", "runtime reduction [%]", "key point reduction [%]"])
    t2 = Table(["map", "A* length [m]", "A* key points", "A* runtime [s]", f"{improved.upper()} mean length [m]",
                f"{improved.upper()} key points", f"{improved.upper()} runtime [s]", "optimum [m]",
                "length reduction [%]", "runtime reduction [%]", "key point reduction [%]"])
    details = []
    for t in res.spec.targets:
        opt = exact_optimum_of(t.spec)
        sets = {s.algorithm: s for s in res.run_sets(t.name)}
        stats = {}
        for pair_base, pair_improved in pairs:
            for a in dict.fromkeys((pair_base, pair_improved)):
                rs = sets[a]
                L = rs.values("length")
                stats[a] = (L.mean() if len(L) else np.nan,
                            np.mean([r.runtime_s for r in rs.results]) if rs.results else np.nan,
                            np.mean([key_points(r) for r in rs.feasible]) if rs.feasible else np.nan)
            for a in dict.fromkeys((pair_base, pair_improved)):
                Lm, tm, km = stats[a]
                red = ["", "", ""]
                if a == pair_improved and a != pair_base:
                    b = stats[pair_base]
                    red = [f"{100 * (1 - Lm / b[0]):.1f}", f"{100 * (1 - tm / b[1]):.1f}",
                           f"{100 * (1 - km / b[2]):.1f}"]
                t1.rows.append([t.name, a, f"{Lm:.3f}", f"{100 * (Lm / opt - 1):.2f}", f"{tm:.3f}", f"{km:.1f}",
                                *red])
        world, s, g = plan_target(json.dumps(dict(t.spec), sort_keys=True))
        astar = plan(world, s, g, algorithm="astar")
        iga = sets[improved]
        a_keys = len(remove_collinear(astar.path)) - 2
        i_len, i_keys = iga.values("length").mean(), np.mean([key_points(r) for r in iga.feasible])
        i_time = np.mean([r.runtime_s for r in iga.results])
        # Table 2's reductions relative to A* (A*'s own time is a single fast search here)
        t2.rows.append([t.name, f"{astar.length:.3f}", str(a_keys), f"{astar.runtime_s:.4f}", f"{i_len:.3f}",
                        f"{i_keys:.1f}", f"{i_time:.3f}", f"{opt:.3f}", f"{100 * (1 - i_len / astar.length):.1f}",
                        f"{100 * (1 - i_time / astar.runtime_s):.1f}" if astar.runtime_s > 0 else "-",
                        f"{100 * (1 - i_keys / a_keys):.1f}" if a_keys > 0 else "-"])
        details.append((t.name, opt, list(sets.values())))
    out = [f"## {res.spec.formatted_title()}\n", t1.render(fmt), f"\n## li2023 Table 2 analog: A* vs "
           f"{improved.upper()}\n", t2.render(fmt), f"\n## Per-map detail (Wilcoxon rank-sum of lengths against "
           f"{base})\n"]
    for name, opt, sets in details:
        out += [f"### {name}\n", global_table(sets, opt, reference=base, fmt=fmt), ""]
    return "\n".join(out + _notes(res)).rstrip("\n") + "\n"


def _outcomes(rows: list[dict]) -> tuple[int, int, int, int]:
    """``(success, reached, collision-free, timeouts)`` among finished closed-loop rows
    (success: goal reached with zero collisions)."""
    return (sum(bool(r.get("reached")) and not r.get("collisions") for r in rows),
            sum(bool(r.get("reached")) for r in rows), sum(not r.get("collisions") for r in rows),
            sum(r.get("result_status") == "timeout" for r in rows))


def _pipeline_name(res: ExperimentResults, g: tuple) -> str:
    """A closed-loop table's row name: the group name, with the local planner in brackets when
    the spec has only one (the group name then leaves it out)."""
    return res.group_name(*g) + (f" ({g[2]})" if len(res.spec.local_planners) == 1 and g[2] else "")


def closed_loop(res: ExperimentResults, fmt: str = "markdown") -> str:
    """Closed-loop runs (``op.simulate``): per scenario and pipeline, success (goal reached with
    zero collisions), goal reached, collision-free runs, timeouts, time, distance, clearance and
    smoothness, with the rank-sum p-value of the time to goal."""
    from .stats import TOO_FEW, compare, too_few_note

    spec = res.spec
    out = [f"## {spec.formatted_title()}\n"]
    for t in spec.targets:
        groups = res.groups(t.name)
        too_few = False
        table = Table(["pipeline", "runs", "failed", "success", "reached", "collision-free", "timeouts", "mean time [s]",
                       "mean distance [m]", "min clearance [m]", "max |a| [m/s^2]", "max |alpha| [rad/s^2]",
                       "mean step [ms]", "p time vs reference"])
        for g, recs in groups.items():
            rows = [res.rows[r.key] for r in recs if r.key in res.rows and res.rows[r.key]["status"] == "ok"]
            stored, failed, ok = res.counts(recs)

            def col(name, agg=np.mean, rows=rows):
                v = [float(r[name]) for r in rows if r.get(name) is not None]
                return f"{agg(v):.3f}" if v else "-"

            ref = res.reference_group(g)
            p = "-"
            if ref is not None and ref != g and ref in groups:
                pv, sign = compare(res.values(groups[ref], "time_s"), res.values(recs, "time_s"), spec.alpha)
                p = "-" if not np.isfinite(pv) else f"{pv:.3g} ({sign})"
                too_few |= sign == TOO_FEW
            table.rows.append([_pipeline_name(res, g),
                               f"{stored}/{len(recs)}", str(failed),
                               *(f"{n}/{stored}" for n in _outcomes(rows)), col("time_s"),
                               col("path_length"), col("min_clearance", np.min), col("max_abs_accel", np.max),
                               col("max_abs_ang_accel", np.max), col("mean_step_ms"), p])
        errors = {res.rows[r.key]["error"] for recs in groups.values() for r in recs
                  if r.key in res.rows and res.rows[r.key]["status"] != "ok"}
        table.notes += [f"failed: {e}" for e in sorted(e for e in errors if e)][:3]
        if too_few:
            table.notes.append(too_few_note(spec.alpha))
        out += [f"### {t.name}\n", table.render(fmt), ""]
    if len(spec.targets) > 1:
        out += ["### all scenarios\n", closed_loop_overall(res).render(fmt), ""]
    return "\n".join(out + _notes(res)).rstrip("\n") + "\n"


def closed_loop_overall(res: ExperimentResults) -> Table:
    """Per pipeline over every scenario of the spec: success with its Wilson 95 % interval,
    reached, collision-free and timeouts; with a reference, the exact McNemar p-value of the
    success difference on runs paired by scenario and seed."""
    from .stats import mcnemar_p, wilson_interval

    spec = res.spec
    pooled: dict = {}  # group -> {(target, seed): success or None when not stored}
    finished: dict = {}  # group -> finished rows
    for t in spec.targets:
        for g, recs in res.groups(t.name).items():
            pairs, rows = pooled.setdefault(g, {}), finished.setdefault(g, [])
            for r in recs:
                row = res.rows.get(r.key)
                ok = row is not None and row["status"] == "ok"
                pairs[(t.name, r.seed)] = res.successful(r) if ok else None
                if ok:
                    rows.append(row)
    head = ["pipeline", "runs", "success", "success [%]", "95 % interval [%]", "reached", "collision-free", "timeouts"]
    with_ref = spec.reference is not None
    if with_ref:
        head += ["only reference / only this", "p success vs reference"]
    table = Table(head)
    for g, pairs in pooled.items():
        n = len(finished[g])
        k, reached, free, timeouts = _outcomes(finished[g])
        lo, hi = wilson_interval(k, n)
        cells = [_pipeline_name(res, g),
                 f"{n}/{len(pairs)}", f"{k}/{n}", f"{100 * k / n:.1f}" if n else "-",
                 f"{100 * lo:.1f}-{100 * hi:.1f}" if n else "-", f"{reached}/{n}", f"{free}/{n}", f"{timeouts}/{n}"]
        if with_ref:
            ref = res.reference_group(g)
            if ref == g:
                cells += ["ref", "-"]
            elif ref in pooled:
                both = [key for key, v in pairs.items() if v is not None and pooled[ref].get(key) is not None]
                p, only_ref, only_this = mcnemar_p([pooled[ref][key] for key in both], [pairs[key] for key in both])
                cells += [f"{only_ref} / {only_this}", f"{p:.3g}"]
            else:
                cells += ["-", "-"]
        table.rows.append(cells)
    table.notes.append("success: goal reached with zero collisions; interval: Wilson score interval"
                       + ("; p: exact McNemar test on the runs both pipelines share (same scenario and seed)"
                          if with_ref else ""))
    return table


def local_runs(res: ExperimentResults) -> list:
    """``optplan.sim.experiments.LocalRuns`` per scenario and local planner, rebuilt from the database
    (trajectories left out), for the example scripts' closed-loop tables."""
    from ..results import SimResult
    from ..sim.experiments import LocalRuns

    out = []
    for t in res.spec.targets:
        for (label, refine, local), recs in res.groups(t.name).items():
            lr = LocalRuns(t.name, local if len(res.spec.algorithms) == 1 else f"{label}+{local}")
            for r in recs:
                row = res.rows.get(r.key)
                if row is None:
                    continue
                if row["status"] != "ok":
                    lr.error = lr.error or row["error"] or "failed"
                    continue
                lr.results.append(SimResult(
                    reached=bool(row["reached"]), collisions=int(row["collisions"] or 0), time_s=_f(row["time_s"]),
                    path_length=_f(row["path_length"]), min_clearance=_f(row["min_clearance"]),
                    max_abs_accel=_f(row["max_abs_accel"]), max_abs_ang_accel=_f(row["max_abs_ang_accel"]),
                    steps=int(row["steps"] or 0), mean_step_ms=_f(row["mean_step_ms"]), trajectory=np.zeros((0, 6)),
                    status=row.get("result_status") or "", message=row.get("message") or "",
                    global_planner=r.algorithm, local_planner=local or "", refine=refine, seed=r.seed,
                    replans=int(row.get("replans") or 0), max_abs_jerk=_f(row.get("max_abs_jerk")),
                    path_switches=int(row.get("path_switches") or 0), reroute_s=row.get("reroute_s")))
            out.append(lr)
    return out


def _f(v) -> float:
    return float("nan") if v is None else float(v)


def local_tables(res: ExperimentResults, fmt: str = "markdown") -> str:
    """The closed-loop table of the example scripts' ``--part local`` (``optplan.sim.experiments``):
    success, reached, collisions, timeouts, stuck runs, time, path length, step time, clearance."""
    from ..sim.experiments import local_table

    spec = res.spec
    a = spec.algorithms[0]
    head = (f"global planner: {a.name} {a.params.get('global_options') or ''}; seeds {spec.seeds[0]}.."
            f"{spec.seeds[-1]}; local planners: {', '.join(str(p) for p in spec.local_planners)}\n")
    return head + "\n" + local_table(local_runs(res), spec.formatted_title()) + "\n" + _tail(res)


def yuan2021_local(res: ExperimentResults, fmt: str = "markdown") -> str:
    """yuan2021 §4.2, §5.2-5.3: the closed-loop table plus path switches, re-plans and the wall time of
    an answer to a blocked global path per local planner."""
    from ..sim.experiments import path_switches

    table = Table(["local planner", "runs", "mean path switches", "mean re-plans (incl. switches)",
                   "runs with a blocked path", "mean answer to a blocked path [ms]"])
    for s in local_runs(res):
        if s.results:
            sw = [path_switches(r) for r in s.results]
            answers = [r.reroute_s for r in s.results if r.reroute_s is not None]
            table.rows.append([s.planner, str(len(s.results)), f"{sum(sw) / len(s.results):.2f}",
                               f"{sum(r.replans for r in s.results) / len(s.results):.2f}", str(len(answers)),
                               f"{1e3 * np.mean(answers):.1f}" if answers else "-"])
    return local_tables(res, fmt) + "\n" + table.render(fmt) + "\n"


def li2023_local(res: ExperimentResults, fmt: str = "markdown") -> str:
    """li2023 Experiment II: the closed-loop table plus the Figure 17 analog (mean path length of the
    successful runs against the number of moving obstacles, scenario names ``..._<movers>``)."""
    sets = local_runs(res)
    scenarios = [t.name for t in res.spec.targets]
    movers = [n.rsplit("_", 1)[-1] for n in scenarios]
    table = Table(["local planner", *(f"{m} movers" for m in movers)])
    for p in dict.fromkeys(s.planner for s in sets):
        cells = []
        for sc in scenarios:
            s = next(x for x in sets if x.planner == p and x.scenario == sc)
            ok = s.successes
            cells.append(f"{np.mean([r.path_length for r in ok]):.2f} ({len(ok)}/{len(s.results)})" if ok
                         else f"- (0/{len(s.results)})")
        table.rows.append([p, *cells])
    return (local_tables(res, fmt) + "\n## li2023 Figure 17 analog: mean path length [m] of successful "
            "runs by number of moving obstacles\n\n" + table.render(fmt) + "\n\n(successful runs / runs in brackets)\n")


def summary_layout(res: ExperimentResults, fmt: str = "markdown") -> str:
    """The generic summary (:func:`optplan.bench.summary.format_summary`)."""
    notes = [res.spec.notes.strip()] if res.spec.notes.strip() else []
    return "\n".join([format_summary(res, fmt)] + notes) + "\n"


LAYOUTS: dict[str, Callable[..., str]] = {
    "summary": summary_layout,
    "global": global_tables,
    "chen2025-paths": chen2025_paths,
    "functions": functions,
    "yang2023-global": yang2023_global,
    "yuan2021-turns": yuan2021_turns,
    "li2023-global": li2023_global,
    "closed-loop": closed_loop,
    "local": local_tables,
    "yuan2021-local": yuan2021_local,
    "li2023-local": li2023_local,
}


def render_report(res: ExperimentResults, fmt: str = "markdown", plots_dir: Path | None = None,
                  layout: str | None = None) -> str:
    """The tables of ``res`` in its spec's layout (``report:`` key) or in ``layout``."""
    from ..errors import ParameterError

    name = layout or res.spec.report
    if name not in LAYOUTS:
        raise ParameterError(f"unknown report layout {name!r}; known: {', '.join(LAYOUTS)}")
    text = LAYOUTS[name](res, fmt)
    if plots_dir is not None:
        # figures belong to the viz layer, found by name at run time (docs/architecture.md)
        figures = importlib.import_module(FIGURE_WRITER)
        text = text.rstrip("\n") + "\n" + "\n".join(figures.write_figures(res, plots_dir)) + "\n"
    from .claims import render_claims

    text = text.rstrip("\n") + "\n" + render_claims(res, fmt)   # the paper's claims, judged
    if fmt == "latex":  # headings and notes become LaTeX comments around the table environments
        text = "\n".join(("% " + line.lstrip("#").strip()) if line.startswith("#") else line
                          for line in text.splitlines()) + "\n"
    return text
