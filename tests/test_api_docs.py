"""docs/api.md is generated from the docstrings and must be current; docs/ holds what a user
needs without the shared design notes."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_api_reference_is_current():
    sys.path.insert(0, str(ROOT / "docs"))
    import make_api

    assert (ROOT / "docs" / "api.md").read_text() == make_api.render(), \
        "docs/api.md is out of date; run: python docs/make_api.py"


def test_api_reference_lists_every_public_name():
    import optplan as op

    text = (ROOT / "docs" / "api.md").read_text()
    missing = [n for n in op.__all__ if f"### `op.{n}" not in text]
    assert not missing, missing


def test_docs_cite_the_five_papers_in_full_and_link_nothing_outside_the_repository():
    refs = (ROOT / "docs" / "references.md").read_text()
    for doi in ("10.3390/act13010024", "10.3390/s21134389", "10.3390/su15054656", "10.3390/s25030892"):
        assert doi in refs
    assert "Improved Particle Swarm Optimization and Improved Dynamic Window Approach" in refs
    for page in ("README.md", "docs/design.md", "docs/references.md", "docs/architecture.md"):
        text = (ROOT / page).read_text()
        assert "../shared" not in text, f"{page} links outside the repository"
        for link in re.findall(r"\]\(([^)#]+)\)", text):
            if not link.startswith(("http://", "https://")):
                assert (ROOT / page).parent.joinpath(link).exists(), f"{page}: broken link {link}"


def test_the_generator_check_mode_agrees(tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "docs" / "make_api.py"), "--check"], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr


def test_the_type_stub_lists_every_lazy_name():
    sys.path.insert(0, str(ROOT / "docs"))
    import make_stub

    assert (ROOT / "optplan" / "__init__.pyi").read_text() == make_stub.render(), \
        "optplan/__init__.pyi is out of date; run: python docs/make_stub.py"
    assert (ROOT / "optplan" / "py.typed").is_file()
