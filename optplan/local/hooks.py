"""The contract between the DWA core (``dwa.py``) and its mechanisms.

A mechanism is a part of a paper's DWA variant that is not a cost term. It hooks into
one place of the control step:

* ``adjust_window``: narrows the dynamic window (hou2024's adaptive velocity, eq 23-24);
* ``override``: replaces the sampled choice by a fixed manoeuvre for this step
  (li2023's brake-and-wait, §5.4, and initial heading, eq 11);
* ``predict``: replaces the constant-velocity prediction of movers whose motion it knows
  better (the sweep gate, once it has seen where a mover turns round);
* ``filter``: removes samples and reports findings to the cost terms through
  ``step.aux`` (yang2023's velocity-obstacle test, eq 12-14; the sweep gate of
  ``qp-dwa``); ``strict_filter`` is the same test without any fallback (``qp-dwa``
  checks its refined command with it); ``report`` copies what a filter found into
  ``Command.info``.

Every hook gets a :class:`PlannerView` - the robot, the control period and the
planner's options, read-only - not the planner: a mechanism keeps its own state and
publishes what it learns through its own typed attributes (``InitialHeading.heading``,
``SweepGate.tracks``), which the planner reads.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Mapping

import numpy as np

from ..world.robot import RobotSpec, RobotState
from .base import LocalContext
from .rollout import Step
from .window import Window


@dataclass(frozen=True)
class PlannerView:
    """What a mechanism may know of the planner it belongs to.

    Attributes:
        robot: footprint and limits.
        dt: control period, seconds.
        options: the planner's options (``DWAPlanner.OPTIONS`` after overrides), read-only.
    """

    robot: RobotSpec
    dt: float
    options: Mapping[str, Any]


class Mechanism:
    """A hook into the control step (see the module docstring). Hooks default to no-ops."""

    name: ClassVar[str] = ""

    def reset(self, view: PlannerView, state: RobotState, global_path: np.ndarray) -> None:
        """Forget the previous run."""

    def adjust_window(self, view: PlannerView, ctx: LocalContext, window: Window) -> Window:
        """The window for this step (narrowed or as it is)."""
        return window

    def override(self, view: PlannerView, ctx: LocalContext, window: Window) -> tuple[float, float, dict] | None:
        """``(v_desired, w_desired, info)`` to clip into the window instead of sampling, or ``None``."""
        return None

    def predict(self, view: PlannerView, ctx: LocalContext, centres: np.ndarray, t: np.ndarray) -> np.ndarray:
        """Predicted mover centres ``(K, H)`` complex at the rollout times ``t`` (one row per
        row of ``ctx.dynamic``); ``centres`` is the prediction so far, which may be updated in place."""
        return centres

    def filter(self, view: PlannerView, step: Step) -> np.ndarray | None:
        """Mask of samples to keep (``None`` = all)."""
        return None

    def strict_filter(self, view: PlannerView, step: Step) -> np.ndarray | None:
        """``filter`` without any relaxation it applies when nothing passes: judges a single
        trajectory on its own (``qp-dwa`` checks its refined command with it)."""
        return self.filter(view, step)

    def report(self, step: Step) -> dict:
        """What this step's ``filter`` found, for ``Command.info`` (empty by default)."""
        return {}
