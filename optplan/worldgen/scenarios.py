"""The seed-dependent parts of a scenario, realised: random unknown obstacles and random
movers placed on the run's global path, and the timing jitter of the file's movers.

The file keys (``random_obstacles``, ``random_dynamic``, ``timing_jitter``) and their
limits are read and checked by :mod:`optplan.world.scenario`; drawing them needs a
planner (the reference path, the reachability test) and so happens here, above the
solvers. ``op.simulate`` realises a scenario with its ``seed`` on its initial global
path (:func:`realize`), so the same scenario file, seed and global path always give the
same world; :func:`optplan.sim.closed_loop.realized_scenario` rebuilds it for plotting.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..errors import OptplanError, ScenarioError
from ..rng import as_generator
from ..world.polyline import densify, point_segment_distances
from ..world.scenario import DynamicObstacle, Scenario, validate

DENSE_STEP = 0.25   # metres between the points of a reference path


def realize(sc: Scenario, seed=0, path=None) -> Scenario:
    """A copy of ``sc`` whose seed-dependent parts are realised: the random obstacles
    (``random_obstacles``, ``random_dynamic``) drawn from ``seed`` and added as ordinary
    unknown / moving obstacles, and the file's movers advanced by up to ``timing_jitter``
    seconds. A scenario without such parts comes back as it is.

    Args:
        sc: the scenario (e.g. ``op.load_scenario(name)``).
        seed: int or Generator.
        path: ``(N, 2)`` reference path (metres) the random obstacles are placed on
            (the run's global path); default: the known map's shortest path
            (:func:`reference_path`).
    """
    if not sc.random_obstacles and not sc.random_dynamic and not sc.timing_jitter:
        return sc
    rng = as_generator(seed)
    cells, circles, dynamic = sc.unknown_cells, sc.unknown_circles, list(sc.dynamic)
    if sc.timing_jitter:
        dynamic = _jitter_movers(sc, rng)
    if sc.random_obstacles or sc.random_dynamic:
        path = reference_path(sc) if path is None else densify(np.asarray(path, dtype=float).reshape(-1, 2), DENSE_STEP)
    if sc.random_obstacles:
        new_cells, new_circles = _draw_random_obstacles(sc, sc.random_obstacles, rng, path)
        cells = np.vstack([cells, new_cells]) if len(new_cells) else cells
        circles = np.vstack([circles, new_circles]) if len(new_circles) else circles
    if sc.random_dynamic:
        dynamic += _draw_random_movers(sc, sc.random_dynamic, rng, path)
    return replace(sc, unknown_cells=cells, unknown_circles=circles, dynamic=dynamic,
                   random_obstacles=None, random_dynamic=None, timing_jitter=0.0)


def reference_path(sc: Scenario) -> np.ndarray:
    """The known map's shortest path for the robot's footprint (dense polyline)."""
    from ..solvers.graph import shortest_path

    method = "astar" if sc.is_grid else "visibility"
    try:
        res = shortest_path(sc.world, sc.start[:2], sc.goal, method=method, clearance=sc.robot.radius)
    except OptplanError:
        res = shortest_path(sc.world, sc.start[:2], sc.goal, method=method)
    return densify(np.vstack([sc.start[:2], res.path, sc.goal]), DENSE_STEP)


def _reachable(sc: Scenario, cells: np.ndarray, circles: np.ndarray) -> bool:
    """Can the robot's footprint still get from start to goal with these extra obstacles?"""
    from ..solvers.graph import shortest_path

    trial = replace(sc, unknown_cells=np.vstack([sc.unknown_cells, cells]) if len(cells) else sc.unknown_cells,
                    unknown_circles=np.vstack([sc.unknown_circles, circles]) if len(circles) else sc.unknown_circles,
                    random_obstacles=None, random_dynamic=None, timing_jitter=0.0)
    world = trial.true_world()
    if sc.is_grid and len(trial.unknown_circles):
        return True  # discs on a grid: accepted without a reachability test
    if sc.is_grid and sc.robot.radius <= 0.5 * world.resolution:
        # 4-neighbour moves between free cell centres keep half a cell from every blocked
        # cell, so 4-connectivity of the free cells suffices for this footprint
        from scipy.ndimage import label

        lab, _ = label(~world.occ)
        (sx, sy), (gx, gy) = world.cell_of(sc.start[:2]), world.cell_of(sc.goal)
        return bool(lab[sy, sx] != 0 and lab[sy, sx] == lab[gy, gx])
    try:
        shortest_path(world, sc.start[:2], sc.goal, method="astar" if sc.is_grid else "visibility",
                      clearance=sc.robot.radius)
    except OptplanError:
        return False
    return True


def _draw_random_obstacles(sc: Scenario, spec: dict, rng, path: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    count, size, keep = int(spec["count"]), float(spec["size"]), float(spec["keep_away"])
    if count == 0:
        return np.zeros((0, 2), np.int64), np.zeros((0, 3))
    far = (np.hypot(*(path - sc.start[:2]).T) >= keep) & (np.hypot(*(path - sc.goal).T) >= keep)
    candidates = path[far]
    if not len(candidates):
        raise ScenarioError(f"random_obstacles: no point of the reference path is {keep:g} m from start and goal; "
                            "lower keep_away")
    for _ in range(200):
        picks = candidates[rng.choice(len(candidates), size=count, replace=len(candidates) < count)]
        if sc.is_grid:
            k = max(int(round(size)), 1)
            corner = sc.world.cell_of(picks) - (k - 1) // 2
            offs = np.stack(np.meshgrid(np.arange(k), np.arange(k)), -1).reshape(-1, 2)
            cells = np.unique((corner[:, None, :] + offs[None]).reshape(-1, 2), axis=0)
            cells = cells[sc.world.in_map(cells)]
            cells = cells[~sc.world.occ[cells[:, 1], cells[:, 0]]]
            trial = replace(sc, unknown_cells=np.vstack([sc.unknown_cells, cells]), random_obstacles=None,
                            random_dynamic=None) if len(cells) else None
            if trial is None:
                continue
            try:
                validate(trial)
            except ScenarioError:
                continue
            if _reachable(sc, cells, np.zeros((0, 3))):
                return cells, np.zeros((0, 3))
        else:
            circles = np.column_stack([picks, np.full(count, size / 2)])
            try:
                validate(replace(sc, unknown_circles=np.vstack([sc.unknown_circles, circles]),
                                 random_obstacles=None, random_dynamic=None))
            except ScenarioError:
                continue
            if _reachable(sc, np.zeros((0, 2), np.int64), circles):
                return np.zeros((0, 2), np.int64), circles
    raise ScenarioError("random_obstacles: no draw in 200 tries left the goal reachable; lower count or size")


def _jitter_movers(sc: Scenario, rng) -> list[DynamicObstacle]:
    """The scenario's movers, each advanced by ``U(0, timing_jitter)`` seconds; a shift that
    would put a mover onto the robot's start is drawn again (then dropped to zero)."""
    out = []
    for ob in sc.dynamic:
        for _ in range(20):
            shift = float(rng.uniform(0.0, sc.timing_jitter))
            if ob.waypoints is not None:
                # the wait at the start first, then along the route
                moved = replace(ob, delay=max(ob.delay - shift, 0.0),
                                phase=ob.phase + ob.speed * max(shift - ob.delay, 0.0))
            else:
                pos, vel = ob.state(shift, sc.bounds)
                moved = replace(ob, start=pos, velocity=vel if ob.at_border != "stop" else ob.velocity)
                if ob.at_border == "stop" and not np.any(vel):
                    moved = replace(ob, start=pos, velocity=np.zeros(2))
            pos, _ = moved.state(0.0, sc.bounds)
            if np.hypot(*(pos - sc.start[:2])) >= ob.radius + sc.robot.radius:
                out.append(moved)
                break
        else:
            out.append(ob)
    return out


def _segments_distance(a, b, c, d) -> float:
    """Distance between the segments ``a -> b`` and ``c -> d`` (0 when they cross)."""
    def cross(o, p, q) -> float:
        return float((p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0]))
    d1, d2, d3, d4 = cross(c, d, a), cross(c, d, b), cross(a, b, c), cross(a, b, d)
    if d1 * d2 < 0 and d3 * d4 < 0:
        return 0.0
    # otherwise the closest pair has an end point of one segment
    return float(min(point_segment_distances(np.array([a, b]), c, d).min(),
                     point_segment_distances(np.array([c, d]), a, b).min()))


def _draw_random_movers(sc: Scenario, spec: dict, rng, path: np.ndarray) -> list[DynamicObstacle]:
    count, radius, keep = int(spec["count"]), float(spec["radius"]), float(spec["keep_away"])
    if count == 0:
        return []
    far = (np.hypot(*(path - sc.start[:2]).T) >= keep) & (np.hypot(*(path - sc.goal).T) >= keep)
    idx = np.nonzero(far)[0]
    if not len(idx):
        raise ScenarioError(f"random_dynamic: no point of the reference path is {keep:g} m from start and goal; "
                            "lower keep_away")
    world = sc.world
    out: list[DynamicObstacle] = []
    tries = 0
    while len(out) < count:
        tries += 1
        if tries > 500 * count:
            raise ScenarioError("random_dynamic: could not place the moving obstacles in free space; "
                                "lower count, radius or length")
        i = idx[rng.integers(len(idx))]
        j = min(i + 1, len(path) - 1)
        tangent = path[j] - path[max(j - 1, 0)]
        ang = math.atan2(tangent[1], tangent[0]) + math.radians(rng.uniform(60, 120)) * rng.choice([-1, 1])
        u = np.array([math.cos(ang), math.sin(ang)])
        half = rng.uniform(*spec["length"]) / 2
        a, b = path[i] - half * u, path[i] + half * u
        # shorten each half until it keeps the radius from known obstacles and the border
        for end in ("a", "b"):
            for _ in range(20):
                p = a if end == "a" else b
                if bool(world.segments_free(path[i], p, radius)):
                    break
                p = path[i] + 0.8 * (p - path[i])
                a, b = (p, b) if end == "a" else (a, p)
        if not bool(world.segments_free(a, b, radius)) or np.hypot(*(b - a)) < max(1.0, spec["length"][0] / 2):
            continue
        if spec.get("motion") == "once" and spec.get("ends_unseen"):
            # the robot may see the mover only while it drives: a start or stop in view is a
            # jump in velocity that no prediction from its motion can foresee
            a, b = _out_of_sight(sc, path, i, a, radius), _out_of_sight(sc, path, i, b, radius)
            if a is None or b is None:
                continue
        # the mover must never touch the robot waiting at the start or arrived at the goal
        near = radius + sc.robot.radius + 0.5
        if point_segment_distances(np.stack([sc.start[:2], sc.goal]), a, b).min() < near:
            continue
        # it must *cross* the path once, not run along it (say, up and down a corridor the path
        # follows), so that a robot that cannot reverse can always wait before its sweep
        swept = np.nonzero(point_segment_distances(path, a, b) < near)[0]
        crossing = 2 * near / math.sin(math.radians(60)) + 0.5
        if not len(swept) or swept[-1] - swept[0] + 1 != len(swept) or \
                float(np.hypot(*np.diff(path[swept], axis=0).T).sum()) > crossing:
            continue
        # movers are solid: two tracks keep the movers apart whatever their timing (drawn
        # independently, tracks used to cross or share an end, and movers drove through
        # each other)
        if any(_segments_distance(a, b, other.waypoints[0], other.waypoints[-1]) < radius + other.radius + 0.1
               for other in out):
            continue
        speed = rng.uniform(*spec["speed"])
        phase = rng.uniform(0, 2 * np.hypot(*(b - a)))  # drawn in both motions: a seed's later draws line up
        if spec.get("motion", "shuttle") == "once":
            # it stands where it ends, so it must end where it leaves the path free (as start
            # and goal are left free): a mover parked on the path blocks a corridor for good
            clear = [float(np.hypot(*(path - e).T).min()) >= near for e in (a, b)]
            if not any(clear):
                continue
            if not clear[1] or (clear[0] and rng.random() < 0.5):
                a, b = b, a
            out.append(_once_across(sc, path, i, a, b, radius, speed, rng))
            continue
        ob = DynamicObstacle(radius, waypoints=np.round(np.array([a, b]), 3), speed=round(float(speed), 3), loop=True,
                             phase=round(float(phase), 3))
        out.append(ob)
    return out


_UNSEEN_MARGIN = 0.5  # m beyond sensor_range: the robot strays this far from the reference path
_UNSEEN_STEP = 0.1  # m: the approach grows in these steps


def _out_of_sight(sc: Scenario, path: np.ndarray, i: int, end: np.ndarray, radius: float) -> np.ndarray | None:
    """The end ``end`` of a track through ``path[i]``, moved outwards along the track until a
    mover standing there is out of a robot's sensing from every point of ``path``, or ``None``
    when that longer track is not free of known obstacles and the border (by ``radius``)."""
    out = end - path[i]
    length = float(np.hypot(*out))
    if length == 0:
        return None
    xmin, ymin, xmax, ymax = sc.bounds
    along = np.arange(length, math.hypot(xmax - xmin, ymax - ymin) + _UNSEEN_STEP, _UNSEEN_STEP)
    ends = path[i] + along[:, None] * (out / length)
    gap = np.hypot(ends[:, None, 0] - path[None, :, 0], ends[:, None, 1] - path[None, :, 1]).min(axis=1)
    far = np.flatnonzero(gap >= sc.sensor_range + radius + _UNSEEN_MARGIN)
    if not len(far) or not bool(sc.world.segments_free(path[i], ends[far[0]], radius)):
        return None
    return np.round(ends[far[0]], 3)


def _once_across(sc: Scenario, path: np.ndarray, i: int, a: np.ndarray, b: np.ndarray, radius: float,
                 speed: float, rng) -> DynamicObstacle:
    """A mover that drives the segment once, from ``a`` to ``b``, timed to cross the reference
    path (at ``path[i]``, on the segment) when a robot driving the path from the start at
    30-100 % of its ``v_max`` (drawn from ``rng``) would get there."""
    arc = float(np.hypot(*np.diff(path[:i + 1], axis=0).T).sum())
    meet = arc / (sc.robot.v_max * rng.uniform(0.3, 1.0))
    wait = meet - float(np.hypot(*(path[i] - a))) / speed if speed > 0 else 0.0  # a still mover stands
    length = float(np.hypot(*(b - a)))
    delay, phase = (wait, 0.0) if wait >= 0 else (0.0, min(-wait * speed, length))
    return DynamicObstacle(radius, waypoints=np.round(np.array([a, b]), 3), speed=round(float(speed), 3), loop=False,
                           phase=round(phase, 3), delay=round(delay, 3))
