"""Issue 44, "summary" and "across targets": statements judged as a combination of the claims judging
their parts (kinds ``all``, ``most``, ``net``) and the trend of one group's lead over another along
ordered targets (kind ``lead_trend``). Hand-made runs only; nothing runs a planner."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from claim_stubs import StubSpec, StubTarget

from optplan.bench import claim_inventory as inv
from optplan.bench.claims import (CLAIMS, COMBINED_KINDS, LI2023_MAPS, PRINTED_TWINS, TOO_FEW_RUNS, Claim,
                                  claims_table, combined_claim, judge, judge_combined, judge_lead_trend,
                                  lead_trend_claim, part_labels)


@dataclass
class _Results:
    """What judge() reads of ExperimentResults: ``data[target][group][metric]`` values (every run
    succeeds)."""

    spec: StubSpec
    data: dict

    def groups(self, target):
        return {(g, None, None): (target, g) for g in self.data.get(target, {})}

    def group_name(self, lab, refine, local):
        return lab

    def values(self, key, metric=None):
        target, group = key
        return np.asarray(self.data[target][group].get(metric, ()), float)   # a metric not stored: no runs

    def counts(self, key):
        target, group = key
        n = len(next(iter(self.data[target][group].values())))
        return n, 0, n


def _res(spec: str, data: dict) -> _Results:
    return _Results(StubSpec(spec, [StubTarget(t) for t in data], "plan"), data)


def _noise(n: int = 20, seed: int = 0, width: float = 1.0) -> np.ndarray:
    return width * np.random.default_rng(seed).random(n)


# ------------------------------------------------------------------------------ combining verdicts

H, W, N, R, T, X = "holds", "weaker", "not significant", "reversed", TOO_FEW_RUNS, "not run"


@pytest.mark.parametrize("verdicts, expected", [
    ([H, H, H, H], H),
    ([H, H, W, H], W),               # holds only counting the weaker part
    ([H, H, N, H], N),               # one part open: not shown
    ([H, R, H, H], R),               # one part against: the summary fails
    ([R, X, N, H], R),               # a reversed part decides, whatever the others
    ([H, X, H, H], X),               # a part without a verdict leaves it undecided
    ([H, T, X, H], T),
])
def test_all_holds_when_every_part_holds_and_fails_on_any_reversed_part(verdicts, expected):
    assert judge_combined("all", verdicts)[1] == expected


@pytest.mark.parametrize("verdicts, expected", [
    ([H, H, H, N, R], H),             # 3 of 5 hold
    ([H, H, W, N, R], W),
    ([H, H, N, N, R, R], N),          # 2 of 6 hold, 2 reversed: neither shown
    ([H, H, H, R, R, R], R),          # half reversed: at most half can hold
    ([H, H, H, H, X, X, X], H),       # proved whatever the three without a verdict would give
    ([H, H, H, X, X, X, N], X),
])
def test_most_holds_when_more_than_half_hold_and_fails_when_half_are_reversed(verdicts, expected):
    assert judge_combined("most", verdicts)[1] == expected


@pytest.mark.parametrize("verdicts, expected", [
    ([H] * 5 + [N] * 3 + [R], H),     # tally 5/3/1
    ([H] + [N] * 3 + [R] * 3, R),     # 1/3/3
    ([H, H, N, R, R], N),             # 2/1/2: as many wins as losses
    ([H, H, R, X], X),                # the unknown part could even it out
    ([H, H, H, R, X], H),
])
def test_net_is_the_direction_of_a_tally_of_wins_and_losses(verdicts, expected):
    assert judge_combined("net", verdicts)[1] == expected


def test_the_figure_counts_the_parts_and_names_the_reversed_ones():
    figure, verdict = judge_combined("all", [H, H, H, R], ["F1", "F2", "F3", "F8"])
    assert verdict == R and figure == "3/4 hold, 1 reversed (reversed: F8)"
    assert judge_combined("all", [H] * 4)[0] == "4/4 hold"
    figure, _ = judge_combined("net", [H, W, N, N, R])
    assert figure == "1/5 hold, 1 weaker, 2 not significant, 1 reversed; wins/ties/losses 2/2/1 (reversed: 5)"
    with pytest.raises(ValueError):
        judge_combined("some", [H])
    with pytest.raises(ValueError):
        judge_combined("all", [])
    with pytest.raises(ValueError):
        judge_combined("all", ["fine"])


# ------------------------------------------------------------------------ combinations of claims

def _parts(spec: str = "s", target: str = "m") -> list[Claim]:
    return [Claim(spec, "T1", "a below b", target, "less", "a", "b"),
            Claim(spec, "T1", "a's best below b's", target, "less_best", "a", "b"),
            Claim(spec, "T1", "a below c", target, "less", "a", "c"),
            Claim(spec, "T1", "a always succeeds", target, "rate", "a", claimed=1.0)]


def test_a_combination_of_claims_is_judged_on_the_parts_runs():
    low, high = 10 + _noise(seed=1), 12 + _noise(seed=2)
    parts = _parts()
    every = combined_claim("all", "§1", "a beats b and c", parts)
    assert every.id == "s:m:all:a:b+c:length" and every.other == "b+c" and every.target == "m"
    res = _res("s", {"m": {"a": {"length": low}, "b": {"length": high}, "c": {"length": high + 1}}})
    assert judge(every, res) == ("4/4 hold", "holds")
    # c better than a: one part (a below c) fails, so the summary fails; most of its parts still hold
    res.data["m"]["c"] = {"length": low - 2}
    figure, verdict = judge(every, res)
    assert verdict == "reversed" and figure == "3/4 hold, 1 reversed (reversed: mean c)"
    assert judge(combined_claim("most", "§1", "a beats b and c mostly", parts), res)[1] == "holds"
    # a group missing from the runs: its parts are not run, and a summary of nothing judged is not run
    del res.data["m"]["c"]
    assert judge(combined_claim("all", "§1", "a beats c", parts[2:3]), res) == ("0/1 hold, 1 not run", "not run")


def test_the_claims_table_prints_the_count_of_parts(monkeypatch):
    from optplan.bench import claims as claims_mod

    parts = _parts("sx")
    every = combined_claim("all", "§1", "a beats b and c", parts)
    monkeypatch.setattr(claims_mod, "CLAIMS", (*parts, every))
    res = _res("sx", {"m": {"a": {"length": 10 + _noise(seed=1)}, "b": {"length": 12 + _noise(seed=2)},
                            "c": {"length": 10 + _noise(seed=3)}}})
    table = claims_table(res)
    row = table.rows[-1]
    assert row[2] == "m" and row[3] == "all of 4: a vs b+c (length)" and row[4] == "all hold"
    assert row[5].startswith("3/4 hold, 1 not significant") and row[6] == "not significant"
    assert any(n.startswith("all / most / net -> ") for n in table.notes)


def test_a_combination_is_checked_when_it_is_built():
    with pytest.raises(ValueError, match="own spec"):
        combined_claim("all", "", "two specs", [*_parts("s"), *_parts("t")])
    with pytest.raises(ValueError, match="run time"):
        combined_claim("all", "", "mixed", [Claim("s", "", "", "m", "less", "a", "b", "runtime_s"),
                                            Claim("s", "", "", "m", "less", "a", "b", "length")])
    with pytest.raises(ValueError):
        combined_claim("less", "", "not a combination", _parts())
    with pytest.raises(ValueError):
        Claim("s", "", "", "m", "all", "a", "b")                     # a combination needs parts
    with pytest.raises(ValueError):
        Claim("s", "", "", "m", "less", "a", "b", parts=tuple(_parts()))
    timed = combined_claim("all", "", "faster", [Claim("s", "", "", "m", "less", "a", o, "runtime_s")
                                                  for o in ("b", "c")])
    assert timed.metric == "runtime_s"                                # the row doc_tables does not compare
    assert part_labels(_parts()) == ["mean b", "best b", "mean c", "rate"]


def test_the_printed_twin_of_a_local_summary_combines_the_parts_twins():
    ours = [c for c in CLAIMS if c.kind == "all" and c.spec == "li2023_local_exp2" and c.id in PRINTED_TWINS]
    assert len(ours) == 1
    twin = PRINTED_TWINS[ours[0].id]
    assert twin.better == "iga/iga-dwa-printed" and len(twin.parts) == len(ours[0].parts) == 8
    assert all(p.better == "iga/iga-dwa-printed" for p in twin.parts)


# --------------------------------------------------------------------------------------- lead trend

def _pairs(leads, n: int = 20, reference_runs: int = 1, seed: int = 0):
    """Per target: a stochastic group whose mean lies ``lead`` below a reference at 10 x (target + 1)."""
    out = []
    for i, lead in enumerate(leads):
        ref = 10.0 * (i + 1)
        u = np.random.default_rng(seed + i).random(n)
        a = ref * (1 - lead) + ref * 0.02 * (u - u.mean())
        out.append((a, np.full(reference_runs, ref)))
    return out


def test_a_growing_lead_holds_a_shrinking_one_is_reversed_a_flat_one_is_not_significant():
    figure, verdict = judge_lead_trend(_pairs((0.02, 0.05, 0.09)), None)
    assert verdict == "holds" and figure.startswith("reductions +") and "first to last +" in figure
    assert judge_lead_trend(_pairs((0.09, 0.05, 0.02)), None)[1] == "reversed"
    assert judge_lead_trend(_pairs((0.05, 0.05, 0.05), seed=3), None)[1] == "not significant"


def test_a_lead_growing_less_than_claimed_is_weaker_and_too_few_runs_get_no_verdict():
    pairs = _pairs((0.02, 0.09))
    assert judge_lead_trend(pairs, 0.03)[1] == "holds"
    assert judge_lead_trend(pairs, 0.30)[1] == "weaker"
    # three runs against one: the comparison at each end could never be significant
    assert judge_lead_trend(_pairs((0.02, 0.09), n=3), None)[1] == TOO_FEW_RUNS
    assert judge_lead_trend(_pairs((0.02,)), None)[1] == "not run"


def test_a_deterministic_reference_stored_once_or_repeated_gives_the_same_verdict():
    once = judge_lead_trend(_pairs((0.02, 0.04, 0.05)), None)
    repeated = judge_lead_trend(_pairs((0.02, 0.04, 0.05), reference_runs=20), None)
    assert once == repeated
    # the lead of the mean: 1 - mean(a) / reference, printed per target
    assert once[0].startswith("reductions +2.0 % -> +4.0 % -> +5.0 %")


@pytest.mark.parametrize("reference_runs", [1, 20])
def test_the_test_keeps_its_false_positive_rate_when_the_lead_does_not_change(reference_runs):
    """Under no change of the lead (the same 10 % at every target, skewed runs whose spread does not
    scale with the target) the test rejects about alpha of the time, with a deterministic reference
    and with a stochastic one."""
    rng = np.random.default_rng(11)
    rejected, trials = 0, 300
    for _ in range(trials):
        pairs = []
        for ref in (30.0, 60.0, 90.0):
            b = np.full(1, ref) if reference_runs == 1 else ref + rng.normal(0.0, 2.0, reference_runs)
            pairs.append((0.9 * ref + rng.exponential(2.0, 20) - 2.0, b))
        rejected += judge_lead_trend(pairs, None)[1] in ("holds", "reversed")
    assert rejected / trials < 0.1


def _li2023_runs(astar_runs: int = 1) -> _Results:
    """IGA against TGA and A* on li2023's three maps: IGA's length lead over A* grows (2 -> 5 -> 8 %),
    its lead over TGA stays at 5 %, its key-point lead over A* shrinks from 30x30 to 90x90."""
    data = {}
    for i, m in enumerate(LI2023_MAPS):
        ref = 40.0 * (i + 1)
        iga = ref * (1 - (0.02, 0.05, 0.08)[i]) + _noise(seed=i)
        data[m] = {"iga": {"length": iga, "n_turns": (6.0, 7.0, 8.0)[i] + _noise(seed=10 + i),
                           "runtime_s": 1 + _noise(seed=20 + i)},
                   "ga": {"length": iga / 0.95 + _noise(seed=30 + i), "n_turns": 20 + _noise(seed=40 + i),
                          "runtime_s": 2 + _noise(seed=50 + i)},
                   "astar": {"length": np.full(astar_runs, ref), "n_turns": np.full(astar_runs, (10.0, 11.0, 20.0)[i]),
                             "runtime_s": np.full(astar_runs, 0.01)}}
    return _res("li2023_global", data)


def test_judge_reads_a_lead_trend_along_the_claims_targets():
    res = _li2023_runs()
    claims = {c.id: c for c in CLAIMS}
    length = claims[inv.lid("li2023_global", LI2023_MAPS, "iga", "astar", "length")]
    assert judge(length, res)[1] == "holds"
    tga = claims[inv.lid("li2023_global", LI2023_MAPS[1:], "iga", "ga", "length")]
    assert judge(tga, res)[1] == "not significant"
    # the key-point lead over A* shrinks from 30x30 to 90x90 (40 % -> 60 %... reversed here: it grows)
    keys = claims[inv.lid("li2023_global", LI2023_MAPS[::-1], "iga", "astar", "n_turns")]
    assert keys.targets == LI2023_MAPS[::-1]
    assert judge(keys, res)[1] == "reversed"
    # A* repeated instead of stored once: the same verdicts
    assert judge(length, _li2023_runs(20))[1] == "holds"
    # a quick run on one map
    quick = _res("li2023_global", {LI2023_MAPS[0]: res.data[LI2023_MAPS[0]]})
    assert judge(length, quick) == ("target not in this run", "not run")
    table = claims_table(res)
    rows = [r for r in table.rows if r[3].startswith("lead trend: ")]
    assert len(rows) == 6 and all(" -> " in r[2] for r in rows)
    assert {r[3] for r in rows if r[3].endswith("(runtime_s)")} == {"lead trend: iga vs ga (runtime_s)",
                                                                     "lead trend: iga vs astar (runtime_s)"}
    assert any(n.startswith("lead trend -> ") for n in table.notes)


def test_a_lead_trend_names_its_targets_in_order_and_its_other_group():
    c = lead_trend_claim("s", "", "", ("a", "b", "c"), "g", "h", "length", 0.05)
    assert c.id == "s:a>b>c:lead_trend:g:h:length" and c.target == "a"
    assert lead_trend_claim("s", "", "", ("c", "b", "a"), "g", "h", "length").id != c.id
    with pytest.raises(ValueError):
        Claim("s", "", "", "a", "lead_trend", "g", None, targets=("a", "b"))   # needs the other group
    with pytest.raises(ValueError):
        lead_trend_claim("s", "", "", ("a",), "g", "h", "length")


# ------------------------------------------------------------------------------------------ inventory

SUMMARIES = ("hou2024.s4.3.all-best", "yuan2021.t1.iba-best-of-three", "li2023.s6.1.tga-premature",
             "li2023.s6.4.summary", "chen2025.t7.tally", "chen2025.f9.most", "yang2023.s7.1.best-of-four")


def test_the_summary_and_across_target_statements_are_judged():
    by_id = {s.id: s for s in inv.statements()}
    kinds = {c.id: c.kind for c in CLAIMS}
    for sid in SUMMARIES:
        assert by_id[sid].judged and {kinds[c] for c in by_id[sid].claims} <= set(COMBINED_KINDS), sid
    assert {kinds[c] for c in by_id["chen2025.t7.tally"].claims} == {"net"}
    assert {kinds[c] for c in by_id["chen2025.f9.most"].claims} == {"most"}
    assert len(by_id["chen2025.f9.most"].claims) == 2 * 7          # per baseline, in both function specs
    for sid in ("li2023.f15.trend", "li2023.s6.3.trend"):
        assert by_id[sid].judged and {kinds[c] for c in by_id[sid].claims} == {"lead_trend"}, sid
    # the printed twins of the local summary are named too
    assert len(by_id["li2023.s6.4.summary"].claims) == 4
    # no statement is left as a summary or across targets
    assert not [s.id for s in by_id.values() if s.reason == "summary"]
    assert "across targets" not in inv.REASONS
    assert not [s.id for s in by_id.values() if s.reason == "across targets"]
    assert inv.problems() == []


def test_every_part_of_a_summary_is_a_claim_of_its_spec():
    known = {c.id for c in CLAIMS}
    for c in CLAIMS:
        if c.kind not in COMBINED_KINDS:
            continue
        assert all(p.spec == c.spec for p in c.parts), c.id
        if not c.spec.startswith("chen2025_functions"):
            # the parts of the other summaries are claims listed on their own
            assert all(p.id in known for p in c.parts), c.id
