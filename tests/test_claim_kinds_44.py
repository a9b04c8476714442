"""Issue 44: the claim kinds that judge the best / worst run of two groups (``less_best``,
``less_worst``), equally good groups (``tie``, ``tie_best``) and reaching a function's optimum
(``reaches``), on synthetic runs. Nothing here runs a planner."""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
import pytest
from claim_stubs import StubSpec, StubTarget

from optplan.bench import claim_inventory as inv
from optplan.bench.claims import (CLAIMS, FUNCTION_TOL, Claim, claims_table, judge, judge_less_extreme,
                                  judge_reaches, judge_tie, precedence_p, smallest_precedence_p)


def _runs(centre: float, spread: float, n: int = 20, seed: int = 0) -> np.ndarray:
    return centre + spread * np.random.default_rng(seed).random(n)


# ------------------------------------------------------------------------------ less_best / less_worst

def test_a_clearly_better_best_run_holds_and_the_reverse_is_reversed():
    a, b = _runs(10.0, 1.0, seed=1), _runs(11.0, 1.0, seed=2)   # every run of a below b's best
    figure, verdict = judge_less_extreme(a, b, None)
    assert verdict == "holds" and figure.startswith("+") and "lead +20 runs" in figure
    figure, verdict = judge_less_extreme(b, a, None)
    assert verdict == "reversed" and figure.startswith("-") and "lead -20 runs" in figure


def test_the_best_run_is_judged_not_the_mean():
    # a: one excellent run among poor ones; b: uniformly middling. a's mean is worse, its best better
    a = np.r_[np.full(5, 1.0), _runs(20.0, 1.0, n=15, seed=3)]
    b = _runs(10.0, 1.0, seed=4)
    assert a.mean() > b.mean() and a.min() < b.min()
    figure, verdict = judge_less_extreme(a, b, None)
    assert verdict == "holds" and figure.startswith(f"{100 * (1 - a.min() / b.min()):+.1f} %")
    # the worst run of a is the higher one
    assert judge_less_extreme(a, b, None, worst=True)[0].startswith(f"{100 * (1 - a.max() / b.max()):+.1f} %")
    assert judge_less_extreme(a, b, None, worst=True)[1] == "reversed"
    assert judge_less_extreme(b, a, None, worst=True)[1] == "holds"


def test_a_best_run_below_by_less_than_claimed_is_weaker():
    a, b = _runs(10.0, 1.0, seed=1), _runs(11.0, 1.0, seed=2)
    red = 1 - a.min() / b.min()
    assert judge_less_extreme(a, b, red / 2)[1] == "holds"
    assert judge_less_extreme(a, b, 3 * red)[1] == "weaker"


def test_groups_sharing_their_best_run_are_not_significant():
    # path planners often find the same shortest path: equal minima are no evidence either way
    a = np.r_[27.74, 27.74, _runs(28.0, 2.0, n=18, seed=5)]
    b = np.r_[27.74, _runs(28.0, 2.0, n=19, seed=6)]
    figure, verdict = judge_less_extreme(a, b, 0.03)
    assert verdict == "not significant" and figure.startswith("+0.0 %") and "lead +0 runs" in figure


def test_one_lucky_run_is_not_enough():
    a, b = np.r_[9.0, _runs(10.0, 1.0, n=19, seed=7)], _runs(10.0, 1.0, seed=8)
    p, lead = precedence_p(a, b)
    assert lead >= 1 and p > 0.05
    assert judge_less_extreme(a, b, None)[1] == "not significant"


def test_too_few_runs_get_no_verdict():
    assert smallest_precedence_p(3, 3) == pytest.approx(0.1)
    assert judge_less_extreme([1.0, 1.1, 1.2], [5.0, 5.1, 5.2], None)[1] == "too few runs"
    assert judge_less_extreme([1.0], [5.0, 5.1], None)[1] == "not run"


@pytest.mark.parametrize("n, m", [(4, 5), (5, 5), (3, 6)])
def test_the_precedence_p_is_the_exact_permutation_probability(n, m):
    """Every split of n + m distinct values into the two groups is equally likely under the null; the
    p-value of a lead of k is the share of splits whose lead is at least k in absolute value."""
    values = np.arange(n + m, dtype=float)
    leads = []
    for idx in itertools.combinations(range(n + m), n):
        a = values[list(idx)]
        b = np.delete(values, list(idx))
        leads.append(abs(precedence_p(a, b)[1]))
    leads = np.array(leads)
    for k in range(1, max(n, m) + 1):
        a = np.r_[np.arange(k, dtype=float) - 100, np.arange(n - k, dtype=float) + 1000] if k <= n else None
        if a is None:   # b leads by k
            b = np.r_[np.arange(k, dtype=float) - 100, np.arange(m - k, dtype=float) + 1000]
            a = np.arange(n, dtype=float) + 500
        else:
            b = np.arange(m, dtype=float) + 500
        p, lead = precedence_p(a, b)
        assert abs(lead) == k
        assert p == pytest.approx(np.mean(leads >= k)), k
    assert smallest_precedence_p(n, m) == pytest.approx(np.mean(leads >= max(n, m)))
    assert math.isclose(smallest_precedence_p(n, m), 1 / math.comb(n + m, max(n, m)) * (1 + (n == m)))


# ------------------------------------------------------------------------------------------- tie

def test_identical_groups_tie_and_clearly_different_ones_do_not():
    a = np.full(20, 0.397887) + 1e-12 * np.random.default_rng(0).random(20)
    assert judge_tie(a, a.copy(), FUNCTION_TOL)[1] == "holds"
    assert judge_tie(a, a + 1e-3, FUNCTION_TOL)[1] == "reversed"
    b, c = _runs(10.0, 1.0, seed=1), _runs(12.0, 1.0, seed=2)
    assert judge_tie(b, c, FUNCTION_TOL)[1] == "reversed"


def test_the_margin_decides_and_overlapping_noise_proves_nothing():
    a, b = _runs(10.0, 1.0, seed=1), _runs(10.0, 1.0, seed=2)
    # the same distribution, but its spread dwarfs the margin: equality is not shown, nor a difference
    assert judge_tie(a, b, FUNCTION_TOL)[1] == "not significant"
    # with a margin wider than the spread the same runs are equivalent
    assert judge_tie(a, b, 1.0)[1] == "holds"


def test_tie_best_compares_the_best_runs():
    shared = 27.740892
    a = np.r_[np.full(6, shared), _runs(28.0, 3.0, n=14, seed=1)]
    b = np.r_[np.full(6, shared), _runs(30.0, 3.0, n=14, seed=2)]   # a far worse mean, the same best
    assert judge_tie(a, b, 5e-5)[1] != "holds"
    assert judge_tie(a, b, 5e-5, best=True)[1] == "holds"
    c = _runs(29.0, 1.0, seed=3)
    assert judge_tie(a, c, 5e-5, best=True)[1] == "reversed"
    assert judge_tie([1.0, 1.0, 1.0], [1.0, 1.0, 1.0], 1e-8)[1] == "too few runs"


# ------------------------------------------------------------------------------------------ reaches

def test_reaching_the_optimum_counts_runs_within_the_tolerance():
    assert judge_reaches(np.full(20, 1e-12), 20, FUNCTION_TOL, 1.0)[1] == "holds"
    assert judge_reaches(np.r_[np.zeros(15), np.full(5, 1e-3)], 20, FUNCTION_TOL, 1.0)[1] == "weaker"
    assert judge_reaches(np.full(20, 1e-3), 20, FUNCTION_TOL, 1.0)[1] == "reversed"
    # a failed run (no stored error) does not reach it
    assert judge_reaches(np.zeros(18), 20, FUNCTION_TOL, 1.0)[1] == "weaker"


# --------------------------------------------------------------------------- judge() on stored runs

_Target, _Spec = StubTarget, StubSpec


@dataclass
class _Results:
    """The part of ExperimentResults that judge() reads: groups of runs and their values."""

    spec: _Spec
    data: dict                      # label -> {metric: values}
    runs: dict = field(default_factory=dict)

    def groups(self, target):
        return {(lab, None, None): lab for lab in self.data}

    def group_name(self, lab, refine, local):
        return lab

    def values(self, recs, metric=None):
        return np.asarray(self.data[recs][metric], float)

    def counts(self, recs):
        n = len(next(iter(self.data[recs].values())))
        return self.runs.get(recs, n), 0, n


def test_judge_dispatches_the_new_kinds_on_stored_runs():
    good = np.r_[np.full(5, 1.0), _runs(20.0, 1.0, n=15, seed=3)]
    mid = _runs(10.0, 1.0, seed=4)
    res = _Results(_Spec("s", [_Target("m")], "plan"), {"a": {"length": good}, "b": {"length": mid}})
    assert judge(Claim("s", "", "", "m", "less", "a", "b"), res)[1] == "reversed"        # mean
    assert judge(Claim("s", "", "", "m", "less_best", "a", "b"), res)[1] == "holds"      # best run
    assert judge(Claim("s", "", "", "m", "less_worst", "b", "a"), res)[1] == "holds"     # worst run
    # a tie on a spec that is not a benchmark function must name its margin
    with pytest.raises(ValueError, match="tol"):
        judge(Claim("s", "", "", "m", "tie", "a", "b"), res)
    # the same runs on both sides still vary between resamples: equal within a margin wider than that
    assert judge(Claim("s", "", "", "m", "tie", "b", "b", tol=1e-6), res)[1] == "not significant"
    assert judge(Claim("s", "", "", "m", "tie", "b", "b", tol=1.0), res)[1] == "holds"
    # on a function spec the margin is the benchmark tolerance, and reaches reads the stored error
    fres = _Results(_Spec("f", [_Target("F15")], "optimize"),
                    {"x": {"f": np.full(20, 0.3979), "f_error": np.full(20, 1e-14)},
                     "y": {"f": np.full(20, 0.3979) + 1e-6, "f_error": np.full(20, 1e-6)}})
    assert judge(Claim("f", "", "", "F15", "tie", "x", "x", "f"), fres)[1] == "holds"
    assert judge(Claim("f", "", "", "F15", "tie", "x", "y", "f"), fres)[1] == "reversed"
    assert judge(Claim("f", "", "", "F15", "reaches", "x", metric="f_error", claimed=1.0), fres)[1] == "holds"
    assert judge(Claim("f", "", "", "F15", "reaches", "y", metric="f_error", claimed=1.0), fres)[1] == "reversed"


def test_the_claims_table_names_the_kind_and_keeps_the_run_time_mark():
    from optplan.bench import claims as claims_mod

    runs = {lab: {"length": _runs(c, 1.0, seed=i), "runtime_s": _runs(c, 1.0, seed=10 + i),
                  "turn_angle_deg": _runs(10 * c, 10.0, seed=20 + i)}
            for i, (lab, c) in enumerate((("missa", 10.0), ("aco", 12.0), ("iaco", 12.0), ("ssa", 12.0),
                                          ("aco-pruned", 12.0), ("iaco-pruned", 12.0), ("missa-evals", 10.0)))}
    spec = _Spec("hou2024_global", [_Target("hou2024_env1")], "plan")
    table = claims_table(_Results(spec, runs))
    best = [r for r in table.rows if r[3].startswith("best: ")]
    # environment 2 is not in these runs: its rows are listed as not run
    assert {r[6] for r in best if r[2] == "hou2024_env2"} == {"not run"}
    rows = [r for r in best if r[2] == "hou2024_env1"]
    timed = [r for r in rows if "runtime" in r[1]]
    assert timed and all(r[3].endswith("(runtime_s)") for r in timed)   # doc_tables skips these cells
    assert {r[6] for r in rows if r[1].startswith("best length")} == {"holds"}
    assert any("precedence" in n for n in table.notes)
    assert claims_mod.claims_of("hou2024_global")


# ------------------------------------------------------------------------------------- inventory

def test_the_extreme_and_tie_statements_are_judged_by_the_new_kinds():
    by_id = {s.id: s for s in inv.statements()}
    kinds = {c.id: c.kind for c in CLAIMS}
    assert not [s.id for s in by_id.values() if s.reason in ("extreme", "tie")]
    assert {kinds[c] for c in by_id["hou2024.t2.best-length.aco"].claims} == {"less_best"}
    assert {kinds[c] for c in by_id["yuan2021.t1.worst.pso"].claims} == {"less_worst"}
    assert {kinds[c] for c in by_id["chen2025.t7.F9.aro"].claims} == {"tie"}
    assert {kinds[c] for c in by_id["chen2025.t9-10.same-best-aro"].claims} == {"tie_best"}
    assert {kinds[c] for c in by_id["chen2025.t6.f15.every-run"].claims} == {"reaches"}
    # the runs a figure draws stay unjudged, with their own reason
    for sid in ("hou2024.s4.5.evasions", "yang2023.f12.escape", "chen2025.f15-17.paths"):
        assert not by_id[sid].judged and by_id[sid].reason == "one drawn run", sid


def test_a_share_kind_has_a_share_id_and_the_path_ties_name_their_margin():
    c = Claim("chen2025_functions", "", "", "F15", "reaches", "aro", metric="f_error", claimed=1.0)
    assert c.id == "chen2025_functions:F15:reaches:aro"
    path_ties = [c for c in CLAIMS if c.kind in ("tie", "tie_best") and c.spec == "chen2025_paths"]
    assert path_ties and all(c.tol is not None for c in path_ties)


def test_staying_off_the_optimum_is_judged_on_the_runs_within_the_tolerance():
    from optplan.bench.claims import judge_misses

    off = np.full(10, 1e-5)
    figure, verdict = judge_misses(off, 10, FUNCTION_TOL, 0.0)
    assert verdict == "holds" and figure.startswith("0/10 within 1e-08 of the optimum")
    # Table 4's GWO value on F1 (6e-28) is the optimum by the benchmark tolerance
    assert judge_misses(np.r_[np.full(3, 6e-28), off[:7]], 10, FUNCTION_TOL, 0.0)[1] == "weaker"
    assert judge_misses(np.full(10, 6e-28), 10, FUNCTION_TOL, 0.0)[1] == "reversed"
    spec = _Spec("f", [_Target("F1")], "optimize")
    claim = Claim("f", "", "", "F1", "misses", "gwo", metric="f_error", claimed=0.0)
    assert claim.id == "f:F1:misses:gwo"
    assert judge(claim, _Results(spec, {"gwo": {"f_error": off}}))[1] == "holds"
