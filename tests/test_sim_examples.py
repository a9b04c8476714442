"""The paper scripts' --part local run in their --quick form and print a row for every preset asked."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

CASES = [
    ("hou2024_missa_dwa.py", ["| hou2024_table4_1 | dwa | 1 |", "| hou2024_table4_1 | missa-dwa | 1 |"]),
    ("yang2023_ipso_idwa.py", ["| yang2023_idwa_crossing | dwa | 1 |", "| yang2023_idwa_crossing | idwa | 1 |"]),
    ("yuan2021_iba_dwa.py", ["| yuan2021_path_switch | ba-dwa | 1 |", "mean path switches"]),
    ("li2023_iga_idwa.py", ["| li2023_exp1 | dwa | 1 |", "| li2023_exp1 | iga-dwa | 1 |"]),
]


@pytest.mark.parametrize("script,needles", CASES, ids=[c[0] for c in CASES])
def test_quick_local_part_prints_its_table(tmp_path, script, needles):
    cmd = [sys.executable, str(EXAMPLES / script), "--part", "local", "--quick"]
    if script.startswith("li2023"):
        cmd += ["--gif", str(tmp_path / "run.gif")]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    for n in needles:
        assert n in proc.stdout
    assert "success [%]" in proc.stdout and "not run" not in proc.stdout
    if script.startswith("li2023"):
        assert (tmp_path / "run.gif").read_bytes()[:3] == b"GIF"
