"""Issue 44: the run metrics added for the statements that had "no metric" (chen2025 Figs 6-7 and
18-20, li2023 Fig 13 and Experiment I), each checked on a case whose value is known by hand."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from optplan.bench.claims import CLAIMS
from optplan.bench.kinds import get_kind
from optplan.bench.kinds.optimize import ERROR_AT_ITERS, OptimizeKind, convergence_metrics
from optplan.bench.kinds.plan import history_metrics
from optplan.bench.kinds.simulate import heading_change_per_m
from optplan.bench.spec import load_spec

NEW_METRICS = {"optimize": ("opt_iter", "f_error_50", "f_error_150"), "plan": ("fitness_final",),
               "simulate": ("heading_change_per_m",)}


def test_opt_iter_is_the_first_iteration_within_the_tolerance():
    # the error falls below 1e-8 first at entry 3 (5e-9), not at entry 2 (1e-7)
    m = convergence_metrics([10.0, 1.0, 1e-7, 5e-9, 0.0], f_opt=0.0)
    assert m["opt_iter"] == 3.0
    # a negative optimum (F8, F17, F18): the distance to it counts, from either side
    assert convergence_metrics([-0.5, -1.0 + 2e-9, -1.0], f_opt=-1.0)["opt_iter"] == 1.0
    # another tolerance moves it
    assert convergence_metrics([10.0, 1.0, 1e-7, 5e-9], f_opt=0.0, tol=1e-6)["opt_iter"] == 2.0


def test_a_run_that_never_reaches_the_optimum_is_censored_past_its_last_iteration():
    m = convergence_metrics([3.0, 2.0, 1.0], f_opt=0.0)
    assert m["opt_iter"] == 3.0       # one past iteration 2, behind every run that got there
    assert convergence_metrics([], f_opt=0.0)["opt_iter"] is None


def test_error_after_k_iterations():
    history = 1.0 + 1.0 / (1.0 + np.arange(501))   # f_opt 1: error 1 / (i + 1) after iteration i
    m = convergence_metrics(history, f_opt=1.0)
    assert ERROR_AT_ITERS == (50, 150)
    assert m["f_error_50"] == pytest.approx(1 / 51) and m["f_error_150"] == pytest.approx(1 / 151)
    # a run of 60 iterations has no iteration 150: its last error, an upper bound on it, is stored
    short = convergence_metrics(history[:61], f_opt=1.0)
    assert short["f_error_50"] == pytest.approx(1 / 51) and short["f_error_150"] == pytest.approx(1 / 61)


def test_an_optimize_run_stores_the_metrics_of_its_own_history():
    rec = SimpleNamespace(target_spec={"function": "F1", "shifted": False, "dim": 5}, seed=3, algorithm="gwo",
                          params={"pop": 10, "iters": 80})
    res, extra = OptimizeKind().run(rec)
    assert len(res.history) == 81
    assert {k: extra[k] for k in NEW_METRICS["optimize"]} == convergence_metrics(res.history, 0.0)
    err = np.abs(res.history)
    assert extra["f_error_50"] == err[50]
    assert extra["f_error_150"] == err[-1] == pytest.approx(extra["f_error"])
    within = np.flatnonzero(err <= 1e-8)
    assert extra["opt_iter"] == (within[0] if len(within) else 81)


def test_fitness_final_is_where_the_convergence_curve_ends():
    m = history_metrics([9.0, 7.0, 5.0, 5.0, 4.5])
    assert m["fitness_final"] == 4.5 and m["convergence_iter"] == 4.0
    assert history_metrics(np.zeros(0)) == {"convergence_iter": None, "fitness_final": None}   # graph search


def test_heading_change_per_metre_of_a_driven_path():
    # straight 1 m, a 90 degree left turn, straight 1 m, a 90 degree right turn: 180 degrees over 2 m
    traj = np.array([[0.0, 0, 0, 0.0, 1, 0],
                     [1.0, 1, 0, 0.0, 1, 0],
                     [2.0, 1, 0, np.pi / 2, 0, 1],
                     [3.0, 1, 1, np.pi / 2, 1, 0],
                     [4.0, 1, 1, 0.0, 0, -1]])
    assert heading_change_per_m(traj, 2.0) == pytest.approx(90.0)
    # a heading that crosses +-pi turns by the short way round (10 degrees, not 350)
    eps = np.radians(5)
    across = np.array([[0.0, 0, 0, np.pi - eps, 1, 0], [1.0, -1, 0, -np.pi + eps, 1, 0]])
    assert heading_change_per_m(across, 1.0) == pytest.approx(10.0)
    # a straight drive does not turn; a robot that never moved has no value
    straight = np.array([[0.0, 0, 0, 0.3, 1, 0], [1.0, 1, 0, 0.3, 1, 0]])
    assert heading_change_per_m(straight, 1.0) == 0.0
    assert heading_change_per_m(straight, 0.0) is None and heading_change_per_m(straight[:1], 1.0) is None


def test_the_kinds_list_the_new_metrics_and_every_claim_names_one_its_spec_stores():
    for kind, names in NEW_METRICS.items():
        assert set(names) <= set(get_kind(kind).metric_names())
    new = [c for c in CLAIMS if c.metric in {n for names in NEW_METRICS.values() for n in names}]
    assert {c.spec for c in new} == {"chen2025_functions", "chen2025_functions_unshifted",
                                     "li2023_global", "li2023_local_exp1"}
    for spec in {c.spec for c in new}:
        kind = get_kind(load_spec(spec).kind)
        assert {c.metric for c in new if c.spec == spec} <= set(kind.metric_names()), spec
