"""Solver faults are reported with their status and handled as documented.

Each fault is injected for real (an iteration cap of 1, an objective that returns
NaN, a run that raises inside a worker), not simulated by mocking the result.
"""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.world.papermaps import paper_map


@pytest.fixture
def starved_ipopt(monkeypatch):
    """IPOPT limited to one iteration: every solve ends in Maximum_Iterations_Exceeded."""
    from optplan.solvers.nlp import smoothing

    for options in (smoothing.IPOPT_OPTIONS, smoothing.IPOPT_WARM_OPTIONS):
        monkeypatch.setitem(options, "max_iter", 1)
    # no cache to clear: the IPOPT options are part of the built solvers' key
    return paper_map("chen2025_20")


def test_ipopt_failure_falls_back_to_the_seed_with_its_status(starved_ipopt):
    world, s, g = starved_ipopt
    seed = op.plan(world, s, g, algorithm="astar")
    res = op.plan(world, s, g, algorithm="astar", refine="casadi")
    assert not res.refined and res.feasible
    np.testing.assert_array_equal(res.path, seed.path)
    assert "Maximum_Iterations_Exceeded" in res.message and "fell back" in res.message


@pytest.fixture
def starved_osqp(monkeypatch):
    from optplan.solvers.qp import program

    monkeypatch.setitem(program.OSQP_SETTINGS, "max_iter", 1)
    monkeypatch.setitem(program.OSQP_SETTINGS, "polishing", False)
    # no cache to clear: the settings are part of the cached set-up's key


def test_osqp_max_iter_falls_back_to_the_seed_with_its_status(starved_osqp):
    world, s, g = paper_map("chen2025_20")
    seed = op.plan(world, s, g, algorithm="astar")
    res = op.plan(world, s, g, algorithm="astar", refine="qp")
    assert not res.refined and res.feasible
    np.testing.assert_array_equal(res.path, seed.path)
    assert "maximum iterations" in res.message.lower()


def test_nan_objective_inside_a_path_planner_is_survived():
    """A formulation that returns NaN for some individuals: they count as worst, the run
    finishes, and the returned path still goes through the exact check. The NaN is injected
    where the swarm reads the program's cost (both the program's own view and the segment
    tables' acceleration go through ``PathProgram.population``), so the acceleration check
    still sees two views that agree."""
    from optplan.formulations.program import PathProgram

    world, s, g = paper_map("chen2025_20")
    original = PathProgram.population
    calls = {"n": 0}

    def flaky(self, X, variables=None):
        f, v = original(self, X, variables)
        calls["n"] += 1
        f = np.array(f, dtype=float)
        f[::3] = np.nan
        return f, v

    try:
        PathProgram.population = flaky
        res = op.plan(world, s, g, algorithm="gwo", seed=0, pop=12, iters=20)
    finally:
        PathProgram.population = original
    assert calls["n"] > 0                      # the fault was really injected
    assert res.feasible == bool(op.validate_path(world, res.path))
    assert np.isfinite(res.length) and "NaN" in res.message


def test_an_exception_inside_a_dask_worker_is_a_failed_run_and_the_rest_continue(tmp_path):
    from distributed import Client, LocalCluster

    from optplan.bench.runner import run_records
    from optplan.bench.spec import load_spec
    from optplan.bench.store import ResultStore

    spec = tmp_path / "faulty.yaml"
    spec.write_text(
        "name: faulty\nkind: plan\nmaps: [chen2025_20]\n"
        "algorithms:\n  - gwo\n  - {name: gwo, label: broken, params: {pop: 1}}\n"
        "params: {pop: 8, iters: 5}\nruns: 3\n"
    )
    records = load_spec(spec).expand()
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        store = ResultStore(tmp_path / "r.sqlite")
        run_records(records, store, executor=client, progress=False)
        rows = store.rows()
        store.close()
    status = sorted(r["status"] for r in rows.values())
    assert status == ["failed"] * 3 + ["ok"] * 3
    assert all("pop" in (r.get("error") or "") for r in rows.values() if r["status"] == "failed")


def test_ipopt_options_per_call_reach_the_smoother_and_leave_the_defaults_alone():
    """refine_options={"ipopt": ...} sets this call's IPOPT options (issue 24: solver settings
    per call, not module globals); the next default call builds from the defaults again."""
    world, s, g = paper_map("chen2025_20")
    starved = op.plan(world, s, g, algorithm="astar", refine="casadi", refine_options={"ipopt": {"max_iter": 1}})
    assert not starved.refined and "Maximum_Iterations_Exceeded" in starved.message
    default = op.plan(world, s, g, algorithm="astar", refine="casadi")
    assert default.refined and default.feasible
    with pytest.raises(op.ParameterError, match="ipopt must be a dict"):
        op.plan(world, s, g, algorithm="astar", refine="casadi", refine_options={"ipopt": 5})


def test_osqp_settings_per_call_reach_the_corridor_qp_and_leave_the_defaults_alone():
    world, s, g = paper_map("chen2025_20")
    starved = op.plan(world, s, g, algorithm="astar", refine="qp",
                      refine_options={"osqp": {"max_iter": 1, "polishing": False}})
    assert not starved.refined and "maximum iterations" in starved.message.lower()
    default = op.plan(world, s, g, algorithm="astar", refine="qp")
    assert default.refined and default.feasible
    with pytest.raises(op.ParameterError, match="osqp must be a dict"):
        op.plan(world, s, g, algorithm="astar", refine="qp", refine_options={"osqp": "fast"})


def test_settings_key_ignores_order_and_separates_values():
    """Cached solvers are keyed by their settings: the same settings in another order must hit
    the same entry, and a changed value must not."""
    from optplan.checks import settings_key
    assert settings_key({"tol": 1e-6, "max_iter": 100}) == settings_key({"max_iter": 100, "tol": 1e-6})
    assert settings_key({"tol": 1e-6}) != settings_key({"tol": 1e-7})
    assert settings_key({"tol": 1e-6}) != settings_key({"tol": 1e-6, "max_iter": 100})
    hash(settings_key({"warm_start": True, "eps_abs": 1e-5}))
