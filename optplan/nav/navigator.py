"""The fusion layer: global plan (+ refinement) -> subgoals -> local planner.

A :class:`Navigator` owns everything between the global planner and the local
planner during one closed-loop run:

* the initial global plan through ``optplan.planning.plan`` on the *known* map, with
  the robot radius as clearance (if that finds no valid path, it retries with zero
  clearance and says so in :attr:`messages`); on grids the path is extended by the
  exact start and goal (A* snaps both to cell centres, which lie in the same free cell);
* the subgoal strategy (``optplan.nav.subgoals``) of the local planner's paper;
* what to do when a newly sensed obstacle blocks the rest of the global path:
  ``"switch"`` — yuan2021 §4.2's virtual-point graph and Dijkstra
  (``optplan.nav.path_switch``), falling back to a re-plan when the graph has no route;
  ``"replan"`` — plan again from the robot's position on the known map plus what has
  been sensed; ``"ignore"`` — leave avoidance to the local planner (hou2024, yang2023
  and li2023 do this);
* stuck recovery: when the robot has moved less than ``stuck_distance`` in the last
  ``stuck_time`` seconds, the path is re-planned from where it is (at most
  ``max_replans`` times in a run). Re-plans for a blocked path do not count against that
  budget: they follow newly sensed obstacles, so there is at most one per sensing event,
  and a robot that has spent its stuck re-plans waiting for movers to pass must still
  be able to go round an obstacle it sees later;
* mover sweeps: a local planner that learns where movers drive back and forth
  (``qp-dwa``'s sweep gate, ``mover_sweeps()``) hands the sweeps over; when the path
  crosses one, the route round them is taken if it is at most ``sweep_detour`` times as
  long, and a stuck re-plan tries the way round them first.

Re-plans use fast exact graph search (``astar`` on grids, ``visibility`` on circle
worlds) on the believed world, not the global metaheuristic: a re-plan must be
available within a control period or two. ``replanner="global"`` re-plans a blocked
path with the run's own global planner and options instead (yuan2021 §4.2 compares its
path switch with running IBA again), falling back to exact search when that finds no
valid path; stuck recovery always re-plans exactly.

The wall time spent answering a blocked global path (the switch, or the re-plan, and a
switch's fallback re-plan) is recorded per answer (:attr:`Navigator.reroute_s`: their
mean, ``None`` while no path was blocked); building the switch's graph of the known map,
which §4.2 does with the global plan, is not part of that time.
"""
from __future__ import annotations

import time
from collections import deque

import numpy as np

from ..errors import InfeasibleQueryError, OptplanError, ParameterError, UnknownAlgorithmError
from ..papers import LOCAL_GUIDANCE, PAPERS, global_clearance_extra, local_guidance
from ..planning import plan
from ..world.polyline import point_segment_distances
from ..results import PlanResult
from .subgoals import SubgoalStrategy, make_strategy

# m beyond the robot radius: the intermediate clearances of Navigator.clearance_ladder
_LADDER_EXTRA = (0.1, 0.05, 0.025)

# each local planner preset's default (subgoal strategy, on_blocked), from the table of
# paper methods (optplan/papers.py)
PRESET_DEFAULTS = {**{p.local_preset: (p.subgoals, p.on_blocked) for p in PAPERS.values() if p.local_preset},
                   **LOCAL_GUIDANCE}
ON_BLOCKED = ("switch", "replan", "ignore")
# who re-plans: exact graph search, or the run's own global planner with its options
REPLANNERS = ("exact", "global")


def preset_defaults(local_name: str) -> tuple[str, str]:
    """``(subgoal strategy, on_blocked)`` used for a local planner name."""
    return local_guidance(local_name)


def default_global_clearance(local_name: str, radius: float) -> float | None:
    """The global path clearance a local planner asks for by default (``None``: the robot
    radius, the navigator's own default; ``optplan/papers.py:GLOBAL_CLEARANCE_EXTRA``)."""
    extra = global_clearance_extra(local_name)
    return radius + extra if extra else None


class Navigator:
    """Global path, subgoals and recovery for one run.

    Args:
        world: the known map.
        robot: RobotSpec (its radius is the planning clearance).
        start, goal: ``(2,)`` metres.
        global_planner: name for ``op.plan`` (``astar`` on a circle world means ``visibility``).
        refine: ``None``, ``"casadi"`` or ``"qp"``.
        seed: seed of the global planner.
        subgoals: strategy name or a :class:`SubgoalStrategy`.
        on_blocked: ``"switch"``, ``"replan"`` or ``"ignore"``.
        stuck_time, stuck_distance: seconds and metres of the stuck test.
        max_replans: stuck re-plans allowed in a run (re-plans for a blocked path are not
            limited: each follows newly sensed obstacles).
        global_options: extra keyword arguments for ``op.plan`` (``pop``, ``iters``, ...).
        subgoal_options: keyword arguments of the strategy (``switch_radius``, ...).
        sweep_detour: longest route round learnt mover sweeps, as a multiple of the rest of
            the path (:meth:`on_sweeps`); ``None`` keeps crossing them.
        replanner: who re-plans a blocked path: ``"exact"`` (graph search) or ``"global"``
            (``global_planner`` with ``global_options``, exact search when it finds no valid
            path).
    """

    def __init__(self, world, robot, start, goal, global_planner: str = "astar", refine: str | None = None,
                 seed=0, subgoals: str | SubgoalStrategy = "key_points", on_blocked: str = "replan",
                 stuck_time: float = 10.0, stuck_distance: float = 0.3, max_replans: int = 5,
                 global_options: dict | None = None, subgoal_options: dict | None = None,
                 sweep_detour: float | None = 1.5, replanner: str = "exact"):
        if on_blocked not in ON_BLOCKED:
            raise ParameterError(f"on_blocked must be one of {', '.join(ON_BLOCKED)}, got {on_blocked!r}")
        if replanner not in REPLANNERS:
            raise ParameterError(f"replanner must be one of {', '.join(REPLANNERS)}, got {replanner!r}")
        self.replanner = replanner
        self.world = world
        self.robot = robot
        self.start = np.asarray(start, float)
        self.goal = np.asarray(goal, float)
        self.is_grid = world.is_grid
        if not isinstance(global_planner, str):
            raise UnknownAlgorithmError(f"global_planner must be an algorithm name (see op.algorithms()), "
                                        f"got {global_planner!r:.60}")
        self.global_planner = global_planner.lower()
        if not self.is_grid and self.global_planner in ("astar", "dijkstra"):
            self.global_planner = "visibility"
        self.refine = None if refine in (None, "none") else refine
        self.seed = seed
        self.on_blocked = on_blocked
        self.stuck_time = float(stuck_time)
        self.stuck_distance = float(stuck_distance)
        self.max_replans = int(max_replans)
        if sweep_detour in (None, False, 0):
            sweep_detour = None
        elif isinstance(sweep_detour, bool) or not isinstance(sweep_detour, (int, float)) or not sweep_detour >= 1:
            raise ParameterError(f"sweep_detour must be a number >= 1 (longest detour, as a multiple of the rest of "
                                 f"the path) or None to keep crossing sweeps, got {sweep_detour!r}")
        self.sweep_detour = None if sweep_detour is None else float(sweep_detour)
        self.global_options = dict(global_options or {})
        self.strategy = subgoals if isinstance(subgoals, SubgoalStrategy) else \
            make_strategy(subgoals, robot.radius, **{"w_max": robot.w_max, **(subgoal_options or {})})
        self.replans = 0
        self.stuck_replans = 0
        self._n_sweeps = 0
        self._went_round = False
        self.switches = 0
        self.reroute_times: list[float] = []   # wall time of each answer to a blocked global path, seconds
        self.messages: list[str] = []
        self.plan_result: PlanResult | None = None
        self.path = np.zeros((0, 2))
        self._graph = None
        self._history: deque = deque()

    # ------------------------------------------------------------------ global plan
    def plan_initial(self, given: PlanResult | None = None) -> PlanResult:
        """Plan on the known map (the requested clearance, default the robot radius; if that
        gives no valid path, the robot radius, then zero clearance), or adopt
        ``given`` (a PlanResult planned earlier for the same map, start and goal)."""
        if given is not None:
            self.plan_result = given
            if not given.feasible:
                self.messages.append(f"the given global path is not valid ({given.message}); following it anyway")
            self._adopt(self._with_ends(given.path, self.start))
            return given
        opts = dict(self.global_options)
        wanted = float(opts.pop("clearance", self.robot.radius))
        tries = self.clearance_ladder(wanted)
        res = None
        for k, clearance in enumerate(tries):
            last = k == len(tries) - 1
            try:
                res = plan(self.world, self.start, self.goal, algorithm=self.global_planner, refine=self.refine,
                           seed=self.seed, clearance=clearance, **opts)
            except InfeasibleQueryError:
                if last:
                    raise
                continue
            if res.feasible or last:
                break
        if tries.index(clearance) > 0:
            self.messages.append(f"no valid global path with clearance {wanted:g} m; planned with {clearance:g} m")
        if not res.feasible:
            self.messages.append(f"the global path is not valid ({res.message}); following it anyway")
        self.plan_result = res
        self._adopt(self._with_ends(res.path, self.start))
        return res

    def clearance_ladder(self, wanted: float) -> list[float]:
        """Clearances tried in turn, the first valid path winning: ``wanted``, then (when it
        is above the robot radius) ``radius + 0.1``, ``+ 0.05``, ``+ 0.025`` below it, then the
        radius, then zero. Dropping from the wanted clearance straight to the bare footprint
        gave paths through gaps 1 cm wider than the robot where a gap 5 cm wider was there
        too; a local planner that keeps a safety margin stops in front of the former
        (issue 27). The intermediate rungs give the widest of those bottlenecks."""
        r = self.robot.radius
        tries = [wanted] + [r + e for e in _LADDER_EXTRA if r + e < wanted] + [r, 0.0]
        return list(dict.fromkeys(c for c in tries if c <= wanted))

    def _with_ends(self, path: np.ndarray, origin: np.ndarray) -> np.ndarray:
        P = np.asarray(path, float).reshape(-1, 2)
        if not len(P):
            return np.array([origin, self.goal])
        if np.hypot(*(P[0] - origin)) > 1e-9:
            P = np.vstack([origin, P])
        if np.hypot(*(P[-1] - self.goal)) > 1e-9:
            P = np.vstack([P, self.goal])
        return P

    def _adopt(self, path: np.ndarray, world=None) -> None:
        """Follow ``path``; subgoals are extracted against ``world`` (what is known now)."""
        self.path = path
        self.strategy.reset(path, self.world if world is None else world, self.goal)
        self.route = np.vstack([path[:1], self.strategy.targets])

    # --------------------------------------------------------------------- each step
    def subgoal(self, position, velocity, dynamic, static_distance=None) -> np.ndarray:
        """The local planner's target for this period."""
        return self.strategy.select(np.asarray(position, float), np.asarray(velocity, float), dynamic, static_distance)

    def path_blocked(self, believed_world, position) -> bool:
        """Whether the rest of the route the robot follows (its subgoal chain, from the
        point of the current leg nearest the robot on) collides with what is known now
        (exact rule, robot radius as clearance)."""
        R = self.route
        i = min(self.strategy.index, len(R) - 2)
        if i < 0:
            return False
        a, b = R[i], R[i + 1]
        ab = b - a
        L2 = float(ab @ ab)
        t = 0.0 if L2 == 0 else float(np.clip((np.asarray(position) - a) @ ab / L2, 0.0, 1.0))
        P = np.vstack([a + t * ab, R[i + 1:]])
        return not bool(np.all(believed_world.segments_free(P[:-1], P[1:], self.robot.radius)))

    def on_new_obstacles(self, believed_world, position, t: float) -> bool:
        """React to newly sensed static obstacles; True when the global path changed."""
        if self.on_blocked == "ignore":
            return False
        if not self.path_blocked(believed_world, position):
            return False
        if self.on_blocked == "switch":
            # the graph of the known map, which §4.2 builds with the global plan: not part of the answer's time
            self._switch_graph()
        t0 = time.perf_counter()
        try:
            if self.on_blocked == "switch":
                if self._switch(believed_world, position):
                    return True
                self.messages.append(f"t={t:.1f}s: path switch found no route; re-planning")
            return self.replan(believed_world, position, t, why="global path blocked", replanner=self.replanner)
        finally:
            self.reroute_times.append(time.perf_counter() - t0)

    def _switch_graph(self):
        """The virtual-point graph of the known map (yuan2021 §4.2), built once."""
        from .path_switch import VirtualPointGraph

        if self._graph is None:
            self._graph = VirtualPointGraph(self.world, self.start, self.goal, self.robot.radius)
        return self._graph

    def _switch(self, believed_world, position) -> bool:
        self._switch_graph().update(believed_world)
        route = self._graph.route(believed_world, position)
        if route is None:
            return False
        self.switches += 1
        self.replans += 1
        self._adopt(route, believed_world)
        return True

    def recover_stuck(self, believed_world, position, t: float, avoid=None) -> bool:
        """Stuck recovery: re-plan from ``position`` while the ``max_replans`` budget lasts;
        False when it is spent or the re-plan failed (the attempt counts).

        ``avoid``: ``(n, 5)`` rows ``(x0, y0, x1, y1, r)`` of stretches the movers sweep
        back and forth (a disc of radius ``r`` sliding from one end to the other), as the
        local planner has learnt them. A robot held up that long is usually waiting at a
        sweep it cannot cross between two passes (a sluggish robot next to a short, busy
        track), and the plain re-plan gives the same path back; so the re-plan first
        treats those sweeps as obstacles and takes a route round them if there is one."""
        if self.stuck_replans >= self.max_replans:
            return False
        self.stuck_replans += 1
        avoid = np.asarray(avoid if avoid is not None else np.zeros((0, 5)), float).reshape(-1, 5)
        if self._went_round:  # stuck on the way round: try the plain way again
            avoid = avoid[:0]
        self._went_round = False
        if len(avoid):
            around = self._without_sweeps(believed_world, avoid, np.asarray(position, float))
            res = None if around is None else self._plan_from(around, position, (self.robot.radius, 0.0))
            if res is not None:
                self.replans += 1
                self.messages.append(f"t={t:.1f}s: re-planned round {len(avoid)} mover sweep(s) (stuck)")
                self._went_round = True
                self._adopt(self._with_ends(res.path, np.asarray(position, float)), around)
                return True
        return self.replan(believed_world, position, t, why="stuck")

    def on_sweeps(self, believed_world, position, t: float, sweeps) -> bool:
        """React to the mover sweeps the local planner has learnt (rows as in
        :meth:`recover_stuck`); True when the global path changed.

        Each time the set grows and the rest of the path passes within the robot radius plus
        0.1 m of a sweep, the path is re-planned with every learnt sweep blocked; the route
        round is taken when it is at most ``sweep_detour`` times as long as the rest of the
        current path. Crossing a mover's sweep means timing a gap between two passes; where
        a short detour avoids that, the sluggish robots of li2023 Experiment II stop being
        run into (``benchmarks/dynamic_qp_dwa.yaml``: li2023_exp2_3-5 134 -> 140 of 150),
        at the price of a few runs on the open 50x50 maps of hou2024 (see the issue note)."""
        sweeps = np.asarray(sweeps, float).reshape(-1, 5)
        grew = len(sweeps) > self._n_sweeps
        self._n_sweeps = len(sweeps)
        if not grew or not self.sweep_detour:
            return False
        position = np.asarray(position, float)
        rest = self._rest_of_path(position)
        dense = np.vstack([np.linspace(a, b, max(2, int(np.hypot(*(b - a)) / 0.05) + 1))
                           for a, b in zip(rest[:-1], rest[1:])])
        near = [point_segment_distances(dense, row[:2], row[2:4]).min() < row[4] + self.robot.radius + 0.1 for row in sweeps]
        if not any(near):
            return False
        around = self._without_sweeps(believed_world, sweeps, position)
        res = None if around is None else self._plan_from(around, position, (self.robot.radius, 0.0))
        if res is None or res.length > self.sweep_detour * float(np.hypot(*np.diff(rest, axis=0).T).sum()):
            return False
        self.replans += 1
        self.messages.append(f"t={t:.1f}s: re-planned round {len(sweeps)} mover sweep(s) (the path crossed one)")
        self._adopt(self._with_ends(res.path, position), around)
        self._went_round = True
        return True

    def _rest_of_path(self, position: np.ndarray) -> np.ndarray:
        """The robot's position, then the path from the node after the nearest one on."""
        P = self.path
        i = int(np.argmin(np.hypot(*(P - position).T)))
        return np.vstack([position, P[i + 1:] if i + 1 < len(P) else P[-1:]])

    @staticmethod
    def _without_sweeps(world, sweeps: np.ndarray, position: np.ndarray):
        """``world`` with the mover sweeps (capsules) blocked, or ``None`` where that is not
        representable. On a grid the cells a capsule reaches into are blocked, except the
        robot's own cell (the robot waits beside the sweep, often in a cell it touches)."""
        discs = []
        for x0, y0, x1, y1, r in sweeps:  # a capsule as discs r/2 apart (scallops < 0.04 r deep)
            n = max(1, int(np.ceil(np.hypot(x1 - x0, y1 - y0) / (0.5 * r))))
            f = np.linspace(0.0, 1.0, n + 1)
            discs.append(np.stack([x0 + f * (x1 - x0), y0 + f * (y1 - y0), np.full(n + 1, r)], axis=1))
        discs = np.vstack(discs)
        if world.is_grid:
            from ..world.grid import GridMap

            occ = world.occ | world.cells_touched_by_discs(discs)
            ix, iy = world.cell_of(position)
            if world.in_map(np.array([ix, iy])):
                occ[iy, ix] = world.occ[iy, ix]
            return GridMap(occ, world.resolution, world.origin, f"{world.name}+sweeps")
        if hasattr(world, "circles"):
            from ..world.circles import CircleWorld

            return CircleWorld(world.bounds, np.vstack([world.circles, discs]), world.safety, f"{world.name}+sweeps")
        return None

    @property
    def gave_up(self) -> bool:
        """Every stuck re-plan has been used."""
        return self.stuck_replans >= self.max_replans

    @property
    def reroute_s(self) -> float | None:
        """Mean wall time of one answer to a blocked global path (switch or re-plan), seconds;
        ``None`` when no path was blocked."""
        return float(np.mean(self.reroute_times)) if self.reroute_times else None

    def replan(self, believed_world, position, t: float, why: str, replanner: str = "exact") -> bool:
        """Plan again from ``position`` on ``believed_world`` (exact graph search, or with
        ``replanner="global"`` the run's global planner; stuck recovery always re-plans exactly:
        a stuck robot needs a way out now)."""
        wanted = float(self.global_options.get("clearance", self.robot.radius))
        res = self._plan_from(believed_world, position, self.clearance_ladder(wanted), replanner)
        self.replans += 1  # a failed attempt counts too, so a hopeless situation ends
        if res is None:
            self.messages.append(f"t={t:.1f}s: re-planning failed ({why})")
            return False
        self.messages.append(f"t={t:.1f}s: re-planned ({why})")
        self._adopt(self._with_ends(res.path, np.asarray(position, float)), believed_world)
        return True

    def _plan_from(self, world, position, clearances, replanner: str = "exact") -> PlanResult | None:
        """The first valid path from ``position`` to the goal on ``world`` with one of
        ``clearances`` (``replanner``'s, then exact graph search), or ``None``."""
        exact = "astar" if self.is_grid else "visibility"
        tries = [(exact, {})]
        if replanner == "global" and self.global_planner != exact:
            tries.insert(0, (self.global_planner, {"seed": self.seed, **{k: v for k, v in self.global_options.items()
                                                                          if k != "clearance"}}))
        for k, (method, opts) in enumerate(tries):
            for clearance in clearances:
                try:
                    res = plan(world, np.asarray(position, float), self.goal, algorithm=method, clearance=clearance,
                               **opts)
                except OptplanError:
                    continue
                if res.feasible:
                    return res
            if k + 1 < len(tries):
                self.messages.append(f"{method} found no valid path from here; exact search re-plans")
        return None

    def check_stuck(self, position, t: float, dt: float) -> bool:
        """Record the position; True when the robot stayed within ``stuck_distance`` of
        where it was ``stuck_time`` seconds ago all that time."""
        self._history.append((t, np.asarray(position, float).copy()))
        while self._history and self._history[0][0] < t - self.stuck_time - 1e-9:
            self._history.popleft()
        t0, p0 = self._history[0]
        if t - t0 < self.stuck_time - 0.5 * dt:
            return False
        # cheap test first: the newest position already left the circle
        if float(np.hypot(*(position - p0))) >= self.stuck_distance:
            return False
        P = np.array([p for _, p in self._history])
        if float(np.hypot(*(P - p0).T).max()) < self.stuck_distance:
            self._history.clear()
            return True
        return False
