"""Issue 27: qp-dwa's path creep - after a stall, straight checked legs along the global path
through gaps a centimetre wider than the robot, which the sampled window stops in front of."""
from __future__ import annotations

import math

import numpy as np
import pytest

import optplan as op
from optplan.local import make_local_planner
from optplan.local.base import LocalContext
from optplan.local.creep import PathCreep
from optplan.local.hooks import PlannerView
from optplan.local.window import dynamic_window
from optplan.world.grid import GridMap
from optplan.world.robot import RobotState
from optplan.world.scenario import Scenario
from optplan.worldgen.clutter import BARN_ROBOT

RES = 0.15


def diagonal_gap_world() -> GridMap:
    """Two blocks whose facing corners are 2 x 2 cells apart: the only way from left to right
    is the diagonal gap between them, 0.424 m wide for a 0.4 m robot (1.2 cm each side)."""
    occ = np.zeros((22, 30), dtype=bool)
    occ[0:10, 10:12] = True    # lower block, top-right corner at cell corner (12, 10)
    occ[12:22, 14:16] = True   # upper block, bottom-left corner at (14, 12)
    return GridMap(occ[::-1], RES)  # rows top first, as a map file


def lane_beside_a_wall() -> GridMap:
    """Open ground with a wall whose top edge is at y = 1.2 m: a robot on the lane y = 1.5 m
    stands 0.1 m (edge to edge) from it, near enough for the creep to start."""
    occ = np.zeros((20, 40), dtype=bool)
    occ[7, :] = True                 # rows bottom first here: the wall spans y 1.05-1.2 m
    return GridMap(occ[::-1], RES)


def gap_scenario() -> Scenario:
    return Scenario(diagonal_gap_world(), BARN_ROBOT, np.array([0.6, 2.4, 0.0]), np.array([3.9, 0.6]),
                    sensor_range=2.5, dt=0.1, time_limit=60.0, goal_tolerance=0.2, name="diagonal-gap")


def modes_of(scenario, **kwargs) -> tuple[op.SimResult, list]:
    modes = []

    def record(t, state, info):
        modes.append((info["command"].info.get("mode"), state.x, state.y))

    res = op.simulate(scenario, local_planner="qp-dwa", seed=0, progress=record, **kwargs)
    return res, modes


def test_the_gap_world_is_passable_only_by_the_diagonal_gap():
    g = diagonal_gap_world()
    corner_gap = math.hypot(2 * RES, 2 * RES)
    assert corner_gap / 2 - BARN_ROBOT.radius == pytest.approx(0.0121, abs=1e-4)
    path = op.shortest_path(g, (0.6, 2.4), (3.9, 0.6), method="astar", clearance=BARN_ROBOT.radius)
    assert path.feasible
    with pytest.raises(op.OptplanError):
        op.shortest_path(g, (0.6, 2.4), (3.9, 0.6), method="astar", clearance=BARN_ROBOT.radius + 0.0125)


# the window's static margin (the field's error bound plus swept_margin) made wider than the
# gap's 1.2 cm to spare, so the sampled window cannot take the gap and the creep must
NARROW = {"swept_margin": 0.01}


def test_qp_dwa_creeps_through_a_gap_a_centimetre_wider_than_the_robot_without_touching_it():
    res, modes = modes_of(gap_scenario(), planner_params={"path_creep": {}, **NARROW})
    assert res.reached and res.collisions == 0, res.message
    assert res.min_clearance > 0.0
    crept = [(x, y) for m, x, y in modes if m == "creep-drive"]
    assert crept, "the sampled window alone should not be what passed the gap"
    # the creep drove through the gap itself (between the corners at x 1.8 and 2.1 m)
    assert any(1.8 <= x <= 2.1 for x, _ in crept)
    assert res.max_abs_accel <= BARN_ROBOT.a_max * (1 + 1e-6)
    assert res.max_abs_ang_accel <= BARN_ROBOT.alpha_max * (1 + 1e-6)


def test_without_the_creep_the_sampled_window_stops_in_front_of_that_gap():
    # the creep turned off (qp-dwa's default has it where the global path is tight, as here)
    res, _ = modes_of(gap_scenario(), planner_params={"path_creep": False, **NARROW})
    assert res.status == "timeout" and not res.reached and res.collisions == 0


def test_on_the_distance_field_alone_the_creep_keeps_its_error_margin_and_never_collides():
    # without the exact segment rule a leg must keep the field's error bound too; the field
    # underestimates the clearance at this gap, so the robot may not get through, but it must
    # never drive a leg closer than the robot radius
    planner = make_local_planner("qp-dwa", BARN_ROBOT, 0.1, path_creep=True)
    off = make_local_planner("qp-dwa", BARN_ROBOT, 0.1, path_creep=False)
    assert not any(isinstance(m, PathCreep) for m in off.mechanisms)
    creep = next(m for m in planner.mechanisms if isinstance(m, PathCreep))
    g = diagonal_gap_world()
    exact = g.clearance
    ctx = LocalContext(state=RobotState(1.3, 1.9, -0.6), subgoal=np.array([3.9, 0.6]), goal=np.array([3.9, 0.6]),
                       global_path=np.array([[1.3, 1.9], [1.95, 1.65], [2.4, 1.2], [3.9, 0.6]]),
                       static_distance=exact, dynamic=np.zeros((0, 5)), dt=0.1, distance_error=0.0045)
    view = PlannerView(BARN_ROBOT, 0.1, planner.options)
    need = creep.required_gap(view, ctx)
    assert need == pytest.approx(BARN_ROBOT.radius + creep.clearance + 0.0045 + 0.0025)
    ends = np.array([1.95 + 1.65j, 2.4 + 1.2j])
    ok = creep.legs_free(ctx, complex(1.3, 1.9), ends, need)
    for end, free in zip(ends, ok):
        z = np.linspace(complex(1.3, 1.9), end, 400)
        if free:
            assert exact(np.stack([z.real, z.imag], axis=1)).min() >= BARN_ROBOT.radius


def test_the_creep_waits_for_a_stall_and_leaves_waiting_among_movers_to_the_sampler():
    creep = PathCreep(stall_time=0.3)
    view = PlannerView(BARN_ROBOT, 0.1, {})
    g = lane_beside_a_wall()
    state = RobotState(1.0, 1.5, 0.0)
    path = np.array([[1.0, 1.5], [5.0, 1.5]])
    creep.reset(view, state, path)

    def ctx(dynamic):
        return LocalContext(state=state, subgoal=path[-1], goal=path[-1], global_path=path,
                            static_distance=g.clearance, dynamic=dynamic, dt=0.1,
                            segments_free=lambda a, b, c: g.segments_free(a, b, c))

    win = dynamic_window(BARN_ROBOT, state, 0.1)
    mover = np.array([[1.6, 1.5, 0.0, 0.0, 0.15]])
    for _ in range(5):  # stood long enough, but a mover stands on the path ahead
        assert creep.override(view, ctx(mover), win) is None
    assert creep.override(view, ctx(np.zeros((0, 5))), win) is None  # the stall count restarted
    took = [creep.override(view, ctx(np.zeros((0, 5))), win) for _ in range(3)]
    assert took[-1] is not None and took[-1][2]["mode"] == "creep-drive"
    v, w, info = took[-1]
    assert 0 < v <= creep.speed and w == 0.0


def test_a_robot_held_in_a_movers_way_creeps_out_of_it_at_once_but_not_towards_it():
    """Standing on a lane a mover comes along: the creep takes over at once (no stall wait)
    when driving on along the path keeps the robot ahead of the mover, and stays out when
    the mover comes from ahead, where driving on would meet it sooner."""
    view = PlannerView(BARN_ROBOT, 0.1, {})
    g = lane_beside_a_wall()
    state = RobotState(1.0, 1.5, 0.0)
    path = np.array([[1.0, 1.5], [5.0, 1.5]])
    win = dynamic_window(BARN_ROBOT, state, 0.1)

    def first_command(mover):
        creep = PathCreep()
        creep.reset(view, state, path)
        ctx = LocalContext(state=state, subgoal=path[-1], goal=path[-1], global_path=path,
                           static_distance=g.clearance, dynamic=np.array([mover]), dt=0.1,
                           segments_free=lambda a, b, c: g.segments_free(a, b, c))
        return creep, creep.override(view, ctx, win)

    creep, took = first_command([0.3, 1.5, 0.3, 0.0, 0.15])     # from behind, 0.3 m/s
    moving, standing = creep.mover_gaps(view, LocalContext(
        state=state, subgoal=path[-1], goal=path[-1], global_path=path, static_distance=g.clearance,
        dynamic=np.array([[0.3, 1.5, 0.3, 0.0, 0.15]]), dt=0.1), complex(1.0, 1.5), 1.0, 1.5)
    assert standing < 0 < moving                                  # standing is hit, driving on is not
    assert took is not None and took[2]["mode"] == "creep-drive" and took[0] > 0
    _, took = first_command([2.0, 1.5, -0.3, 0.0, 0.15])           # from ahead
    assert took is None


def test_bad_creep_parameters_say_what_is_wrong():
    with pytest.raises(op.OptplanError, match="path_creep"):
        make_local_planner("qp-dwa", BARN_ROBOT, 0.1, path_creep={"speed": -1.0})
    with pytest.raises(op.OptplanError, match="path_creep"):
        make_local_planner("qp-dwa", BARN_ROBOT, 0.1, path_creep=1.0)
    with pytest.raises(op.OptplanError, match="path_creep"):
        make_local_planner("qp-dwa", BARN_ROBOT, 0.1, path_creep={"nope": 1.0})


def test_the_creep_does_not_start_in_the_open():
    """Standing far from every static obstacle the sampler waits for movers or turns; the
    creep is for clutter and stays out however long the robot stands."""
    creep = PathCreep(stall_time=0.3)
    view = PlannerView(BARN_ROBOT, 0.1, {})
    g = GridMap(np.zeros((20, 40), dtype=bool), RES)
    state = RobotState(1.0, 1.5, 0.0)
    path = np.array([[1.0, 1.5], [5.0, 1.5]])
    creep.reset(view, state, path)
    ctx = LocalContext(state=state, subgoal=path[-1], goal=path[-1], global_path=path,
                       static_distance=g.clearance, dynamic=np.zeros((0, 5)), dt=0.1,
                       segments_free=lambda a, b, c: g.segments_free(a, b, c))
    win = dynamic_window(BARN_ROBOT, state, 0.1)
    assert all(creep.override(view, ctx, win) is None for _ in range(20))


def test_a_steady_turn_on_the_spot_is_not_a_stall_but_three_stall_times_of_standing_are():
    """The window's escape turn (the robot turning steadily on the spot beside a wall) is a way
    out, not a stall: the creep waits. Standing still for ``stall_time`` starts it, and so does
    standing ``3 * stall_time`` in all, however the robot turns."""
    view = PlannerView(BARN_ROBOT, 0.1, {})
    g = lane_beside_a_wall()
    path = np.array([[1.0, 1.5], [5.0, 1.5]])

    def run(headings):
        creep = PathCreep()
        creep.reset(view, RobotState(1.0, 1.5, headings[0]), path)
        for k, theta in enumerate(headings):
            state = RobotState(1.0, 1.5, float(theta))
            ctx = LocalContext(state=state, subgoal=path[-1], goal=path[-1], global_path=path,
                               static_distance=g.clearance, dynamic=np.zeros((0, 5)), dt=0.1,
                               segments_free=lambda a, b, c: g.segments_free(a, b, c))
            if creep.override(view, ctx, dynamic_window(BARN_ROBOT, state, 0.1)) is not None:
                return k
        return None

    turning = 0.5 - 0.05 * np.arange(25)            # 0.5 rad/s for 2.5 s, towards the path
    assert run(turning) is None
    assert run(np.zeros(15)) == 9                   # the tenth period: 1 s standing still
    assert run(0.05 * np.sin(np.arange(40))) == 9   # a jitter is no steady turn
    assert run(3.0 - 0.05 * np.arange(40)) == 29    # 3 s of turning in all
