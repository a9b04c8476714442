"""The contract between the DWA core (``dwa.py``) and its mechanisms.

A mechanism is a part of a paper's DWA variant that is not a cost term. It plays one or
more small roles in the control step, each a protocol of its own:

* :class:`Resets`: forgets the previous run (``reset``);
* :class:`CapsWindow`: narrows the dynamic window (hou2024's adaptive velocity, eq 23-24);
* :class:`TakesOver`: replaces the sampled choice by a fixed manoeuvre for this step
  (li2023's brake-and-wait, §5.4, and initial heading, eq 11);
* :class:`PredictsMovers`: replaces the constant-velocity prediction of movers whose
  motion it knows better (the sweep gate, once it has seen where a mover turns round);
* :class:`FiltersSamples`: judges the current sample set (a :class:`~optplan.local.rollout.Step`)
  and reports findings to the cost terms through ``step.aux`` (yang2023's
  velocity-obstacle test, eq 12-14; the sweep gate of ``qp-dwa``); ``strict_filter`` is
  the same test without any fallback, ``passes_like`` judges one trajectory as the filter
  judged a chosen sample (``qp-dwa`` checks its refined command with it);
  ``report`` copies what the filter found into ``Command.info``.

A mechanism class subclasses :class:`Mechanism` (its registry ``name``) and implements
the methods of the roles it plays; :class:`Roles` sorts a planner's mechanisms by role
once, at construction, and the planner calls each role in the order of the preset.
Every hook gets a :class:`PlannerView` - the robot, the control period and the planner's
options, read-only - and the context or sample set of this step, never the planner: a
mechanism keeps its own state and publishes what it learns through its own typed
attributes (``InitialHeading.heading``, ``SweepGate.tracks``), which the planner reads.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Mapping, Protocol, runtime_checkable

import numpy as np

from ..world.robot import RobotSpec, RobotState
from .base import LocalContext
from .rollout import Step
from .window import Window


def build_part(cls, params: Mapping[str, Any], what: str):
    """``cls(**params)``, a critic or mechanism of a local planner built from user parameters: an
    unknown parameter of a dataclass is named with the known ones, any other refusal becomes a
    :class:`ParameterError` naming ``what``."""
    import dataclasses

    from ..errors import ParameterError, named_with_hints

    if dataclasses.is_dataclass(cls):
        known = [f.name for f in dataclasses.fields(cls) if f.init]
        unknown = sorted(set(params) - set(known))
        if unknown:
            raise ParameterError(f"bad parameters for {what}: unknown {named_with_hints(unknown, known)}; "
                                 f"known: {', '.join(known)}")
    try:
        return cls(**params)
    except TypeError as e:
        raise ParameterError(f"bad parameters for {what}: {dict(params)!r} ({e})") from None


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
    """Base of the mechanisms: the name the presets use (``mechanisms.MECHANISMS``).

    It declares no hooks; a subclass implements those of the roles it plays."""

    name: ClassVar[str] = ""


@runtime_checkable
class Resets(Protocol):
    """Role: keeps state across steps and forgets it at the start of a run."""

    def reset(self, view: PlannerView, state: RobotState, global_path: np.ndarray) -> None:
        """Forget the previous run."""


@runtime_checkable
class CapsWindow(Protocol):
    """Role: narrows the dynamic window of this step."""

    def adjust_window(self, view: PlannerView, ctx: LocalContext, window: Window) -> Window:
        """The window for this step (narrowed or as it is)."""


@runtime_checkable
class TakesOver(Protocol):
    """Role: may replace the sampled choice by a fixed manoeuvre."""

    def override(self, view: PlannerView, ctx: LocalContext, window: Window) -> tuple[float, float, dict] | None:
        """``(v_desired, w_desired, info)`` to clip into the window instead of sampling, or ``None``."""


@runtime_checkable
class PredictsMovers(Protocol):
    """Role: predicts some movers better than constant velocity."""

    def predict(self, view: PlannerView, ctx: LocalContext, centres: np.ndarray, t: np.ndarray) -> np.ndarray:
        """Predicted mover centres ``(K, H)`` complex at the rollout times ``t`` (one row per
        row of ``ctx.dynamic``); ``centres`` is the prediction so far, which may be updated in place."""


@runtime_checkable
class FiltersSamples(Protocol):
    """Role: judges the current sample set."""

    def filter(self, view: PlannerView, step: Step) -> np.ndarray | None:
        """Mask of samples to keep (``None`` = all)."""

    def strict_filter(self, view: PlannerView, step: Step) -> np.ndarray | None:
        """``filter`` without any relaxation it applies when nothing passes: judges a single
        trajectory on its own (``qp-dwa`` checks its refined command with it)."""

    def passes_like(self, view: PlannerView, check: Step, step: Step, i: int) -> bool:
        """Whether the single trajectory of ``check`` passes as sample ``i`` of ``step`` passed
        this step's ``filter``: by the strict test, or by the same relaxation when the filter
        relaxed it this step (``qp-dwa`` checks its refined command with it)."""

    def clearance_rows(self, view: PlannerView, step: Step, i: int,
                       like: tuple[Step, int] | None = None) -> list[tuple[int, complex, float, float]]:
        """This step's test of sample ``i`` as clearances ``qp-dwa``'s QP can linearise:
        ``(rollout index, unit normal (complex), gap, gap asked)`` per row, or ``[]`` when the
        test is not a clearance. With ``like = (judged, j)`` the gaps asked are those the test
        asked of sample ``j`` of ``judged`` (``passes_like``'s standard for a refined command)."""

    def report(self, step: Step) -> dict:
        """What this step's ``filter`` found, for ``Command.info`` (may be empty)."""


@dataclass(frozen=True)
class Roles:
    """A planner's mechanisms sorted by the roles they play (each tuple in preset order)."""

    resets: tuple[Resets, ...] = ()
    caps_window: tuple[CapsWindow, ...] = ()
    takes_over: tuple[TakesOver, ...] = ()
    predicts: tuple[PredictsMovers, ...] = ()
    filters: tuple[FiltersSamples, ...] = ()

    @classmethod
    def of(cls, mechanisms) -> "Roles":
        """Sort ``mechanisms`` (an iterable of :class:`Mechanism`) by role."""
        ms = tuple(mechanisms)
        return cls(resets=tuple(m for m in ms if isinstance(m, Resets)),
                   caps_window=tuple(m for m in ms if isinstance(m, CapsWindow)),
                   takes_over=tuple(m for m in ms if isinstance(m, TakesOver)),
                   predicts=tuple(m for m in ms if isinstance(m, PredictsMovers)),
                   filters=tuple(m for m in ms if isinstance(m, FiltersSamples)))
