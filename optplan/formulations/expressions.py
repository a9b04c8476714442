"""Objective terms and constraints of path programs, each written once.

A term is a function of one path ``P`` (``(N, 2)`` points) written against a
numpy-like namespace ``m`` (:mod:`optplan.formulations.namespaces`). The same
function is evaluated **batched** over a population ``(n, N, 2)`` for the
swarms and the reports, and **symbolically** (CasADi) for IPOPT and SLSQP. A
term that is a sum of squares of affine functions of the points says so
(``quadratic``); the QP solvers take objectives made only of those. A term
without a smooth form (a count) carries a documented smooth *surrogate* that
gradient solvers optimise instead; the program's cost is always the exact
batched value.

Terms combine with ``+``, ``-`` and scalar ``*``; vector terms reduce with
``.sum()``, ``.sumsq()``, ``.max()``, ``.min()``, ``.mean()``; comparing a term with a
number (``>=``, ``<=``) makes a :class:`Constraint`, element-wise for vector terms.

``clearance`` is special in one way only: as a constraint its verdict is the
project's one exact segment rule (:func:`optplan.world.geometry.validate_path`),
its violation the number of colliding segments plus, on those paths, how deep
they go; the symbolic view is a smooth sampled model with a cushion, and every
result is judged by the exact rule.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..checks import integer
from ..errors import ParameterError
from .namespaces import BATCHED, SYMBOLIC, Batch, Sym


class ProgramContext:
    """What terms may read besides the path: the world, start, goal, and caches that
    the program owns (the sampled distance field, the symbolic clearance model)."""

    def __init__(self, world, start: np.ndarray, goal: np.ndarray) -> None:
        self.world = world
        self.start = np.asarray(start, float)
        self.goal = np.asarray(goal, float)
        self.is_grid = world.is_grid
        self._distance = None

    @property
    def distance(self) -> Callable:
        """Vectorised signed distance ``points (..., 2) -> (...)`` (sampled field on grids)."""
        if self._distance is None:
            from ..world.fields import distance_function

            self._distance = distance_function(self.world)
        return self._distance

    @property
    def cell(self) -> float:
        """Length scale of the world: the grid resolution, or 1 m for circle worlds."""
        return float(self.world.resolution) if self.is_grid else 1.0

    # symbolic view -------------------------------------------------------------
    # the strip of the distance field a symbolic problem reads on grids: (capacity, radius),
    # set by PathProgram.symbolic while it builds, and the parameter made for it
    strip: tuple | None = None
    _field_param = None

    def field_parameter(self):
        """The CasADi (MX) parameter column holding the distance-field strip of the problem
        being built (:func:`~optplan.formulations.clearance_model.field_strip`); one per
        problem, shared by every term that reads the field. Without a strip set (a term's
        symbolic view used on its own), the strip holds the whole map."""
        if self._field_param is None:
            import casadi as ca

            from ..world.fields import TILE, distance_spline

            nty, ntx = distance_spline(self.world).tiles
            if self.strip is None:   # every tile: the map's diagonal around its corners
                self.strip = (nty * ntx + 1, float(np.hypot(*np.ptp(np.reshape(self.world.bounds, (2, 2)), axis=0))))
            self._field_param = ca.MX.sym("field_strip", nty * ntx + self.strip[0] * (TILE + 3) ** 2)
        return self._field_param

    def field_values(self, path: np.ndarray) -> np.ndarray:
        """Values of :meth:`field_parameter` for the strip around ``path`` (``(N, 2)``, metres)."""
        from .clearance_model import field_strip

        if self.strip is None:
            raise ValueError("no distance-field strip was set for this problem")
        cap, radius = self.strip
        return field_strip(self, np.asarray(path, float), radius, cap)[0]


# ------------------------------------------------------------------ expressions


class Expr:
    """Base of every objective expression. Subclasses implement ``batch`` and ``symbolic``."""

    name: str = "expr"
    vector: bool = False
    smooth: bool = True
    quadratic: bool = False

    # views ---------------------------------------------------------------
    def batch(self, P: np.ndarray, ctx: ProgramContext) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def symbolic(self, P: Sym, ctx: ProgramContext) -> Sym:  # pragma: no cover - abstract
        raise NotImplementedError

    def leaves(self) -> list["Expr"]:
        return [self]

    def surrogates(self) -> list[str]:
        """Notes of the leaves whose symbolic view is a smooth surrogate."""
        return [f"{t.name}: {t.surrogate_note}" for t in self.leaves() if getattr(t, "surrogate_note", None)]

    # algebra -------------------------------------------------------------
    def __add__(self, other):
        return Linear.of(self) + other

    def __radd__(self, other):
        return Linear.of(self) + other

    def __sub__(self, other):
        return Linear.of(self) + (-1.0) * _as_expr(other)

    def __rsub__(self, other):
        return _as_expr(other) + (-1.0) * self

    def __mul__(self, k):
        return Linear.of(self) * k

    __rmul__ = __mul__

    def __truediv__(self, k):
        return Linear.of(self) * (1.0 / _scalar(k))

    def __neg__(self):
        return Linear.of(self) * -1.0

    def sum(self) -> "Expr":
        return Reduced(self, "sum")

    def sumsq(self) -> "Expr":
        return Reduced(self, "sumsq")

    def max(self) -> "Expr":
        return Reduced(self, "max")

    def min(self) -> "Expr":
        return Reduced(self, "min")

    def mean(self) -> "Expr":
        return Reduced(self, "mean")

    def __ge__(self, bound):
        return Constraint(self, lower=_scalar(bound))

    def __le__(self, bound):
        return Constraint(self, upper=_scalar(bound))

    def __repr__(self) -> str:
        return self.name

    __hash__ = object.__hash__


def _scalar(k) -> float:
    if isinstance(k, bool) or not isinstance(k, (int, float, np.integer, np.floating)):
        raise ParameterError(f"terms are scaled by and compared with plain numbers, got {k!r}")
    v = float(k)
    if not math.isfinite(v):
        raise ParameterError(f"terms are scaled by and compared with finite numbers, got {k!r}")
    return v


def _as_expr(x) -> Expr:
    if isinstance(x, Expr):
        return x
    return Constant(_scalar(x))


@dataclass(eq=False, repr=False)
class Constant(Expr):
    value: float = 0.0

    def __post_init__(self) -> None:
        self.name = f"{self.value:g}"
        self.quadratic = True

    def batch(self, P, ctx):
        return np.full(len(P), self.value)

    def symbolic(self, P, ctx):
        return Sym(_casadi().DM(self.value), ())

    def leaves(self):
        return []


@dataclass(eq=False, repr=False)
class Linear(Expr):
    """``sum_i c_i * e_i`` (all scalar, or all vector terms of one length)."""

    parts: list = field(default_factory=list)

    def __post_init__(self) -> None:
        self.vector = any(e.vector for _, e in self.parts)
        if self.vector and not all(e.vector for _, e in self.parts):
            raise ParameterError("cannot add a vector term and a scalar term; reduce the vector first "
                                 "(.sum(), .sumsq(), .max())")
        self.smooth = all(e.smooth for _, e in self.parts)
        self.quadratic = all(e.quadratic and c >= 0 for c, e in self.parts)
        self.name = " + ".join(e.name if c == 1 else f"{c:g}*{e.name}" for c, e in self.parts) or "0"

    @staticmethod
    def of(e: Expr) -> "Linear":
        return e if isinstance(e, Linear) else Linear([(1.0, e)])

    def __add__(self, other):
        o = _as_expr(other)
        return Linear(self.parts + (o.parts if isinstance(o, Linear) else [(1.0, o)]))

    __radd__ = __add__

    def __mul__(self, k):
        k = _scalar(k)
        return Linear([(c * k, e) for c, e in self.parts])

    __rmul__ = __mul__

    def batch(self, P, ctx):
        out = 0.0
        for c, e in self.parts:
            out = out + c * e.batch(P, ctx)
        return out

    def symbolic(self, P, ctx):
        out = None
        for c, e in self.parts:
            term = e.symbolic(P, ctx) * c
            out = term if out is None else out + term
        return out if out is not None else Sym(_casadi().DM(0.0), ())

    def leaves(self):
        return [leaf for _, e in self.parts for leaf in e.leaves()]


REDUCTIONS = ("sum", "sumsq", "max", "min", "mean")


@dataclass(eq=False, repr=False)
class Reduced(Expr):
    """A vector term reduced to a scalar."""

    inner: Expr = None
    how: str = "sum"

    def __post_init__(self) -> None:
        if not self.inner.vector:
            raise ParameterError(f"{self.inner.name} is already a scalar; .{self.how}() reduces vector terms")
        self.name = f"{self.inner.name}.{self.how}()"
        self.smooth = self.inner.smooth and self.how in ("sum", "sumsq", "mean")
        self.quadratic = self.inner.quadratic and self.how == "sum"

    def batch(self, P, ctx):
        v = np.asarray(self.inner.batch(P, ctx), float)
        if v.shape[1] == 0:
            return np.zeros(len(v))
        if self.how == "sumsq":
            return (v * v).sum(axis=1)
        return getattr(v, self.how)(axis=1)

    def symbolic(self, P, ctx):
        v = self.inner.symbolic(P, ctx)
        if v.shape == (0,):
            return Sym(_casadi().DM(0.0), ())
        return getattr(SYMBOLIC, self.how)(v)

    def leaves(self):
        return self.inner.leaves()


@dataclass(eq=False, repr=False)
class PathTerm(Expr):
    """A term written once as ``fn(P, m)``; ``surrogate(P, m)`` replaces it in the
    symbolic view when the term has no smooth form (``smooth=False``)."""

    fn: Callable = None
    term_name: str = "term"
    is_vector: bool | None = False
    is_smooth: bool = True
    is_quadratic: bool = False
    surrogate: Callable | None = None
    surrogate_note: str | None = None

    def __post_init__(self) -> None:
        self.name = self.term_name
        self.vector = bool(self.is_vector)
        self.smooth = self.is_smooth
        self.quadratic = self.is_quadratic

    def batch(self, P, ctx):
        out = self.fn(Batch(P), BATCHED) if not getattr(self.fn, "wants_context", False) \
            else self.fn(Batch(P), BATCHED, ctx)
        a = out.a if isinstance(out, Batch) else np.broadcast_to(np.asarray(out, float), (len(P),))
        a = np.asarray(a, dtype=float)
        if a.ndim > 2 or (self.vector and a.ndim != 2) or (not self.vector and a.ndim != 1):
            want = "one vector per path" if self.vector else "one number per path"
            raise ParameterError(f"term {self.name!r} must give {want}; it gave per-path shape {a.shape[1:]} "
                                 f"(declare vector=True for element-wise terms)")
        return a

    def symbolic(self, P, ctx):
        fn = self.fn
        if not self.smooth:
            if self.surrogate is None:
                raise ParameterError(f"term {self.name!r} has no smooth form and no surrogate: a gradient solver "
                                     "cannot take it (use a metaheuristic, or give custom(..., surrogate=fn))")
            fn = self.surrogate
        out = fn(P, SYMBOLIC) if not getattr(fn, "wants_context", False) else fn(P, SYMBOLIC, ctx)
        out = out if isinstance(out, Sym) else Sym(_casadi().DM(float(out)), ())
        if self.vector and out.ndim != 1 or not self.vector and out.ndim != 0:
            raise ParameterError(f"term {self.name!r}: its symbolic view has shape {out.shape}, "
                                 f"expected {'a 1-D vector' if self.vector else 'a scalar'}")
        return out


def _casadi():
    import casadi as ca

    return ca


def _with_context(fn):
    fn.wants_context = True
    return fn


# ------------------------------------------------------------------- built-ins

def _segments(P, m):
    return m.diff(P, axis=0)


def _turn_angles(P, m):
    """Absolute heading change at every interior vertex, radians in [0, pi]."""
    d = _segments(P, m)
    a, b = d[:-1], d[1:]
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    dot = a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]
    # + 0.0 turns -0.0 into 0.0: next to a zero-length segment (repeats at a path's end) both
    # are zeros, and atan2(-0.0, -0.0) is -pi, a U-turn that is not there
    return m.abs(m.atan2(cross + 0.0, dot + 0.0))


def length() -> Expr:
    """Path length, metres (yang2023 eq 2, yuan2021 eq 10, chen2025 eq 32)."""
    return PathTerm(lambda P, m: m.sum(m.smooth_norm(_segments(P, m), axis=1)), "length")


def squared_length() -> Expr:
    """Sum of squared segment lengths (a quadratic stand-in for length: it also spreads points evenly)."""
    return PathTerm(lambda P, m: m.sumsq(_segments(P, m)), "squared_length", is_quadratic=True)


def bending() -> Expr:
    """Sum of squared second differences ``|p[i+1] - 2 p[i] + p[i-1]|^2`` (quadratic)."""
    return PathTerm(lambda P, m: m.sumsq(P[2:] - 2.0 * P[1:-1] + P[:-2]), "bending", is_quadratic=True)


def segment_lengths() -> Expr:
    """Length of every segment, metres (vector)."""
    return PathTerm(lambda P, m: m.smooth_norm(_segments(P, m), axis=1), "segment_lengths", is_vector=True)


def turn_angles() -> Expr:
    """Absolute heading change at every interior vertex, radians (vector; li2023 eq 2 theta
    is its ``.sum()``)."""
    return PathTerm(_turn_angles, "turn_angles", is_vector=True)


TURN_TOL = math.radians(1e-6)     # below this a vertex is not a turn (world.metrics' tolerance)
SURROGATE_WIDTH = math.radians(2.0)


def _soft_step(a, m, width=SURROGATE_WIDTH):
    """Smooth 0 -> 1 as ``a`` grows past ``width`` (``a^2 / (a^2 + width^2)``)."""
    return a * a / (a * a + width * width)


def turn_count(tol_deg: float = 1e-6) -> Expr:
    """Number of vertices whose heading changes by more than ``tol_deg`` (li2023 eq 2).

    No smooth form: gradient solvers optimise the surrogate ``sum a^2 / (a^2 + w^2)``
    with ``w`` = 2 degrees (each turn counts about 1 once it is a few degrees sharp)."""
    tol = math.radians(_scalar(tol_deg))
    return PathTerm(lambda P, m: m.sum(_turn_angles(P, m) > tol), "turn_count", is_smooth=False,
                    surrogate=lambda P, m: m.sum(_soft_step(_turn_angles(P, m), m)),
                    surrogate_note="sum a^2/(a^2 + (2 deg)^2) over the turn angles a")


def turn_cost() -> Expr:
    """yuan2021 eq 12: ``pi/4`` per turn of up to 45 degrees and ``pi/2`` per sharper turn.

    No smooth form: the surrogate charges ``pi/4 * s(a) + pi/4 * s(a - 45 deg)`` with
    the smooth step ``s`` of :func:`turn_count` (``s`` of a negative argument is 0)."""
    quarter = math.pi / 4

    def exact(P, m):
        a = _turn_angles(P, m)
        small = (a > TURN_TOL) * (a <= quarter + 1e-11)
        sharp = a > quarter + 1e-11
        return quarter * m.sum(small) + (math.pi / 2) * m.sum(sharp)

    def smooth(P, m):
        a = _turn_angles(P, m)
        over = m.fmax(a - quarter, 0.0)
        return quarter * m.sum(_soft_step(a, m)) + quarter * m.sum(_soft_step(over, m))

    return PathTerm(exact, "turn_cost", is_smooth=False, surrogate=smooth,
                    surrogate_note="pi/4 * (s(a) + s(max(a - 45 deg, 0))), s(a) = a^2/(a^2 + (2 deg)^2)")


def curvature() -> Expr:
    """Discrete curvature at every interior vertex: turn angle over the mean of the two
    adjacent segment lengths, 1/metres (vector)."""
    def fn(P, m):
        seg = m.smooth_norm(_segments(P, m), axis=1)
        return _turn_angles(P, m) / (0.5 * (seg[:-1] + seg[1:]))
    return PathTerm(fn, "curvature", is_vector=True)


def _heading_error(which: str, theta: float):
    c, s = math.cos(theta), math.sin(theta)

    def fn(P, m):
        d = P[1] - P[0] if which == "start" else P[-1] - P[-2]
        return m.abs(m.atan2(c * d[1] - s * d[0], c * d[0] + s * d[1]))
    return fn


def start_heading(theta: float) -> Expr:
    """Absolute angle between the first segment and heading ``theta`` (radians), in [0, pi]."""
    return PathTerm(_heading_error("start", _scalar(theta)), "start_heading")


def goal_heading(theta: float) -> Expr:
    """Absolute angle between the last segment and heading ``theta`` (radians), in [0, pi]."""
    return PathTerm(_heading_error("goal", _scalar(theta)), "goal_heading")


def custom(fn: Callable, name: str = "custom", vector: bool = False, smooth: bool = True,
           surrogate: Callable | None = None) -> Expr:
    """A user term written once: ``fn(P, m)`` with ``P`` one path and ``m`` the namespace.

    ``vector=True`` when ``fn`` returns one value per element; ``smooth=False`` for a
    term with no derivatives (then give ``surrogate(P, m)`` for gradient solvers, or
    use it with metaheuristics only)."""
    if not callable(fn):
        raise ParameterError(f"custom needs a function fn(P, m), got {fn!r}")
    if not isinstance(name, str) or not name:
        raise ParameterError("custom needs a non-empty name")
    return PathTerm(fn, name, is_vector=bool(vector), is_smooth=bool(smooth), surrogate=surrogate,
                    surrogate_note=f"the user's surrogate of {name}" if surrogate is not None and not smooth else None)


# ------------------------------------------------------------------ clearance


def segment_samples(P, per_segment: int):
    """Points at fractions ``j / per_segment`` (``j = 0 .. per_segment - 1``) of every segment,
    plus the last point: works on numpy batches ``(n, N, 2)``."""
    t = np.arange(per_segment) / per_segment
    a, b = P[:, :-1, None, :], P[:, 1:, None, :]
    pts = (a + t[None, None, :, None] * (b - a)).reshape(P.shape[0], -1, 2)
    return np.concatenate([pts, P[:, -1:, :]], axis=1)


@dataclass(eq=False, repr=False)
class Clearance(Expr):
    """Signed distance to the nearest obstacle at points along the path, metres (vector).

    ``per_segment`` points per segment (``None``: chosen by the solver from the
    segment lengths). As a constraint ``clearance() >= c`` the verdict is the exact
    segment rule with clearance ``c``."""

    per_segment: int | None = None

    def __post_init__(self) -> None:
        self.name = "clearance"
        self.vector = True

    def batch(self, P, ctx):
        k = self.per_segment or 8
        return ctx.distance(segment_samples(np.asarray(P, float), k))

    def symbolic(self, P, ctx):
        from .clearance_model import symbolic_signed_distance

        return symbolic_signed_distance(P, ctx, self.per_segment or 8)


def clearance(per_segment: int | None = None) -> Expr:
    """Signed distance to obstacles along the path (see :class:`Clearance`)."""
    return Clearance(integer(1, optional=True)("per_segment", per_segment))


# ------------------------------------------------------------------ constraints

VIOLATION_TOL = 1e-6  # a continuous constraint violated by less than this holds (solvers meet bounds to ~1e-8)


@dataclass(eq=False)
class Constraint:
    """``lower <= expr`` and/or ``expr <= upper``, element-wise for vector terms."""

    expr: Expr
    lower: float | None = None
    upper: float | None = None
    name: str = ""
    # the paper's penalty (per colliding segment, per metre^2 of penetration): how a swarm in
    # penalty mode weighs this constraint (clearance only, see penalised)
    paper_penalty: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if not self.name:
            parts = []
            if self.lower is not None:
                parts.append(f"{self.expr.name} >= {self.lower:g}")
            if self.upper is not None:
                parts.append(f"{self.expr.name} <= {self.upper:g}")
            self.name = " and ".join(parts)

    @property
    def is_clearance(self) -> bool:
        return isinstance(self.expr, Clearance) and self.lower is not None and self.upper is None

    def __le__(self, upper):  # (a >= 1) <= 2 is not supported: say so
        raise ParameterError("write a two-sided constraint as two constraints")

    @property
    def penetration_samples(self) -> int:
        """Samples per segment of the penetration integral (the clearance term's ``per_segment``, else 8)."""
        return getattr(self.expr, "per_segment", None) or 8

    def penalised(self, per_collision: float, per_penetration: float = 0.0) -> "Constraint":
        """This clearance constraint with the papers' penalty: a swarm in penalty mode adds
        ``per_collision`` per colliding segment (the exact rule) plus ``per_penetration`` times
        the penetration integral (:func:`optplan.formulations.terms.penetration`) instead of
        its uniform ``penalty * violation``. The verdict and the violation are unchanged."""
        from dataclasses import replace

        from ..checks import number

        if not self.is_clearance:
            raise ParameterError(f"only a clearance constraint (clearance() >= c) has the papers' penalty, not {self.name}")
        pc = number(0.0)("per_collision", per_collision)
        pp = number(0.0)("per_penetration", per_penetration)
        return replace(self, paper_penalty=(float(pc), float(pp)))

    def penalty(self, P: np.ndarray, ctx: ProgramContext, weight: float) -> np.ndarray:
        """What penalty mode adds for paths ``P`` ``(n, N, 2)``, ``(n,)``: the paper's penalty
        when one is attached (:meth:`penalised`), else ``weight * violation``."""
        if self.paper_penalty is None:
            return weight * self.violation(P, ctx)
        from .terms import collisions, penetration

        pc, pp = self.paper_penalty
        out = pc * collisions(ctx.world, P, self.lower)
        if pp:
            out = out + pp * penetration(ctx.world, P, self.lower, self.penetration_samples)
        return out

    def violation(self, P: np.ndarray, ctx: ProgramContext) -> np.ndarray:
        """How much each path of ``P`` ``(n, N, 2)`` violates this, ``(n,)``; 0 where it holds."""
        if self.is_clearance:
            return clearance_violation(ctx.world, P, self.lower, self.penetration_samples)
        v = np.asarray(self.expr.batch(P, ctx), float)
        v = v.reshape(len(P), -1)
        out = np.zeros(len(P))
        if self.lower is not None:
            out += np.maximum(self.lower - v, 0.0).sum(axis=1)
        if self.upper is not None:
            out += np.maximum(v - self.upper, 0.0).sum(axis=1)
        return np.where(out > VIOLATION_TOL, out, 0.0)


def clearance_violation(world, P: np.ndarray, clearance: float, samples_per_segment: int = 8) -> np.ndarray:
    """Colliding segments (the exact rule) plus, on colliding paths only, the penetration
    integral (so the search is guided, and a path the exact rule accepts scores 0)."""
    from .terms import collisions, penetration

    coll = collisions(world, P, clearance)
    if not coll.any():
        return coll
    pen = np.zeros(len(P))
    bad = coll > 0
    pen[bad] = penetration(world, P[bad], clearance, samples_per_segment)
    return coll + pen
