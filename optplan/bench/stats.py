"""Statistics for algorithm comparisons: summary tables and Wilcoxon rank-sum tests
(chen2025 §4.2, Table 7: ``+`` the reference is significantly better, ``-`` worse,
``=`` no significant difference at ``alpha``); for success rates, the Wilson score
interval and an exact McNemar test on runs paired by scenario and seed."""
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


def wilson_interval(successes: int, runs: int, confidence: float = 0.95) -> tuple[float, float]:
    """Wilson score interval of a success rate (``(nan, nan)`` without runs). Unlike the
    normal approximation it stays inside [0, 1] and is honest at 0 or all successes."""
    from scipy.stats import norm

    if runs <= 0:
        return float("nan"), float("nan")
    z = float(norm.ppf(0.5 + confidence / 2))
    p = successes / runs
    centre = (p + z * z / (2 * runs)) / (1 + z * z / runs)
    half = z / (1 + z * z / runs) * np.sqrt(p * (1 - p) / runs + z * z / (4 * runs * runs))
    return float(max(0.0, centre - half)), float(min(1.0, centre + half))


def mcnemar_p(reference: Sequence[bool], other: Sequence[bool]) -> tuple[float, int, int]:
    """Exact two-sided McNemar test of two success records paired run by run (same scenario,
    same seed): ``(p, reference-only successes, other-only successes)``. Only the discordant
    pairs carry information; under the null each is equally likely to go either way."""
    from scipy.stats import binomtest

    a, b = np.asarray(reference, bool), np.asarray(other, bool)
    if a.shape != b.shape:
        raise ValueError(f"paired success records differ in length: {a.shape} vs {b.shape}")
    only_ref, only_other = int((a & ~b).sum()), int((~a & b).sum())
    if only_ref + only_other == 0:
        return 1.0, 0, 0
    return float(binomtest(only_ref, only_ref + only_other, 0.5).pvalue), only_ref, only_other


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
