"""``op.simulate``: one closed-loop run, global planner + navigation + local planner.

Each period ``dt`` (the scenario's):

1. the robot senses (unknown static obstacles within ``sensor_range`` become known;
   moving obstacles in range are reported with their velocities);
2. if something new blocks the rest of the global path, the navigator switches or
   re-plans (see ``optplan.nav.navigator``); if the robot has been stuck, it re-plans;
   if the path crosses a mover sweep the local planner has just learnt, it may re-plan
   round it (``sweep_detour``);
3. the navigator picks the subgoal, the local planner returns a command
   (timed: ``mean_step_ms``);
4. the command becomes the robot's velocity for the period (no hidden clipping unless
   ``actuator_limits=True``, so the recorded accelerations are the planner's own) and
   the pose advances by the paper's motion model (``optplan.sim.kinematics``);
5. the swept segment is checked exactly against every obstacle, sensed or not.

The run ends when the robot is within ``goal_tolerance`` of the goal (``reached``), when
``time_limit`` passes (``timeout``), when it stays stuck after its re-plans are used up
(``stuck``), or at the first collision when ``stop_on_collision=True`` (``collision``).
Collisions otherwise are counted per period and the run goes on.
"""
from __future__ import annotations

import inspect
import sys
import time
from dataclasses import replace
from typing import Any, Callable

import numpy as np

from ..checks import seed as checked_seed
from ..checks import seed_bound
from ..errors import ParameterError, UnknownAlgorithmError, named_with_hints
from ..local.base import LocalContext, MoverSweepSource
from ..nav.navigator import Navigator, default_global_clearance, preset_defaults
from ..results import SimResult
from ..world.robot import Command, RobotState
from ..world.scenario import MOVER_MOTIONS, Scenario, load_scenario
from ..worldgen.clutter import family_options, family_scenario
from ..worldgen.scenarios import realize
from .environment import SimEnvironment
from .kinematics import step_pose

OPTIONS = ("subgoals", "on_blocked", "replanner", "stuck_time", "stuck_distance", "max_replans", "sweep_detour", "stop_on_collision",
           "actuator_limits", "planner_params", "global_options", "subgoal_options", "progress", "time_limit", "global_plan",
           "mover_motion", "local_program")


def make_planner(local_planner, robot, dt: float, params: dict):
    """A local planner instance from a name (``optplan.local.make_local_planner``) or an
    object that already has ``command(ctx)``."""
    if hasattr(local_planner, "command"):
        return local_planner
    if not isinstance(local_planner, str):
        raise UnknownAlgorithmError(f"local_planner must be a name or a planner object, got {local_planner!r}")
    from ..local import make_local_planner

    return make_local_planner(local_planner.lower(), robot, dt, **params)


def _preset_program_name(program) -> str | None:
    """The paper preset a ``local_program`` option names (a preset's name or its program), else ``None``."""
    from ..local import PRESETS
    from ..local.preset_programs import PresetProgram

    if isinstance(program, PresetProgram):
        return program.name
    if isinstance(program, str) and program.lower() in PRESETS:
        return program.lower()
    return None


def _apply_limits(cmd: Command, prev: RobotState, robot, dt: float) -> tuple[float, float, float]:
    """Clip a command to speed limits and to the acceleration limits from ``prev``."""
    v = float(np.clip(cmd.v, max(robot.v_min, prev.v - robot.a_max * dt), min(robot.v_max, prev.v + robot.a_max * dt)))
    w = float(np.clip(cmd.w, max(-robot.w_max, prev.w - robot.alpha_max * dt), min(robot.w_max, prev.w + robot.alpha_max * dt)))
    vy = 0.0
    if robot.model == "omni":
        vy = float(np.clip(cmd.vy, max(-robot.vy_max, prev.vy - robot.a_max * dt), min(robot.vy_max, prev.vy + robot.a_max * dt)))
    return v, w, vy


def _progress_printer(every: float) -> Callable:
    next_t = [0.0]

    def report(t, state, info):
        if t + 1e-9 >= next_t[0]:
            next_t[0] += every
            print(f"t={t:7.1f}s  x={state.x:7.2f} y={state.y:7.2f}  v={state.v:5.2f}  "
                  f"to goal {info['to_goal']:6.2f} m  collisions {info['collisions']}", file=sys.stderr)

    return report


def scenario_for(scenario, seed=0) -> Scenario:
    """The scenario a run with ``seed`` uses: a generated family's world for that seed
    (``"clutter"``, ``"clutter-movers"``: :data:`optplan.worldgen.clutter.FAMILIES`), else
    ``load_scenario(scenario)`` (a Scenario, a file path or a shipped name)."""
    generated = family_scenario(scenario, seed) if isinstance(scenario, str) else None
    return generated if generated is not None else load_scenario(scenario)


def simulate(scenario: Scenario | str, global_planner: str = "astar", local_planner: Any = "dwa",
             refine: str | None = None, seed=0, **options) -> SimResult:
    """Run the robot of ``scenario`` from start to goal in closed loop.

    The global path is planned first; the scenario's random parts are then drawn from
    ``seed`` on that path (``optplan.worldgen.scenarios.realize``; :func:`realized_scenario`
    gives the same world for plotting).

    Args:
        scenario: a :class:`Scenario`, a path / shipped name for ``load_scenario``, or a
            generated family's name (``"clutter"``, ``"clutter-movers"``: the world is
            drawn from ``seed``, :func:`scenario_for`).
        global_planner: ``op.plan`` algorithm on the known map (``astar`` means
            ``visibility`` on circle worlds). The robot radius is the clearance
            (zero if no valid path keeps it; ``SimResult.message`` says so).
        local_planner: a preset name (``dwa``, ``missa-dwa``, ``idwa``, ``ba-dwa``,
            ``iga-dwa``, ``qp-dwa``), ``mpc`` (NMPC of a window program) or a planner object
            with ``reset``/``command``.
        refine: ``None``, ``"casadi"`` or ``"qp"`` refinement of the global path.
        seed: drives the global planner and the scenario's random obstacles.
        **options:
            subgoals: strategy name (``goal``, ``key_points``, ``turning_points``,
                ``navigation_points``); default: the local preset's paper default.
            on_blocked: ``switch`` / ``replan`` / ``ignore``; default per preset.
            replanner: ``exact`` (default: graph search, milliseconds) or ``global`` (the run's
                global planner with its options, e.g. IBA again as yuan2021 §4.2 re-plans).
            stuck_time (10 s), stuck_distance (0.3 m), max_replans (5): stuck recovery (re-plans
                for a blocked path are not limited).
            sweep_detour (1.5): re-plan round the mover sweeps the local planner has learnt
                (``qp-dwa``'s sweep gate) when the path crosses one and the way round is at most
                this many times as long; ``None`` keeps crossing them.
            stop_on_collision (False): end the run at the first collision.
            actuator_limits (False): clip commands to the speed/acceleration limits.
            planner_params: keyword arguments for ``make_local_planner``.
            global_options: keyword arguments for ``op.plan`` (``pop``, ``iters``, ``clearance``).
            subgoal_options: keyword arguments for the subgoal strategy.
            progress: ``True`` prints a status line to stderr every 10 simulated seconds;
                a number sets the interval; a callable gets ``(t, state, info)`` every period.
            time_limit: override the scenario's, seconds.
            mover_motion: override the motion of the scenario's random movers
                (``random_dynamic.motion``: ``"shuttle"`` or ``"once"``); a scenario without
                random movers is a ``ParameterError``.
            global_plan: a PlanResult to follow instead of planning (e.g. one global plan
                shared by several local planners; it must be for the same map, start and goal).
            local_program: an :class:`~optplan.formulations.local_program.LocalProgram`, or the
                name of one (``"default"``), solved every period by ``local_planner="dwa"``
                (sampling), ``"qp-dwa"`` (sampling + one SQP step, OSQP) or ``"mpc"`` (NMPC).
                ``mpc`` solves the default program without it.

    Returns:
        A :class:`SimResult` (``to_json_dict()`` gives the ``optplan simulate --json`` keys).
    """
    unknown = sorted(set(options) - set(OPTIONS))
    if unknown:
        named = list(inspect.signature(simulate).parameters)[1:-1]  # a misspelt local_planner= lands here too
        raise ParameterError(f"unknown simulate option(s) {named_with_hints(unknown, [*OPTIONS, *named])}; "
                             f"known: {', '.join(OPTIONS)}")
    checked_seed("seed", seed)
    seed_bound("seed", seed)
    options = {**family_options(scenario), **options}
    sc = with_mover_motion(scenario_for(scenario, seed), options.get("mover_motion"))
    if "time_limit" in options:
        sc = replace(sc, time_limit=options["time_limit"])
    robot, dt = sc.robot, sc.dt
    time_limit = sc.time_limit
    local_name = local_planner if isinstance(local_planner, str) else getattr(local_planner, "name", "custom")
    # a paper preset's program sampled by "dwa" is that preset: its navigation defaults and the
    # scenario's parameters for it are the preset's
    preset_name = _preset_program_name(options.get("local_program"))
    method_name = preset_name or str(local_name).lower()
    default_subgoals, default_blocked = preset_defaults(method_name)
    global_options = {**sc.global_options, **(options.get("global_options") or {})}
    wanted = default_global_clearance(method_name, robot.radius)
    if wanted is not None and "clearance" not in global_options:
        global_options["clearance"] = wanted
    nav = Navigator(sc.world, robot, sc.start[:2], sc.goal, global_planner=global_planner, refine=refine, seed=seed,
                    subgoals=options.get("subgoals", default_subgoals),
                    on_blocked=options.get("on_blocked", default_blocked),
                    stuck_time=options.get("stuck_time", 10.0), stuck_distance=options.get("stuck_distance", 0.3),
                    max_replans=options.get("max_replans", 5), global_options=global_options or None,
                    subgoal_options=options.get("subgoal_options"), sweep_detour=options.get("sweep_detour", 1.5),
                    replanner=options.get("replanner", "exact"))
    params = {}   # the scenario file's parameters of this planner, under the caller's
    if isinstance(local_planner, str):
        from ..local import algorithm_names

        unknown = sorted(set(sc.planner_params) - set(algorithm_names()))
        if unknown:
            raise ParameterError(f"the scenario's planner_params name(s) {named_with_hints(unknown, algorithm_names())}, "
                                 f"which are not local planners; known: {', '.join(algorithm_names())}")
        params = sc.planner_params.get(method_name, {})
    planner_params = {**params, **(options.get("planner_params") or {})}
    if options.get("local_program") is not None:
        planner_params["local_program"] = options["local_program"]
    planner = make_planner(local_planner, robot, dt, planner_params)
    # the global plan comes first: random obstacles are placed on the path the robot is given
    nav.plan_initial(options.get("global_plan"))
    sc = realize(sc, seed, path=nav.path)
    env = SimEnvironment(sc)
    progress = options.get("progress")
    if progress is True:
        progress = _progress_printer(10.0)
    elif isinstance(progress, (int, float)) and not isinstance(progress, bool) and progress > 0:
        progress = _progress_printer(float(progress))
    stop_on_collision = bool(options.get("stop_on_collision", False))
    limits = bool(options.get("actuator_limits", False))

    state = RobotState(float(sc.start[0]), float(sc.start[1]), float(sc.start[2]))
    planner.reset(state, nav.path)
    n_max = int(np.ceil(time_limit / dt - 1e-9))
    rows = [[0.0, state.x, state.y, state.theta, 0.0, 0.0]]
    vys = [0.0]
    step_ms: list[float] = []
    collisions, status = 0, "timeout"
    moving_hit = np.zeros(n_max, dtype=bool)
    moving_clear = np.full(n_max, np.inf)
    t = 0.0
    movers_now = env.movers(0.0)
    pos = np.array([state.x, state.y])
    if env.sense(pos):
        nav.on_new_obstacles(env.believed_world(), pos, t)
    for k in range(n_max):
        if np.hypot(*(pos - sc.goal)) <= sc.goal_tolerance:
            status = "reached"
            break
        if nav.check_stuck(pos, t, dt):
            sweeps = planner.mover_sweeps() if isinstance(planner, MoverSweepSource) else None
            if not nav.recover_stuck(env.believed_world(), pos, t, avoid=sweeps):
                if nav.gave_up:
                    status = "stuck"
                    break
        c, s_ = np.cos(state.theta), np.sin(state.theta)
        velocity = np.array([state.v * c - state.vy * s_, state.v * s_ + state.vy * c])
        seen = env.sensed_movers(pos, movers_now)
        subgoal = nav.subgoal(pos, velocity, seen, env.static_distance)
        ctx = LocalContext(state=RobotState(state.x, state.y, state.theta, state.v, state.w, state.vy),
                           subgoal=subgoal.copy(), goal=sc.goal.copy(), global_path=nav.path,
                           static_distance=env.static_distance, dynamic=seen, dt=dt, t=t,
                           static_points=env.static_points(pos), bounds=sc.bounds,
                           distance_error=env.distance_error, segments_free=env.known_segments_free)
        t0 = time.perf_counter()
        cmd = planner.command(ctx)
        step_ms.append((time.perf_counter() - t0) * 1e3)
        if not np.all(np.isfinite([cmd.v, cmd.w, cmd.vy])):
            raise ParameterError(f"local planner {local_name!r} returned a non-finite command "
                                 f"(v={cmd.v}, w={cmd.w}, vy={cmd.vy}) at t={t:.1f} s; this is a planner bug")
        if limits:
            v, w, vy = _apply_limits(cmd, state, robot, dt)
        else:
            v, w = float(cmd.v), float(cmd.w)
            vy = float(cmd.vy) if robot.model == "omni" else 0.0
        x1, y1, th1 = step_pose(robot.model, state.x, state.y, state.theta, v, w, dt, vy)
        new_pos = np.array([float(x1), float(y1)])
        t_next = (k + 1) * dt
        movers_next = env.movers(t_next)
        gap = env.moving_gap(pos, new_pos, movers_now, movers_next)
        moving_hit[k] = gap < 0
        moving_clear[k] = gap
        if stop_on_collision:
            static_hit, _ = env.static_check(np.array([pos, new_pos]))
            if moving_hit[k] or static_hit[0]:
                collisions += 1
                status = "collision"
        elif moving_hit[k]:
            collisions += 1  # running count for progress reports; recounted exactly below
        state = RobotState(float(x1), float(y1), float(th1), v, w, vy)
        pos, t, movers_now = new_pos, t_next, movers_next
        rows.append([t, state.x, state.y, state.theta, v, w])
        vys.append(vy)
        if status == "collision":
            break
        if env.sense(pos):
            nav.on_new_obstacles(env.believed_world(), pos, t)
        if isinstance(planner, MoverSweepSource):
            nav.on_sweeps(env.believed_world(), pos, t, planner.mover_sweeps())
        if progress:
            progress(t, state, {"to_goal": float(np.hypot(*(pos - sc.goal))), "collisions": collisions,
                                "subgoal": subgoal, "command": cmd})
    else:
        if np.hypot(*(pos - sc.goal)) <= sc.goal_tolerance:
            status = "reached"

    traj = np.array(rows)
    # static collisions of every period at once (exact rule), merged with the moving ones
    n = len(traj) - 1
    static_hit, static_clear = env.static_check(traj[:, 1:3])
    hit = static_hit | moving_hit[:n]
    collisions = int(hit.sum())
    min_clear = float(min(static_clear.min(initial=np.inf), moving_clear[:n].min(initial=np.inf)))
    if not np.isfinite(min_clear):  # no period driven: clearance of the start pose
        min_clear = float(env.true_clearance(traj[0, 1:3])) - env.radius
    return _result(sc, traj, np.array(vys), step_ms, collisions, min_clear, status, nav, global_planner,
                   local_name, refine, seed)


def with_mover_motion(sc: Scenario, motion: str | None) -> Scenario:
    """``sc`` with its random movers' motion set to ``motion`` (``None``: unchanged)."""
    if motion is None:
        return sc
    if motion not in MOVER_MOTIONS:
        raise ParameterError(f"mover_motion must be one of {', '.join(MOVER_MOTIONS)}, got {motion!r}")
    if not sc.random_dynamic:
        raise ParameterError(f"mover_motion: scenario {sc.name or '(unnamed)'} has no random movers (random_dynamic)")
    return replace(sc, random_dynamic={**sc.random_dynamic, "motion": motion})


def realized_scenario(scenario, seed, global_plan, mover_motion: str | None = None) -> Scenario:
    """The world a run of ``op.simulate(scenario, seed=seed, global_plan=global_plan,
    mover_motion=mover_motion)`` meets: random obstacles drawn from ``seed`` on the global path
    (with the exact start and goal)."""
    sc = with_mover_motion(scenario_for(scenario, seed), mover_motion)
    nav = Navigator(sc.world, sc.robot, sc.start[:2], sc.goal)
    nav.plan_initial(global_plan)
    return realize(sc, seed, path=nav.path)


def _result(sc: Scenario, traj: np.ndarray, vys: np.ndarray, step_ms, collisions: int, min_clear: float, status: str,
            nav: Navigator, global_planner, local_name, refine, seed) -> SimResult:
    dt = sc.dt
    # velocities include the robot at rest before the first period
    v = traj[:, 4]
    w = traj[:, 5]
    dv = np.hypot(np.diff(v), np.diff(vys)) if sc.robot.model == "omni" else np.abs(np.diff(v))
    acc = dv / dt
    signed_acc = np.diff(v) / dt
    jerk = np.abs(np.diff(signed_acc)) / dt if len(signed_acc) > 1 else np.zeros(0)
    length = float(np.hypot(*np.diff(traj[:, 1:3], axis=0).T).sum()) if len(traj) > 1 else 0.0
    steps = len(traj) - 1
    reached = status == "reached"
    words = {"reached": "reached the goal", "timeout": f"time limit {sc.time_limit:g} s reached",
             "stuck": "stuck after using every re-plan", "collision": "stopped at the first collision"}
    msg = f"{words[status]} after {traj[-1, 0]:.1f} s"
    if collisions:
        msg += f"; {collisions} period(s) in collision"
    if nav.switches:
        msg += f"; {nav.switches} path switch(es)"
    extra = [m for m in nav.messages]
    if extra:
        msg += "; " + "; ".join(extra[:6])
    return SimResult(reached=reached, collisions=int(collisions), time_s=float(traj[-1, 0]), path_length=length,
                     min_clearance=float(min_clear) if np.isfinite(min_clear) else float("inf"),
                     max_abs_accel=float(acc.max()) if len(acc) else 0.0,
                     max_abs_ang_accel=float((np.abs(np.diff(w)) / dt).max()) if len(w) > 1 else 0.0,
                     steps=steps, mean_step_ms=float(np.mean(step_ms)) if step_ms else 0.0, trajectory=traj,
                     status=status, message=msg, global_planner=nav.global_planner, local_planner=str(local_name),
                     refine=None if refine in (None, "none") else refine, global_path=nav.path,
                     seed=int(seed) if isinstance(seed, (int, np.integer)) else None, replans=nav.replans,
                     max_abs_jerk=float(jerk.max()) if len(jerk) else 0.0, path_switches=int(nav.switches),
                     reroute_s=nav.reroute_s)
