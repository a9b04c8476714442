"""Declared dependency floors: each is a version the code works with (the floor job,
``.ci/floors``, installs exactly these and runs the demo and a qp-dwa simulation), and CI runs
that job after the README's test command."""
from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.version import Version

ROOT = Path(__file__).resolve().parents[1]

# the oldest releases found to work, and why the one before does not (see pyproject.toml)
KNOWN_FLOORS = {
    "casadi": "3.6.1",    # 3.6.0's Linux wheel: no libgfortran, IPOPT does not load
    "osqp": "1.0.3",      # 0.6.x: no 'polishing' setting; 1.0.0 / 1.0.1: no osqp.SolverStatus
    "ruckig": "0.12.1",   # 0.9.2: raises on qp-dwa's unlimited jerk
}


def _project() -> dict:
    if sys.version_info < (3, 11):
        pytest.skip("tomllib needs Python 3.11")
    import tomllib

    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def test_every_dependency_declares_one_floor_and_none_is_known_broken():
    floors = {}
    for dep in _project()["dependencies"]:
        req = Requirement(dep)
        specs = list(req.specifier)
        assert len(specs) == 1 and specs[0].operator == ">=", f"{dep}: the floor job needs exactly one '>=' floor"
        floors[req.name.lower()] = Version(specs[0].version)
    for name, first_working in KNOWN_FLOORS.items():
        assert floors[name] >= Version(first_working), f"{name} >= {floors[name]} allows a version that fails"


def test_no_extra_pulls_mealpy():
    # mealpy 3.0.3 requires numpy <= 1.26.0: installing it downgrades numpy and breaks cvxpy
    for extra, deps in _project().get("optional-dependencies", {}).items():
        assert not any(Requirement(d).name.lower() == "mealpy" for d in deps), f"extra {extra!r} pulls mealpy"


def test_ci_runs_the_readme_test_command_then_the_floor_job():
    readme_command = re.search(r"^(python3 -m venv .*python -m pytest -q)$", (ROOT / "README.md").read_text(), re.M)
    assert readme_command
    lines = (ROOT / ".ci" / "run").read_text().splitlines()
    tests = lines.index(readme_command.group(1))
    floors = next(i for i, ln in enumerate(lines) if ln.strip() == "bash .ci/floors")
    assert tests < floors
    assert (ROOT / ".ci" / "floors").is_file()
