from __future__ import annotations

import numpy as np
import pytest

from optplan.bench.stats import compare, ranksum_p, summary, summary_table, wilcoxon_table


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
