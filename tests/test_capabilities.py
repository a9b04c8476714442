"""Planner capabilities are declared once, by each planner, and they are true: the grid-only
planners refuse circle worlds (and op.algorithms(world) leaves them out), the deterministic
ones ignore the seed, the stochastic ones depend on it, and 'alternatives' is accepted exactly
by the planners that declare it."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import optplan as op
from optplan.planning import global_planner_names
from optplan.solvers.catalog import planner_capabilities, planner_kind, planner_options

GRID = op.GridMap.from_rows([[0] * 8 for _ in range(6)])
CIRCLES = op.CircleWorld(bounds=(0, 0, 8, 6), circles=[(4.0, 3.0, 1.0)])


@pytest.mark.parametrize("name", global_planner_names())
def test_every_planner_declares_what_the_checks_use(name):
    caps = planner_capabilities(name)
    assert caps.name == name and caps.kind == planner_kind(name, GRID)
    assert ("alternatives" in planner_options(name, GRID)) == caps.alternatives
    assert caps.runs_on(GRID)
    assert caps.runs_on(CIRCLES) == (caps.grid_only is None)


@pytest.mark.parametrize("name", [n for n in global_planner_names() if planner_capabilities(n).grid_only])
def test_grid_only_planners_refuse_circle_worlds_and_are_not_offered_there(name):
    with pytest.raises(op.ParameterError, match="needs a grid map"):
        op.plan(CIRCLES, (0.5, 0.5), (7.5, 5.5), algorithm=name)
    assert name not in op.algorithms(CIRCLES) and name in op.algorithms(GRID)


def test_the_seed_matters_exactly_for_the_stochastic_planners():
    world = op.load_map("chen2025_20")
    s, g = (0.5, 0.5), (19.5, 19.5)
    for name in ("astar", "visibility", "pso", "aco"):
        a = op.plan(world, s, g, algorithm=name, seed=0, pop=8, iters=10) if planner_capabilities(name).stochastic \
            else op.plan(world, s, g, algorithm=name, seed=0)
        b = op.plan(world, s, g, algorithm=name, seed=1, pop=8, iters=10) if planner_capabilities(name).stochastic \
            else op.plan(world, s, g, algorithm=name, seed=1)
        same = a.path.shape == b.path.shape and np.array_equal(a.path, b.path) and np.array_equal(a.history, b.history)
        assert same != planner_capabilities(name).stochastic, name


def test_unknown_planner_has_no_capabilities():
    with pytest.raises(op.UnknownAlgorithmError):
        planner_capabilities("nope")


def test_cli_lists_the_capabilities():
    out = subprocess.run([sys.executable, "-m", "optplan", "algorithms", "--details"], capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    lines = dict(line.split(None, 1) for line in out.stdout.splitlines())
    assert lines["astar"].strip() == "graph, grid only, deterministic, exact"
    assert lines["dwa"].strip() == "local planner" and set(lines) == set(op.algorithms())


def test_a_spec_pairing_a_grid_only_planner_with_a_circle_world_is_refused_at_load(tmp_path):
    from optplan.bench.spec import load_spec

    spec = tmp_path / "cw.yaml"
    spec.write_text("name: cw\nkind: plan\nmaps: [yang2023_env1]\nalgorithms: [pso, aco]\nruns: 1\n")
    with pytest.raises(op.ScenarioError, match="'aco' needs a grid map.*circle world"):
        load_spec(spec)
    spec.write_text("name: cw\nkind: plan\nmaps: [yang2023_env1]\nalgorithms: [pso, visibility]\nruns: 1\n")
    assert len(load_spec(spec).expand()) == 2
