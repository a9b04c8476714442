from __future__ import annotations

import numpy as np
import pytest

from optplan.bench.stats import (TOO_FEW, compare, mcnemar_p, ranksum_p, smallest_p, summary, summary_table,
                                 wilcoxon_table, wilson_interval)


def test_summary_and_ranksum():
    s = summary([1.0, 2.0, 3.0])
    assert s == {"best": 1.0, "mean": 2.0, "worst": 3.0, "std": pytest.approx(np.sqrt(2 / 3))}
    assert ranksum_p([1, 1, 1], [1, 1, 1]) == 1.0
    rng = np.random.default_rng(0)
    a, b = rng.normal(0, 1, 20), rng.normal(3, 1, 20)
    p, sign = compare(a, b)
    assert p < 1e-4 and sign == "+"
    assert compare(b, a)[1] == "-"
    assert compare(a, rng.normal(0, 1, 20))[1] == "="


def test_tables_have_the_tally():
    res = {"F1": {"x": [1, 1, 1, 1, 1], "y": [5, 6, 7, 8, 9]}, "F2": {"x": [1, 2, 3, 4, 5], "y": [1, 2, 3, 4, 5]}}
    t = wilcoxon_table(res, "x")
    assert t.splitlines()[-1] == "| +/=/- | 1/1/0 |"
    assert "| F1 | y |" in summary_table(res)


def test_wilson_interval_matches_published_values():
    # Newcombe (1998), Table I: 0/10 -> 0-0.2775, 5/10 -> 0.2366-0.7634 (95 %)
    assert wilson_interval(0, 10) == pytest.approx((0.0, 0.2775), abs=1e-4)
    assert wilson_interval(5, 10) == pytest.approx((0.2366, 0.7634), abs=1e-4)
    lo, hi = wilson_interval(10, 10)
    assert (lo, hi) == pytest.approx((0.7225, 1.0), abs=1e-4)
    assert all(np.isnan(wilson_interval(0, 0)))


def test_mcnemar_counts_only_the_discordant_pairs():
    ref = [True] * 10 + [True, False] * 5
    other = [False] * 10 + [True, False] * 5
    p, only_ref, only_other = mcnemar_p(ref, other)
    assert (only_ref, only_other) == (10, 0)
    assert p == pytest.approx(2 * 0.5 ** 10)  # ten discordant pairs, all one way
    assert mcnemar_p(other, ref)[0] == pytest.approx(p)
    assert mcnemar_p([True, False], [True, False]) == (1.0, 0, 0)
    with pytest.raises(ValueError):
        mcnemar_p([True], [True, False])


def test_three_against_three_is_exact_and_never_significant():
    # the normal approximation gave p = 0.0495 for complete separation, so --quick tables (3 runs
    # per group) marked such cells '+'; the exact test gives 2 / C(6, 3) = 0.1
    assert ranksum_p([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]) == pytest.approx(0.1)
    assert compare([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]) == (pytest.approx(0.1), TOO_FEW)
    assert smallest_p(3, 3) == pytest.approx(0.1) and smallest_p(4, 4) == pytest.approx(2 / 70)
    assert compare([1.0, 2.0, 3.0, 3.5], [4.0, 5.0, 6.0, 7.0]) == (pytest.approx(2 / 70), "+")
    t = wilcoxon_table({"F1": {"x": [1, 2, 3], "y": [4, 5, 6]}}, "x")
    assert "0.1 (n/a)" in t and "| +/=/- | 0/0/0 |" in t and "too few runs" in t


def test_the_exact_rank_sum_matches_scipy_without_ties_and_brute_force_with_ties():
    from itertools import combinations

    from scipy.stats import mannwhitneyu, rankdata

    rng = np.random.default_rng(3)
    for n, m in ((2, 5), (5, 7), (10, 10), (30, 30)):
        a, b = rng.normal(0, 1, n), rng.normal(0.7, 1, m)
        assert ranksum_p(a, b) == pytest.approx(mannwhitneyu(a, b, method="exact").pvalue, rel=1e-12)
    a, b = [1, 1, 2, 3, 5], [2, 2, 3, 4, 4, 5]
    r = rankdata(a + b)
    far = abs(r[:5].sum() - 5 * 12 / 2)
    splits = list(combinations(range(11), 5))
    want = sum(abs(r[list(c)].sum() - 30) >= far - 1e-9 for c in splits) / len(splits)
    assert ranksum_p(a, b) == pytest.approx(want, rel=1e-12)
    big = rng.normal(0, 1, 40), rng.normal(0, 1, 40)  # past the exact range: normal approximation
    assert ranksum_p(*big) == pytest.approx(mannwhitneyu(*big, method="asymptotic", use_continuity=False).pvalue)
