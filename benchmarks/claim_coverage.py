"""How many of the papers' quantitative statements are judged by a claim (issue 44).

    python benchmarks/claim_coverage.py                    # the coverage table, per paper (markdown)
    python benchmarks/claim_coverage.py --unjudged li2023  # a paper's statements no claim judges, and why
    python benchmarks/claim_coverage.py --reasons          # what each reason means
    python benchmarks/claim_coverage.py --list             # every statement: id, where, claims or reason
    python benchmarks/claim_coverage.py --update-docs      # rewrite the marked tables of docs/fidelity

The statements and what judges them are optplan/bench/claim_inventory.py; the claims and their
verdicts optplan/bench/claims.py (computed from runs by ``optplan reproduce PAPER``). Nothing is
run here: the table counts statements, not verdicts.
"""
from __future__ import annotations

import sys

from optplan.bench.claim_inventory import render

if __name__ == "__main__":
    print(render(sys.argv[1:]))
