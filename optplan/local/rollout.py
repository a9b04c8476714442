"""Forward simulation of every velocity sample at once, and its clearance.

Positions are complex numbers ``x + i y`` so that one rotation is one multiplication.
Under a constant command ``(v, vy, w)`` the motion model the simulator uses
(unicycle: yuan2021 eq 14-18; omni: hou2024 eq 19, ``vy`` = 0 gives the unicycle) is

    z_{k+1} = z_k + dt (v + i vy) exp(i theta_k),    theta_k = theta_0 + k w dt,

so ``z_k = z_0 + dt (v + i vy) C_k(w)`` with ``C_k(w) = sum_{j<k} exp(i theta_j)``. ``C`` is
computed once per sampled yaw rate and scaled by every linear velocity: the whole
samples x horizon rollout is one complex multiplication.

Moving obstacles are predicted at constant velocity along the horizon (``assess`` lets a
planner's mechanisms replace that for movers they know better). Their clearance is
accumulated one obstacle at a time over the full samples x horizon array: with ~10
obstacles this keeps the working set in cache and is several times faster than one
broadcast ``(samples, horizon, obstacles)`` array (measured in ``benchmarks/dwa_step.py``).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..world.robot import RobotSpec, RobotState
from .base import LocalContext
from .window import stopping_distance


@dataclass
class Rollouts:
    """Predicted trajectories of ``S`` samples over ``H`` steps.

    Attributes:
        v, vy, w: ``(S,)`` sampled command of each trajectory (m/s, m/s, rad/s).
        z: ``(S, H)`` complex positions ``x + i y`` at times ``t`` (metres).
        t: ``(H,)`` times of the positions, ``dt, 2 dt, ..., H dt`` (s).
        z0: start position (complex), theta0: start heading (rad), dt: step (s).
        theta: ``(S, H)`` headings after each step (ramped rollouts; ``None``: ``theta0 + w t``).
        profile: ``(S, H)`` planar speed held during each step (ramped rollouts, whose speed
            changes along the horizon; ``None``: the sampled speed throughout).
        tracking: ``(S,)`` mask of the samples that follow the global path with a command that
            changes along the horizon (:func:`rollout_tracking`; their ``v, w`` is the first
            period's command); ``None``: none does.
    """

    v: np.ndarray
    vy: np.ndarray
    w: np.ndarray
    z: np.ndarray
    t: np.ndarray
    z0: complex
    theta0: float
    dt: float
    theta: np.ndarray | None = None
    profile: np.ndarray | None = None
    tracking: np.ndarray | None = None

    @property
    def n(self) -> int:
        return self.z.shape[0]

    @property
    def xy(self) -> np.ndarray:
        """``(S, H, 2)`` float view of the positions (no copy)."""
        return self.z.view(np.float64).reshape(self.z.shape + (2,))

    @property
    def speed(self) -> np.ndarray:
        """Planar speed of each sample, m/s."""
        return np.hypot(self.v, self.vy)

    @property
    def max_speed(self) -> float:
        """Fastest planar speed anywhere on the rollouts, m/s (a ramp may start faster than
        its target): every rollout point at time ``t`` lies within ``max_speed t`` of ``z0``."""
        fastest = self.speed if self.profile is None else self.profile
        return float(fastest.max(initial=0.0))

    def heading(self, k: int | None = None) -> np.ndarray:
        """Heading after ``k`` steps (default: at the end of the horizon), rad."""
        k = self.z.shape[1] if k is None else k
        if self.theta is not None:  # ramped rollouts keep their headings
            return self.theta[:, k - 1] if k > 0 else np.full(self.n, self.theta0)
        return self.theta0 + self.w * (k * self.dt)

    def position(self, k: int | None = None) -> np.ndarray:
        """Complex position after ``k`` steps (``k`` = 0 is the start), default the end."""
        k = self.z.shape[1] if k is None else k
        return np.full(self.n, self.z0) if k == 0 else self.z[:, k - 1]


def rollout(state: RobotState, lin_v: np.ndarray, lin_vy: np.ndarray, w: np.ndarray, dt: float,
            steps: int) -> Rollouts:
    """Roll out the grid ``(lin_v, lin_vy) x w`` (see ``window.sample_grid``) for ``steps``
    steps of ``dt`` seconds from ``state``."""
    k = np.arange(steps)
    rot = np.exp(1j * (state.theta + np.multiply.outer(w, k * dt)))  # (n_w, H): exp(i theta_j)
    C = np.cumsum(rot, axis=1)
    C *= dt
    lin = (np.asarray(lin_v) + 1j * np.asarray(lin_vy))[:, None, None]  # (n_lin, 1, 1)
    z0 = complex(state.x, state.y)
    z = (lin * C[None]).reshape(-1, steps)
    z += z0
    n_lin = len(lin_v)
    return Rollouts(v=np.repeat(lin_v, len(w)), vy=np.repeat(lin_vy, len(w)), w=np.tile(w, n_lin), z=z,
                    t=(k + 1) * dt, z0=z0, theta0=float(state.theta), dt=float(dt))


def _ramp(current: float, target: np.ndarray, accel: float, t: np.ndarray) -> np.ndarray:
    """``(S, H)`` velocity moving from ``current`` towards each target at ``accel``."""
    return current + np.clip(np.asarray(target)[:, None] - current, -accel * t, accel * t)


def rollout_ramped(state: RobotState, lin_v: np.ndarray, lin_vy: np.ndarray, w: np.ndarray, dt: float, steps: int,
                   accel: tuple[float, float, float]) -> Rollouts:
    """Like :func:`rollout`, but each sample is a *target* velocity that the robot approaches
    from its current velocity at the accelerations ``accel`` ``(a_v, a_w, a_vy)`` and then
    holds. Used when the targets span more than one period's reach (the ``lookahead``
    option of ``qp-dwa``, whose commands follow a Ruckig profile to the target). Same grid
    layout as :func:`rollout`; every sample is integrated with the same motion model."""
    n_w, n_lin = len(w), len(lin_v)
    t = np.arange(steps) * dt  # velocity held during step j is the ramp's value at j dt... (j+1) dt
    t1 = t + dt
    v = _ramp(state.v, lin_v, accel[0], t1)  # (n_lin, H)
    vy = _ramp(state.vy, lin_vy, accel[2], t1)
    wr = _ramp(state.w, w, accel[1], t1)  # (n_w, H)
    theta_w = state.theta + np.cumsum(wr, axis=1) * dt  # heading after each step
    start_heading = np.concatenate([np.full((n_w, 1), state.theta), theta_w[:, :-1]], axis=1)
    theta = np.tile(theta_w, (n_lin, 1))
    # (n_lin, 1, H) x (1, n_w, H) broadcast: the same products as repeating and tiling both
    z = ((v + 1j * vy)[:, None, :] * np.exp(1j * start_heading)[None]).reshape(-1, steps)
    np.cumsum(z, axis=1, out=z)  # in place: the same sums, one array fewer
    z *= dt
    z0 = complex(state.x, state.y)
    z += z0
    return Rollouts(v=np.repeat(lin_v, n_w), vy=np.repeat(lin_vy, n_w), w=np.tile(w, n_lin), z=z, t=t1, z0=z0,
                    theta0=float(state.theta), dt=float(dt), theta=theta,
                    profile=np.repeat(np.hypot(v, vy), n_w, axis=0))


def join_rollouts(a: Rollouts, b: Rollouts) -> Rollouts:
    """The samples of ``a`` followed by those of ``b`` (same start, step and horizon)."""
    both = dict(v=np.concatenate((a.v, b.v)), vy=np.concatenate((a.vy, b.vy)), w=np.concatenate((a.w, b.w)),
                z=np.vstack([a.z, b.z]), t=a.t, z0=a.z0, theta0=a.theta0, dt=a.dt)
    if all(r.theta is None and r.profile is None and r.tracking is None for r in (a, b)):
        # constant commands both: headings and speeds follow from (v, vy, w), nothing per step
        return Rollouts(**both)

    def per_step(r: Rollouts) -> tuple[np.ndarray, np.ndarray]:
        theta = r.theta if r.theta is not None else r.theta0 + np.multiply.outer(r.w, r.t)
        profile = r.profile if r.profile is not None else np.broadcast_to(r.speed[:, None], r.z.shape)
        return theta, profile

    (ta, pa), (tb, pb) = per_step(a), per_step(b)
    mask = [r.tracking if r.tracking is not None else np.zeros(r.n, dtype=bool) for r in (a, b)]
    return Rollouts(**both, theta=np.vstack([ta, tb]), profile=np.vstack([pa, pb]), tracking=np.concatenate(mask))


def rollout_tracking(state: RobotState, path: np.ndarray, speeds: np.ndarray, look_aheads: np.ndarray, dt: float,
                     steps: int, robot: RobotSpec, turn_first: np.ndarray = (np.pi / 2,),
                     spacing: float = 0.05) -> Rollouts:
    """Trajectories that follow the global path by pure pursuit, one per ``(speed, look-ahead,
    turn_first)`` triple (all triples of the three arrays), every step at once across the samples.

    At each step a sample steers towards the path point ``look_ahead`` metres beyond the path
    point nearest to it (curvature ``2 sin(alpha) / look_ahead``, ``alpha`` the bearing of that
    point in the robot frame), at its speed times ``cos alpha``: it slows down to turn, and
    while ``|alpha|`` exceeds ``turn_first`` (rad) it turns in place towards the point (a robot
    squeezed into a gap at an angle can only leave it after facing along it). The velocities
    change by at most
    ``a_max dt`` and ``alpha_max dt`` per step and stay within the speed limits, so the first
    step's velocity (``v, w`` of the result) can be commanded for the next period.

    A constant command over the horizon is an arc; in clutter no arc follows a bend of the
    path for three seconds, so every arc sample met an obstacle and the robot stopped in
    front of a passage the path threads (issue 27). These samples can take the bend; they
    are judged by the same critics and the same admissibility test as the others.
    """
    P = np.asarray(path, dtype=float).reshape(-1, 2)
    pc = P[:, 0] + 1j * P[:, 1]
    z0 = complex(state.x, state.y)
    if len(pc) > 1:  # the path densely resampled from near the robot on (arc lengths s)
        L = np.abs(np.diff(pc))
        along = np.r_[0.0, np.cumsum(L)]
        j = int(np.argmin(np.abs(pc - z0)))
        s_to = min(along[-1], along[j] + robot.v_max * steps * dt + float(np.max(look_aheads)) + 1.0)
        s = np.arange(along[max(j - 1, 0)], s_to + spacing, spacing)
        k = np.clip(np.searchsorted(along, s, side="right") - 1, 0, len(L) - 1)
        dense = pc[k] + (np.clip(s, 0, along[-1]) - along[k]) / np.maximum(L[k], 1e-18) * np.diff(pc)[k]
    else:
        dense = pc
    speeds, look_aheads, turn_first = (np.asarray(x, dtype=float).ravel() for x in (speeds, look_aheads, turn_first))
    v_target, ahead, align = (g.ravel() for g in np.meshgrid(speeds, look_aheads, turn_first, indexing="ij"))
    shift = np.maximum(1, np.round(ahead / spacing).astype(int))
    n = len(v_target)
    z = np.full(n, z0)
    theta = np.full(n, float(state.theta))
    v = np.full(n, float(state.v))
    w = np.full(n, float(state.w))
    dv, dw = robot.a_max * dt, robot.alpha_max * dt
    v_lo = max(robot.v_min, 0.0)
    # an omni robot's sideways speed is commanded to 0 and decays at a_max
    vy = float(state.vy) - np.clip(float(state.vy), -dv, dv) * (np.arange(steps) + 1)
    vy = np.where(np.sign(vy) == np.sign(state.vy), vy, 0.0)
    Z, TH, V, W = (np.empty((n, steps), dtype=complex), np.empty((n, steps)), np.empty((n, steps)),
                   np.empty((n, steps)))
    for k in range(steps):  # a loop over the horizon; each step is vectorised over the samples
        near = np.argmin(np.abs(z[:, None] - dense[None, :]), axis=1)
        carrot = dense[np.minimum(near + shift, len(dense) - 1)]
        alpha = np.angle((carrot - z) * np.exp(-1j * theta))
        go = np.abs(alpha) <= align
        v_want = np.where(go, v_target * np.maximum(np.cos(alpha), 0.0), 0.0)
        w_want = np.where(go, 2.0 * v_want * np.sin(alpha) / ahead, np.sign(alpha) * robot.w_max)
        v = np.clip(np.clip(v_want, v - dv, v + dv), v_lo, robot.v_max)
        w = np.clip(np.clip(w_want, w - dw, w + dw), -robot.w_max, robot.w_max)
        z = z + (v + 1j * vy[k]) * dt * np.exp(1j * theta)
        theta = theta + w * dt
        Z[:, k], TH[:, k], V[:, k], W[:, k] = z, theta, v, w
    return Rollouts(v=V[:, 0].copy(), vy=np.full(n, vy[0]), w=W[:, 0].copy(), z=Z, t=(np.arange(steps) + 1) * dt,
                    z0=z0, theta0=float(state.theta), dt=float(dt), theta=TH, profile=np.hypot(V, vy[None, :]),
                    tracking=np.ones(n, bool))


def predict_movers(dynamic: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Constant-velocity prediction of the sensed moving obstacles.

    Returns ``(centres (K, H) complex, velocities (K,) complex, radii (K,))``."""
    d = np.asarray(dynamic, dtype=float).reshape(-1, 5)
    pos = d[:, 0] + 1j * d[:, 1]
    vel = d[:, 2] + 1j * d[:, 3]
    return pos[:, None] + vel[:, None] * t[None, :], vel, d[:, 4]


@dataclass
class Step:
    """One control step under evaluation: the rollouts and everything the cost terms share.

    Attributes:
        ctx, robot: the inputs.
        roll: the rollouts.
        static_gap: ``(S, H)`` distance from the robot's edge to static obstacles, m
            (centre distance minus the robot radius; negative = overlap).
        dyn_gap: ``(S, H)`` distance from the robot's edge to the nearest moving obstacle's
            edge at the same predicted time, m (``inf`` without movers).
        movers, mover_vel, mover_r: predicted centres ``(K, H)``, velocities ``(K,)``, radii ``(K,)``.
        free_distance: ``(S,)`` path length before the first predicted collision with a
            static obstacle, m (``inf`` when there is none within the horizon).
        stopping: ``(S,)`` path length the robot needs to stop when it follows the sample
            for the reaction time and then brakes at ``a_max``, m.
        admissible: ``(S,)`` the robot can stop before that collision (hou2024 eq 22:
            ``stopping <= free_distance``).
        mover_contact: ``(S,)`` index of the first rollout point in predicted contact with a
            mover (``H`` = none). Braking does not help against a mover, so instead of eq 22
            such trajectories are discarded, as the papers discard colliding trajectories
            (yuan2021 §3.3); ``mover_free`` is the mask of the others.
        target: current subgoal as a complex number.
        static_hit: ``(S,)`` index of the first rollout point in collision with a static
            obstacle (``H`` = none; see :func:`first_hit`): the robot following the sample
            has to stop before it, so cost terms judge the trajectory up to there.
        aux: scratch space mechanisms use to pass findings to cost terms (e.g. the VO threat).
        mover_range: movers that provably stay farther than this (m, edge to edge) from every
            rollout were left out of ``dyn_gap`` (``assess``'s ``mover_range`` plus margins).
        mover_points: ``(S, H)`` complex positions ``dyn_gap`` was measured from (the rollout,
            or with ``movers_meet_stop`` the rollout held where it meets a static obstacle);
            ``None``: ``roll.z``.
    """

    ctx: LocalContext
    robot: RobotSpec
    roll: Rollouts
    static_gap: np.ndarray
    dyn_gap: np.ndarray
    movers: np.ndarray
    mover_vel: np.ndarray
    mover_r: np.ndarray
    free_distance: np.ndarray
    stopping: np.ndarray
    admissible: np.ndarray
    mover_contact: np.ndarray
    target: complex
    growth: np.ndarray | float = 0.0
    static_hit: np.ndarray | None = None
    aux: dict = field(default_factory=dict)
    mover_range: float = np.inf
    mover_points: np.ndarray | None = None

    @property
    def mover_free(self) -> np.ndarray:
        return self.mover_contact >= self.roll.z.shape[1]

    def stop_index(self) -> np.ndarray:
        """``(S,)`` rollout points each trajectory can be followed for: those before its first
        static collision (``static_hit``; all ``H`` without one)."""
        H = self.roll.z.shape[1]
        return np.full(self.roll.n, H) if self.static_hit is None else np.minimum(self.static_hit, H)

    def held_at_stop(self) -> np.ndarray:
        """``(S, H)`` positions with every point from the first static collision on replaced by
        the last point before it: where the robot following the sample ends up, since it has
        to stop before the obstacle (the start when the very first point collides)."""
        k = self.stop_index()
        z = self.roll.z
        last = np.where(k > 0, z[np.arange(self.roll.n), np.maximum(k - 1, 0)], self.roll.z0)
        return np.where(np.arange(z.shape[1])[None, :] < k[:, None], z, last[:, None])

    def pose_at_stop(self) -> tuple[np.ndarray, np.ndarray]:
        """``(position (S,) complex, heading (S,) rad)`` at the last point before each
        trajectory's first static collision (the trajectory's end without one)."""
        k = self.stop_index()
        roll = self.roll
        rows = np.arange(roll.n)
        z = np.where(k > 0, roll.z[rows, np.maximum(k - 1, 0)], roll.z0)
        if roll.theta is not None:
            heading = np.where(k > 0, roll.theta[rows, np.maximum(k - 1, 0)], roll.theta0)
        else:
            heading = roll.theta0 + roll.w * (k * roll.dt)
        return z, heading

    def sensed_dyn_gap(self) -> np.ndarray:
        """``(S, H)`` edge-to-edge distance (m) from each rollout point to the nearest mover
        disc where the mover is sensed now (``ctx.dynamic``), not where the constant-velocity
        prediction puts it at that point's time: hou2024 eq 28 as printed, whose obstacle
        coordinates ``(x_i, y_i)`` carry no time index. Measured from the same points as
        ``dyn_gap`` (``mover_points``) and over the movers that can come within
        ``mover_range`` of a rollout (``inf`` without one). Kept in ``aux`` for the step."""
        if "sensed_dyn_gap" not in self.aux:
            d = np.asarray(self.ctx.dynamic, dtype=float).reshape(-1, 5)
            z = self.roll.z if self.mover_points is None else self.mover_points
            still = np.broadcast_to((d[:, 0] + 1j * d[:, 1])[:, None], (len(d), len(self.roll.t)))
            keep = relevant_movers(self.roll.z0, still, d[:, 4], self.roll.t, self.roll.max_speed,
                                   self.robot.radius, self.mover_range)
            self.aux["sensed_dyn_gap"] = dynamic_gaps(z, still[keep, :1], d[keep, 4], self.robot.radius)
        return self.aux["sensed_dyn_gap"]

    @property
    def gap(self) -> np.ndarray:
        """``(S, H)`` clearance to any obstacle, static or moving, m; the movers' predicted
        discs are enlarged by ``growth`` ``(H,)`` for the uncertainty of the prediction."""
        return np.minimum(self.static_gap, self.dyn_gap - self.growth)


def dynamic_gaps(z: np.ndarray, movers: np.ndarray, radii: np.ndarray, robot_radius: float) -> np.ndarray:
    """Edge-to-edge distance from each rollout point to the nearest mover at the same time."""
    gap = np.full(z.shape, np.inf)
    buf = np.empty(z.shape)
    for centre, r in zip(movers, radii):  # one pass per obstacle over all samples x horizon
        np.abs(z - centre, out=buf)
        buf -= r
        np.minimum(gap, buf, out=gap)
    gap -= robot_radius
    return gap


def relevant_movers(z0: complex, movers: np.ndarray, radii: np.ndarray, t: np.ndarray, max_speed: float,
                    robot_radius: float, beyond: float) -> np.ndarray:
    """Mask of movers that can come within ``beyond`` metres (edge to edge) of some rollout:
    a rollout point at time ``t`` lies within ``max_speed t`` of the start, so a mover whose
    predicted edge stays farther than that plus ``beyond`` is irrelevant (exact bound)."""
    if len(radii) == 0:
        return np.zeros(0, dtype=bool)
    lower = np.abs(movers - z0) - radii[:, None] - robot_radius - max_speed * t[None, :]
    return lower.min(axis=1) <= beyond


def current_gaps(ctx: LocalContext, robot: RobotSpec) -> tuple[float, float]:
    """Clearance (m, edge to edge) of the robot where it stands: to static obstacles, to movers."""
    z0 = np.array([[ctx.state.x, ctx.state.y]])
    static = float(np.asarray(ctx.static_distance(z0)).ravel()[0]) - robot.radius
    d = np.asarray(ctx.dynamic, dtype=float).reshape(-1, 5)
    moving = float((np.hypot(d[:, 0] - z0[0, 0], d[:, 1] - z0[0, 1]) - d[:, 4]).min()) - robot.radius if len(d) else np.inf
    return static, moving


def static_gradient(ctx: LocalContext, points: np.ndarray, h: float = 0.05) -> np.ndarray:
    """Gradient ``(n,)`` (complex ``d/dx + i d/dy``) of the static distance at the complex
    ``points``, by central differences ``h`` metres wide (well below a grid cell)."""
    pts = np.asarray(points, dtype=complex).ravel()
    probe = np.concatenate([pts + h, pts - h, pts + 1j * h, pts - 1j * h])
    dist = np.asarray(ctx.static_distance(probe.view(np.float64).reshape(-1, 2)), dtype=float).ravel()
    n = len(pts)
    gx = (dist[:n] - dist[n:2 * n]) / (2 * h)  # real divisions: a complex one rounds differently
    gy = (dist[2 * n:3 * n] - dist[3 * n:]) / (2 * h)
    return gx + 1j * gy


def first_hit(hit: np.ndarray) -> np.ndarray:
    """Index of the first ``True`` of each row (the row length when there is none)."""
    return np.where(hit.any(axis=1), np.argmax(hit, axis=1), hit.shape[1])


def assess(ctx: LocalContext, robot: RobotSpec, roll: Rollouts, *, margin: float = 0.0,
           static_margin: float | None = None, reaction: float = 0.0,
           mover_range: float = 3.0, mover_growth: float = 0.0, growth_cap: float = 0.0,
           predict: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
           movers_meet_stop: bool = False, exact_free: bool = False) -> Step:
    """Clearance of every rollout point, the free distance and the admissibility of every sample.

    A rollout point collides when its clearance is below ``margin``; when the robot already
    stands closer than that (``current_gaps``), only points closer than where it stands count,
    so trajectories that lead out of a tight spot stay admissible.

    Args:
        margin: extra clearance, m, below which a point counts as a collision.
        static_margin: the same for static obstacles (``None``: ``margin``).
        reaction: reaction time in the stopping distance (see :func:`_stopping_test`).
        mover_range: movers that provably stay more than this far (edge to edge) from every
            rollout are skipped; cost terms therefore see mover clearances up to this value.
        mover_growth, growth_cap: for the cost terms (``Step.gap``) the predicted movers' discs
            grow by ``mover_growth * (fastest mover's speed) * t`` up to ``growth_cap`` metres:
            a mover may turn or reverse (waypoint movers do), which the constant-velocity
            prediction does not see. The contact test uses the prediction without growth.
        predict: ``(centres (K, H), t) -> centres``: replaces the constant-velocity
            prediction of movers whose motion is known better (a planner's mechanisms).
        movers_meet_stop: judge the movers against where the robot would really be: a rollout
            that meets a static obstacle holds its last free point for the rest of the
            horizon. Otherwise the rollout runs on through the obstacle, and a trajectory
            that would leave the robot stopped in a pocket of clutter on a mover's track
            counts as clear of the mover because its straight continuation is.
        exact_free: the free distance runs on from the last free rollout point to where the
            clearance, interpolated linearly, crosses the margin. Cut at the last free point it
            falls short by up to a step's length, by a different amount from one period to the
            next: a robot that braked on an arc judged able to stop could find the same arc
            judged unable one period later (docs/fidelity/yang2023.md).
    """
    static_gap = np.asarray(ctx.static_distance(roll.xy), dtype=float) - robot.radius
    movers, vel, radii = predict_movers(ctx.dynamic, roll.t)
    if predict is not None:
        movers = predict(movers, roll.t)
    beyond = max(mover_range, margin) + growth_cap
    keep = relevant_movers(roll.z0, movers, radii, roll.t, roll.max_speed, robot.radius, beyond)
    now_static, now_moving = current_gaps(ctx, robot)
    s_margin = margin if static_margin is None else static_margin
    limit = min(s_margin, now_static)
    first = first_hit(static_gap < limit)  # 0 = the point after one step
    z = roll.z
    if movers_meet_stop and (first < z.shape[1]).any():
        held = np.minimum(np.arange(z.shape[1])[None, :], first[:, None] - 1)       # -1: still at z0
        z = np.where(held >= 0, np.take_along_axis(z, np.maximum(held, 0), axis=1), roll.z0)
    dyn_gap = dynamic_gaps(z, movers[keep], radii[keep], robot.radius)
    fastest = float(np.abs(vel[keep]).max(initial=0.0))
    growth = np.minimum(mover_growth * fastest * roll.t, growth_cap) if mover_growth > 0 else 0.0
    free, stopping = _stopping_test(roll, first, robot.a_max, reaction)
    if exact_free:
        free = free + _beyond_last_free(roll, first, static_gap, limit, now_static)
    admissible = stopping <= free + 1e-12
    contact = first_hit(dyn_gap < min(margin, now_moving))
    target = complex(*np.asarray(ctx.subgoal, dtype=float)[:2])
    return Step(ctx, robot, roll, static_gap, dyn_gap, movers, vel, radii, free, stopping, admissible, contact, target,
                growth, first, mover_range=beyond, mover_points=z)


def _beyond_last_free(roll: Rollouts, first: np.ndarray, static_gap: np.ndarray, limit: float,
                      gap_now: float) -> np.ndarray:
    """``(S,)`` path length (m) from each sample's last free rollout point (the robot where
    none is) to where its clearance, linear between that point and the first colliding one,
    falls to ``limit``; 0 for samples that stay free."""
    S, H = static_gap.shape
    hit = first < H
    out = np.zeros(S)
    if not hit.any():
        return out
    rows = np.flatnonzero(hit)
    k = first[rows]
    inside = static_gap[rows, k]
    before = np.where(k > 0, static_gap[rows, np.maximum(k - 1, 0)], gap_now)
    # before >= limit > inside (limit is at most gap_now): the drop is positive
    frac = np.clip((before - limit) / (before - inside), 0.0, 1.0)
    step = (roll.profile[rows, k] if roll.profile is not None else roll.speed[rows]) * roll.dt
    out[rows] = frac * step
    return out


def _stopping_test(roll: Rollouts, first: np.ndarray, decel: float, reaction: float) -> tuple[np.ndarray, np.ndarray]:
    """``(free distance, stopping distance)`` ``(S,)`` of every sample (hou2024 eq 22).

    The free distance is the path length up to the last point before the first static
    collision (``first``, see :func:`first_hit`). At a constant sampled speed ``v`` the
    robot needs ``v t_r + v^2 / (2 a)`` to stop. A ramped rollout changes speed on the way:
    the robot follows the ramp for the reaction time ``t_r`` (its distance and speed are
    read off the rollout, rounded up to whole steps and at least one) and then brakes from
    the speed it has reached. Judging a ramp by its target speed instead would call a robot that brakes
    from 0.45 to 0.25 m/s able to stop within the 0.2 m a 0.25 m/s robot needs, and let it
    drive into a wall it can no longer avoid."""
    H = roll.z.shape[1]
    if roll.profile is None:
        speed = roll.speed
        free = np.where(first < H, first * speed * roll.dt, np.inf)
        return free, stopping_distance(speed, decel, reaction)
    travelled = np.cumsum(roll.profile, axis=1)  # path length after each step
    travelled *= roll.dt
    before = np.take_along_axis(travelled, np.clip(first - 1, 0, H - 1)[:, None], axis=1)[:, 0]
    free = np.where(first >= H, np.inf, np.where(first > 0, before, 0.0))
    # a command is held for at least one step, so the ramp is followed for one step or more
    k = min(H, max(1, int(np.ceil(reaction / roll.dt - 1e-9))))
    s = roll.profile[:, k - 1]
    return free, travelled[:, k - 1] + stopping_distance(s, decel)
