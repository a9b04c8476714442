"""Issue 44, "every claim of every paper judged": the inventory of the papers' quantitative
statements (optplan/bench/claim_inventory.py) against the claims that judge them
(optplan/bench/claims.py), and the coverage tables of docs/fidelity that it prints.

Nothing here runs a planner: the checks are about the lists and the docs."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from optplan.bench import claim_inventory as inv
from optplan.bench import claims as claims_mod
from optplan.bench.claims import CHEN2025_TABLE7, CHEN2025_TABLE7_BASELINES, CHEN2025_TABLE7_TALLY, CLAIMS, Claim

STATEMENTS = inv.statements()


def test_the_inventory_is_sound():
    assert inv.problems() == []


def test_every_claim_id_the_inventory_names_exists_in_claims_py():
    ids = {c.id for c in CLAIMS}
    missing = sorted({c for s in STATEMENTS for c in s.claims} - ids)
    assert not missing, f"the inventory names claims claims.py does not define: {missing[:10]}"


def test_every_claim_of_claims_py_judges_a_listed_statement():
    named = {c for s in STATEMENTS for c in s.claims}
    orphans = [f"{c.id} ({c.source}: {c.quote})" for c in CLAIMS if c.id not in named]
    assert not orphans, "claims no statement of the inventory names:\n" + "\n".join(orphans)


def test_every_statement_not_judged_has_a_known_reason():
    for s in STATEMENTS:
        if s.judged:
            assert not s.reason, s.id
        else:
            assert s.reason.strip() and s.reason in inv.REASONS, (s.id, s.reason)


def test_ids_are_unique_and_name_their_paper():
    ids = [s.id for s in STATEMENTS]
    assert len(ids) == len(set(ids))
    assert len({c.id for c in CLAIMS}) == len(CLAIMS)
    for s in STATEMENTS:
        assert s.paper in inv.PAPERS and s.id.startswith(s.paper + "."), s.id
        assert s.where.strip() and s.says.strip(), s.id
        # a statement of one paper is judged by that paper's specs only
        assert all(c.split(":")[0].startswith(s.paper) for c in s.claims), s.id


def test_claim_ids_depend_on_what_the_verdict_is_computed_from():
    c = Claim("yuan2021_table1", "Table 1", "q", "yuan2021_25", "less", "iba", "ba")
    assert c.id == "yuan2021_table1:yuan2021_25:less:iba:ba:length" == inv.cid("yuan2021_table1", "yuan2021_25",
                                                                             "less", "iba", "ba")
    assert replace(c, quote="other words", claimed=0.5, source="§5").id == c.id
    assert replace(c, metric="n_turns").id != c.id and replace(c, better="pso").id != c.id
    assert Claim("s", "", "", "m", "rate", "iba", claimed=1.0).id == "s:m:rate:iba"


def test_the_checks_fail_on_a_broken_inventory(monkeypatch):
    good = inv.statements

    def with_extra(*extra):
        return lambda paper=None: good(paper) + [s for s in extra if paper in (None, s.paper)]

    # a statement naming a claim that does not exist
    ghost = inv.Statement("yuan2021", "yuan2021.ghost", "Table 9", "a claim that is not there",
                          ("yuan2021_table1:yuan2021_25:less:iba:nope:length",))
    monkeypatch.setattr(inv, "statements", with_extra(ghost))
    assert any("does not define" in p for p in inv.problems())
    # a statement not judged, without a reason
    monkeypatch.setattr(inv, "statements", with_extra(inv.Statement("li2023", "li2023.mute", "§6", "says")))
    assert any("li2023.mute" in p and "reason" in p for p in inv.problems())
    # a duplicate statement id
    monkeypatch.setattr(inv, "statements", with_extra(good("hou2024")[0]))
    assert any("used twice" in p for p in inv.problems())
    monkeypatch.setattr(inv, "statements", good)
    # a claim in claims.py that no statement names
    orphan = Claim("yuan2021_table1", "Table 1", "an orphan", "yuan2021_25", "less", "pso", "ba")
    monkeypatch.setattr(inv, "CLAIMS", CLAIMS + (orphan,))
    assert any(orphan.id in p and "judges no statement" in p for p in inv.problems())
    monkeypatch.setattr(inv, "CLAIMS", CLAIMS)
    assert inv.problems() == []


def test_the_coverage_table_adds_up():
    rows = inv.coverage()
    assert [r["paper"] for r in rows] == list(inv.PAPERS)
    for r in rows:
        st = inv.statements(r["paper"])
        assert r["statements"] == len(st) > 0
        assert r["judged"] + sum(r["not_judged"].values()) == r["statements"]
        assert r["judged"] == sum(s.judged for s in st)
    text = inv.coverage_markdown()
    total = text.splitlines()[-1].split("|")
    assert total[1].strip() == "all" and int(total[2]) == len(STATEMENTS)
    assert int(total[3]) == sum(s.judged for s in STATEMENTS) and int(total[8]) == len(CLAIMS)
    # the quantitative statements (not a qualitative wording) and those of them judged
    quantitative = [s for s in STATEMENTS if s.quantitative]
    assert total[6].split("(")[0].strip() == f"{sum(s.judged for s in quantitative)} / {len(quantitative)}"
    # a qualitative wording judged on our reading says what it was read as, and is judged
    read = [s for s in STATEMENTS if s.reading]
    assert int(total[7]) == len(read) >= 3 and all(s.judged and not s.quantitative for s in read)


def test_chen2025_table7_reads_as_its_own_tally():
    # the transcription of Table 7 (minus signs lost in the text) against the table's last row
    for j, o in enumerate(CHEN2025_TABLE7_BASELINES):
        col = [row[j] for row in CHEN2025_TABLE7.values()]
        assert (col.count("+"), col.count("="), col.count("-")) == CHEN2025_TABLE7_TALLY[o], o
    assert list(CHEN2025_TABLE7) == [f"F{i}" for i in range(1, 19)]
    # every entry is one statement; an implemented "+"/"-" entry is judged in both function specs
    t7 = {s.id: s for s in inv.statements("chen2025") if s.id.startswith("chen2025.t7.F")}
    assert len(t7) == 18 * 7
    s = t7["chen2025.t7.F8.woa"]   # WOA better than MSIAR-GWO in F8: WOA is the claim's better group
    assert s.judged and all(":less:woa:msiar-gwo:f" in c for c in s.claims) and len(s.claims) == 2
    # an "=" entry is judged by the equivalence kind ``tie`` (issue 44), in both function specs
    for sid, f, o in (("chen2025.t7.F9.aro", "F9", "aro"), ("chen2025.t7.F1.rsmgwo", "F1", "rsmgwo")):
        assert t7[sid].judged and sorted(t7[sid].claims) == sorted(
            inv.cid(s, f, "tie", "msiar-gwo", o, "f") for s in ("chen2025_functions", "chen2025_functions_unshifted"))
    # AGWO and RSMGWO run since issue 44 item 5: RSMGWO better than MSIAR-GWO in F8 ("-")
    s = t7["chen2025.t7.F8.rsmgwo"]
    assert s.judged and all(":less:rsmgwo:msiar-gwo:f" in c for c in s.claims) and len(s.claims) == 2


def test_the_added_claims_keep_the_existing_ones_first_and_unchanged():
    added = claims_mod.ADDED_CLAIMS
    assert CLAIMS[-len(added):] == added
    assert not {c.id for c in added} & {c.id for c in CLAIMS[:-len(added)]}


def test_the_docs_hold_the_coverage_tables_and_they_are_current():
    blocks = inv.doc_blocks()
    where = {(p.name, " ".join(argv)) for p, *_, argv, _ in blocks}
    assert ("README.md", "") in where and ("README.md", "--reasons") in where
    for paper in inv.PAPERS:
        assert (f"{paper}.md", f"--unjudged {paper}") in where
    stale = inv.stale_blocks()
    assert not stale, "stale coverage tables (python benchmarks/claim_coverage.py --update-docs):\n" + "\n".join(stale)


def test_doc_markers_are_checked(tmp_path):
    doc = tmp_path / "x.md"
    doc.write_text(f'{inv.DOC_BEGIN} command="python {inv.SCRIPT} --unjudged li2023" -->\n| old |\n{inv.DOC_END}\n')
    assert inv.stale_blocks([doc])
    assert inv.update_docs([doc]) == [doc] and inv.stale_blocks([doc]) == []
    assert inv.update_docs([doc]) == []
    assert doc.read_text().splitlines()[1:-1] == inv.unjudged_markdown("li2023").splitlines()
    doc.write_text(f'{inv.DOC_BEGIN} command="python {inv.SCRIPT}" -->\n| a |\n')
    with pytest.raises(ValueError, match="without its END"):
        inv.doc_blocks([doc])
    doc.write_text(f'{inv.DOC_BEGIN} command="optplan reproduce li2023" -->\n{inv.DOC_END}\n')
    with pytest.raises(ValueError, match="coverage marker"):
        inv.doc_blocks([doc])


def test_the_coverage_markers_leave_the_run_tables_alone():
    from optplan.bench import doc_tables

    # the run tables' parser reads the same files; it must not mistake a coverage block for one of its own
    assert all(b.table for b in doc_tables.find_blocks())


def test_the_script_prints_the_table(capsys):
    import runpy
    import sys
    from pathlib import Path

    script = Path(inv.__file__).resolve().parents[2] / inv.SCRIPT
    argv = sys.argv
    try:
        sys.argv = [str(script), "--unjudged", "yuan2021"]
        runpy.run_path(str(script), run_name="__main__")
    finally:
        sys.argv = argv
    assert capsys.readouterr().out.strip() == inv.unjudged_markdown("yuan2021")


def test_a_reduction_of_negative_means_keeps_its_direction():
    """F8's optimum is below zero: a lower mean is still the better one (the sign of
    1 - mean(a) / mean(b) flips there)."""
    from optplan.bench.claims import judge_less

    better = np.array([-12569.0, -12500.0, -12550.0, -12560.0, -12540.0, -12530.0])
    worse = np.array([-3077.0, -3100.0, -3000.0, -3050.0, -3200.0, -2900.0])
    figure, verdict = judge_less(better, worse, None)
    assert verdict == "holds" and figure.startswith("+")
    figure, verdict = judge_less(worse, better, None)
    assert verdict == "reversed" and figure.startswith("-")
    assert judge_less(np.array([1.0, 1.1, 0.9, 1.05, 0.95, 1.0]), np.array([2.0, 2.1, 1.9, 2.05, 1.95, 2.0]),
                      0.5)[1] == "holds"
