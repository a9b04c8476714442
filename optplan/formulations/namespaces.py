"""Two array namespaces that let one function of a path be evaluated two ways.

A term of a program is written once as ``fn(P, m)``: ``P`` is one path, an
``(N, 2)`` array of points, and ``m`` a small numpy-like namespace (``sum``,
``sqrt``, ``atan2``, ``diff``, ``norm``, ...). The same function then runs

* **batched** (:class:`BatchNamespace`): ``P`` is a :class:`Batch`, a whole
  population ``(n, N, 2)`` that behaves like one ``(N, 2)`` path: indexing,
  arithmetic, broadcasting and reductions act on the per-path axes and carry the
  population axis along, so one call scores every individual with numpy;
* **symbolically** (:class:`SymbolicNamespace`): ``P`` is a :class:`Sym`, a
  CasADi matrix with numpy's shape rules (1-D vectors, row indexing,
  broadcasting of a row over a matrix), so IPOPT and SLSQP get exact
  derivatives of the very same expression.

Only what path terms need is supported; anything else raises a clear
``ParameterError`` rather than computing something different in the two views.
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError

# --------------------------------------------------------------------- batched


class Batch:
    """A population of arrays that acts like one of them (the leading axis is the population)."""

    __slots__ = ("a",)
    __array_priority__ = 1000  # numpy defers to our operators

    def __init__(self, a) -> None:
        self.a = a if isinstance(a, np.ndarray) else np.asarray(a)

    @property
    def shape(self) -> tuple:
        return self.a.shape[1:]

    @property
    def ndim(self) -> int:
        return self.a.ndim - 1

    def __len__(self) -> int:
        return self.a.shape[1]

    def __getitem__(self, idx):
        if not isinstance(idx, tuple):
            idx = (idx,)
        return Batch(self.a[(slice(None),) + idx])

    @property
    def T(self) -> "Batch":
        return Batch(np.swapaxes(self.a, -1, -2)) if self.ndim == 2 else self

    # arithmetic -----------------------------------------------------------
    def _bin(self, other, op, reverse=False):
        # fast paths: a plain number, or a Batch of the same per-path rank (the common cases)
        if isinstance(other, (int, float)) or (isinstance(other, Batch) and other.a.ndim == self.a.ndim):
            o = other.a if isinstance(other, Batch) else other
            return Batch(op(o, self.a) if reverse else op(self.a, o))
        x, y = _aligned(self, other)
        return Batch(op(y, x) if reverse else op(x, y))

    def __add__(self, o): return self._bin(o, np.add)
    def __radd__(self, o): return self._bin(o, np.add, True)
    def __sub__(self, o): return self._bin(o, np.subtract)
    def __rsub__(self, o): return self._bin(o, np.subtract, True)
    def __mul__(self, o): return self._bin(o, np.multiply)
    def __rmul__(self, o): return self._bin(o, np.multiply, True)
    def __truediv__(self, o): return self._bin(o, np.true_divide)
    def __rtruediv__(self, o): return self._bin(o, np.true_divide, True)
    def __pow__(self, o): return self._bin(o, np.power)
    def __rpow__(self, o): return self._bin(o, np.power, True)
    def __lt__(self, o): return self._bin(o, np.less)
    def __le__(self, o): return self._bin(o, np.less_equal)
    def __gt__(self, o): return self._bin(o, np.greater)
    def __ge__(self, o): return self._bin(o, np.greater_equal)
    def __neg__(self): return Batch(-self.a)
    def __abs__(self): return Batch(np.abs(self.a))

    def __matmul__(self, o):
        b = o.a if isinstance(o, Batch) else np.asarray(o)
        return Batch(np.matmul(self.a, b))

    def __rmatmul__(self, o):
        return Batch(np.matmul(np.asarray(o), self.a))

    def __bool__(self):
        raise ParameterError("a term cannot branch on a value with `if`; use m.where(cond, a, b)")


def _raw(x):
    return x.a if isinstance(x, Batch) else x


def _aligned(x, y):
    """Both operands as numpy arrays whose per-path axes line up (numpy rules per path)."""
    xa, ya = _raw(x), _raw(y)
    xb, yb = isinstance(x, Batch), isinstance(y, Batch)
    if xb and yb:
        px, py = xa.ndim - 1, ya.ndim - 1
        if px < py:
            xa = xa.reshape(xa.shape[:1] + (1,) * (py - px) + xa.shape[1:])
        elif py < px:
            ya = ya.reshape(ya.shape[:1] + (1,) * (px - py) + ya.shape[1:])
        return xa, ya
    ya = np.asarray(ya)
    xa = np.asarray(xa)
    if xb and ya.ndim > xa.ndim - 1:
        xa = xa.reshape(xa.shape[:1] + (1,) * (ya.ndim - xa.ndim + 1) + xa.shape[1:])
    if yb and xa.ndim > ya.ndim - 1:
        ya = ya.reshape(ya.shape[:1] + (1,) * (xa.ndim - ya.ndim + 1) + ya.shape[1:])
    return xa, ya


def _batch_axis(x: Batch, axis):
    """numpy axis of a per-path axis (``None``: every per-path axis)."""
    if axis is None:
        return tuple(range(1, x.a.ndim))
    axis = int(axis)
    nd = x.ndim
    if not -nd <= axis < nd:
        raise ParameterError(f"axis {axis} is out of range for a per-path array of {nd} dimensions")
    return axis + 1 if axis >= 0 else x.a.ndim + axis


def _unary(fn):
    def f(x):
        return Batch(fn(_raw(x))) if isinstance(x, Batch) else fn(x)
    return f


def _binary(fn):
    def f(x, y):
        if isinstance(x, Batch) or isinstance(y, Batch):
            xa, ya = _aligned(x, y)
            return Batch(fn(xa, ya))
        return fn(x, y)
    return f


def _population_arrays(items):
    """The items as arrays with the population axis first (constants repeated over it), or
    ``None`` when no item is a :class:`Batch`."""
    n = next((i.a.shape[0] for i in items if isinstance(i, Batch)), None)
    if n is None:
        return None
    return [i.a if isinstance(i, Batch) else np.broadcast_to(np.asarray(i), (n,) + np.shape(i)) for i in items]


def _reduction(fn):
    """``fn`` (a numpy reduction) over per-path axes of a :class:`Batch`."""
    def reduce(x, axis=None):
        if not isinstance(x, Batch):
            return fn(np.asarray(x), axis=axis)
        return Batch(fn(x.a, axis=_batch_axis(x, axis)))
    return reduce


class BatchNamespace:
    """numpy over a :class:`Batch` (and plain numbers)."""

    name = "batched"
    pi = np.pi
    inf = np.inf
    sqrt = staticmethod(_unary(np.sqrt))
    exp = staticmethod(_unary(np.exp))
    log = staticmethod(_unary(np.log))
    sin = staticmethod(_unary(np.sin))
    cos = staticmethod(_unary(np.cos))
    tan = staticmethod(_unary(np.tan))
    tanh = staticmethod(_unary(np.tanh))
    arcsin = asin = staticmethod(_unary(np.arcsin))
    arccos = acos = staticmethod(_unary(np.arccos))
    abs = fabs = staticmethod(_unary(np.abs))
    arctan2 = atan2 = staticmethod(_binary(np.arctan2))
    fmax = maximum = staticmethod(_binary(np.maximum))
    fmin = minimum = staticmethod(_binary(np.minimum))

    @staticmethod
    def hypot(x, y):
        return BatchNamespace.sqrt(x * x + y * y)

    sum = staticmethod(_reduction(np.sum))
    mean = staticmethod(_reduction(np.mean))
    max = staticmethod(_reduction(np.max))
    min = staticmethod(_reduction(np.min))

    @staticmethod
    def sumsq(x, axis=None):
        return BatchNamespace.sum(x * x, axis)

    @staticmethod
    def norm(x, axis=-1):
        """Euclidean norm along ``axis`` (rows of points by default)."""
        return BatchNamespace.sqrt(BatchNamespace.sum(x * x, axis))

    @staticmethod
    def diff(x, axis=0):
        if not isinstance(x, Batch):
            return np.diff(x, axis=axis)
        return Batch(np.diff(x.a, axis=_batch_axis(x, axis)))

    @staticmethod
    def where(cond, a, b):
        items = (cond, a, b)
        if not any(isinstance(v, Batch) for v in items):
            return np.where(cond, a, b)
        top = max(v.ndim if isinstance(v, Batch) else np.ndim(v) for v in items)
        arrs = [v.a.reshape(v.a.shape[:1] + (1,) * (top - v.ndim) + v.a.shape[1:]) if isinstance(v, Batch)
                else np.asarray(v) for v in items]
        return Batch(np.where(*arrs))

    @staticmethod
    def stack(items, axis=-1):
        """Stack per-path arrays of equal shape along a new per-path ``axis``."""
        arrs = _population_arrays(items)
        if arrs is None:
            return np.stack([np.asarray(i) for i in items], axis=axis)
        ax = axis + 1 if axis >= 0 else arrs[0].ndim + 1 + axis
        return Batch(np.stack(arrs, axis=ax))

    @staticmethod
    def concatenate(items, axis=0):
        arrs = _population_arrays(items)
        if arrs is None:
            return np.concatenate([np.asarray(i) for i in items], axis=axis)
        ax = axis + 1 if axis >= 0 else arrs[0].ndim + axis
        return Batch(np.concatenate(arrs, axis=ax))

    @staticmethod
    def smooth_norm(x, axis=-1):
        """The norm (the symbolic view adds a tiny constant under the root so it is differentiable at 0)."""
        return BatchNamespace.norm(x, axis)


# -------------------------------------------------------------------- symbolic


class Sym:
    """A CasADi matrix with numpy's shape rules: ``shape`` is ``()``, ``(k,)`` or ``(r, c)``.

    1-D vectors are stored as CasADi columns; a 1-D operand broadcasts over the
    rows of a 2-D one, as in numpy.
    """

    __slots__ = ("m", "shape")
    __array_priority__ = 1000

    def __init__(self, m, shape: tuple) -> None:
        self.m = m
        self.shape = tuple(shape)

    @property
    def ndim(self) -> int:
        return len(self.shape)

    def __len__(self) -> int:
        if not self.shape:
            raise ParameterError("a scalar has no length")
        return self.shape[0]

    def __getitem__(self, idx):
        if not isinstance(idx, tuple):
            idx = (idx,)
        if self.ndim == 1:
            if len(idx) != 1:
                raise ParameterError("too many indices for a 1-D symbolic vector")
            i = idx[0]
            if isinstance(i, (int, np.integer)):
                return Sym(self.m[_norm_index(i, self.shape[0]), 0], ())
            if isinstance(i, slice):
                r = range(*i.indices(self.shape[0]))
                return Sym(self.m[list(r), 0], (len(r),))
            raise ParameterError(f"unsupported symbolic index {i!r}")
        if self.ndim == 2:
            rows, cols = self.shape
            i = idx[0]
            j = idx[1] if len(idx) > 1 else slice(None)
            if len(idx) > 2:
                raise ParameterError("too many indices for a 2-D symbolic array")
            ri, rshape = _index_list(i, rows)
            ci, cshape = _index_list(j, cols)
            sub = self.m[ri, ci]
            shape = rshape + cshape
            if len(shape) == 1 and rshape == ():   # one row: a 1-D vector over columns
                return Sym(sub.T, shape)
            return Sym(sub, shape)
        raise ParameterError("a scalar cannot be indexed")

    @property
    def T(self) -> "Sym":
        if self.ndim == 2:
            return Sym(self.m.T, self.shape[::-1])
        return self

    def _bin(self, other, op, reverse=False):
        a, b, shape = _sym_aligned(self, other)
        return Sym(op(b, a) if reverse else op(a, b), shape)

    def __add__(self, o): return self._bin(o, lambda a, b: a + b)
    def __radd__(self, o): return self._bin(o, lambda a, b: a + b, True)
    def __sub__(self, o): return self._bin(o, lambda a, b: a - b)
    def __rsub__(self, o): return self._bin(o, lambda a, b: a - b, True)
    def __mul__(self, o): return self._bin(o, lambda a, b: a * b)
    def __rmul__(self, o): return self._bin(o, lambda a, b: a * b, True)
    def __truediv__(self, o): return self._bin(o, lambda a, b: a / b)
    def __rtruediv__(self, o): return self._bin(o, lambda a, b: a / b, True)
    def __pow__(self, o): return self._bin(o, lambda a, b: a ** b)
    def __rpow__(self, o): return self._bin(o, lambda a, b: a ** b, True)
    def __lt__(self, o): return self._bin(o, lambda a, b: a < b)
    def __le__(self, o): return self._bin(o, lambda a, b: a <= b)
    def __gt__(self, o): return self._bin(o, lambda a, b: a > b)
    def __ge__(self, o): return self._bin(o, lambda a, b: a >= b)
    def __neg__(self): return Sym(-self.m, self.shape)

    def __abs__(self):
        import casadi as ca

        return Sym(ca.fabs(self.m), self.shape)

    def __matmul__(self, o):
        return _sym_matmul(self, o)

    def __rmatmul__(self, o):
        return _sym_matmul(_as_sym(o), self)

    def __bool__(self):
        raise ParameterError("a term cannot branch on a value with `if`; use m.where(cond, a, b)")


def _norm_index(i: int, n: int) -> int:
    i = int(i)
    if not -n <= i < n:
        raise ParameterError(f"index {i} is out of range for length {n}")
    return i % n


def _index_list(i, n: int) -> tuple[list[int], tuple]:
    if isinstance(i, (int, np.integer)):
        return [_norm_index(i, n)], ()
    if isinstance(i, slice):
        r = list(range(*i.indices(n)))
        return r, (len(r),)
    raise ParameterError(f"unsupported symbolic index {i!r}")


def _as_sym(x) -> Sym:
    if isinstance(x, Sym):
        return x
    import casadi as ca

    a = np.asarray(x, dtype=float)
    if a.ndim == 0:
        return Sym(ca.DM(float(a)), ())
    if a.ndim == 1:
        return Sym(ca.DM(a.reshape(-1, 1)), a.shape)
    if a.ndim == 2:
        return Sym(ca.DM(a), a.shape)
    raise ParameterError("symbolic terms support arrays of at most 2 dimensions")


def _broadcast_to(s: Sym, shape: tuple):
    """CasADi matrix of ``s`` repeated to the 2-D (or 1-D) numpy ``shape``."""
    import casadi as ca

    if s.shape == shape or s.shape == ():
        return s.m
    if len(shape) == 1:
        if s.shape == (1,):
            return ca.repmat(s.m, shape[0], 1)
    elif len(shape) == 2:
        r, c = shape
        if s.shape in ((c,), (1, c)):
            row = s.m.T if s.ndim == 1 else s.m
            return ca.repmat(row, r, 1)
        if s.shape == (r, 1):
            return ca.repmat(s.m, 1, c)
        if s.shape == (1, 1) or s.shape == (1,):
            return ca.repmat(s.m, r, c)
    raise ParameterError(f"cannot broadcast symbolic shapes {s.shape} and {shape}")


def _broadcast_shape(a: tuple, b: tuple) -> tuple:
    try:
        return tuple(np.broadcast_shapes(a, b))
    except ValueError:
        raise ParameterError(f"shapes {a} and {b} do not broadcast") from None


def _sym_aligned(x, y):
    xs, ys = _as_sym(x), _as_sym(y)
    shape = _broadcast_shape(xs.shape, ys.shape)
    if len(shape) > 2:
        raise ParameterError("symbolic terms support arrays of at most 2 dimensions")
    return _broadcast_to(xs, shape), _broadcast_to(ys, shape), shape


def _sym_matmul(a, b):
    import casadi as ca

    a, b = _as_sym(a), _as_sym(b)
    if a.ndim == 2 and b.ndim == 2:
        return Sym(ca.mtimes(a.m, b.m), (a.shape[0], b.shape[1]))
    if a.ndim == 2 and b.ndim == 1:
        return Sym(ca.mtimes(a.m, b.m), (a.shape[0],))
    if a.ndim == 1 and b.ndim == 2:
        return Sym(ca.mtimes(a.m.T, b.m).T, (b.shape[1],))
    if a.ndim == 1 and b.ndim == 1:
        return Sym(ca.dot(a.m, b.m), ())
    raise ParameterError("matmul needs arrays, not scalars")


def _sym_unary(name):
    def f(x):
        import casadi as ca

        s = _as_sym(x)
        return Sym(getattr(ca, name)(s.m), s.shape)
    return staticmethod(f)


def _sym_binary(name):
    def f(x, y):
        import casadi as ca

        a, b, shape = _sym_aligned(x, y)
        return Sym(getattr(ca, name)(a, b), shape)
    return staticmethod(f)


def _fold(fn, cols):
    out = cols[0]
    for c in cols[1:]:
        out = fn(out, c)
    return out


class SymbolicNamespace:
    """CasADi with numpy's shape rules, over :class:`Sym` (and plain numbers)."""

    name = "symbolic"
    pi = np.pi
    inf = np.inf
    EPS = 1e-12  # under the root of smooth_norm: differentiable where a segment has length 0
    sqrt = _sym_unary("sqrt")
    exp = _sym_unary("exp")
    log = _sym_unary("log")
    sin = _sym_unary("sin")
    cos = _sym_unary("cos")
    tan = _sym_unary("tan")
    tanh = _sym_unary("tanh")
    arcsin = asin = _sym_unary("asin")
    arccos = acos = _sym_unary("acos")
    abs = fabs = _sym_unary("fabs")
    arctan2 = atan2 = _sym_binary("atan2")
    fmax = maximum = _sym_binary("fmax")
    fmin = minimum = _sym_binary("fmin")

    @staticmethod
    def hypot(x, y):
        return SymbolicNamespace.sqrt(x * x + y * y)

    @staticmethod
    def _reduce(x, axis, whole, along_rows, along_cols):
        s = _as_sym(x)
        if s.ndim == 0:
            return s
        if axis is None or s.ndim == 1:
            if axis not in (None, 0, -1):
                raise ParameterError(f"axis {axis} is out of range for a 1-D vector")
            return Sym(whole(s.m), ())
        axis = int(axis)
        if axis in (0, -2):
            return Sym(along_rows(s.m), (s.shape[1],))
        if axis in (1, -1):
            return Sym(along_cols(s.m), (s.shape[0],))
        raise ParameterError(f"axis {axis} is out of range for a 2-D array")

    @staticmethod
    def sum(x, axis=None):
        import casadi as ca

        return SymbolicNamespace._reduce(x, axis, lambda m: ca.sum1(ca.sum2(m)), lambda m: ca.sum1(m).T,
                                         lambda m: ca.sum2(m))

    @staticmethod
    def mean(x, axis=None):
        s = _as_sym(x)
        total = SymbolicNamespace.sum(s, axis)
        count = int(np.prod(s.shape)) if axis is None or s.ndim == 1 else s.shape[int(axis) % 2]
        return total / max(count, 1)

    @staticmethod
    def _extreme(x, axis, whole: str, pair: str):
        import casadi as ca

        both = getattr(ca, pair)
        return SymbolicNamespace._reduce(
            x, axis, getattr(ca, whole),
            lambda m: _fold(both, [m[i, :] for i in range(m.shape[0])]).T,
            lambda m: _fold(both, [m[:, j] for j in range(m.shape[1])]))

    @staticmethod
    def max(x, axis=None):
        return SymbolicNamespace._extreme(x, axis, "mmax", "fmax")

    @staticmethod
    def min(x, axis=None):
        return SymbolicNamespace._extreme(x, axis, "mmin", "fmin")

    @staticmethod
    def sumsq(x, axis=None):
        s = _as_sym(x)
        return SymbolicNamespace.sum(s * s, axis)

    @staticmethod
    def norm(x, axis=-1):
        return SymbolicNamespace.sqrt(SymbolicNamespace.sum(x * x, axis))

    @staticmethod
    def smooth_norm(x, axis=-1):
        return SymbolicNamespace.sqrt(SymbolicNamespace.sum(x * x, axis) + SymbolicNamespace.EPS)

    @staticmethod
    def diff(x, axis=0):
        s = _as_sym(x)
        if s.ndim == 1 or axis in (0, -2) and s.ndim == 2:
            return s[1:] - s[:-1]
        if s.ndim == 2 and axis in (1, -1):
            return s[:, 1:] - s[:, :-1]
        raise ParameterError(f"diff along axis {axis} of shape {s.shape} is not supported")

    @staticmethod
    def where(cond, a, b):
        import casadi as ca

        c = _as_sym(cond)
        shape = _broadcast_shape(_broadcast_shape(c.shape, _as_sym(a).shape), _as_sym(b).shape)
        return Sym(ca.if_else(_broadcast_to(c, shape), _broadcast_to(_as_sym(a), shape),
                              _broadcast_to(_as_sym(b), shape)), shape)

    @staticmethod
    def stack(items, axis=-1):
        import casadi as ca

        syms = [_as_sym(i) for i in items]
        if any(s.ndim != 1 for s in syms) or len({s.shape for s in syms}) != 1:
            raise ParameterError("symbolic stack takes 1-D vectors of one length")
        if axis in (-1, 1):
            return Sym(ca.horzcat(*[s.m for s in syms]), (syms[0].shape[0], len(syms)))
        return Sym(ca.horzcat(*[s.m for s in syms]).T, (len(syms), syms[0].shape[0]))

    @staticmethod
    def concatenate(items, axis=0):
        import casadi as ca

        syms = [_as_sym(i) for i in items]
        if all(s.ndim == 1 for s in syms):
            return Sym(ca.vertcat(*[s.m for s in syms]), (sum(s.shape[0] for s in syms),))
        if all(s.ndim == 2 for s in syms) and axis in (0, -2):
            return Sym(ca.vertcat(*[s.m for s in syms]), (sum(s.shape[0] for s in syms), syms[0].shape[1]))
        raise ParameterError("symbolic concatenate takes 1-D vectors, or 2-D arrays along axis 0")


BATCHED = BatchNamespace()
SYMBOLIC = SymbolicNamespace()
