"""Hindsight reference for closed-loop runs: could this run have been driven without contact?

A local planner meets the movers one sensor range at a time and does not know where they
will turn round. With hindsight the whole future is known, and the question "was this
collision avoidable?" becomes a search. :func:`hindsight_profile` answers it for the
simplest manoeuvre family there is: drive along one fixed path, forward only, choosing in
every control period to accelerate at ``a_max``, hold the speed, or brake at ``a_max``
(path-velocity decomposition, Kant & Zucker 1986). With those three choices the position
along the path after ``n`` periods is an integer multiple of ``q = a_max dt^2 / 2`` and the
speed a multiple of ``a_max dt``, so the set of reachable ``(speed, position)`` states is
propagated exactly, period by period, and states whose footprint meets a mover are
dropped. The first period in which a state reaches the goal tolerance gives the earliest
arrival.

What the answer means:

* **feasible** -- a witness exists: a speed profile along the path whose footprint stays
  clear of every mover at every period end by ``margin`` plus half the distance robot and
  mover can close within a period (so no contact between the samples either). It ignores
  turning at the path's corners and the start heading, which a unicycle must spend time on.
* **not found** -- no profile of this family exists. That is not a proof that the run was
  unavoidable: leaving the path, reversing or finer acceleration choices are not searched.

It is a reference, like the exact optimum next to a metaheuristic's path length: the share
of runs that are avoidable in hindsight bounds from below what better prediction could buy.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..local.critics import point_at_arc
from ..world.scenario import Scenario


@dataclass(frozen=True)
class HindsightProfile:
    """The result of :func:`hindsight_profile`.

    Attributes:
        feasible: a contact-free speed profile along the path reaches the goal in time.
        time_s: its earliest arrival (s), ``None`` when none was found.
        path_length: length of the path followed, m.
        periods: control periods searched (up to arrival or the time limit).
    """

    feasible: bool
    time_s: float | None
    path_length: float
    periods: int


def hindsight_profile(scenario: Scenario, path, margin: float = 0.0, spacing: float = 0.01) -> HindsightProfile:
    """Earliest contact-free arrival along ``path`` with the movers' whole future known.

    Args:
        scenario: a realised scenario (its movers are the ones the run met; see
            ``closed_loop.realized_scenario``).
        path: ``(N, 2)`` path from the start to the goal, metres.
        margin: extra edge-to-edge clearance demanded from every mover, m.
        spacing: the footprint test is made at path points this far apart (m); the
            clearance is widened by half of it so that the test stays conservative.

    Returns:
        A :class:`HindsightProfile`; the robot starts at rest at ``path[0]``.
    """
    P = np.asarray(path, dtype=float)
    if P.ndim != 2 or P.shape[1] != 2 or len(P) < 2 or not np.all(np.isfinite(P)):
        raise ParameterError(f"path must be a finite (N >= 2, 2) array of points, got shape {P.shape}")
    margin, spacing = float(margin), float(spacing)
    if not (margin >= 0 and math.isfinite(margin)) or not (spacing > 0 and math.isfinite(spacing)):
        raise ParameterError(f"margin must be >= 0 and spacing > 0 (metres), got {margin!r} and {spacing!r}")
    robot, dt = scenario.robot, scenario.dt
    a, v_max = robot.a_max, robot.v_max
    total = float(np.hypot(*np.diff(P, axis=0).T).sum())
    q = a * dt * dt / 2                      # position quantum: every reachable position is k q
    n_speed = int(math.floor(v_max / (a * dt) + 1e-9)) + 1
    n_pos = int(total / q) + 2 * n_speed + 1  # room for the last period's step past the goal
    goal_index = max(0, int(math.ceil((total - scenario.goal_tolerance) / q - 1e-9)))
    # the footprint test on a coarser grid of points, repeated onto the quanta it covers
    stride = max(1, int(spacing / q))
    probe_s = np.arange(0, n_pos, stride) * q
    probes = point_at_arc(P, probe_s)  # complex x + i y
    reach = np.zeros((n_speed, n_pos), dtype=bool)
    reach[0, 0] = True
    limit = int(round(scenario.time_limit / dt))
    shift = 2 * np.arange(n_speed)          # (v + v') dt / 2 / q = 2 k + choice
    for n in range(1, limit + 1):
        t = n * dt
        blocked = np.zeros(len(probe_s), dtype=bool)
        for ob in scenario.dynamic:
            pos, vel = ob.state(t, scenario.bounds)
            closing = (v_max + math.hypot(vel[0], vel[1])) * dt / 2
            clear = ob.radius + robot.radius + margin + closing + stride * q / 2
            blocked |= np.abs(probes - complex(pos[0], pos[1])) < clear
        blocked = np.repeat(blocked, stride)[:n_pos]
        new = np.zeros_like(reach)
        for k in np.flatnonzero(reach.any(axis=1)):
            row = reach[k]
            for choice in (-1, 0, 1):
                k2, d = k + choice, shift[k] + choice
                if not 0 <= k2 < n_speed or d < 0:
                    continue
                if d == 0:
                    new[k2] |= row
                else:
                    new[k2, d:] |= row[:-d]
        new[:, blocked] = False
        reach = new
        if reach[:, goal_index:].any():
            return HindsightProfile(True, t, total, n)
        if not reach.any():
            return HindsightProfile(False, None, total, n)
    return HindsightProfile(False, None, total, limit)
