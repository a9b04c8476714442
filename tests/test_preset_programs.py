"""The papers' DWA presets as named window programs (issue 42): sampling a preset's program is
the preset's planner, bit for bit; its cost is the program's; added terms reach the sampler."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan import local_terms as LT
from optplan.local import PRESETS, make_local_planner
from optplan.local.base import LocalContext
from optplan.local.preset_programs import CriticTerm, PresetProgram, SampleSet
from optplan.world.robot import RobotState

from test_local_program import SCENARIO


@pytest.mark.parametrize("preset", sorted(PRESETS))
def test_sampling_a_presets_program_is_the_preset_bit_for_bit(preset):
    solver = "qp-dwa" if PRESETS[preset].refine == "qp" else "dwa"
    for scenario in ("yang2023_idwa_crossing", "li2023_exp2_2"):
        own = op.simulate(scenario, local_planner=preset, seed=0, time_limit=12.0)
        prog = op.simulate(scenario, local_planner=solver, local_program=preset, seed=0, time_limit=12.0)
        assert np.array_equal(np.asarray(own.trajectory), np.asarray(prog.trajectory)), (preset, scenario)
        assert own.status == prog.status


def test_the_program_describes_the_preset():
    sc = op.load_scenario("hou2024_dynamic1")
    prog = op.local_program("missa-dwa", sc.robot, sc.dt, weights={"heading": 0.3})
    assert isinstance(prog, PresetProgram) and prog.K == 1 and prog.horizon == 3.0
    weights = {t.name: w for w, t in prog.objective}
    assert weights == {"heading": 0.3, "velocity": 0.2, "static_inverse": 0.15, "dynamic_inverse": 0.25,
                       "path_deviation": 0.3}
    assert all(isinstance(t, CriticTerm) for _, t in prog.objective)
    assert "adaptive_velocity" in prog.mechanisms and "missa-dwa" in prog.describe()


def _step(planner, sc):
    """One control step of ``planner`` at the start of scenario ``sc`` with a mover ahead."""
    path = np.array([sc.start[:2], sc.goal])
    state = RobotState(float(sc.start[0]), float(sc.start[1]), float(sc.start[2]), 0.3, 0.0)
    planner.reset(state, path)
    return LocalContext(state=state, subgoal=np.asarray(sc.goal, float), goal=np.asarray(sc.goal, float),
                       global_path=path, static_distance=lambda P: np.full(np.shape(P)[:-1], 5.0),
                       dynamic=np.array([[state.x + 2.0, state.y + 0.3, -0.2, 0.0, 0.2]]), dt=sc.dt)


@pytest.mark.parametrize("preset", ["dwa", "missa-dwa", "iga-dwa", "ba-dwa"])
def test_the_sampled_choice_is_the_programs_least_cost(preset):
    """The chosen sample is the least-cost candidate under the program's terms (each critic
    normalised over the step's candidates), and the step reports that cost."""
    sc = op.load_scenario("hou2024_dynamic1")
    planner = make_local_planner(preset, sc.robot, sc.dt)
    ctx = _step(planner, sc)
    win = planner.window(ctx)
    step = planner.evaluate(ctx, win)
    best, info = planner.choose(step)
    assert info["mode"] == "sample" and info["violation"] == 0.0
    cand = step.admissible & step.mover_free
    from optplan.local.program_planners import situation_of

    sit = situation_of(ctx)
    sit.samples = SampleSet(step, cand, np.ones(step.roll.n, bool))
    cost = sum(w * t.batched(None, None, sit, planner.program) for w, t in planner.program.objective)
    assert int(np.argmin(np.where(cand, cost, np.inf))) == best
    assert cost[best] == pytest.approx(info["cost"], rel=1e-12, abs=1e-15)
    cmd = planner.command(ctx)
    assert cmd.info["status"] == "sampled" and cmd.info["solve_ms"] >= 0


def test_a_term_added_to_a_presets_program_steers_its_sampler():
    """missa-dwa's program with a term preferring one side of the block passes it on that side."""
    sc = op.load_scenario(SCENARIO)
    sides = {}
    for sign in (1.0, -1.0):
        prog = op.local_program("missa-dwa", sc.robot, sc.dt)
        prog.add(0.01 * LT.custom(lambda Z, U, m, s=sign: -s * m.mean(Z[:, 1] - 1.75), "prefer_side"))
        r = op.simulate(sc, local_planner="dwa", local_program=prog, seed=0, subgoals="goal")
        assert r.reached and r.collisions == 0, r.message
        T = np.asarray(r.trajectory)
        sides[sign] = T[np.argmin(np.abs(T[:, 1] - 4.0)), 2]
    assert sides[1.0] > 1.75 + 0.3 and sides[-1.0] < 1.75 - 0.3, sides


def test_preset_programs_refuse_what_they_cannot_do():
    sc = op.load_scenario("hou2024_dynamic1")
    with pytest.raises(op.ParameterError, match="symbolic view"):
        make_local_planner("mpc", sc.robot, sc.dt, local_program="idwa")
    with pytest.raises(op.ParameterError, match="solved by 'dwa'"):
        make_local_planner("qp-dwa", sc.robot, sc.dt, local_program="idwa")
    prog = op.local_program("idwa", sc.robot, sc.dt)
    with pytest.raises(op.ParameterError, match="add terms"):
        prog.minimize(LT.speed())
    with pytest.raises(op.ParameterError, match="another robot or control period"):
        make_local_planner("dwa", sc.robot, 0.2, local_program=prog)
    with pytest.raises(op.ParameterError, match="presets are named programs"):
        op.local_program("idwaa", sc.robot, sc.dt)
    with pytest.raises(op.ParameterError, match="unknown parameter"):
        op.local_program("idwa", sc.robot, sc.dt, n_vv=3)
    with pytest.raises(op.ParameterError, match="sampling solver"):
        prog.evaluate(_situation_without_samples(sc), np.zeros((1, 1, 3)))


def _situation_without_samples(sc):
    from optplan.formulations.local_program import Situation

    return Situation(state=np.zeros(6), subgoal=np.asarray(sc.goal, float), path=np.array([sc.start[:2], sc.goal]),
                     static_distance=lambda P: np.full(np.shape(P)[:-1], 5.0))
