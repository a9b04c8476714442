"""Scenario files: the DESIGN.md schema, optplan's optional keys, and every error class."""
from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np
import pytest

import optplan as op
from optplan.errors import ScenarioError
from optplan.world.scenario import DynamicObstacle, load_scenario, scenario_names
from optplan.world.polyline import point_segment_distances
from optplan.worldgen.scenarios import realize

ROWS = [
    [0, 0, 0, 0, 0, 0],
    [0, 0, 0, 1, 0, 0],
    [0, 0, 0, 1, 0, 0],
    [0, 0, 0, 0, 0, 0],
]  # top row first: the blocked cells are (3, 1) and (3, 2)


def base(**over):
    d = {"map": ROWS, "start": [0.5, 0.5, 90], "goal": [5.5, 3.5]}
    d.update(over)
    return d


def test_full_design_example_loads_from_a_yaml_file_with_a_relative_map(tmp_path):
    (tmp_path / "maps").mkdir()
    (tmp_path / "maps" / "room.txt").write_text("\n".join(" ".join("0" * 20) for _ in range(20)) + "\n")
    (tmp_path / "s.yaml").write_text("""
map: maps/room.txt
resolution: 1.0
robot: {model: unicycle, radius: 0.2, v_max: 1.0, w_max_deg: 30, a_max: 0.3, alpha_max_deg: 50, jerk_max: null}
start: [0.5, 0.5, 45]
goal: [19.5, 19.5]
sensor_range: 3.0
dt: 0.1
time_limit: 300
unknown_obstacles:
  - {cells: [[5, 6], [5, 7]]}
  - {circle: [12.0, 8.0, 0.5]}
dynamic_obstacles:
  - {radius: 0.3, waypoints: [[3, 10], [15, 10]], speed: 0.5, loop: true}
  - {radius: 0.6, start: [19, 5], velocity: [-0.6, 0.0]}
""")
    sc = op.load_scenario(tmp_path / "s.yaml")
    assert sc.world.width == 20 and sc.is_grid
    assert sc.robot.w_max == pytest.approx(math.radians(30)) and sc.robot.jerk_max is None
    assert np.allclose(sc.start, [0.5, 0.5, math.radians(45)])
    assert sc.unknown_cells.tolist() == [[5, 6], [5, 7]]
    assert sc.unknown_circles.tolist() == [[12.0, 8.0, 0.5]]
    assert len(sc.dynamic) == 2 and sc.dynamic[1].at_border == "bounce"
    assert sc.name == "s"
    # the true world holds the unknown cells, the known one does not
    assert sc.true_world().occ[6, 5] and not sc.world.occ[6, 5]


def test_inline_rows_are_top_row_first_and_take_the_resolution():
    sc = load_scenario(base(resolution=0.5, start=[0.25, 0.25], goal=[2.75, 1.75]))
    assert sc.world.resolution == 0.5
    assert sc.world.occ[1, 3] and sc.world.occ[2, 3] and sc.world.occ.sum() == 2
    assert sc.start[2] == 0.0  # heading defaults to 0


def test_shipped_map_name_and_circle_world():
    sc = load_scenario({"map": "yang2023_env1", "start": [0.3, 0.3, 45], "goal": [9.7, 9.7],
                        "unknown_obstacles": [{"circle": [5.0, 0.6, 0.3]}]})
    assert not sc.is_grid and len(sc.unknown_circles) == 1


@pytest.mark.parametrize("name", scenario_names())
def test_every_shipped_scenario_loads_and_realises(name):
    sc = load_scenario(name)
    assert sc.description, f"{name} must say which paper experiment it stands in for"
    r1, r2 = realize(sc, 3), realize(sc, 3)
    assert np.array_equal(r1.unknown_cells, r2.unknown_cells)
    assert [d.phase for d in r1.dynamic] == [d.phase for d in r2.dynamic]


@pytest.mark.parametrize("data,needle", [
    ({"start": [0.5, 0.5], "goal": [5.5, 3.5]}, "missing required key"),
    (base(speed=1), "unknown scenario key"),
    (base(robot={"radius": 0.2, "wheels": 4}), "unknown robot key"),
    (base(robot={"radius": "big"}), "robot.radius must be a number"),
    (base(robot={"model": "tank"}), "model must be one of"),
    (base(start="corner"), "start must be a list"),
    (base(goal=[1.0]), "goal must be a list of 2"),
    (base(dt=float("nan")), "dt must be a finite number"),
    (base(sensor_range=-1.0), "sensor_range must be > 0"),
    (base(time_limit=True), "time_limit must be a number"),
    (base(start=[7.0, 0.5]), "outside the map"),
    (base(goal=[3.5, 2.5]), "goal (3.5, 2.5) is blocked"),
    (base(start=[2.9, 1.5]), "closer than the robot radius"),
    (base(unknown_obstacles=[{"cells": [[0, 0]]}]), "unknown obstacle overlaps the robot at the start"),
    (base(unknown_obstacles=[{"cells": [[9, 9]]}]), "outside the 6x4 map"),
    (base(unknown_obstacles=[{"cells": [[1.5, 2]]}]), "integer cell indices"),
    (base(unknown_obstacles=[{"cells": [[1, 2], [1e300, 2]]}]), "cell [1e+300, 2.0] is outside any map"),
    (base(unknown_obstacles=[{"box": [1, 2]}]), "unknown key(s) 'box'"),
    (base(dynamic_obstacles=[{"radius": 0.3, "start": [0.8, 0.5], "velocity": [0, 0]}]), "overlaps the robot's start"),
    (base(dynamic_obstacles=[{"radius": 0.3, "waypoints": [[1, 1], [2, 2]]}]), "no 'speed'"),
    (base(dynamic_obstacles=[{"radius": 0.3, "start": [4, 3], "velocity": [1, 0], "at_border": "wrap"}]), "at_border"),
    (base(dynamic_obstacles=[{"waypoints": [[1, 1]], "speed": 1}]), "missing 'radius'"),
    (base(random_obstacles={"size": 1}), "missing 'count'"),
    (base(random_obstacles={"count": 10 ** 9}), "random_obstacles.count (1000000000) is more than"),
    (base(random_obstacles={"count": 2, "size": 1e300}), "random_obstacles.size (1e+300 cells) is larger"),
    (base(random_dynamic={"count": 10 ** 9}), "random_dynamic.count (1000000000) is more than 84 discs"),
    (base(random_dynamic={"count": 1, "radius": 1e6}), "random_dynamic.radius (1e+06 m) is larger"),
    (base(map=[[0, 2], [0, 0]]), "list of equal-length rows of 0/1"),
    (base(map="no_such_map_anywhere"), "does not exist"),
    ({"map": "yang2023_env1", "start": [0.3, 0.3], "goal": [9.7, 9.7], "unknown_obstacles": [{"cells": [[1, 1]]}]},
     "need a grid map"),
])
def test_malformed_scenarios_raise_scenario_error_naming_the_problem(data, needle):
    with pytest.raises(ScenarioError) as exc, warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # caught by a check, not by overflowing numpy
        load_scenario(data)
    assert needle in str(exc.value)


def test_file_errors(tmp_path):
    with pytest.raises(ScenarioError, match="does not exist"):
        load_scenario(tmp_path / "missing.yaml")
    bad = tmp_path / "bad.yaml"
    bad.write_text("map: [0, 1\nstart: ]")
    with pytest.raises(ScenarioError, match="not valid YAML"):
        load_scenario(bad)
    empty = tmp_path / "empty.yaml"
    empty.write_text("")
    with pytest.raises(ScenarioError, match="empty"):
        load_scenario(empty)


def test_cli_reports_a_bad_scenario_in_one_line(tmp_path, capsys):
    from optplan.cli import main

    f = tmp_path / "s.yaml"
    f.write_text("map: arena\nstart: [1.5, 37.5]\n")
    assert main(["simulate", str(f)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("optplan: error:") and "goal" in err and "\n" not in err


def test_random_parts_are_drawn_from_the_seed_on_the_path_and_keep_the_goal_reachable():
    sc = load_scenario({"map": "li2023_11", "start": [0.5, 0.5, 0], "goal": [10.5, 10.5],
                        "random_obstacles": {"count": 2, "keep_away": 2.0},
                        "random_dynamic": {"count": 2, "radius": 0.3, "speed": [0.3, 0.5], "length": [3, 5]}})
    a, b, c = realize(sc, 0), realize(sc, 0), realize(sc, 1)
    assert a.unknown_cells.tolist() == b.unknown_cells.tolist()
    assert 1 <= len(a.unknown_cells) <= 2 and a.random_obstacles is None
    assert len(a.dynamic) == 2
    assert (a.unknown_cells.tolist() != c.unknown_cells.tolist()
            or [d.waypoints.tolist() for d in a.dynamic] != [d.waypoints.tolist() for d in c.dynamic])
    for cell in a.unknown_cells:
        assert not sc.world.occ[cell[1], cell[0]]
        centre = sc.world.cell_center(cell)
        assert min(np.hypot(*(centre - sc.start[:2])), np.hypot(*(centre - sc.goal))) >= 1.5
    res = op.shortest_path(a.true_world(), sc.start[:2], sc.goal, clearance=sc.robot.radius)
    assert res.feasible
    for d in a.dynamic:
        assert bool(sc.world.segments_free(d.waypoints[0], d.waypoints[1], d.radius))


def test_segment_distance_is_zero_for_crossing_segments_and_exact_otherwise():
    from optplan.worldgen.scenarios import _segments_distance
    o = np.zeros(2)
    assert _segments_distance(o, np.array([2.0, 2.0]), np.array([0.0, 2.0]), np.array([2.0, 0.0])) == 0.0
    # parallel, 1 m apart; then end to end along one line, 0.5 m apart
    assert math.isclose(_segments_distance(o, np.array([2.0, 0.0]), np.array([0.0, 1.0]), np.array([2.0, 1.0])), 1.0)
    assert math.isclose(_segments_distance(o, np.array([1.0, 0.0]), np.array([1.5, 0.0]), np.array([3.0, 0.0])), 0.5)
    # a T: the end of one 0.3 m short of the other's middle
    assert math.isclose(_segments_distance(np.array([1.0, 0.3]), np.array([1.0, 2.0]), o, np.array([2.0, 0.0])), 0.3)


@pytest.mark.parametrize("name", ["li2023_exp2_5", "hou2024_dynamic4"])
def test_random_movers_never_touch_each_other(name):
    """Drawn tracks keep two movers apart whatever their timing: on the shipped crowded
    scenarios, tracks used to cross or share an end, and movers drove through each other."""
    sc = load_scenario(name)
    t = np.linspace(0.0, 1.0, 401)[:, None]
    for seed in range(6):
        movers = realize(sc, seed).dynamic
        assert len(movers) == sc.random_dynamic["count"]
        for i, m in enumerate(movers):
            for n in movers[i + 1:]:
                # every point of one track to the other segment, sampled densely
                P = m.waypoints[0] + t * (m.waypoints[-1] - m.waypoints[0])
                a, b = n.waypoints[0], n.waypoints[-1]
                u = np.clip((P - a) @ (b - a) / float((b - a) @ (b - a)), 0.0, 1.0)
                gap = np.hypot(*(P - (a + u[:, None] * (b - a))).T).min() - m.radius - n.radius
                assert gap >= 0.1 - 1e-6, (seed, gap)


def test_mover_positions_over_time():
    bounds = (0.0, 0.0, 10.0, 10.0)
    loop = DynamicObstacle(0.3, waypoints=np.array([[1.0, 1.0], [5.0, 1.0], [5.0, 4.0]]), speed=1.0, loop=True)
    # perimeter 4 + 3 + 5 = 12 m at 1 m/s
    for t, want in ((0.0, (1, 1)), (2.0, (3, 1)), (5.5, (5, 2.5)), (7.0 + 2.5, (3, 2.5)), (12.0 + 2.0, (3, 1))):
        assert np.allclose(loop.state(t, bounds)[0], want), t
    assert np.allclose(loop.state(5.5, bounds)[1], (0, 1.0))
    once = DynamicObstacle(0.3, waypoints=np.array([[1.0, 1.0], [3.0, 1.0]]), speed=0.5, loop=False, phase=0.5)
    assert np.allclose(once.state(1.0, bounds)[0], (2.0, 1.0))
    assert np.allclose(once.state(50.0, bounds), [(3.0, 1.0), (0.0, 0.0)])
    bounce = DynamicObstacle(0.5, start=np.array([8.0, 5.0]), velocity=np.array([1.0, 0.0]))
    # reaches x = 9.5 (border minus radius) at t = 1.5, then comes back
    assert np.allclose(bounce.state(1.0, bounds)[0], (9.0, 5.0))
    assert np.allclose(bounce.state(2.5, bounds), [(8.5, 5.0), (-1.0, 0.0)])
    assert np.allclose(bounce.state(1.5 + 9.0 + 1.0, bounds)[0], (1.5, 5.0))  # bounced off x = 0.5 too
    stop = DynamicObstacle(0.5, start=np.array([8.0, 5.0]), velocity=np.array([1.0, 1.0]), at_border="stop")
    assert np.allclose(stop.state(10.0, bounds), [(9.5, 6.5), (0.0, 0.0)])
    gone = DynamicObstacle(0.5, start=np.array([8.0, 5.0]), velocity=np.array([1.0, 0.0]), at_border="pass")
    assert np.allclose(gone.state(10.0, bounds)[0], (18.0, 5.0))


def test_random_movers_cross_the_path_at_independently_drawn_places():
    # Each mover's crossing is drawn from the whole stretch of path kept away from start
    # and goal; a bug once drew every mover after the first from the previous one's sweep,
    # piling all of them onto one crossing.
    sc = load_scenario("hou2024_dynamic4")
    spreads = []
    for seed in range(6):
        world = realize(sc, seed)
        centres = np.array([d.waypoints.mean(axis=0) for d in world.dynamic])
        spreads.append(float(np.max(np.hypot(*(centres[:, None] - centres[None]).transpose(2, 0, 1)))))
    # six crossings drawn along a ~70 m path: the farthest two are far apart in most draws
    assert np.median(spreads) > 10.0, spreads


def _room(**over):
    d = {"map": [[0] * 10 for _ in range(6)], "start": [0.5, 3.0, 0], "goal": [9.5, 3.0]}
    d.update(over)
    return load_scenario(d)


def test_a_waypoint_loop_of_zero_length_is_a_mover_that_stands_still():
    # two waypoints at one place with speed > 0 once gave s % 0 = NaN: a mover nowhere
    still = DynamicObstacle(0.4, waypoints=np.array([[5.0, 3.0], [5.0, 3.0]]), speed=1.0, loop=True)
    for t in (0.0, 0.1, 7.3, 100.0):
        pos, vel = still.state(t, (0.0, 0.0, 10.0, 6.0))
        assert pos.tolist() == [5.0, 3.0] and vel.tolist() == [0.0, 0.0]
    sc = _room(dynamic_obstacles=[{"radius": 0.4, "waypoints": [[5, 3], [5, 3]], "speed": 1.0}])
    assert np.isfinite(sc.dynamic[0].state(2.0, sc.bounds)[0]).all()


def test_a_bouncing_mover_wider_than_the_map_is_refused_naming_it():
    # radius 3.5 m on a 6 m tall map: bouncing would have to put it somewhere it never was
    with pytest.raises(ScenarioError, match=r"dynamic_obstacles\[1\].*radius 3.5"):
        _room(dynamic_obstacles=[{"radius": 0.3, "start": [8, 1], "velocity": [0, 0.5]},
                                 {"radius": 3.5, "start": [5, 3], "velocity": [0.2, 0.0]}])
    with pytest.raises(ScenarioError, match=r"dynamic_obstacles\[0\]"):
        _room(dynamic_obstacles=[{"radius": 3.5, "start": [5, 3], "velocity": [0.2, 0.0], "at_border": "stop"}])
    # leaving the map is its own choice, and needs no room inside it
    sc = _room(dynamic_obstacles=[{"radius": 3.5, "start": [5, 12], "velocity": [0.2, 0.0], "at_border": "pass"}])
    assert sc.dynamic[0].state(1.0, sc.bounds)[0].tolist() == [5.2, 12.0]
    with pytest.raises(ScenarioError, match="wider than"):
        DynamicObstacle(3.5, start=np.array([5.0, 3.0]), velocity=np.array([0.2, 0.0])).state(1.0, sc.bounds)


def test_a_bouncing_mover_that_starts_over_the_border_is_not_moved():
    # x = 9.8 with radius 0.5 on a 10 m wide map: the disc pokes out. It used to be folded
    # into the map at t = 0 (x = 9.2); now it drives on until it is inside, then bounces.
    bounds = (0.0, 0.0, 10.0, 6.0)
    inward = DynamicObstacle(0.5, start=np.array([9.8, 3.0]), velocity=np.array([-1.0, 0.0]))
    assert np.allclose(inward.state(0.0, bounds)[0], (9.8, 3.0))
    assert np.allclose(inward.state(0.2, bounds)[0], (9.6, 3.0))
    assert np.allclose(inward.state(0.3 + 9.0 + 1.0, bounds), [(1.5, 3.0), (1.0, 0.0)])  # off x = 0.5, back
    outward = DynamicObstacle(0.5, start=np.array([9.8, 3.0]), velocity=np.array([0.5, 0.0]))
    assert np.allclose(outward.state(4.0, bounds), [(11.8, 3.0), (0.5, 0.0)])  # leaves, never folded back
    parked = DynamicObstacle(0.5, start=np.array([9.8, 3.0]), velocity=np.array([0.0, 0.5]))
    assert np.allclose(parked.state(1.0, bounds)[0], (9.8, 3.5))
    exact = DynamicObstacle(3.0, start=np.array([5.0, 3.0]), velocity=np.array([0.5, 0.5]))  # just fits in y
    assert np.allclose(exact.state(1.7, bounds), [(5.85, 3.0), (0.5, 0.0)])


def test_a_delayed_mover_waits_where_it_stands_then_drives():
    bounds = (0.0, 0.0, 10.0, 6.0)
    late = DynamicObstacle(0.3, waypoints=np.array([[1.0, 1.0], [3.0, 1.0]]), speed=0.5, loop=False, delay=4.0)
    pos, vel = late.states([0.0, 3.9, 5.0, 100.0], bounds)
    assert np.allclose(pos, [(1, 1), (1, 1), (1.5, 1), (3, 1)])
    assert np.allclose(vel, [(0, 0), (0, 0), (0.5, 0), (0, 0)])
    sc = _room(dynamic_obstacles=[{"radius": 0.4, "waypoints": [[5, 1], [5, 5]], "speed": 1.0, "delay": 2.5}])
    assert sc.dynamic[0].delay == 2.5 and np.allclose(sc.dynamic[0].state(3.5, sc.bounds)[0], (5, 2))
    with pytest.raises(ScenarioError, match="delay"):
        _room(dynamic_obstacles=[{"radius": 0.4, "waypoints": [[5, 1], [5, 5]], "speed": 1.0, "delay": -1}])
    with pytest.raises(ScenarioError, match="delay"):
        _room(dynamic_obstacles=[{"radius": 0.4, "start": [5, 1], "velocity": [0, 1], "delay": 1}])


def test_timing_jitter_spends_a_movers_wait_before_its_route():
    sc = _room(dynamic_obstacles=[{"radius": 0.3, "waypoints": [[5, 1], [5, 5]], "speed": 1.0, "loop": False,
                                   "delay": 100.0}], timing_jitter=3.0)
    ob = realize(sc, 0).dynamic[0]
    assert 97.0 <= ob.delay < 100.0 and ob.phase == 0.0  # still waiting: not moved along


def test_movers_drawn_to_cross_once_meet_a_robot_driving_the_path():
    """``motion: once``: each mover drives its track once, from one end to the other, and is on
    the reference path when a robot driving that path at 30-100 % of v_max would be there; it
    then stands clear of the path (parked on it, it blocked a corridor for good)."""
    from optplan.worldgen.scenarios import reference_path

    sc = load_scenario("li2023_exp2_5")
    once = replace(sc, random_dynamic={**sc.random_dynamic, "motion": "once"})
    path = reference_path(once)
    arc = np.r_[0.0, np.cumsum(np.hypot(*np.diff(path, axis=0).T))]
    timed = 0
    for seed in range(4):
        movers = realize(once, seed).dynamic
        assert len(movers) == 5 and all(not m.loop for m in movers)
        for m in movers:
            a, b = m.waypoints
            t = np.linspace(0.0, 200.0, 20001)
            pos, _ = m.states(t, once.bounds)
            assert np.allclose(pos[-1], b) and np.allclose(pos[0], a + (b - a) * m.phase / np.hypot(*(b - a)))
            # where it stands at the end leaves the path free, as start and goal must
            assert np.hypot(*(path - b).T).min() >= m.radius + once.robot.radius + 0.5 - 1e-3
            # when the mover's centre is nearest the path, a robot on the path would be there
            d = np.hypot(*(pos[:, None, :] - path[None]).transpose(2, 0, 1))
            k = int(np.argmin(d.min(axis=1)))
            at = arc[int(np.argmin(d[k]))]
            if m.phase == 0.0:  # (a mover that would have had to start before t = 0 is late)
                assert at / once.robot.v_max - 0.5 <= t[k] <= at / (0.3 * once.robot.v_max) + 0.5
                timed += 1
    assert timed >= 10  # of the 20 movers
    assert _room(random_dynamic={"count": 1, "motion": "once"}).random_dynamic["motion"] == "once"
    assert _room(random_dynamic={"count": 1}).random_dynamic["motion"] == "shuttle"
    with pytest.raises(ScenarioError, match="motion"):
        _room(random_dynamic={"count": 1, "motion": "twice"})


def test_movers_with_unseen_ends_are_seen_only_while_they_drive():
    """``ends_unseen``: a once-mover waits and stops where a robot on the reference path
    cannot sense it, so the robot never sees it stand and then set off (yang2023's movers
    drive at 0.8 m/s); its track still crosses the path, on time, through free space."""
    from optplan.worldgen.scenarios import reference_path

    sc = load_scenario("yang2023_fusion")
    assert sc.random_dynamic["ends_unseen"] is True
    once = replace(sc, random_dynamic={**sc.random_dynamic, "motion": "once"})
    path = reference_path(once)
    for seed in range(3):
        for m in realize(once, seed).dynamic:
            a, b = m.waypoints
            for end in (a, b):
                gap = np.hypot(*(path - end).T).min() - m.radius
                assert gap >= once.sensor_range + 0.5 - 1e-3
            assert bool(once.world.segments_free(a, b, m.radius))
            assert point_segment_distances(path, a, b).min() < 0.01  # it crosses the path
    # the plain draw leaves ends in view (the case the option exists for)
    plain = replace(once, random_dynamic={**once.random_dynamic, "ends_unseen": False})
    ends = np.array([m.waypoints[0] for s in range(3) for m in realize(plain, s).dynamic])
    assert (np.array([np.hypot(*(path - e).T).min() for e in ends]) - 0.6 < once.sensor_range).any()
    assert _room(random_dynamic={"count": 1}).random_dynamic["ends_unseen"] is False
    with pytest.raises(ScenarioError, match="ends_unseen must be true or false"):
        _room(random_dynamic={"count": 1, "ends_unseen": 1})

