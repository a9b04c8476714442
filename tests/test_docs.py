"""The newcomer path: every public function and class documents itself, and the command
line shows an example in each subcommand's help."""
from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import optplan
from optplan.cli import build_parser


def _public_objects():
    for info in pkgutil.walk_packages(optplan.__path__, "optplan."):
        if info.name.endswith("__main__"):
            continue  # running it is the command line
        module = importlib.import_module(info.name)
        yield info.name, "<module>", module
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
                continue
            if inspect.isfunction(obj) or inspect.isclass(obj):
                yield info.name, name, obj


def test_every_public_module_function_and_class_has_a_docstring():
    missing = [f"{mod}.{name}" for mod, name, obj in _public_objects() if not inspect.getdoc(obj)]
    assert not missing, f"undocumented: {missing}"


UNITS = ("metre", "second", "m/s", "rad", "deg", " m)", " m,", "m]")


@pytest.mark.parametrize("name", ["plan", "shortest_path", "simulate", "load_scenario", "validate_path",
                                  "path_metrics", "CircleWorld", "GridMap", "RobotSpec"])
def test_public_api_docstrings_state_units(name):
    doc = inspect.getdoc(getattr(optplan, name)) or ""
    assert any(u in doc for u in UNITS), f"op.{name}'s docstring names no unit"


def test_every_subcommand_help_shows_an_example():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    assert {"plan", "simulate", "bench", "reproduce", "algorithms", "demo"} <= set(sub.choices)
    for name, p in sub.choices.items():
        assert "example" in p.format_help().lower(), f"'optplan {name} --help' shows no example"


README = Path(__file__).resolve().parents[1] / "README.md"


def _readme_python_blocks() -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", README.read_text(), re.S | re.M)


@pytest.mark.parametrize("index", range(len(_readme_python_blocks())))
def test_every_python_snippet_of_the_readme_runs(index, tmp_path, monkeypatch):
    # each block on its own, in a fresh namespace: a snippet that leans on names it never
    # defines fails here, as it would for a reader who pastes it
    monkeypatch.chdir(tmp_path)
    code = _readme_python_blocks()[index]
    exec(compile(code, f"README.md python block {index}", "exec"), {"__name__": "__readme__"})


def test_the_readme_s_featured_simulation_reaches_its_goal(capsys):
    import json

    from optplan.cli import main

    lines = [ln.strip() for ln in README.read_text().splitlines() if ln.startswith("    optplan simulate ")]
    assert lines, "the README features no simulate command"
    argv = re.sub(r"\[[^]]*\]", "", lines[0]).split()[1:]   # drop the optional [--json] [--gif ...]
    assert main(argv + ["--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["reached"] is True and out["collisions"] == 0 and out["status"] == "reached"


def test_the_readme_links_only_what_a_clone_has_and_cites_the_papers():
    text = README.read_text()
    root = README.parent
    for target in re.findall(r"\]\(([^)#][^)]*)\)", text):
        if not target.startswith(("http://", "https://")):
            assert (root / target).exists(), f"README links {target}, which the repository does not have"
    assert "../shared" not in text
    refs = " ".join(text.split("## References", 1)[-1].split())   # titles may wrap
    for paper in ("MSIAR-GWO", "Improved Sparrow Search Algorithm", "Improved Genetic Algorithm",
                  "Improved Particle Swarm Optimization", "Improved Bat Algorithm"):
        assert paper in refs
