"""Path smoothing as a nonlinear program (CasADi + IPOPT).

Variables: the interior points of the seed path resampled to ``N`` points by arc
length (start and goal are parameters, so they stay exactly fixed and cost no
equality constraints); the map box enters as simple variable bounds, which
IPOPT treats more cheaply than general constraints. Objective: the smoothing program's energy (``op.smoothing_program``,
:func:`optplan.formulations.paper_programs.smoothing_energy`, read through its
symbolic view) ``J = sum |p_{i+1} - p_i|^2 + w * sum |p_{i+1} - 2 p_i + p_{i-1}|^2``
(squared segment lengths pull the path taut and spread the points evenly; the
second differences smooth it). Constraints: clearance of at least ``margin`` at every
interior point and every segment midpoint.

* Circle worlds: each query point keeps the analytic squared distance to its
  ``K`` nearest circles above ``(R + margin)^2``. Which circles those are is a
  parameter, so the NLP is built once per ``(N, K, w)`` directly in SX (no
  Opti layer, nothing to expand) and an outer loop reassigns neighbours and
  re-solves, warm-started, while the exact check finds a violation.
* Grid maps: the signed distance field (``optplan.world.fields``) becomes a CasADi
  cubic B-spline (:func:`optplan.world.fields.distance_spline`: the function CasADi's
  ``interpolant('bspline')`` makes of it, fitted in time linear in the map, read as
  4 x 4 indexed coefficients per point so that neither the NLP nor its derivatives grow
  with the map), built once per map and cached (MX graph, not expanded). The spline only approximates the field near corners, so ``margin``
  carries a small cushion that is raised when the exact check fails.

Warm starts: every successful result carries a :class:`WarmStart` (points,
IPOPT's bound and constraint multipliers, the neighbour assignment). Passing it
to the next :func:`smooth_path` call of the same size starts IPOPT from that
primal-dual point with ``warm_start_init_point`` and a small barrier parameter,
which is what a replanning loop needs (the start moves a little, the rest of
the problem stays).

On grids the validated NLP solution is finally polished by the convex corridor
smoother (:mod:`optplan.solvers.qp`), which works on the exact cell geometry and
so removes the cushion the sampled constraints need (see ``polish``).

Status discipline: start and goal clearance are checked first; every solution
goes through ``validate_path``; a failed solve or an invalid result is retried
once with twice the points and a larger cushion; after that the seed comes back
unchanged with the reason (never a colliding path).
"""
from __future__ import annotations

import time
import weakref

import numpy as np

from ...checks import settings_key
from ...errors import ParameterError
from ...world.geometry import validate_path
from ..smoother import SmoothResult, WarmStart, check_seed_ends, default_points, resample

IPOPT_OPTIONS = {
    "print_level": 0,
    "sb": "yes",
    # adaptive mu: fewer iterations than monotone from a cold start; limited-memory Hessians
    # stall (benchmarks/refine_solvers.py; docs/measurements.md)
    "mu_strategy": "adaptive",
    "tol": 1e-6,
    "max_iter": 300,
}
# grids: no segment may grow beyond this multiple of the seed's point spacing. Without
# the cap IPOPT sometimes stretches one segment across a corner the samples cannot see
# (docs/measurements.md)
SEGMENT_STRETCH = 1.5
# from a previous primal-dual solution: keep the point where it is (tiny bound pushes)
# and start with a small barrier parameter instead of re-centring
IPOPT_WARM_OPTIONS = {
    **IPOPT_OPTIONS,
    "mu_strategy": "monotone",
    "warm_start_init_point": "yes",
    "mu_init": 1e-6,
    "warm_start_bound_push": 1e-9,
    "warm_start_bound_frac": 1e-9,
    "warm_start_slack_bound_push": 1e-9,
    "warm_start_slack_bound_frac": 1e-9,
    "warm_start_mult_bound_push": 1e-9,
}


def smoothing_objective(points: np.ndarray, w_smooth: float) -> float:
    """``J`` of a path: the smoothing program's objective
    (:func:`optplan.formulations.paper_programs.smoothing_energy`), batched view."""
    from ...formulations.paper_programs import smoothing_energy

    P = np.asarray(points, float)
    return float(smoothing_energy(w_smooth).batch(P[None], None)[0])


# --------------------------------------------------------------------- builders
class _BuiltNlps:
    """The smoother's own store of built NLPs (nothing is kept on the worlds): circle-world
    NLPs by shape, grid NLPs per map and dropped with the map. The IPOPT options in force are
    part of every key, so a caller that changes ``IPOPT_OPTIONS`` gets new instances and never
    has to clear anything."""

    def __init__(self) -> None:
        self.shared: dict = {}
        self.per_world: dict[int, tuple[weakref.ref, dict]] = {}

    @staticmethod
    def options_key(options: tuple[dict, dict]) -> tuple:
        return tuple(settings_key(o) for o in options)

    def of(self, world) -> dict:
        """The NLPs built for ``world`` (a dict forgotten when the world is collected)."""
        entry = self.per_world.get(id(world))
        if entry is None or entry[0]() is not world:
            entry = self.per_world[id(world)] = (weakref.ref(world), {})
            weakref.finalize(world, self.per_world.pop, id(world), None)
        return entry[1]

    def clear(self, *worlds) -> None:
        self.shared.clear()
        for w in worlds:
            self.per_world.pop(id(w), None)


_BUILT = _BuiltNlps()


def ipopt_options(ipopt: dict | None = None) -> tuple[dict, dict]:
    """The cold- and warm-start IPOPT options of one call: the module's defaults
    (``IPOPT_OPTIONS``, ``IPOPT_WARM_OPTIONS``) updated by the call's own ``ipopt`` settings."""
    if ipopt is not None and (not isinstance(ipopt, dict) or not all(isinstance(k, str) for k in ipopt)):
        raise ParameterError(f"ipopt must be a dict of IPOPT options (e.g. {{'max_iter': 100}}), got {ipopt!r}")
    extra = dict(ipopt or {})
    return {**IPOPT_OPTIONS, **extra}, {**IPOPT_WARM_OPTIONS, **extra}


def _path_expressions(ca, z, ends, N: int, w_smooth: float, per_segment: int = 1):
    """Objective and query points of the path ``ends[0:2], interior z, ends[2:4]``
    with ``z = (x_1..x_{N-2}, y_1..y_{N-2})``: the interior points, then
    ``per_segment`` evenly spaced points inside every segment (1: the midpoints)."""
    from ...formulations.namespaces import Sym
    from ...formulations.paper_programs import smoothing_energy

    n = N - 2
    xs = ca.vertcat(ends[0], z[:n], ends[2])
    ys = ca.vertcat(ends[1], z[n:], ends[3])
    # the energy is the smoothing program's objective, read symbolically (one formulation)
    J = smoothing_energy(w_smooth).symbolic(Sym(ca.horzcat(xs, ys), (N, 2)), None).m
    fr = [(j + 1) / (per_segment + 1) for j in range(per_segment)]
    qx = ca.vertcat(xs[1:-1], *[(1 - f) * xs[:-1] + f * xs[1:] for f in fr])
    qy = ca.vertcat(ys[1:-1], *[(1 - f) * ys[:-1] + f * ys[1:] for f in fr])
    seg2 = (xs[1:] - xs[:-1]) ** 2 + (ys[1:] - ys[:-1]) ** 2
    return J, qx, qy, seg2


class _TwoSolvers(dict):
    """A cold-start (``"cold"``) and a warm-start (``"warm"``) IPOPT instance of the same NLP
    (options are fixed per instance), each created on first use: building one takes time
    that grows with the NLP's parameter vector, and many callers never warm-start."""

    def __init__(self, name: str, nlp: dict, options: tuple[dict, dict], **entries) -> None:
        super().__init__(entries)
        self._name, self._nlp, self._options = name, nlp, options

    def __missing__(self, which: str):
        if which not in ("cold", "warm"):
            raise KeyError(which)
        import casadi as ca

        opts = self._options[0] if which == "cold" else self._options[1]
        name = self._name if which == "cold" else self._name + "_warm"
        solver = self[which] = ca.nlpsol(name, "ipopt", self._nlp, {"print_time": False, "ipopt": dict(opts)})
        return solver


def circle_nlp(N: int, K: int, w_smooth: float, ipopt: dict | None = None) -> dict:
    """NLP for circle worlds, built once per ``(N, K, w)`` in SX.

    Parameters ``p = (ends (4), centre x (M*K), centre y (M*K), grown radius (M*K))``
    with ``M = 2N - 3`` query points, column-major ``(M, K)`` blocks.
    """
    options = ipopt_options(ipopt)
    key = ("circles", N, K, float(w_smooth), _BUILT.options_key(options))
    if key not in _BUILT.shared:
        import casadi as ca

        M = 2 * N - 3
        z = ca.SX.sym("z", 2 * (N - 2))
        p = ca.SX.sym("p", 4 + 3 * M * K)
        J, qx, qy, _ = _path_expressions(ca, z, p[:4], N, w_smooth)
        cx = ca.reshape(p[4:4 + M * K], M, K)
        cy = ca.reshape(p[4 + M * K:4 + 2 * M * K], M, K)
        R = ca.reshape(p[4 + 2 * M * K:], M, K)
        g = ca.vertcat(*[(qx - cx[:, k]) ** 2 + (qy - cy[:, k]) ** 2 - R[:, k] ** 2 for k in range(K)])
        _BUILT.shared[key] = _TwoSolvers("smooth_circles", {"x": z, "p": p, "f": J, "g": g}, options, key=key)
    return _BUILT.shared[key]


# grids: the distance spline is handed to the NLP for the cells within this many cells of
# the seed (DistanceSpline.strip); farther away it reads as free. A local smoother moves
# points along the path, not that far across it
STRIP_CELLS = 6.0


def grid_nlp(grid, N: int, w_smooth: float, per_segment: int = 1, subdiv: int = 4, blocks: int = 1,
             ipopt: dict | None = None) -> dict:
    """NLP for a grid map, built once per ``(map, N, w, per_segment, strip capacity)``:
    parameters ``p = (ends (4), margin, longest segment, strip)``; clearance constraints at
    the interior points and at ``per_segment`` points inside each segment, and every
    segment at most the given length (so the samples stay as close as the cushion
    assumes). ``blocks``: the strip's capacity (:meth:`DistanceSpline.strip`), rounded up
    to a power of two so that seeds of similar length share one NLP."""
    cap = 1 << max(int(blocks) - 1, 0).bit_length()
    options = ipopt_options(ipopt)
    key = ("grid", N, float(w_smooth), per_segment, subdiv, cap, _BUILT.options_key(options))
    built = _BUILT.of(grid)
    cached = built.get(key)
    if cached is None:
        import casadi as ca

        from ...world.fields import TILE, distance_spline

        spline = distance_spline(grid, subdiv)
        nty, ntx = spline.tiles
        z = ca.MX.sym("z", 2 * (N - 2))
        p = ca.MX.sym("p", 6 + nty * ntx + cap * (TILE + 3) ** 2)
        J, qx, qy, seg2 = _path_expressions(ca, z, p[:4], N, w_smooth, per_segment)
        g = spline.symbolic(qx, qy, p[6:]) - p[4]
        if SEGMENT_STRETCH is not None:
            g = ca.vertcat(g, p[5] ** 2 - seg2)
        cached = built[key] = _TwoSolvers("smooth_grid", {"x": z, "p": p, "f": J, "g": g}, options,
                                                key=("grid", id(grid)) + key[1:], blocks=cap)
    return cached


def clear_solver_cache(*worlds) -> None:
    """Forget built IPOPT instances to free memory: the circle-world ones, and the grid ones
    of each of ``worlds`` (never needed for correctness: the options are part of the key)."""
    _BUILT.clear(*worlds)


# ------------------------------------------------------------------------ solve
def nearest_circles(world, Q: np.ndarray, K: int) -> np.ndarray:
    """Indices ``(len(Q), K)`` of the ``K`` circles whose grown edge is nearest to each point."""
    d = np.hypot(Q[:, None, 0] - world.circles[None, :, 0], Q[:, None, 1] - world.circles[None, :, 1]) - world.radii
    return np.argsort(d, axis=1)[:, :K]


def _query_points(X: np.ndarray) -> np.ndarray:
    return np.vstack([X[1:-1], (X[1:] + X[:-1]) / 2])


def _remap_multipliers(lam_g: np.ndarray, old: np.ndarray, new: np.ndarray) -> np.ndarray:
    """Carry constraint multipliers over a neighbour reassignment: a (point, circle)
    pair that stays keeps its multiplier, a new pair starts at zero."""
    M, K = new.shape
    lam = lam_g.reshape(K, M).T                       # g is stacked slot by slot
    match = new[:, :, None] == old[:, None, :]
    return (match * lam[:, None, :]).sum(axis=2).T.ravel()


def _unpack(z: np.ndarray, ends: np.ndarray) -> np.ndarray:
    n = len(z) // 2
    return np.vstack([ends[0], np.stack([z[:n], z[n:]], axis=1), ends[1]])


def _pack(X: np.ndarray) -> np.ndarray:
    return np.concatenate([X[1:-1, 0], X[1:-1, 1]])


class _Solve:
    """Runs one IPOPT instance and keeps count of time, iterations and calls."""

    def __init__(self) -> None:
        self.iterations = 0
        self.calls = 0

    def __call__(self, solver, **args):
        sol = solver(**args)
        st = solver.stats()
        self.iterations += int(st.get("iter_count", 0))
        self.calls += 1
        if not st.get("success", False):
            raise RuntimeError(f"IPOPT: {st.get('return_status', 'failed')}")
        return sol


def _box_bounds(world, N: int, clearance: float):
    xmin, ymin, xmax, ymax = world.bounds
    n = N - 2
    lbx = np.concatenate([np.full(n, xmin + clearance), np.full(n, ymin + clearance)])
    ubx = np.concatenate([np.full(n, xmax - clearance), np.full(n, ymax - clearance)])
    return lbx, ubx


def _solve_circles(world, X0, clearance, cushion, w_smooth, K, run, warm: WarmStart | None, max_rounds=6,
                   ipopt: dict | None = None):
    N = len(X0)
    ends = np.stack([X0[0], X0[-1]])
    if len(world.circles) == 0:
        return resample(ends, N), None, "no obstacles"
    K = min(K, len(world.circles))
    nlp = circle_nlp(N, K, w_smooth, ipopt)
    lbx, ubx = _box_bounds(world, N, clearance)
    X = X0
    lam_x = lam_g = idx = None
    if warm is not None and warm.key == nlp["key"]:
        X = np.vstack([ends[0], warm.points[1:-1], ends[1]])
        lam_x, lam_g, idx = warm.lam_x, warm.lam_g, warm.neighbours
    for _ in range(max_rounds):
        new_idx = nearest_circles(world, _query_points(X), K)
        if lam_g is not None and idx is not None:
            lam_g = _remap_multipliers(lam_g, idx, new_idx)
        idx = new_idx
        p = np.concatenate([ends.ravel(), world.circles[idx, 0].ravel(order="F"), world.circles[idx, 1].ravel(order="F"),
                            (world.radii[idx] + clearance + cushion).ravel(order="F")])
        args = dict(x0=_pack(X), p=p, lbx=lbx, ubx=ubx, lbg=0.0, ubg=np.inf)
        if lam_g is not None:
            sol = run(nlp["warm"], lam_x0=lam_x, lam_g0=lam_g, **args)
        else:
            sol = run(nlp["cold"], **args)
        X = _unpack(np.asarray(sol["x"]).ravel(), ends)
        lam_x, lam_g = np.asarray(sol["lam_x"]).ravel(), np.asarray(sol["lam_g"]).ravel()
        if validate_path(world, X, clearance):
            return X, WarmStart(X, lam_x, lam_g, idx, nlp["key"]), "ok"
    return X, None, "neighbour reassignment did not settle"


def _solve_grid(world, X0, clearance, cushion, w_smooth, per_segment, max_segment, run, warm: WarmStart | None,
                ipopt: dict | None = None):
    N = len(X0)
    ends = np.stack([X0[0], X0[-1]])
    from ...world.fields import distance_spline

    # the strip holds the seed and the warm start's points, whichever the solve starts from
    near = X0 if warm is None else np.vstack([X0, warm.points])
    radius = STRIP_CELLS * world.resolution
    spline = distance_spline(world)
    _, blocks = spline.strip(near, radius)
    nlp = grid_nlp(world, N, w_smooth, per_segment, blocks=blocks, ipopt=ipopt)
    strip, _ = spline.strip(near, radius, nlp["blocks"])
    lbx, ubx = _box_bounds(world, N, 0.0)
    args = dict(p=np.concatenate([ends.ravel(), [clearance + cushion, max_segment], strip]), lbx=lbx, ubx=ubx,
                lbg=0.0, ubg=np.inf)
    if warm is not None and warm.key == nlp["key"]:
        X = np.vstack([ends[0], warm.points[1:-1], ends[1]])
        sol = run(nlp["warm"], x0=_pack(X), lam_x0=warm.lam_x, lam_g0=warm.lam_g, **args)
    else:
        sol = run(nlp["cold"], x0=_pack(X0), **args)
    X = _unpack(np.asarray(sol["x"]).ravel(), ends)
    return X, WarmStart(X, np.asarray(sol["lam_x"]).ravel(), np.asarray(sol["lam_g"]).ravel(), None, nlp["key"]), "ok"


def _polish(world, X: np.ndarray, clearance: float, w_smooth: float) -> tuple[np.ndarray, str]:
    """The QP corridor pass from a valid NLP solution; the NLP solution stays if it fails."""
    from ..qp import smooth_path_qp

    q = smooth_path_qp(world, X, clearance, n_points=len(X), w_smooth=w_smooth)
    if q.success:
        return q.path, ""
    return X, f"QP polish skipped ({q.message})"


def smooth_path(world, seed_path, clearance: float = 0.0, n_points: int | None = None, w_smooth: float = 0.5,
                k_nearest: int = 2, cushion: float | None = None, grid_samples: int = 1,
                warm_start: "WarmStart | SmoothResult | None" = None, polish: bool | None = None,
                ipopt: dict | None = None) -> SmoothResult:
    """Smooth and shorten ``seed_path`` under clearance constraints with IPOPT.

    Args:
        world: GridMap or CircleWorld.
        seed_path: ``(M, 2)`` polyline in metres (start first, goal last).
        clearance: required distance to obstacles, metres.
        n_points: resampled points (default: about 4 per cell or per 0.25 m, 20-100).
        w_smooth: weight of the squared second differences.
        k_nearest: circles per point in the constraints (circle worlds); 2 needs the
            fewest IPOPT iterations (docs/measurements.md), and the outer loop adds rounds
            when a path nears a third circle.
        cushion: extra margin over ``clearance`` at the sampled points. Constraints
            hold at sample points ``h`` apart, so a straight piece between two
            samples can come closer to an obstacle than either sample: by up to ``h/2``
            at a grid corner (distance is 1-Lipschitz) and ``h^2 / (8 R)`` at a circle
            of radius ``R`` (sagitta). The default cushion covers that, so the exact
            check passes on the first try.
        grid_samples: constrained points inside each segment on grids (the cushion
            shrinks with the spacing; more samples cost constraint evaluations, not
            variables); 1 and 2 give the same gaps with the polish on, 1 at half the
            cost (docs/measurements.md).
        warm_start: a previous result (or its ``.warm``) of a solve with the same
            number of points: IPOPT starts from its points and multipliers (the new
            seed's start and goal replace the old ends). Ignored when the sizes differ.
        polish: after a valid NLP solution, run the QP corridor smoother
            (:func:`optplan.solvers.qp.smooth_path_qp`) from it. The NLP keeps the
            sampling cushion away from every corner; the corridor pass works on the
            exact geometry and removes it (docs/measurements.md). Default: on for grids,
            off for circle worlds (there the cushion is ~1e-3 m).
        ipopt: IPOPT options of this call (e.g. ``{"max_iter": 100}``), over the module's
            defaults ``IPOPT_OPTIONS``; solvers built with other options are kept apart.
            Through ``op.plan``: ``refine_options={"ipopt": {...}}``.

    Returns:
        SmoothResult; ``success`` only when the result passed ``validate_path``.
    """
    t0 = time.perf_counter()
    ipopt_options(ipopt)   # a bad option set is refused before any work
    P, refused = check_seed_ends(world, seed_path, clearance)
    if refused is not None:
        return refused
    warm = warm_start.warm if isinstance(warm_start, SmoothResult) else warm_start
    if warm is not None and not isinstance(warm, WarmStart):
        raise ParameterError(f"warm_start must be a SmoothResult or WarmStart, got {type(warm_start).__name__}")
    is_grid = world.is_grid
    res = world.resolution if is_grid else 1.0
    if n_points is None:
        N = len(warm.points) if warm is not None else default_points(P, 0.25 * res)
    else:
        N = int(n_points)
        if N < 3:
            raise ParameterError(f"n_points must be at least 3, got {n_points}")
    if cushion is not None:
        base = cushion
    else:
        L = float(np.hypot(*np.diff(P, axis=0).T).sum())
        seg = L / (N - 1)
        r_min = float(world.radii.min()) if not is_grid and len(world.circles) else 1.0
        # spacing of the constrained samples: grid_samples per segment of the seed's
        # spacing (grids; segments are capped at SEGMENT_STRETCH x that), or 1 midpoint
        # per segment (circles)
        base = (0.55 * seg / (grid_samples + 1) if is_grid
                else (seg / 2) ** 2 / (8 * r_min) + 1e-6)
    reasons = []
    run = _Solve()
    for attempt in range(2):
        n = N if attempt == 0 else min(2 * N, 200)
        cush = base if attempt == 0 else 5 * base + (0.05 * res if is_grid else 1e-3)
        X0 = resample(P, n)
        ws = warm if attempt == 0 else None
        try:
            if is_grid:
                L = float(np.hypot(*np.diff(P, axis=0).T).sum())
                X, ws_out, note = _solve_grid(world, X0, clearance, cush, w_smooth, grid_samples,
                                              (SEGMENT_STRETCH or 1.0) * L / (n - 1), run, ws, ipopt=ipopt)
            else:
                X, ws_out, note = _solve_circles(world, X0, clearance, cush, w_smooth, k_nearest, run, ws,
                                                 ipopt=ipopt)
        except RuntimeError as exc:  # IPOPT failures surface as RuntimeError
            reasons.append(f"attempt {attempt + 1}: IPOPT failed ({str(exc).splitlines()[0][:120]})")
            continue
        check = validate_path(world, X, clearance)
        if check:
            msg = "" if attempt == 0 else f"succeeded on retry ({reasons[0]})"
            if polish if polish is not None else is_grid:
                X, note = _polish(world, X, clearance, w_smooth)
                msg = "; ".join(m for m in (msg, note) if m)
            return SmoothResult(X, True, msg, time.perf_counter() - t0, run.iterations, smoothing_objective(X, w_smooth),
                                run.calls, ws_out)
        reasons.append(f"attempt {attempt + 1}: result invalid ({check.reason}; {note})")
    return SmoothResult(P, False, "; ".join(reasons), time.perf_counter() - t0, run.iterations,
                        smoothing_objective(P, w_smooth), run.calls)
