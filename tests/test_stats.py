from __future__ import annotations

import numpy as np
import pytest

from optplan.bench.stats import (compare, mcnemar_p, ranksum_p, summary, summary_table, wilcoxon_table,
                                 wilson_interval)


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
