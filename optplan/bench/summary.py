"""Summaries of a stored experiment: groups, min/mean/max/std, rank-sum tests, tables.

Results are selected by the run keys of the spec's expansion (not by experiment
name), so a database shared by several specs, or filled by an earlier
interrupted run, gives each spec exactly its own runs.

A group is one (target, algorithm label, refine mode, local planner). Only
*successful* runs enter the statistics: a feasible path (``plan``), a goal
reached without collision (``simulate``), any finished run (``optimize``), a
feasible solution under the program (``program``). Failed and infeasible runs
are counted in the tables, never averaged in.
"""
from __future__ import annotations

import functools
import json
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .kinds import get_kind
from .spec import ExperimentSpec, RunRecord
from .stats import TOO_FEW, compare, summary, too_few_note
from .tables import Table

GroupKey = tuple  # (label, refine, local_planner)


def pipeline_name(label: str, refine: str | None, local: str | None, vary_refine: bool, vary_local: bool) -> str:
    """The name of one pipeline (algorithm x refine x local planner) in tables and exports:
    ``label``, plus ``+refine`` / ``/local`` where the experiment varies them."""
    name = label
    if vary_refine:
        name += f"+{refine or 'none'}"
    if vary_local:
        name += f"/{local}"
    return name


@dataclass
class ExperimentResults:
    """The stored rows of one spec, with helpers to group them."""

    spec: ExperimentSpec
    records: list[RunRecord]
    rows: dict[str, dict[str, Any]]
    store: Any = None
    _traces: dict[str, dict] = field(default_factory=dict)

    @property
    def missing(self) -> int:
        """Runs of the spec with no stored row yet."""
        return sum(r.key not in self.rows for r in self.records)

    def traces(self, keys) -> dict[str, dict]:
        want = [k for k in keys if k not in self._traces]
        if want and self.store is not None:
            self._traces.update(self.store.traces(want))
        return {k: self._traces.get(k, {}) for k in keys}

    def group_name(self, label: str, refine: str | None, local: str | None) -> str:
        """``label``, plus ``+refine`` / ``/local`` when the spec varies them."""
        return pipeline_name(label, refine, local, len(self.spec.refine) > 1, len(self.spec.local_planners) > 1)

    def groups(self, target: str) -> dict[GroupKey, list[RunRecord]]:
        """Records of one target by (label, refine, local planner), in spec order."""
        out: dict[GroupKey, list[RunRecord]] = {}
        for r in self.records:
            if r.target == target:
                out.setdefault((r.label, r.refine, r.local_planner), []).append(r)
        return out

    def row(self, rec: RunRecord) -> dict[str, Any] | None:
        return self.rows.get(rec.key)

    def successful(self, rec: RunRecord) -> bool:
        row = self.rows.get(rec.key)
        if row is None or row["status"] != "ok":
            return False
        return get_kind(self.spec.kind).successful(row)

    def values(self, recs: list[RunRecord], metric: str | None = None, successful_only: bool = True) -> np.ndarray:
        """``metric`` of the (successful) runs among ``recs`` (NULLs dropped)."""
        metric = metric or self.spec.metric
        vals = []
        for r in recs:
            row = self.rows.get(r.key)
            if row is None or row["status"] != "ok" or (successful_only and not self.successful(r)):
                continue
            v = row.get(metric)
            if v is not None:
                vals.append(float(v))
        return np.asarray(vals, dtype=float)

    def counts(self, recs: list[RunRecord]) -> tuple[int, int, int]:
        """(stored runs, failed runs, successful runs) among ``recs``."""
        stored = [r for r in recs if r.key in self.rows]
        failed = sum(self.rows[r.key]["status"] != "ok" for r in stored)
        return len(stored), failed, sum(self.successful(r) for r in stored)

    def reference_group(self, group: GroupKey) -> GroupKey | None:
        """The group ``group`` is compared against (same refine/local unless the spec pins them)."""
        ref = self.spec.reference
        if ref is None:
            return None
        if isinstance(ref, dict):
            return (ref["algorithm"], ref.get("refine"), ref.get("local_planner") or group[2])
        return (ref, group[1], group[2])

    # ------------------------------------------------------------------ plan results as RunSets
    def run_sets(self, target: str):
        """``[RunSet]`` of one target with :class:`PlanResult` s rebuilt from the database (plan specs)."""
        from ..results import PlanResult
        from .global_runs import RunSet

        sets = []
        for (label, refine, local), recs in self.groups(target).items():
            rs = RunSet(self.group_name(label, refine, local))
            tr = self.traces([r.key for r in recs if r.key in self.rows])
            for r in recs:
                row = self.rows.get(r.key)
                if row is None:
                    continue
                if row["status"] != "ok":
                    rs.failed += 1
                    continue
                t = tr.get(r.key, {})
                rs.results.append(PlanResult(
                    algorithm=r.algorithm, path=np.asarray(t.get("path", np.zeros((0, 2))), float).reshape(-1, 2),
                    feasible=bool(row.get("feasible")), length=_num(row.get("length")),
                    turn_angle_deg=_num(row.get("turn_angle_deg")), n_turns=int(row.get("n_turns") or 0),
                    min_clearance=_num(row.get("min_clearance")), runtime_s=_num(row.get("runtime_s")),
                    history=np.asarray([np.nan if h is None else h for h in t.get("history", [])], float),
                    refined=bool(row.get("refined")), seed=r.seed, message=row.get("message") or "",
                    nfev=int(row.get("nfev") or 0)))
            sets.append(rs)
        return sets


def _num(v) -> float:
    return float("inf") if v is None else float(v)


def load_results(spec: ExperimentSpec, store) -> ExperimentResults:
    """The rows stored for ``spec``'s runs."""
    records = spec.expand()
    return ExperimentResults(spec, records, store.rows([r.key for r in records]), store)


@functools.lru_cache(maxsize=64)
def _exact_optimum(target_json: str, inputs: str, clearance: float = 0.0) -> float:
    from .global_runs import exact_optimum
    from .kinds.plan import plan_target

    world, start, goal = plan_target(target_json)
    return exact_optimum(world, start, goal, clearance)


def exact_optimum_of(target_spec, clearance: float = 0.0) -> float:
    """Length (metres) of the exact any-angle optimum of a plan target at ``clearance`` (with a
    clearance, the visibility planner's conservative optimum), cached per process (by the
    content of its map file too, so an edited map gets its own optimum)."""
    from .kinds import get_kind

    return _exact_optimum(json.dumps(dict(target_spec), sort_keys=True), get_kind("plan").inputs_digest(target_spec),
                          float(clearance))


def _clearance_of(recs) -> float:
    """The clearance the runs of one group plan with (``params.clearance``, default 0)."""
    return float(recs[0].params.get("clearance", 0.0) or 0.0) if recs else 0.0


def _fmt(x: float) -> str:
    return f"{x:.4e}" if (x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e5)) else f"{x:.4f}"


def summary_tables(res: ExperimentResults, metric: str | None = None) -> list[Table]:
    """One table per target: runs, failures, successes, best/mean/worst/std of ``metric`` over the
    successful runs, the gap to the exact optimum (plan specs, metric ``length``), and the
    rank-sum p-value and ``+/=/-`` sign against the reference; plus a tally table."""
    spec = res.spec
    metric = metric or spec.metric
    if spec.kind == "program":
        return program_tables(res, metric)
    with_gap = spec.kind == "plan" and metric == "length"
    tally: dict[str, dict[str, int]] = {}
    tables = []
    for target in spec.targets:
        groups = res.groups(target.name)
        too_few = False
        head = ["algorithm", "runs", "failed", "success", f"best {metric}", f"mean {metric}", f"worst {metric}",
                f"std {metric}"]
        optima: dict[float, float] = {}
        if with_gap:
            head += ["best gap [%]", "mean gap [%]", "mean class gap [%]", "mean in-class gap [%]", "optimal class"]
        if spec.reference is not None:
            head += ["p vs reference", "sign"]
        table = Table(head, caption=f"{spec.name}: {target.name}")
        for g, recs in groups.items():
            name = res.group_name(*g)
            stored, failed, ok = res.counts(recs)
            vals = res.values(recs, metric)
            cells = [name, f"{stored}/{len(recs)}", str(failed), f"{ok}/{stored}"]
            if len(vals):
                s = summary(vals)
                cells += [_fmt(s["best"]), _fmt(s["mean"]), _fmt(s["worst"]), _fmt(s["std"])]
            else:
                cells += ["-"] * 4
            if with_gap:  # against the optimum at the clearance this group plans with
                clearance = _clearance_of(recs)
                if clearance not in optima:
                    optima[clearance] = exact_optimum_of(target.spec, clearance)
                optimum = optima[clearance]
                cells += ([f"{100 * (vals.min() / optimum - 1):.2f}", f"{100 * (vals.mean() / optimum - 1):.2f}"]
                          if len(vals) else ["-", "-"])
                cells += _split_cells(res, recs)
            ref_cells, few = _reference_cells(res, groups, g, name, vals, metric, spec.alpha, tally)
            cells += ref_cells
            too_few |= few
            table.rows.append(cells)
        if optima:
            at = "; ".join(f"{v:.4f} m" + (f" at clearance {c:g} m (corners grown as squares: conservative)" if c else "")
                           for c, v in sorted(optima.items()))
            table.notes.append(f"exact optimum (any-angle, same start/goal): {at}; gap = class gap (the "
                               "corridor: the run's h-signature class optimum vs the optimum) + in-class gap (the "
                               "shape: the path vs its class optimum)")
        if spec.kind == "optimize":
            from .kinds.optimize import function_target

            F = function_target(json.dumps(dict(target.spec), sort_keys=True))
            table.notes.append(f"known optimum of {target.name}: {F.f_opt:.6g}")
        if too_few:
            table.notes.append(too_few_note(spec.alpha))
        tables.append(table)
    if tally:
        tables.append(_tally_table(res, tally, metric))
    return tables


def _split_cells(res: ExperimentResults, recs) -> list[str]:
    """Mean class gap and in-class gap (%) and the share of runs in the optimum's class, from
    the split every plan run stores (runs stored before it existed show ``-``)."""
    cg, ig = res.values(recs, "class_gap"), res.values(recs, "in_class_gap")
    best = res.values(recs, "optimal_class")
    return [f"{100 * cg.mean():.2f}" if len(cg) else "-", f"{100 * ig.mean():.2f}" if len(ig) else "-",
            f"{int(best.sum())}/{len(best)}" if len(best) else "-"]


def _tally_table(res: ExperimentResults, tally: dict[str, dict[str, int]], metric: str) -> Table:
    spec = res.spec
    t = Table(["algorithm vs reference", "+", "=", "-"],
              caption=f"{spec.name}: Wilcoxon rank-sum tally against the reference at alpha {spec.alpha}")
    for name, c in tally.items():
        t.rows.append([name, str(c["+"]), str(c["="]), str(c["-"])])
    t.notes.append(f"+: the reference ({_ref_text(res)}) is significantly better at alpha {spec.alpha}; "
                   f"-: significantly worse; =: no significant difference (targets counted; {metric}, minimised)")
    return t


def program_tables(res: ExperimentResults, metric: str | None = None) -> list[Table]:
    """``program`` specs: one table per map with a row per solver (or chain): stored runs,
    failures, the feasible share, best and median ``metric`` (default ``cost``) over the feasible
    runs, median time and median evaluations over the finished runs, and the rank-sum p-value
    and sign of the feasible runs' ``metric`` against the reference solver; plus the tally."""
    spec = res.spec
    metric = metric or spec.metric
    tally: dict[str, dict[str, int]] = {}
    tables = []
    for target in spec.targets:
        groups = res.groups(target.name)
        head = ["solver", "runs", "failed", "feasible", f"best {metric}", f"median {metric}", "median time [s]",
                "median nfev"]
        if spec.reference is not None:
            head += ["p vs reference", "sign"]
        table = Table(head, caption=f"{spec.name}: {target.name}")
        too_few = False
        for g, recs in groups.items():
            name = res.group_name(*g)
            stored, failed, ok = res.counts(recs)
            vals = res.values(recs, metric)
            times = res.values(recs, "runtime_s", successful_only=False)
            nfev = res.values(recs, "nfev", successful_only=False)
            cells = [name, f"{stored}/{len(recs)}", str(failed), f"{ok}/{stored}",
                     _fmt(float(vals.min())) if len(vals) else "-", _fmt(float(np.median(vals))) if len(vals) else "-",
                     f"{np.median(times):.3f}" if len(times) else "-", f"{np.median(nfev):.0f}" if len(nfev) else "-"]
            ref_cells, few = _reference_cells(res, groups, g, name, vals, metric, spec.alpha, tally)
            cells += ref_cells
            too_few |= few
            table.rows.append(cells)
        program = spec.program.get("program", "?")
        args = spec.program.get("args") or {}
        table.notes.append(f"program {program}" + (f" with {json.dumps(args, sort_keys=True)}" if args else "")
                           + (f", every solver that takes a start starts from the {spec.program['init']} path"
                              if spec.program.get("init") else "")
                           + f"; feasible: feasible runs / stored runs; {metric} over the feasible runs, time and nfev over "
                             f"the finished ones")
        if too_few:
            table.notes.append(too_few_note(spec.alpha))
        tables.append(table)
    if tally:
        tables.append(_tally_table(res, tally, metric))
    return tables


def _ref_text(res: ExperimentResults) -> str:
    ref = res.spec.reference
    if isinstance(ref, dict):
        return res.group_name(ref["algorithm"], ref.get("refine"), ref.get("local_planner"))
    return f"{ref}, same refine mode and local planner" if (len(res.spec.refine) > 1
                                                           or len(res.spec.local_planners) > 1) else str(ref)


def format_summary(res: ExperimentResults, fmt: str = "markdown", metric: str | None = None) -> str:
    """All summary tables of one experiment as text, with a line on missing runs."""
    parts = [f"## {res.spec.formatted_title()}\n"]
    for t in summary_tables(res, metric):
        if fmt == "markdown":
            parts.append(f"### {t.caption.split(': ', 1)[-1]}\n\n{t.markdown()}\n")
        else:
            parts.append(t.latex() + "\n")
    if res.missing:
        parts.append(f"({res.missing} of {len(res.records)} runs are not in the database yet; rerun to complete)")
    return "\n".join(parts)


def _reference_cells(res, groups, g, name, vals, metric, alpha, tally) -> tuple[list[str], bool]:
    """The p-value and sign cells of group ``g`` against its reference (none when it has no
    reference), counting the sign in ``tally[name]``; also whether the groups were too small
    to ever reach ``alpha``. chen2025 Table 7 convention: '+' means the reference is
    significantly better."""
    ref = res.reference_group(g)
    if ref is None:
        return [], False
    if ref == g or ref not in groups:
        return ["-", "ref" if ref == g else "-"], False
    p, sign = compare(res.values(groups[ref], metric), vals, alpha)
    counts = tally.setdefault(name, {"+": 0, "=": 0, "-": 0})
    if sign == TOO_FEW:
        return ["-" if not np.isfinite(p) else f"{p:.3g}", sign], True
    counts[sign] += 1
    return ["-" if not np.isfinite(p) else f"{p:.3g}", sign], False
