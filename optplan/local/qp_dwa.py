"""qp-dwa: sampled DWA, then a small QP that refines the chosen velocity, then Ruckig.

1. **Sampling** (``DWAPlanner``): the best admissible sample ``u0`` of the window under
   the preset's terms.
2. **QP** (OSQP, set up once, updated and warm-started every step): stay as close as
   possible to ``u0`` inside the dynamic window while keeping ``qp_margin`` metres of
   clearance to the obstacles the chosen trajectory comes closest to, linearised at ``u0``:

       minimise   1/2 (u - u0)' W (u - u0) + c s + 1/2 M s^2
       subject to window_lo <= u <= window_hi,   s >= 0,
                  g_j(u0) + grad g_j(u0) . (u - u0) + s >= qp_margin    (rows j)

   ``g_j`` is the edge-to-edge gap at the time the trajectory passes closest to a predicted
   mover (over ``qp_horizon``), or at the trajectory's closest points to static obstacles
   over the part the robot is committed to before it can stop (gradient of the distance
   field by central differences); a static row asks no more margin than the global path
   keeps next to that point. The slack ``s`` keeps the QP feasible when the
   margin cannot be met within the window (the second pass's rows that must hold take it at
   1/100). ``W`` scales each component by its window
   half-width so a step across the window costs the same in ``v`` and ``w``. The position
   derivatives ``dz/du`` come from the rollout formula of ``rollout.py`` in closed form.
   The QP is not run when ``u0`` meets every row by its margin (``u0`` is then its
   optimum) or no command of the window moves a row's point. The result is checked on the
   exact rollout (admissible, no earlier mover contact, no closer to obstacles than ``u0``)
   and by the filters, as they judged ``u0`` (``passes_like``). A result that fails a check
   gets a second pass (``qp_passes``) with rows for what it failed, and the QP is solved
   again: where it comes closer to an obstacle no row was linearised at, rows linearised at
   the result; where it fails a filter, the filter's rows of its trajectory, asking what the
   filter asked of ``u0``; where it meets a mover earlier than ``u0``, rows from that contact
   to ``u0``'s, and where it cannot stop before a static obstacle, rows at its first
   colliding points, both linearised at ``u0``. These ask only what ``u0`` achieves: the
   slack relaxes them 100 times less (``_SLACK_REPAIR_FACTOR``). A result that still fails a check is
   shortened towards ``u0`` or towards the first pass's answer (half, then a quarter of the
   step; the QP's convex objective falls all the way). On a non-solved OSQP status, or when no step passes, the sampled
   ``u0`` is used; ``info["qp"]`` says which case happened.
3. **Ruckig** (``limiter.RuckigLimiter``): the refined velocity becomes the target of a
   jerk-limited profile; the command is the profile one period ahead.
4. **Recursive feasibility** (``safe_continuation``): the command is sent only if, after it,
   the limiter's stop stays clear of the static map and of every predicted mover for the
   horizon, or holding it does; otherwise the sampled command, then braking, is tried, and
   if none qualifies the first choice is sent and ``info["continuation"]`` is ``"none"``.
   Braking is the last option, so a step whose command was checked leaves the next step a
   checked stop (the same jerk-limited profile).

The window of the next step is the velocity range the Ruckig profile can reach in one
period (``window.py``), and the stopping distance in the admissibility test includes one
period plus the jerk ramp ``a_max / jerk_max`` of reaction time.

From the first step at which the global path near the robot is tight (:func:`path_is_tight`,
read from the map the planner sees), the sampling stage also uses the clutter mechanisms of
issue 27 (:data:`TIGHT_PATH_PARAMS`): pure-pursuit samples along the path, the path critics
judged up to where the robot must stop, and the path creep (``creep.py``). They stay on for
the rest of the run (``tight_hold``): switched off again on an open stretch between tight ones,
they left robots stuck in clutter (docs/measurements.md, "qp-dwa's clutter mechanisms by default").

Everything is deterministic.
"""
from __future__ import annotations

import dataclasses
import math
import time
from typing import Any, Mapping

import numpy as np
import osqp
import scipy.sparse as sp

from ..checks import boolean
from ..errors import ParameterError
from ..world.robot import Command, RobotSpec, RobotState
from .base import LocalContext
from .dwa import DWAPlanner, Preset
from .hooks import Roles, build_part
from .limiter import RuckigLimiter
from .critics import point_at_arc, project_on_path
from .mechanisms import MECHANISMS
from .rollout import Rollouts, Step, current_gaps, static_gradient
from .window import Window, dynamic_window

_SLACK_LINEAR, _SLACK_QUADRATIC = 1e2, 1e4
# the rows that ask only what the sample achieves (QPDWAPlanner._repair_rows) take the slack
# at 1/100: with it at full weight, a margin the window cannot give (0.35 m of slack) waived
# them as well (a second slack variable did the same, but OSQP hit its iteration limit twice
# as often)
_SLACK_REPAIR_FACTOR = 100.0

# info["qp"] of the steps whose QP stage solves nothing: no row is active, the chosen sample
# follows the path with a command that changes along the horizon (the QP linearises a constant one),
# the sample meets every row, or no command of the window moves the rows' points
_REACH = 1e-6  # m: a row no command of the window moves by this much is out of the QP's reach
_BACKTRACK = (0.5, 0.25)  # shorter steps towards the QP's optimum tried when the full one fails a check
_GAP_TOL = 1e-5  # m: OSQP's tolerance (1e-5 in the command) moves the gaps by micrometres
QP_NOT_RUN = ("inactive", "path sample", "rows hold at the sample", "rows out of the command's reach")


_BLOCKED = 0.01  # m: a global path this far inside the footprint's clearance runs into an obstacle
_TIGHT_SHARE = 0.5  # path_is_tight: the share of the stretch near the robot that must run close to obstacles

# qp-dwa's clutter mechanisms (issue 27), as planner parameters: pure-pursuit samples along the
# global path at 0.5 and 1 x v_max (rollout.rollout_tracking), the path critics judged up to
# where the robot must stop before a static obstacle (critics._trajectory_end), and the path
# creep (creep.py). They are qp-dwa's defaults where the global path is tight
# (path_is_tight); a parameter the user gives (e.g. path_creep=False, path_samples=()) is
# used everywhere instead.
TIGHT_PATH_PARAMS: dict[str, Any] = {
    "path_samples": (0.5, 1.0),
    "path_progress": {"until_stop": True}, "path_heading": {"until_stop": True},
    "path_deviation": {"until_stop": True},
    "path_creep": {},
}


def path_is_tight(ctx: LocalContext, radius: float, gap: float, ahead: float) -> bool:
    """qp-dwa's rule for its clutter mechanisms (issue 43): whether the global path near the robot
    is *tight*: at least half of it (``_TIGHT_SHARE``) runs within ``gap`` metres of a static
    obstacle, edge to edge beyond a footprint of ``radius``.

    Read from the static world the planner sees (``ctx.static_distance``: the map and the
    obstacles sensed so far) at path points 5 cm apart, from ``radius`` behind the robot's
    nearest path point to ``ahead`` metres beyond it. Half the stretch is more than one convex
    corner can account for (a path passing a corner comes within ``gap`` of it over at most
    ``2 (radius + gap)`` metres, 0.7 m of the 1.7 m for a 0.2 m robot): the path runs along
    obstacles or threads a row of gaps, as in clutter. A path that enters an obstacle
    (``_BLOCKED`` inside the footprint's clearance) is blocked, not tight: it runs into an
    obstacle sensed after it was planned, and the navigator re-plans it.

    Why this rule: the window's constant-command arcs and the QP keep ``qp_margin`` (0.15 m) of
    clearance where they can. Along a path that keeps less than that for metres (BARN-style
    clutter, where an A* path with the footprint as clearance hugs one obstacle after another),
    every arc grazes an obstacle within a second and the window stalls; there the path samples,
    the critics judged to the stop and the creep get the robot through. Past a single corner,
    or along open ground, the arcs have room; there (the shipped and paper maps with crossing
    movers, whose replanned and metaheuristic paths hug corners) the mechanisms only changed
    which runs a mover caught, and on open ground they slowed the robot. Measured with
    ``benchmarks/qp_dwa_defaults.py`` (docs/measurements.md, issue 43)."""
    if not math.isfinite(gap):
        return True
    if gap <= 0:
        return False
    p = np.asarray(ctx.global_path, dtype=float).reshape(-1, 2)
    if len(p) < 2:
        return False
    # the robot's nearest path point (all segments at once), then points along the path
    a, ab = p[:-1], np.diff(p, axis=0)
    L = np.hypot(ab[:, 0], ab[:, 1])
    t = np.clip(((ctx.state.x - a[:, 0]) * ab[:, 0] + (ctx.state.y - a[:, 1]) * ab[:, 1]) / np.maximum(L * L, 1e-18),
                0.0, 1.0)
    k = int(np.argmin(np.hypot(a[:, 0] + t * ab[:, 0] - ctx.state.x, a[:, 1] + t * ab[:, 1] - ctx.state.y)))
    along = np.r_[0.0, np.cumsum(L)]
    s = np.clip(along[k] + t[k] * L[k] + np.arange(-radius, ahead + 1e-9, 0.05), 0.0, along[-1])
    j = np.clip(np.searchsorted(along, s, side="right") - 1, 0, len(ab) - 1)
    pts = a[j] + ((s - along[j]) / np.maximum(L[j], 1e-18))[:, None] * ab[j]
    clear = np.asarray(ctx.static_distance(pts), dtype=float).ravel() - radius
    if clear.min() < -_BLOCKED:
        return False
    return bool(np.mean(clear < gap) >= _TIGHT_SHARE)


def qp_outcome(info: Mapping[str, Any]) -> str | None:
    """How a qp-dwa step's QP stage ended, from its command's ``info``: ``"used"`` (the QP
    result was commanded), ``"not run"`` or ``"fallback"`` (``None``: the stage was not reached).
    The QP's share is used / (used + fallback)."""
    status = info.get("qp")
    if status is None:
        return None
    if status.startswith("solved"):
        return "used"
    return "not run" if status in QP_NOT_RUN else "fallback"


class LeanOSQP:
    """The per-step calls of an ``osqp.OSQP`` object, without the Python wrapper's
    bookkeeping.

    ``osqp.OSQP.update`` looks up ``OSQP_INFTY`` and fills a derivative cache on every
    call, and ``solve`` copies every info field into a new namespace; for a 4-variable
    QP solved each 0.1 s control period that costs 2-3 times OSQP's own solve time
    (measured with ``benchmarks/dwa_step.py``). Where the installed osqp exposes its
    compiled solver (``_solver``, osqp >= 1.0) the calls go to it directly; otherwise the
    public API is used. Either way the same solver runs with the same data.
    """

    def __init__(self, qp: osqp.OSQP) -> None:
        self.qp = qp
        self.infinity = float(qp.constant("OSQP_INFTY"))
        core = getattr(qp, "_solver", None)
        self.core = core if core is not None and hasattr(core, "update_data_vec") and hasattr(core, "solve") else None

    def step(self, q: np.ndarray, lower: np.ndarray, upper: np.ndarray, Ax: np.ndarray,
             x_start: np.ndarray) -> tuple[int, str, np.ndarray | None, float]:
        """Update ``q``, bounds and the values of ``A``, warm-start at ``x_start``, solve;
        returns ``(status_val, status, x, OSQP's solve time in s)``. ``lower`` and ``upper``
        are clipped to OSQP's infinity in place (the caller builds them fresh each step)."""
        if self.core is None:
            self.qp.update(q=q, l=lower, u=upper, Ax=Ax)
            self.qp.warm_start(x=x_start)
            res = self.qp.solve(raise_error=False)
            return res.info.status_val, res.info.status, res.x, float(res.info.solve_time)
        # ufuncs rather than np.clip, and positional calls straight to the compiled solver:
        # each Python-level layer costs microseconds when the caches are cold, as they are
        # after the step's rollouts
        np.maximum(lower, -self.infinity, out=lower)
        np.minimum(upper, self.infinity, out=upper)
        core = self.core
        core.update_data_vec(q, lower, upper)
        core.update_data_mat(None, None, Ax, None)
        core.warm_start(x_start, None)
        core.solve()
        info = core.info
        return info.status_val, info.status, np.array(core.solution.x), info.solve_time


class QPDWAPlanner(DWAPlanner):
    """The ``qp-dwa`` local planner (see the module docstring)."""

    OPTIONS = {
        **DWAPlanner.OPTIONS,
        "qp_horizon": 1.5,       # s of the trajectory whose clearance the QP constrains
        "qp_margin": 0.15,       # edge-to-edge clearance the QP tries to keep, m
        "qp_activate": 0.6,      # obstacles closer than this to the chosen trajectory become rows, m
        "qp_rows_moving": 4,     # at most this many mover rows ...
        "qp_rows_static": 4,     # ... and static rows
        "qp_rows_filters": 4,    # ... and rows for the filters' clearances (the sweep gate's intervals)
        "qp_max_iter": 10000,    # OSQP iteration budget (a non-solved status falls back)
        "qp_passes": 2,          # linearisations: a pass adds rows where the last result came close
        "ang_jerk_max": None,    # rad/s^3; None = jerk_max * alpha_max / a_max (same ramp time)
        # issue 27 (clutter), off by default: each gave 1-2 collisions in the 40 runs of
        # benchmarks/dynamic_qp_dwa.yaml in some combination (see docs/measurements.md)
        "qp_committed": False,        # static rows over the committed part only, margins capped
        "continuation_check": False,  # recursive feasibility check of every command
        # where the clutter mechanisms (TIGHT_PATH_PARAMS) apply: path_is_tight's gap (m; 0 =
        # nowhere, inf = everywhere) and the metres of path ahead of the robot it reads
        "tight_gap": 0.15,
        "tight_ahead": 1.5,
        "tight_hold": math.inf,  # s the mechanisms stay after the path was last tight (default: the rest of the run)
    }

    def __init__(self, preset: Preset, robot: RobotSpec, dt: float, program=None, **params: Any) -> None:
        super().__init__(preset, robot, dt, program=program, **params)
        o = self.options
        for k in ("qp_horizon", "qp_margin", "qp_activate"):
            o[k] = self._number(k, o[k], allow_zero=k == "qp_margin")
        for k in ("tight_gap", "tight_hold"):  # inf: everywhere / for the rest of the run
            o[k] = self._number(k, o[k], allow_zero=True, allow_inf=True)
        o["tight_ahead"] = self._number("tight_ahead", o["tight_ahead"], allow_zero=True)
        self._setup_tight(params)
        for k in ("qp_rows_moving", "qp_rows_static", "qp_rows_filters", "qp_max_iter", "qp_passes"):
            if isinstance(o[k], bool) or not isinstance(o[k], (int, np.integer)) or o[k] < (1 if k in ("qp_max_iter", "qp_passes") else 0):
                raise ParameterError(f"{k} must be a non-negative int, got {o[k]!r}")
            o[k] = int(o[k])
        for k in ("qp_committed", "continuation_check"):
            o[k] = boolean(k, o[k])
        if robot.jerk_max is None:
            self.jerk = (None, None)
        else:
            ang = o["ang_jerk_max"]
            ang = robot.jerk_max * robot.alpha_max / robot.a_max if ang is None else self._number("ang_jerk_max", ang)
            self.jerk = (robot.jerk_max, ang)
        # components: v, w (, vy)
        self.n_u = 3 if self.omni else 2
        # omni: the limits bound the (v, vy) vector, so each component gets 1/sqrt(2) of them
        self.a_lin = robot.a_max / math.sqrt(2) if self.n_u == 3 else robot.a_max
        lin_jerk = None if self.jerk[0] is None else self.jerk[0] * self.a_lin / robot.a_max
        self.jerk = (lin_jerk, self.jerk[1])
        acc = [self.a_lin, robot.alpha_max, self.a_lin][:self.n_u]
        jerk = [self.jerk[0], self.jerk[1], self.jerk[0]][:self.n_u]
        self.limiter = RuckigLimiter(self.dt, acc, [math.inf if j is None else j for j in jerk])
        self._setup_qp(acc)
        self.qp_times_us: list[float] = []

    # ------------------------------------------------------------------ tight paths
    def _setup_tight(self, params: Mapping[str, Any]) -> None:
        """The two configurations the rule chooses between (:func:`path_is_tight`): the one the
        user's parameters give, and the same with those of :data:`TIGHT_PATH_PARAMS` the user
        did not give. ``self.tight`` says which one the last step used."""
        self.tight = False
        self._tight_until = -math.inf
        self._plain = (list(self.terms), self.options["path_samples"], self.roles)
        given = set(params)
        samples = self.options["path_samples"]
        if "path_samples" not in given and self.options["path_look_aheads"] and self.options["path_turn_first"]:
            samples = tuple(TIGHT_PATH_PARAMS["path_samples"])
        terms = []
        for critic, w in self.terms:
            extra = TIGHT_PATH_PARAMS.get(critic.name, {})
            mine = params.get(critic.name)
            own = set(mine) if isinstance(mine, Mapping) else set()
            change = {k: v for k, v in extra.items() if k not in own and hasattr(critic, k)}
            terms.append((dataclasses.replace(critic, **change) if change else critic, w))
        self._creep = None
        if "path_creep" not in given and not any(m.name == "path_creep" for m in self.mechanisms):
            self._creep = build_part(MECHANISMS["path_creep"], TIGHT_PATH_PARAMS["path_creep"], "path_creep")
            self.mechanisms.append(self._creep)
        roles = Roles.of(self.mechanisms) if self._creep is not None else self.roles
        self._tight = (terms, samples, roles)
        self._rule = self._tight[:2] != self._plain[:2] or self._creep is not None

    def _use(self, ctx: LocalContext | None) -> None:
        """Take the configuration of this step: the tight one where :func:`path_is_tight` says
        so (``ctx=None``: the plain one). A creep under way goes on until it hands back; the
        creep's stall count runs only while the path is tight."""
        if not self._rule:
            return
        o = self.options
        if ctx is None:
            self._tight_until = -math.inf
        elif ctx.t > self._tight_until and path_is_tight(ctx, self.robot.radius, o["tight_gap"], o["tight_ahead"]):
            self._tight_until = ctx.t + o["tight_hold"]
        self.tight = ctx is not None and ctx.t <= self._tight_until
        creeping = self._creep is not None and self._creep.active
        self.terms, o["path_samples"], self.roles = self._tight if self.tight or creeping else self._plain
        if self._creep is not None and not (self.tight or creeping) and ctx is not None:
            self._creep.reset(self.view, ctx.state, ctx.global_path)

    def command(self, ctx: LocalContext) -> Command:
        self._use(ctx)
        cmd = super().command(ctx)
        if self._rule:
            cmd.info["tight"] = self.tight
        return cmd

    # ------------------------------------------------------------------ QP set-up (once)
    def _setup_qp(self, acc) -> None:
        n = self.n_u + 1  # + slack
        o = self.options
        # the first pass has every kind of row, each later one adds mover and static rows
        m_rows = (o["qp_rows_moving"] + o["qp_rows_static"]) * o["qp_passes"] + o["qp_rows_filters"]
        half_width = np.asarray(acc, dtype=float) * (self.options["lookahead"] or self.dt)  # of the window
        self._half_width = half_width
        self._W = 1.0 / half_width ** 2
        P = sp.diags(np.r_[self._W, _SLACK_QUADRATIC]).tocsc()
        # box rows (identity) then clearance rows, dense in every column: the pattern is fixed
        # once so each step only updates values (explicit zeros kept in the pattern)
        dense = np.vstack([np.eye(n), np.ones((m_rows, n))])
        rows, cols = np.nonzero(dense)
        order = np.lexsort((rows, cols))  # CSC order: by column, then row
        self._A_rows, self._A_cols = rows[order], cols[order]
        A = sp.csc_matrix((np.ones(len(order)), (self._A_rows, self._A_cols)), shape=dense.shape)
        A.sort_indices()
        self._m_rows = m_rows
        self._n_x = n
        self._qp = osqp.OSQP()
        self._qp.setup(P, np.zeros(n), A, np.full(dense.shape[0], -np.inf), np.full(dense.shape[0], np.inf),
                       verbose=False, warm_starting=True, polishing=False, max_iter=self.options["qp_max_iter"],
                       eps_abs=1e-5, eps_rel=1e-5, check_termination=5)
        self._lean = LeanOSQP(self._qp)
        self._solved = osqp.SolverStatus.OSQP_SOLVED

    # ------------------------------------------------------------------ overrides
    def _reaction(self) -> float:
        ramp = 0.0 if self.jerk[0] is None else self.a_lin / self.jerk[0]
        return self.options["reaction"] + self.dt + ramp

    def reset(self, state: RobotState, global_path: np.ndarray) -> None:
        self._use(None)
        super().reset(state, global_path)
        if self._creep is not None:
            self._creep.reset(self.view, state, global_path)
        self.limiter.reset(self._vel(state))

    def _vel(self, state: RobotState) -> np.ndarray:
        return np.array([state.v, state.w, state.vy][:self.n_u])

    def window(self, ctx: LocalContext) -> Window:
        self._resynced = self.limiter.sync(self._vel(ctx.state))
        if self.options["lookahead"] is not None:  # targets that Ruckig will ramp to
            win = dynamic_window(self.robot, ctx.state, self.options["lookahead"], omni=self.omni, a_lin=self.a_lin)
        else:  # what the jerk-limited profile can reach within one period
            acc = np.r_[self.limiter.acceleration, 0.0, 0.0][:3]
            a3 = (acc[0], acc[1], acc[2] if self.n_u == 3 else 0.0)
            win = dynamic_window(self.robot, ctx.state, ctx.dt, omni=self.omni, accel=a3, jerk=self.jerk,
                                 a_lin=self.a_lin)
        for m in self.roles.caps_window:
            win = m.adjust_window(self.view, ctx, win)
        return win

    def finish(self, ctx, window, u, step, info):
        target = u
        tracking = step is not None and step.roll.tracking is not None and info.get("index") is not None and bool(step.roll.tracking[info["index"]])
        if tracking:  # its command changes along the horizon; the QP linearises a constant one
            info["qp"] = "path sample"
        elif step is not None and info.get("mode") in ("sample", "sample-relaxed", "evade"):
            target = self.refine(ctx, window, u, step, info)
        # recursive feasibility: the command must leave a safe continuation (see
        # safe_continuation); else the sampled command, else braking, is commanded
        options = [("refined", target)] if target is not u else []
        if self.options["continuation_check"]:
            options += [("sampled", u), ("brake", (0.0, 0.0, 0.0))]
        else:
            options = options or [("sampled", u)]
        snap = self.limiter.snapshot()
        for name, tgt in options:
            self.limiter.restore(snap)
            out, result = self.limiter.step(np.array([tgt[0], tgt[1], tgt[2]][:self.n_u]))
            if not self.options["continuation_check"]:
                how = "unchecked"
                break
            how = self.safe_continuation(ctx, out)
            if how:
                break
        else:
            # nothing is known safe (e.g. a mover closing in, or every stop on a mover's predicted
            # line): the first choice, as without the check. Taking the sampled command here
            # instead threw away the QP's added mover clearance exactly when it mattered, and a
            # mover hit the robot in hou2024_dynamic4 seed 2 of benchmarks/dynamic_qp_dwa.yaml
            name, tgt = options[0]
            self.limiter.restore(snap)
            out, result = self.limiter.step(np.array([tgt[0], tgt[1], tgt[2]][:self.n_u]))
            how = "none"
        info["continuation"] = how
        if name != options[0][0]:
            info["continuation_fallback"] = name
            if options[0][0] == "refined":
                info["qp"] = "fallback: refined command leaves no safe continuation"
        target = tgt
        info["target"] = [float(x) for x in target]
        info["ruckig"] = result
        if self._resynced:
            info["ruckig_resync"] = True
        return float(out[0]), float(out[1]), float(out[2]) if self.n_u == 3 else 0.0

    def legal_samples(self, step: Step) -> np.ndarray:
        """Path-following samples only where no mover comes within ``qp_activate`` of them over
        ``qp_horizon``: they are not refined (their command changes along the horizon), so
        near a mover they would forgo the mover clearance the QP adds to an arc. Taken
        there, the sluggish robots of li2023 Experiment II were run into in 3 of the 40 runs
        of ``benchmarks/dynamic_qp_dwa.yaml --runs 4``."""
        legal = super().legal_samples(step)
        if step.roll.tracking is not None and len(step.mover_r):
            H = max(1, min(step.roll.z.shape[1], int(round(self.options["qp_horizon"] / step.roll.dt))))
            near = step.dyn_gap[:, :H].min(axis=1) < self.options["qp_activate"]
            legal &= ~(step.roll.tracking & near)
        return legal

    # ------------------------------------------------------------------ recursive feasibility
    def continuation_rollout(self, ctx: LocalContext, out: np.ndarray, brake: bool) -> Rollouts:
        """The trajectory (one sample) when ``out`` is commanded for one period and then either
        the limiter's jerk-limited stop follows (``brake``), or ``out`` is held."""
        H = max(1, int(math.ceil(self.options["horizon"] / self.dt - 1e-9)))
        vel = np.zeros((H, 3))
        vel[0, :self.n_u] = out
        if brake:
            vel[1:, :self.n_u] = self.limiter.braking(H - 1)
        else:
            vel[1:, :self.n_u] = out
        v, w, vy = vel[:, 0], vel[:, 1], vel[:, 2]
        th = ctx.state.theta + np.cumsum(w) * self.dt  # heading after each period
        start = np.r_[ctx.state.theta, th[:-1]]
        z0 = complex(ctx.state.x, ctx.state.y)
        z = z0 + np.cumsum((v + 1j * vy) * np.exp(1j * start)) * self.dt
        return Rollouts(v=vel[:1, 0], vy=vel[:1, 2], w=vel[:1, 1], z=z[None, :], t=np.arange(1, H + 1) * self.dt,
                        z0=z0, theta0=float(ctx.state.theta), dt=self.dt, theta=th[None, :],
                        profile=np.hypot(v, vy)[None, :])

    def safe_continuation(self, ctx: LocalContext, out: np.ndarray) -> str:
        """How the robot can go on safely after commanding ``out`` for one period: ``"brake"``
        (the jerk-limited stop that follows stays clear of static obstacles, by the static
        margin, and of every predicted mover for the whole horizon, standing included),
        ``"cross"`` (holding ``out`` stays clear over the horizon: the crossing is completed),
        or ``""`` (neither). The limiter must hold the state after ``out``."""
        for brake, name in ((True, "brake"), (False, "cross")):
            check = self._assess(ctx, self.continuation_rollout(ctx, out, brake))
            if check.static_hit[0] >= check.roll.z.shape[1] and check.mover_free[0]:
                return name
        return ""

    # ------------------------------------------------------------------ refinement
    def _committed(self, step: Step, i: int) -> int:
        """Number of rollout points of sample ``i`` the robot is committed to: those it may
        pass before it can stop, if it follows the sample for the reaction time and then
        brakes at ``a_max`` (at most ``qp_horizon``). Later points are re-planned before they
        are reached. Asking a fixed-time margin of them too only rewards slowing down: in
        clutter every constant-command trajectory meets an obstacle within a second, and the
        QP braked the robot to a standstill in front of the passage (issue 27)."""
        roll = step.roll
        speed = float(roll.speed[i]) if roll.profile is None else float(roll.profile[i].max())
        t_commit = self._reaction() + speed / self.robot.a_max + roll.dt
        t_cap = min(self.options["qp_horizon"], t_commit)
        return max(1, min(roll.z.shape[1], int(math.ceil(t_cap / roll.dt - 1e-9))))

    def _static_margins(self, ctx: LocalContext, points: np.ndarray) -> np.ndarray:
        """Static margin (m) asked at each complex point: ``qp_margin``, but no more than the
        global path keeps next to it (its clearance at the nearest path point). A passage the
        global path threads with 3 cm to spare cannot be driven with 15 cm; asking for them
        made the QP trade all speed for the margin's slack."""
        path = ctx.global_path
        s, _ = project_on_path(path, points, complex(ctx.state.x, ctx.state.y), 2.0)
        near = point_at_arc(path, s)
        offered = np.asarray(ctx.static_distance(np.column_stack([near.real, near.imag])), float).ravel()
        return np.clip(offered - self.robot.radius, 0.0, self.options["qp_margin"])

    def _rows(self, ctx: LocalContext, step: Step, i: int, filters: bool = False):
        """Linearised clearance rows ``(grad (k, n_u), gap0 (k,), margin (k,))`` at sample ``i``:
        mover rows over ``qp_horizon`` (movers come at the robot whatever it does), static
        rows over the committed part only (:meth:`_committed`), and with ``filters`` the
        filters' tests that are clearances (``clearance_rows``: the sweep gate's intervals),
        as the filters judged sample ``i`` of ``step``."""
        o = self.options
        roll = step.roll
        H = max(1, min(roll.z.shape[1], int(round(o["qp_horizon"] / roll.dt))))
        H_static = min(H, self._committed(step, i)) if o["qp_committed"] else H
        z = roll.z[i, :H]
        R = self.robot.radius
        # the rows first: the derivative rollout below is only needed when one is active
        rows: list[tuple[int, complex, float, float]] = []  # (rollout point, outward normal, gap, margin)
        if len(step.mover_r) and o["qp_rows_moving"]:
            d = np.abs(z[None, :] - step.movers[:, :H]) - step.mover_r[:, None] - R  # (K, H)
            k_t = np.argmin(d, axis=1)
            g = d[np.arange(len(d)), k_t]
            for k in np.argsort(g, kind="stable")[:o["qp_rows_moving"]]:
                if g[k] >= o["qp_activate"]:
                    break
                t = int(k_t[k])
                nrm = z[t] - step.movers[k, t]
                rows.append((t, nrm / abs(nrm) if abs(nrm) > 0 else 1.0, float(g[k]), o["qp_margin"]))
        picked: list[int] = []
        if o["qp_rows_static"]:
            sg = step.static_gap[i, :H_static]
            for t in np.argsort(sg, kind="stable"):
                if sg[t] >= o["qp_activate"] or len(picked) == o["qp_rows_static"]:
                    break
                if all(abs(t - q) >= 3 for q in picked):  # spread the rows along the trajectory
                    picked.append(int(t))
        gate = self._filter_rows(step, i, lambda row: row[2] < o["qp_activate"]) if filters else []
        if picked:
            grad_z = static_gradient(ctx, z[picked])
            asked = (self._static_margins(ctx, z[picked]).tolist() if o["qp_committed"]
                     else [o["qp_margin"]] * len(picked))
            rows += [(t, grad_z[q], sg[t], asked[q]) for q, t in enumerate(picked)]
        return self._linearise(ctx, roll, i, rows + gate)

    def _filter_rows(self, step: Step, i: int, wanted, like: tuple[Step, int] | None = None) -> list:
        """The filters' clearance rows of sample ``i`` of ``step`` that ``wanted(row)`` selects,
        nearest first, at most ``qp_rows_filters`` (``like``: see ``clearance_rows``)."""
        found = (row for m in self.roles.filters for row in m.clearance_rows(self.view, step, i, like=like))
        return sorted((row for row in found if wanted(row)), key=lambda row: row[2])[:self.options["qp_rows_filters"]]

    def _linearise(self, ctx: LocalContext, roll: Rollouts, i: int, rows: list[tuple[int, complex, float, float]]):
        """``(grad (k, n_u), gap0 (k,), margin (k,))`` of clearance rows ``(rollout point, outward
        normal, gap, margin)`` of sample ``i`` of ``roll``: a row's gradient is its normal
        times the point's derivative in the command."""
        if not rows:
            return np.zeros((0, self.n_u)), np.zeros(0), np.zeros(0)
        # dz/du by forward differences of the planner's own rollout (constant or ramped)
        v, w, vy, h = roll.v[i], roll.w[i], roll.vy[i], 1e-4
        r = self.rollout_of(ctx.state, [v, v + h, v], [vy, vy, vy + h], [w, w + h])
        zz = r.z  # rows: (v,w) (v,w+h) (v+h,w) (v+h,w+h) (vy+h,w) (vy+h,w+h)
        dz = [(zz[2] - zz[0]) / h, (zz[1] - zz[0]) / h, (zz[4] - zz[0]) / h][:self.n_u]
        grads = [[(np.conj(normal) * dzc[t]).real for dzc in dz] for t, normal, _, _ in rows]
        gaps = [gap for _, _, gap, _ in rows]
        margins = [margin for _, _, _, margin in rows]
        return (np.asarray(grads, dtype=float).reshape(-1, self.n_u), np.asarray(gaps, dtype=float),
                np.asarray(margins, dtype=float))

    def _repair_rows(self, ctx: LocalContext, failed: str, check: Step, step: Step, i: int
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool, bool] | None:
        """Rows for the test the refined command (``check``) failed, as ``(grads, gaps,
        margins, at_sample, must_hold)``; ``at_sample``: linearised at sample ``i`` rather
        than at the refined command. Rows that ask only what the sample achieves (a filter's
        standard, no earlier contact, no earlier static collision) must hold: the slack relaxes
        them ``_SLACK_REPAIR_FACTOR`` times less; clearance rows ask ``qp_margin``, which the
        sample itself may miss. ``None`` when there are none.

        - closer to an obstacle: the clearance rows of the refined trajectory;
        - a filter: the filters' rows of the refined trajectory, asking what they asked of
          sample ``i``;
        - not admissible (it cannot stop before a static obstacle): rows at its first
          colliding points, asking the collision test's clearance, linearised at the sample;
        - an earlier mover contact: a row per point from the refined trajectory's first
          contact to the sample's (possibly past ``qp_horizon``), asking the contact test's
          gap, linearised at the sample: at the refined command a ramping rollout's early
          points need not move with the command at all."""
        if failed == "closer to an obstacle":
            rows = self._rows(ctx, check, 0)
        elif failed == "filter":
            rows = self._linearise(ctx, check.roll, 0, self._filter_rows(check, 0, lambda row: row[2] < row[3], like=(step, i)))
        elif failed == "not admissible":  # the sample's trajectory is clear at those points
            t_h, t_s = int(check.static_hit[0]), int(step.stop_index()[i])
            asked = min(self.static_margin(ctx), current_gaps(ctx, self.robot)[0]) + _GAP_TOL
            z = step.roll.z[i, t_h:min(t_s, t_h + self.options["qp_rows_static"])]
            if len(z) == 0:
                return None
            grad = static_gradient(ctx, z)
            found = [(t_h + q, grad[q], float(step.static_gap[i, t_h + q]), asked) for q in range(len(z))]
            rows = self._linearise(ctx, step.roll, i, found)
            return (*rows, True, True) if len(rows[1]) else None
        elif failed == "earlier mover contact":
            t_c, t_s = int(check.mover_contact[0]), min(int(step.mover_contact[i]), step.roll.z.shape[1])
            asked = min(self.options["margin"], current_gaps(ctx, self.robot)[1]) + _GAP_TOL
            found = []
            for t in range(t_c, t_s):
                k = int(np.argmin(np.abs(check.roll.z[0, t] - check.movers[:, t]) - check.mover_r))
                normal = step.roll.z[i, t] - step.movers[k, t]
                found.append((t, normal / abs(normal) if abs(normal) > 0 else 1.0,
                              float(abs(normal) - step.mover_r[k] - self.robot.radius), asked))
            rows = self._linearise(ctx, step.roll, i, found[:self.options["qp_rows_moving"]])
            return (*rows, True, True) if len(rows[1]) else None
        else:
            return None
        return (*rows, False, failed == "filter") if len(rows[1]) else None

    def _legal_after_filters(self, check: Step, step: Step, i: int) -> bool:
        """Whether the (single) trajectory of ``check`` passes the preset's filters as sample
        ``i`` of ``step`` passed them."""
        return all(m.passes_like(self.view, check, step, i) for m in self.roles.filters)

    def _solve(self, x0: np.ndarray, lo: np.ndarray, hi: np.ndarray, grads: np.ndarray, lb_rows: np.ndarray,
               x_start: np.ndarray, info: dict, must_hold: np.ndarray | None = None) -> np.ndarray | None:
        """One OSQP solve: closest to ``x0`` in the window ``[lo, hi]`` under the clearance rows
        ``grads . u + s >= lb_rows`` (``s / _SLACK_REPAIR_FACTOR`` in the rows marked
        ``must_hold``); ``None`` (with ``info["qp"]`` saying why) unless solved."""
        n_u, n = self.n_u, self._n_x
        rows = np.zeros((self._m_rows, n))
        lb = np.full(self._m_rows, -np.inf)
        k = len(lb_rows)
        rows[:k, :n_u] = grads
        rows[:k, n_u] = 1.0 if must_hold is None else np.where(must_hold, 1.0 / _SLACK_REPAIR_FACTOR, 1.0)
        lb[:k] = lb_rows
        dense = np.vstack([np.eye(n), rows])
        q = np.r_[-self._W * x0, _SLACK_LINEAR]
        lower = np.r_[lo, 0.0, lb]
        upper = np.r_[hi, np.inf, np.full(self._m_rows, np.inf)]
        Ax = dense[self._A_rows, self._A_cols]
        t0 = time.perf_counter()  # the OSQP calls only: update (refactorises), warm start, solve
        status_val, status, x_opt, solve_s = self._lean.step(q, lower, upper, Ax, np.r_[x_start, 0.0])
        elapsed = (time.perf_counter() - t0) * 1e6
        self.qp_times_us.append(elapsed)
        info["qp_us"] += elapsed
        info["qp_solve_us"] += solve_s * 1e6
        info["qp_rows"] = k
        if status_val != self._solved or x_opt is None or not np.all(np.isfinite(x_opt)):
            info["qp"] = f"fallback: OSQP status {status!r}"
            return None
        return x_opt

    def _verdict(self, ctx: LocalContext, step: Step, i: int, x: np.ndarray, margin_min: float,
                 info: dict) -> tuple[str, Step, float | None]:
        """Whether the refined command ``x`` may replace sample ``i``: ``("", check, None)``, or
        what it fails (``"not admissible"``, ``"earlier mover contact"``, ``"closer to an
        obstacle"`` with how much closer, or ``"filter"``), with its one-trajectory ``check``."""
        o = self.options
        u = (float(x[0]), float(x[1]), float(x[2]) if self.n_u == 3 else 0.0)
        check = self._assess(ctx, self.rollout_of(ctx.state, [u[0]], [u[2]], [u[1]]))
        H = max(1, min(step.roll.z.shape[1], int(round(o["qp_horizon"] / step.roll.dt))))
        Hs = min(H, max(self._committed(step, i), self._committed(check, 0))) if o["qp_committed"] else H
        # the rows constrain the plain predicted gaps (static ones over the committed part),
        # so judge the result on those
        gap_new = min(check.static_gap[0, :Hs].min(), check.dyn_gap[0, :H].min())
        allowed = min(min(step.static_gap[i, :Hs].min(), step.dyn_gap[i, :H].min()), margin_min)
        if not check.admissible[0]:
            return "not admissible", check, None
        if check.mover_contact[0] < step.mover_contact[i]:
            return "earlier mover contact", check, None
        if gap_new < allowed - _GAP_TOL:
            return "closer to an obstacle", check, float(allowed - gap_new)
        if info.get("mode") == "sample" and not self._legal_after_filters(check, step, i):
            return "filter", check, None
        return "", check, None

    def refine(self, ctx: LocalContext, window: Window, u0: tuple[float, float, float], step: Step,
               info: dict) -> tuple[float, float, float]:
        """The QP refinement of the sampled command ``u0`` (falls back to ``u0``)."""
        i = info["index"]
        grads, gaps, margins = self._rows(ctx, step, i, filters=info.get("mode") == "sample")
        if len(gaps) == 0:
            info["qp"] = "inactive"
            return u0
        if np.all(gaps >= margins):
            # the sample meets every row with zero slack, so it is the QP's optimum (the
            # objective is 0 there and nowhere lower): solving would only hand it back
            info["qp"] = "rows hold at the sample"
            return u0
        # a row at a point no command moves (the robot's own position, turning on the spot)
        # only adds slack; OSQP's answer is then the sample up to its tolerance
        movable = np.abs(grads) @ self._half_width >= _REACH
        if not np.any(movable & (gaps < margins)):
            info["qp"] = "rows out of the command's reach"
            return u0
        grads, gaps, margins = grads[movable], gaps[movable], margins[movable]
        o = self.options
        n_u = self.n_u
        x0 = np.array([u0[0], u0[1], u0[2]][:n_u])
        lo = np.array([window.v[0], window.w[0], window.vy[0]][:n_u])
        hi = np.array([window.v[1], window.w[1], window.vy[1]][:n_u])
        row_grads, row_lb = grads, margins - gaps + grads @ x0
        must_hold = np.zeros(len(row_lb), bool)
        margin_min = float(margins.min())
        info["qp_us"] = info["qp_solve_us"] = 0.0
        results = []  # each pass's answer
        for p in range(1, o["qp_passes"] + 1):
            x_opt = self._solve(x0, lo, hi, row_grads, row_lb, x0 if p == 1 else x, info, must_hold)
            if x_opt is None:
                return u0
            x = np.clip(x_opt[:n_u], lo, hi)
            results.append(x)
            failed, check, closer_by = self._verdict(ctx, step, i, x, margin_min, info)
            info["qp_passes"] = p
            if not failed:
                break
            more = self._repair_rows(ctx, failed, check, step, i) if p < o["qp_passes"] else None
            if more is not None and len(row_lb) + len(more[1]) <= self._m_rows:
                # sequential linearisation: the refined trajectory failed a test no row stood
                # for, so add rows for it and solve again
                g2, gap2, m2, at_sample, hold = more
                row_grads = np.vstack([row_grads, g2])
                row_lb = np.r_[row_lb, m2 - gap2 + g2 @ (x0 if at_sample else x)]
                must_hold = np.r_[must_hold, np.full(len(m2), hold)]
                continue
            # a shorter step towards a pass's answer, the last pass's first: the QP's objective
            # (convex) falls all the way from the sample to it, and the checks are relative to
            # the sample, which passes them
            shorter = next(((xr, f) for xr in reversed(results) for f in _BACKTRACK
                            if not self._verdict(ctx, step, i, x0 + f * (xr - x0), margin_min, info)[0]), None)
            if shorter is not None:
                x = x0 + shorter[1] * (shorter[0] - x0)
                info["qp_fraction"] = shorter[1]
            else:
                info["qp"] = (f"fallback: refined command failed the rollout check ({failed})" if failed != "filter" else
                              "fallback: refined command failed a filter the sampled one passed")
                if closer_by is not None:
                    info["qp_closer_by"] = closer_by
                return u0
            break
        u = (float(x[0]), float(x[1]), float(x[2]) if n_u == 3 else 0.0)
        info["qp"] = "solved" if "qp_fraction" not in info else f"solved: {info['qp_fraction']:g} of the step"
        # info["cost"] stays the sampled choice's cost under the program: its critics are scaled
        # over the step's samples, so the polished command has no cost of its own
        info["status"] = "polished"
        info["qp_slack"] = float(x_opt[n_u])
        # a solved QP may hand back the sample itself (its optimum); benchmarks count real changes
        info["qp_change"] = float(max(abs(a - b) for a, b in zip(u, u0)))
        return u
