"""Results tables in the docs that the commands write, so they cannot go stale.

A results table in ``README.md`` or ``docs/fidelity/*.md`` sits between two markers::

    <!-- optplan:table BEGIN command="optplan reproduce yuan2021 --part global" spec=yuan2021_table1 table=claims seeds=0-19 -->
    | source | claim | ... |
    <!-- optplan:table END -->

* ``command`` — the command that prints the table: ``optplan reproduce PAPER [--part P]
  [--runs N] [--quick]`` or ``optplan bench SPEC [--runs N] [--quick]``;
* ``spec`` — the shipped spec whose report holds it;
* ``table`` — which table of that report: ``claims`` (the paper's claims judged, ``## Claims of
  the paper (SPEC)``) or the text of the heading the table follows;
* ``seeds`` — the seeds the command ran (written by the command, checked by the tests).

Between the markers is the table exactly as the command prints it (its ``|`` lines).
``optplan reproduce PAPER ... --update-docs`` rewrites every block whose spec it ran with the
very runs the block's command runs (the same run keys: seeds, budgets, files); ``tests/test_doc_tables.py`` runs each block's command at its
seeds and fails when the committed table differs. Cells measured on the wall clock
(:data:`WALL_CLOCK_COLUMNS`; the figure and verdict of a claim about run time,
:data:`WALL_CLOCK_ROW_MARKS`) are written but not compared.
"""
from __future__ import annotations

import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import ParameterError

ROOT = Path(__file__).resolve().parents[2]
BEGIN = "<!-- optplan:table BEGIN"
END = "<!-- optplan:table END -->"
_ATTR = re.compile(r'(\w+)=("([^"]*)"|\S+)')
CLAIMS = "claims"
# a column whose header holds one of these is a wall-clock measurement (not compared): a
# planner's run time, a control step's time (a closed loop's "mean time [s]" is simulated time)
WALL_CLOCK_COLUMNS = ("runtime", "[ms]")
# a row holding one of these compares wall times (a planner's run time, the time of an answer to a
# blocked path): its RESULT_COLUMNS are not compared
WALL_CLOCK_ROW_MARKS = ("(runtime_s)", "(reroute_s)")
RESULT_COLUMNS = ("ours (95 % interval, p)", "verdict")


def doc_files(root: Path | None = None) -> list[Path]:
    """The files whose marked tables the commands write: README.md and docs/fidelity/*.md."""
    root = Path(root) if root is not None else ROOT
    return [p for p in [root / "README.md", *sorted((root / "docs" / "fidelity").glob("*.md"))] if p.is_file()]


@dataclass(frozen=True)
class Invocation:
    """What a doc table's command runs: ``kind`` ``reproduce`` (``name`` a paper) or ``bench``
    (``name`` a spec), with its ``part``, ``runs`` and ``quick``."""

    kind: str
    name: str
    part: str | None = None
    runs: int | None = None
    quick: bool = False


def parse_command(command: str) -> Invocation:
    """The :class:`Invocation` of ``optplan reproduce ...`` / ``optplan bench ...`` (only the options
    that change what runs are allowed: ``--part``, ``--runs``, ``--quick``)."""
    words = shlex.split(command)
    if len(words) < 3 or words[0] != "optplan" or words[1] not in ("reproduce", "bench"):
        raise ParameterError(f"a doc table's command must be 'optplan reproduce PAPER ...' or 'optplan bench SPEC "
                             f"...', got {command!r}")
    kind, name, rest = words[1], words[2], words[3:]
    part, runs, quick = None, None, False
    i = 0
    while i < len(rest):
        w = rest[i]
        if w == "--quick":
            quick = True
        elif w in ("--part", "--runs") and i + 1 < len(rest) and not (w == "--part" and kind == "bench"):
            if w == "--part":
                part = rest[i + 1]
            else:
                try:
                    runs = int(rest[i + 1])
                except ValueError:
                    raise ParameterError(f"--runs takes a number in {command!r}") from None
            i += 1
        else:
            raise ParameterError(f"a doc table's command may use only --part (reproduce), --runs and --quick; "
                                 f"{w!r} in {command!r}")
        i += 1
    return Invocation(kind, name, part, runs, quick)


def seeds_text(seeds) -> str:
    """``0-19`` for a run of consecutive seeds, else ``3,5,8``."""
    seeds = [int(s) for s in seeds]
    if len(seeds) > 1 and seeds == list(range(seeds[0], seeds[-1] + 1)):
        return f"{seeds[0]}-{seeds[-1]}"
    return ",".join(map(str, seeds))


@dataclass
class Block:
    """One marked table: where it is, its marker's attributes and the lines between the markers."""

    path: Path
    begin: int          # index of the BEGIN line
    end: int            # index of the END line
    attrs: dict
    body: list[str] = field(default_factory=list)

    @property
    def command(self) -> str:
        return self.attrs["command"]

    @property
    def spec(self) -> str:
        return self.attrs["spec"]

    @property
    def table(self) -> str:
        return self.attrs["table"]

    @property
    def invocation(self) -> Invocation:
        return parse_command(self.command)

    def where(self) -> str:
        return f"{self.path.name}:{self.begin + 1} ({self.spec}, {self.table})"


def _marker(attrs: dict) -> str:
    def value(v: str) -> str:
        return f'"{v}"' if (not v or re.search(r"\s", v)) else v

    return f"{BEGIN} " + " ".join(f"{k}={value(str(attrs[k]))}" for k in ("command", "spec", "table", "seeds")
                                  if k in attrs) + " -->"


def read_blocks(path: Path) -> list[Block]:
    """The marked tables of one file (an unclosed or incomplete marker is an error)."""
    lines = Path(path).read_text().splitlines()
    blocks, open_block = [], None
    for i, line in enumerate(lines):
        s = line.strip()
        if s.startswith(BEGIN):
            if open_block is not None:
                raise ParameterError(f"{path}:{i + 1}: a table BEGIN marker inside the block opened at line "
                                     f"{open_block.begin + 1}")
            attrs = {m.group(1): (m.group(3) if m.group(3) is not None else m.group(2))
                     for m in _ATTR.finditer(s[len(BEGIN):].removesuffix("-->"))}
            missing = [k for k in ("command", "spec", "table") if k not in attrs]
            if missing:
                raise ParameterError(f"{path}:{i + 1}: table marker without {', '.join(missing)}")
            parse_command(attrs["command"])
            open_block = Block(Path(path), i, -1, attrs)
        elif s == END:
            if open_block is None:
                raise ParameterError(f"{path}:{i + 1}: table END marker without BEGIN")
            open_block.end = i
            open_block.body = lines[open_block.begin + 1:i]
            blocks.append(open_block)
            open_block = None
    if open_block is not None:
        raise ParameterError(f"{path}:{open_block.begin + 1}: table BEGIN marker without END")
    return blocks


def find_blocks(paths=None) -> list[Block]:
    """Every marked table of ``paths`` (default :func:`doc_files`)."""
    return [b for p in (doc_files() if paths is None else paths) for b in read_blocks(p)]


def _heading(table: str, spec: str) -> str:
    return f"Claims of the paper ({spec})" if table == CLAIMS else table


def extract_table(report: str, spec: str, table: str) -> list[str]:
    """The ``|`` lines of the first table after the heading ``table`` names in ``report`` (the text
    the command prints for ``spec``), before the next heading."""
    want = _heading(table, spec)
    lines = report.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("#") and line.lstrip("#").strip() == want:
            rows = []
            for ln in lines[i + 1:]:
                if ln.startswith("#"):
                    break
                if ln.startswith("|"):
                    rows.append(ln)
                elif rows:
                    break
            if rows:
                return rows
            break
    raise ParameterError(f"{spec}'s report has no table under the heading {want!r}")


def _cells(line: str) -> list[str]:
    return [c.strip() for c in line.strip().strip("|").split("|")]


def comparable(rows: list[str]) -> list[list[str]]:
    """The cells of a table with its wall-clock cells blanked (``~``)."""
    if not rows:
        return []
    head = _cells(rows[0])
    masked_cols = {j for j, h in enumerate(head) if any(w in h for w in WALL_CLOCK_COLUMNS)}
    result_cols = {j for j, h in enumerate(head) if h in RESULT_COLUMNS}
    out = []
    for k, line in enumerate(rows):
        cells = _cells(line)
        blank = set(masked_cols)
        if k >= 2 and any(m in c for m in WALL_CLOCK_ROW_MARKS for c in cells):
            blank |= result_cols
        out.append([("~" if j in blank and k >= 2 else c) for j, c in enumerate(cells)])
    return out


def differences(block: Block, report: str, seeds) -> list[str]:
    """How ``block`` differs from ``report``, the text its command printed now at ``seeds``
    (empty: the committed table is current; wall-clock cells are not compared)."""
    out = []
    recorded = block.attrs.get("seeds")
    if recorded != seeds_text(seeds):
        out.append(f"{block.where()}: recorded seeds {recorded}, the command runs {seeds_text(seeds)}")
    fresh = comparable(extract_table(report, block.spec, block.table))
    old = comparable([ln for ln in block.body if ln.strip()])
    if len(fresh) != len(old):
        out.append(f"{block.where()}: {len(old)} committed lines, {len(fresh)} printed")
    for a, b in zip(old, fresh):
        if a != b:
            out.append(f"{block.where()}:\n  committed: | {' | '.join(a)} |\n  printed:   | {' | '.join(b)} |")
    return out


def write_tables(blocks: list[Block], reports: dict[str, str], seeds: dict[str, list[int]]) -> None:
    """Rewrite ``blocks`` in place with their tables from ``reports`` (the text the command printed
    per spec) and the ``seeds`` it ran per spec."""
    by_path: dict[Path, list[Block]] = {}
    for b in blocks:
        by_path.setdefault(b.path, []).append(b)
    for path, bs in by_path.items():
        lines = Path(path).read_text().splitlines()
        for b in sorted(bs, key=lambda b: -b.begin):   # bottom up: earlier indices stay valid
            table = extract_table(reports[b.spec], b.spec, b.table)
            lines[b.begin:b.end + 1] = [_marker({**b.attrs, "seeds": seeds_text(seeds[b.spec])}), *table, END]
        Path(path).write_text("\n".join(lines) + "\n")
