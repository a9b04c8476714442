"""Simulator: kinematics, sensing, exact collision counting, metrics, reproducibility, CLI."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

import optplan as op
from optplan.errors import ParameterError
from optplan.sim import SimEnvironment, step_pose
from optplan.world.robot import Command
from optplan.world.scenario import load_scenario
from optplan.worldgen.scenarios import realize


class GoToSubgoal:
    """Test double of a local planner: turn towards the subgoal, drive when facing it,
    within the speed and acceleration limits (ignores obstacles)."""

    name = "goto"

    def __init__(self, robot, dt):
        self.robot, self.dt = robot, dt

    def reset(self, state, path):
        self.calls = 0

    def command(self, ctx):
        s, r, dt = ctx.state, self.robot, self.dt
        d = ctx.subgoal - np.array([s.x, s.y])
        err = (math.atan2(d[1], d[0]) - s.theta + math.pi) % (2 * math.pi) - math.pi
        w = float(np.clip(2.0 * err, max(-r.w_max, s.w - r.alpha_max * dt), min(r.w_max, s.w + r.alpha_max * dt)))
        v_target = r.v_max * max(0.0, math.cos(err)) ** 4
        v = float(np.clip(v_target, max(0.0, s.v - r.a_max * dt), min(r.v_max, s.v + r.a_max * dt)))
        return Command(v, w)


class Replay:
    """Plays a fixed command list, then stands still."""

    name = "replay"

    def __init__(self, commands):
        self.commands = list(commands)

    def reset(self, state, path):
        self.k = 0

    def command(self, ctx):
        self.k += 1
        return self.commands[self.k - 1] if self.k <= len(self.commands) else Command(0.0, 0.0)


FAST = {"w_max_deg": 120, "alpha_max_deg": 360, "a_max": 1.0}


def open_room(**over):
    d = {"map": [[0] * 10 for _ in range(6)], "start": [0.5, 0.5, 0], "goal": [9.5, 5.5], "robot": dict(FAST)}
    d.update(over)
    return load_scenario(d)


# --------------------------------------------------------------------- kinematics
def test_unicycle_steps_follow_the_closed_form_of_eq_14_18():
    v, w, dt, n, th0 = 0.8, 0.5, 0.1, 37, 0.3
    x, y, th = 1.0, 2.0, th0
    for _ in range(n):
        x, y, th = step_pose("unicycle", x, y, th, v, w, dt)
    phi = w * dt  # heading increment; the sum of cos/sin over an arithmetic sequence is closed form
    scale = v * dt * math.sin(n * phi / 2) / math.sin(phi / 2)
    mid = th0 + (n - 1) * phi / 2
    assert x == pytest.approx(1.0 + scale * math.cos(mid), abs=1e-12)
    assert y == pytest.approx(2.0 + scale * math.sin(mid), abs=1e-12)
    assert th == pytest.approx((th0 + n * phi + math.pi) % (2 * math.pi) - math.pi)
    # straight motion and broadcasting over samples
    X, Y, T = step_pose("unicycle", np.zeros(3), np.zeros(3), np.array([0, math.pi / 2, math.pi]), 2.0, 0.0, 0.5)
    assert np.allclose(np.c_[X, Y], [[1, 0], [0, 1], [-1, 0]])


def test_omni_model_of_hou2024_eq_19_slides_sideways():
    x, y, th = step_pose("omni", 0.0, 0.0, math.pi / 2, 0.0, 0.0, 1.0, vy=0.5)
    assert (x, y) == pytest.approx((-0.5, 0.0))  # facing +y, "left" is -x
    x, y, th = step_pose("omni", 0.0, 0.0, 0.0, 1.0, 0.2, 0.5, vy=1.0)
    assert (x, y, th) == pytest.approx((0.5, 0.5, 0.1))
    with pytest.raises(ParameterError):
        step_pose("tank", 0, 0, 0, 1, 0, 0.1)


def test_simulated_robot_moves_by_the_model_with_recorded_rows():
    sc = open_room(time_limit=1.0)
    cmds = [Command(0.5, 0.4)] * 10
    res = op.simulate(sc, local_planner=Replay(cmds), subgoals="goal")
    x, y, th = 0.5, 0.5, 0.0
    for k in range(10):
        x, y, th = step_pose("unicycle", x, y, th, 0.5, 0.4, 0.1)
        assert np.allclose(res.trajectory[k + 1], [(k + 1) * 0.1, x, y, th, 0.5, 0.4])
    assert res.status == "timeout" and not res.reached and res.steps == 10
    assert res.max_abs_accel == pytest.approx(5.0)  # 0 -> 0.5 m/s in one period
    assert res.max_abs_ang_accel == pytest.approx(4.0)


# ----------------------------------------------------------------------- sensing
def test_unknown_obstacle_is_invisible_until_in_sensor_range():
    sc = open_room(unknown_obstacles=[{"cells": [[6, 0]]}], sensor_range=2.0)
    env = SimEnvironment(sc)
    probe = np.array([[6.5, 0.5], [5.8, 0.5]])
    before = env.static_distance(probe)
    assert before[0] > 0.4  # the known map is empty there
    assert not env.sense(np.array([0.5, 0.5]))       # 5.5 m away: not seen
    assert np.allclose(env.static_distance(probe), before)
    assert not env.sense(np.array([3.9, 0.5]))       # 2.1 m from the cell's edge
    assert env.sense(np.array([4.0, 0.5]))           # exactly 2.0 m: seen
    after = env.static_distance(probe)
    assert after[0] == pytest.approx(-0.5) and after[1] == pytest.approx(0.2)
    assert env.sensed_cell_indices.tolist() == [[6, 0]]
    assert env.believed_world().occ[0, 6] and not sc.world.occ[0, 6]
    assert not env.sense(np.array([4.0, 0.5]))       # nothing new the second time


def test_moving_obstacles_are_reported_only_in_range():
    sc = open_room(dynamic_obstacles=[{"radius": 0.5, "start": [8.0, 3.0], "velocity": [-1.0, 0.0], "at_border": "pass"}],
                   sensor_range=3.0)
    env = SimEnvironment(sc)
    rows = env.movers(1.0)
    assert np.allclose(rows, [[7.0, 3.0, -1.0, 0.0, 0.5]])
    assert len(env.sensed_movers(np.array([0.5, 0.5]), rows)) == 0
    assert len(env.sensed_movers(np.array([4.0, 3.0]), rows)) == 1


# -------------------------------------------------------------------- collisions
def brute_static_hits(P, box_lo, box_hi, r, n=2001):
    """Reference: dense sampling of each segment against a box (no shared code)."""
    hits = []
    for a, b in zip(P[:-1], P[1:]):
        s = np.linspace(0, 1, n)[:, None]
        q = a + s * (b - a)
        gap = np.maximum(np.maximum(box_lo - q, q - box_hi), 0)
        hits.append(bool((np.hypot(gap[:, 0], gap[:, 1]) < r).any()))
    return np.array(hits)


def test_deliberate_collisions_are_counted_by_the_exact_swept_check():
    # a wall cell (4, 0) ahead of the robot; drive through it and out again
    rows = [[0] * 10 for _ in range(6)]
    rows[5][4] = 1
    sc = load_scenario({"map": rows, "start": [0.52, 0.5, 0], "goal": [9.5, 5.5], "robot": dict(FAST),
                        "time_limit": 3.0})
    res = op.simulate(sc, local_planner=Replay([Command(3.0, 0.0)] * 30), subgoals="goal")
    P = res.trajectory[:, 1:3]
    want = brute_static_hits(P, np.array([4.0, 0.0]), np.array([5.0, 1.0]), 0.2)
    assert want.sum() >= 3
    assert res.collisions == int(want.sum())
    assert res.min_clearance < 0


def test_a_mover_crossing_a_waiting_robot_is_a_collision_and_swept_between_samples():
    # the mover passes through the robot within one period: only the swept test sees it
    sc = open_room(dynamic_obstacles=[{"radius": 0.1, "start": [0.5, 5.0], "velocity": [0.0, -40.0],
                                       "at_border": "pass"}], time_limit=0.5)
    res = op.simulate(sc, local_planner=Replay([]), subgoals="goal")
    rows = SimEnvironment(realize(sc, 0)).movers
    ys = [rows(t)[0, 1] for t in res.trajectory[:, 0]]
    assert all(abs(y - 0.5) > 0.3 for y in ys)  # no sampled instant overlaps
    assert res.collisions == 1 and res.min_clearance < 0


def test_goal_reached_without_collisions_and_metrics_in_limits():
    sc = open_room(unknown_obstacles=[{"cells": [[4, 3]]}])
    res = op.simulate(sc, local_planner=GoToSubgoal(sc.robot, sc.dt))
    assert res.reached and res.status == "reached" and res.collisions == 0
    assert np.hypot(*(res.trajectory[-1, 1:3] - sc.goal)) <= sc.goal_tolerance
    assert res.max_abs_accel <= sc.robot.a_max + 1e-9
    assert res.max_abs_ang_accel <= sc.robot.alpha_max + 1e-9
    assert res.min_clearance > 0
    assert res.path_length == pytest.approx(np.hypot(*np.diff(res.trajectory[:, 1:3], axis=0).T).sum())
    assert res.time_s == pytest.approx(res.steps * sc.dt)


def test_same_seed_gives_identical_result_and_other_seeds_differ():
    sc = load_scenario({"map": "li2023_11", "start": [0.5, 0.5, 0], "goal": [10.5, 10.5], "robot": dict(FAST),
                        "random_obstacles": {"count": 1},
                        "random_dynamic": {"count": 2, "speed": [0.3, 0.6], "length": [3, 5]}})
    runs = [op.simulate(sc, local_planner=GoToSubgoal(sc.robot, sc.dt), seed=s) for s in (4, 4, 5)]
    a, b, c = (r.to_dict() for r in runs)
    for d in (a, b, c):   # wall times
        d.pop("mean_step_ms")
        d.pop("reroute_s")
    assert a == b
    assert a != c


def test_stuck_robot_replans_then_gives_up():
    sc = open_room(time_limit=100.0)
    res = op.simulate(sc, local_planner=Replay([]), subgoals="goal", stuck_time=2.0, max_replans=2)
    assert res.status == "stuck" and not res.reached and res.replans == 2
    assert res.time_s < 10


def test_unknown_option_and_unknown_local_planner():
    sc = open_room()
    with pytest.raises(ParameterError, match="unknown simulate option"):
        op.simulate(sc, local_planner=Replay([]), warp_speed=True)
    # a shortened parameter name is pointed at the one meant, not just listed as unknown
    with pytest.raises(ParameterError, match=r"'local' \(did you mean 'local_planner'\?\)"):
        op.simulate(sc, local="dwa")
    with pytest.raises(op.UnknownAlgorithmError):
        op.simulate(sc, local_planner="no-such-planner")


def test_cli_json_has_exactly_the_contract_keys(tmp_path, capsys, monkeypatch):
    import optplan.sim.closed_loop as loop
    from optplan.cli import main

    monkeypatch.setattr(loop, "make_planner", lambda name, robot, dt, params: GoToSubgoal(robot, dt))
    f = tmp_path / "s.yaml"
    f.write_text("map: li2023_11\nstart: [0.5, 0.5, 0]\ngoal: [2.5, 0.5]\n"
                 "robot: {w_max_deg: 120, alpha_max_deg: 360, a_max: 1.0}\n")
    gif = tmp_path / "run.gif"
    assert main(["simulate", str(f), "--local", "dwa", "--json", "--seed", "1", "--gif", str(gif)]) == 0
    out = json.loads(capsys.readouterr().out)
    # DESIGN.md's keys first, in its order, then the ones optplan adds
    assert list(out) == ["reached", "collisions", "time_s", "path_length", "min_clearance", "max_abs_accel",
                         "max_abs_ang_accel", "steps", "mean_step_ms", "trajectory",
                         "status", "message", "seed", "global_path"]
    assert out["reached"] is True and len(out["trajectory"]) == out["steps"] + 1
    assert len(out["trajectory"][0]) == 6
    assert out["status"] == "reached" and out["seed"] == 1 and out["message"]
    assert out["global_path"][0] == [0.5, 0.5] and out["global_path"][-1] == [2.5, 0.5]
    assert gif.stat().st_size > 1000 and gif.read_bytes()[:3] == b"GIF"


@pytest.mark.parametrize("as_json", [True, False])
def test_cli_exits_1_when_the_goal_is_missed(tmp_path, capsys, monkeypatch, as_json):
    # a robot that never moves times out: the outcome is printed, and the exit status says so
    import optplan.sim.closed_loop as loop
    from optplan.cli import EXIT_GOAL_MISSED, main

    monkeypatch.setattr(loop, "make_planner", lambda name, robot, dt, params: Replay([]))
    f = tmp_path / "s.yaml"
    f.write_text("map: li2023_11\nstart: [0.5, 0.5, 0]\ngoal: [2.5, 0.5]\ntime_limit: 1.0\n")
    status = main(["simulate", str(f), "--seed", "4"] + (["--json"] if as_json else []))
    assert status == EXIT_GOAL_MISSED == 1
    out = capsys.readouterr().out
    if as_json:
        d = json.loads(out)
        assert d["reached"] is False and d["status"] == "timeout" and d["seed"] == 4 and "time limit" in d["message"]
    else:
        assert "status         timeout" in out


def test_omni_robot_slides_sideways_in_the_loop():
    sc = open_room(robot={"model": "omni", "radius": 0.2, "vy_max": 0.5, "a_max": 10.0}, start=[2.5, 0.5, 90],
                   time_limit=1.0)
    res = op.simulate(sc, local_planner=Replay([Command(0.0, 0.0, vy=-0.5)] * 10), subgoals="goal")
    # facing +y, a negative sideways speed moves the robot towards +x
    assert np.allclose(res.trajectory[-1, 1:4], [3.0, 0.5, math.pi / 2])
    assert res.max_abs_accel == pytest.approx(5.0)  # the sideways change counts as acceleration


def test_circle_world_scenario_with_an_unknown_disc():
    sc = load_scenario({"map": "yang2023_env1", "start": [0.6, 0.6, 0], "goal": [9.4, 9.4],
                        "robot": dict(FAST), "unknown_obstacles": [{"circle": [4.5, 0.6, 0.3]}]})
    env = SimEnvironment(sc)
    centre = np.array([4.5, 0.6])
    assert env.static_distance(centre) > 0.5 and not env.sense(np.array([0.6, 0.6]))
    assert env.sense(np.array([1.3, 0.6]))
    assert env.static_distance(centre) == pytest.approx(-0.3)
    # straight through the unknown disc: the swept check counts it
    res = op.simulate(sc, local_planner=Replay([Command(1.0, 0.0)] * 60), subgoals="goal", time_limit=6.0)
    d = np.hypot(*(res.trajectory[:, 1:3] - centre).T)
    assert res.collisions >= int((d < 0.5).sum()) - 1 > 0
    # the obstacle-blind test double needs a roomy path: plan with twice the radius
    ok = op.simulate(sc, local_planner=GoToSubgoal(sc.robot, sc.dt), global_options={"clearance": 0.4})
    assert ok.reached and ok.collisions == 0 and ok.global_planner == "visibility"


def test_a_non_finite_command_is_reported_not_simulated():
    with pytest.raises(ParameterError, match="non-finite command"):
        op.simulate(open_room(), local_planner=Replay([Command(float("nan"), 0.0)]), subgoals="goal")


def test_stop_on_collision_and_actuator_limits():
    rows = [[0] * 10 for _ in range(6)]
    rows[5][4] = 1
    sc = load_scenario({"map": rows, "start": [0.52, 0.5, 0], "goal": [9.5, 5.5], "robot": dict(FAST),
                        "time_limit": 3.0})
    res = op.simulate(sc, local_planner=Replay([Command(3.0, 0.0)] * 30), subgoals="goal", stop_on_collision=True)
    assert res.status == "collision" and res.collisions == 1 and not res.reached
    P = res.trajectory[:, 1:3]
    hits = brute_static_hits(P, np.array([4.0, 0.0]), np.array([5.0, 1.0]), 0.2)
    assert hits[-1] and not hits[:-1].any()  # it stopped on the first colliding period
    # with actuator limits the 3 m/s request becomes a ramp at a_max up to v_max
    lim = op.simulate(sc, local_planner=Replay([Command(3.0, 2.0)] * 5), subgoals="goal", actuator_limits=True,
                      time_limit=0.5)
    assert np.allclose(lim.trajectory[1:, 4], [0.1, 0.2, 0.3, 0.4, 0.5])
    assert lim.max_abs_accel == pytest.approx(sc.robot.a_max)
    assert lim.max_abs_ang_accel == pytest.approx(sc.robot.alpha_max)


def test_path_switches_are_a_result_field():
    """yuan2021 §4.2: the added obstacles block the global path twice; the run reports both
    switches in ``SimResult.path_switches`` (and counts them among the re-plans)."""
    from optplan.sim.experiments import path_switches

    res = op.simulate("yuan2021_path_switch", local_planner="ba-dwa", seed=0, time_limit=160)
    assert res.path_switches == 2 and res.replans >= res.path_switches
    assert path_switches(res) == 2 and "2 path switch" in res.message
    # each answer to the blocked path is timed (yuan2021 §4.2's switch-vs-re-plan claim reads it)
    assert isinstance(res.reroute_s, float)
    ignored = op.simulate("yuan2021_path_switch", local_planner="ba-dwa", seed=0, time_limit=20, on_blocked="ignore")
    assert ignored.reroute_s is None and ignored.path_switches == 0


def test_a_blocked_path_is_re_planned_by_the_global_planner_when_asked():
    """``replanner="global"``: a blocked path is planned again by the run's global planner with its
    options (yuan2021 §4.2 runs IBA again); the default and stuck recovery use exact search."""
    from optplan.nav.navigator import Navigator

    sc = op.load_scenario("yuan2021_path_switch")
    nav = Navigator(sc.world, sc.robot, sc.start[:2], sc.goal, global_planner="iba",
                    global_options={"encoding": "paper", "pop": 20, "iters": 20}, replanner="global")
    nav.plan_initial()
    pos = np.asarray(sc.start[:2], float) + [0.4, 0.4]
    ladder = nav.clearance_ladder(sc.robot.radius)
    by_iba = nav._plan_from(sc.world, pos, ladder, "global")
    assert by_iba.algorithm == "iba" and by_iba.feasible
    assert nav._plan_from(sc.world, pos, ladder).algorithm == "astar"
    with pytest.raises(op.ParameterError, match="replanner"):
        op.simulate("yuan2021_path_switch", local_planner="ba-dwa", replanner="ibaa")


def test_a_mover_on_a_zero_length_loop_is_seen_and_hit():
    # waypoints [[5, 3], [5, 3]] with speed > 0 once gave the mover a NaN position: the robot drove
    # through it and the run said reached, 0 collisions. It stands still now, in the robot's way.
    sc = open_room(start=[0.5, 3.0, 0], goal=[9.5, 3.0],
                   dynamic_obstacles=[{"radius": 0.4, "waypoints": [[5, 3], [5, 3]], "speed": 1.0}])
    assert np.allclose(SimEnvironment(sc).movers(3.0), [[5.0, 3.0, 0.0, 0.0, 0.4]])
    res = op.simulate(sc, local_planner=GoToSubgoal(sc.robot, sc.dt), subgoals="goal")  # ignores obstacles
    assert res.collisions > 0 and res.min_clearance < 0


def test_a_non_finite_mover_position_stops_the_run_instead_of_hiding_the_mover(monkeypatch):
    from optplan.errors import ScenarioError
    from optplan.world.scenario import DynamicObstacle

    sc = open_room(dynamic_obstacles=[{"radius": 0.4, "waypoints": [[5, 3], [6, 3]], "speed": 1.0}])
    monkeypatch.setattr(DynamicObstacle, "state", lambda self, t, bounds: (np.full(2, np.nan), np.zeros(2)))
    # the simulator tabulates its movers at the control instants through states()
    monkeypatch.setattr(DynamicObstacle, "states",
                        lambda self, t, bounds: (np.full((len(t), 2), np.nan), np.zeros((len(t), 2))))
    with pytest.raises(ScenarioError, match="dynamic obstacle 0"):
        op.simulate(sc, local_planner=Replay([]), subgoals="goal")
    env = SimEnvironment(open_room())
    with pytest.raises(ParameterError, match="non-finite"):
        env.moving_gap(np.zeros(2), np.ones(2), np.array([[np.nan, 1.0, 0, 0, 0.3]]), np.array([[1.0, 1.0, 0, 0, 0.3]]))
    with pytest.raises(ParameterError, match="non-finite"):
        env.static_check(np.array([[0.5, 0.5], [np.nan, 0.5]]))


def test_the_movers_table_equals_each_movers_closed_form_at_every_control_instant():
    from dataclasses import replace

    from optplan.world.scenario import DynamicObstacle
    from optplan.worldgen.scenarios import realize

    movers = [DynamicObstacle(0.3, start=np.array([5.0, 5.0]), velocity=np.array([0.7, -0.4]), at_border=m)
              for m in ("bounce", "stop", "pass")]
    movers += [DynamicObstacle(0.3, waypoints=np.array([[1, 1], [1, 1], [4, 1], [4, 3]], float), speed=0.5,
                               loop=loop, phase=0.3) for loop in (True, False)]
    for sc in (realize(load_scenario("li2023_exp2_3"), 3),
               replace(load_scenario("yang2023_idwa_crossing"), dynamic=movers, timing_jitter=0.0)):
        env = SimEnvironment(sc)
        for k in range(0, int(sc.time_limit / sc.dt) + 1, 7):
            t = k * sc.dt
            exact = np.array([[*ob.state(t, env.bounds)[0], *ob.state(t, env.bounds)[1], ob.radius]
                              for ob in sc.dynamic])
            assert np.array_equal(env.movers(t), exact), (sc.name, k)
        off_grid = 0.05
        assert np.array_equal(env.movers(off_grid)[:, :2],
                              np.array([ob.state(off_grid, env.bounds)[0] for ob in sc.dynamic]))


def test_mover_motion_option_sets_the_random_movers_motion_or_says_why_not():
    from optplan.sim.closed_loop import realized_scenario

    plan = op.plan(load_scenario("li2023_exp2_2").world, (0.5, 0.5), (9.5, 9.5), algorithm="astar", clearance=0.2)
    shuttle = realized_scenario("li2023_exp2_2", 3, plan).dynamic
    once = realized_scenario("li2023_exp2_2", 3, plan, mover_motion="once").dynamic
    assert all(m.loop for m in shuttle) and not any(m.loop for m in once)
    res = op.simulate("li2023_exp2_2", global_planner="astar", local_planner="dwa", seed=3, global_plan=plan,
                      mover_motion="once", time_limit=1.0)
    assert res.status == "timeout"
    with pytest.raises(ParameterError, match="mover_motion must be one of"):
        op.simulate("li2023_exp2_2", local_planner="dwa", mover_motion="twice", time_limit=1.0)
    with pytest.raises(ParameterError, match="no random movers"):
        op.simulate("li2023_exp1", local_planner="dwa", mover_motion="once", time_limit=1.0)
