"""The simulated world around the robot: moving obstacles, sensing and exact collision checks.

* Moving obstacles follow their closed-form motion (``DynamicObstacle.state``); within
  one period their centres are taken to move on the straight segment between their
  positions at the start and the end of the period.
* Sensing: an unknown static obstacle (a cell or a disc missing from the known map)
  becomes known to the robot, for good, once its nearest point is within
  ``sensor_range`` of the robot centre; moving obstacles are reported (position and
  velocity) while they are within that range. There is no occlusion.
* The local planner's static distance is the known map's distance field
  (``grid_distance_field`` with 8 samples per cell on grids; it may overestimate the
  distance by up to ~0.02 cells near obstacle corners, so planners need a small
  margin; the analytic disc distance on circle worlds,
  where the planning safety margin is *not* included) combined with the exact
  distance to what has been sensed so far.
* Collisions are decided per period by the exact rule on the segment the robot
  centre drove (``segments_free(..., clearance=radius)`` on the true static world
  including every unknown obstacle, sensed or not) and, for each moving obstacle,
  by the exact minimum distance between the two linearly moving centres.
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError, ScenarioError
from ..world.circles import CircleWorld
from ..world.fields import grid_distance_field
from ..world.scenario import Scenario, circle_distance


FIELD_SUBDIV = 8
FIELD_ERROR_CELLS = 0.03  # bound on the field's overestimate with FIELD_SUBDIV, in cells (0.018 measured outside obstacles)


def box_distance(points: np.ndarray, lo: np.ndarray, size: float, chunk: int = 64) -> np.ndarray:
    """Signed distance (m) from points ``(..., 2)`` to the union of axis-aligned squares
    with lower-left corners ``lo`` ``(m, 2)`` and side ``size`` (inside: minus the depth
    into the deepest square; ``inf`` when ``m == 0``)."""
    p = np.asarray(points, dtype=float)
    out = np.full(p.shape[:-1], np.inf)
    for k in range(0, len(lo), chunk):
        L = lo[k:k + chunk]
        below = L - p[..., None, :]                 # > 0 when left of / below the square
        above = p[..., None, :] - (L + size)        # > 0 when right of / above it
        gap = np.maximum(np.maximum(below, above), 0.0)
        outside = np.hypot(gap[..., 0], gap[..., 1])
        depth = np.minimum(-below, -above).min(axis=-1)   # distance to the nearest side when inside
        d = np.where(outside > 0, outside, -np.maximum(depth, 0.0))
        out = np.minimum(out, d.min(axis=-1))
    return out


def _require_finite(what: str, *arrays) -> None:
    """Refuse NaN or infinite positions before a collision test: every comparison with NaN is
    false, so a non-finite centre would silently count as no contact."""
    for a in arrays:
        if not np.all(np.isfinite(a)):
            raise ParameterError(f"{what}: non-finite position {np.asarray(a).tolist()}; "
                                 "a collision cannot be judged for it (this is a bug in what produced it)")


def moving_min_distance(p0: np.ndarray, p1: np.ndarray, q0: np.ndarray, q1: np.ndarray) -> np.ndarray:
    """Smallest distance during one period between a point moving ``p0 -> p1`` and
    points moving ``q0 -> q1`` ``(k, 2)``, all linearly in time (exact)."""
    d0 = p0 - q0                       # relative position at the start
    dd = (p1 - p0) - (q1 - q0)         # relative displacement over the period
    L2 = np.einsum("ij,ij->i", dd, dd)
    s = np.where(L2 > 0, np.clip(-np.einsum("ij,ij->i", d0, dd) / np.where(L2 > 0, L2, 1.0), 0.0, 1.0), 0.0)
    rel = d0 + s[:, None] * dd
    return np.hypot(rel[:, 0], rel[:, 1])


class SimEnvironment:
    """Ground truth and the robot's knowledge of it during one run.

    Args:
        scenario: a realised scenario (``optplan.worldgen.scenarios.realize`` already applied).
    """

    def __init__(self, scenario: Scenario):
        self.sc = scenario
        self.radius = scenario.robot.radius
        self.bounds = scenario.bounds
        self.true_static = scenario.true_world()
        self.is_grid = scenario.is_grid
        if self.is_grid:
            grid = scenario.world
            self.res = grid.resolution
            self.cell_lo = grid.to_world(scenario.unknown_cells.astype(float)) if len(scenario.unknown_cells) \
                else np.zeros((0, 2))
            # 8 samples per cell: the bilinear field overestimates the distance near convex
            # corners by at most ~0.02 cells (0.04 with the default 4); built once per map
            self._known_distance = grid_distance_field(grid, FIELD_SUBDIV)
            self.distance_error = FIELD_ERROR_CELLS * self.res
            iy, ix = np.nonzero(grid.occ)
            self._known_points = grid.cell_center(np.stack([ix, iy], axis=1)) if len(ix) else np.zeros((0, 2))
        else:
            self.res = 1.0
            self.cell_lo = np.zeros((0, 2))
            physical = CircleWorld(scenario.world.bounds, scenario.world.circles, 0.0)
            self._known_distance = physical.clearance
            self.distance_error = 0.0  # exact
            self._known_points = scenario.world.circles[:, :2].copy()
        self.circles = scenario.unknown_circles
        self.sensed_cells = np.zeros(len(self.cell_lo), dtype=bool)
        self.sensed_circles = np.zeros(len(self.circles), dtype=bool)
        self._tree = None
        self._table: np.ndarray | None = None
        self._known_world = None  # (sensed counts, world) of known_segments_free
        if len(self._known_points):
            from scipy.spatial import cKDTree

            self._tree = cKDTree(self._known_points)

    # ------------------------------------------------------------- moving obstacles
    def _mover_table(self) -> np.ndarray:
        """``(n, k, 5)`` rows of every mover at the control instants ``0, dt, ..., time_limit``,
        computed once per run (each mover's closed form at all instants at once): rebuilding
        every mover's path each period took a quarter of the loop with 30 movers (issue 30)."""
        if self._table is None:
            n = int(np.ceil(self.sc.time_limit / self.sc.dt - 1e-9)) + 2
            times = np.arange(n) * self.sc.dt
            table = np.zeros((n, len(self.sc.dynamic), 5))
            for i, ob in enumerate(self.sc.dynamic):  # once per mover, vectorised over the instants
                pos, vel = ob.states(times, self.bounds)
                table[:, i, :2], table[:, i, 2:4], table[:, i, 4] = pos, vel, ob.radius
            self._table = table
        return self._table

    def movers(self, t: float) -> np.ndarray:
        """``(k, 5)`` rows ``(x, y, vx, vy, radius)`` of every moving obstacle at time ``t``
        (looked up in the run's table at the control instants ``k dt``, else computed)."""
        k = t / self.sc.dt
        j = int(round(k))
        if self.sc.dynamic and abs(k - j) < 1e-9 and 0 <= j and j * self.sc.dt == t \
                and j < len(self._mover_table()):
            rows = self._table[j].copy()
        else:
            rows = np.zeros((len(self.sc.dynamic), 5))
            for i, ob in enumerate(self.sc.dynamic):  # a handful of obstacles, closed form each
                pos, vel = ob.state(t, self.bounds)
                rows[i] = (pos[0], pos[1], vel[0], vel[1], ob.radius)
        if not np.all(np.isfinite(rows)):
            # a NaN centre compares false with every distance, so the collision test would never
            # see this mover: the run would drive through it and report no collision
            i = int(np.nonzero(~np.all(np.isfinite(rows), axis=1))[0][0])
            raise ScenarioError(f"dynamic obstacle {i} has no finite position or velocity at t={t:g} s "
                                f"(row {rows[i, :4].tolist()}); check its waypoints, speed, start and velocity")
        return rows

    def sensed_movers(self, position: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """The rows of ``rows`` whose disc comes within ``sensor_range`` of ``position``."""
        if not len(rows):
            return rows
        gap = np.hypot(rows[:, 0] - position[0], rows[:, 1] - position[1]) - rows[:, 4]
        return rows[gap <= self.sc.sensor_range]

    # ------------------------------------------------------------------- sensing
    def sense(self, position: np.ndarray) -> bool:
        """Reveal unknown static obstacles within ``sensor_range``; True when something new was seen."""
        new = False
        rng = self.sc.sensor_range
        if len(self.cell_lo):
            d = self._cell_gaps(position)
            seen = (d <= rng) & ~self.sensed_cells
            if np.any(seen):
                self.sensed_cells |= seen
                new = True
        if len(self.circles):
            d = np.hypot(self.circles[:, 0] - position[0], self.circles[:, 1] - position[1]) - self.circles[:, 2]
            seen = (d <= rng) & ~self.sensed_circles
            if np.any(seen):
                self.sensed_circles |= seen
                new = True
        return new

    def _cell_gaps(self, position: np.ndarray) -> np.ndarray:
        gap = np.maximum(np.maximum(self.cell_lo - position, position - (self.cell_lo + self.res)), 0.0)
        return np.hypot(gap[:, 0], gap[:, 1])

    @property
    def sensed_cell_indices(self) -> np.ndarray:
        """``(m, 2)`` integer cells of the unknown obstacles sensed so far."""
        return self.sc.unknown_cells[self.sensed_cells]

    @property
    def sensed_circle_rows(self) -> np.ndarray:
        """``(k, 3)`` unknown discs sensed so far."""
        return self.circles[self.sensed_circles]

    def believed_world(self):
        """The static world as the robot knows it now: known map plus sensed unknown
        obstacles (for re-planning and blocked-path tests). Sensed discs on a grid are
        rasterised to the cells they touch."""
        sc = self.sc
        if self.is_grid:
            from ..world.grid import GridMap

            cells = self.sensed_cell_indices
            circles = self.sensed_circle_rows
            if not len(cells) and not len(circles):
                return sc.world
            occ = sc.world.occ.copy()
            if len(cells):
                occ[cells[:, 1], cells[:, 0]] = True
            if len(circles):
                occ |= sc.world.cells_touched_by_discs(circles[:, :3])
            return GridMap(occ, sc.world.resolution, sc.world.origin, f"{sc.world.name}+sensed")
        circles = self.sensed_circle_rows
        if not len(circles):
            return sc.world
        return CircleWorld(sc.world.bounds, np.vstack([sc.world.circles, circles]), sc.world.safety, sc.world.name)

    def known_segments_free(self, a, b, clearance: float) -> np.ndarray:
        """The exact segment rule (``segments_free``) on the static world the robot knows now,
        without a circle world's planning ``safety``: ``(n,)`` bool for segments ``a[i] -> b[i]``."""
        key = (int(self.sensed_cells.sum()), int(self.sensed_circles.sum()))
        if self._known_world is None or self._known_world[0] != key:
            world = self.believed_world()
            if not self.is_grid:
                world = CircleWorld(world.bounds, world.circles, 0.0, world.name)
            self._known_world = (key, world)
        return self._known_world[1].segments_free(np.asarray(a, float).reshape(-1, 2),
                                                  np.asarray(b, float).reshape(-1, 2), clearance)

    # ------------------------------------------------------------ what the planner gets
    def static_distance(self, points) -> np.ndarray:
        """Signed distance (m) from points ``(..., 2)`` to the static obstacles the robot
        knows about (known map + sensed unknown obstacles); robot radius not subtracted."""
        p = np.asarray(points, dtype=float)
        d = np.asarray(self._known_distance(p), dtype=float)
        if np.any(self.sensed_cells):
            d = np.minimum(d, box_distance(p, self.cell_lo[self.sensed_cells], self.res))
        if np.any(self.sensed_circles):
            d = np.minimum(d, circle_distance(p, self.circles[self.sensed_circles]))
        return d

    def static_points(self, position: np.ndarray) -> np.ndarray:
        """Centres of known obstacle cells (or discs) and sensed unknown ones within
        ``sensor_range`` (plus half a cell diagonal) of ``position``."""
        reach = self.sc.sensor_range + self.res * np.sqrt(0.5)
        parts = []
        if self._tree is not None:
            idx = self._tree.query_ball_point(position, reach)
            if idx:
                parts.append(self._known_points[np.sort(idx)])
        if np.any(self.sensed_cells):
            c = self.cell_lo[self.sensed_cells] + self.res / 2
            parts.append(c[np.hypot(*(c - position).T) <= reach])
        if np.any(self.sensed_circles):
            c = self.circles[self.sensed_circles, :2]
            parts.append(c[np.hypot(*(c - position).T) <= reach])
        return np.vstack(parts) if parts else np.zeros((0, 2))

    # ----------------------------------------------------------------- ground truth
    def true_clearance(self, points) -> np.ndarray:
        """Exact signed distance (m) from points to every static obstacle, sensed or not."""
        d = np.asarray(self.true_static.clearance(points), dtype=float)
        if self.is_grid and len(self.circles):
            d = np.minimum(d, circle_distance(points, self.circles))
        return d

    def moving_gap(self, p0: np.ndarray, p1: np.ndarray, movers0: np.ndarray, movers1: np.ndarray) -> float:
        """Smallest footprint-to-mover distance (m) during one period (negative: overlap);
        ``inf`` without movers. Centres move linearly over the period (exact for that)."""
        if not len(movers0):
            return float("inf")
        _require_finite("moving collision check", p0, p1, movers0[:, :2], movers1[:, :2])
        gap = moving_min_distance(p0, p1, movers0[:, :2], movers1[:, :2]) - movers0[:, 4] - self.radius
        return float(gap.min())

    def static_check(self, positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Exact static collision test of a driven polyline, all periods at once.

        Args:
            positions: ``(n + 1, 2)`` robot centres at the period boundaries.

        Returns:
            ``(hit, clearance)``: ``hit[i]`` when the segment ``positions[i] -> positions[i+1]``
            fails ``segments_free(..., clearance=radius)`` on the true static world (and
            the unknown discs of a grid scenario); ``clearance[i]`` the smallest
            footprint-to-obstacle distance in that period (<= 0 where ``hit``), metres.
        """
        P = np.asarray(positions, dtype=float).reshape(-1, 2)
        _require_finite("static collision check", P)
        r = self.radius
        if len(P) < 2:
            return np.zeros(0, bool), np.zeros(0)
        a, b = P[:-1], P[1:]
        ok = np.asarray(self.true_static.segments_free(a, b, r), dtype=bool).reshape(-1)
        if self.is_grid and len(self.circles):
            ab = b - a
            L2 = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
            q = self.circles[:, :2]
            t = np.clip(np.einsum("ikj,ij->ik", q[None] - a[:, None], ab) / L2[:, None], 0.0, 1.0)
            near = a[:, None] + t[..., None] * ab[:, None]
            ok &= np.all(np.hypot(*(near - q[None]).transpose(2, 0, 1)) >= self.circles[:, 2] + r, axis=1)
        ends = self.true_clearance(P) - r
        clear = np.minimum(ends[:-1], ends[1:])
        bad = np.nonzero(~ok)[0]
        if len(bad):
            # the exact test failed somewhere along these segments: report the deepest sample
            s = np.linspace(0.0, 1.0, 17)
            pts = a[bad, None] + s[None, :, None] * (b[bad] - a[bad])[:, None]
            deep = self.true_clearance(pts.reshape(-1, 2)).reshape(len(bad), -1).min(axis=1) - r
            clear[bad] = np.minimum(np.minimum(clear[bad], deep), 0.0)
        return ~ok, clear
