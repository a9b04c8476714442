"""Property-based fuzzing of the scenario parser: any input gives a Scenario or one
OptplanError (ScenarioError for the file's content), never another exception."""
from __future__ import annotations

import copy

import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import optplan as op

VALID = {
    "map": [[0, 0, 0, 0, 0], [0, 1, 1, 0, 0], [0, 0, 0, 0, 0], [0, 0, 0, 1, 0], [0, 0, 0, 0, 0]],
    "resolution": 1.0,
    "robot": {"model": "unicycle", "radius": 0.2, "v_max": 1.0, "w_max_deg": 30, "a_max": 0.3,
              "alpha_max_deg": 50, "jerk_max": None},
    "start": [0.5, 0.5, 45],
    "goal": [4.5, 4.5],
    "sensor_range": 3.0,
    "dt": 0.1,
    "time_limit": 60,
    "unknown_obstacles": [{"cells": [[2, 4]]}, {"circle": [3.5, 1.5, 0.3]}],
    "dynamic_obstacles": [{"radius": 0.3, "waypoints": [[1, 2.5], [4, 2.5]], "speed": 0.5, "loop": True},
                          {"radius": 0.2, "start": [4.5, 0.5], "velocity": [-0.3, 0.0]}],
}

HOSTILE = st.one_of(
    st.none(), st.booleans(), st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=8), st.lists(st.floats(allow_nan=True), max_size=4),
    st.dictionaries(st.text(max_size=5), st.integers(), max_size=3),
)


def _paths(d, prefix=()):
    """Every key path into the nested mapping/list structure."""
    if isinstance(d, dict):
        for k, v in d.items():
            yield prefix + (k,)
            yield from _paths(v, prefix + (k,))
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield prefix + (i,)
            yield from _paths(v, prefix + (i,))


PATHS = list(_paths(VALID))
FUZZ = settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _load(data):
    try:
        sc = op.load_scenario(data)
    except op.OptplanError as exc:
        assert str(exc)
        return None
    assert sc.dt > 0 and sc.time_limit > 0 and sc.robot.radius > 0
    return sc


def test_the_valid_scenario_loads():
    assert _load(copy.deepcopy(VALID)) is not None


@FUZZ
@given(edits=st.lists(st.tuples(st.sampled_from(PATHS), HOSTILE, st.booleans()), min_size=1, max_size=3))
def test_mutated_scenarios_load_or_raise_an_optplan_error(edits):
    data = copy.deepcopy(VALID)
    for path, value, delete in edits:
        parent = data
        try:
            for k in path[:-1]:
                parent = parent[k]
            if delete and isinstance(parent, dict):
                parent.pop(path[-1], None)
            else:
                parent[path[-1]] = value
        except (KeyError, IndexError, TypeError):
            continue  # an earlier edit removed or replaced this branch
    _load(data)


@FUZZ
@given(text=st.text(max_size=300))
def test_random_yaml_text_loads_or_raises_an_optplan_error(tmp_path_factory, text):
    p = tmp_path_factory.mktemp("fz") / "s.yaml"
    p.write_text(text)
    _load(p)


@FUZZ
@given(extra=st.dictionaries(st.text(min_size=1, max_size=8), HOSTILE, min_size=1, max_size=2))
def test_unknown_keys_are_refused(extra):
    data = {**copy.deepcopy(VALID), **{f"x_{k}": v for k, v in extra.items()}}
    try:
        op.load_scenario(data)
    except op.ScenarioError as exc:
        assert "x_" in str(exc)
    else:
        raise AssertionError("an unknown key was accepted")


def test_yaml_round_trip_of_the_valid_scenario(tmp_path):
    p = tmp_path / "ok.yaml"
    p.write_text(yaml.safe_dump(VALID))
    assert _load(p) is not None
