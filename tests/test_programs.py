"""Path programs: one formulation, many solvers (issue 24)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import optplan as op
from optplan import terms as T
from optplan.errors import OptplanError, ParameterError, UnknownAlgorithmError
from optplan.formulations.namespaces import BATCHED, SYMBOLIC, Batch, Sym
from optplan.world.metrics import path_length, turn_angles_deg


def circles_world():
    return op.CircleWorld(bounds=(0, 0, 10, 10), circles=[(4.0, 5.0, 1.2), (7.0, 3.0, 0.8), (6.5, 7.5, 0.9)])


def block_grid():
    rows = np.zeros((12, 12), dtype=int)
    rows[3:9, 5:7] = 1          # a wall in the middle (file rows: top first)
    rows[1, 2:4] = 1
    return op.GridMap.from_rows(rows)


def exposure(P, m):
    """A user term: how long the path stays near (3, 3)."""
    d = P - np.array([3.0, 3.0])
    return m.sum(m.exp(-m.sum(d * d, axis=1) / 4.0))


def turn_program(world, variables=None, clearance=0.1, limit_deg=80.0):
    prog = op.PathProgram(world, (0.5, 0.5), (9.5, 9.5) if not hasattr(world, "occ") else (11.5, 11.5),
                          variables=variables or op.Waypoints(4))
    prog.minimize(T.length() + 0.3 * T.turn_angles().sumsq() + 2.0 * T.custom(exposure, name="exposure"))
    prog.subject_to(T.clearance() >= clearance)
    prog.subject_to(T.turn_angles() <= math.radians(limit_deg))
    return prog


# ------------------------------------------------------------------ namespaces

def test_batched_and_symbolic_views_of_a_custom_term_agree_with_plain_numpy():
    rng = np.random.default_rng(0)
    P = rng.random((5, 7, 2)) * 10

    def fn(P, m):
        d = m.diff(P, axis=0)
        seg = m.norm(d, axis=1)
        mid = (P[1:] + P[:-1]) / 2
        return m.sum(seg * m.exp(-mid[:, 0] / 5)) + m.max(seg) - m.atan2(P[-1, 1], P[0, 0])

    want = []
    for p in P:
        d = np.diff(p, axis=0)
        seg = np.hypot(d[:, 0], d[:, 1])
        mid = (p[1:] + p[:-1]) / 2
        want.append((seg * np.exp(-mid[:, 0] / 5)).sum() + seg.max() - np.arctan2(p[-1, 1], p[0, 0]))
    got = fn(Batch(P), BATCHED).a
    np.testing.assert_allclose(got, want, rtol=1e-12)

    import casadi as ca

    x = ca.SX.sym("x", 7, 2)
    f = ca.Function("f", [x], [fn(Sym(x, (7, 2)), SYMBOLIC).m])
    np.testing.assert_allclose([float(f(p)) for p in P], want, rtol=1e-9)


def test_builtin_terms_match_the_metrics_module():
    rng = np.random.default_rng(1)
    P = rng.random((4, 6, 2)) * 5
    ctx = op.PathProgram(circles_world(), (0.5, 0.5), (9.5, 9.5)).ctx
    np.testing.assert_allclose(T.length().batch(P, ctx), path_length(P), rtol=1e-12)
    np.testing.assert_allclose(np.degrees(T.turn_angles().batch(P, ctx)), turn_angles_deg(P), atol=1e-9)
    np.testing.assert_allclose(T.turn_count().batch(P, ctx), (turn_angles_deg(P) > 1e-6).sum(axis=1))


def test_objective_must_be_scalar_and_terms_take_numbers():
    prog = op.PathProgram(circles_world(), (0.5, 0.5), (9.5, 9.5))
    with pytest.raises(ParameterError, match="scalar"):
        prog.minimize(T.turn_angles())
    with pytest.raises(ParameterError, match="plain numbers"):
        T.length() * "2"
    with pytest.raises(ParameterError, match="vector term and a scalar"):
        T.length() + T.turn_angles()


# ------------------------------------------------------------------- variables

@pytest.mark.parametrize("variables", [op.Waypoints(3), op.Points(12), op.BSpline(ctrl=4, samples=20)])
def test_continuous_variables_decode_the_same_in_numpy_and_casadi(variables):
    import casadi as ca

    prog = op.PathProgram(circles_world(), (0.5, 0.5), (9.5, 9.5), variables=variables)
    v = prog.variables
    X = v.lower + np.random.default_rng(2).random((3, v.dim)) * (v.upper - v.lower)
    P = v.decode(X)
    np.testing.assert_array_equal(P[:, 0], np.broadcast_to(prog.start, (3, 2)))
    np.testing.assert_allclose(P[:, -1], np.broadcast_to(prog.goal, (3, 2)), atol=1e-12)
    x = ca.SX.sym("x", v.dim)
    f = ca.Function("d", [x], [v.decode_symbolic(x).m])
    for row, want in zip(X, P):
        np.testing.assert_allclose(np.asarray(f(row)), want, atol=1e-12)


def test_cell_sequence_decodes_chains_of_adjacent_cells_and_is_swarm_only():
    grid = block_grid()
    prog = op.PathProgram(grid, (0.5, 0.5), (11.5, 11.5), variables=op.CellSequence(via=3))
    prog.minimize(T.length())
    v = prog.variables
    X = v.lower + np.random.default_rng(3).random((20, v.dim)) * (v.upper - v.lower)
    for P in v.decode(X):
        steps = np.abs(np.diff(P[:-1], axis=0))
        assert np.all(steps <= 1.0 + 1e-12)            # 8-adjacent cells (or a repeat of the goal)
        assert np.allclose(P[0], prog.start) and np.allclose(P[-1], prog.goal)
    with pytest.raises(ParameterError, match="discrete"):
        prog.solve("ipopt")


# --------------------------------------------------------------- conformance



def _swarm_names():
    from optplan.programs import solver_names

    return [n for n in solver_names() if n not in ("ipopt", "slsqp", "osqp", "cvxpy")]


@pytest.mark.parametrize("name", _swarm_names())
def test_every_swarm_solver_obeys_the_contract(name):
    prog = turn_program(circles_world())
    r = prog.solve(name, max_evals=200, pop=10, seed=3)
    assert r.nfev == 200                                     # the budget is exact
    cost, viol, feasible = prog.judge(r.path)
    assert r.feasible == feasible and r.cost == pytest.approx(cost) and r.violations == viol
    again = prog.solve(name, max_evals=200, pop=10, seed=3)
    np.testing.assert_array_equal(r.x, again.x)              # same seed, same numbers
    with pytest.raises(ParameterError, match="no option 'max_eval'"):
        prog.solve(name, max_eval=200)
    with pytest.raises(OptplanError):
        prog.solve(name, pop=0)


@pytest.mark.parametrize("name", ["ipopt", "slsqp"])
def test_gradient_solvers_obey_the_contract(name):
    prog = turn_program(circles_world())
    seed = prog.solve("pso", max_evals=1500, seed=0)
    r = prog.solve(name, init=seed)
    cost, viol, feasible = prog.judge(r.path)
    assert r.feasible == feasible and r.cost == pytest.approx(cost)
    if r.feasible:
        assert np.all(turn_angles_deg(r.path[None])[0] <= 80.0 + 1e-6)
        assert op.validate_path(prog.world, r.path, 0.1)
    again = prog.solve(name, init=seed)
    np.testing.assert_allclose(r.x, again.x)
    with pytest.raises(ParameterError, match=f"{name} has no option 'seeds'"):
        prog.solve(name, seeds=3)
    with pytest.raises(ParameterError, match="max_iter"):
        prog.solve(name, max_iter=-1)


@pytest.mark.parametrize("name", ["osqp", "cvxpy"])
def test_qp_solvers_take_quadratic_programs_and_refuse_others_by_name(name):
    world = block_grid()
    seed = op.plan(world, (0.5, 0.5), (11.5, 11.5), algorithm="astar")
    prog = op.smoothing_program(world, (0.5, 0.5), (11.5, 11.5), n=30, clearance=0.1)
    r = prog.solve(name, init=seed.path)
    assert r.feasible and op.validate_path(world, r.path, 0.1)
    assert r.cost <= prog.evaluate(prog.variables.decode(prog.variables.from_path(seed.path)[None])[0])[0] + 1e-9
    with pytest.raises(ParameterError, match="not quadratic: length"):
        turn_program(world).solve(name, init=seed.path)
    with pytest.raises(ParameterError, match="needs init"):
        prog.solve(name)


def test_an_option_named_solver_reaches_the_solver_through_prog_solve():
    # cvxpy's own option 'solver' used to collide with PathProgram.solve's first parameter
    world = block_grid()
    seed = op.plan(world, (0.5, 0.5), (11.5, 11.5), algorithm="astar")
    prog = op.smoothing_program(world, (0.5, 0.5), (11.5, 11.5), n=20)
    r = prog.solve("cvxpy", init=seed.path, solver="CLARABEL")
    assert r.feasible and r.solver == "cvxpy"


def test_unknown_solver_and_wrong_types_are_optplan_errors():
    prog = turn_program(circles_world())
    with pytest.raises(UnknownAlgorithmError, match="unknown program solver"):
        prog.solve("simplex")
    with pytest.raises(ParameterError, match="init"):
        prog.solve("ipopt", init=np.zeros(3))
    with pytest.raises(ParameterError):
        prog.subject_to("clearance >= 1")


# -------------------------------------------------------------- known optima

def test_ipopt_finds_the_straight_line_in_an_empty_world():
    world = op.CircleWorld(bounds=(0, 0, 10, 10), circles=np.zeros((0, 3)))
    prog = op.PathProgram(world, (1, 1), (9, 4), variables=op.Waypoints(3))
    prog.minimize(T.length())
    prog.subject_to(T.clearance() >= 0.0)
    r = prog.solve("ipopt", init=np.array([[1, 1], [3, 8], [6, 1], [7, 9], [9, 4]], float))
    assert r.feasible and r.cost == pytest.approx(math.hypot(8, 3), abs=1e-6)


def test_smoothing_program_solvers_agree_on_its_optimum():
    world = circles_world()
    s, g = (0.5, 0.5), (9.5, 9.5)
    seed = op.plan(world, s, g, algorithm="visibility")
    prog = op.smoothing_program(world, s, g, n=25, clearance=0.05)
    costs = {name: prog.solve(name, init=seed.path) for name in ("ipopt", "slsqp")}
    assert all(r.feasible for r in costs.values())
    assert costs["ipopt"].cost == pytest.approx(costs["slsqp"].cost, rel=1e-4)


# --------------------------------------------------------------------- chains

def test_a_chain_is_never_worse_than_its_first_stage_and_reports_every_stage():
    prog = turn_program(circles_world())
    first = prog.solve("gwo", max_evals=900, seed=1)
    chain = prog.solve(["gwo", "ipopt"], max_evals=900, seed=1)
    assert [s["solver"] for s in chain.stages] == ["gwo", "ipopt"]
    assert chain.stages[0]["cost"] == pytest.approx(first.cost)
    assert (not first.feasible) or chain.feasible
    assert chain.cost <= first.cost + 1e-12 or not first.feasible
    assert chain.nfev == sum(s["nfev"] for s in chain.stages)
    assert prog.evaluate(chain.path)[0] == pytest.approx(chain.cost)
    with pytest.raises(ParameterError, match="has no option 'foo'"):
        prog.solve(["gwo", "ipopt"], foo=1)


def test_gradient_solvers_name_the_surrogates_they_used():
    prog = op.PathProgram(circles_world(), (0.5, 0.5), (9.5, 9.5), variables=op.Waypoints(3))
    prog.minimize(T.length() + 0.5 * T.turn_count())
    prog.subject_to(T.clearance() >= 0.0)
    r = prog.solve("ipopt", init=prog.solve("pso", max_evals=600, seed=0))
    assert "surrogate of turn_count" in r.message


# ------------------------------------------------------------ paper programs

def test_paper_program_is_the_fitness_the_planner_optimises():
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("hou2024_env1")
    res = op.plan(world, s, g, algorithm="gwo", pop=10, iters=20, seed=0, preset="li2023", postprocess="none",
                  encoding="paper")
    prog = op.paper_program("li2023", world, s, g)
    assert prog.evaluate(res.path)[0] == pytest.approx(float(res.history[-1]), rel=1e-12)


def test_op_plan_solves_the_paper_program_through_the_program_solvers():
    """op.plan's column-node run is the paper program solved by the program swarm solver,
    its segment tables a checked acceleration: the same run on the program's own view
    (no tables) gives the same history and path."""
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("hou2024_env1")
    res = op.plan(world, s, g, algorithm="gwo", pop=10, iters=20, seed=0, preset="li2023", postprocess="none",
                  encoding="paper")
    prog = op.paper_program("li2023", world, s, g, variables=op.ColumnNodes())
    assert prog.acceleration is None
    own = prog.solve("gwo", pop=10, iters=20, seed=0)
    np.testing.assert_allclose(own.history, res.history, rtol=1e-12)
    assert own.cost == pytest.approx(float(res.history[-1]), rel=1e-12)
    assert own.nfev == res.nfev


def test_an_acceleration_that_changes_the_objective_is_refused():
    from optplan.formulations.paper_programs import planner_program
    from optplan.solvers.paths import make_problem
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("hou2024_env1")
    problem = make_problem(world, s, g, preset="li2023", constraint="feasibility")
    prog = planner_program(problem, "li2023")
    assert prog.acceleration_name == "column segment tables"
    X = prog.variables.initial_population(6, np.random.default_rng(3), 0.0)
    for a, b in zip(prog.population(X), prog.own_population(X)):
        np.testing.assert_allclose(a, b, rtol=1e-12)
    other = op.paper_program("li2023", world, s, g, variables=op.ColumnNodes())
    wrong = make_problem(world, s, g, preset="chen2025", constraint="feasibility")   # another fitness
    with pytest.raises(op.ParameterError, match="does not evaluate program"):
        other.accelerate(wrong.evaluate, name="chen2025 tables")
    assert other.acceleration is None


def test_refinement_reports_when_it_raises_the_planners_fitness():
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("hou2024_env1")
    r = op.plan(world, s, g, algorithm="iga", pop=20, iters=40, seed=0, refine="casadi")
    first, second = r.stages
    assert first["program"] == "li2023" and second["fitness_before"] == first["fitness"]
    assert second["worse"] == (second["fitness"] > first["fitness"] + 1e-9)
    if second["worse"]:
        assert "raised the li2023 fitness" in r.message
        kept = op.plan(world, s, g, algorithm="iga", pop=20, iters=40, seed=0, refine="casadi",
                       refine_options={"if_worse": "reject"})
        assert not kept.refined and kept.length == pytest.approx(first["length"])


def test_compare_tabulates_and_stores(tmp_path):
    prog = turn_program(circles_world())
    table = op.compare(prog, ["pso", ["pso", "ipopt"]], seeds=[0, 1], max_evals=600, db=tmp_path / "c.sqlite")
    assert len(table.rows) == 4
    assert {r["solver"] for r in table.rows} == {"pso", "pso>ipopt"}
    assert "pso>ipopt" in table.table()
    from optplan.bench.store import ResultStore

    with ResultStore(tmp_path / "c.sqlite") as st:
        assert st.count() == 4


def test_ipopt_from_a_feasible_seed_on_a_grid_never_ends_worse():
    """From a seed the exact test accepts, IPOPT moves within a trust region whose obstacles
    are read off the current path, takes only improving steps, and ends feasible and no
    worse than the seed (before the trust region it could jump to another corridor and end
    far longer)."""
    occ = np.zeros((12, 12), bool)
    occ[3:9, 5:7] = True
    occ[0:3, 9] = True
    grid = op.GridMap(occ)
    prog = op.PathProgram(grid, (0.5, 0.5), (11.5, 11.5), variables=op.BSpline(ctrl=5, samples=40))
    prog.minimize(T.length() + 0.3 * T.turn_angles().sumsq())
    prog.subject_to(T.clearance() >= 0.1)
    seed = prog.solve("pso", max_evals=1500, seed=0)
    assert seed.feasible
    res = prog.solve("ipopt", init=seed)
    assert res.feasible and op.validate_path(grid, res.path, 0.1)
    assert res.cost < seed.cost - 0.05
    assert abs(prog.evaluate(res.path)[0] - res.cost) < 1e-9


def test_a_clearance_term_on_a_grid_reads_a_path_local_strip_of_the_distance_spline():
    """Clearance in the objective: IPOPT reads the distance field's spline near the start
    path (a parameter), never a whole-map CasADi interpolant, and improves a feasible start."""
    occ = np.zeros((64, 64), bool)
    occ[20:40, 28:34] = True
    grid = op.GridMap(occ)
    prog = op.PathProgram(grid, (2.5, 30.5), (60.5, 30.5), variables=op.Points(12))
    prog.minimize(T.length() + (-0.05) * T.clearance(per_segment=2).sum())
    prog.subject_to(T.clearance() >= 0.2)
    seed = op.plan(grid, (2.5, 30.5), (60.5, 30.5), algorithm="visibility", clearance=0.5)
    start = prog.solve("pso", max_evals=10, seed=0, init=seed.path)
    res = prog.solve("ipopt", init=start, max_iter=100)
    assert res.feasible and res.cost <= start.cost + 1e-9
    assert abs(prog.evaluate(res.path)[0] - res.cost) < 1e-9
    from optplan.world.derived import derived_keys

    assert not any(isinstance(k, tuple) and k[0] == "casadi_sdf" for _, k in derived_keys(grid))


def test_the_casadi_smoother_minimises_the_smoothing_programs_energy():
    """smooth_path's energy is op.smoothing_program's objective: its reported objective is
    the program's cost of the refined path."""
    from optplan.solvers.nlp import smooth_path

    world = circles_world()
    seed = op.plan(world, (0.5, 0.5), (9.5, 9.5), algorithm="visibility", clearance=0.1)
    out = smooth_path(world, seed.path, 0.1, n_points=30, w_smooth=0.5)
    assert out.success
    prog = op.smoothing_program(world, (0.5, 0.5), (9.5, 9.5), n=30, w_smooth=0.5, clearance=0.1)
    assert prog.evaluate(out.path)[0] == pytest.approx(out.objective, rel=1e-12)


def test_repeated_end_points_add_no_turn_to_the_program_terms():
    """A path that reaches the goal moving left and down, padded with goal copies: the zero-length
    segments give cross = dot = -0.0, and atan2(-0.0, -0.0) = -pi counted a U-turn there."""
    from optplan.world.metrics import turn_angles_deg

    w = op.CircleWorld(bounds=(0, 0, 10, 10), circles=[])
    P = np.array([[9.0, 9.0], [5.0, 8.0], [1.0, 1.0], [1.0, 1.0], [1.0, 1.0]])
    prog = op.PathProgram(w, P[0], P[-1], variables=op.Points(3))
    prog.minimize(T.turn_angles().sum() + T.turn_count())
    want = np.radians(turn_angles_deg(P)).sum() + 1.0
    assert prog.path_costs(P[None])[0] == pytest.approx(want, abs=1e-12)
