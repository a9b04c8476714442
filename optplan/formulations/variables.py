"""Decision variables of path programs: how a vector ``x`` becomes a path.

Every variable set decodes a population ``X`` ``(n, d)`` into paths
``(n, N, 2)`` with numpy (for swarms and reports) and one column ``x`` into a
symbolic ``(N, 2)`` path with CasADi (for gradient solvers). Start and goal are
fixed and never variables.

* :class:`Waypoints` — ``k`` free points between start and goal.
* :class:`Points` — ``n`` dense free points, started from a resampled seed (the
  smoothing variables).
* :class:`BSpline` — a clamped cubic B-spline through start and goal with ``ctrl``
  free control points, sampled at ``samples`` points (the path is linear in them).
* :class:`SplineThrough` — a cubic spline interpolating start, ``k`` free handle points and
  goal (yang2023 eq 3-4, the planners' ``encoding="spline"``), sampled at ``samples`` points.
* :class:`ColumnNodes` — one node per grid column (chen2025 §4.3.1). Snapped to
  cell centres for the swarms; gradient solvers see its continuous relaxation
  (:meth:`Variables.relaxed`), and say so.
* :class:`CellSequence` — li2023's cell sequence: ``via`` cells joined by 8-connected
  grid lines, so the path is a chain of adjacent cells (discrete: swarms only).
* :class:`GeneralVias` — the general encoding: ``m`` via points joined by geodesic legs
  over the world's roadmap; every path class on every grid and circle world, always
  collision-free (discrete: swarms; gradient solvers get dense points through its path).
"""
from __future__ import annotations


import numpy as np

from ..checks import integer
from ..errors import ParameterError
from ..world.polyline import repeats_to_end, resample_path
from .namespaces import Sym


def _count(value, what: str, minimum: int = 1) -> int:
    return integer(minimum)(what, value)


class Variables:
    """Base class. ``bind`` returns a copy set up for one program's world, start and goal."""

    name = "variables"
    smooth = True     # the symbolic decode is the numpy decode
    affine = True     # the path is an affine function of x (QP solvers need this)
    relax_note = ""

    def bind(self, ctx) -> "Variables":
        import copy

        v = copy.copy(self)
        v.ctx = ctx
        v._setup()
        return v

    def _setup(self) -> None:  # pragma: no cover - abstract
        raise NotImplementedError

    # every subclass sets dim, lower, upper in _setup
    def decode(self, X: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def decode_symbolic(self, x) -> Sym:  # pragma: no cover - abstract
        raise ParameterError(f"{self.name} is discrete and has no symbolic form: gradient solvers need "
                             "Waypoints, Points, BSpline or ColumnNodes")

    def from_path(self, path: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def relaxed(self) -> "Variables":
        """The variables a gradient solver optimises (themselves, unless discrete)."""
        return self

    def initial_population(self, n: int, rng: np.random.Generator, clearance: float) -> np.ndarray | None:
        """A start population for swarms (``None``: uniform in the bounds)."""
        return None

    repair = None

    def _box(self):
        xmin, ymin, xmax, ymax = self.ctx.world.bounds
        return np.array([xmin, ymin]), np.array([xmax, ymax])

    def __repr__(self) -> str:
        return self.name


class Waypoints(Variables):
    """``k`` free 2-D points between start and goal; ``x = (x1, y1, ..., xk, yk)``."""

    def __init__(self, k: int = 6) -> None:
        self.k = _count(k, "Waypoints(k)")
        self.name = f"Waypoints({self.k})"

    def _setup(self) -> None:
        lo, hi = self._box()
        self.dim = 2 * self.k
        self.lower = np.tile(lo, self.k)
        self.upper = np.tile(hi, self.k)
        self.n_points = self.k + 2

    def decode(self, X):
        X = np.asarray(X, dtype=float).reshape(-1, self.dim)
        n = len(X)
        P = np.empty((n, self.k + 2, 2))
        P[:, 0] = self.ctx.start
        P[:, -1] = self.ctx.goal
        P[:, 1:-1] = X.reshape(n, self.k, 2)
        return P

    def decode_symbolic(self, x):
        import casadi as ca

        inner = ca.reshape(x, 2, self.k).T
        m = ca.vertcat(ca.DM(self.ctx.start).T, inner, ca.DM(self.ctx.goal).T)
        return Sym(m, (self.k + 2, 2))

    def from_path(self, path):
        P = np.asarray(path, float)
        if len(P) != self.k + 2:
            P = resample_path(P, self.k + 2)
        return np.clip(P[1:-1].ravel(), self.lower, self.upper)

    def initial_population(self, n, rng, clearance):
        """Points spread along the start-goal line with scatter across it: half within
        a narrow band, half over the whole map, each sorted along the line."""
        s, g = self.ctx.start, self.ctx.goal
        lo, hi = self._box()
        span = hi - lo
        t = np.sort(rng.random((n, self.k)), axis=1)
        base = s + t[..., None] * (g - s)
        scale = np.where(np.arange(n) < n // 2, 0.15, 0.6)[:, None, None] * span
        X = base + rng.normal(size=(n, self.k, 2)) * scale
        return np.clip(X.reshape(n, -1), self.lower, self.upper)


class Points(Waypoints):
    """``n`` dense free points between start and goal (the smoothing variables)."""

    def __init__(self, n: int = 50) -> None:
        super().__init__(_count(n, "Points(n)"))
        self.name = f"Points({self.k})"


class BSpline(Variables):
    """A clamped cubic B-spline with control points ``[start, c_1 .. c_ctrl, goal]``,
    sampled at ``samples`` parameter values evenly spread in [0, 1]; the first and
    last samples are start and goal exactly (the spline is clamped)."""

    def __init__(self, ctrl: int = 4, samples: int = 40) -> None:
        self.ctrl = _count(ctrl, "BSpline(ctrl)")
        self.samples = _count(samples, "BSpline(samples)", 3)
        self.name = f"BSpline(ctrl={self.ctrl}, samples={self.samples})"

    def _setup(self) -> None:
        from scipy.interpolate import BSpline as _SciBSpline

        n_ctrl = self.ctrl + 2
        degree = min(3, n_ctrl - 1)
        inner = np.linspace(0, 1, n_ctrl - degree + 1)[1:-1]
        knots = np.concatenate([np.zeros(degree + 1), inner, np.ones(degree + 1)])
        u = np.linspace(0, 1, self.samples)
        B = _SciBSpline(knots, np.eye(n_ctrl), degree)(u)
        B[-1] = 0.0
        B[-1, -1] = 1.0   # the right end exactly (evaluation at u = 1 is one-sided)
        self.basis = B
        lo, hi = self._box()
        self.dim = 2 * self.ctrl
        self.lower = np.tile(lo, self.ctrl)
        self.upper = np.tile(hi, self.ctrl)
        self.n_points = self.samples
        self._ends = np.outer(B[:, 0], self.ctx.start) + np.outer(B[:, -1], self.ctx.goal)

    def decode(self, X):
        X = np.asarray(X, dtype=float).reshape(-1, self.dim)
        C = X.reshape(len(X), self.ctrl, 2)
        return np.matmul(self.basis[:, 1:-1], C) + self._ends

    def decode_symbolic(self, x):
        import casadi as ca

        C = ca.reshape(x, 2, self.ctrl).T
        return Sym(ca.mtimes(ca.DM(self.basis[:, 1:-1]), C) + ca.DM(self._ends), (self.samples, 2))

    def from_path(self, path):
        target = resample_path(np.asarray(path, float), self.samples) - self._ends
        C, *_ = np.linalg.lstsq(self.basis[:, 1:-1], target, rcond=None)
        return np.clip(C.ravel(), self.lower, self.upper)

    def initial_population(self, n, rng, clearance):
        return Waypoints.initial_population(self, n, rng, clearance) if self.dim else None

    @property
    def k(self) -> int:  # the sorting in Waypoints.initial_population works on control points
        return self.ctrl


class SplineThrough(Variables):
    """A cubic spline through start, ``k`` free handle points and goal (yang2023 eq 3-4),
    parametrised uniformly in [0, 1] and sampled at ``samples`` points: the planners'
    ``encoding="spline"`` (:class:`optplan.formulations.encodings.SplinePath`, whose sampling
    matrix it reads). ``x = (x1, y1, ..., xk, yk)``; the path is linear in ``x``."""

    def __init__(self, k: int = 3, samples: int = 100) -> None:
        self.k = _count(k, "SplineThrough(k)")
        self.samples = _count(samples, "SplineThrough(samples)", 3)
        self.name = f"SplineThrough(k={self.k}, samples={self.samples})"

    def _setup(self) -> None:
        from .encodings import SplinePath

        self.encoding = SplinePath(self.ctx.world, self.ctx.start, self.ctx.goal, m=self.k, samples=self.samples)
        self.dim = self.encoding.dim
        self.lower, self.upper = self.encoding.lower, self.encoding.upper
        self.n_points = self.samples
        B = self.encoding._basis
        self._inner = B[:, 1:-1]
        self._ends = np.outer(B[:, 0], self.ctx.start) + np.outer(B[:, -1], self.ctx.goal)

    def decode(self, X):
        return self.encoding.decode(X)

    def decode_symbolic(self, x):
        import casadi as ca

        C = ca.reshape(x, 2, self.k).T
        return Sym(ca.mtimes(ca.DM(self._inner), C) + ca.DM(self._ends), (self.samples, 2))

    def from_path(self, path):
        target = resample_path(np.asarray(path, float), self.samples) - self._ends
        C, *_ = np.linalg.lstsq(self._inner, target, rcond=None)
        return np.clip(C.ravel(), self.lower, self.upper)

    def initial_population(self, n, rng, clearance):
        return Waypoints.initial_population(self, n, rng, clearance)


class ColumnNodes(Variables):
    """One node per grid column strictly between start and goal (chen2025 §4.3.1):
    ``x[j]`` is the row coordinate (grid units) of the node in the ``j``-th column.

    ``snap=True`` (the papers') puts each node at its cell's centre; swarms search
    that, with the nearest-free-cell repair and collision-free random starts.
    Gradient solvers optimise the continuous rows instead (:meth:`relaxed`)."""

    def __init__(self, snap: bool = True) -> None:
        self.snap = bool(snap)
        self.name = "ColumnNodes()" if self.snap else "ColumnNodes(snap=False)"
        self.smooth = not self.snap
        self.relax_note = "continuous rows instead of cell centres" if self.snap else ""

    def _setup(self) -> None:
        from .encodings import ColumnNodes as _Encoding

        if not self.ctx.is_grid:
            raise ParameterError("ColumnNodes needs a grid map; on a circle world use Waypoints, Points or BSpline")
        self.encoding = _Encoding(self.ctx.world, self.ctx.start, self.ctx.goal, snap=self.snap)
        self.dim = self.encoding.dim
        self.lower, self.upper = self.encoding.lower, self.encoding.upper
        self.n_points = self.dim + 2
        self.repair = self.encoding.repair if self.snap else None

    def relaxed(self):
        return ColumnNodes(snap=False).bind(self.ctx) if self.snap else self

    def decode(self, X):
        return self.encoding.decode(X)

    def decode_symbolic(self, x):
        import casadi as ca

        if self.snap:
            return self.relaxed().decode_symbolic(x)
        g = self.ctx.world
        xs = (self.encoding.columns + 0.5) * g.resolution + g.origin[0]
        ys = x * g.resolution + g.origin[1]
        inner = ca.horzcat(ca.DM(xs), ys)
        m = ca.vertcat(ca.DM(self.ctx.start).T, inner, ca.DM(self.ctx.goal).T)
        return Sym(m, (self.dim + 2, 2))

    def from_path(self, path):
        """Rows where the path crosses each column centre (the first crossing)."""
        P = np.asarray(path, float)
        g = self.ctx.world
        xs = (self.encoding.columns + 0.5) * g.resolution + g.origin[0]
        order = np.argsort(P[:, 0], kind="stable")
        y = np.interp(xs, P[order, 0], P[order, 1])
        return np.clip((y - g.origin[1]) / g.resolution, self.lower, self.upper)

    def initial_population(self, n, rng, clearance):
        return self.encoding.sample_feasible(n, rng, clearance) if self.snap and self.dim else None


class CellSequence(Variables):
    """li2023's representation: a chain of 8-adjacent grid cells from the start's cell to
    the goal's, shaped by ``via`` free via cells (``x`` holds their grid coordinates).

    Each pair of consecutive cells (start, vias, goal) is joined by the 8-connected
    grid line between them; repeated cells are dropped. The path is the start, the
    centres of the chain's cells and the goal, padded with copies of the goal to a
    fixed length (zero-length segments change no term). Discrete: swarms only."""

    smooth = False
    affine = False

    def __init__(self, via: int = 3) -> None:
        self.via = _count(via, "CellSequence(via)")
        self.name = f"CellSequence(via={self.via})"

    def _setup(self) -> None:
        g = self.ctx.world
        if not self.ctx.is_grid:
            raise ParameterError("CellSequence needs a grid map")
        self.dim = 2 * self.via
        self.lower = np.zeros(self.dim)
        self.upper = np.tile([g.width - 1e-9, g.height - 1e-9], self.via)
        self.leg = max(g.width, g.height)
        self.n_points = (self.via + 1) * self.leg + 2
        self._s_cell = g.cell_of(self.ctx.start).astype(float)
        self._g_cell = g.cell_of(self.ctx.goal).astype(float)

    def decode(self, X):
        g = self.ctx.world
        X = np.asarray(X, dtype=float).reshape(-1, self.dim)
        n = len(X)
        vias = np.floor(np.clip(X, self.lower, self.upper)).reshape(n, self.via, 2)
        knots = np.concatenate([np.broadcast_to(self._s_cell, (n, 1, 2)), vias,
                                np.broadcast_to(self._g_cell, (n, 1, 2))], axis=1)
        a, b = knots[:, :-1], knots[:, 1:]                       # (n, legs, 2)
        steps = np.abs(b - a).max(axis=2)                        # Chebyshev length of each leg
        j = np.arange(1, self.leg + 1)
        frac = np.minimum(j[None, None, :] / np.maximum(steps, 1)[..., None], 1.0)   # (n, legs, leg)
        cells = np.rint(a[..., None, :] + frac[..., None] * (b - a)[..., None, :])   # (n, legs, leg, 2)
        cells = cells.reshape(n, -1, 2)
        centres = (cells + 0.5) * g.resolution + np.asarray(g.origin, float)
        P = np.concatenate([self.ctx.start[None, None].repeat(n, 0), centres,
                            self.ctx.goal[None, None].repeat(n, 0)], axis=1)
        return repeats_to_end(P, self.ctx.goal)

    def from_path(self, path):
        g = self.ctx.world
        P = resample_path(np.asarray(path, float), self.via + 2)[1:-1]
        return np.clip(g.to_grid(P).ravel(), self.lower, self.upper)

    def initial_population(self, n, rng, clearance):
        """Via cells spread along the start-goal line with scatter across it."""
        g = self.ctx.world
        s, e = g.to_grid(self.ctx.start), g.to_grid(self.ctx.goal)
        t = np.sort(rng.random((n, self.via)), axis=1)
        base = s + t[..., None] * (e - s)
        X = base + rng.normal(size=(n, self.via, 2)) * (0.25 * np.array([g.width, g.height]))
        return np.clip(X.reshape(n, -1), self.lower, self.upper)


class GeneralVias(Variables):
    """The general encoding (:class:`optplan.formulations.encodings.GeneralPath`) as program
    variables: ``x = (x1, y1, ..., xm, ym)`` via points, each snapped to the nearest roadmap
    node the start reaches, joined by shortest roadmap legs. ``clearance`` (metres) is the
    distance the roadmap keeps from obstacles. Decoded paths have a fixed number of points
    (the encoding's bound; short ones repeat the goal). Gradient solvers optimise dense
    points through the decoded path instead (:meth:`relaxed`), and say so."""

    smooth = False
    affine = False
    relax_note = "dense free points through the decoded path (snapping to roadmap nodes has no gradient)"

    def __init__(self, m: int = 3, clearance: float = 0.0, corridor_start: bool = False) -> None:
        from ..checks import number

        self.m = _count(m, "GeneralVias(m)")
        self.clearance = number(0.0)("GeneralVias(clearance)", clearance)
        if not isinstance(corridor_start, bool):
            raise ParameterError(f"GeneralVias(corridor_start) must be True or False, got {corridor_start!r}")
        self.corridor_start = corridor_start
        self.name = f"GeneralVias({self.m})" if not self.clearance else f"GeneralVias({self.m}, clearance={self.clearance:g})"

    def initial_population(self, n, rng, clearance):
        """With ``corridor_start``: one random corridor per individual
        (:meth:`~optplan.formulations.encodings.GeneralPath.sample_corridors`, what ``op.plan``
        starts the general encoding from); else uniform in the bounds."""
        return self.encoding.sample_corridors(n, rng) if self.corridor_start else None

    def _setup(self) -> None:
        from .encodings import GeneralPath

        self.encoding = GeneralPath(self.ctx.world, self.ctx.start, self.ctx.goal, m=self.m, clearance=self.clearance)
        self.dim = self.encoding.dim
        self.lower, self.upper = self.encoding.lower, self.encoding.upper
        self.n_points = None   # decoded paths fit each batch (goal copies pad them: no term changes)

    def decode(self, X):
        return self.encoding.decode(X, self.n_points)   # repeats already at the end

    def relaxed(self):
        return Points(max(8, 4 * (self.m + 1))).bind(self.ctx)

    def from_path(self, path):
        return self.encoding.from_path(path)


def as_variables(v) -> Variables:
    """``v`` when it is a variable set, else a ParameterError naming the choices."""
    if isinstance(v, Variables):
        return v
    raise ParameterError(f"variables must be op.Waypoints(k), op.Points(n), op.BSpline(ctrl, samples), "
                         f"op.SplineThrough(k, samples), op.ColumnNodes(), op.CellSequence(via) or "
                         f"op.GeneralVias(m), got {v!r}")


