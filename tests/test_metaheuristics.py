"""The engine, every algorithm, and each paper mechanism doing what its equation says."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.formulations.functions import get_function
from optplan.solvers.metaheuristics import algorithm_names, get_algorithm
from optplan.solvers.metaheuristics.engine import Problem, State
from optplan.solvers.metaheuristics.gwo import GWO, MSIARGWO
from optplan.solvers.metaheuristics.operators import levy, logistic_tent

ALGOS = [a for a in algorithm_names()]
IMPROVED = ["missa", "ipso", "iba", "msiar-gwo"]
SPHERE = get_function("F1", shifted=True)


def random_median(F, evals: int, runs: int = 11) -> float:
    return float(np.median([op.optimize(F, F.bounds, algorithm="random", pop=30, iters=None, max_evals=evals,
                                        seed=s).f for s in range(runs)]))


@pytest.mark.parametrize("algo", ALGOS)
def test_same_seed_same_result(algo):
    F = get_function("F9", shifted=True, dim=5)
    a = op.optimize(F, F.bounds, algorithm=algo, pop=12, iters=30, seed=4)
    b = op.optimize(F, F.bounds, algorithm=algo, pop=12, iters=30, seed=4)
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.history, b.history)
    assert a.f == F(a.x[None])[0]


@pytest.mark.parametrize("algo", ALGOS)
def test_evaluation_budget_is_exact(algo):
    calls = []

    def f(X):
        calls.append(len(X))
        return (X ** 2).sum(1)

    r = op.optimize(f, [(-5, 5)] * 4, algorithm=algo, pop=10, iters=None, max_evals=537, seed=0)
    assert r.nfev == sum(calls) == 537 and r.status == "max_evals"
    assert np.all(np.diff(r.history) <= 0) and r.history_nfev[-1] == 537


@pytest.mark.parametrize("algo", [a for a in ALGOS if a != "random"])
def test_beats_random_search_on_shifted_sphere(algo):
    """Every algorithm must clearly beat random search at the same budget (15,000 evaluations).
    The issue's 1000x target is measured, not asserted: see benchmarks/shifted_sphere.py."""
    med = random_median(SPHERE, 15000, runs=5)
    r = op.optimize(SPHERE, SPHERE.bounds, algorithm=algo, pop=30, iters=None, max_evals=15000, seed=1)
    assert r.f < med


@pytest.mark.parametrize("runs,needed", [(5, 4), pytest.param(20, 18, marks=pytest.mark.slow)])
@pytest.mark.parametrize("fname", ["F15", "F16"])
@pytest.mark.parametrize("algo", IMPROVED)
def test_improved_variants_reach_fixed_dim_optima(fname, algo, runs, needed):
    """Issue 3: within 1e-3 of the optimum in >= 18 of 20 runs (CI runs 5 and needs 4)."""
    F = get_function(fname)
    hits = sum(abs(op.optimize(F, F.bounds, algorithm=algo, pop=30, iters=500, seed=s).f - F.f_opt) < 1e-3
               for s in range(runs))
    assert hits >= needed


def test_logistic_tent_stays_in_unit_interval_and_covers_it():
    x = logistic_tent(np.random.default_rng(0), (200, 50))
    assert x.min() >= 0 and x.max() < 1
    hist, _ = np.histogram(x, bins=10, range=(0, 1))
    assert hist.min() > 0.03 * x.size  # every tenth of [0, 1) is visited


def test_levy_steps_are_heavy_tailed():
    s = levy(np.random.default_rng(1), 200_000, beta=1.5, scale=1.0)
    g = np.random.default_rng(1).normal(size=200_000) * s.std()
    # far more extreme steps than a normal with the same spread
    assert (np.abs(s) > 10 * np.median(np.abs(s))).mean() > 20 * (np.abs(g) > 10 * np.median(np.abs(g))).mean()


def _state(n=20, d=3, it=0, iters=100, seed=0):
    st = State(Problem(lambda X: (X ** 2).sum(1), np.full(d, -5.0), np.full(d, 5.0)), n, iters, None,
               np.random.default_rng(seed))
    st.it = it
    return st


def test_iba_weight_decreases_logarithmically():
    iba = get_algorithm("iba")(noise_factor=0.0)
    T = 100
    ws = []
    for t in (1, 10, 100):
        st = _state(it=t, iters=T)
        ws.append(iba.inertia(st))
    # w(t) = w_max - (w_max - w_min) log_T(t): 0.9 at t=1, midway at t=sqrt(T)=10, w_min at T
    assert ws == pytest.approx([0.9, 0.65, 0.4])


def test_msiar_convergence_factor_runs_from_initial_to_final():
    m = MSIARGWO()
    st = _state(iters=200)
    values = []
    for t in range(0, 201, 20):
        st.it = t
        values.append(m.convergence_factor(st))
    assert values[0] == pytest.approx(m.a_initial) and values[-1] == pytest.approx(m.a_final)
    assert np.all(np.diff(values) <= 1e-12)
    g = GWO()
    st.it = 100
    assert g.convergence_factor(st) == pytest.approx(1.0)  # linear midpoint for the canonical GWO


def test_msiar_leader_weights_favour_alpha_and_sum_to_one():
    m = MSIARGWO()
    m.leader_f = np.array([1.0, 2.0, 4.0])
    w = m.leader_weights()
    assert w.sum() == pytest.approx(1.0) and w[0] > w[1] > w[2]
    assert w[0] / w[1] == pytest.approx(2.0)  # W_k proportional to 1 / f_k (eq 21-23)


def test_centroid_opposition_touches_only_the_worst_ten_percent():
    m = MSIARGWO()
    st = _state(n=30, d=4)
    st.X = np.random.default_rng(3).uniform(-5, 5, (30, 4))
    st.F, st.V = st.problem.f(st.X), np.zeros(30)
    before = st.X.copy()
    order = np.argsort(st.F)
    m.centroid_opposition(st)
    changed = np.nonzero(np.any(st.X != before, axis=1))[0]
    assert set(changed) <= set(order[-3:])
    assert st.nfev == 3  # exactly the worst 10 % were evaluated


def test_bad_parameters_raise():
    f = lambda X: (X ** 2).sum(1)  # noqa: E731
    with pytest.raises(op.ParameterError):
        op.optimize(f, [(-1, 1)] * 2, pop=0)
    with pytest.raises(op.ParameterError):
        op.optimize(f, [(-1, 1)] * 2, iters=-1)
    with pytest.raises(op.ParameterError):
        op.optimize(f, [(1, -1)] * 2)
    with pytest.raises(op.ParameterError):
        op.optimize(f, [(-1, np.nan)] * 2)
    with pytest.raises(op.ParameterError):
        op.optimize(f, [(-1, 1)] * 2, algorithm="gwo", not_a_parameter=3)
    with pytest.raises(op.UnknownAlgorithmError, match="known"):
        op.optimize(f, [(-1, 1)] * 2, algorithm="nope")


def test_nan_objective_is_treated_as_worst_and_reported():
    def f(X):
        out = (X ** 2).sum(1)
        out[X[:, 0] > 0] = np.nan
        return out

    r = op.optimize(f, [(-1, 1)] * 3, algorithm="pso", pop=10, iters=20, seed=0)
    assert np.isfinite(r.f) and r.x[0] <= 0 and "NaN" in r.message


def test_feasibility_rule_prefers_feasible_points():
    # minimise x + y subject to x^2 + y^2 >= 1 (violation = max(0, 1 - r^2))
    def f(X):
        return X.sum(1), np.maximum(0.0, 1 - (X ** 2).sum(1))

    r = op.optimize(f, [(-2, 2)] * 2, algorithm="gwo", pop=20, iters=200, seed=0)
    assert (r.x ** 2).sum() >= 1 - 1e-12
    assert r.f == pytest.approx(-4.0, abs=1e-2)  # the corner (-2, -2) is feasible and optimal


def test_q_learning_tuning_is_reproducible_and_stays_on_the_grid():
    from optplan.solvers.metaheuristics.tuning import tune_lambdas

    a = tune_lambdas(steps=6, seed=1, runs=1, iters=15)
    b = tune_lambdas(steps=6, seed=1, runs=1, iters=15)
    assert a[:2] == b[:2] and 1 <= a[0] <= 10 and 1 <= a[1] <= 10
    assert a[2][a[:2]] == min(a[2].values())  # the returned state is the best scored


def test_sparrows_are_evaluated_once_per_iteration():
    """hou2024 §2.2.5: producers, scroungers and scouts move, then the flock is evaluated
    once; MISSA adds its producers' elite opposition and one Cauchy-t candidate."""
    F = get_function("F9", shifted=True, dim=6)
    pop, iters = 20, 7
    ssa = op.optimize(F, F.bounds, algorithm="ssa", pop=pop, iters=iters, seed=0)
    missa = op.optimize(F, F.bounds, algorithm="missa", pop=pop, iters=iters, seed=0)
    producers = round(0.3 * pop)
    assert ssa.nfev == pop * (iters + 1)
    assert missa.nfev == pop + iters * (producers + pop + 1)


def test_ipso_inertia_adapts_to_fitness():
    """yang2023 eq 8 / §4.1: the best particle gets w_min, better-than-average particles
    less inertia the better they are, average or worse particles w_max."""
    ipso = get_algorithm("ipso")()
    st = _state(n=10, d=3)
    st.F, st.V = np.array([1.0, 2.0, 3.0, 4.0, 10.0, 10.0, 10.0, 10.0, 10.0, 10.0]), np.zeros(10)
    w = ipso.inertia(st).ravel()              # average fitness 7.0
    assert w[0] == pytest.approx(ipso.w_min) and np.all(w[4:] == ipso.w_max)
    assert np.all(np.diff(w[:5]) > 0)
    assert w[3] == pytest.approx(ipso.w_min + (ipso.w_max - ipso.w_min) * 3 / 6)


def test_bat_velocity_pulls_towards_the_best():
    """yuan2021 eq 2: V = V + (x_* - x_i) f with f >= 0, so a bat at rest moves towards the best."""
    ba = get_algorithm("ba")(pulse0=1.0)      # pulse rate 1: no local walks, only the velocity rule
    st = _state(n=6, d=2, it=1)
    st.X = np.random.default_rng(0).uniform(-5, 5, (6, 2))
    st.F, st.V = st.problem.f(st.X), np.zeros(6)
    st.best_x = np.array([0.0, 0.0])
    ba.setup(st)
    X0 = st.X.copy()
    captured = []
    st.eval_new = lambda X: (captured.append(X.copy()), (X, np.full(len(X), np.inf), np.zeros(len(X))))[1]
    ba.step(st)
    step = captured[0] - X0
    assert np.all(np.einsum("ij,ij->i", step, st.best_x - X0) >= 0)


# ---------------------------------------------------------------- issue 30: the standard versions
def test_pso_particles_lose_the_velocity_that_takes_them_out_of_the_box():
    """Absorbing walls: a particle pushed past a wall sits on it and keeps only the
    velocity components that stayed inside."""
    pso = get_algorithm("pso")()
    st = _state(n=2, d=2)
    st.X = np.array([[4.9, 0.0], [0.0, -4.0]])
    st.F, st.V = st.problem.f(st.X), np.zeros(2)
    pso.setup(st)
    pso.move(st, np.array([[0.5, 0.3], [-0.2, -1.5]]))
    np.testing.assert_allclose(st.X, [[5.0, 0.3], [-0.2, -5.0]])
    np.testing.assert_allclose(pso.V, [[0.0, 0.3], [-0.2, 0.0]])


def test_pso_no_longer_stalls_on_the_shifted_sphere():
    """Before the wall rule PSO ended near 1.9e3 here (median of 5); now it converges."""
    finals = [op.optimize(SPHERE, SPHERE.bounds, algorithm="pso", pop=30, iters=None, max_evals=15030, seed=s).f
              for s in range(3)]
    assert np.median(finals) < 1.0


@pytest.mark.parametrize("algo", ["gwo", "woa"])
def test_greedy_gwo_and_woa_never_lose_a_position(algo):
    F = get_function("F9", shifted=True, dim=6)
    seen = []
    op.optimize(F, F.bounds, algorithm=algo, pop=10, iters=20, seed=2, callback=lambda st: seen.append(st.F.copy()))
    assert all(np.all(b <= a) for a, b in zip(seen, seen[1:]))
    seen.clear()
    op.optimize(F, F.bounds, algorithm=algo, pop=10, iters=20, seed=2, greedy=False,
                callback=lambda st: seen.append(st.F.copy()))
    assert any(np.any(b > a) for a, b in zip(seen, seen[1:]))      # the replacement rule does


def test_ssa_scrounger_steps():
    """Default: each coordinate keeps its own distance to the producer; hou2024 eq 5 read
    literally (``pseudo-inverse``) moves every coordinate of a fed scrounger by one number."""
    st = _state(n=10, d=4)
    st.X = st.rng.uniform(-5, 5, (10, 4))
    Xs, producer, worst = st.X[3:], st.X[0], st.X[-1]
    ranks = np.arange(3, 10)
    fed = (ranks + 1) <= 5
    lit = get_algorithm("ssa")(scrounger_step="pseudo-inverse").scrounger_move(st, Xs, ranks, producer, worst)
    step = lit[fed] - producer
    np.testing.assert_allclose(step, step[:, :1].repeat(4, axis=1))
    std = get_algorithm("ssa")().scrounger_move(st, Xs, ranks, producer, worst)
    ratio = (std[fed] - producer) / np.abs(Xs[fed] - producer)
    np.testing.assert_allclose(ratio, ratio[:, :1].repeat(4, axis=1))   # one normal draw times |X - X_p|
    with pytest.raises(op.ParameterError, match="scrounger_step"):
        get_algorithm("ssa")(scrounger_step="diagonal").scrounger_move(st, Xs, ranks, producer, worst)


def test_ipso_keeps_clipping_and_bad_wall_rules_are_refused():
    assert get_algorithm("ipso")().walls == "clip" and get_algorithm("pso")().walls == "absorb"
    with pytest.raises(op.ParameterError, match="walls"):
        op.optimize(SPHERE, SPHERE.bounds, algorithm="pso", pop=5, iters=2, walls="bounce")


def test_progress_to_a_log_file_is_lines_not_carriage_returns(capsys, monkeypatch):
    """Issue 47: progress redrew one line with carriage returns every 0.5 s, also into a log
    file; off a terminal it prints plain lines (every 10 s) and no stray newline."""
    import optplan.solvers.metaheuristics.engine as engine

    clock = iter(float(t) for t in range(0, 10_000, 3))
    monkeypatch.setattr(engine.time, "perf_counter", lambda: next(clock))
    op.optimize(lambda X: (X ** 2).sum(1), [(-5, 5)] * 2, algorithm="gwo", iters=12, progress=True)
    err = capsys.readouterr().err
    assert "\r" not in err and err.count("gwo: iteration") >= 2
