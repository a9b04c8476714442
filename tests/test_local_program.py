"""The window program (issue 42): one local objective, solved by sampling (dwa) and NMPC (mpc)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import optplan as op
from optplan import local_terms as LT
from optplan.formulations.local_program import Situation, SymbolicSituation

ROBOT = op.RobotSpec(radius=0.2, v_max=0.8, w_max=1.2, a_max=0.8, alpha_max=2.0)


def _situation(movers=np.zeros((0, 5))):
    def dist(P):
        P = np.asarray(P, float)
        return np.hypot(P[..., 0] - 3.0, P[..., 1] - 0.3) - 0.5     # one disc obstacle
    return Situation(state=np.array([0.0, 0.0, 0.1, 0.4, 0.1, 0.0]), subgoal=np.array([5.0, 1.0]),
                     path=np.array([[0.0, 0.0], [2.5, 1.2], [5.0, 1.0]]), static_distance=dist, movers=movers)


def test_the_batched_and_symbolic_views_are_one_objective():
    """At the reference trajectory the symbolic objective equals the batched one (the static
    field's model and the path lines are exact there)."""
    import casadi as ca

    lp = op.LocalProgram(ROBOT, horizon=2.0, intervals=5, step=0.1)
    lp.minimize(1.0 * LT.goal_distance() + 0.3 * LT.goal_heading() + 0.5 * LT.path_distance() - 0.4 * LT.speed()
                + 0.1 * LT.smoothness() + 0.2 * LT.obstacle_cost() + 0.4 * LT.stop_cost(2.0)
                + 0.7 * LT.custom(lambda Z, U, m: m.sum(Z[:, 1] ** 2) + m.sum(U[:, 1] * U[:, 0]), "mine"))
    sit = _situation(np.array([[2.0, -0.5, 0.1, 0.2, 0.3]]))
    U = np.random.default_rng(0).uniform([0.0, -0.8], [0.8, 0.8], (1, lp.K, 2))
    cost, _, _ = lp.evaluate(sit, U)
    opti = ca.Opti()
    ps = SymbolicSituation(opti, lp, max_movers=1)
    Z = lp.rollout(sit, U)[0]
    Zs, Us = opti.parameter(lp.N + 1, 3), opti.parameter(lp.K, 2)
    expr = sum(w * t.symbolic(Zs, Us, ps, lp) for w, t in lp.objective)
    ps.set(lp.symbolic_values(sit, Z, 1))
    opti.set_value(Zs, Z)
    opti.set_value(Us, U[0])
    assert float(opti.value(expr)) == pytest.approx(float(cost[0]), rel=1e-6)


def test_the_symbolic_dynamics_are_the_batched_rollout():
    lp = op.LocalProgram(ROBOT, horizon=1.0, intervals=4, step=0.05)
    sit = _situation()
    U = np.array([[[0.5, 0.3], [0.6, -0.4], [0.2, 0.0], [0.7, 0.9]]])
    Z = lp.rollout(sit, U)[0]
    z = np.asarray(sit.state[:3], float)[None]
    for k in range(lp.K):
        for _ in range(lp.m):
            z = np.asarray(lp.step_symbolic(z[0], U[0, k]), float).reshape(1, 3)
    np.testing.assert_allclose(z[0], Z[-1], atol=1e-12)


def test_constraints_report_violations():
    lp = op.LocalProgram(ROBOT, horizon=2.0, intervals=4)
    lp.minimize(LT.goal_distance())
    lp.subject_to(LT.clearance() >= 0.05)
    lp.subject_to(LT.can_stop())
    sit = _situation()
    sit.state = np.array([1.8, 0.3, 0.0, 0.8, 0.0, 0.0])   # 0.7 m before the disc, heading for it
    into = np.tile([0.8, 0.0], (1, 4, 1))            # full speed at the disc
    away = np.tile([0.0, 0.0], (1, 4, 1))            # stand still (0.2 m from the disc's edge)
    _, v_into, parts = lp.evaluate(sit, into)
    _, v_away, _ = lp.evaluate(sit, away)
    assert v_into[0] > 0 and parts["clearance"][0] > 0 and v_away[0] == 0


SCENARIO = {
    "map": [[0] * 16 for _ in range(3)] + [[0] * 7 + [1, 1] + [0] * 7] + [[0] * 16 for _ in range(3)],
    "resolution": 0.5,
    "robot": {"model": "unicycle", "radius": 0.15, "v_max": 0.6, "w_max_deg": 90, "a_max": 0.8,
              "alpha_max_deg": 180, "jerk_max": 4.0},
    "start": [0.5, 1.75, 0], "goal": [7.5, 1.75], "sensor_range": 3.0, "dt": 0.1, "time_limit": 60,
}


def _side_program(sign: float) -> op.LocalProgram:
    """Reach the goal, with a custom term that prefers passing above (+1) or below (-1) y = 1.75."""
    robot = op.load_scenario(SCENARIO).robot
    lp = op.LocalProgram(robot, horizon=2.0, intervals=5, step=0.1)
    lp.minimize(1.0 * LT.goal_distance() - 0.5 * LT.speed() + 0.05 * LT.smoothness()
                + 0.5 * LT.custom(lambda Z, U, m: -sign * m.sum(Z[:, 1] - 1.75) / 21.0, "prefer_side"))
    lp.subject_to(LT.clearance() >= 0.02)
    lp.subject_to(LT.can_stop(0.02))
    return lp


@pytest.mark.parametrize("solver", ["dwa", "qp-dwa", "mpc"])
def test_a_custom_local_term_reaches_every_solver(solver):
    """The same custom term steers every solver round the block on its side; none collides."""
    sides = {}
    for sign in (1.0, -1.0):
        r = op.simulate(op.load_scenario(SCENARIO), global_planner="astar", local_planner=solver,
                        local_program=_side_program(sign), seed=0, subgoals="goal")
        assert r.reached and r.collisions == 0, r.message
        T = np.asarray(r.trajectory)
        at_block = T[np.argmin(np.abs(T[:, 1] - 4.0)), 2]
        sides[sign] = at_block
    assert sides[1.0] > 1.75 + 0.3 and sides[-1.0] < 1.75 - 0.3, sides


def test_mpc_reaches_the_goal_within_the_robot_limits():
    r = op.simulate("hou2024_dynamic1", global_planner="astar", local_planner="mpc", seed=0)
    sc = op.load_scenario("hou2024_dynamic1")
    assert r.reached and r.collisions == 0, r.message
    assert r.max_abs_accel <= sc.robot.a_max * (1 + 1e-6)


def test_mpc_reports_cost_violation_and_status_per_step():
    from optplan.local import make_local_planner
    from optplan.local.base import LocalContext
    from optplan.world.robot import RobotState

    sit = _situation()
    planner = make_local_planner("mpc", ROBOT, 0.1)
    state = RobotState(0.0, 0.0, 0.1, 0.4, 0.1)
    planner.reset(state, sit.path)
    ctx = LocalContext(state=state, subgoal=sit.subgoal, goal=sit.subgoal, global_path=sit.path,
                       static_distance=sit.static_distance, dynamic=np.zeros((0, 5)), dt=0.1)
    cmd = planner.command(ctx)
    for key in ("cost", "violation", "status", "solve_ms", "mode"):
        assert key in cmd.info
    assert cmd.info["mode"] in ("mpc", "fallback-sample") and math.isfinite(cmd.info["cost"])


def test_bad_local_program_requests_are_refused():
    lp = op.LocalProgram(ROBOT)
    with pytest.raises(op.ParameterError, match="paper preset"):
        op.simulate("hou2024_dynamic1", local_planner="idwa", local_program=lp)
    from optplan.local import make_local_planner

    with pytest.raises(op.ParameterError, match="max_mover"):
        make_local_planner("mpc", ROBOT, 0.1, max_movrs=3)
    with pytest.raises(op.ParameterError, match="intervals"):
        op.LocalProgram(ROBOT, intervals=0)


def _one_step(name, **params):
    from optplan.local import make_local_planner
    from optplan.local.base import LocalContext
    from optplan.world.robot import RobotState

    sit = _situation()
    planner = make_local_planner(name, ROBOT, 0.1, **params)
    state = RobotState(0.0, 0.0, 0.1, 0.4, 0.1)
    planner.reset(state, sit.path)
    ctx = LocalContext(state=state, subgoal=sit.subgoal, goal=sit.subgoal, global_path=sit.path,
                       static_distance=sit.static_distance, dynamic=np.zeros((0, 5)), dt=0.1)
    return sit, planner, planner.command(ctx)


def test_qp_dwa_over_a_program_is_never_worse_than_its_best_sample():
    """The polish is kept only when the program prefers it: the step's cost is at most the
    best sample's, under the same program's batched view."""
    sit, planner, cmd = _one_step("qp-dwa", local_program="default")
    assert cmd.info["planner"] == "qp-dwa" and cmd.info["mode"] in ("qp-dwa", "fallback-sample")
    from optplan.world.robot import RobotState

    lp = planner.lp
    U = planner.sampler.samples(type("C", (), {"state": RobotState(0.0, 0.0, 0.1, 0.4, 0.1), "dt": 0.1})())
    i, cost, viol = planner.sampler.best(sit, U)
    assert viol[i] <= 1e-6 and cmd.info["violation"] <= 1e-6
    assert cmd.info["cost"] <= cost[i] + 1e-9
    assert lp.name == "default"


def test_a_named_local_program_is_the_same_program_and_a_wrong_name_is_refused():
    _, by_name, a = _one_step("dwa", local_program="default")
    _, by_object, b = _one_step("dwa", local_program=op.local_terms.default_local_program(ROBOT, step=0.1))
    assert (a.v, a.w) == (b.v, b.w) and a.info["cost"] == b.info["cost"]
    with pytest.raises(op.ParameterError, match="did you mean 'default'"):
        _one_step("mpc", local_program="defualt")
    with pytest.raises(op.ParameterError, match="path_creep"):
        _one_step("mpc", path_creep={"sped": 0.1})


def test_the_local_programs_spec_names_a_program_and_its_solvers():
    from optplan.bench.spec import load_spec

    runs = load_spec("local_programs", quick=True).expand()
    assert {r.local_planner for r in runs} == {"dwa", "mpc"}
    assert all(r.params["local_program"] == "default" for r in runs)


@pytest.mark.parametrize("turns", [False, True])
def test_mover_clearance_is_one_rule_in_both_views(turns):
    """The symbolic mover rows give the batched shortfall at the reference; a mover that may
    turn round is kept clear of its whole line segment, so it never leaves more room."""
    import casadi as ca

    lp = op.LocalProgram(ROBOT, horizon=2.0, intervals=5, step=0.1)
    lp.subject_to(LT.clearance(mover_margin=0.1, mover_growth=0.1, mover_turns=turns) >= 0.02)
    # a mover driving away from the robot along its path: turning round brings it back
    sit = _situation(np.array([[1.0, 0.1, 0.4, 0.0, 0.2]]))
    U = np.tile([0.6, 0.0], (1, lp.K, 1))
    Z = lp.rollout(sit, U)[0]
    gaps = next(lp.mover_gaps(Z[None], sit, turns=turns))[0]
    opti = ca.Opti()
    ps = SymbolicSituation(opti, lp, max_movers=1)
    Zs = opti.parameter(lp.N + 1, 3)
    rows = lp.mover_rows(Zs, ps, squared=False, turns=turns)
    ps.set(lp.symbolic_values(sit, Z, 1))
    opti.set_value(Zs, Z)
    assert np.allclose([float(opti.value(r)) for r in rows], gaps, atol=1e-6)
    straight = next(lp.mover_gaps(Z[None], sit, turns=False))[0]
    assert np.all(gaps <= straight + 1e-12)
    if turns:
        assert gaps.min() < straight.min() - 0.1
