"""Statistics for algorithm comparisons: summary tables and Wilcoxon rank-sum tests
(chen2025 §4.2, Table 7: ``+`` the reference is significantly better, ``-`` worse,
``=`` no significant difference at ``alpha``)."""
from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np


def summary(values: Sequence[float]) -> dict[str, float]:
    """Best, mean, worst and standard deviation (ddof 0, as the papers report)."""
    v = np.asarray(values, dtype=float)
    return {"best": float(v.min()), "mean": float(v.mean()), "worst": float(v.max()), "std": float(v.std())}


def ranksum_p(a: Sequence[float], b: Sequence[float]) -> float:
    """Two-sided Wilcoxon rank-sum p-value; 1.0 when both samples are the same constant."""
    from scipy.stats import ranksums

    a, b = np.asarray(a, float), np.asarray(b, float)
    if len(a) == 0 or len(b) == 0:
        return float("nan")
    if np.all(a == a[0]) and np.all(b == b[0]) and a[0] == b[0]:
        return 1.0
    return float(ranksums(a, b).pvalue)


def compare(reference: Sequence[float], other: Sequence[float], alpha: float = 0.05) -> tuple[float, str]:
    """``(p, sign)``: sign ``+`` when the reference (minimised) is significantly better."""
    p = ranksum_p(reference, other)
    if not np.isfinite(p) or p >= alpha:
        return p, "="
    return p, "+" if np.median(reference) < np.median(other) else "-"


def _fmt(x: float) -> str:
    return f"{x:.4e}" if (x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e5)) else f"{x:.4f}"


def summary_table(results: Mapping[str, Mapping[str, Sequence[float]]], fmt: str = "markdown") -> str:
    """Markdown (or LaTeX with ``fmt="latex"``): one row per (problem, algorithm) with best/mean/worst/std.

    ``results[problem][algorithm] = values``.
    """
    from .tables import Table

    table = Table(["problem", "algorithm", "best", "mean", "worst", "std"])
    for prob, algos in results.items():
        for algo, vals in algos.items():
            if len(vals) == 0:
                table.rows.append([prob, algo, "-", "-", "-", "-"])
                continue
            s = summary(vals)
            table.rows.append([prob, algo, _fmt(s["best"]), _fmt(s["mean"]), _fmt(s["worst"]), _fmt(s["std"])])
    return table.render(fmt)


def wilcoxon_table(results: Mapping[str, Mapping[str, Sequence[float]]], reference: str,
                   alpha: float = 0.05, fmt: str = "markdown") -> str:
    """Markdown (or LaTeX): p-values of ``reference`` against each other algorithm per problem,
    and the ``+/=/-`` totals (chen2025 Table 7 layout)."""
    from .tables import Table

    others = [a for a in next(iter(results.values())) if a != reference]
    table = Table(["problem", *others])
    tally = {a: {"+": 0, "=": 0, "-": 0} for a in others}
    for prob, algos in results.items():
        cells = []
        for a in others:
            p, sign = compare(algos[reference], algos[a], alpha)
            tally[a][sign] += 1
            cells.append(f"{p:.3g} ({sign})" if np.isfinite(p) else "-")
        table.rows.append([prob, *cells])
    table.rows.append(["+/=/-", *(f"{t['+']}/{t['=']}/{t['-']}" for t in tally.values())])
    return table.render(fmt)
