"""Navigation layer: subgoal strategies, the velocity-obstacle test, path switch, re-planning."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.errors import ParameterError
from optplan.nav import Navigator, VirtualPointGraph, make_strategy, velocity_obstacle_hits
from optplan.world.polyline import point_segment_distances as segment_distance
from optplan.world.robot import RobotSpec


def two_corridor_map() -> op.GridMap:
    """15x9 room split by a wall with two doors (upper and lower corridor)."""
    occ = np.zeros((9, 15), dtype=bool)
    occ[:, 7] = True
    occ[1, 7] = False   # lower door (7, 1)
    occ[7, 7] = False   # upper door (7, 7)
    return op.GridMap(occ)


def test_key_and_turning_points_end_at_the_goal_and_advance_in_order():
    grid = two_corridor_map()
    path = op.shortest_path(grid, (1.5, 3.5), (13.5, 3.5), clearance=0.2).path
    goal = np.array([13.5, 3.5])
    turning = make_strategy("turning_points", 0.2)
    turning.reset(path, grid, goal)
    key = make_strategy("key_points", 0.2, switch_radius=0.5)
    key.reset(path, grid, goal)
    assert np.allclose(turning.targets[-1], goal) and np.allclose(key.targets[-1], goal)
    assert 2 <= len(key.targets) < len(turning.targets)
    # consecutive key points see each other with the robot radius
    chain = np.vstack([path[:1], key.targets])
    assert np.all(grid.segments_free(chain[:-1], chain[1:], 0.2))
    first = key.select(np.array([1.5, 3.5]), np.zeros(2), np.zeros((0, 5)))
    assert np.allclose(first, key.targets[0])
    second = key.select(key.targets[0] + 0.1, np.zeros(2), np.zeros((0, 5)))
    assert np.allclose(second, key.targets[1])
    goal_only = make_strategy("goal", 0.2)
    goal_only.reset(path, grid, goal)
    assert goal_only.targets.tolist() == [goal.tolist()]
    with pytest.raises(op.UnknownAlgorithmError):
        make_strategy("wander", 0.2)


def test_an_obstructed_stage_target_is_skipped():
    s = make_strategy("turning_points", 0.2)
    s.reset(np.array([[0, 0], [2, 0], [2, 2], [4, 2]], float), None, np.array([4.0, 2.0]))
    blocked_at_2_0 = lambda p: np.hypot(*(np.asarray(p) - (2.0, 0.0)).T) - 0.1  # noqa: E731
    assert np.allclose(s.select(np.zeros(2), np.zeros(2), np.zeros((0, 5)), blocked_at_2_0), (2, 2))


def test_a_stage_target_the_robot_went_past_is_not_chased_back():
    """hou2024_dynamic2 seed 9: qp-dwa swerved round a mover 1.5 m from a key point and the
    subgoal stayed on that key point for the remaining 60 s of the run."""
    none = np.zeros((0, 5))

    def fresh():
        s = make_strategy("turning_points", 0.2)
        s.reset(np.array([[0, 0], [2, 0], [2, 2], [4, 2]], float), None, np.array([4.0, 2.0]))
        return s

    # on the next leg, 1.3 m from the corner it cut: the next target
    assert np.allclose(fresh().select(np.array([3.0, 0.8]), np.zeros(2), none), (2, 2))
    # short of the corner, or overshot beyond it but no further along the next leg: still the corner
    assert np.allclose(fresh().select(np.array([1.0, 0.8]), np.zeros(2), none), (2, 0))
    assert np.allclose(fresh().select(np.array([2.9, -0.5]), np.zeros(2), none), (2, 0))


def test_velocity_obstacle_flags_only_collision_courses():
    obstacles = np.array([
        [5.0, 0.0, 0.0, 0.0, 0.5],     # dead ahead, still: hit
        [5.0, 3.0, 0.0, 0.0, 0.5],     # off to the side: miss
        [0.0, 5.0, 0.0, -1.0, 0.5],    # crossing, meets the robot at (5, 0)? no: it comes down x = 0
        [-5.0, 0.0, 0.0, 0.0, 0.5],    # behind: miss
        [5.0, 5.0, 0.0, -1.0, 0.5],    # comes down x = 5 while the robot drives to x = 5: hit
    ])
    hits = velocity_obstacle_hits(np.zeros(2), np.array([1.0, 0.0]), obstacles, 0.2)
    assert hits.tolist() == [True, False, False, False, True]


def test_navigation_points_jump_from_i_plus_n_to_i_plus_kn_on_collision_risk():
    nav = make_strategy("navigation_points", 0.2, spacing=0.25, lookahead_time=1.0, min_lookahead=1.0,
                        avoid_distance=2.0)
    path = np.array([[0.0, 0.0], [20.0, 0.0]])
    nav.reset(path, None, path[-1])
    pos, vel = np.array([5.0, 0.0]), np.array([1.0, 0.0])
    calm = nav.select(pos, vel, np.zeros((0, 5)))
    assert calm == pytest.approx([6.0, 0.0])               # n = 1 m / 0.25 m = 4 points ahead
    far_mover = np.array([[15.0, 0.0, -1.0, 0.0, 0.5]])
    assert nav.select(pos, vel, far_mover) == pytest.approx([6.0, 0.0])  # beyond the avoidance distance
    head_on = np.array([[7.0, 0.0, -1.0, 0.0, 0.5]])
    jumped = nav.select(pos, vel, head_on)
    assert nav.last_k >= 2 and jumped[0] >= 5.0 + 2 * 1.0 - 1e-9
    passing = np.array([[7.0, 1.5, 1.0, 0.0, 0.5]])       # near but moving away in parallel
    assert nav.select(pos, vel, passing) == pytest.approx([6.0, 0.0])


def test_navigation_point_is_no_nearer_than_the_turning_diameter():
    """A point nearer than 2 v / w_max can lie inside the robot's tightest circle (orbited at
    full speed), so the lookahead is at least that; the Navigator hands the robot's w_max over,
    and a caller's subgoal_options may override it."""
    path = np.array([[0.0, 0.0], [20.0, 0.0]])
    bounded = make_strategy("navigation_points", 0.1, w_max=0.5)   # 2 * 1 m/s / 0.5 rad/s = 4 m
    free = make_strategy("navigation_points", 0.1)
    for nav in (bounded, free):
        nav.reset(path, None, path[-1])
    pos, vel = np.array([5.0, 0.0]), np.array([1.0, 0.0])
    assert bounded.select(pos, vel, np.zeros((0, 5))) == pytest.approx([9.0, 0.0])
    assert free.select(pos, vel, np.zeros((0, 5))) == pytest.approx([6.5, 0.0])   # 1.5 s at 1 m/s
    grid = op.GridMap(np.zeros((5, 25), dtype=bool))
    robot = RobotSpec(radius=0.1, w_max=0.5)
    assert Navigator(grid, robot, (0.5, 0.5), (20.5, 0.5), subgoals="navigation_points").strategy.w_max == 0.5
    own = Navigator(grid, robot, (0.5, 0.5), (20.5, 0.5), subgoals="navigation_points",
                    subgoal_options={"w_max": None})
    assert own.strategy.w_max is None


def blocked_upper_corridor(grid: op.GridMap, path: np.ndarray) -> op.GridMap:
    occ = grid.occ.copy()
    occ[6:9, 7] = True   # close the upper door region
    occ[7, 6] = True
    return op.GridMap(occ)


def test_path_switch_finds_the_detour_through_the_other_door():
    grid = two_corridor_map()
    start, goal = np.array([1.5, 7.5]), np.array([13.5, 7.5])
    g = VirtualPointGraph(grid, start, goal, clearance=0.2)
    first = g.route(grid, start)
    assert first is not None and bool(op.validate_path(grid, first, 0.2))
    assert np.max(first[:, 1]) > 6.5 and np.min(first[:, 1]) > 4  # the short way: upper door
    believed = blocked_upper_corridor(grid, first)
    g.update(believed)
    detour = g.route(believed, np.array([3.5, 7.5]))
    assert detour is not None
    assert bool(op.validate_path(believed, detour, 0.2))
    assert np.allclose(detour[0], (3.5, 7.5)) and np.allclose(detour[-1], goal)
    assert np.min(detour[:, 1]) < 2.5  # goes through the lower door (7, 1)


def test_navigator_switches_when_a_sensed_obstacle_blocks_the_path():
    grid = two_corridor_map()
    robot = RobotSpec(radius=0.2)
    nav = Navigator(grid, robot, (1.5, 7.5), (13.5, 7.5), subgoals="turning_points", on_blocked="switch")
    nav.plan_initial()
    believed = blocked_upper_corridor(grid, nav.path)
    assert not nav.on_new_obstacles(grid, np.array([3.5, 7.5]), 1.0)  # nothing new: path still fine
    assert nav.on_new_obstacles(believed, np.array([3.5, 7.5]), 1.0)
    assert nav.switches == 1 and nav.replans == 1
    assert bool(op.validate_path(believed, nav.path, 0.2))
    assert not nav.path_blocked(believed, np.array([3.5, 7.5]))
    # with "replan" the same situation is solved by graph search on the believed map
    nav2 = Navigator(grid, robot, (1.5, 7.5), (13.5, 7.5), on_blocked="replan")
    nav2.plan_initial()
    assert nav2.on_new_obstacles(believed, np.array([3.5, 7.5]), 1.0) and nav2.switches == 0
    assert bool(op.validate_path(believed, nav2.path, 0.2))


def test_a_blocked_path_is_replanned_after_the_stuck_budget_is_spent():
    # a robot that waited out its stuck re-plans (movers crossing) must still go round an
    # obstacle it senses later (hou2024_dynamic4 runs ended 'stuck' against such a cell)
    grid = two_corridor_map()
    nav = Navigator(grid, RobotSpec(radius=0.2), (1.5, 7.5), (13.5, 7.5), on_blocked="replan", max_replans=1)
    nav.plan_initial()
    here = np.array([3.5, 7.5])
    assert nav.recover_stuck(grid, here, 10.0) and not nav.recover_stuck(grid, here, 20.0)
    assert nav.gave_up and nav.stuck_replans == 1
    believed = blocked_upper_corridor(grid, nav.path)
    assert nav.path_blocked(believed, here)
    assert nav.on_new_obstacles(believed, here, 25.0)
    assert bool(op.validate_path(believed, nav.path, 0.2)) and not nav.path_blocked(believed, here)
    assert nav.replans == 2 and nav.stuck_replans == 1

def test_stuck_recovery_plans_round_the_mover_sweeps_it_is_given():
    grid = two_corridor_map()
    start, goal = (3.5, 7.5), (13.5, 7.5)
    nav = Navigator(grid, RobotSpec(radius=0.2), start, goal, max_replans=3)
    nav.plan_initial()
    assert nav.path[:, 1].min() > 6.5  # the short way: the upper door (7, 7)
    # a 0.35 m mover sweeping x = 8.5 from y = 6 to the top wall, just behind the upper door
    sweep = np.array([[8.5, 6.0, 8.5, 9.0, 0.35]])
    here = np.array(start)
    assert nav.recover_stuck(grid, here, 10.0)  # without the sweep: the same way again
    assert nav.path[:, 1].min() > 6.5
    assert nav.recover_stuck(grid, here, 20.0, avoid=sweep)
    assert nav.path[:, 1].min() < 2.5  # round by the lower door
    assert bool(op.validate_path(grid, nav.path, 0.2))
    dense = np.vstack([np.linspace(p, q, 50) for p, q in zip(nav.path[:-1], nav.path[1:])])
    assert segment_distance(dense, sweep[0, :2], sweep[0, 2:4]).min() > 0.35
    assert "round 1 mover sweep" in nav.messages[-1]
    assert nav.stuck_replans == 2 and nav.replans == 2
    # a sweep with no way round (it closes both doors): the plain re-plan is the fallback
    both = np.vstack([sweep, [[8.5, 0.0, 8.5, 3.0, 0.35]]])
    assert nav.recover_stuck(grid, here, 30.0, avoid=both)
    assert nav.path[:, 1].min() > 6.5 and "round" not in nav.messages[-1]


def test_a_learnt_sweep_across_the_path_is_avoided_when_the_way_round_is_short_enough():
    grid = two_corridor_map()
    start, goal = (3.5, 7.5), (13.5, 7.5)
    sweep = np.array([[8.5, 6.0, 8.5, 9.0, 0.35]])  # behind the upper door, as above
    here = np.array(start)
    # the way by the lower door is about 1.4 times as long from here
    refused = Navigator(grid, RobotSpec(radius=0.2), start, goal, sweep_detour=1.2)
    refused.plan_initial()
    assert not refused.on_sweeps(grid, here, 5.0, sweep) and refused.path[:, 1].min() > 6.5
    off = Navigator(grid, RobotSpec(radius=0.2), start, goal, sweep_detour=None)
    off.plan_initial()
    assert not off.on_sweeps(grid, here, 5.0, sweep)
    nav = Navigator(grid, RobotSpec(radius=0.2), start, goal, sweep_detour=2.0)
    nav.plan_initial()
    assert not nav.on_sweeps(grid, here, 5.0, np.zeros((0, 5)))
    assert nav.on_sweeps(grid, here, 5.0, sweep)
    assert nav.path[:, 1].min() < 2.5 and bool(op.validate_path(grid, nav.path, 0.2))
    assert "the path crossed one" in nav.messages[-1] and nav.replans == 1
    assert not nav.on_sweeps(grid, here, 6.0, sweep)  # nothing new learnt: no re-plan
    # a sweep nowhere near the path changes nothing
    far = Navigator(grid, RobotSpec(radius=0.2), start, goal, sweep_detour=2.0)
    far.plan_initial()
    assert not far.on_sweeps(grid, here, 5.0, np.array([[11.0, 1.0, 12.0, 1.0, 0.35]]))
    with pytest.raises(ParameterError):
        Navigator(grid, RobotSpec(radius=0.2), start, goal, sweep_detour=0.5)

def test_global_plan_keeps_the_robot_radius_and_extends_to_exact_ends():
    grid = two_corridor_map()
    nav = Navigator(grid, RobotSpec(radius=0.3), (1.2, 7.3), (13.5, 7.5))
    res = nav.plan_initial()
    assert res.feasible
    assert np.allclose(nav.path[0], (1.2, 7.3)) and np.allclose(nav.path[-1], (13.5, 7.5))
    assert bool(op.validate_path(grid, nav.path[1:], 0.3))
    assert not nav.messages
