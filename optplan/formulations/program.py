"""Path programs: one planning problem, written once, for every solver.

A :class:`PathProgram` holds decision variables (:mod:`.variables`), an objective
built from terms (:mod:`.expressions`) and constraints. It offers the views the
solvers need and nothing solver-specific:

* :meth:`PathProgram.population` — ``(cost, violation)`` of a population
  ``X (n, d)``, batched numpy (the swarms' view);
* :meth:`PathProgram.symbolic` — the objective and constraint rows as CasADi
  expressions of one variable column (the gradient solvers' view);
* :meth:`PathProgram.evaluate` — cost and per-constraint violations of one path,
  the number every solver and every stage of a chain is judged by; ``feasible``
  is the exact verdict.

Solvers implement :class:`ProgramSolver` and register themselves by name
(:func:`register_solver`; the built-in ones live in :mod:`optplan.solvers.programs`),
so this layer never imports a solver. ``op.PathProgram`` is this class with the
built-in solvers registered.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from ..errors import ParameterError, UnknownAlgorithmError, named_with_hints
from ..world.queries import check_start_goal
from .expressions import Constraint, Expr, ProgramContext
from .variables import Variables, Waypoints, as_variables


# an acceleration must reproduce the program's own view to this relative tolerance (the
# summation order of the terms may differ: measured 2e-16 for the segment tables)
ACCELERATION_RTOL = 1e-9


@dataclass(frozen=True)
class Option:
    """One solver option: its default, a checker returning the clean value, and a line of doc."""

    default: Any
    check: Callable[[str, Any], Any]
    doc: str


class ProgramSolver:
    """A solver of path programs. Subclasses set ``name``, ``options`` and ``capabilities``
    and implement :meth:`run`; :meth:`solve` checks the options first (one place)."""

    name = "solver"
    options: dict[str, Option] = {}
    # "stochastic" (takes seed), "gradient" (symbolic view), "quadratic" (QP), "needs_init", "chain"
    capabilities: frozenset = frozenset()

    def __init__(self, **settings) -> None:
        self.settings = self.check_options(settings)

    def check_options(self, given: dict) -> dict:
        """The given options checked and cleaned; an unknown one is a ParameterError naming
        the solver and its options."""
        known = self.all_options()
        unknown = sorted(set(given) - set(known))
        if unknown:
            raise ParameterError(f"{self.name} has no option {named_with_hints(unknown, known)}; its options are "
                                 f"{', '.join(sorted(known)) or 'none'} (op.show_options({self.name!r}) lists them)")
        return {k: known[k].check(k, v) for k, v in given.items()}

    def all_options(self) -> dict[str, Option]:
        return dict(self.options)

    def show_options(self) -> str:
        """One line per option: name, default and meaning."""
        return "\n".join(f"{k} = {o.default!r}: {o.doc}" for k, o in sorted(self.all_options().items()))

    def solve(self, program: "PathProgram", **options):
        opts = {k: o.default for k, o in self.all_options().items()}
        opts.update(self.settings)
        opts.update(self.check_options(options))
        return self.run(program, **opts)

    def run(self, program: "PathProgram", **options):  # pragma: no cover - abstract
        raise NotImplementedError


SOLVERS: dict[str, Callable[[], ProgramSolver]] = {}


def register_solver(name: str, factory: Callable[[], ProgramSolver]) -> None:
    """Make a program solver available by ``name`` (lower case)."""
    SOLVERS[name.lower()] = factory


def get_solver(solver) -> ProgramSolver:
    """A solver instance for a name, a list of names (a chain) or an instance."""
    if isinstance(solver, ProgramSolver):
        return solver
    if isinstance(solver, (list, tuple)):
        if "chain" not in SOLVERS:
            raise UnknownAlgorithmError("no chain solver is registered (use op.PathProgram, which registers them)")
        return SOLVERS["chain"](stages=list(solver))
    if not isinstance(solver, str):
        raise UnknownAlgorithmError(f"solver must be a name, a list of names (a chain) or a solver instance, "
                                    f"got {solver!r}")
    key = solver.lower()
    if key not in SOLVERS:
        hint = ("; no solver is registered yet: use op.PathProgram (it registers the built-in solvers)"
                if not SOLVERS else "")
        raise UnknownAlgorithmError(f"unknown program solver {solver!r}; known: "
                                    f"{', '.join(sorted(k for k in SOLVERS if k != 'chain'))}{hint}")
    return SOLVERS[key]()


def solver_names() -> list[str]:
    """Names of the registered program solvers (chains are lists of them)."""
    return sorted(k for k in SOLVERS if k != "chain")


# -------------------------------------------------------------------- program


class PathProgram:
    """A path planning problem as a constrained program.

    Args:
        world: a GridMap or CircleWorld.
        start, goal: ``(x, y)`` metres (fixed, not variables).
        variables: how a decision vector becomes a path (default ``Waypoints(6)``).
        name: shown in tables.
    """

    def __init__(self, world, start, goal, variables: Variables | None = None, name: str = "") -> None:
        s, g = check_start_goal(world, start, goal)
        self.world = world
        self.start, self.goal = s, g
        self.ctx = ProgramContext(world, s, g)
        self.variables = as_variables(variables if variables is not None else Waypoints(6)).bind(self.ctx)
        self.objective: Expr | None = None
        self.constraints: list[Constraint] = []
        self.name = name or "program"
        # symbolic problems built by gradient solvers for this program, reused by later solves
        self.built_solvers: dict = {}
        # opt-in batched evaluators of the program's own variables (accelerate)
        self.acceleration: Callable | None = None
        self.penalised_acceleration: Callable | None = None
        self.acceleration_name = ""

    # building ---------------------------------------------------------------
    def minimize(self, objective: Expr) -> "PathProgram":
        """Set the objective (a scalar term expression). Returns the program."""
        if not isinstance(objective, Expr):
            raise ParameterError(f"minimize takes a term expression such as T.length() + 0.1 * T.bending(), "
                                 f"got {objective!r}")
        if objective.vector:
            raise ParameterError(f"the objective must be a scalar; reduce {objective.name} with .sum(), "
                                 ".sumsq() or .max()")
        self.objective = objective
        return self

    def subject_to(self, *constraints: Constraint) -> "PathProgram":
        """Add constraints (``term >= number`` or ``term <= number``). Returns the program."""
        for c in constraints:
            if not isinstance(c, Constraint):
                raise ParameterError(f"subject_to takes constraints such as T.clearance() >= 0.2, got {c!r}")
            if c.is_clearance:
                for p, what in ((self.start, "start"), (self.goal, "goal")):
                    self.world.check_query_point(p, what, c.lower)
            self.constraints.append(c)
        return self

    @property
    def clearance(self) -> float:
        """The largest clearance any constraint asks for (0 without one), metres."""
        return max([c.lower for c in self.constraints if c.is_clearance], default=0.0)

    def _need_objective(self) -> Expr:
        if self.objective is None:
            raise ParameterError("the program has no objective: call prog.minimize(...) first")
        return self.objective

    # views -----------------------------------------------------------------
    def path_costs(self, P: np.ndarray) -> np.ndarray:
        """Objective of paths ``P`` ``(n, N, 2)``, ``(n,)``."""
        out = np.asarray(self._need_objective().batch(P, self.ctx), float).reshape(-1)
        return np.broadcast_to(out, (len(P),)) if out.size == 1 else out

    def path_violations(self, P: np.ndarray) -> np.ndarray:
        """Violation of each constraint by paths ``P`` ``(n, N, 2)``, ``(n, m)``."""
        if not self.constraints:
            return np.zeros((len(P), 0))
        return np.stack([c.violation(P, self.ctx) for c in self.constraints], axis=1)

    def population(self, X: np.ndarray, variables: Variables | None = None) -> tuple[np.ndarray, np.ndarray]:
        """``(cost, total violation)`` of a population ``X`` ``(n, d)`` (the swarms' view;
        served by the :meth:`accelerate` evaluator when one is attached)."""
        if self.acceleration is not None and (variables is None or variables is self.variables):
            return self.acceleration(X)
        return self.own_population(X, variables)

    def own_population(self, X: np.ndarray, variables: Variables | None = None) -> tuple[np.ndarray, np.ndarray]:
        """``(cost, total violation)`` of ``X`` from the terms themselves (never accelerated)."""
        P = (variables or self.variables).decode(X)
        return self.path_costs(P), self.path_violations(P).sum(axis=1)

    @property
    def has_paper_penalty(self) -> bool:
        """Whether a constraint carries the papers' penalty (:meth:`Constraint.penalised`)."""
        return any(c.paper_penalty is not None for c in self.constraints)

    def penalised(self, X: np.ndarray, weight: float) -> np.ndarray:
        """The penalty-mode fitness of a population ``X`` ``(n, d)``: cost plus each
        constraint's penalty (the paper's where attached, else ``weight * violation``);
        served by the :meth:`accelerate` evaluator given as ``penalised``."""
        if self.penalised_acceleration is not None and self.has_paper_penalty:
            return self.penalised_acceleration(X)
        return self.own_penalised(X, weight)

    def own_penalised(self, X: np.ndarray, weight: float) -> np.ndarray:
        """:meth:`penalised` from the terms themselves (never accelerated)."""
        if not self.has_paper_penalty:  # the uniform penalty: cost + weight * total violation
            c, v = self.population(X)
            return c + weight * v
        P = self.variables.decode(X)
        out = self.path_costs(P)
        for c in self.constraints:
            out = out + c.penalty(P, self.ctx, weight)
        return out

    def accelerate(self, evaluator: Callable, name: str = "", sample: int = 16, seed: int = 0,
                   rtol: float = ACCELERATION_RTOL, penalised: Callable | None = None) -> "PathProgram":
        """Serve :meth:`population` by ``evaluator(X) -> (cost, violation)``, a faster batched
        evaluator of the same program over the same variables (e.g. the column nodes'
        segment tables, :class:`~optplan.formulations.problem.PathProblem`), and, when
        given, :meth:`penalised` (the papers' penalty) by ``penalised(X) -> fitness``.

        Opt-in and checked: on ``sample`` populations rows (half the variables' own
        starts, half uniform in the box, repaired like a swarm's) both views must give the
        same cost (relative ``rtol``) and the same violation (zero on the same rows, equal
        to ``rtol`` otherwise), and the same penalised fitness; else a ParameterError, so an
        acceleration can never change the objective silently. Returns the program."""
        v = self.variables
        rng = np.random.default_rng(seed)
        half = max(int(sample), 2) // 2
        parts = [v.lower + rng.random((half, v.dim)) * (v.upper - v.lower)]
        own = v.initial_population(half, rng, self.clearance) if v.dim else None
        if own is not None:
            parts.insert(0, own)
        X = np.vstack(parts)
        if getattr(v, "repair", None) is not None:
            X = v.repair(X)
        c1, v1 = (np.asarray(a, float).reshape(-1) for a in evaluator(X))
        c2, v2 = (np.asarray(a, float).reshape(-1) for a in self.own_population(X))
        same_cost = np.allclose(c1, c2, rtol=rtol, atol=rtol)
        same_viol = np.array_equal(v1 > 0, v2 > 0) and np.allclose(v1, v2, rtol=rtol, atol=rtol)
        if not (same_cost and same_viol):
            worst = float(np.max(np.abs(c1 - c2) / np.maximum(np.abs(c2), 1.0)))
            raise ParameterError(f"the acceleration {name or evaluator!r} does not evaluate program {self.name!r}: "
                                 f"cost differs by up to {worst:.3g} (relative) or the violations differ on "
                                 f"{int(np.sum((v1 > 0) != (v2 > 0)))} of {len(X)} sample rows")
        if penalised is not None:
            if not self.has_paper_penalty:
                raise ParameterError("a penalised acceleration needs a constraint with the papers' penalty "
                                     "(T.clearance() >= c).penalised(...)")
            p1 = np.asarray(penalised(X), float).reshape(-1)
            p2 = np.asarray(self.own_penalised(X, 0.0), float).reshape(-1)
            if not np.allclose(p1, p2, rtol=rtol, atol=rtol):
                worst = float(np.max(np.abs(p1 - p2) / np.maximum(np.abs(p2), 1.0)))
                raise ParameterError(f"the acceleration {name or penalised!r} does not give program {self.name!r}'s "
                                     f"penalised fitness: it differs by up to {worst:.3g} (relative)")
        self.acceleration, self.acceleration_name = evaluator, name or getattr(evaluator, "__name__", "evaluator")
        self.penalised_acceleration = penalised
        return self

    def evaluate(self, path) -> tuple[float, dict[str, float]]:
        """Cost and violations (one entry per constraint, 0 when it holds) of one path ``(N, 2)``."""
        P = np.asarray(path, dtype=float)
        if P.ndim != 2 or P.shape[1] != 2 or len(P) < 2:
            raise ParameterError(f"evaluate takes an (N, 2) path, got shape {P.shape}")
        cost = float(self.path_costs(P[None])[0])
        viol = self.path_violations(P[None])[0]
        return cost, {c.name: float(v) for c, v in zip(self.constraints, viol)}

    def judge(self, path) -> tuple[float, dict[str, float], bool]:
        """``(cost, violations, feasible)``: feasible means the path runs from start to goal,
        every constraint holds, and the exact collision test accepts it."""
        from ..world.geometry import validate_path

        cost, viol = self.evaluate(path)
        P = np.asarray(path, float)
        ends = np.allclose(P[0], self.start, atol=1e-9) and np.allclose(P[-1], self.goal, atol=1e-9)
        ok = ends and all(v == 0 for v in viol.values()) and bool(validate_path(self.world, P, self.clearance))
        return cost, viol, bool(ok and math.isfinite(cost))

    def symbolic(self, variables: Variables, x, per_segment: int, shapes: dict | None = None):
        """The objective and constraint rows for one variable column ``x`` (CasADi).

        Returns ``(f, g, lbg, ubg, p, fill)``: ``lbg <= g <= ubg`` row-wise; ``p`` is the
        parameter column of the clearance model (obstacle data and margin, see
        :func:`~optplan.formulations.clearance_model.clearance_rows`, with ``per_segment``
        samples per segment and active sets of the given ``shapes``) and
        ``fill(margin, active)`` its values, so a built solver is reused while the
        shapes stay the same."""
        import casadi as ca

        from .clearance_model import clearance_rows

        sym = ca.SX if isinstance(x, ca.SX) else ca.MX
        P = variables.decode_symbolic(x)
        ctx = self.ctx
        ctx.strip, ctx._field_param = (shapes or {}).get("strip"), None   # one strip parameter per problem
        f = self._need_objective().symbolic(P, ctx).m
        rows, lb, ub, params, fills = [], [], [], [], []
        for c in self.constraints:
            if c.is_clearance:
                g, p, fill = clearance_rows(P, self.ctx, c.lower, per_segment, sym, shapes or {})
                lo, hi = np.zeros(g.shape[0]), np.full(g.shape[0], np.inf)
                params.append(p)
                fills.append(fill)
            else:
                sv = c.expr.symbolic(P, self.ctx)
                g = sv.m
                k = int(np.prod(sv.shape)) if sv.shape else 1
                lo = np.full(k, -np.inf if c.lower is None else c.lower)
                hi = np.full(k, np.inf if c.upper is None else c.upper)
            rows.append(g)
            lb.append(lo)
            ub.append(hi)
        if ctx._field_param is not None:
            # the distance field's strip around the start path (active["path"])
            params.append(ctx._field_param)
            fills.append(lambda margin, active: ctx.field_values(active["path"]))
        g = ca.vertcat(*rows) if rows else sym.zeros(0, 1)
        lbg = np.concatenate(lb) if lb else np.zeros(0)
        ubg = np.concatenate(ub) if ub else np.zeros(0)
        p = ca.vertcat(*params) if params else sym.zeros(0, 1)

        def fill_all(margin: float, active: dict) -> np.ndarray:
            return np.concatenate([fn(margin, active) for fn in fills]) if fills else np.zeros(0)

        return f, g, lbg, ubg, p, fill_all

    def reads_field(self) -> bool:
        """Whether the symbolic view reads the distance field (a clearance term in the
        objective or in a constraint other than ``clearance() >= c``): on grids that is
        the strip parameter, which needs MX."""
        from .expressions import Clearance

        exprs = [self._need_objective()] + [c.expr for c in self.constraints if not c.is_clearance]
        return any(isinstance(t, Clearance) for e in exprs for t in e.leaves())

    def surrogate_notes(self) -> list[str]:
        """Which terms a gradient solver replaces by a smooth surrogate, and how."""
        notes = self._need_objective().surrogates()
        for c in self.constraints:
            notes.extend(c.expr.surrogates())
        return notes

    # solving ---------------------------------------------------------------
    def solve(self, solver="msiar-gwo", /, **options):
        """Solve with a registered solver name, a chain ``["msiar-gwo", "ipopt"]`` or a
        solver instance; returns a :class:`optplan.results.ProgramResult`. Options are
        checked by the solver (``op.show_options(name)``); an unknown one is a
        ParameterError. ``solver`` is positional, so a solver's own option of that name
        (cvxpy's ``solver="CLARABEL"``) passes through."""
        self._need_objective()
        return get_solver(solver).solve(self, **options)

    def __repr__(self) -> str:
        obj = self.objective.name if self.objective is not None else "(no objective)"
        cons = "; ".join(c.name for c in self.constraints) or "none"
        return f"PathProgram({self.name}: minimize {obj} over {self.variables.name}; subject to {cons})"
