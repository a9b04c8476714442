"""The papers' DWA presets as named window programs (DESIGN.md, "Local programs").

A preset's critics do not score a trajectory on its own: Fox et al. 1997 scale every term
over the candidate samples of the step (``normalise``: each value over the sum, or Fox's
[0, 1] range), and the papers keep that. So a preset's terms are window-program terms
whose batched view judges a step's assessed samples (:class:`CriticTerm`, the samples in
:attr:`Situation.samples <optplan.formulations.local_program.Situation>`), and they have
no symbolic view; its constraint is Fox's admissibility with the preset's vetoes
(:class:`SampledAdmissibility`). Sampling such a program (``dwa``) is the preset's own
planner, bit for bit: :class:`~optplan.local.dwa.DWAPlanner` scores its samples with the
program's terms.

Terms added to a preset program (``prog.add(0.3 * LT.custom(fn))``, or any
:mod:`optplan.local_terms` term) are judged by the same sampler on every sample's
predicted states, raw (not normalised), and subtracted from the preset's score::

    prog = op.local_program("idwa", robot, dt=0.1)
    prog.add(0.5 * LT.custom(lambda Z, U, m: -m.mean(Z[:, 1]), name="prefer_north"))
    op.simulate(scenario, local_planner="dwa", local_program=prog)

``mpc`` needs a symbolic view of every term, which the papers' critics do not have (the
scale of a term is its step's sample set), so it does not take a preset program; nor does
the QP polish of ``qp-dwa``, except for ``qp-dwa``'s own program.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..formulations.local_program import LocalConstraint, LocalObjective, LocalProgram, LocalTerm, Situation
from ..world.robot import RobotSpec
from .critics import Critic
from .rollout import Step


@dataclass
class SampleSet:
    """A sampling solver's assessed samples of one step, what the papers' critics judge.

    Attributes:
        step: the assessed rollouts (:class:`~optplan.local.rollout.Step`).
        candidates: ``(S,)`` the samples the step chooses among (a critic is scaled over them).
        legal: ``(S,)`` the samples the preset's filters and critics allow.
    """

    step: Step
    candidates: np.ndarray
    legal: np.ndarray

    def broken(self) -> np.ndarray:
        """``(S,)`` how many of Fox's admissibility rules, as the preset judges them, each sample
        breaks: stopping before the first static collision, meeting no predicted mover, passing
        the preset's filters and critics (0: admissible)."""
        return ((~self.step.admissible).astype(float) + (~self.step.mover_free).astype(float)
                + (~self.legal).astype(float))


def normalised(values: np.ndarray, cand: np.ndarray, how: str) -> np.ndarray:
    """A critic's values scaled over the candidate samples: ``"sum"`` (the papers' sigma: each
    value over the sum of magnitudes), ``"minmax"`` (Fox's [0, 1] range) or ``"none"``."""
    if how == "none":
        return values
    v = values[cand]
    if how == "sum":
        total = np.abs(v).sum()
        return values / total if total > 0 and np.isfinite(total) else np.zeros_like(values)
    lo, hi = v.min(), v.max()
    return (values - lo) / (hi - lo) if hi > lo else np.zeros_like(values)


def critic_cost(critic: Critic, samples: SampleSet, how: str) -> np.ndarray:
    """``(S,)`` one critic's part of the program's cost (to minimise): its normalised score,
    negated where the critic is a reward."""
    n = normalised(critic.score(samples.step), samples.candidates, how)
    return n if critic.cost else -n


def _samples_of(sit: Situation, what: str) -> SampleSet:
    if not isinstance(sit.samples, SampleSet):
        raise ParameterError(f"{what} is judged against the other samples of a step (the papers' per-step "
                             "normalisation): evaluate it with the sampling solver 'dwa'")
    return sit.samples


class CriticTerm(LocalTerm):
    """A paper's critic (:data:`optplan.local.critics.CRITICS`) as a window-program term,
    scaled over its step's candidate samples (``normalise``). Batched view only."""

    def __init__(self, critic: Critic, normalise: str) -> None:
        self.critic, self.normalise, self.name = critic, normalise, critic.name

    def batched(self, Z, U, sit, prog):
        return critic_cost(self.critic, _samples_of(sit, f"the critic {self.name!r}"), self.normalise)

    def symbolic(self, Z, U, ps, prog):
        raise ParameterError(f"the critic {self.name!r} has no symbolic view: it is scaled over its step's samples")

    def __repr__(self) -> str:
        params = {k: v for k, v in vars(self.critic).items() if not k.startswith("_")}
        return f"{self.name}({', '.join(f'{k}={v!r}' for k, v in params.items())})"


class SampledAdmissibility(LocalConstraint):
    """Fox's admissibility as the preset judges it: the robot can stop before the first
    static collision of the sample, the sample meets no predicted mover, and the preset's
    filters and critics allow it. The violation counts the rules a sample breaks (0: none).
    Batched view only."""

    name = "admissible"

    def batched(self, Z, U, sit, prog):
        return _samples_of(sit, "Fox's admissibility").broken()

    def symbolic(self, Z, U, ps, prog):
        raise ParameterError("Fox's admissibility is judged on the sampled rollouts; it has no symbolic view")


class PresetProgram(LocalProgram):
    """A paper's DWA preset as a window program: ``K = 1`` constant command over the preset's
    horizon, the preset's critics as :class:`CriticTerm`, :class:`SampledAdmissibility`.

    Built with :func:`optplan.local_program` (``op.local_program("idwa", robot, dt)``) or
    ``local_program="idwa"`` in ``op.simulate`` / scenario files. ``preset``, ``params``
    (the planner parameters it was built with) and ``mechanisms`` (the preset's mechanisms
    after ``params``: velocity obstacles, brake-and-wait, ...) say what the sampler runs
    besides the terms.
    """

    def __init__(self, preset: Any, robot: RobotSpec, dt: float, params: dict, terms: list, options: dict,
                 mechanisms: list[str]) -> None:
        step = options["rollout_dt"] or dt
        super().__init__(robot, horizon=options["horizon"], intervals=1, step=step, name=preset.name)
        self.preset, self.params, self.dt = preset, dict(params), float(dt)
        self.options, self.mechanisms = dict(options), list(mechanisms)
        self.normalise = options["normalise"]
        self.objective = [(float(w), CriticTerm(c, self.normalise)) for c, w in terms]
        self.constraints = [SampledAdmissibility()]

    def add(self, objective) -> "PresetProgram":
        """Add terms to the objective (``prog.add(0.5 * LT.custom(fn))``): judged raw on every
        sample's predicted states, next to the preset's normalised critics."""
        objective = objective if isinstance(objective, LocalObjective) else LocalObjective([(1.0, objective)])
        for w, t in objective.parts:
            if not isinstance(t, LocalTerm) or not np.isfinite(w):
                raise ParameterError(f"add takes a weighted sum of local terms, got {t!r:.60}")
            if isinstance(t, CriticTerm):
                raise ParameterError("a critic term belongs to its preset; set its weight with weights={...}")
        self.objective = self.objective + list(objective.parts)
        return self

    def minimize(self, objective) -> "PresetProgram":
        raise ParameterError(f"{self.name!r} is a paper preset: its critics stay (their weights: "
                             f"op.local_program({self.name!r}, ..., weights={{...}})); add terms with .add(...)")

    def extra_terms(self) -> list[tuple[float, LocalTerm]]:
        """The terms added to the preset's critics (:meth:`add`)."""
        return [(w, t) for w, t in self.objective if not isinstance(t, CriticTerm)]

    def describe(self) -> str:
        """The program in a few lines: terms with weights, constraints, mechanisms, source."""
        lines = [f"local program {self.name!r}: K = 1 constant command over {self.horizon:g} s "
                 f"({self.N} steps of {self.h:g} s), critics normalised {self.normalise!r}",
                 f"  source: {self.preset.source}"]
        lines += [f"  minimise {w:+g} x {t!r}" + ("" if isinstance(t, CriticTerm) else " (added, raw)")
                  for w, t in self.objective]
        lines += [f"  subject to {c.name}" for c in self.constraints]
        lines += [f"  mechanisms: {', '.join(self.mechanisms) or 'none'}"]
        return "\n".join(lines)

    def __repr__(self) -> str:
        return f"PresetProgram({self.name!r}, {len(self.objective)} terms, mechanisms={self.mechanisms})"


def step_arrays(samples: SampleSet, nu: int) -> tuple[np.ndarray, np.ndarray]:
    """``(Z, U)`` of a step's samples in the window program's layout: states ``(S, H + 1, 3)``
    (the start first) and the sampled commands ``(S, 1, nu)`` (a path-following sample's
    command changes along the window: its first period's command)."""
    roll = samples.step.roll
    S, H = roll.z.shape
    Z = np.empty((S, H + 1, 3))
    Z[:, 0, 0], Z[:, 0, 1], Z[:, 0, 2] = roll.z0.real, roll.z0.imag, roll.theta0
    Z[:, 1:, 0], Z[:, 1:, 1] = roll.z.real, roll.z.imag
    Z[:, 1:, 2] = roll.theta if roll.theta is not None else roll.theta0 + roll.w[:, None] * roll.t[None, :]
    cols = [roll.v, roll.w, roll.vy][:nu]
    return Z, np.stack(cols, axis=1)[:, None, :]
