"""OSQP and cvxpy on programs with a quadratic objective and corridor constraints.

They take programs whose objective is built only of quadratic terms
(``squared_length``, ``bending``, their non-negative sums) over variables that
decode affinely (``Points``, ``Waypoints``, ``BSpline``, continuous
``ColumnNodes``), and whose only constraint is clearance. Clearance becomes the
safe corridor of the current path (:func:`optplan.solvers.qp.corridor.build_corridor`:
a free box per piece on grids, tangent half-planes in circle worlds), so every
QP solution is collision-free by construction; rounds rebuild the corridor
around the new path until the cost stops falling by ``tol``. They need a
collision-free start (``init``) and stay in its homotopy class. Anything else
is refused with one line naming the term or constraint.
"""
from __future__ import annotations

import time

import numpy as np

from ...checks import integer, mapping, number
from ...errors import ParameterError
from ...formulations.program import Option, ProgramSolver
from .common import INIT_OPTION, result_of, start_vector

OSQP_DEFAULTS = {"verbose": False, "eps_abs": 1e-8, "eps_rel": 1e-8, "polishing": True, "max_iter": 20000}


def quadratic_form(program, variables):
    """``(H, q, c)`` with cost ``0.5 x'Hx + q'x + c`` (exact: the objective is quadratic)."""
    import casadi as ca

    x = ca.SX.sym("x", variables.dim)
    f = program.objective.symbolic(variables.decode_symbolic(x), program.ctx).m
    H, g = ca.hessian(f, x)
    fn = ca.Function("q", [x], [H, g, f])
    Hv, gv, fv = fn(np.zeros(variables.dim))
    return np.asarray(ca.densify(Hv), float), np.asarray(gv, float).reshape(-1), float(fv)


def affine_decode(variables):
    """``(A, b)`` with the flattened path ``[x0, y0, x1, y1, ...] = A x + b``."""
    b = variables.decode(np.zeros((1, variables.dim)))[0]
    cols = variables.decode(np.eye(variables.dim)) - b
    return cols.reshape(variables.dim, -1).T, b.reshape(-1)


class CorridorQPSolver(ProgramSolver):
    capabilities = frozenset({"quadratic", "needs_init"})
    options = {
        "init": INIT_OPTION,
        "rounds": Option(6, integer(1, 100), "corridor rounds at most"),
        "tol": Option(1e-3, number(0.0), "stop when a round lowers the cost by less than this fraction"),
        "max_cells": Option(3, integer(0, 50), "grid boxes grow by at most this many cell lines per side"),
        "k_halfplanes": Option(6, integer(1, 50), "half-planes per piece (circle worlds)"),
        "max_step": Option(None, number(0.0, optional=True, strict_minimum=True),
                           "trust-box half-width in circle worlds, metres (default: 2 cells / 1 m)"),
    }

    def check_program(self, program, variables) -> None:
        obj = program.objective
        if not obj.quadratic:
            bad = [t.name for t in obj.leaves() if not t.quadratic] or [obj.name]
            raise ParameterError(f"{self.name} takes quadratic objectives only; not quadratic: {', '.join(bad)} "
                                 "(use squared_length / bending, or ipopt and slsqp)")
        for c in program.constraints:
            if not c.is_clearance:
                raise ParameterError(f"{self.name} takes clearance constraints only (as a corridor); "
                                     f"{c.name!r} has no convex corridor form (use ipopt or slsqp)")
        if not variables.affine:
            raise ParameterError(f"{self.name} needs variables that decode affinely; {variables.name} does not")

    def run(self, program, **o):
        from ..qp.corridor import build_corridor

        t0 = time.perf_counter()
        variables = program.variables.relaxed()
        self.check_program(program, variables)
        x = start_vector(program, variables, o["init"])
        if x is None:
            raise ParameterError(f"{self.name} needs init= (a collision-free path or result): its corridor is "
                                 "built around it")
        path = variables.decode(x[None])[0]
        cost, _, ok = program.judge(path)
        if not ok:
            return result_of(program, variables, x, self.name, "infeasible_start",
                             f"{self.name} needs a feasible start; the start given is not", 0, t0)
        H, q, _ = quadratic_form(program, variables)
        A_dec, b_dec = affine_decode(variables)
        world, clearance = program.world, program.clearance
        step = o["max_step"] or (2.0 * program.ctx.cell if program.ctx.is_grid else 1.0)
        solves, status, note = 0, "no round", ""
        for _ in range(o["rounds"]):
            corridor = build_corridor(world, path, clearance, k=o["k_halfplanes"], max_cells=o["max_cells"],
                                      max_step=step, split=False)
            if len(corridor.points) != len(path):
                note = "the corridor could not be built on the path's own points"
                break
            A, lo, hi = corridor_rows(corridor, A_dec, b_dec)
            solves += 1
            z, status = self._solve_qp(H, q, A, lo, hi, x, o)
            if z is None:
                note = f"QP round {solves} did not solve ({status})"
                break
            new_path = variables.decode(z[None])[0]
            new_cost, _, new_ok = program.judge(new_path)
            if not new_ok or new_cost > cost:
                note = f"QP round {solves} gave no better feasible path; kept the previous one"
                break
            gain = (cost - new_cost) / max(abs(cost), 1e-12)
            x, path, cost = z, new_path, new_cost
            if gain < o["tol"]:
                break
        return result_of(program, variables, x, self.name, status, note, solves, t0)


def corridor_rows(corridor, A_dec: np.ndarray, b_dec: np.ndarray):
    """Linear rows ``lo <= A x <= hi`` that keep every point in its boxes and both ends of
    every piece on the right side of its half-planes."""
    rows, lo, hi = [A_dec], (corridor.lo.reshape(-1) - b_dec), (corridor.hi.reshape(-1) - b_dec)
    lo_l, hi_l = [lo], [hi]
    N = corridor.n_points
    for i in range(N - 1):
        for kk in range(corridor.k_slots):
            off = corridor.offsets[i, kk]
            nrm = corridor.normals[i, kk]
            if not np.isfinite(off) or not np.any(nrm):
                continue
            for j in (i, i + 1):
                r = nrm[0] * A_dec[2 * j] + nrm[1] * A_dec[2 * j + 1]
                rows.append(r[None])
                lo_l.append(np.array([off - (nrm[0] * b_dec[2 * j] + nrm[1] * b_dec[2 * j + 1])]))
                hi_l.append(np.array([np.inf]))
    A = np.vstack(rows)
    lo, hi = np.concatenate(lo_l), np.concatenate(hi_l)
    keep = np.any(A != 0, axis=1)      # rows of fixed points (start, goal) involve no variable
    return A[keep], lo[keep], hi[keep]


class OsqpSolver(CorridorQPSolver):
    """The corridor QP solved by OSQP."""

    name = "osqp"
    options = {**CorridorQPSolver.options,
               "settings": Option({}, mapping("OSQP settings (e.g. {'eps_abs': 1e-9})"), "OSQP's settings for this call")}

    def _solve_qp(self, H, q, A, lo, hi, x0, o):
        import osqp
        import scipy.sparse as sp

        solver = osqp.OSQP()
        solver.setup(sp.triu(sp.csc_matrix(H), format="csc"), q, sp.csc_matrix(A), lo, hi,
                     **{**OSQP_DEFAULTS, **o["settings"]})
        solver.warm_start(x=x0)
        res = solver.solve(raise_error=False)
        if res.info.status_val not in (1, 2) or res.x is None:   # solved / solved inaccurate
            return None, str(res.info.status)
        return np.asarray(res.x, float), str(res.info.status)


class CvxpySolver(CorridorQPSolver):
    """The same corridor QP stated in cvxpy (any QP solver cvxpy has)."""

    name = "cvxpy"
    options = {**CorridorQPSolver.options,
               "solver": Option(None, lambda k, v: v, "cvxpy solver name (default: CLARABEL when installed)")}

    def _solve_qp(self, H, q, A, lo, hi, x0, o):
        import cvxpy as cp

        z = cp.Variable(len(q))
        cons = []
        fin_lo, fin_hi = np.isfinite(lo), np.isfinite(hi)
        if fin_lo.any():
            cons.append(A[fin_lo] @ z >= lo[fin_lo])
        if fin_hi.any():
            cons.append(A[fin_hi] @ z <= hi[fin_hi])
        prob = cp.Problem(cp.Minimize(0.5 * cp.quad_form(z, cp.psd_wrap(H)) + q @ z), cons)
        solver = o["solver"] or ("CLARABEL" if "CLARABEL" in cp.installed_solvers() else None)
        try:
            # cvxpy's own default choice stalled on the first corridor round of chen2025_20
            # (cost stayed at the start's); Clarabel solves it like OSQP does
            prob.solve(solver=solver) if solver else prob.solve()
        except cp.error.SolverError as exc:
            return None, f"solver error: {exc}"
        if prob.status not in ("optimal", "optimal_inaccurate") or z.value is None:
            return None, str(prob.status)
        return np.asarray(z.value, float), str(prob.status)
