"""Closed-loop simulation: time stepping, moving obstacles, sensing, exact collision
checks, metrics and trajectory recording (``op.simulate``)."""
from __future__ import annotations

from .closed_loop import simulate
from .environment import SimEnvironment
from .kinematics import step_pose, wrap_angle

__all__ = ["SimEnvironment", "simulate", "step_pose", "wrap_angle"]
