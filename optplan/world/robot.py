"""The robot: its footprint and motion limits, and its kinematic state.

Two motion models are supported:

* ``unicycle`` (yuan2021 eq 14-18): commands ``(v, w)``, the robot moves along its
  heading ``theta``.
* ``omni`` (hou2024 eq 19): commands ``(v, vy, w)``; ``v`` is along the heading and
  ``vy`` to its left, so the robot can slide sideways.

Units: metres, seconds, radians internally; the scenario file gives angles in
degrees (``w_max_deg``, ``alpha_max_deg``), converted once here.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ParameterError, named_with_hints

MODELS = ("unicycle", "omni")
FIELDS = ("model", "radius", "v_max", "v_min", "w_max", "a_max", "alpha_max", "jerk_max", "vy_max")
# keys of a scenario file's ``robot`` mapping (angles in degrees there)
FILE_KEYS = ("model", "radius", "v_max", "v_min", "w_max_deg", "a_max", "alpha_max_deg", "jerk_max", "vy_max")


def _positive(name: str, value, allow_zero: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"robot {name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        need = ">= 0" if allow_zero else "> 0"
        raise ParameterError(f"robot {name} must be a finite number {need}, got {value!r}")
    return v


@dataclass(frozen=True)
class RobotSpec:
    """Footprint and limits of the robot.

    Attributes:
        model: ``"unicycle"`` or ``"omni"``.
        radius: footprint radius, metres.
        v_max: top forward speed, m/s.
        v_min: lowest forward speed, m/s (0 = no reversing; negative allows reversing).
        w_max: top yaw rate, rad/s.
        a_max: linear acceleration limit (also used for braking), m/s^2.
        alpha_max: angular acceleration limit, rad/s^2.
        jerk_max: linear jerk limit, m/s^3 (``None`` = unlimited).
        vy_max: top sideways speed of the omni model, m/s (0 for a unicycle).
    """

    model: str = "unicycle"
    radius: float = 0.2
    v_max: float = 1.0
    v_min: float = 0.0
    w_max: float = math.radians(30.0)
    a_max: float = 0.3
    alpha_max: float = math.radians(50.0)
    jerk_max: float | None = None
    vy_max: float = 0.0

    def __post_init__(self) -> None:
        if self.model not in MODELS:
            raise ParameterError(f"robot model must be one of {', '.join(MODELS)}, got {self.model!r}")
        for name in ("radius", "v_max", "w_max", "a_max", "alpha_max"):
            object.__setattr__(self, name, _positive(name, getattr(self, name)))
        try:
            v_min = float(self.v_min)
        except (TypeError, ValueError):
            v_min = math.nan
        if not math.isfinite(v_min) or v_min > self.v_max:
            raise ParameterError(f"robot v_min must be finite and <= v_max ({self.v_max:g}), got {self.v_min!r}")
        object.__setattr__(self, "v_min", v_min)
        if self.jerk_max is not None:
            object.__setattr__(self, "jerk_max", _positive("jerk_max", self.jerk_max))
        object.__setattr__(self, "vy_max", _positive("vy_max", self.vy_max, allow_zero=True))

    @classmethod
    def from_dict(cls, d: dict) -> "RobotSpec":
        """Build from the scenario file's ``robot`` mapping (angles in degrees)."""
        d = dict(d)
        if "w_max_deg" in d:
            d["w_max"] = math.radians(float(d.pop("w_max_deg")))
        if "alpha_max_deg" in d:
            d["alpha_max"] = math.radians(float(d.pop("alpha_max_deg")))
        unknown = set(d) - set(FIELDS)
        if unknown:
            raise ParameterError(f"unknown robot key(s) {named_with_hints(sorted(unknown), FILE_KEYS)}; known: {', '.join(FILE_KEYS)}")
        return cls(**d)


@dataclass
class RobotState:
    """Pose and velocity of the robot at one instant (metres, radians, m/s, rad/s).

    ``vy`` is the sideways speed of the omni model (0 for a unicycle).
    """

    x: float
    y: float
    theta: float
    v: float = 0.0
    w: float = 0.0
    vy: float = 0.0

    @property
    def position(self) -> tuple[float, float]:
        return (self.x, self.y)


@dataclass
class Command:
    """Velocity command for one control period.

    Attributes:
        v: forward speed, m/s.
        w: yaw rate, rad/s.
        vy: sideways speed (omni model only), m/s.
        info: diagnostics of the planner (chosen cost, QP status, fallback used, ...).
    """

    v: float
    w: float
    vy: float = 0.0
    info: dict | None = None
