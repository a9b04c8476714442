"""The corridor smoothing QP, written once and handed to OSQP or to cvxpy.

Decision variable: the ``N`` path points, stacked ``z = (x_0..x_{N-1}, y_0..y_{N-1})``
(metres). Objective, the same as the CasADi smoother's
(:mod:`optplan.solvers.nlp.smoothing`)::

    J(z) = sum_i |p_{i+1} - p_i|^2  +  w_smooth * sum_i |p_{i+1} - 2 p_i + p_{i-1}|^2

(squared first differences: a length surrogate that pulls the path taut and
spaces the points evenly; squared second differences: smoothness). It is
:func:`optplan.formulations.paper_programs.smoothing_energy`, written once: OSQP and
cvxpy take it as ``1/2 z' P z`` with ``P`` its exact Hessian (:func:`energy_hessian`,
``2 blkdiag(H, H)``, ``H = D1'D1 + w D2'D2``), and :func:`objective_value` is its
batched view.

Constraints (a :class:`~optplan.solvers.qp.corridor.Corridor`):
``lo <= p_j <= hi`` per point (start, goal and pinned points have ``lo = hi``),
and ``n_{ik} . p >= b_{ik}`` for both ends ``p_i``, ``p_{i+1}`` of each piece ``i``
and each half-plane slot ``k``.

The sparsity pattern depends only on ``(N, K)``, so each backend builds its
problem once per ``(N, K, w_smooth)`` and later calls only change numbers:
OSQP through ``update(l=, u=, Ax=)`` plus ``warm_start``, cvxpy through
Parameters (the problem is DPP, so it is canonicalised once).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...checks import settings_key
from ...errors import ParameterError
from .corridor import Corridor

OSQP_SETTINGS = {
    "verbose": False,
    "eps_abs": 1e-5,
    "eps_rel": 1e-5,
    "rho": 1.0,             # fewer iterations than OSQP's 0.1 on the paper maps (docs/measurements.md)
    "polishing": True,      # an active-set polish makes touching constraints exact to ~1e-10
    "max_iter": 20000,
    "warm_starting": True,
}


@dataclass
class QPSolution:
    """One corridor QP solve: points ``(N, 2)``, objective ``J``, solver status and effort."""

    points: np.ndarray
    objective: float
    status: str
    ok: bool
    iterations: int
    solve_time_s: float
    dual: np.ndarray | None = None


def energy_hessian(N: int, w_smooth: float) -> sp.csc_matrix:
    """``P = 2 blkdiag(H, H)`` (``2N x 2N``, ``z = (x.., y..)``): the Hessian of the smoothing
    energy (:func:`optplan.formulations.paper_programs.smoothing_energy`, its symbolic view)
    with all ``N`` points free; exact, the energy is quadratic (its terms' quadratic view)."""
    import casadi as ca

    from ...formulations.namespaces import Sym
    from ...formulations.paper_programs import smoothing_energy

    energy = smoothing_energy(w_smooth)
    if not energy.quadratic:  # pragma: no cover - the energy's terms are declared quadratic
        raise ParameterError(f"the smoothing energy {energy.name} is not quadratic")
    z = ca.SX.sym("z", 2 * N)
    f = energy.symbolic(Sym(ca.horzcat(z[:N], z[N:]), (N, 2)), None).m
    H = ca.Function("hessian", [z], [ca.hessian(f, z)[0]])(np.zeros(2 * N))   # constant: any point
    P = sp.csc_matrix(H.sparse())
    P.eliminate_zeros()   # a zero weight leaves structural zeros (no entries, as OSQP wants)
    P.sort_indices()
    return P


def objective_value(points: np.ndarray, w_smooth: float) -> float:
    """``J`` of a path (see the module docstring): the smoothing energy's batched view."""
    from ...formulations.paper_programs import smoothing_energy

    P = np.asarray(points, float)
    return float(smoothing_energy(w_smooth).batch(P[None], None)[0])


class OsqpCorridorQP:
    """The corridor QP for a fixed ``(N, K, w_smooth)`` held by one OSQP solver object.

    ``solve(corridor)`` updates the bounds and half-plane values (same sparsity),
    warm-starts and solves. Rows: ``2N`` identity rows (box bounds), then
    ``2 K (N-1)`` half-plane rows ordered by piece, slot, end.
    """

    def __init__(self, N: int, K: int, w_smooth: float, settings: dict | None = None) -> None:
        import osqp

        self.settings = dict(OSQP_SETTINGS if settings is None else settings)
        if N < 2:
            raise ParameterError(f"the corridor QP needs at least 2 points, got {N}")
        self.N, self.K, self.w_smooth = N, K, float(w_smooth)
        self.P = sp.triu(energy_hessian(N, w_smooth), format="csc")
        # half-plane rows: piece i, slot k, end e -> point j = i + e; entries at x_j and y_j
        i, k, e = np.meshgrid(np.arange(N - 1), np.arange(K), np.arange(2), indexing="ij")
        j = (i + e).ravel()
        n_hp = j.size
        rows = np.concatenate([np.arange(2 * N), 2 * N + np.repeat(np.arange(n_hp), 2)])
        cols = np.concatenate([np.arange(2 * N), np.stack([j, N + j], axis=1).ravel()])
        tag = np.arange(1, rows.size + 1, dtype=float)   # to find where each value lands in CSC order
        A = sp.csc_matrix((tag, (rows, cols)), shape=(2 * N + n_hp, 2 * N))
        A.sort_indices()
        self._perm = A.data.astype(np.int64) - 1
        self._n_hp = n_hp
        self._values = np.ones(rows.size)
        A.data = self._values[self._perm]
        self.solver = osqp.OSQP()
        m = A.shape[0]
        self.solver.setup(self.P, np.zeros(2 * N), A, -np.inf * np.ones(m), np.inf * np.ones(m), **self.settings)

    def _data(self, c: Corridor):
        N, K = self.N, self.K
        vals = self._values.copy()
        l = np.concatenate([c.lo[:, 0], c.lo[:, 1], np.full(self._n_hp, -np.inf)])
        u = np.concatenate([c.hi[:, 0], c.hi[:, 1], np.full(self._n_hp, np.inf)])
        if K:
            nrm = np.repeat(c.normals[:, :, None, :], 2, axis=2).reshape(-1, 2)   # piece, slot, end
            off = np.repeat(c.offsets[:, :, None], 2, axis=2).ravel()
            active = np.isfinite(off) & (np.abs(nrm).sum(axis=1) > 0)
            nrm = np.where(active[:, None], nrm, 1.0)   # unused rows keep a nonzero value, free bounds
            vals[2 * N:] = nrm.ravel()
            l[2 * N:] = np.where(active, off, -np.inf)
        return vals[self._perm], l, u

    def solve(self, corridor: Corridor, x0: np.ndarray | None = None, y0: np.ndarray | None = None) -> QPSolution:
        """Solve over ``corridor``; warm start from points ``x0`` (default: the corridor's points)
        and constraint multipliers ``y0`` (default: zero)."""
        import time

        if corridor.n_points != self.N or corridor.k_slots != self.K:
            raise ParameterError(f"corridor has N={corridor.n_points}, K={corridor.k_slots}; "
                                 f"this QP was built for N={self.N}, K={self.K}")
        Ax, l, u = self._data(corridor)
        t = time.perf_counter()
        self.solver.update(Ax=Ax, l=l, u=u)
        X0 = corridor.points if x0 is None else np.asarray(x0, float)
        self.solver.warm_start(x=np.concatenate([X0[:, 0], X0[:, 1]]),
                               y=np.zeros(len(l)) if y0 is None else y0)
        res = self.solver.solve(raise_error=False)
        polished = res.info.status_polish == 1
        if res.info.status_val == 1 and not polished:
            # polishing can fail (degenerate active sets: neighbouring pieces share nearly the
            # same half-plane); then tighten the tolerances and continue from this solution,
            # so the constraints hold to ~1e-8 m, well inside the cushion
            self.solver.update_settings(eps_abs=1e-9, eps_rel=1e-9)
            res2 = self.solver.solve(raise_error=False)
            self.solver.update_settings(eps_abs=self.settings["eps_abs"], eps_rel=self.settings["eps_rel"])
            if res2.info.status_val == 1:
                res, polished = res2, res2.info.status_polish == 1
        dt = time.perf_counter() - t
        status = str(res.info.status) + ("" if polished else " (not polished)")
        ok = res.info.status_val == 1   # OSQP_SOLVED (not "solved inaccurate")
        z = res.x if res.x is not None else np.full(2 * self.N, np.nan)
        X = np.stack([z[:self.N], z[self.N:]], axis=1)
        if ok:  # the box rows are bounds: put points exactly inside them (removes ~1e-10 overshoot)
            X = np.clip(X, corridor.lo, corridor.hi)
        return QPSolution(X, objective_value(X, self.w_smooth) if ok else float("inf"), status, ok,
                          int(res.info.iter), dt, res.y if ok else None)


class CvxpyCorridorQP:
    """The same QP in cvxpy with Parameters (DPP: canonicalised once per ``(N, K, w)``)."""

    def __init__(self, N: int, K: int, w_smooth: float, solver: str = "CLARABEL") -> None:
        import cvxpy as cp

        self.N, self.K, self.w_smooth, self.solver_name = N, K, float(w_smooth), solver
        X = cp.Variable((N, 2))
        self.lo = cp.Parameter((N, 2))
        self.hi = cp.Parameter((N, 2))
        cons = [X >= self.lo, X <= self.hi]
        if K:
            self.nx = cp.Parameter((N - 1, K))
            self.ny = cp.Parameter((N - 1, K))
            self.b = cp.Parameter((N - 1, K))
            ones = np.ones((1, K))
            for ends in (X[:-1], X[1:]):   # both ends of every piece
                cons.append(cp.multiply(self.nx, ends[:, 0:1] @ ones) + cp.multiply(self.ny, ends[:, 1:2] @ ones) >= self.b)
        # vec(X) stacks the columns: z = (x.., y..), the layout of energy_hessian
        J = 0.5 * cp.quad_form(cp.vec(X, order="F"), cp.psd_wrap(energy_hessian(N, w_smooth)))
        self.X = X
        self.problem = cp.Problem(cp.Minimize(J), cons)
        if not self.problem.is_dpp():  # would be re-canonicalised on every solve
            raise RuntimeError("the corridor QP is not DPP; cvxpy would rebuild it on every solve")

    def solve(self, corridor: Corridor) -> QPSolution:
        import time

        import cvxpy as cp

        # infinite bounds are not accepted as parameter values: replace by a far box
        big = 1e6
        self.lo.value = np.maximum(corridor.lo, -big)
        self.hi.value = np.minimum(corridor.hi, big)
        if self.K:
            active = np.isfinite(corridor.offsets)
            self.nx.value = np.where(active, corridor.normals[..., 0], 0.0)
            self.ny.value = np.where(active, corridor.normals[..., 1], 0.0)
            self.b.value = np.where(active, corridor.offsets, -1.0)   # 0 >= -1: an unused slot
        t = time.perf_counter()
        try:
            self.problem.solve(solver=self.solver_name)
        except cp.error.SolverError as exc:
            return QPSolution(corridor.points, float("inf"), f"solver error: {exc}", False, 0, time.perf_counter() - t)
        dt = time.perf_counter() - t
        ok = self.problem.status == cp.OPTIMAL
        X = np.asarray(self.X.value) if ok else corridor.points
        if ok:
            X = np.clip(X, corridor.lo, corridor.hi)
        iters = int(self.problem.solver_stats.num_iters or 0) if self.problem.solver_stats else 0
        return QPSolution(X, objective_value(X, self.w_smooth) if ok else float("inf"), str(self.problem.status), ok,
                          iters, dt)


_PROGRAMS: dict = {}
MAX_CACHED_PROGRAMS = 64   # set-ups are cheap (ms); keep memory bounded in long sessions


def osqp_settings(osqp: dict | None = None) -> dict:
    """The OSQP settings of one call: the module's defaults ``OSQP_SETTINGS`` updated by the
    call's own ``osqp`` settings."""
    if osqp is not None and (not isinstance(osqp, dict) or not all(isinstance(k, str) for k in osqp)):
        raise ParameterError(f"osqp must be a dict of OSQP settings (e.g. {{'max_iter': 2000}}), got {osqp!r}")
    return {**OSQP_SETTINGS, **(osqp or {})}


def corridor_program(N: int, K: int, w_smooth: float, backend: str = "osqp", osqp: dict | None = None):
    """The cached program for ``(N, K, w_smooth)`` and a backend (``"osqp"`` or ``"cvxpy"``).
    The OSQP settings (the defaults updated by ``osqp``) are part of the key, so changing them
    gives a new set-up instead of a stale one (nothing to clear)."""
    if backend not in ("osqp", "cvxpy"):
        raise ParameterError(f"backend must be 'osqp' or 'cvxpy', got {backend!r}")
    merged = osqp_settings(osqp)
    key = (backend, N, K, float(w_smooth), settings_key(merged))
    prog = _PROGRAMS.pop(key, None)   # re-inserted below: the dict's order is least recently used first
    if prog is None:
        prog = OsqpCorridorQP(N, K, w_smooth, merged) if backend == "osqp" else CvxpyCorridorQP(N, K, w_smooth)
        while len(_PROGRAMS) >= MAX_CACHED_PROGRAMS:
            _PROGRAMS.pop(next(iter(_PROGRAMS)))
    _PROGRAMS[key] = prog
    return prog
