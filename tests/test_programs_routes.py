"""op.plan's metaheuristic routes are the paper program solved by the program swarm solver
(issue 24): penalty mode, waypoints, spline and general encodings. Each test solves the
same program directly on its own view (the terms, no acceleration) and gets op.plan's run."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan import terms as T
from optplan.formulations.variables import SplineThrough


def circles():
    return op.CircleWorld(bounds=(0, 0, 10, 10), circles=[(3, 3, 1.0), (6, 6, 1.2), (7, 2.5, 0.8)], safety=0.1)


S, G = (0.5, 0.5), (9.5, 9.5)


def same_run(res, own, path_equal=True):
    np.testing.assert_allclose(own.history, res.history, rtol=1e-12)
    assert own.nfev == res.nfev
    if path_equal:
        np.testing.assert_allclose(own.path, res.path, rtol=0, atol=1e-12)


@pytest.fixture
def routes(monkeypatch):
    """Names of the algorithms op.plan handed to the program swarm solver."""
    from optplan.solvers.programs.swarm import SwarmSolver

    seen = []
    orig = SwarmSolver.search

    def spy(self, program, **o):
        seen.append((self.name, program.variables.name, o.get("constraint")))
        return orig(self, program, **o)

    monkeypatch.setattr(SwarmSolver, "search", spy)
    return seen


def test_penalty_mode_is_the_programs_paper_penalty(routes):
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("hou2024_env1")
    kw = dict(pop=8, iters=15, seed=1)
    res = op.plan(world, s, g, algorithm="gwo", preset="chen2025", constraint="penalty", init="own",
                  encoding="columns", postprocess="none", **kw)
    assert routes == [("gwo", "ColumnNodes()", "penalty")]
    prog = op.paper_program("chen2025", world, s, g, variables=op.ColumnNodes(), paper_penalty=True)
    assert prog.acceleration is None and prog.has_paper_penalty
    own = prog.solve("gwo", constraint="penalty", start="algorithm", **kw)
    same_run(res, own)


def test_waypoints_on_circles_with_penalty(routes):
    w = circles()
    kw = dict(pop=8, iters=20, seed=0)
    res = op.plan(w, S, G, algorithm="gwo", preset="yang2023", encoding="waypoints", constraint="penalty",
                  postprocess="none", **kw)
    assert routes == [("gwo", "Waypoints(3)", "penalty")]
    prog = op.paper_program("yang2023", w, S, G, variables=op.Waypoints(3), paper_penalty=True)
    own = prog.solve("gwo", constraint="penalty", start="algorithm", **kw)
    same_run(res, own)


def test_waypoints_on_a_grid_feasibility_rule(routes):
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("chen2025_20")
    kw = dict(pop=8, iters=20, seed=0)
    res = op.plan(world, s, g, algorithm="pso", preset="length", encoding="waypoints", postprocess="none", **kw)
    assert routes == [("pso", "Waypoints(3)", "feasibility")]
    own = op.paper_program("length", world, s, g, variables=op.Waypoints(3)).solve("pso", start="algorithm", **kw)
    same_run(res, own)


def test_spline_encoding_is_the_spline_through_variables(routes):
    w = circles()
    kw = dict(pop=8, iters=20, seed=2)
    res = op.plan(w, S, G, algorithm="gwo", preset="li2023", postprocess="none", encoding="paper", **kw)  # spline
    assert routes == [("gwo", "SplineThrough(k=3, samples=100)", "feasibility")]
    prog = op.paper_program("li2023", w, S, G, variables=SplineThrough(3, 100), per_segment=1)
    own = prog.solve("gwo", start="algorithm", **kw)
    same_run(res, own)
    # the variables decode in CasADi like in numpy (the spline is linear in the handles)
    import casadi as ca

    x = own.x
    sym = ca.Function("d", [xs := ca.SX.sym("x", x.size)], [prog.variables.decode_symbolic(xs).m])(x)
    np.testing.assert_allclose(np.asarray(sym), prog.variables.decode(x[None])[0], atol=1e-12)


def test_general_encoding_starts_from_corridors(routes):
    w = circles()
    kw = dict(pop=8, iters=15, seed=0)
    res = op.plan(w, S, G, algorithm="gwo", preset="length", encoding="general", postprocess="none", **kw)
    assert routes == [("gwo", "GeneralVias(3)", "feasibility")]
    prog = op.paper_program("length", w, S, G, variables=op.GeneralVias(3, corridor_start=True), per_segment=1)
    own = prog.solve("gwo", **kw)
    same_run(res, own, path_equal=False)
    keep = np.r_[True, np.any(np.diff(own.path, axis=0) != 0, axis=1)]   # the padding repeats the goal
    np.testing.assert_allclose(own.path[keep], res.path, atol=1e-12)
    assert own.feasible and res.feasible


def test_general_encoding_under_turn_terms_is_the_program(routes):
    """li2023's fitness (turn terms) over the general encoding: a via point snapped onto the
    start repeats it, which is no turn for the planner's rule nor for the program's
    turn_angles, so the run is the program's."""
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("hou2024_env1")
    kw = dict(pop=8, iters=10, seed=0)
    res = op.plan(world, s, g, algorithm="gwo", preset="li2023", encoding="general", postprocess="none", **kw)
    assert len(routes) == 1 and routes[0][0] == "gwo" and routes[0][1].startswith("GeneralVias")
    assert res.feasible == bool(op.validate_path(world, res.path))


def test_routes_that_stay_direct_say_why(routes):
    """Pruned-path scoring keeps the planner's own fitness (its violation counts the blocked
    cells a kept segment passes, not the clearance constraint's), and the run is unchanged."""
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("chen2025_20")
    res = op.plan(world, s, g, algorithm="gwo", pop=6, iters=5, seed=0, fitness_on="pruned", encoding="paper")
    assert routes == [] and res.feasible


def test_paper_penalty_is_constraint_handling():
    w = circles()
    prog = op.PathProgram(w, S, G, variables=op.Waypoints(1))
    prog.minimize(T.length())
    prog.subject_to((T.clearance() >= 0.0).penalised(100.0, 10.0))
    X = np.array([[5.0, 5.0], [1.0, 9.0]])           # the first crosses discs, the second is free
    P = prog.variables.decode(X)
    from optplan.formulations.terms import collisions, penetration

    want = prog.path_costs(P) + 100.0 * collisions(w, P, 0.0) + 10.0 * penetration(w, P, 0.0)
    np.testing.assert_allclose(prog.penalised(X, 1e6), want)
    assert want[0] > prog.path_costs(P)[0] + 100 and want[1] == pytest.approx(prog.path_costs(P)[1])
    # the violation and the verdict do not depend on the penalty
    plain = op.PathProgram(w, S, G, variables=op.Waypoints(1)).minimize(T.length()).subject_to(T.clearance() >= 0.0)
    for a, b in zip(prog.population(X), plain.population(X)):
        np.testing.assert_allclose(a, b)
    with pytest.raises(op.ParameterError, match="only a clearance constraint"):
        (T.length() <= 3.0).penalised(1.0)
    with pytest.raises(op.ParameterError):
        (T.clearance() >= 0.0).penalised(-1.0)
    with pytest.raises(op.ParameterError, match="penalised acceleration"):
        plain.accelerate(plain.own_population, penalised=lambda X: np.zeros(len(X)))


@pytest.mark.parametrize("w", [0.0, 0.5, 0.3])
def test_corridor_qp_hessian_is_the_smoothing_energys(w):
    """The OSQP/cvxpy corridor program's Hessian comes from smoothing_energy's symbolic view:
    1/2 z'Pz is the energy's batched value on any path, and P is D1'D1 + w D2'D2 per coordinate."""
    import scipy.sparse as sp

    from optplan.formulations.paper_programs import smoothing_energy
    from optplan.solvers.qp.program import energy_hessian, objective_value

    N = 9
    P = energy_hessian(N, w)
    pts = np.random.default_rng(4).random((N, 2)) * 5
    z = np.concatenate([pts[:, 0], pts[:, 1]])
    want = float(smoothing_energy(w).batch(pts[None], None)[0])
    assert 0.5 * z @ (P @ z) == pytest.approx(want, rel=1e-12)
    assert objective_value(pts, w) == want
    D1 = np.diff(np.eye(N), axis=0)
    D2 = np.diff(np.eye(N), 2, axis=0)
    H = D1.T @ D1 + w * D2.T @ D2
    np.testing.assert_array_equal(P.toarray(), 2 * sp.block_diag([H, H]).toarray())
    assert not np.any(P.data == 0)


def test_general_vias_paths_repeat_points_only_at_the_end():
    """A via snapped next to another leaves repeated points; GeneralVias moves them to the
    end (copies of the goal), so the turn terms see every turn of the path."""
    from optplan.world.papermaps import paper_map

    world, s, g = paper_map("chen2025_20")
    v = op.PathProgram(world, s, g, variables=op.GeneralVias(3)).variables
    X = v.lower + np.random.default_rng(0).random((32, v.dim)) * (v.upper - v.lower)
    P = v.decode(X)
    raw = v.encoding.decode(X, v.n_points)
    for p, r in zip(P, raw):
        moved = np.any(np.diff(p, axis=0) != 0, axis=1)
        n = int(moved.sum())
        assert moved[:n].all() and not moved[n:].any()         # repeats only after the last move
        keep = np.r_[True, np.any(np.diff(r, axis=0) != 0, axis=1)]
        np.testing.assert_array_equal(p[:n + 1], r[keep])       # the same polyline
        np.testing.assert_array_equal(p[n + 1:], np.broadcast_to(g, (len(p) - n - 1, 2)))


def test_a_budget_object_is_a_swarm_solver_option(routes):
    from optplan.solvers.budget import Budget

    w = circles()
    b = Budget(iterations=40, stagnation=5)
    res = op.plan(w, S, G, algorithm="pso", pop=8, seed=3, budget=b, postprocess="none", encoding="paper")
    assert routes and routes[0][0] == "pso"
    prog = op.paper_program("yang2023", w, S, G, variables=SplineThrough(3, 100), per_segment=1)  # pso's paper
    own = prog.solve("pso", pop=8, seed=3, budget=b, start="algorithm")
    same_run(res, own)
    assert own.nfev < 8 * 41          # the stagnation stop of the Budget acted
    with pytest.raises(op.ParameterError, match="not both"):
        op.plan(w, S, G, algorithm="pso", pop=8, budget=b, max_evals=100)
