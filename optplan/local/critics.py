"""Cost terms of the DWA evaluation functions, one small class per term (like Nav2's DWB critics).

Every critic maps a :class:`~optplan.local.rollout.Step` to one value per sample.
``cost = False`` terms are rewards (higher is better, e.g. heading, velocity);
``cost = True`` terms are penalties (e.g. distance to the global path) and enter the
evaluation with a minus sign. A critic may also declare samples illegal (``legal``), which
removes them before the choice, like the papers' "discard the trajectory" rules.

The planner normalises each term over the candidate samples before weighting
(the papers' sigma in hou2024 eq 31, yuan2021 eq 22-23, yang2023 eq 18), so the raw
values below keep their physical units (rad, m, m/s, 1/m).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..checks import boolean
from ..world.geometry import wrap_angle
from .rollout import Step


def body_direction(v, vy):
    """Direction of the velocity ``(v, vy)`` in the robot frame, rad (0 when standing)."""
    v, vy = np.asarray(v, dtype=float), np.asarray(vy, dtype=float)
    return np.where((v == 0) & (vy == 0), 0.0, np.arctan2(vy, v))


def polyline_distance(z: np.ndarray, path: np.ndarray, near: complex | None = None,
                      reach: float = np.inf) -> np.ndarray:
    """Distance (m) from complex points ``z`` (any shape) to the polyline ``path`` ``(N, 2)``.

    Only segments within ``reach`` of ``near`` are considered (the part of the path a local
    trajectory can approach); when none is, the nearest ones. The distance half of
    :func:`project_on_path`.
    """
    return project_on_path(path, z, near, reach, arc=False)[1]


class Critic:
    """One term of the evaluation function (see the module docstring)."""

    name: ClassVar[str] = ""
    cost: ClassVar[bool] = False

    def score(self, step: Step) -> np.ndarray:  # pragma: no cover - interface
        raise NotImplementedError

    def legal(self, step: Step) -> np.ndarray | None:
        """Mask of samples this term allows (``None`` = all)."""
        return None


# ---------------------------------------------------------------- Fox et al. 1997 (dwa)
@dataclass
class Heading(Critic):
    """``heading = pi - |alpha|`` with ``alpha`` the angle between the robot's heading and the
    direction to the subgoal, both at the end of the trajectory (Fox 1997; yuan2021 §3.3;
    yang2023 eq 15; li2023 eq 10 ``h``), rad.

    ``one_step_within``: yang2023 §5.2. When the robot is closer than this (m) to the subgoal
    the angle is taken at the pose after one control period instead of the trajectory end,
    so that the robot does not circle a nearby target.
    """

    name: ClassVar[str] = "heading"
    one_step_within: float | None = None

    def score(self, step: Step) -> np.ndarray:
        roll = step.roll
        target = step.target
        k = None
        if self.one_step_within is not None and abs(target - roll.z0) < self.one_step_within:
            k = max(1, int(round(step.ctx.dt / roll.dt)))
            step.aux["heading_one_step"] = True
        z = roll.position(k)
        bearing = np.angle(target - z)
        return np.pi - np.abs(wrap_angle(bearing - roll.heading(k)))


def project_on_path(path: np.ndarray, z: np.ndarray, near: complex | None = None,
                    reach: float = np.inf, arc: bool = True) -> tuple[np.ndarray | None, np.ndarray]:
    """Arc length (m) along the polyline ``path`` of the path point nearest to each complex
    point ``z`` (any shape), and the distance (m) to it. With ``near`` and ``reach`` only the
    segments within ``reach`` of ``near`` are searched (the nearest ones if none is)."""
    p = np.asarray(path, dtype=float).reshape(-1, 2)
    pc = p[:, 0] + 1j * p[:, 1]
    z = np.asarray(z, dtype=complex)
    if z.ndim == 0:  # one point: the loop below writes in place
        s, d = project_on_path(path, z[None], near, reach, arc)
        return (None if s is None else s[0]), d[0]
    if len(pc) == 1:
        return (np.zeros(z.shape) if arc else None), np.abs(z - pc[0])
    a, ab = pc[:-1], np.diff(pc)
    L = np.abs(ab)
    along = np.r_[0.0, np.cumsum(L)]
    segments = range(len(a))
    if near is not None and np.isfinite(reach):
        t = np.clip(((near - a) * np.conj(ab)).real / np.maximum(L * L, 1e-18), 0.0, 1.0)
        d_near = np.abs(near - (a + t * ab))
        within = d_near <= reach
        segments = np.flatnonzero(within if within.any() else d_near == d_near.min())
    best_d = np.full(z.shape, np.inf)
    best_s = np.zeros(z.shape) if arc else None
    for i in segments:  # nearby segments of the global path, each over all points at once
        t = ((z - a[i]) * np.conj(ab[i])).real / max(L[i] ** 2, 1e-18)
        np.clip(t, 0.0, 1.0, out=t)
        d = np.abs(z - (a[i] + t * ab[i]))
        if not arc:
            np.minimum(best_d, d, out=best_d)
            continue
        closer = d < best_d
        np.copyto(best_d, d, where=closer)
        t *= L[i]
        t += along[i]
        np.copyto(best_s, t, where=closer)
    return best_s, best_d


def point_at_arc(path: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Complex points at arc lengths ``s`` (m) along the polyline ``path`` (clamped to its ends)."""
    p = np.asarray(path, dtype=float).reshape(-1, 2)
    pc = p[:, 0] + 1j * p[:, 1]
    if len(pc) == 1:
        return np.full(np.shape(s), pc[0])
    ab = np.diff(pc)
    L = np.abs(ab)
    along = np.r_[0.0, np.cumsum(L)]
    s = np.clip(s, 0.0, along[-1])
    j = np.clip(np.searchsorted(along, s, side="right") - 1, 0, len(ab) - 1)
    return pc[j] + (s - along[j]) / np.maximum(L[j], 1e-18) * ab[j]


def _trajectory_end(step: Step, until_stop: bool) -> tuple[np.ndarray, np.ndarray]:
    """``(position (S,) complex, heading (S,))`` a path critic judges each trajectory by: its
    end, or with ``until_stop`` its last point before the first static collision, where
    the robot following it has to stop. Judged by its end, a trajectory that runs into a
    wall 0.3 m ahead was credited the progress of the 1.5 m it cannot drive; it beat every
    free trajectory, and the QP then braked it to a standstill, step after step, in front
    of the obstacle (issue 27)."""
    if until_stop:
        return step.pose_at_stop()
    return step.roll.position(), step.roll.heading()


def _projected_ends(step: Step, until_stop: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(end, heading, s)``: :func:`_trajectory_end` and the arc lengths ``s`` ``(S + 1,)`` of
    the path points nearest to the robot (first) and to each end. Kept in ``step.aux`` for
    the step, so the path critics that judge the same ends project them once."""
    key = ("projected_ends", until_stop)
    if key not in step.aux:
        end, heading = _trajectory_end(step, until_stop)
        s, _ = project_on_path(step.ctx.global_path, np.r_[step.roll.z0, end], step.roll.z0, _reach(step))
        step.aux[key] = (end, heading, s)
    return step.aux[key]


def _reach(step: Step) -> float:
    """How far (m) from the robot any rollout point can be, plus a metre of slack."""
    roll = step.roll
    return roll.max_speed * float(roll.t[-1]) + 1.0


@dataclass
class PathHeading(Heading):
    """Heading towards a carrot on the global path: for each trajectory, the path point
    ``look_ahead`` metres beyond the path point nearest to the trajectory's end (the
    pure-pursuit target; Nav2 DWB's path-align idea), instead of the subgoal. The robot then
    follows the path around corners that the straight line to a subgoal would cut, and a
    trajectory never "passes" its target. ``until_stop``: see :func:`_trajectory_end`."""

    name: ClassVar[str] = "path_heading"
    look_ahead: float = 1.0
    until_stop: bool = False

    def score(self, step: Step) -> np.ndarray:
        end, heading, s = _projected_ends(step, self.until_stop)
        bearing = np.angle(point_at_arc(step.ctx.global_path, s[1:] + self.look_ahead) - end)
        return np.pi - np.abs(wrap_angle(bearing - heading))


@dataclass
class PathProgress(Critic):
    """How far (m) the trajectory's end has advanced along the global path: arc length of
    its nearest path point minus that of the robot's (Nav2 DWB's path-progress idea). It
    rewards moving on along the path even when every trajectory is short (low speed).

    With ``within_travel`` the advance is capped at the length the trajectory drives: a
    trajectory that heads straight past a bend of the path projects onto the path beyond
    the bend and was credited more progress than it drove, so the sum of terms preferred
    cutting the corner into clutter the global path keeps clear of (issue 27, where such
    runs ended pinned in a gap off the path). ``until_stop``: see :func:`_trajectory_end`."""

    name: ClassVar[str] = "path_progress"
    within_travel: bool = False
    until_stop: bool = False

    def score(self, step: Step) -> np.ndarray:
        roll = step.roll
        _, _, s = _projected_ends(step, self.until_stop)
        gain = s[1:] - s[0]
        if not self.within_travel:
            return gain
        fastest = roll.speed[:, None] if roll.profile is None else roll.profile
        held = np.broadcast_to(fastest, roll.z.shape)
        if self.until_stop:
            held = np.where(np.arange(roll.z.shape[1])[None, :] < step.stop_index()[:, None], held, 0.0)
        driven = held.sum(axis=1) * roll.dt
        return np.minimum(gain, driven)


@dataclass
class Clearance(Critic):
    """Fox's ``dist``: the smallest edge-to-edge distance (m) to any obstacle, static or
    moving, along the trajectory, capped at ``cap`` (no obstacle close to the trajectory)
    and floored at ``floor`` (0: every contact scores the same; a negative floor lets a
    deeper predicted overlap with an uncertain mover disc score worse)."""

    name: ClassVar[str] = "clearance"
    cap: float = 2.0
    floor: float = 0.0

    def score(self, step: Step) -> np.ndarray:
        return np.clip(step.gap.min(axis=1), self.floor, self.cap)


@dataclass
class Velocity(Critic):
    """Fox's ``vel``: the forward speed (m/s; the planar speed for the omni model)."""

    name: ClassVar[str] = "velocity"

    def score(self, step: Step) -> np.ndarray:
        r = step.roll
        return r.speed if np.any(r.vy) else r.v


# ---------------------------------------------------------------- hou2024 §3.1 (missa-dwa)
@dataclass
class PathDeviation(Critic):
    """hou2024 eq 25 ``Pathdist``: mean distance (m) between ``N`` sampling points of the
    trajectory and ``N`` sampling points of the global path (every ``stride``-th rollout point).

    ``paired`` (default) reads eq 25 literally: the i-th trajectory point is compared with
    the i-th path point, the path being sampled ahead of the robot's nearest path point at
    the spacing of a robot that follows it at ``v_max`` - so lagging behind the path costs
    as much as leaving it sideways, and standing still is not free. ``paired=False``
    measures each trajectory point's distance to the nearest point of the path instead.
    ``until_stop``: the points from the first static collision on are taken where the robot
    has to stop, before it (see :func:`_trajectory_end`)."""

    name: ClassVar[str] = "path_deviation"
    cost: ClassVar[bool] = True
    stride: int = 3
    paired: bool = True
    until_stop: bool = False

    def score(self, step: Step) -> np.ndarray:
        roll = step.roll
        idx = np.arange(self.stride - 1, roll.z.shape[1], self.stride)
        pts = (step.held_at_stop() if self.until_stop else roll.z)[:, idx]
        path = step.ctx.global_path
        if self.paired:
            s0, _ = project_on_path(path, np.array([roll.z0]), roll.z0, 1.0)
            ref = point_at_arc(path, s0[0] + step.robot.v_max * roll.t[idx])
            return np.abs(pts - ref[None, :]).mean(axis=1)
        return polyline_distance(pts, path, roll.z0, _reach(step)).mean(axis=1)


@dataclass
class StaticInverseDistance(Critic):
    """hou2024 eq 26-27 ``Dist_S``: ``1 / D_s`` with ``D_s`` the smallest distance (m) from the
    robot centre to a static obstacle along the trajectory; trajectories with
    ``D_s < factor R`` (``factor`` = 1.15, R the robot radius) are discarded.

    The paper writes the evaluation as one sum to maximise, but ``1/D_s`` grows as the robot
    gets closer and the companion term ``Pathdist`` is a distance to minimise; we read both
    as penalties, and the "0" branch of eq 27 as the discard rule."""

    name: ClassVar[str] = "static_inverse"
    cost: ClassVar[bool] = True
    factor: float = 1.15

    def _d(self, step: Step) -> np.ndarray:
        return step.static_gap.min(axis=1) + step.robot.radius

    def score(self, step: Step) -> np.ndarray:
        return 1.0 / np.maximum(self._d(step), 1e-3)

    def legal(self, step: Step) -> np.ndarray:
        return self._d(step) >= self.factor * step.robot.radius


@dataclass
class DynamicInverseDistance(Critic):
    """hou2024 eq 28-30 ``Dist_D``: ``1 / D_d`` with ``D_d`` the smallest edge-to-edge
    distance (m) from the trajectory to a moving obstacle; trajectories with
    ``D_d < factor S`` are discarded, ``S = v dt`` the distance the robot covers in one
    control period (eq 30) and ``factor`` = 1.15. (Eq 29 repeats ``D_s``; ``D_d`` is meant.)

    ``at_sensed_position``: which obstacle position eq 28 measures to. Eq 28,
    ``D_d = min((x_t - x_i)^2 + (y_t - y_i)^2)``, gives the trajectory points a time index
    and the obstacle's coordinates ``(x_i, y_i)`` none. ``False`` (default) compares each
    trajectory point with the mover predicted at constant velocity to the same time
    (``Step.dyn_gap``); ``True`` reads eq 28 as printed: the distance to the mover's disc
    where it is sensed now (``Step.sensed_dyn_gap``), used by both the score (eq 28-29) and
    the discard rule (eq 29). The planner's contact test with the predicted movers is the
    same either way. (We keep distances, not the squared distances eq 28 prints: eq 29
    compares ``D_d`` with a length.)

    ``also_predicted`` (not the paper's; with ``at_sensed_position``): each point's distance
    is the smaller of the two, to the sensed and to the predicted mover."""

    name: ClassVar[str] = "dynamic_inverse"
    cost: ClassVar[bool] = True
    factor: float = 1.15
    at_sensed_position: bool = False
    also_predicted: bool = False

    def __post_init__(self) -> None:
        for k in ("at_sensed_position", "also_predicted"):
            setattr(self, k, boolean(k, getattr(self, k)))

    def d_d(self, step: Step) -> np.ndarray:
        """``(S,)`` eq 28's ``D_d`` of every sample, m (edge to edge)."""
        if not self.at_sensed_position:
            return step.dyn_gap.min(axis=1)
        gap = step.sensed_dyn_gap()
        if self.also_predicted:
            gap = np.minimum(gap, step.dyn_gap)
        return gap.min(axis=1)

    def score(self, step: Step) -> np.ndarray:
        return 1.0 / np.maximum(self.d_d(step), 1e-3)

    def legal(self, step: Step) -> np.ndarray:
        S = step.roll.speed * step.ctx.dt
        return self.d_d(step) >= self.factor * S


# ---------------------------------------------------------------- yang2023 §5 (idwa)
@dataclass
class BinaryDistance(Critic):
    """yang2023 eq 16 ``Dist``: 1 when the trajectory keeps the robot centre farther than
    the obstacles' influence radius ``R`` from every static obstacle, else 0.1, so the robot
    may pass close to (but not into) obstacles and keeps following the global path.
    ``R`` = robot radius + ``influence`` (m)."""

    name: ClassVar[str] = "binary_distance"
    influence: float = 0.1

    def score(self, step: Step) -> np.ndarray:
        far = step.static_gap.min(axis=1) > self.influence
        return np.where(far, 1.0, 0.1)


@dataclass
class HeadingChange(Critic):
    """yang2023 eq 17 ``vh``: how much the trajectory increases the angle ``VA`` between the
    robot's velocity and the velocity of the mover the velocity-obstacle test flagged
    (``step.aux["vo_threat"]``), rad. ``VA(t)`` is taken now and ``VA(t+1)`` at the end of the
    trajectory. When ``VA(t)`` is 0 or pi either turn is equally good, so the change counts by
    its magnitude. Without a flagged mover the term is 0 for every sample: eq 19's
    ``lambda = 0`` when the VO predicts no collision (``lambda = 1.5 alpha`` otherwise is the
    preset's weight)."""

    name: ClassVar[str] = "heading_change"
    tol: float = 1e-3

    def score(self, step: Step) -> np.ndarray:
        k = step.aux.get("vo_threat")
        roll = step.roll
        if k is None:
            return np.zeros(roll.n)
        phi_obs = np.angle(step.mover_vel[k])
        state = step.ctx.state
        va_now = abs(wrap_angle(roll.theta0 + body_direction(state.v, state.vy) - phi_obs))
        va_next = np.abs(wrap_angle(roll.heading() + body_direction(roll.v, roll.vy) - phi_obs))
        change = va_next - va_now
        if va_now < self.tol or va_now > np.pi - self.tol:
            change = np.abs(change)
        return change


# ---------------------------------------------------------------- yuan2021 (ba-dwa)
@dataclass
class GlobalPathDistance(Critic):
    """yuan2021 eq 23 ``gdist``: distance (m) from the trajectory's end to the nearest point
    of the global path. We measure to the path polyline (the limit of densely spaced nodes)
    because the navigation layer may pass only the turning points."""

    name: ClassVar[str] = "gdist"
    cost: ClassVar[bool] = True

    def score(self, step: Step) -> np.ndarray:
        roll = step.roll
        return polyline_distance(roll.position(), step.ctx.global_path, roll.z0, _reach(step))


# ---------------------------------------------------------------- li2023 eq 10 (iga-dwa)
@dataclass
class GoalDistance(Critic):
    """li2023 eq 10 ``d``: distance (m) from the trajectory's end to the subgoal."""

    name: ClassVar[str] = "goal_distance"
    cost: ClassVar[bool] = True

    def score(self, step: Step) -> np.ndarray:
        return np.abs(step.target - step.roll.position())


@dataclass
class EndClearance(Critic):
    """li2023 eq 10 ``o``: edge-to-edge distance (m) from the trajectory's end to the
    nearest obstacle, capped at ``cap``.

    ``at_sensed_position``: where a moving obstacle is taken. §5.2 defines ``o`` as "the
    minimum distance from the end of the simulated trajectory to the obstacle" and says
    nothing of predicting obstacles (§6.4 sums up that the fused planner plans "based on the
    real-time obstacle position").
    ``False`` (default): the mover predicted at constant velocity to the end's time
    (``Step.dyn_gap``); ``True``: the mover where it is sensed now (``Step.sensed_dyn_gap``)."""

    name: ClassVar[str] = "end_clearance"
    cap: float = 2.0
    at_sensed_position: bool = False

    def __post_init__(self) -> None:
        self.at_sensed_position = boolean("at_sensed_position", self.at_sensed_position)

    def score(self, step: Step) -> np.ndarray:
        dyn = step.sensed_dyn_gap() if self.at_sensed_position else step.dyn_gap
        return np.clip(np.minimum(step.static_gap[:, -1], dyn[:, -1]), 0.0, self.cap)


CRITICS: dict[str, type[Critic]] = {c.name: c for c in (
    Heading, PathHeading, PathProgress, Clearance, Velocity, PathDeviation, StaticInverseDistance, DynamicInverseDistance,
    BinaryDistance, HeadingChange, GlobalPathDistance, GoalDistance, EndClearance)}
