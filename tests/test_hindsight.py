"""Hindsight profiles: the earliest contact-free arrival along a path with the movers' future known."""
from __future__ import annotations

import numpy as np
import pytest

from optplan.errors import ParameterError
from optplan.sim.hindsight import hindsight_profile
from optplan.world.scenario import load_scenario

ROBOT = {"radius": 0.2, "v_max": 1.0, "a_max": 0.2}
PATH = np.array([[0.5, 3.0], [11.5, 3.0]])
# from rest at 0.2 m/s^2: 50 periods of 0.1 s to 1 m/s over 2.5 m, then 8.2 m at 1 m/s to the
# goal tolerance (11 m - 0.3 m): 132 periods
FREE_ARRIVAL = 13.2


def corridor(*movers):
    return load_scenario({"map": [[0] * 12 for _ in range(6)], "start": [0.5, 3.0, 0], "goal": [11.5, 3.0],
                          "robot": ROBOT, "dynamic_obstacles": list(movers), "time_limit": 60})


def test_without_movers_the_arrival_is_the_bang_bang_time():
    prof = hindsight_profile(corridor(), PATH)
    assert prof.feasible and prof.time_s == pytest.approx(FREE_ARRIVAL)
    assert prof.path_length == pytest.approx(11.0)


def test_a_mover_crossing_where_the_free_run_would_be_delays_the_arrival():
    # the free run passes x = 5.5 at t = 7.5 s; this mover crosses the path there and then
    mover = {"radius": 0.3, "start": [5.5, 3.0 + 0.3 * 7.5], "velocity": [0.0, -0.3], "at_border": "pass"}
    prof = hindsight_profile(corridor(mover), PATH)
    assert prof.feasible
    assert FREE_ARRIVAL + 0.5 < prof.time_s < FREE_ARRIVAL + 10  # (15.2 s: it waits)
    # more clearance never makes it earlier
    assert hindsight_profile(corridor(mover), PATH, margin=0.3).time_s >= prof.time_s


def test_a_mover_driving_down_the_path_towards_the_robot_cannot_be_avoided_forward_only():
    mover = {"radius": 0.3, "start": [11.0, 3.0], "velocity": [-0.3, 0.0], "at_border": "pass"}
    prof = hindsight_profile(corridor(mover), PATH)
    assert not prof.feasible and prof.time_s is None


def test_bad_paths_and_margins_are_refused():
    sc = corridor()
    with pytest.raises(ParameterError, match="path"):
        hindsight_profile(sc, [[0.5, 3.0]])
    with pytest.raises(ParameterError, match="margin"):
        hindsight_profile(sc, PATH, margin=-0.1)


def test_the_benchmark_counts_a_stored_failure_in_an_avoidable_world(tmp_path, capsys):
    """``benchmarks/closed_loop_hindsight.py --db``: a stored failed run whose world has a
    hindsight profile is counted as an avoidable failure, a stored success is not."""
    import importlib.util
    from pathlib import Path

    from optplan.bench.spec import load_spec
    from optplan.bench.store import ResultStore

    script = Path(__file__).parents[1] / "benchmarks" / "closed_loop_hindsight.py"
    spec = importlib.util.spec_from_file_location("closed_loop_hindsight", script)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    recs = load_spec({"kind": "simulate", "scenarios": ["yang2023_idwa_crossing"], "algorithms": ["astar"],
                      "local_planners": ["dwa", "qp-dwa"], "runs": 1}).expand()
    db = tmp_path / "runs.sqlite"
    store = ResultStore(db)
    for r in recs:
        won = r.local_planner == "qp-dwa"
        store.write(r.to_dict(), {"status": "ok", "metrics": {"success": int(won), "time_s": 31.0}})
    store.conn.close()
    assert bench.main(["yang2023_idwa_crossing", "--seeds", "0", "1", "--workers", "1", "--db", str(db)]) == 0
    out = capsys.readouterr().out
    assert "| yang2023_idwa_crossing | 1 | 1 |" in out
    row = {line.split("|")[1].strip(): line for line in out.splitlines() if line.startswith("| ")}
    assert row["dwa"].split("|")[2:6] == [" 1 ", " 0 ", " 1 ", " 1 "]
    assert row["qp-dwa"].split("|")[2:6] == [" 1 ", " 1 ", " 0 ", " 0 "]
