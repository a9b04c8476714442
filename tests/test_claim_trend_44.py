"""Issue 44: the ``trend`` claim kind, a monotone trend of one group's metric along ordered targets
(Spearman's rank correlation with a permutation p-value). Synthetic runs only; nothing runs a planner."""
from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np
import pytest
from claim_stubs import StubSpec, StubTarget
from scipy.stats import spearmanr

from optplan.bench import claim_inventory as inv
from optplan.bench import claims as claims_mod
from optplan.bench.claims import (CLAIMS, HOU2024_TABLE4_TARGETS, LI2023_EXP2_TARGETS, PRINTED_TWINS, TOO_FEW_RUNS,
                                  Claim, claims_table, judge, judge_trend, smallest_trend_p, trend_claim, trend_p)


def _groups(step: float, k: int = 4, n: int = 20, seed: int = 0) -> list[np.ndarray]:
    """``k`` targets of ``n`` runs each, uniform noise of width 1 around ``10 + step * target``."""
    rng = np.random.default_rng(seed)
    return [10.0 + step * i + rng.random(n) for i in range(k)]


# ------------------------------------------------------------------------------------------ verdicts

def test_a_clear_increase_holds():
    figure, verdict = judge_trend(_groups(0.5), None)
    assert verdict == "holds"
    assert figure.startswith("means ") and "rho=+" in figure


def test_a_clear_decrease_is_reversed():
    figure, verdict = judge_trend(_groups(-0.5), None)
    assert verdict == "reversed" and "rho=-" in figure and "first to last -" in figure


def test_a_flat_metric_is_not_significant():
    assert judge_trend(_groups(0.0, seed=3), None)[1] == "not significant"
    # every value the same: no order at all
    assert judge_trend([np.full(5, 7.0)] * 3, None)[1] == "not significant"


def test_a_growth_below_the_claimed_change_is_weaker():
    groups = _groups(0.5)
    change = groups[-1].mean() / groups[0].mean() - 1
    assert judge_trend(groups, change / 2)[1] == "holds"
    assert judge_trend(groups, 3 * change)[1] == "weaker"


def test_the_figure_gives_the_means_and_the_change_first_to_last():
    groups = [np.array([1.0, 1.2]), np.array([2.0, 2.2]), np.array([4.0, 4.2])]
    figure, _ = judge_trend(groups, None)
    assert figure.startswith("means 1.1 -> 2.1 -> 4.1; first to last +272.7 % [")


def test_too_few_runs_and_missing_runs_get_no_verdict():
    # one run on each of four targets: 24 orders, the two extreme ones give p = 2/24 > 0.05
    assert smallest_trend_p([[1, 1, 1, 1]]) == pytest.approx(2 / 24)
    assert judge_trend([[1.0], [2.0], [3.0], [4.0]], None)[1] == TOO_FEW_RUNS
    # two runs each: 2520 orders, the same perfect order is significant
    assert judge_trend([[1.0, 1.1], [2.0, 2.1], [3.0, 3.1], [4.0, 4.1]], None)[1] == "holds"
    # paired by seed the same runs allow only (4!)^2 = 576 deals, still enough
    assert smallest_trend_p([[1, 1, 1, 1], [1, 1, 1, 1]]) == pytest.approx(2 / 576)
    # one seed per target (nothing paired): no deal, no verdict; 3 against 3 in one block: 0.1, as rank-sum
    assert smallest_trend_p([[1, 0], [0, 1]]) == 1.0 and smallest_trend_p([[3, 3]]) == pytest.approx(0.1)
    assert judge_trend([[1.0, 2.0], [3.0, 4.0]], None, blocks=[[0, 1], [2, 3]])[1] == TOO_FEW_RUNS
    assert judge_trend([[1.0, 2.0], []], None)[1] == "not run"
    assert judge_trend([[1.0, 2.0]], None)[1] == "not run"


def test_runs_paired_by_seed_show_a_trend_the_spread_between_seeds_hides():
    # every seed grows by 1 % per target, but the seeds lie 10 % apart (another global path each)
    base = 100.0 * (1 + 0.1 * np.random.default_rng(0).standard_normal(10))
    groups = [base * (1 + 0.01 * i) for i in range(4)]
    seeds = [np.arange(10)] * 4
    paired, unpaired = judge_trend(groups, None, blocks=seeds), judge_trend(groups, None)
    assert paired[1] == "holds" and "rho=+1.00 within seeds" in paired[0]
    assert unpaired[1] == "not significant"
    # the paired interval of the change is the per-seed 3 %, not the spread between seeds
    assert "first to last +3.0 % [+3.0, +3.0]" in paired[0]
    assert judge_trend(groups[::-1], None, blocks=seeds)[1] == "reversed"


# --------------------------------------------------------------------------------------- the p-value

def _brute_force_p(groups) -> float:
    """The two-sided p of Spearman's rho by every permutation of the pooled values over the runs'
    target positions (each of the N! equally likely under the null), with scipy's rho."""
    order = np.repeat(np.arange(len(groups)), [len(g) for g in groups])
    values = np.concatenate([np.asarray(g, float) for g in groups])
    observed = abs(spearmanr(order, values)[0])
    rhos = np.array([abs(spearmanr(order, values[list(perm)])[0])
                     for perm in itertools.permutations(range(len(values)))])
    return float(np.mean(rhos >= observed - 1e-12))


@pytest.mark.parametrize("groups", [
    [[1.0, 2.5], [2.0, 4.0], [3.0, 3.5]],            # untied
    [[1.0, 2.0], [2.0, 4.0], [2.0]],                 # ties, unequal sizes
    [[3.0, 1.0, 2.0], [5.0, 4.0, 0.5]],              # two targets (a rank-sum in disguise)
])
def test_the_p_value_is_the_brute_force_enumeration(groups):
    rho, p = trend_p(groups)
    assert p == pytest.approx(_brute_force_p(groups), abs=1e-12)
    order = np.repeat(np.arange(len(groups)), [len(g) for g in groups])
    assert rho == pytest.approx(spearmanr(order, np.concatenate(groups))[0])


def _brute_force_blocked_p(groups, blocks) -> float:
    """The same within blocks: every permutation of each block's values over its runs' target
    positions; the statistic sums each block's product of centred ranks (Page's test)."""
    from scipy.stats import rankdata

    order = np.repeat(np.arange(len(groups)), [len(g) for g in groups])
    values, blk = np.concatenate(groups), np.concatenate(blocks)
    idx = [np.flatnonzero(blk == b) for b in np.unique(blk)]

    def stat(v):
        return sum((rankdata(order[i]) - rankdata(order[i]).mean()) @ (rankdata(v[i]) - rankdata(v[i]).mean())
                   for i in idx)

    observed = abs(stat(values))
    stats = []
    for perms in itertools.product(*(itertools.permutations(i) for i in idx)):
        v = values.copy()
        for i, perm in zip(idx, perms):
            v[i] = values[list(perm)]
        stats.append(abs(stat(v)))
    return float(np.mean(np.array(stats) >= observed - 1e-12))


@pytest.mark.parametrize("groups, blocks", [
    ([[1.0, 5.0], [2.0, 4.0], [3.0, 6.0]], [[0, 1], [0, 1], [0, 1]]),               # two seeds, three targets
    ([[1.0, 5.0, 2.0], [2.0, 4.0], [3.0, 6.0, 2.5]], [[0, 1, 2], [0, 1], [0, 1, 2]]),  # seed 2 failed once
    ([[1.0, 1.0], [1.0, 4.0], [3.0, 6.0]], [[0, 1], [0, 1], [0, 1]]),               # ties
])
def test_the_blocked_p_value_is_the_brute_force_enumeration(groups, blocks):
    assert trend_p(groups, blocks)[1] == pytest.approx(_brute_force_blocked_p(groups, blocks), abs=1e-12)


def test_the_sampled_p_value_repeats_and_agrees_with_the_exact_one(monkeypatch):
    groups = _groups(0.25, k=3, n=4, seed=2)          # 34,650 orders: sampled by default
    _, sampled = trend_p(groups)
    assert trend_p(groups) == trend_p(groups)         # seeded: the verdict repeats
    monkeypatch.setattr(claims_mod, "TREND_EXACT", 10 ** 6)
    _, exact = trend_p(groups)
    assert 0.02 < exact < 0.98 and sampled == pytest.approx(exact, abs=0.01)
    # within seeds: 6 seeds on 3 targets, 6^6 = 46,656 deals
    seeds = [np.arange(6)] * 3
    groups = _groups(0.15, k=3, n=6, seed=4)
    monkeypatch.setattr(claims_mod, "TREND_EXACT", 20000)
    _, sampled = trend_p(groups, seeds)
    assert trend_p(groups, seeds) == trend_p(groups, seeds)
    monkeypatch.setattr(claims_mod, "TREND_EXACT", 10 ** 6)
    _, exact = trend_p(groups, seeds)
    assert 0.02 < exact < 0.98 and sampled == pytest.approx(exact, abs=0.01)


# ------------------------------------------------------------------------------------ the claim kind

def test_a_trend_claim_names_its_targets_in_order():
    c = trend_claim("s", "Fig 1", "grows", ("a", "b", "c"), "g", "path_length")
    assert c.kind == "trend" and c.target == "a" and c.targets == ("a", "b", "c") and c.other is None
    assert c.id == "s:a>b>c:trend:g:path_length"
    assert trend_claim("s", "", "", ("c", "b", "a"), "g", "path_length").id != c.id   # the order is the claim
    assert inv.tid("s", ("a", "b", "c"), "g", "path_length") == c.id
    with pytest.raises(ValueError):
        trend_claim("s", "", "", ("a",), "g", "length")                  # one target is no trend
    with pytest.raises(ValueError):
        Claim("s", "", "", "a", "less", "g", "h", targets=("a", "b"))   # only a trend names several


_Target, _Spec = StubTarget, StubSpec


@dataclass(frozen=True)
class _Run:
    target: str
    group: str
    seed: int


@dataclass
class _Results:
    """What judge() reads of ExperimentResults, per target: target -> group -> metric -> values by seed."""

    spec: _Spec
    data: dict = field(default_factory=dict)

    def groups(self, target):
        return {(g, None, None): [_Run(target, g, s) for s in range(len(m["path_length"]))]
                for g, m in self.data.get(target, {}).items()}

    def group_name(self, lab, refine, local):
        return lab

    def values(self, runs, metric=None):
        return np.asarray([self.data[r.target][r.group][metric][r.seed] for r in runs], float)

    def counts(self, runs):
        return len(runs), 0, len(runs)


def _table4_runs(targets=HOU2024_TABLE4_TARGETS, step=1.0) -> _Results:
    # each seed its own global path (lengths 60-80), each obstacle adding ``step`` (taking it off the time)
    seed_length = 60 + 20 * np.random.default_rng(0).random(20)
    seed_time = 90 + 20 * np.random.default_rng(1).random(20)
    runs = {t: {"missa/missa-dwa": {"path_length": seed_length * (1 + step / 70 * i),
                                    "time_s": seed_time - step * i + 0.1 * np.random.default_rng(10 + i).random(20)}}
            for i, t in enumerate(targets)}
    return _Results(_Spec("hou2024_local_table4", [_Target(t) for t in targets]), runs)


def test_judge_reads_each_target_in_the_claims_order():
    res = _table4_runs()
    length, time = (c for c in CLAIMS if c.kind == "trend" and c.spec == "hou2024_local_table4")
    assert judge(length, res)[1] == "holds"               # lengths grow with the obstacles
    assert judge(time, res)[1] == "reversed"              # times shrink: the claim is reversed
    # a spec run on fewer targets (the quick run) or without the group leaves it not run
    quick = _table4_runs(HOU2024_TABLE4_TARGETS[1:2])
    assert judge(length, quick) == ("target not in this run", "not run")
    res.data[HOU2024_TABLE4_TARGETS[2]] = {}
    assert judge(length, res) == ("group not in this run", "not run")


def test_the_claims_table_shows_the_targets_in_order_and_explains_the_kind():
    table = claims_table(_table4_runs())
    rows = [r for r in table.rows if r[3].startswith("trend: ")]
    assert len(rows) == 2
    assert all(r[2] == " -> ".join(HOU2024_TABLE4_TARGETS) for r in rows)
    assert {r[3] for r in rows} == {"trend: missa/missa-dwa (path_length)", "trend: missa/missa-dwa (time_s)"}
    assert [r[6] for r in rows] == ["holds", "reversed"] and rows[0][4] == "+2.8 %"
    assert any(n.startswith("trend -> ") for n in table.notes)
    # the rate claims of the same spec are still judged on their one target
    assert {r[6] for r in table.rows if r[3] == "missa/missa-dwa"} == {"holds"}


def test_the_fusions_trend_is_judged_as_printed_and_with_our_change():
    ours = trend_claim("li2023_local_exp2", "", "", LI2023_EXP2_TARGETS, "iga/iga-dwa", "path_length")
    twin = PRINTED_TWINS[ours.id]
    assert twin.kind == "trend" and twin.targets == LI2023_EXP2_TARGETS and twin.better == "iga/iga-dwa-printed"


# ------------------------------------------------------------------------------------------ inventory

def test_the_trend_statements_are_judged_and_the_leads_keep_their_reason():
    by_id = {s.id: s for s in inv.statements()}
    kinds = {c.id: c.kind for c in CLAIMS}
    for sid in ("hou2024.t4.trend", "li2023.s6.2.exp2.growth", "li2023.s6.2.exp2.steady"):
        assert by_id[sid].judged and {kinds[c] for c in by_id[sid].claims} == {"trend"}, sid
    assert len(by_id["hou2024.t4.trend"].claims) == 2                   # length and time
    # a trend of one group's lead over another is not what the kind judges: lead_trend does
    for sid in ("li2023.f15.trend", "li2023.s6.3.trend"):
        assert by_id[sid].judged and {kinds[c] for c in by_id[sid].claims} == {"lead_trend"}, sid
    assert inv.problems() == []
