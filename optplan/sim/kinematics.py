"""Motion models of the simulated robot, integrated exactly as the papers write them.

* unicycle (yuan2021 eq 14-18): over one period ``dt`` the robot drives straight
  along its current heading, then turns::

      x += v dt cos(theta);  y += v dt sin(theta);  theta += w dt

* omni (hou2024 eq 19): the body-frame velocity ``(v, vy)`` (forward, to the left) is
  rotated by the current heading::

      x += (v cos(theta) - vy sin(theta)) dt;  y += (v sin(theta) + vy cos(theta)) dt;  theta += w dt

Because the position update uses the heading at the start of the period, the robot
centre moves along a straight segment during each period; the simulator's swept
collision test checks exactly that segment.

Both functions broadcast over leading dimensions, so local planners may use them
for rollouts too. Units: metres, seconds, radians.
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..world.geometry import wrap_angle


def step_pose(model: str, x, y, theta, v, w, dt: float, vy=0.0):
    """Pose after one period of constant command ``(v, vy, w)``.

    Args:
        model: ``"unicycle"`` or ``"omni"`` (``vy`` is ignored for the unicycle).
        x, y, theta: pose (metres, radians); arrays broadcast.
        v, w: forward speed (m/s) and yaw rate (rad/s).
        dt: period, seconds.
        vy: sideways speed of the omni model (m/s, positive to the left).

    Returns:
        ``(x, y, theta)`` after ``dt`` (theta wrapped to ``[-pi, pi)``).
    """
    c, s = np.cos(theta), np.sin(theta)
    if model == "unicycle":
        dx, dy = v * c, v * s
    elif model == "omni":
        dx, dy = v * c - vy * s, v * s + vy * c
    else:
        raise ParameterError(f"motion model must be 'unicycle' or 'omni', got {model!r}")
    return x + dx * dt, y + dy * dt, wrap_angle(theta + w * dt)
