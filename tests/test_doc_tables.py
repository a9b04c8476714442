"""Docs that cannot go stale (issue 44): every marked results table of README.md and
docs/fidelity/*.md is what its command prints at its recorded seeds (optplan/bench/doc_tables.py).

Default suite: every marker names a command that runs its spec at the seeds it records, and the
machinery end to end (``optplan reproduce ... --update-docs`` on a quick run writes a table that a
fresh run then agrees with). Blocks whose command is ``--quick`` or in ``SMALL`` are rerun here; the
others (full reproductions, minutes each) are rerun by the slow test (``-m slow``).
Wall-clock cells are never compared (doc_tables.WALL_CLOCK_COLUMNS, WALL_CLOCK_ROW_MARKS).
"""
from __future__ import annotations

from collections import defaultdict

import pytest

from optplan.bench import doc_tables
from optplan.bench.command import command_reports, command_specs
from optplan.cli import main

BLOCKS = doc_tables.find_blocks()
BY_COMMAND: dict[str, list] = defaultdict(list)
for _b in BLOCKS:
    BY_COMMAND[_b.command].append(_b)
# small full commands checked in the default suite as well (only the specs the docs show are run:
# yuan2021's global part, 120 runs, and yang2023's crossing test, 120 closed loops; about 15 s
# each on 2 cores); every other full reproduction is the slow test's
SMALL = {"optplan reproduce yuan2021 --part global", "optplan reproduce yang2023 --part local"}
FAST = sorted(c for c in BY_COMMAND if doc_tables.parse_command(c).quick or c in SMALL)
SLOW = sorted(c for c in BY_COMMAND if c not in FAST)


def _stale(command: str, workers: int | None) -> list[str]:
    blocks = BY_COMMAND[command]
    reports = command_reports(command, [b.spec for b in blocks], workers=workers)
    return [d for b in blocks for d in doc_tables.differences(b, *reports[b.spec])]


def test_the_docs_have_marked_tables():
    files = {b.path.name for b in BLOCKS}
    assert {"README.md", "yang2023.md"} <= files
    assert {b.spec for b in BLOCKS} >= {"hou2024_global", "yuan2021_table1", "yuan2021_table2", "li2023_global",
                                       "yang2023_global", "chen2025_functions", "chen2025_paths",
                                       "yang2023_local_crossing"}


@pytest.mark.parametrize("block", BLOCKS, ids=lambda b: f"{b.path.name}:{b.spec}:{b.table[:20]}")
def test_every_marker_names_a_command_that_prints_it_at_its_seeds(block):
    specs = {s.name: s for s in command_specs(block.command)}
    assert block.spec in specs, f"{block.where()}: {block.command!r} does not run {block.spec}"
    assert block.attrs.get("seeds") == doc_tables.seeds_text(specs[block.spec].seeds), \
        f"{block.where()}: the command now runs other seeds; rerun it with --update-docs"
    rows = [ln for ln in block.body if ln.strip()]
    assert rows and all(ln.startswith("|") for ln in rows), f"{block.where()}: not a table"


@pytest.mark.parametrize("command", FAST)
def test_fast_doc_tables_match_a_fresh_run(command):
    stale = _stale(command, workers=1 if doc_tables.parse_command(command).quick else None)
    assert not stale, "stale doc tables (rerun the command with --update-docs):\n" + "\n".join(stale)


@pytest.mark.slow
@pytest.mark.parametrize("command", SLOW)
def test_slow_doc_tables_match_a_fresh_run(command):
    stale = _stale(command, workers=None)
    assert not stale, "stale doc tables (rerun the command with --update-docs):\n" + "\n".join(stale)


DOC = """# notes

<!-- optplan:table BEGIN command="optplan reproduce yuan2021 --part global --quick" spec=yuan2021_table1 table=claims -->
| stale |
<!-- optplan:table END -->

text between

<!-- optplan:table BEGIN command="optplan reproduce yuan2021 --part global --runs 5" spec=yuan2021_table1 table=claims seeds=0-4 -->
| other runs, left alone |
<!-- optplan:table END -->

<!-- optplan:table BEGIN command="optplan reproduce yuan2021 --quick --runs 3" spec=yuan2021_table2 table=claims -->
<!-- optplan:table END -->
"""


def test_update_docs_writes_what_the_command_prints_and_a_fresh_run_agrees(tmp_path, monkeypatch, capsys):
    doc = tmp_path / "README.md"
    doc.write_text(DOC)
    monkeypatch.setattr(doc_tables, "doc_files", lambda root=None: [doc])
    assert main(["reproduce", "yuan2021", "--part", "global", "--quick", "--no-progress", "--update-docs"]) == 0
    printed = capsys.readouterr().out
    first, second, third = doc_tables.read_blocks(doc)
    assert first.attrs["seeds"] == "0-2"
    assert first.body == doc_tables.extract_table(printed, "yuan2021_table1", "claims")
    assert "\n".join(first.body) in printed             # the printed text, unchanged
    assert second.body == ["| other runs, left alone |"] and second.attrs["seeds"] == "0-4"
    assert "text between" in doc.read_text()
    # another command that runs the very same runs (the same run keys) is written too
    assert third.attrs["seeds"] == "0-2"
    assert third.body == doc_tables.extract_table(printed, "yuan2021_table2", "claims")
    # a fresh run at the recorded seeds agrees; an edited cell or other seeds do not
    text, seeds = command_reports(first.command, ["yuan2021_table1"])["yuan2021_table1"]
    assert doc_tables.differences(first, text, seeds) == []
    edited = doc_tables.Block(first.path, first.begin, first.end, first.attrs,
                              [*first.body[:2], first.body[2].rstrip(" |") + "x |", *first.body[3:]])
    assert doc_tables.differences(edited, text, seeds)
    assert doc_tables.differences(first, text, [0, 1, 2, 3])


def test_wall_clock_cells_are_not_compared():
    head = ["| compared | ours (95 % interval, p) | verdict | mean step [ms] |", "|---|---|---|---|"]
    a = head + ["| iga vs ga (runtime_s) | +52.5 % | holds | 0.58 |", "| iga vs ga (length) | +3.7 % | holds | 0.6 |"]
    b = head + ["| iga vs ga (runtime_s) | +20.0 % | weaker | 0.91 |", "| iga vs ga (length) | +3.7 % | holds | 1.2 |"]
    assert doc_tables.comparable(a) == doc_tables.comparable(b)
    c = head + ["| iga vs ga (runtime_s) | +20.0 % | weaker | 0.91 |", "| iga vs ga (length) | +3.8 % | holds | 1.2 |"]
    assert doc_tables.comparable(a) != doc_tables.comparable(c)


@pytest.mark.parametrize("command", ["optplan plan map", "optplan reproduce yuan2021 --workers 2",
                                     "optplan bench x --part global", "optplan reproduce yuan2021 --runs many"])
def test_a_marker_command_that_is_not_a_doc_table_command_is_refused(command):
    from optplan.errors import ParameterError

    with pytest.raises(ParameterError):
        doc_tables.parse_command(command)


def test_unclosed_and_unknown_markers_are_errors(tmp_path):
    from optplan.errors import ParameterError

    doc = tmp_path / "x.md"
    doc.write_text('<!-- optplan:table BEGIN command="optplan reproduce yuan2021" spec=s table=claims -->\n| a |\n')
    with pytest.raises(ParameterError, match="without END"):
        doc_tables.read_blocks(doc)
    doc.write_text("<!-- optplan:table END -->\n")
    with pytest.raises(ParameterError, match="without BEGIN"):
        doc_tables.read_blocks(doc)
    with pytest.raises(ParameterError, match="no table under the heading"):
        doc_tables.extract_table("## other\n\n| a |\n", "yuan2021_table1", "claims")
