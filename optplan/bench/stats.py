"""Statistics for algorithm comparisons: summary tables and Wilcoxon rank-sum tests
(chen2025 §4.2, Table 7: ``+`` the reference is significantly better, ``-`` worse,
``=`` no significant difference at ``alpha``); for success rates, the Wilson score
interval and an exact McNemar test on runs paired by scenario and seed.

The rank-sum test is exact for small samples (:data:`EXACT_MAX_RUNS` runs in all or
fewer): its p-value counts, over every way of splitting the pooled runs into two groups of
the same sizes, the splits whose rank sum lies at least as far from its mean as the
observed one (mid-ranks for ties). The normal approximation is only used above that size,
where it is good; with 3 runs against 3 it said p = 0.0495 where the exact value is 0.1.
Groups so small that no outcome could reach ``alpha`` get no sign at all
(:data:`TOO_FEW`): with 3 against 3 the smallest possible p is 2 / C(6, 3) = 0.1.
"""
from __future__ import annotations

import math
from typing import Mapping, Sequence

import numpy as np

EXACT_MAX_RUNS = 60   # pooled runs up to which the rank-sum p-value is exact (about 1 ms there)
TOO_FEW = "n/a"       # the sign of a comparison whose sizes can never reach significance


def summary(values: Sequence[float]) -> dict[str, float]:
    """Best, mean, worst and standard deviation (ddof 0, as the papers report)."""
    v = np.asarray(values, dtype=float)
    return {"best": float(v.min()), "mean": float(v.mean()), "worst": float(v.max()), "std": float(v.std())}


def _exact_ranksum_p(a: np.ndarray, b: np.ndarray) -> float:
    """Two-sided permutation p-value of the rank sum of ``a`` in the pooled sample.

    Ranks are mid-ranks, doubled so that they are integers; the number of ``len(a)``-subsets
    of the pooled ranks with each possible sum is counted by dynamic programming over the
    ranks (exact integer counts), so ties are handled exactly too.
    """
    from scipy.stats import rankdata

    if len(a) > len(b):
        a, b = b, a   # the same p-value; fewer subset sizes to count
    n, N = len(a), len(a) + len(b)
    r2 = np.rint(2 * rankdata(np.concatenate([a, b]))).astype(np.int64)   # doubled mid-ranks
    total = int(r2.sum())
    # ways[k, s]: subsets of the ranks seen so far with k members and doubled rank sum s; the
    # counts stay below C(N, n) <= C(60, 30) ~ 1.2e17, exact in int64
    ways = np.zeros((n + 1, total + 1), dtype=np.int64)
    ways[0, 0] = 1
    for r in r2.tolist():
        ways[1:, r:] += ways[:-1, :total + 1 - r].copy()   # add rank r to every smaller subset
    observed = int(r2[:n].sum())
    sums = np.arange(total + 1, dtype=np.int64)
    centre = n * total            # N times the mean doubled sum: distances stay integers
    far = np.abs(N * sums - centre) >= abs(N * observed - centre)
    hits = int(ways[n, far].sum())
    return min(1.0, hits / math.comb(N, n))


def ranksum_p(a: Sequence[float], b: Sequence[float]) -> float:
    """Two-sided Wilcoxon rank-sum (Mann-Whitney) p-value: exact when the two samples hold
    :data:`EXACT_MAX_RUNS` runs or fewer, else the normal approximation with the tie
    correction; 1.0 when both samples are the same constant, NaN when one is empty."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    if len(a) == 0 or len(b) == 0:
        return float("nan")
    if np.all(a == a[0]) and np.all(b == b[0]) and a[0] == b[0]:
        return 1.0
    if len(a) + len(b) <= EXACT_MAX_RUNS:
        return _exact_ranksum_p(a, b)
    from scipy.stats import mannwhitneyu

    return float(mannwhitneyu(a, b, alternative="two-sided", method="asymptotic", use_continuity=False).pvalue)


def smallest_p(n: int, m: int) -> float:
    """The smallest two-sided rank-sum p-value any data can give with ``n`` against ``m`` runs
    (complete separation, no ties): ``2 / C(n + m, n)``."""
    if n <= 0 or m <= 0:
        return 1.0
    return min(1.0, 2.0 / math.comb(n + m, n)) if n + m <= EXACT_MAX_RUNS else 0.0


def compare(reference: Sequence[float], other: Sequence[float], alpha: float = 0.05) -> tuple[float, str]:
    """``(p, sign)``: sign ``+`` when the reference (minimised) is significantly better, ``-``
    when significantly worse, ``=`` when not significantly different, and :data:`TOO_FEW`
    when the sample sizes could not reach ``alpha`` whatever the values."""
    p = ranksum_p(reference, other)
    if not np.isfinite(p):
        return p, "="
    if smallest_p(len(reference), len(other)) >= alpha:
        return p, TOO_FEW
    if p >= alpha:
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
    too_few = False
    for prob, algos in results.items():
        cells = []
        for a in others:
            p, sign = compare(algos[reference], algos[a], alpha)
            if sign == TOO_FEW:
                too_few = True
            else:
                tally[a][sign] += 1
            cells.append(f"{p:.3g} ({sign})" if np.isfinite(p) else "-")
        table.rows.append([prob, *cells])
    table.rows.append(["+/=/-", *(f"{t['+']}/{t['=']}/{t['-']}" for t in tally.values())])
    if too_few:
        table.notes.append(too_few_note(alpha))
    return table.render(fmt)


def too_few_note(alpha: float) -> str:
    """The table note that explains :data:`TOO_FEW` cells."""
    return (f"{TOO_FEW}: too few runs for the rank-sum test to ever reach alpha {alpha:g} (with n runs "
            f"against m the smallest two-sided p is 2 / C(n + m, n): 0.1 for 3 against 3, 0.029 for 4 against 4); "
            f"not counted in +/=/-")
