"""Safety invariants over whole closed-loop runs, checked independently of the simulator.

* the recorded commands respect the robot's acceleration (and jerk, when set) limits,
  recomputed here from the trajectory itself;
* a run that reports no collision has a trajectory that the exact segment rule accepts
  against the *true* static world (known map plus the unknown cells), with the robot
  radius as clearance;
* Ruckig is never handed ``intermediate_positions`` (that would call a remote service).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import ruckig

import optplan as op


class _NoIntermediatePositions(ruckig.InputParameter):
    def __setattr__(self, name, value):
        if name == "intermediate_positions":
            raise AssertionError("Ruckig was given intermediate_positions")
        super().__setattr__(name, value)


@pytest.fixture
def ruckig_spy(monkeypatch):
    from optplan.local import limiter

    monkeypatch.setattr(limiter, "InputParameter", _NoIntermediatePositions)
    made = []
    original = limiter.RuckigLimiter.__init__

    def counting_init(self, *args, **kwargs):
        original(self, *args, **kwargs)
        made.append(type(self._inp))

    monkeypatch.setattr(limiter.RuckigLimiter, "__init__", counting_init)
    return made


def _true_grid(scenario) -> op.GridMap:
    occ = np.array(scenario.world.occ)
    for ix, iy in np.asarray(scenario.unknown_cells, dtype=int).reshape(-1, 2):
        occ[iy, ix] = True
    return op.GridMap(occ, scenario.world.resolution, scenario.world.origin)


@pytest.mark.parametrize("name", ["li2023_exp2_3", "yang2023_idwa_crossing", "yuan2021_added_obstacles"])
def test_qp_dwa_runs_keep_every_limit_and_never_collide_unreported(name, ruckig_spy):
    scenario = op.load_scenario(name)
    robot = replace(scenario.robot, jerk_max=4.0 * scenario.robot.a_max)
    scenario = replace(scenario, robot=robot)
    from optplan.sim.closed_loop import realized_scenario
    from optplan.sim.experiments import plan_global

    plan = plan_global(scenario, "astar", seed=1)
    res = op.simulate(scenario, global_planner="astar", local_planner="qp-dwa", seed=1, time_limit=60.0,
                      global_plan=plan)
    truth = realized_scenario(scenario, 1, plan)  # with the obstacles drawn from the seed
    assert ruckig_spy and all(t is _NoIntermediatePositions for t in ruckig_spy)

    traj = res.trajectory
    dt = scenario.dt
    acc = np.diff(traj[:, 4]) / dt
    ang_acc = np.diff(traj[:, 5]) / dt
    jerk = np.diff(acc) / dt
    assert np.abs(acc).max() <= robot.a_max * (1 + 1e-9)
    assert np.abs(ang_acc).max() <= robot.alpha_max * (1 + 1e-9)
    assert np.abs(jerk).max() <= robot.jerk_max * (1 + 1e-6)
    assert res.max_abs_accel == pytest.approx(np.abs(acc).max(), abs=1e-12)
    assert res.path_length > 1.0  # the robot really drove

    if res.collisions == 0:
        check = op.validate_path(_true_grid(truth), traj[:, 1:3], clearance=robot.radius)
        assert check, f"{name}: the run reports no collision but {check.reason}"
