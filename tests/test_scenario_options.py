"""Scenario files and the command line say what the API can (issue 43 item 2):
``planner_params`` per local planner and ``global_options`` in scenario files, ``--params`` on
``optplan plan`` / ``optplan simulate`` and ``--global-params``, checked with the same named
errors as the Python calls."""
from __future__ import annotations

import json

import numpy as np
import pytest

import optplan as op
from optplan.cli import main

BASE = {"map": [[0] * 8 for _ in range(6)], "start": [0.5, 0.5, 0], "goal": [7.0, 5.0], "time_limit": 40}


def _sim(scenario, **kw):
    return op.simulate(op.load_scenario(scenario), global_planner="astar", seed=0, **kw)


def test_a_scenario_files_planner_params_reach_the_local_planner():
    # a 2 x 3 sample grid drives another way: the file's options reach the planner
    slow = _sim({**BASE, "planner_params": {"qp-dwa": {"n_v": 2, "n_w": 3}}}, local_planner="qp-dwa")
    default = _sim(BASE, local_planner="qp-dwa")
    assert not np.array_equal(slow.trajectory, default.trajectory)
    # the caller's planner_params win over the file's
    same = _sim({**BASE, "planner_params": {"qp-dwa": {"n_v": 2, "n_w": 3}}}, local_planner="qp-dwa",
                planner_params={"n_v": 11, "n_w": 21})
    np.testing.assert_array_equal(same.trajectory, default.trajectory)


def test_scenario_options_are_checked_with_named_errors():
    with pytest.raises(op.ParameterError, match="n_vv.*n_v"):
        _sim({**BASE, "planner_params": {"qp-dwa": {"n_vv": 3}}}, local_planner="qp-dwa")
    with pytest.raises(op.ParameterError, match="qp-dwaa.*qp-dwa"):
        _sim({**BASE, "planner_params": {"qp-dwaa": {}}}, local_planner="qp-dwa")
    with pytest.raises(op.ScenarioError, match="planner_params.qp-dwa must be a mapping"):
        op.load_scenario({**BASE, "planner_params": {"qp-dwa": 3}})
    with pytest.raises(op.ScenarioError, match="no .nan"):
        op.load_scenario({**BASE, "global_options": {"clearance": float("nan")}})


def test_a_scenario_files_global_options_reach_the_global_planner():
    block = {**BASE, "map": [[0] * 8 for _ in range(2)] + [[0, 0, 0, 1, 1, 0, 0, 0] for _ in range(2)]
             + [[0] * 8 for _ in range(2)], "start": [1.5, 1.5, 0], "goal": [6.5, 4.5]}
    sc = op.load_scenario({**block, "global_options": {"clearance": 0.45}})
    r = op.simulate(sc, global_planner="visibility", local_planner="dwa", seed=0, time_limit=1)
    plain = op.simulate(op.load_scenario(block), global_planner="visibility", local_planner="dwa", seed=0,
                        time_limit=1)
    P, Q = np.asarray(r.global_path), np.asarray(plain.global_path)
    assert sc.world.segments_clearance(P[:-1], P[1:]).min() >= 0.45 - 1e-9
    assert plain.global_path.shape != r.global_path.shape or not np.allclose(P, Q)
    with pytest.raises(op.ParameterError, match="itrs.*iters"):
        op.simulate(op.load_scenario({**BASE, "global_options": {"itrs": 3}}), global_planner="gwo", seed=0)


def test_params_on_the_command_line(tmp_path, capsys):
    assert main(["plan", "chen2025_20", "--algo", "gwo", "--json", "--params",
                 '{"encoding": "general", "max_evals": 300, "iters": null}']) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["feasible"]
    assert main(["plan", "chen2025_20", "--algo", "gwo", "--params", '{"itrs": 3}']) == 2
    assert "did you mean 'iters'" in capsys.readouterr().err
    assert main(["plan", "chen2025_20", "--algo", "gwo", "--params", "{pop: 3"]) == 2
    assert "one JSON object" in capsys.readouterr().err
    sc = tmp_path / "s.yaml"
    sc.write_text(json.dumps(BASE))
    assert main(["simulate", str(sc), "--local", "qp-dwa", "--params", '{"n_vv": 2}']) == 2
    assert "did you mean 'n_v'" in capsys.readouterr().err
    assert main(["simulate", str(sc), "--global", "gwo", "--global-params", '{"pop": 6, "iters": 5}',
                 "--json"]) in (0, 1)
