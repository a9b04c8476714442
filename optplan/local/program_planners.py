"""Local planners that solve a window program (:mod:`optplan.formulations.local_program`).

* ``dwa`` over a program (:class:`ProgramSampler`): the dynamic window's constant commands,
  each held over the whole window, scored by the program's own cost and constraints; the
  admissible sample of least cost is driven (the least violating one when none holds).
* ``qp-dwa`` over a program (:class:`ProgramQPDWA`): the best sample, then one SQP step
  of the same program (a QP solved by OSQP), kept when the program finds it better.
* ``mpc`` (:class:`MPCPlanner`): CasADi NMPC of the same program by multiple shooting
  (IPOPT), built once with the situation as parameters and solved every period. Its start
  is the better, under the program, of the previous solution shifted by one period and the
  best sample. The answer is judged by the program's batched view; when IPOPT fails or its
  plan violates a constraint there, the best admissible sample is driven instead and the
  step's info says so. Ruckig limits the first command to the robot's jerk.

Every step's ``Command.info`` carries ``cost`` and ``violation`` under the program, the
solver's ``status`` and its ``solve_ms``.

The movers of every solver's situation come from one :class:`MoverTracker` per planner: it
follows each sensed mover along its line of motion and learns where it turns round from what
it observes. The program then predicts (``mover_model``) a mover seen to turn round as
bouncing between the ends it was seen to turn at; where no end is known it may turn round
anywhere beyond the stretch it has been seen on, so it is predicted as a growing stretch of
its line (``"sweep"``, the default), or straight on (``"bounce"``); ``"straight"`` runs every
mover straight on at constant velocity (the model before).
"""
from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..formulations.local_program import LocalProgram, Situation, SymbolicSituation, default_local_program
from ..world.robot import Command, RobotSpec, RobotState
from .base import LocalContext
from .hooks import PlannerView, build_part
from .limiter import RuckigLimiter
from .sweep_gate import Track, follow, learn_turn, line_reach, seen_at
from .window import dynamic_window, sample_grid

FEASIBLE = 1e-6   # a violation below this counts as none (the batched view's round-off)
SLACK_WEIGHT = 1e3  # cost of a metre (or m^2 for mover rows) of constraint shortfall in mpc
TRUST_RADIUS = 0.3  # m: how far a planned position may move from where the field's model was taken


# how the program solvers predict movers (MoverTracker): "bounce" turns a mover round at the
# ends it was seen to turn at, "sweep" also lets it turn anywhere beyond the stretch it was seen
# on where no end is known yet, "straight" runs every mover on at constant velocity
MOVER_MODELS = ("bounce", "sweep", "straight")


def situation_of(ctx: LocalContext, mover_ends: np.ndarray | None = None,
                 mover_seen: np.ndarray | None = None, mover_reach: np.ndarray | None = None) -> Situation:
    """The window program's :class:`Situation` of a control step (``mover_ends``, ``mover_seen``,
    ``mover_reach``: what is known of where the sensed movers turn round, :attr:`Situation.mover_ends`)."""
    s = ctx.state
    return Situation(state=np.array([s.x, s.y, s.theta, s.v, s.w, s.vy], float),
                     subgoal=np.asarray(ctx.subgoal, float), path=np.asarray(ctx.global_path, float),
                     static_distance=ctx.static_distance, movers=np.asarray(ctx.dynamic, float).reshape(-1, 5),
                     distance_error=float(ctx.distance_error or 0.0), mover_ends=mover_ends,
                     mover_seen=mover_seen, mover_reach=mover_reach)


class MoverTracker:
    """Where the sensed movers turn round, learnt from what is observed.

    Every control step each sensed mover is matched to a track (a :class:`~optplan.local.
    sweep_gate.Track`: its line of motion, its position along it, the extent it was seen on):
    the same radius, moving along the track's line, within ``match`` metres of it, and, if
    the track was seen a step ago, within ``match`` of where it was predicted. A reversal of
    the velocity along the line is a turn round: at constant speed ``c``, a mover seen at
    ``s1`` and ``dt`` later at ``s2`` on its way back turned at ``(s1 + s2 + c dt) / 2`` (the
    sweep gate's rule, also across a gap in sensing of at most ``rejoin`` seconds when the
    mover cannot have turned three times). A mover seen past an end it was thought to turn
    at (by more than ``slack`` metres) did not turn there, and that end is forgotten. Tracks
    unseen for ``memory`` seconds are dropped.

    :meth:`observe` gives, per sensed mover, where it turns round ahead of and behind itself
    along its direction of motion (:attr:`Situation.mover_ends`), and the farthest points it
    was seen at (:attr:`Situation.mover_seen`): the program then predicts it bouncing between
    the ends it was seen to turn at, and (``mover_seen`` given) possibly turning round beyond
    the stretch it was seen on where no end is known.
    """

    def __init__(self, match: float = 0.3, memory: float = 60.0, rejoin: float = 10.0, slack: float = 0.1) -> None:
        self.match, self.memory, self.rejoin, self.slack = float(match), float(memory), float(rejoin), float(slack)
        self.tracks: list[Track] = []
        self._t: float | None = None
        self._ends, self._seen, self._reach = np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 2))

    def reset(self) -> None:
        self.tracks, self._t = [], None
        self._ends, self._seen, self._reach = np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 2))

    def observe(self, ctx: LocalContext) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(ends, seen, reach)``, each ``(k, 2)`` rows ``(behind, ahead)`` for the rows of
        ``ctx.dynamic``, metres along each mover's velocity from where it is: where it is known
        to turn round (infinite where no turn is known), the farthest points it was seen at,
        and how far it can go before it touches a static obstacle the robot knew when it first
        saw it, or the border (:func:`~optplan.local.sweep_gate.line_reach`), after learning
        from this step's observation (once per step: a second call at the same time gives the
        same rows)."""
        t = float(ctx.t)
        if self._t is not None and abs(t - self._t) < 1e-12:
            return self._ends, self._seen, self._reach
        self._t = t
        self.tracks = [k for k in self.tracks if t - k.t_seen <= self.memory]
        rows = np.asarray(ctx.dynamic, float).reshape(-1, 5)
        out = np.tile([-math.inf, math.inf], (len(rows), 1))
        reach = out.copy()
        seen = np.zeros((len(rows), 2))
        free = list(self.tracks)
        for row, (x, y, vx, vy, r) in enumerate(rows):
            p, v = complex(x, y), complex(vx, vy)
            c = abs(v)
            if c < 1e-6:
                continue  # standing: nothing to learn, predicted where it stands
            k, s, heading, new = follow(self.tracks, free, p, v, float(r), t, ctx.dt, self.match)
            if new:
                k.reach_lo, k.reach_hi = line_reach(ctx, p, v / c, float(r))
            learn_turn(k, s, heading, c, t, ctx.dt, self.rejoin)
            if s > k.end_hi + self.slack:   # seen beyond where it was thought to turn: it does not
                k.end_hi = math.inf
            if s < k.end_lo - self.slack:
                k.end_lo = -math.inf
            seen_at(k, s, heading, c, t)
            if heading > 0:
                ahead, behind, seen_ahead, seen_behind = k.end_hi - s, k.end_lo - s, k.seen_hi - s, k.seen_lo - s
            else:
                ahead, behind, seen_ahead, seen_behind = s - k.end_lo, s - k.end_hi, s - k.seen_lo, s - k.seen_hi
            reach_ahead, reach_behind = (k.reach_hi - s, k.reach_lo - s) if heading > 0 else (s - k.reach_lo,
                                                                                              s - k.reach_hi)
            out[row] = (min(behind, 0.0), max(ahead, 0.0))
            seen[row] = (min(seen_behind, 0.0), max(seen_ahead, 0.0))
            reach[row] = (min(reach_behind, 0.0), max(reach_ahead, 0.0))
        self._ends, self._seen, self._reach = out, seen, reach
        return out, seen, reach


def _tracker(mover_model: str) -> MoverTracker | None:
    if mover_model not in MOVER_MODELS:
        raise ParameterError(f"mover_model must be one of {', '.join(map(repr, MOVER_MODELS))}, got {mover_model!r}")
    return MoverTracker() if mover_model != "straight" else None


# the path creep is on by default for the program solvers: without it mpc stopped for good in
# the narrowest clutter gaps (docs/measurements.md, "Local planning as programs")
DEFAULT_CREEP: dict = {}


def _creep(params: dict | None):
    """The path creep of a program solver: ``None`` (off) or its parameters (``{}``: defaults)."""
    if params is None:
        return None
    if not isinstance(params, dict):
        raise ParameterError(f"path_creep must be a mapping of its parameters ({{}} for its defaults) or None, "
                             f"got {params!r}")
    from .creep import PathCreep

    return build_part(PathCreep, params, "path_creep")


def _rank(violation: float, cost: float) -> tuple[bool, float]:
    """Order of two plans under a program: admissible before not, then the lesser cost
    (or, between inadmissible ones, the lesser violation)."""
    bad = not violation <= FEASIBLE
    return bad, (violation if bad else cost)


class ProgramSampler:
    """Sampling solver of a window program: the dynamic window's ``n_v x n_w`` constant
    commands (``n_vy`` sideways speeds too on an omni robot), each held over the window.
    ``mover_model``: ``"bounce"`` (movers seen to turn round are predicted turning round
    at the ends they were seen at, :class:`MoverTracker`), ``"sweep"`` (and possibly turning
    beyond the stretch they were seen on where no end is known) or ``"straight"``."""

    def __init__(self, robot: RobotSpec, dt: float, program: LocalProgram | None = None, n_v: int = 11,
                 n_w: int = 21, n_vy: int = 5, name: str = "dwa", mover_model: str = "sweep") -> None:
        self.robot, self.dt, self.name = robot, float(dt), name
        self.tracker, self.mover_model = _tracker(mover_model), mover_model
        self.lp = program if program is not None else default_local_program(robot, step=dt)
        if not isinstance(self.lp, LocalProgram):
            raise ParameterError(f"local_program must be an op.LocalProgram, got {type(self.lp).__name__}")
        if self.lp.robot.model != robot.model:
            raise ParameterError(f"the local program is for a {self.lp.robot.model} robot, the scenario's is "
                                 f"{robot.model}")
        for k, v in (("n_v", n_v), ("n_w", n_w), ("n_vy", n_vy)):
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
                raise ParameterError(f"{k} must be an integer >= 1, got {v!r}")
        self.n = (int(n_v), int(n_w), int(n_vy))

    def reset(self, state: RobotState, global_path: np.ndarray) -> None:
        if self.tracker is not None:
            self.tracker.reset()

    def situation(self, ctx: LocalContext) -> Situation:
        """This step's :class:`Situation`, the movers' known turning points learnt first
        (call it every step: the tracker learns from every observation)."""
        if self.tracker is None:
            return situation_of(ctx)
        ends, seen, reach = self.tracker.observe(ctx)
        return situation_of(ctx, ends, seen if self.mover_model == "sweep" else None, reach)

    def samples(self, ctx: LocalContext) -> np.ndarray:
        """``(S, K, nu)``: the window's constant commands, each repeated over the intervals."""
        win = dynamic_window(self.robot, ctx.state, ctx.dt, omni=self.lp.nu == 3)
        v, vy, w = sample_grid(win, self.n[0], self.n[1], self.n[2] if self.lp.nu == 3 else 1)
        lin = np.repeat(np.asarray(v, float), len(w))
        cols = [lin, np.tile(np.asarray(w, float), len(v))]
        if self.lp.nu == 3:
            cols.append(np.repeat(np.asarray(vy, float), len(w)))
        U = np.stack(cols, axis=1)
        return np.repeat(U[:, None, :], self.lp.K, axis=1)

    def best(self, sit: Situation, U: np.ndarray) -> tuple[int, np.ndarray, np.ndarray]:
        """Index of the best sample (least cost among the admissible, else least violation),
        and every sample's cost and violation."""
        cost, viol, _ = self.lp.evaluate(sit, U)
        ok = viol <= FEASIBLE
        i = int(np.argmin(np.where(ok, cost, np.inf))) if ok.any() else int(np.argmin(viol))
        return i, cost, viol

    def command(self, ctx: LocalContext) -> Command:
        t0 = time.perf_counter()
        sit = self.situation(ctx)
        U = self.samples(ctx)
        i, cost, viol = self.best(sit, U)
        u = U[i, 0]
        info = {"planner": self.name, "mode": "sample" if viol[i] <= FEASIBLE else "least-violation",
                "cost": float(cost[i]), "violation": float(viol[i]), "status": "sampled",
                "n_samples": len(U), "solve_ms": (time.perf_counter() - t0) * 1e3}
        return Command(v=float(u[0]), w=float(u[1]), vy=float(u[2]) if self.lp.nu == 3 else 0.0, info=info)


class MPCPlanner:
    """CasADi NMPC of a window program (see the module docstring).

    Args:
        robot, dt: the robot and the control period.
        program: the :class:`LocalProgram` (default :func:`default_local_program` with a
            2 s horizon in 10 intervals).
        max_movers: mover slots of the built problem (the nearest are taken).
        n_v, n_w: the sampled window (warm start and fallback).
        max_iter: IPOPT's iteration limit per step.
        path_creep: parameters of the path creep (``local/creep.py``) that takes over after
            the robot has stood beside obstacles (default: its own defaults), or ``None``
            for none.
        mover_model: how the program predicts movers: ``"bounce"`` (one seen to turn round
            turns round at the ends it was seen at, :class:`MoverTracker`), ``"sweep"`` (and it
            may turn beyond the stretch it was seen on where no end is known) or ``"straight"``.
    """

    name = "mpc"
    warm_from_previous = True   # start from the shifted previous plan when the program rates it better

    def __init__(self, robot: RobotSpec, dt: float, program: LocalProgram | None = None, max_movers: int = 10,
                 n_v: int = 9, n_w: int = 15, max_iter: int = 20, path_creep: dict | None = DEFAULT_CREEP,
                 mover_model: str = "sweep") -> None:
        self.robot, self.dt = robot, float(dt)
        self.view = PlannerView(robot, self.dt, {})
        self.creep = _creep(path_creep)
        self.sampler = ProgramSampler(robot, dt, program, n_v=n_v, n_w=n_w, name="mpc", mover_model=mover_model)
        lp = self.lp = self.sampler.lp
        if isinstance(max_movers, bool) or not isinstance(max_movers, (int, np.integer)) or max_movers < 0:
            raise ParameterError(f"max_movers must be an integer >= 0, got {max_movers!r}")
        if isinstance(max_iter, bool) or not isinstance(max_iter, (int, np.integer)) or max_iter < 1:
            raise ParameterError(f"max_iter must be an integer >= 1, got {max_iter!r}")
        self.max_movers = int(max_movers)
        self.max_iter = int(max_iter)
        self.repairs = 1   # re-solves with the field's model taken along a plan found too close
        self.trust = TRUST_RADIUS
        self.inputs = ("state", "subgoal", "command", "lines", "static", "movers", "mover_path", "mover_known")
        self._solvers: dict[int, tuple[Any, int]] = {}
        self._slots = self._solver_slots()
        acc = [lp.rates()[c] / (lp.m * lp.h) for c in range(lp.nu)]
        jerk = math.inf if robot.jerk_max is None else robot.jerk_max
        ang_jerk = math.inf if robot.jerk_max is None else robot.jerk_max * robot.alpha_max / robot.a_max
        self.limiter = RuckigLimiter(self.dt, acc, [jerk, ang_jerk, jerk][:lp.nu])
        self.previous: np.ndarray | None = None
        self.duals: np.ndarray | None = None   # the last solve's multipliers: IPOPT's warm start

    def _solver_slots(self) -> tuple[int, ...]:
        """The mover slot counts solvers are built for: a step uses the smallest that holds
        the movers in view (each slot adds a row per predicted state, parked or not)."""
        return tuple(sorted({n for n in (0, 2, 5, self.max_movers) if n <= self.max_movers}))

    def _solver(self, movers: int) -> tuple[Any, int, int]:
        """``(casadi Function, its mover slots, its number of multipliers)`` for ``movers``
        movers in view, built on first use: one Function call per step takes the situation,
        the start and the multipliers in and gives the plan and the multipliers out (Opti's
        set_initial/set_value cost more than the solve)."""
        slots = next((n for n in self._slots if n >= movers), self._slots[-1])
        if slots not in self._solvers:
            import casadi as ca

            lp = self.lp
            opti = ca.Opti()
            U = opti.variable(lp.K, lp.nu)
            Z = opti.variable(lp.N + 1, 3)
            ps = SymbolicSituation(opti, lp, slots)
            opti.subject_to(Z[0, :] == ps.state[:3].T)
            for k in range(lp.K):                       # multiple shooting: every Euler step a constraint
                for i in range(lp.m):
                    j = k * lp.m + i
                    opti.subject_to(Z[j + 1, :] == lp.step_symbolic(Z[j, :], U[k, :]))
            lo, hi = lp.bounds()
            rate = lp.rates()
            first = rate * min(1.0, self.dt / (lp.m * lp.h))   # the first interval: one period's reach
            for c in range(lp.nu):
                opti.subject_to(opti.bounded(lo[c], U[:, c], hi[c]))
                opti.subject_to(opti.bounded(-first[c], U[0, c] - ps.command[c], first[c]))
                if lp.K > 1:
                    opti.subject_to(opti.bounded(-rate[c], U[1:, c] - U[:-1, c], rate[c]))
            objective = 0
            for w, term in lp.objective:
                objective += w * term.symbolic(Z, U, ps, lp)
            # the program's constraints with one shared slack at an exact-penalty weight: zero
            # whenever the constraints can hold (they are then hard), the least shortfall when a
            # mover leaves no way out, so IPOPT still converges to the plan that violates least
            slack = opti.variable()
            opti.subject_to(slack >= 0)
            # a trust region round the reference: the static field's first-order model holds
            # near the positions it was taken at, not across a cluttered window
            for j in range(1, lp.N + 1):
                dx, dy = Z[j, 0] - ps.static[j - 1, 3], Z[j, 1] - ps.static[j - 1, 4]
                opti.subject_to(dx * dx + dy * dy <= self.trust ** 2)
            opti.minimize(objective + SLACK_WEIGHT * slack)
            for con in lp.constraints:
                for expr, lower in con.symbolic(Z, U, ps, lp):
                    opti.subject_to(expr + slack >= lower)
            # no slack for touching a static obstacle, whatever the program (a plan that must
            # touch one fails here, and the best sample, ranked the same way, is driven)
            for expr in lp.static_rows(Z, ps):
                opti.subject_to(expr >= 0.0)
            self._choose_solver(opti)
            fn = opti.to_function(f"mpc{slots}", [getattr(ps, k) for k in self.inputs] + [U, Z, opti.lam_g],
                                  [U, opti.lam_g])
            self._solvers[slots] = (fn, int(opti.lam_g.shape[0]))
        fn, n_duals = self._solvers[slots]
        return fn, slots, n_duals

    def _choose_solver(self, opti) -> None:
        """IPOPT to convergence (or ``max_iter``), warm-started with the last multipliers."""
        opti.solver("ipopt", {"print_time": False, "expand": True},
                    {"print_level": 0, "max_iter": self.max_iter, "tol": 1e-4, "acceptable_tol": 1e-3,
                     "sb": "yes", "warm_start_init_point": "yes", "warm_start_bound_push": 1e-6,
                     "warm_start_mult_bound_push": 1e-6, "mu_init": 1e-3})

    def _solved(self, stats: dict) -> bool:
        return bool(stats.get("success"))

    def reset(self, state: RobotState, global_path: np.ndarray) -> None:
        self.previous = None
        self.duals = None
        self.sampler.reset(state, global_path)
        if self.creep is not None:
            self.creep.reset(self.view, state, global_path)
        self.limiter.reset([state.v, state.w, state.vy][:self.lp.nu])

    def _start(self, sit: Situation, samples: np.ndarray) -> tuple[np.ndarray, int, np.ndarray, np.ndarray]:
        """The solver's start: the better of the shifted previous plan and the best sample."""
        i, cost, viol = self.sampler.best(sit, samples)
        start = samples[i]
        if self.warm_from_previous and self.previous is not None:
            shifted = np.concatenate([self.previous[1:], self.previous[-1:]], axis=0)
            lo, hi = self.lp.bounds()
            shifted = np.clip(shifted, lo, hi)
            c, v, _ = self.lp.evaluate(sit, shifted)
            if (v[0], c[0]) < (viol[i], cost[i]):
                start = shifted
        return start, i, cost, viol

    def command(self, ctx: LocalContext) -> Command:
        t0 = time.perf_counter()
        lp = self.lp
        sit = self.sampler.situation(ctx)   # every step, so the mover tracker sees every observation
        win = dynamic_window(self.robot, ctx.state, ctx.dt, omni=lp.nu == 3)
        took = self.creep.override(self.view, ctx, win) if self.creep is not None else None
        if took is not None:   # the path creep has the robot (see local/creep.py)
            self.previous, self.duals = None, None
            v, w, extra = took
            return self._limited(win.clip(v, w, 0.0), {"planner": self.name, "status": "creep", **extra}, t0)
        samples = self.sampler.samples(ctx)
        start, i, cost, viol = self._start(sit, samples)
        solve, slots, n_duals = self._solver(len(sit.movers))
        # the last multipliers fit only the same problem (the same slots)
        duals = self.duals if self.duals is not None and len(self.duals) == n_duals else np.zeros(n_duals)
        status, mode, plan, p_cost, p_viol = "not run", self.name, None, math.inf, math.inf
        for attempt in range(1 + self.repairs):
            # the symbolic model of the static field is taken along the start; a plan the
            # program finds too close is solved again with the model taken along that plan
            ref = lp.rollout(sit, start[None])[0]
            values = lp.symbolic_values(sit, ref, slots)
            try:
                out_u, out_lam = solve(*[values[k] for k in self.inputs], start, ref, duals)
                stats = solve.stats()
                solved = self._solved(stats)
                status = "solved" if solved else str(stats.get("return_status", "failed"))
                # a failed solve's last iterate may still be a good plan: the program judges it
                plan = np.asarray(out_u, float).reshape(lp.K, lp.nu)
                duals = np.asarray(out_lam, float).ravel() if solved else np.zeros(n_duals)
            except RuntimeError as exc:
                status, plan = f"error: {str(exc).splitlines()[0][:80]}", None
            if plan is None or not np.all(np.isfinite(plan)):
                break
            c, v, _ = lp.evaluate(sit, plan)
            p_cost, p_viol = float(c[0]), float(v[0])
            if p_viol <= FEASIBLE or status != "solved":
                break
            start, mode = plan, f"{self.name}-repaired"
        self.duals = duals if status == "solved" else None
        if plan is None or not np.all(np.isfinite(plan)):
            p_cost, p_viol = math.inf, math.inf
        if _rank(p_viol, p_cost) > _rank(float(viol[i]), float(cost[i])):
            # the program prefers the best sample (admissible first, then cheaper)
            plan, p_cost, p_viol = samples[i], float(cost[i]), float(viol[i])
            mode = "fallback-sample"
        self.previous = plan
        # the first command within one period's reach (an iterate IPOPT stopped at may not
        # hold the rate rows), then jerk-limited
        u = win.clip(plan[0][0], plan[0][1], plan[0][2] if lp.nu == 3 else 0.0)
        return self._limited(u, {"planner": self.name, "mode": mode, "status": status, "cost": p_cost,
                                 "violation": p_viol}, t0)

    def _limited(self, u: tuple[float, float, float], info: dict[str, Any], t0: float) -> Command:
        """The command ``u`` (within the window) after the Ruckig limiter, with the step's info."""
        nu = self.lp.nu
        target = np.array(u[:nu])
        out, ruckig = (self.limiter.step(target) if self.robot.jerk_max is not None
                       else (target, "unlimited"))
        if self.robot.jerk_max is None:
            self.limiter.reset(out)
        info.update(ruckig=ruckig, solve_ms=(time.perf_counter() - t0) * 1e3)
        return Command(v=float(out[0]), w=float(out[1]), vy=float(out[2]) if nu == 3 else 0.0, info=info)


class ProgramQPDWA(MPCPlanner):
    """``qp-dwa`` over a window program: the best sample of the dynamic window, then one
    SQP step of the same program (its local quadratic model, solved by OSQP through
    CasADi's ``sqpmethod``), kept only when the program finds it better than the sample.
    The first command is limited by Ruckig, as in the critic-based ``qp-dwa``.

    Args:
        robot, dt, program, max_movers, n_v, n_w: as :class:`MPCPlanner`.
        max_iter: SQP steps per control period (1: one QP polish).
    """

    name = "qp-dwa"
    warm_from_previous = False  # a polish of this period's best sample

    def __init__(self, robot: RobotSpec, dt: float, program: LocalProgram | None = None, max_movers: int = 10,
                 n_v: int = 11, n_w: int = 21, max_iter: int = 1, path_creep: dict | None = DEFAULT_CREEP,
                 mover_model: str = "sweep") -> None:
        super().__init__(robot, dt, program, max_movers=max_movers, n_v=n_v, n_w=n_w, max_iter=max_iter,
                         path_creep=path_creep, mover_model=mover_model)
        self.sampler.name = self.name
        self.repairs = 0

    def _choose_solver(self, opti) -> None:
        opti.solver("sqpmethod", {"qpsol": "osqp", "max_iter": self.max_iter, "print_header": False,
                                  "print_iteration": False, "print_status": False, "print_time": False,
                                  "error_on_fail": False, "expand": True, "convexify_strategy": "eigen-clip",
                                  "qpsol_options": {"error_on_fail": False, "print_time": False,
                                                    "osqp": {"verbose": False}}})

    def _solved(self, stats: dict) -> bool:
        # the step budget is the method (a polish, not a solve to convergence)
        return bool(stats.get("success")) or stats.get("return_status") == "Maximum_Iterations_Exceeded"
