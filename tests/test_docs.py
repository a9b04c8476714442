"""The newcomer path: every public function and class documents itself, and the command
line shows an example in each subcommand's help."""
from __future__ import annotations

import importlib
import inspect
import pkgutil

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
