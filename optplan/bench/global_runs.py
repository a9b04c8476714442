"""Repeated global planning runs and the tables the example scripts print.

Every table puts each path length next to the exact optimum of the same map
(``visibility`` in centre mode on grids, the tangent graph on circle worlds) and
reports the gap in percent; infeasible runs are counted, never averaged in.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass, field

import numpy as np

from ..results import PlanResult

# each paper's own global planner and (population, iterations), as in the shipped
# reproduction specs (optplan/data/specs/<paper>_global.yaml, yuan2021_table1.yaml,
# chen2025_paths.yaml); used where every paper's planner runs on its own maps
PAPER_PLANNER = {"hou2024": "missa", "yang2023": "ipso", "yuan2021": "iba", "li2023": "iga", "chen2025": "msiar-gwo"}
PAPER_BUDGET = {"hou2024": (60, 300), "yang2023": (50, 300), "yuan2021": (50, 300), "li2023": (50, 200),
                "chen2025": (30, 500)}


@dataclass
class RunSet:
    """All runs of one algorithm on one map."""

    algorithm: str
    results: list[PlanResult] = field(default_factory=list)
    failed: int = 0  # runs that raised instead of returning a result (benchmark runner)

    @property
    def feasible(self) -> list[PlanResult]:
        return [r for r in self.results if r.feasible]

    def values(self, attr: str) -> np.ndarray:
        """``attr`` of the feasible runs."""
        return np.array([getattr(r, attr) for r in self.feasible], dtype=float)


def exact_optimum(world, start, goal, clearance: float = 0.0) -> float:
    """Length of the exact any-angle optimum (metres) between ``start`` and ``goal``."""
    from ..solvers.graph import shortest_path

    return float(shortest_path(world, start, goal, method="visibility", clearance=clearance).length)


def run_many(world, start, goal, algorithm: str, runs: int, seed0: int = 0, progress: bool = True,
             **params) -> RunSet:
    """``runs`` seeded calls of ``op.plan`` (seeds ``seed0 .. seed0 + runs - 1``)."""
    from ..planning import plan

    out = RunSet(algorithm)
    for k in range(runs):
        out.results.append(plan(world, start, goal, algorithm=algorithm, seed=seed0 + k, **params))
        if progress:
            print(f"\r  {algorithm}: {k + 1}/{runs} runs", end="", file=sys.stderr, flush=True)
    if progress:
        print(file=sys.stderr)
    return out


def wilcoxon_p(a: np.ndarray, b: np.ndarray) -> float:
    """Two-sided Wilcoxon rank-sum p-value (NaN when either sample is empty), exact for small
    samples (:func:`optplan.bench.stats.ranksum_p`)."""
    from .stats import ranksum_p

    if len(a) and len(b) and np.allclose(a, a[0]) and np.allclose(b, b[0]) and np.isclose(a[0], b[0]):
        return 1.0
    return ranksum_p(a, b)


def global_table(sets: list[RunSet], optimum: float, reference: str | None = None, fmt: str = "markdown") -> str:
    """Markdown (or LaTeX with ``fmt="latex"``): min/mean/max length and its standard deviation
    (ddof 0; the square is yuan2021 Table 1's variance), gap of the best and mean to
    the optimum, turning, time, objective evaluations spent, feasible share, and the rank-sum
    p-value against ``reference``."""
    return global_table_data(sets, optimum, reference).render(fmt)


def global_table_data(sets: list[RunSet], optimum: float, reference: str | None = None):
    """The :class:`~optplan.bench.tables.Table` behind :func:`global_table`."""
    from .tables import Table

    ref = next((s for s in sets if s.algorithm == reference), None)
    table = Table(["algorithm", "min length [m]", "mean length [m]", "max length [m]", "std length [m]",
                   "best gap [%]", "mean gap [%]", "min turn [deg]", "mean turn [deg]", "mean time [s]",
                   "mean evals", "feasible", "p vs " + (reference or "-")])
    for s in sets:
        L = s.values("length")
        T = s.values("turn_angle_deg")
        t = np.array([r.runtime_s for r in s.results])
        mean_t = f"{t.mean():.3f}" if len(t) else "-"
        evals = f"{np.mean([r.nfev for r in s.results]):.0f}" if s.results else "-"
        count = f"{len(L)}/{len(s.results) + s.failed}" + (f" ({s.failed} failed)" if s.failed else "")
        if len(L):
            p = wilcoxon_p(L, ref.values("length")) if ref is not None and s is not ref else float("nan")
            table.rows.append([s.algorithm, f"{L.min():.4f}", f"{L.mean():.4f}", f"{L.max():.4f}", f"{L.std():.4f}",
                               f"{100 * (L.min() / optimum - 1):.2f}",
                               f"{100 * (L.mean() / optimum - 1):.2f}", f"{T.min():.1f}", f"{T.mean():.1f}", mean_t,
                               evals, count, "-" if np.isnan(p) else f"{p:.3g}"])
        else:
            table.rows.append([s.algorithm, "-", "-", "-", "-", "-", "-", "-", "-", mean_t, evals, count, "-"])
    table.notes.append(f"exact optimum (any-angle, same start/goal): {optimum:.4f} m; std over the feasible runs "
                       "(ddof 0, as the papers report; its square is a variance)")
    return table


def convergence_iteration(history: np.ndarray, rel_tol: float = 1e-9) -> int:
    """First iteration at which the best value is within ``rel_tol`` of its final value."""
    h = np.asarray(history, dtype=float)
    if len(h) == 0 or not np.isfinite(h[-1]):
        return -1
    close = np.abs(h - h[-1]) <= rel_tol * max(abs(h[-1]), 1.0)
    return int(np.argmax(close))


def paper_global(title: str, maps: list[str], algorithms: list[str], runs: int, reference: str,
                 **plan_params) -> dict[str, list[RunSet]]:
    """Run ``algorithms`` on each paper map and print one table per map; returns the runs."""
    from ..world.papermaps import paper_map

    print(f"## {title}\n")
    out = {}
    for name in maps:
        world, s, g = paper_map(name)
        opt = exact_optimum(world, s, g)
        sets = [run_many(world, s, g, a, runs, **plan_params) for a in algorithms]
        print(f"### {name}\n")
        print(global_table(sets, opt, reference=reference))
        print()
        out[name] = sets
    return out
