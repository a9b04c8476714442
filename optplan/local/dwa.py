"""The dynamic window approach, vectorised over samples x horizon, driven by a preset.

One control step (Fox et al. 1997; the papers' §3 / §5 descriptions):

1. the dynamic window ``V_m ∩ V_d`` (hou2024 eq 20-21), narrowed by the preset's mechanisms;
2. a preset mechanism may take over for this step (brake-and-wait, initial heading);
3. an ``n_v x n_w (x n_vy)`` grid of the window is rolled out over the horizon, all at once;
4. clearance to static obstacles and predicted movers for every sample; admissibility
   ``V_a`` (eq 22) against static obstacles, and no predicted contact with a mover
   (braking does not help there; colliding trajectories are discarded, yuan2021 §3.3);
5. the preset's cost terms are evaluated, each normalised over the candidates (the
   papers' sigma: divide by the sum over the candidates; or min-max; or raw units),
   weighted and summed; the best admissible, legal sample is commanded.

When critics or filters leave no candidate, their vetoes are relaxed (admissibility is
kept); when every trajectory meets a predicted mover, the admissible one whose contact
comes latest and that stays farthest from the movers is taken ("evade"); when nothing is
admissible the sample that misses its stopping distance by the least is taken. A robot
pinned by static obstacles (every admissible forward sample stops within a few
centimetres) turns in place to face away from them ("escape-turn"), instead of towards
the goal, which would keep it pinned; when open space is behind it, it keeps turning the
way it already turns. The case is reported in ``Command.info["mode"]``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np

from ..checks import boolean
from ..errors import ParameterError, named_with_hints
from ..world.robot import Command, RobotSpec, RobotState
from .base import LocalContext, MoverSweepSource
from .critics import CRITICS, Critic
from .hooks import Mechanism, PlannerView, Roles, build_part
from .mechanisms import MECHANISMS, InitialHeading
from .preset_programs import PresetProgram, SampleSet, critic_cost, step_arrays
from .rollout import (Rollouts, Step, assess, join_rollouts, rollout, rollout_ramped, rollout_tracking,
                      static_gradient)
from .window import Window, dynamic_window, sample_grid


_PINNED = 0.05  # m: a robot whose admissible forward samples all stop within this is pinned
_TURNING = 1e-3  # rad/s: an angular velocity that says which way the robot is turning


@dataclass(frozen=True)
class Term:
    """One weighted cost term of a preset: a critic name from ``critics.CRITICS``."""

    critic: str
    weight: float
    params: Mapping[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Preset:
    """A local planner described as data: terms, mechanisms and options.

    Attributes:
        name: planner name (``make_local_planner`` key).
        source: where the method comes from (paper, section, equations).
        terms: the evaluation function.
        mechanisms: ``(name, params)`` pairs from ``mechanisms.MECHANISMS``.
        options: overrides of :attr:`DWAPlanner.OPTIONS`.
        refine: ``None`` or ``"qp"`` (sampling followed by the QP and Ruckig, ``qp_dwa``).
    """

    name: str
    source: str
    terms: tuple[Term, ...]
    mechanisms: tuple[tuple[str, Mapping[str, Any]], ...] = ()
    options: Mapping[str, Any] = field(default_factory=dict)
    refine: str | None = None


class DWAPlanner(MoverSweepSource):
    """A dynamic-window local planner configured by a :class:`Preset`.

    Build it with ``optplan.local.make_local_planner(name, robot, dt, **params)``; the
    options (``OPTIONS``), term weights (``weights={"heading": 1.0}``) and the parameters of
    a term or mechanism (``heading={"one_step_within": 1.0}``,
    ``brake_and_wait={"d_s": 1.5}`` or ``brake_and_wait=False`` to drop it) can be overridden.

    The planner is the sampling solver of the preset's window program (``self.program``, a
    :class:`~optplan.local.preset_programs.PresetProgram`): it chooses the admissible sample of
    least cost under the program's terms. ``program``: that program built beforehand
    (``op.local_program(name, ...)``), possibly with terms added; built from the preset otherwise.
    """

    OPTIONS: dict[str, Any] = {
        "n_v": 11,            # linear speed samples
        "n_w": 21,            # yaw rate samples
        "n_vy": 5,            # sideways speed samples (omni presets on an omni robot)
        "horizon": 3.0,       # prediction period, s (hou2024 §4.4)
        "rollout_dt": None,   # rollout step, s (None = the control period)
        "margin": 0.02,       # extra clearance counted as collision, m: covers the sampled
                              # distance field's interpolation and the straight swept segments
                              # between rollout points, which the exact check sees
        "swept_margin": 0.005,  # m: the swept-segment part alone; when the context gives the
                              # field's error bound, the static margin is at most the two summed
        "reaction": 0.0,      # reaction time in the stopping distance, s (eq 22)
        "normalise": "sum",   # "sum" | "minmax" | "none"
        "omni": False,        # sample vy too when the robot is omnidirectional (hou2024 eq 19)
        "mover_range": 3.0,   # movers provably farther than this (edge to edge) are skipped, m
        "mover_growth": 0.0,  # predicted movers grow by this times their speed per second ...
        "growth_cap": 0.0,    # ... up to this much, m (cost terms only)
        "movers_meet_stop": False,  # movers judged against the robot held where a rollout meets
                              # a static obstacle (rollout.assess), not its straight continuation
        "lookahead": None,    # s: sample targets reachable within this time and roll out the
                              # ramp to them (None = the classic window of one period)
        "path_samples": (),   # speeds (fractions of v_max) of extra samples that follow the
                              # global path by pure pursuit (rollout.rollout_tracking); () = none
        "path_look_aheads": (0.25, 0.5),  # m: their pure-pursuit look-ahead distances ...
        "path_turn_first": (1.5708, 0.3),  # ... and bearings (rad) beyond which they turn in place
        "brake_sample": False,  # add the sample that brakes hardest along the arc the robot drives
        "exact_free": False,  # free distance to where the clearance crosses the margin between
                              # rollout points (rollout.assess), not to the last free point
    }

    def __init__(self, preset: Preset, robot: RobotSpec, dt: float, program: PresetProgram | None = None,
                 **params: Any) -> None:
        if not isinstance(robot, RobotSpec):
            raise ParameterError(f"robot must be an optplan RobotSpec, got {type(robot).__name__}")
        try:
            self.dt = float(dt)
        except (TypeError, ValueError):
            raise ParameterError(f"dt must be a number of seconds, got {dt!r}") from None
        if not (math.isfinite(self.dt) and self.dt > 0):
            raise ParameterError(f"dt must be a finite number of seconds > 0, got {dt!r}")
        self.name = preset.name
        self.preset = preset
        self.robot = robot
        opts = {**self.OPTIONS, **preset.options}
        terms = {t.critic: (t.weight, dict(t.params)) for t in preset.terms}
        mechs = {m: dict(p) for m, p in preset.mechanisms}
        for key, value in params.items():
            if key in opts:
                opts[key] = value
            elif key == "weights":
                if not isinstance(value, Mapping) or set(value) - set(terms):
                    raise ParameterError(f"weights must map term names of {preset.name!r} ({', '.join(terms)}) "
                                         f"to numbers, got {value!r}")
                for t, w in value.items():
                    terms[t] = (w, terms[t][1])
            elif key in terms:
                if not isinstance(value, Mapping):
                    raise ParameterError(f"{key} must be a dict of the term's parameters, got {value!r}")
                value = dict(value)
                terms[key] = (value.pop("weight", terms[key][0]), {**terms[key][1], **value})
            elif key in mechs or key in MECHANISMS:
                # a mechanism of the preset is configured or dropped; another registered one is
                # added (e.g. qp-dwa's path creep in the clutter families)
                if value is False or value is None:
                    mechs.pop(key, None)
                elif value is True or isinstance(value, Mapping):
                    mechs.setdefault(key, {}).update({} if value is True else value)
                else:
                    raise ParameterError(f"{key} must be a dict of parameters, True or False, got {value!r}")
            else:
                known = sorted(set(opts) | set(terms) | set(mechs) | set(MECHANISMS) | {"weights"})
                raise ParameterError(f"unknown parameter {named_with_hints([key], known)} for local planner "
                                     f"{preset.name!r}; known: {', '.join(known)}")
        self.options = self._checked(opts)
        # what the mechanisms see of the planner (the options read-only, live)
        self.view = PlannerView(robot, self.dt, MappingProxyType(self.options))
        self.terms: list[tuple[Critic, float]] = []
        for cname, (w, p) in terms.items():
            w = self._number(f"weight of {cname}", w, allow_zero=True)
            self.terms.append((build_part(CRITICS[cname], p, cname), w))
        self.mechanisms: list[Mechanism] = [build_part(MECHANISMS[m], p, m) for m, p in mechs.items()]
        self.roles = Roles.of(self.mechanisms)
        self.rollout_dt = self.options["rollout_dt"] or self.dt
        self.steps = max(1, int(round(self.options["horizon"] / self.rollout_dt)))
        self.omni = bool(self.options["omni"]) and robot.model == "omni" and robot.vy_max > 0
        self.last: Command | None = None
        if program is None:
            program = PresetProgram(preset, robot, self.dt, params, self.terms, self.options,
                                    [m.name for m in self.mechanisms])
        elif not isinstance(program, PresetProgram) or program.preset.name != preset.name:
            raise ParameterError(f"the sampler of {preset.name!r} solves its own preset program, got {program!r:.80}")
        elif program.robot != robot or abs(program.dt - self.dt) > 1e-12:
            raise ParameterError(f"the program {program.name!r} was built for another robot or control period "
                                 f"({program.dt:g} s); build it with the scenario's robot and dt")
        self.program = program

    # ------------------------------------------------------------------ set-up helpers
    @staticmethod
    def _number(name: str, value: Any, allow_zero: bool = False, allow_inf: bool = False) -> float:
        try:
            x = float(value)
        except (TypeError, ValueError):
            raise ParameterError(f"{name} must be a number, got {value!r}") from None
        if math.isnan(x) or (math.isinf(x) and not allow_inf) or x < 0 or (x == 0 and not allow_zero):
            what = "a number" if allow_inf else "a finite number"
            raise ParameterError(f"{name} must be {what} {'>= 0' if allow_zero else '> 0'}, got {value!r}")
        return x

    def _checked(self, o: dict) -> dict:
        for k in ("n_v", "n_w", "n_vy"):
            if isinstance(o[k], bool) or not isinstance(o[k], (int, np.integer)) or o[k] < 1:
                raise ParameterError(f"{k} must be an int >= 1 (number of samples), got {o[k]!r}")
            o[k] = int(o[k])
        o["horizon"] = self._number("horizon", o["horizon"])
        if o["lookahead"] is not None:
            o["lookahead"] = self._number("lookahead", o["lookahead"])
        if o["rollout_dt"] is not None:
            o["rollout_dt"] = self._number("rollout_dt", o["rollout_dt"])
        for k in ("margin", "swept_margin", "reaction", "mover_range", "mover_growth", "growth_cap"):
            o[k] = self._number(k, o[k], allow_zero=True)
        for k, hi in (("path_samples", 1.0), ("path_look_aheads", np.inf), ("path_turn_first", np.pi)):
            try:
                vals = tuple(float(x) for x in o[k])
            except (TypeError, ValueError):
                raise ParameterError(f"{k} must be a list of numbers, got {o[k]!r}") from None
            if not all(0 < x <= hi for x in vals):
                raise ParameterError(f"{k} must hold numbers in (0, {hi:g}], got {o[k]!r}")
            o[k] = vals
        if o["path_samples"] and not (o["path_look_aheads"] and o["path_turn_first"]):
            raise ParameterError("path_samples need at least one of path_look_aheads (m) and of path_turn_first (rad)")
        for k in ("omni", "movers_meet_stop", "brake_sample", "exact_free"):
            o[k] = boolean(k, o[k])
        if o["normalise"] not in ("sum", "minmax", "none"):
            raise ParameterError(f"normalise must be 'sum', 'minmax' or 'none', got {o['normalise']!r}")
        return o

    # ------------------------------------------------------------------ protocol
    def reset(self, state: RobotState, global_path: np.ndarray) -> None:
        """Forget the previous run (adaptive limits, alignment, previous command)."""
        self.last = None
        for m in self.roles.resets:
            m.reset(self.view, state, global_path)

    @property
    def initial_heading(self) -> float | None:
        """li2023 eq 11: the heading (rad) of the first global path segment, published by the
        ``initial_heading`` mechanism at ``reset``; ``None`` without that mechanism."""
        for m in self.mechanisms:
            if isinstance(m, InitialHeading):
                return m.heading
        return None

    def window(self, ctx: LocalContext) -> Window:
        """The dynamic window for this step, after the mechanisms' caps."""
        win = dynamic_window(self.robot, ctx.state, self.options["lookahead"] or ctx.dt, omni=self.omni)
        for m in self.roles.caps_window:
            win = m.adjust_window(self.view, ctx, win)
        return win

    def evaluate(self, ctx: LocalContext, window: Window) -> Step:
        """Roll out and assess the sample grid of ``window``."""
        o = self.options
        lin_v, lin_vy, w = sample_grid(window, o["n_v"], o["n_w"], o["n_vy"] if self.omni else 1)
        roll = self.rollout_of(ctx.state, lin_v, lin_vy, w)
        if o["path_samples"]:
            track = rollout_tracking(ctx.state, ctx.global_path, self.robot.v_max * np.asarray(o["path_samples"]),
                                     np.asarray(o["path_look_aheads"]), self.rollout_dt, self.steps, self.robot,
                                     np.asarray(o["path_turn_first"]))
            roll = join_rollouts(roll, track)
        if o["brake_sample"]:
            brake = self._brake_sample(ctx.state, window, o["lookahead"] or ctx.dt)
            if brake is not None:
                roll = join_rollouts(roll, self.rollout_of(ctx.state, [brake[0]], [brake[1]], [brake[2]]))
        step = self._assess(ctx, roll)
        if self.omni:  # the acceleration limit bounds the (v, vy) vector: keep the disc of the box
            dv = np.hypot(step.roll.v - ctx.state.v, step.roll.vy - ctx.state.vy)
            step.admissible &= dv <= self.robot.a_max * (o["lookahead"] or ctx.dt) * (1 + 1e-9)
        return step

    def _brake_sample(self, state: RobotState, window: Window, period: float) -> tuple[float, float, float] | None:
        """``(v, vy, w)``: the slowest speed of the window on the arc the robot drives now
        (the same curvature), or ``None`` when it stands still. Fox's admissibility asks that
        the robot can stop on a sample's arc; the arc it is on, braked, is rarely on the grid,
        so a grazing robot can find every sample of the next window inadmissible."""
        speed = math.hypot(state.v, state.vy)
        if speed < 1e-6:
            return None
        scale = max(speed - self.robot.a_max * period, 0.0) / speed
        v = float(np.clip(state.v * scale, window.v[0], window.v[1]))
        vy = float(np.clip(state.vy * scale, window.vy[0], window.vy[1])) if self.omni else 0.0
        w = float(np.clip(state.w * scale, window.w[0], window.w[1]))
        return v, vy, w

    def rollout_of(self, state: RobotState, lin_v, lin_vy, w) -> Rollouts:
        """The planner's rollouts of the grid ``(lin_v, lin_vy) x w`` (constant velocities, or
        ramps to target velocities with the ``lookahead`` option)."""
        if self.options["lookahead"] is None:
            return rollout(state, np.asarray(lin_v, float), np.asarray(lin_vy, float), np.asarray(w, float),
                           self.rollout_dt, self.steps)
        a = self.robot.a_max
        return rollout_ramped(state, np.asarray(lin_v, float), np.asarray(lin_vy, float), np.asarray(w, float),
                              self.rollout_dt, self.steps, (a, self.robot.alpha_max, a))

    def _assess(self, ctx: LocalContext, roll) -> Step:
        o = self.options

        def predict(centres: np.ndarray, t: np.ndarray) -> np.ndarray:
            for m in self.roles.predicts:
                centres = m.predict(self.view, ctx, centres, t)
            return centres

        return assess(ctx, self.robot, roll, margin=o["margin"], static_margin=self.static_margin(ctx),
                      reaction=self._reaction(), mover_range=o["mover_range"],
                      mover_growth=o["mover_growth"], growth_cap=o["growth_cap"], predict=predict,
                      movers_meet_stop=o["movers_meet_stop"], exact_free=o["exact_free"])

    def _reaction(self) -> float:
        return self.options["reaction"]

    def static_margin(self, ctx: LocalContext) -> float:
        """Clearance (m) below which a rollout point counts as a static collision: ``margin``,
        or less where the context says how far its distance field may be off
        (``distance_error``, plus ``swept_margin`` for the straight segments between rollout
        points). The fixed 2 cm were sized for the 1 m cells of the shipped maps; on a map of
        0.15 m cells the field errs by 3 mm, and the 2 cm closed gaps the global path threads
        with 1-2 cm to spare (issue 27)."""
        o = self.options
        if ctx.distance_error is None:
            return o["margin"]
        return min(o["margin"], float(ctx.distance_error) + o["swept_margin"])

    def choose(self, step: Step) -> tuple[int | None, dict]:
        """Index of the best candidate sample (``None`` if none is admissible) and diagnostics."""
        legal = self.legal_samples(step)
        for m in self.roles.filters:
            keep = m.filter(self.view, step)
            if keep is not None:
                legal &= keep
        for critic, _ in self.terms:
            ok = critic.legal(step)
            if ok is not None:
                legal &= ok
        safe = step.admissible & step.mover_free
        cand = safe & legal
        mode = "sample"
        if not cand.any():
            cand = safe
            mode = "sample-relaxed"  # the critics' vetoes left nothing: keep the safety rules only
        pool = cand if cand.any() else step.admissible
        turn = self._escape_turn(step, pool)
        if turn is not None:
            return turn, {"mode": "escape-turn", "index": turn, "n_candidates": int(pool.sum()),
                          "free_distance": float(step.free_distance[turn])}
        if not cand.any() and step.admissible.any():
            # every trajectory meets a predicted mover: among those that can stop before static
            # obstacles and whose contact comes latest, flee - take the one that stays farthest
            # from the movers (the cost terms would trade that for progress)
            contact = np.where(step.admissible, step.mover_contact, -1)
            flee = np.where(contact == contact.max(), step.dyn_gap.min(axis=1), -np.inf)
            best = int(np.argmax(flee))
            return best, {"mode": "evade", "index": best, "n_candidates": int(np.isfinite(flee).sum()),
                          "free_distance": float(step.free_distance[best])}
        if not cand.any():
            # no sample can stop before its predicted collision (a mover may be closing in):
            # take the one that misses the stopping distance by the least, rather than
            # braking in place, which leaves the robot in a crossing mover's way
            shortfall = step.free_distance - step.stopping
            best = int(np.argmax(shortfall))
            return best, {"mode": "least-inadmissible", "index": best,
                          "free_distance": float(step.free_distance[best])}
        # the program's cost, negated (a score to maximise, as the papers write it): the
        # preset's critics normalised over the candidates, then any terms added to the program
        samples = SampleSet(step, cand, legal)
        total = np.zeros(step.roll.n)
        how = self.options["normalise"]
        for critic, weight in self.terms:
            if weight == 0:
                continue
            total -= weight * critic_cost(critic, samples, how)
        extra = self.program.extra_terms()
        if extra:
            from .program_planners import situation_of

            sit = situation_of(step.ctx)
            sit.samples = samples
            Z, U = step_arrays(samples, 3 if self.omni else 2)
            for weight, term in extra:
                total -= weight * np.asarray(term.batched(Z, U, sit, self.program), float)
        total[~cand] = -np.inf
        best = int(np.argmax(total))
        broken = samples.broken()[best]
        return best, {"mode": mode, "index": best, "score": float(total[best]), "cost": -float(total[best]),
                      "violation": float(broken), "n_candidates": int(cand.sum()),
                      "free_distance": float(step.free_distance[best])}

    def legal_samples(self, step: Step) -> np.ndarray:
        """``(S,)`` samples the planner itself allows before the mechanisms' and critics' vetoes
        (all; ``qp-dwa`` restricts its path-following samples)."""
        return np.ones(step.roll.n, dtype=bool)

    def _escape_turn(self, step: Step, pool: np.ndarray) -> int | None:
        """The turn in place (among ``pool``) towards open space when static obstacles
        leave the robot no admissible way forward (``None`` otherwise).

        Stopped against a wall or beside a corner, at or inside the ``margin``, every
        forward trajectory that heads for the goal may graze a millimetre closer than the
        margin (or than where the robot stands, see :func:`assess`), so only turns in place
        and creeping a few millimetres stay admissible. The cost terms then pick the turn
        towards the goal, and the evasion rule (all samples meeting a mover) picks among
        turns that all leave the robot in the same place: either way the robot stays.
        Turning up the clearance gradient makes the way out admissible on a later step."""
        roll, ctx = step.roll, step.ctx
        forward = step.admissible & (roll.speed > 0)
        if not pool.any() or (step.free_distance[forward] >= _PINNED).any():
            return None  # a way forward exists
        grad = static_gradient(ctx, [complex(ctx.state.x, ctx.state.y)])[0]
        away = math.atan2(grad.imag, grad.real)
        need = math.remainder(away - ctx.state.theta, 2 * math.pi)
        w_now = ctx.state.w
        if abs(need) > math.pi / 2 and need * w_now < 0 and abs(w_now) > _TURNING:
            # open space is behind the robot, so either way round is a long turn: keep turning
            # the way it turns. Turning the short way against the turn the sampled step had
            # begun made the two alternate, and the robot dithered in a corner for good
            need += math.copysign(2 * math.pi, w_now)
        miss = np.abs(need - roll.w * ctx.dt)
        miss[~pool] = np.inf
        return int(np.argmin(miss))

    def command(self, ctx: LocalContext) -> Command:
        """The velocity command for the next control period."""
        if abs(ctx.dt - self.dt) > 1e-9:
            raise ParameterError(f"the context's dt ({ctx.dt:g} s) differs from the planner's ({self.dt:g} s); "
                                 "build the planner with the simulation's control period")
        t0 = time.perf_counter()
        win = self.window(ctx)
        info: dict[str, Any] = {"planner": self.name, "status": "sampled"}
        step = None
        for m in self.roles.takes_over:
            took = m.override(self.view, ctx, win)
            if took is not None:
                v, w, extra = took
                u = win.clip(v, w, 0.0)
                info.update(extra)
                break
        else:
            step = self.evaluate(ctx, win)
            best, extra = self.choose(step)
            info.update(extra)
            info["n_samples"] = step.roll.n
            for m in self.roles.filters:
                info.update(m.report(step))
            if best is None:
                u = win.clip(0.0, 0.0, 0.0)  # brake as hard as the window allows
            else:
                r = step.roll
                u = (float(r.v[best]), float(r.w[best]), float(r.vy[best]))
        u = self.finish(ctx, win, u, step, info)
        info["solve_ms"] = (time.perf_counter() - t0) * 1e3
        cmd = Command(v=u[0], w=u[1], vy=u[2], info=info)
        self.last = cmd
        return cmd

    def mover_sweeps(self) -> np.ndarray:
        """``(n, 5)`` rows ``(x0, y0, x1, y1, r)``: stretches the mechanisms know movers sweep
        back and forth (the navigation layer's stuck recovery plans round them); the
        mechanisms that learn them declare :class:`~optplan.local.base.MoverSweepSource`."""
        return np.vstack([np.zeros((0, 5))] + [m.mover_sweeps() for m in self.mechanisms
                                               if isinstance(m, MoverSweepSource)])

    def finish(self, ctx: LocalContext, window: Window, u: tuple[float, float, float], step: Step | None,
               info: dict) -> tuple[float, float, float]:
        """Last stage of a step (``qp-dwa`` refines and limits the command here)."""
        return u
