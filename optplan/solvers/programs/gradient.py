"""IPOPT and SLSQP on the program's symbolic view (CasADi gives both exact derivatives).

Both optimise the variables' continuous form (``variables.relaxed()``); terms with
no smooth form are replaced by their documented surrogates, and the result says
which. Clearance constraints use the model of
:mod:`optplan.formulations.clearance_model`: segment-exact distances to circles
and to obstacle corners, samples against walls, with the obstacles each piece
is kept off read from the current path, and (on grids) a cap on segment growth
so the samples stay dense. A start that passed the exact test is never asked
for more than it has (each row's bound widened to include it). The answer is
judged by the exact rule; when it fails, the solve is repeated from where it
ended with the obstacles re-read and a small margin (``attempts`` in all).
"""
from __future__ import annotations

import math
import time

import numpy as np

from ...checks import integer, mapping, number
from ...formulations.clearance_model import active_sets
from ...formulations.program import Option, ProgramSolver
from .common import INIT_OPTION, result_of, start_vector, straight_start

IPOPT_DEFAULTS = {"print_level": 0, "sb": "yes", "mu_strategy": "adaptive", "max_wall_time": 60.0}
FEASIBLE_START_IPOPT = {"bound_push": 1e-6, "bound_frac": 1e-6, "slack_bound_push": 1e-6, "slack_bound_frac": 1e-6}
SEGMENT_GROWTH = 2.0     # grids: a segment may grow to this multiple of the start's longest one
MAX_SAMPLES = 8          # grids: samples per segment at most (longer pieces rely on corner rows and retries)


class GradientSolver(ProgramSolver):
    capabilities = frozenset({"gradient"})
    options = {
        "init": INIT_OPTION,
        "max_iter": Option(500, integer(1), "iteration limit"),
        "tol": Option(1e-6, number(0.0, strict_minimum=True), "convergence tolerance"),
        "per_segment": Option(None, integer(1, 200, optional=True),
                              "clearance samples per segment (default: from the start's segment lengths)"),
        "attempts": Option(3, integer(1, 10), "solves in all when the exact check rejects the answer"),
        "trust_region": Option(0.1, number(0.0, 1.0), "from a feasible start, each variable moves at most this "
                               "share of its range per solve (0: no limit)"),
        "rounds": Option(8, integer(0, 100), "further solves from the last answer while it ends on the trust "
                         "region's edge and improves"),
    }

    @staticmethod
    def _judged(program, variables, x) -> tuple[float, bool]:
        cost, _, ok = program.judge(variables.decode(np.asarray(x, float)[None])[0])
        return cost, ok

    def run(self, program, **o):
        t0 = time.perf_counter()
        variables = program.variables.relaxed()
        x0 = start_vector(program, variables, o["init"])
        if x0 is None:
            x0 = straight_start(program, variables)
        notes = []
        if variables is not program.variables:
            notes.append(f"{self.name} optimised the relaxation of {program.variables.name} "
                         f"({program.variables.relax_note})")
        notes.extend(f"{self.name} used the smooth surrogate of {n}" for n in program.surrogate_notes())
        ctx = program.ctx
        has_clearance = any(c.is_clearance for c in program.constraints)
        x, nfev, status, message = x0, 0, "not run", ""
        start, start_cost, start_ok = x0, *self._judged(program, variables, x0)
        span = np.asarray(variables.upper, float) - np.asarray(variables.lower, float)
        trust = o["trust_region"] * span if o["trust_region"] else None
        failures, moves, shrinks = 0, 0, 0
        k_run = None      # samples per segment: fixed for the run, so later rounds reuse the built solver
        strip = None      # grids, a term reading the distance field: (capacity, radius) of its strip
        reads_field = ctx.is_grid and program.reads_field()
        while failures < o["attempts"] and moves <= o["rounds"]:
            P0 = variables.decode(start[None])[0]
            seg = np.hypot(*np.diff(P0, axis=0).T)
            longest = max(float(seg.max()) * SEGMENT_GROWTH, 1e-3)
            if ctx.is_grid:   # samples closer than half a cell catch every wall between two corners
                k = k_run = k_run or o["per_segment"] or int(np.clip(math.ceil(longest / (0.5 * ctx.cell)), 1,
                                                                     MAX_SAMPLES))
                longest = min(longest, k * 0.5 * ctx.cell)
                margin = 1e-6 * ctx.cell if failures == 0 else 0.02 * ctx.cell * 2 ** (failures - 1)
            else:             # circles are kept off segment by segment, exactly
                k = o["per_segment"] or 1
                margin = 1e-6 * 10 ** failures
            active = active_sets(ctx, P0, k) if has_clearance else None
            if reads_field:
                active = dict(active or {}, path=P0)
                strip = _strip_for(ctx, variables, start, trust if start_ok else None, P0, strip)
            cap = min(longest, MAX_SAMPLES * 0.5 * ctx.cell) if ctx.is_grid and has_clearance else None
            relax = start_ok   # a feasible start is never asked for more margin than it has
            # from a feasible start, move at most ``trust`` per variable: the obstacles each piece
            # is kept off are read off the start, so the model holds only near it
            lo, hi = np.asarray(variables.lower, float), np.asarray(variables.upper, float)
            if relax and trust is not None:
                lo, hi = np.maximum(lo, start - trust), np.minimum(hi, start + trust)
            try:
                x, calls, status = self._solve_nlp(program, variables, start, k, margin, active, cap, o, relax,
                                                   (lo, hi), strip)
            except RuntimeError as exc:   # CasADi reports solver failures as RuntimeError
                message = f"{self.name} failed: {str(exc).splitlines()[0][:160]}"
                x = start
                break
            nfev += calls
            cost, ok = self._judged(program, variables, x)
            if not ok:
                failures += 1
                if not relax:          # no feasible start to go back to: go on from where it ended
                    start = x
                    message = f"attempt {failures} of {o['attempts']} ended infeasible"
                else:                  # keep the feasible start; retry with a margin
                    x = start
                    message = (f"{failures} attempt(s) from the feasible start ended infeasible; "
                               f"{'the start' if not moves else 'the last feasible answer'} is returned")
                continue
            if relax and cost > start_cost:
                # a trust-region step that made things worse is not taken: shrink and retry
                x, shrinks = start, shrinks + 1
                if trust is None or shrinks > 2:
                    message = f"{self.name} found no better feasible point near the start"
                    break
                trust = trust / 4
                continue
            message = "" if failures == 0 else f"feasible after {failures} infeasible attempt(s) (obstacles re-read, margin added)"
            at_edge = trust is not None and relax and bool(np.any(np.abs(x - start) >= 0.999 * trust))
            improved = cost < start_cost - 1e-9 * max(1.0, abs(start_cost))
            start, start_cost, start_ok = x, cost, True
            if not (at_edge and improved):
                break
            moves += 1                 # the step ended on the trust region's edge: go on from there
        return result_of(program, variables, x, self.name, status, message, nfev, t0, notes=notes)

    def _built(self, program, variables, k, active, cap, strip=None):
        """The symbolic problem for these structural choices, built once and kept by the
        program (``program.built_solvers``): obstacle data, margin, the segment cap and the
        distance field's strip are parameters, so later solves with other values reuse it."""
        import casadi as ca

        from ...formulations.clearance_model import active_shapes

        shapes = {k_: v for k_, v in active_shapes(active).items() if k_ != "path"}
        if strip is not None:
            shapes["strip"] = strip
        key = (self.name, variables.name, variables.dim, k, tuple(sorted(shapes.items())), cap is not None,
               id(program.objective), tuple(id(c) for c in program.constraints))
        cache = program.built_solvers
        if key in cache:
            return cache[key]
        # SX is several times faster; only a term reading the grid's distance field (its
        # spline strip, indexed by the path's position) needs MX
        needs_mx = strip is not None
        sym = ca.MX if needs_mx else ca.SX
        x = sym.sym("x", variables.dim)
        f, g, lbg, ubg, p, fill = program.symbolic(variables, x, k, shapes)
        if cap is not None:
            cap_p = sym.sym("cap")
            P = variables.decode_symbolic(x).m
            d = P[1:, :] - P[:-1, :]
            g = ca.vertcat(g, d[:, 0] ** 2 + d[:, 1] ** 2 - cap_p ** 2)
            n = P.shape[0] - 1
            lbg = np.concatenate([lbg, np.full(n, -np.inf)])
            ubg = np.concatenate([ubg, np.zeros(n)])
            p = ca.vertcat(p, cap_p)
        built = {"x": x, "p": p, "f": f, "g": g, "lbg": lbg, "ubg": ubg, "fill": fill, "cap": cap is not None,
                 "g_of": ca.Function("g_of", [x, p], [g]), "solvers": {}}
        cache[key] = built
        return built

    def _problem(self, program, variables, k, margin, active, cap, x0, relax, strip=None):
        """The built problem and this solve's numbers: ``(built, p values, lbg, ubg)``."""
        built = self._built(program, variables, k, active, cap, strip)
        pv = built["fill"](margin, active or {})
        if built["cap"]:
            pv = np.concatenate([pv, [cap]])
        lbg, ubg = built["lbg"], built["ubg"]
        if relax and built["g"].shape[0]:
            # the start passed the exact test: widen each row's bounds to include it, so the NLP
            # starts feasible and the margin only binds where the start keeps it already
            g0 = np.asarray(built["g_of"](x0, pv), float).reshape(-1)
            lbg, ubg = np.minimum(lbg, g0), np.maximum(ubg, g0)
        return built, pv, lbg, ubg


def _strip_for(ctx, variables, x0, trust, P0, strip):
    """``(capacity, radius)`` of the distance-field strip a solve from ``x0`` reads: the
    radius is fixed for the run at :data:`STRIP_CELLS` cells plus the farthest a decoded
    point moves when every variable moves by the trust region (the whole map without
    one); the capacity (blocks, a power of two so similar starts share a built solver)
    grows when a later start needs more."""
    from ...formulations.clearance_model import STRIP_CELLS, field_strip

    if strip is None:
        if trust is None:
            xmin, ymin, xmax, ymax = ctx.world.bounds
            radius = float(np.hypot(xmax - xmin, ymax - ymin))
        else:
            lo = np.clip(x0 - trust, variables.lower, variables.upper)
            hi = np.clip(x0 + trust, variables.lower, variables.upper)
            moved = np.abs(variables.decode(np.stack([lo, hi])) - P0[None]).max()
            radius = STRIP_CELLS * ctx.cell + float(moved)
        cap = 0
    else:
        cap, radius = strip
    blocks = field_strip(ctx, P0, radius)[1]
    if blocks > cap:
        cap = 1 << max(blocks - 1, 0).bit_length()
    return cap, radius


class IpoptSolver(GradientSolver):
    """CasADi + IPOPT (interior point, sparse exact Hessians)."""

    name = "ipopt"
    options = {**GradientSolver.options,
               "ipopt": Option({}, mapping("IPOPT options (e.g. {'mu_strategy': 'monotone'})"),
                               "IPOPT's own options for this call")}

    def _solve_nlp(self, program, variables, x0, k, margin, active, cap, o, relax, box, strip=None):
        import casadi as ca

        built, pv, lbg, ubg = self._problem(program, variables, k, margin, active, cap, x0, relax, strip)
        # from a start the exact test accepted, stay near it: IPOPT's default pushes every
        # variable and slack 1 % into the interior, which leaves the feasible start (the
        # rows it holds exactly) and often ends in restoration or a worse local minimum
        warm = FEASIBLE_START_IPOPT if relax else {}
        opts = {**IPOPT_DEFAULTS, **warm, "max_iter": o["max_iter"], "tol": o["tol"], **o["ipopt"]}
        okey = repr(sorted(opts.items()))
        solver = built["solvers"].get(okey)
        if solver is None:   # IPOPT options are fixed per instance: one instance per option set
            nlp = {"x": built["x"], "p": built["p"], "f": built["f"], "g": built["g"]}
            solver = built["solvers"][okey] = ca.nlpsol("program", "ipopt", nlp, {"print_time": False, "ipopt": opts})
        sol = solver(x0=x0, p=pv, lbx=box[0], ubx=box[1], lbg=lbg, ubg=ubg)
        st = solver.stats()
        xs = np.asarray(sol["x"], float).reshape(-1)
        if not np.all(np.isfinite(xs)):
            raise RuntimeError(f"IPOPT returned non-finite values ({st.get('return_status')})")
        return xs, int(st.get("n_call_nlp_f", 0)), str(st.get("return_status", ""))


class SlsqpSolver(GradientSolver):
    """SciPy's SLSQP (dense sequential least squares) with CasADi derivatives."""

    name = "slsqp"
    options = {**GradientSolver.options, "max_iter": Option(200, integer(1), "iteration limit")}

    def _solve_nlp(self, program, variables, x0, k, margin, active, cap, o, relax, box, strip=None):
        import casadi as ca
        from scipy.optimize import Bounds, minimize

        built, pv, lbg, ubg = self._problem(program, variables, k, margin, active, cap, x0, relax, strip)
        fns = built["solvers"].get("slsqp")
        if fns is None:
            x, p, f, g = built["x"], built["p"], built["f"], built["g"]
            fns = built["solvers"]["slsqp"] = (ca.Function("f", [x, p], [f, ca.gradient(f, x)]),
                                               ca.Function("g", [x, p], [g, ca.jacobian(g, x)]))
        F, G = fns
        lo_rows, hi_rows = np.isfinite(lbg), np.isfinite(ubg)
        count = {"f": 0}

        def fun(z):
            count["f"] += 1
            v, gr = F(z, pv)
            return float(v), np.asarray(gr, float).reshape(-1)

        def cons(z):
            v = np.asarray(G(z, pv)[0], float).reshape(-1)
            return np.concatenate([v[lo_rows] - lbg[lo_rows], ubg[hi_rows] - v[hi_rows]])

        def cons_jac(z):
            J = np.asarray(ca.densify(G(z, pv)[1]), float)
            return np.vstack([J[lo_rows], -J[hi_rows]])

        constraints = [{"type": "ineq", "fun": cons, "jac": cons_jac}] if (lo_rows.any() or hi_rows.any()) else []
        res = minimize(fun, x0, jac=True, method="SLSQP", bounds=Bounds(*box),
                       constraints=constraints, options={"maxiter": o["max_iter"], "ftol": o["tol"]})
        return np.asarray(res.x, float), count["f"], str(res.message)
