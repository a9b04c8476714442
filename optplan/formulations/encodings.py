"""Path encodings: how a row ``x`` of a population ``X`` of shape ``(n, d)`` becomes a path.

Every encoding decodes a whole population at once into ``(n, N, 2)`` polylines
(metres, start first, goal last) with a fixed ``N``, so objective terms are plain
array operations over the population.

* :class:`ColumnNodes` — one node per grid column between start and goal
  (chen2025 §4.3.1; the usual sparrow-search grid encoding of hou2024 §4.1).
* :class:`FreeWaypoints` — ``m`` free 2-D waypoints between start and goal.
* :class:`SplinePath` — ``m`` handle points; the path is the cubic spline through
  start, handles and goal, sampled densely (yang2023 eq 3-4).
* :class:`GeneralPath` — ``m`` via points joined by geodesic legs over the world's roadmap:
  every path class on every grid map and circle world, always collision-free.
"""
from __future__ import annotations

import hashlib
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError
from ..world.derived import DerivedStore
from ..world.polyline import repeats_to_end
from ..world.roadmap import ROADMAP_CORNERS

_DERIVED = DerivedStore("formulations.encodings")  # this module's data derived from worlds


# Segment tables by map content, kept across map objects in this process (a few maps'
# worth: a 90x90 map's tables are about 10 MB). Penetration tables depend only on the
# clearance and the encoding's samples per segment, both part of the key.
_SHARED_TABLES: OrderedDict = OrderedDict()
_SHARED_TABLES_MAX = 8


# the feasible sampler of maps taller than SAMPLE_WINDOW_ROWS decides the moves within
# SAMPLE_WINDOW rows of where each move aims (ColumnSegments.moves)
SAMPLE_WINDOW_ROWS = 256
SAMPLE_WINDOW = 64


def clear_shared_tables() -> None:
    """Forget the segment tables kept across map objects (for cold-start timings)."""
    _SHARED_TABLES.clear()


def _map_fingerprint(grid) -> tuple:
    """Content key of a grid map: occupancy digest, shape, resolution and origin."""
    fp = _DERIVED.of(grid).get("fingerprint")
    if fp is None:
        digest = hashlib.sha1(np.ascontiguousarray(grid.occ, dtype=np.uint8).tobytes()).hexdigest()
        fp = _DERIVED.of(grid)["fingerprint"] = (digest, grid.occ.shape, float(grid.resolution),
                                           tuple(float(o) for o in grid.origin))
    return fp


@dataclass
class PathEncoding:
    """Base class: subclasses set ``lower``/``upper`` (shape ``(d,)``) and implement ``decode``."""

    world: object
    start: np.ndarray
    goal: np.ndarray
    lower: np.ndarray = field(init=False)
    upper: np.ndarray = field(init=False)

    @property
    def dim(self) -> int:
        return int(self.lower.size)

    def decode(self, X: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def waypoints(self, x: np.ndarray) -> np.ndarray:
        """The path's defining points for one individual (what is reported before refinement)."""
        return self.decode(np.asarray(x, dtype=float)[None, :])[0]

    def _frame(self, inner: np.ndarray) -> np.ndarray:
        """Put start and goal around ``inner`` of shape ``(n, m, 2)``."""
        n = inner.shape[0]
        s = np.broadcast_to(self.start, (n, 1, 2))
        g = np.broadcast_to(self.goal, (n, 1, 2))
        return np.concatenate([s, inner, g], axis=1)


@dataclass
class ColumnNodes(PathEncoding):
    """One node per grid column strictly between the start and goal columns.

    ``x[j]`` is the row coordinate (grid units, ``[0, height)``) of the node in the
    ``j``-th column met when walking from the start column to the goal column. With
    ``snap=True`` the node is the centre of the cell ``floor(x[j])`` (the papers'
    grid nodes); with ``snap=False`` it keeps the continuous row coordinate.
    """

    snap: bool = True
    columns: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        grid = self.world
        if not getattr(grid, "is_grid", False):
            raise ParameterError("ColumnNodes needs a GridMap")
        cs, cg = (int(c) for c in (grid.cell_of(self.start)[0], grid.cell_of(self.goal)[0]))
        step = 1 if cg >= cs else -1
        self.columns = np.arange(cs + step, cg, step, dtype=np.int64)
        self.lower = np.zeros(self.columns.size)
        self.upper = np.full(self.columns.size, grid.height - 1e-9)

    def decode(self, X: np.ndarray) -> np.ndarray:
        grid = self.world
        X = np.asarray(X, dtype=float).reshape(-1, self.dim)
        rows = np.clip(X, 0.0, grid.height - 1e-9)
        rows = np.floor(rows) + 0.5 if self.snap else rows
        return self._paths_from_rows(rows)

    def _paths_from_rows(self, rows: np.ndarray) -> np.ndarray:
        """Paths for grid-unit node rows ``(n, d)`` (cell centres when snapped)."""
        grid = self.world
        n = len(rows)
        P = np.empty((n, self.dim + 2, 2))
        P[:, 0] = self.start
        P[:, -1] = self.goal
        P[:, 1:-1, 0] = (self.columns + 0.5) * grid.resolution + grid.origin[0]
        P[:, 1:-1, 1] = rows * grid.resolution + grid.origin[1]
        return P

    penetration_samples = 8

    def repair(self, X: np.ndarray) -> np.ndarray:
        """Move every node to the nearest free cell of its column (the papers draw
        nodes among free cells; keeping them there is a repair, not a constraint)."""
        key = ("column_nearest_free", self.columns.tobytes())
        cache = _DERIVED.of(self.world)
        if key not in cache:
            occ = self.world.occ[:, self.columns]            # (H, d): column j's cells
            H = occ.shape[0]
            rows = np.arange(H)
            free_rows = [np.nonzero(~occ[:, j])[0] for j in range(occ.shape[1])]
            table = np.empty((occ.shape[1], H))
            for j, fr in enumerate(free_rows):               # once per map, not per evaluation
                table[j] = fr[np.abs(fr[None, :] - rows[:, None]).argmin(axis=1)] + 0.5 if fr.size else rows + 0.5
            cache[key] = table
        table = cache[key]
        r = self.rows_of(X)
        # flat gather: entry (j, r) of the (d, H) table
        snapped = table.take(r + self._column_offsets())
        if not self.snap:
            # keep the continuous offset inside the chosen free cell
            return snapped - 0.5 + (np.asarray(X) - np.floor(np.asarray(X)))
        return snapped

    def _column_offsets(self) -> np.ndarray:
        """``j * H`` for each column ``j``: flat offsets into ``(d, H)`` per-column tables."""
        off = getattr(self, "_col_offsets", None)
        if off is None:
            off = self._col_offsets = np.arange(self.dim, dtype=np.int64) * self.world.height
        return off

    def rows_of(self, X: np.ndarray) -> np.ndarray:
        """Integer cell rows of the nodes, ``(n, d)``."""
        # on [0, H-1] truncation is floor; bounding first also maps negatives to row 0
        return np.minimum(np.maximum(np.asarray(X, dtype=float), 0.0), self.world.height - 1).astype(np.int64)

    def segment_tables(self, clearance: float, penetration_fn=None) -> dict:
        """Per-segment collision (and penetration) values for every pair of node rows.

        With snapped nodes a path has only ``height**2`` possible segments between
        two neighbouring columns, so the exact segment rule is evaluated once per
        map for all of them and population evaluation becomes a table lookup.
        Returns arrays ``inner[j, r1, r2]`` (segment from column j to j+1),
        ``first[r]`` (start to the first node) and ``last[r]`` (last node to goal).
        Cached per clearance.
        """
        if not self.snap:
            raise ParameterError("segment tables exist only for snapped column nodes")
        key = ("column_tables", float(clearance), penetration_fn is not None)
        cache = _DERIVED.of(self.world)
        if key in cache and cache[key]["columns"].shape == self.columns.shape \
                and np.array_equal(cache[key]["columns"], self.columns) \
                and np.array_equal(cache[key]["ends"], np.concatenate([self.start, self.goal])):
            return cache[key]
        # the same map loaded again (another run, another task in a worker) reuses its tables
        shared_key = (_map_fingerprint(self.world), key, self.penetration_samples, self.columns.tobytes(),
                      np.concatenate([self.start, self.goal]).tobytes())
        if shared_key in _SHARED_TABLES:
            cache[key] = _SHARED_TABLES[shared_key]
            return cache[key]
        grid, H, d = self.world, self.world.height, self.dim
        rows = np.arange(H) + 0.5
        col_x = self.columns + 0.5
        out = {"columns": self.columns.copy(), "ends": np.concatenate([self.start, self.goal])}

        def evaluate(a, b):
            A, B = grid.to_world(a), grid.to_world(b)
            coll = ~np.asarray(grid.segments_free(A, B, clearance))
            if penetration_fn is None:
                return coll.astype(float), None
            return coll.astype(float), penetration_fn(np.stack([A, B], axis=1))

        g_start, g_goal = grid.to_grid(self.start), grid.to_grid(self.goal)
        if d == 0:
            c, p = evaluate(g_start[None], g_goal[None])
            out.update(direct=c[0], direct_pen=None if p is None else p[0])
        else:
            r1, r2 = np.meshgrid(rows, rows, indexing="ij")
            if d > 1:
                a = np.stack([np.repeat(col_x[:-1], H * H), np.tile(r1.ravel(), d - 1)], axis=1)
                b = np.stack([np.repeat(col_x[1:], H * H), np.tile(r2.ravel(), d - 1)], axis=1)
                c, p = evaluate(a, b)
                out["inner"] = c.reshape(d - 1, H, H)
                out["inner_pen"] = None if p is None else p.reshape(d - 1, H, H)
            else:
                out["inner"] = np.zeros((0, H, H))
                out["inner_pen"] = None if penetration_fn is None else np.zeros((0, H, H))
            first = np.stack([np.full(H, col_x[0]), rows], axis=1)
            last = np.stack([np.full(H, col_x[-1]), rows], axis=1)
            c, p = evaluate(np.repeat(g_start[None], H, 0), first)
            out["first"], out["first_pen"] = c, p
            c, p = evaluate(last, np.repeat(g_goal[None], H, 0))
            out["last"], out["last_pen"] = c, p
        cache[key] = out
        _SHARED_TABLES[shared_key] = out
        while len(_SHARED_TABLES) > _SHARED_TABLES_MAX:
            _SHARED_TABLES.popitem(last=False)
        return out

    def lookup(self, tables: dict, X: np.ndarray, what: str = "") -> np.ndarray:
        """Sum of a per-segment table over each individual's path, ``(n,)``."""
        X = np.asarray(X, dtype=float).reshape(-1, self.dim)
        if self.dim == 0:
            return np.full(len(X), tables["direct" + what])
        return self.lookup_rows(tables, self.rows_of(X), what)

    def lookup_rows(self, tables: dict, r: np.ndarray, what: str = "") -> np.ndarray:
        """:meth:`lookup` for integer rows already computed, ``(n, d)``."""
        if self.dim == 0:
            return np.full(len(r), tables["direct" + what])
        total = tables["first" + what][r[:, 0]] + tables["last" + what][r[:, -1]]
        if self.dim > 1:
            H = self.world.height
            # one flat gather: entry (j, r1, r2) of the (d-1, H, H) table
            flat = (np.arange(self.dim - 1) * (H * H))[None, :] + r[:, :-1] * H + r[:, 1:]
            total = total + np.take(tables["inner" + what].reshape(-1), flat).sum(axis=1)
        return total

    # ---------------------------------------------------- flat segment layout
    # Every per-segment quantity of snapped column nodes lives in one flat array
    # ``[first (H) | inner ((d-1) * H * H) | last (H)]``, so a population's segments
    # are one ``(n, d + 1)`` index array and any table sum is one gather and one sum.

    def segment_index(self, rows: np.ndarray) -> np.ndarray:
        """Flat indices ``(n, d + 1)`` of each individual's segments (start->node 1, ...,
        node d->goal) in the layout above, for integer rows ``(n, d)``; needs ``d >= 1``."""
        H, d = self.world.height, self.dim
        layout = getattr(self, "_layout", None)
        if layout is None:
            # segment k joins padded rows k and k+1 of [0, rows, 0]: index = base + mult * a + b
            mult = np.concatenate([[0], np.full(d - 1, H), [1]]).astype(np.int64)
            base = np.concatenate([[0], H + np.arange(d - 1) * (H * H), [H + (d - 1) * H * H]]).astype(np.int64)
            layout = self._layout = (mult, base)
        padded = np.zeros((len(rows), d + 2), dtype=np.int64)
        padded[:, 1:-1] = rows
        idx = padded[:, :-1] * layout[0]
        idx += padded[:, 1:]
        idx += layout[1]
        return idx

    @staticmethod
    def flat_table(tables: dict, what: str = "") -> np.ndarray:
        """One of :meth:`segment_tables`' arrays (``what`` = ``""`` or ``"_pen"``) in the flat layout."""
        return np.concatenate([tables["first" + what], tables["inner" + what].reshape(-1), tables["last" + what]])

    def segment_lengths(self) -> np.ndarray:
        """Length in metres of every possible segment, in the flat layout (``d >= 1``).

        Computed from the same world coordinates :meth:`decode` produces, so a
        table sum equals ``terms.length`` of the decoded path."""
        return np.hypot(*self._segment_deltas())

    def segment_headings(self) -> np.ndarray:
        """Heading (radians, ``atan2(dy, dx)``) of every possible segment, in the flat layout;
        computed once per encoding from the same coordinates as :meth:`segment_lengths`."""
        h = getattr(self, "_headings", None)
        if h is None:
            dx, dy = self._segment_deltas()
            h = self._headings = np.arctan2(dy, dx)
        return h

    def _segment_deltas(self) -> tuple[np.ndarray, np.ndarray]:
        grid, H = self.world, self.world.height
        res, (ox, oy) = grid.resolution, grid.origin
        ys = (np.arange(H) + 0.5) * res + oy
        xs = (self.columns + 0.5) * res + ox
        d = self.dim
        dx = np.concatenate([np.full(H, xs[0] - self.start[0]),
                             np.repeat(np.diff(xs), H * H), np.full(H, self.goal[0] - xs[-1])])
        dy_inner = np.broadcast_to(ys[None, :] - ys[:, None], (d - 1, H, H)).reshape(-1)  # (r1, r2): ys[r2] - ys[r1]
        dy = np.concatenate([ys - self.start[1], dy_inner, self.goal[1] - ys])
        return dx, dy

    def feasible_transitions(self, clearance: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Boolean masks of collision-free moves: ``first[r]``, ``inner[j, r1, r2]``,
        ``last[r]``, pruned backwards so that every allowed move can still reach
        the goal (a dynamic programme over the columns)."""
        key = ("column_transitions", float(clearance), self.columns.tobytes(),
               np.concatenate([self.start, self.goal]).tobytes())
        cache = _DERIVED.of(self.world)
        if key in cache:
            return cache[key]
        t = self.segment_tables(clearance)
        first, inner, last = t["first"] == 0, t["inner"] == 0, t["last"] == 0
        alive = last.copy()                       # rows of the last column that reach the goal
        pruned = np.zeros_like(inner)
        for j in range(self.dim - 2, -1, -1):
            pruned[j] = inner[j] & alive[None, :]
            alive = pruned[j].any(axis=1)
        cache[key] = (first & alive, pruned, last)  # fixed per map: GA operators reuse it every generation
        return cache[key]

    def optimal_rows(self, segment_cost: np.ndarray | None = None, clearance: float = 0.0) -> tuple[float, np.ndarray]:
        """Exact minimum of a per-segment cost over every collision-free column-node path.

        A dynamic programme over the columns (Viterbi): the best cost of reaching each
        row of column ``j + 1`` is the minimum over the rows of column ``j`` plus the
        segment between them. ``segment_cost`` is in the flat layout (default
        :meth:`segment_lengths`, metres). This is the best any solver of this encoding
        can return before post-processing; terms over segment pairs (turns) are not
        per-segment and are not covered. Returns ``(cost, rows)`` with integer rows ``(d,)``.

        Raises InfeasibleQueryError when no collision-free column-node path exists.
        """
        from ..errors import InfeasibleQueryError

        H, d = self.world.height, self.dim
        if d == 0:
            raise ParameterError("optimal_rows needs at least one column between start and goal")
        cost = self.segment_lengths() if segment_cost is None else np.asarray(segment_cost, dtype=float)
        first, inner, last = self.feasible_transitions(clearance)
        best = np.where(first, cost[:H], np.inf)              # best cost to each row of column 0
        inner_cost = cost[H:H + (d - 1) * H * H].reshape(max(d - 1, 0), H, H)
        back = np.empty((max(d - 1, 0), H), dtype=np.int64)
        for j in range(d - 1):
            total = best[:, None] + np.where(inner[j], inner_cost[j], np.inf)
            back[j] = total.argmin(axis=0)
            best = total.min(axis=0)
        best = best + np.where(last, cost[-H:], np.inf)
        r = int(best.argmin())
        if not np.isfinite(best[r]):
            raise InfeasibleQueryError("no collision-free path with one node per column exists between start and goal")
        rows = np.empty(d, dtype=np.int64)
        rows[-1] = r
        for j in range(d - 2, -1, -1):
            rows[j] = back[j, rows[j + 1]]
        return float(best[r]), rows

    def sample_feasible(self, n: int, rng: np.random.Generator, clearance: float = 0.0,
                        spread: float = 2.0) -> np.ndarray:
        """``n`` random collision-free individuals (rows + 0.5).

        Each move to the next column is drawn among the moves that can still reach
        the goal, with weight ``exp(-|row change| / spread)`` so that paths wander
        rather than zigzag across the map (``spread=inf`` is uniform).

        Raises InfeasibleQueryError when no path with one node per column exists
        (the map needs a path that turns back in x; use another encoding or ``aco``).
        """
        from ..errors import InfeasibleQueryError

        from .segment_store import column_segments

        # the moves are computed for the rows drawn (the same masks as feasible_transitions)
        moves = column_segments(self, clearance)
        first = moves.first_moves()
        if not first.any():
            raise InfeasibleQueryError("no collision-free path with one node per column exists between start and goal; "
                                       "this encoding cannot represent a solution (try encoding='waypoints' or algorithm='aco')")
        rows = np.empty((n, self.dim), dtype=np.int64)

        H = self.world.height
        levels = np.arange(H)

        def pick(mask: np.ndarray, centre: np.ndarray) -> np.ndarray:
            # roulette over allowed rows, weighted by closeness to ``centre``
            w = mask * np.exp(-np.abs(levels[None, :] - centre[:, None]) / spread)
            cum = np.cumsum(w, axis=1)
            r = rng.random(len(mask)) * cum[:, -1]
            return np.minimum((cum < r[:, None]).sum(axis=1), H - 1)

        start_row = np.floor(self.world.to_grid(self.start)[1])
        goal_row = np.floor(self.world.to_grid(self.goal)[1])
        d = self.dim
        # a tall map decides only the moves near the aim (far ones weigh < exp(-64 / spread))
        window = SAMPLE_WINDOW if H > SAMPLE_WINDOW_ROWS else None
        # aim each move at the straight line from the current row to the goal row
        rows[:, 0] = pick(np.broadcast_to(first, (n, H)), np.full(n, start_row + (goal_row - start_row) / (d + 1)))
        for j in range(d - 1):
            aim = rows[:, j] + (goal_row - rows[:, j]) / (d - j)
            rows[:, j + 1] = pick(moves.moves(j, rows[:, j], aim, window), aim)
        return rows + 0.5


@dataclass
class FreeWaypoints(PathEncoding):
    """``m`` free waypoints; ``x = (x1, y1, ..., xm, ym)`` in metres inside the world bounds."""

    m: int = 3
    penetration_samples = 8

    def __post_init__(self) -> None:
        if int(self.m) < 1:
            raise ParameterError(f"number of waypoints m must be >= 1, got {self.m}")
        xmin, ymin, xmax, ymax = self.world.bounds
        self.lower = np.tile([xmin, ymin], self.m).astype(float)
        self.upper = np.tile([xmax, ymax], self.m).astype(float)

    def decode(self, X: np.ndarray) -> np.ndarray:
        X = np.asarray(X, dtype=float).reshape(-1, self.dim)
        return self._frame(X.reshape(X.shape[0], self.m, 2))


@dataclass
class SplinePath(FreeWaypoints):
    """Cubic spline through start, ``m`` handle points and goal (yang2023 eq 3-4).

    Its polyline has many short segments, so one penetration sample per segment
    resolves intrusions as finely as eight per segment do on waypoint paths.

    The spline is parametrised uniformly in ``[0, 1]`` over start, handles and goal
    and sampled at ``samples`` points; the polyline through the samples is the
    path whose length is eq 4's spline length. ``waypoints`` returns the handles.
    """

    samples: int = 100
    penetration_samples = 1

    def __post_init__(self) -> None:
        super().__post_init__()
        if int(self.samples) < 3:
            raise ParameterError(f"samples must be >= 3, got {self.samples}")
        from scipy.interpolate import CubicSpline

        # the spline is linear in its data: precompute the sampling matrix once
        knots = np.linspace(0.0, 1.0, self.m + 2)
        t = np.linspace(0.0, 1.0, self.samples)
        bc = "not-a-knot" if self.m + 2 > 3 else "natural"
        self._basis = CubicSpline(knots, np.eye(self.m + 2), axis=0, bc_type=bc)(t)  # (samples, m+2)

    def handles(self, X: np.ndarray) -> np.ndarray:
        """Start, handle points and goal, ``(n, m + 2, 2)``."""
        return super().decode(X)

    def decode(self, X: np.ndarray) -> np.ndarray:
        H = self.handles(X)
        return np.einsum("sk,nkc->nsc", self._basis, H)

    def waypoints(self, x: np.ndarray) -> np.ndarray:
        return self.decode(np.asarray(x, dtype=float)[None, :])[0]


def _join_through_ends(D: np.ndarray, succ: np.ndarray, M: int) -> None:
    """Complete the geodesics of roadmap nodes ``0..M-1`` through the end points ``S = M``
    and ``G = M + 1`` in place: a start (or goal) can see corners of two parts of the
    roadmap that see no corner of each other, and a leg between those parts runs through
    it. Only pairs the roadmap does not join change; the first hop is the first hop
    towards that end, so each step of a walk shortens what is left."""
    S, G = M, M + 1
    sg = D[S, G]
    # the nodes whose own way to an end avoids the other end: a walk towards that end
    # from them reaches it without passing through the other
    own_s, own_g = np.isfinite(D[:M, S]), np.isfinite(D[:M, G])
    # a node to one end through the other end
    for end, other in ((G, S), (S, G)):
        via = D[:M, other] + sg
        i = np.nonzero(~np.isfinite(D[:M, end]) & np.isfinite(via))[0]
        D[i, end] = D[end, i] = via[i]
        succ[i, end] = succ[i, other]
        succ[end, i] = succ[end, other]
    apart = ~np.isfinite(D[:M, :M])
    if not apart.any():
        return
    i, j = np.nonzero(apart)
    through_s = np.where(own_s[i], D[i, S] + D[S, j], np.inf)
    through_g = np.where(own_g[i], D[i, G] + D[G, j], np.inf)
    ok = np.isfinite(np.minimum(through_s, through_g))
    i, j, through_s, through_g = i[ok], j[ok], through_s[ok], through_g[ok]
    by_s = through_s <= through_g
    D[i, j] = np.where(by_s, through_s, through_g)
    succ[i, j] = np.where(by_s, succ[i, S], succ[i, G])


# grid maps with more convex corners than this get the local graph and landmarks
# (:class:`_LandmarkLegs`) instead of all-pairs geodesics over every corner (:class:`_CornerLegs`)
EXACT_CORNERS = ROADMAP_CORNERS
# the landmarks via points snap to on large maps: about LANDMARK_ROWS / graph nodes of them
# (a Dijkstra row each: time and memory stay bounded), within LANDMARKS
LANDMARK_ROWS = 3_000_000
LANDMARKS = (32, 144)
# times the local graph's radius is doubled when it does not join start and goal, before the
# exact corner legs decide (they say whether the goal is reachable at all)
WIDENINGS = 2


class _CornerLegs:
    """Legs over the world's :class:`~optplan.world.roadmap.Roadmap`: via points snap to any
    corner, legs are exact geodesics (all-pairs tables over the corners, start and goal)."""

    exact = True

    def __init__(self, world, start, goal, clearance: float) -> None:
        from ..errors import InfeasibleQueryError
        from ..world.roadmap import Roadmap

        # circle worlds: fewer polygon vertices per disc when there are many discs, so the
        # all-pairs tables stay near 2000 nodes (paths around discs get a little longer)
        ring = None if world.is_grid else int(np.clip(2000 // max(len(world.circles), 1), 8, 32))
        rm = self.roadmap = Roadmap.of(world, clearance, ring)
        M = len(rm.nodes)
        ds, es = rm.attach(start)
        dg, eg = rm.attach(goal)
        direct = bool(rm.visible(start[None], goal[None])[0])
        via = ds + dg
        k = int(via.argmin()) if M else -1
        sg = float(np.hypot(*(goal - start))) if direct else (float(via[k]) if M else np.inf)
        if not np.isfinite(sg):
            raise InfeasibleQueryError("the goal is not reachable from the start through free space "
                                       "(no chain of visible obstacle corners joins them)")
        S, G = M, M + 1
        D = np.full((M + 2, M + 2), np.inf)
        D[:M, :M] = rm.dist
        D[S, :M], D[:M, S] = ds, ds
        D[G, :M], D[:M, G] = dg, dg
        D[S, G] = D[G, S] = sg
        D[S, S] = D[G, G] = 0.0
        succ = np.full((M + 2, M + 2), -1, dtype=np.int64)
        succ[:M, :M] = rm.succ
        ar = np.arange(M)
        for e, (d, ent) in ((S, (ds, es)), (G, (dg, eg))):
            ok = ent >= 0
            succ[e, :M] = np.where(ok, ent, -1)
            # from node i towards the end: along the roadmap to the node the end enters by, then to it
            succ[:M, e] = np.where(ok, np.where(ent == ar, e, rm.succ[ar, np.maximum(ent, 0)]), -1)
        succ[S, S], succ[G, G] = S, G
        succ[S, G] = G if direct else es[k]
        succ[G, S] = S if direct else eg[k]
        _join_through_ends(D, succ, M)
        self.table, self.succ = D, succ
        self.points = np.vstack([rm.nodes, start[None], goal[None]]) if M else np.stack([start, goal])
        self.path_points = self.points
        self.snap_path = np.arange(len(self.points))

    def walk(self, i: np.ndarray, j: np.ndarray) -> np.ndarray:
        """Path-point sequences ``(n, L)`` of the legs ``i[r] -> j[r]`` (snap indices), each
        padded with its end."""
        from ..world.roadmap import walk_legs

        return walk_legs(self.succ, i, j)


class _LandmarkLegs:
    """Legs on grid maps with many corners: via points snap to a few dozen to :data:`LANDMARKS`
    landmarks (lattice points of the :class:`~optplan.world.roadmap.LocalGraph` spread over the
    map) or to the start or goal, and a leg is the shortest way over the local graph.

    Per map (kept with the graph): a Dijkstra row per landmark over the local graph. Per query:
    the start and goal joined to every node they see, and a Dijkstra row from each. A leg that
    ends at the start or goal is walked on that end's row (the graph is undirected), any other
    on its first landmark's row; so legs between landmarks do not pass through the start or
    goal. No all-pairs table over the corners. Legs bend at lattice points as well as at
    corners, so they are a few per cent longer than the exact geodesics; every one is
    collision-free by the exact segment rule, as every edge of the graph is."""

    exact = False

    def __init__(self, world, start, goal, clearance: float) -> None:
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import dijkstra

        from ..world.roadmap import LocalGraph, tangent_at

        radius = None
        for _ in range(WIDENINGS + 1):
            lg = LocalGraph.of(world, clearance, radius)
            N = len(lg.nodes)
            S, G = N, N + 1
            # the ends see any node, however far
            pairs, weights = [lg.edges], [lg.weights]
            for e, p in ((S, start), (G, goal)):
                d = (lg.nodes - p) / world.resolution
                idx = np.nonzero(tangent_at(d, lg.quadrants))[0]
                idx = idx[~_hidden_from(world, p, d[idx])]
                idx = idx[world.segments_free(np.broadcast_to(p, (len(idx), 2)), lg.nodes[idx], clearance)]
                pairs.append(np.stack([np.full(len(idx), e), idx], axis=1))
                weights.append(np.maximum(np.hypot(*(lg.nodes[idx] - p).T), 1e-12))
            I, w = np.concatenate(pairs), np.concatenate(weights)
            if world.segments_free(start[None], goal[None], clearance)[0]:
                I = np.vstack([I, [[S, G]]])
                w = np.r_[w, max(float(np.hypot(*(goal - start))), 1e-12)]
            graph = coo_matrix((w, (I[:, 0], I[:, 1])), shape=(N + 2, N + 2)).tocsr()
            graph = (graph + graph.T).tocsr()   # both directions stored: Dijkstra runs faster than undirected
            end_dist, end_pred = dijkstra(graph, directed=True, indices=[S, G], return_predecessors=True)
            if np.isfinite(end_dist[0, G]):
                break
            radius = 2.0 * lg.radius   # widen the local edges, a few times at most
        else:
            raise _NotJoined
        marks, mark_dist, mark_pred = lg.landmark_rows(int(np.clip(LANDMARK_ROWS // max(N, 1), *LANDMARKS)))
        K = len(marks)
        self.graph_radius = lg.radius
        self.sources = np.r_[marks, S, G].astype(np.int64)       # snap node -> path point
        T = np.empty((K + 2, K + 2))
        T[:K, :K] = mark_dist[:, marks]
        T[K:, :] = end_dist[:, self.sources]
        T[:K, K:] = T[K:, :K].T
        self.table = T
        self.K = K
        self.mark_pred, self.end_pred = mark_pred, end_pred
        self.points = np.vstack([lg.nodes[marks], start[None], goal[None]])
        self.path_points = np.vstack([lg.nodes, start[None], goal[None]])
        self.snap_path = self.sources

    def walk(self, i: np.ndarray, j: np.ndarray) -> np.ndarray:
        """Path-point sequences ``(n, L)`` of the legs ``i[r] -> j[r]`` (snap indices), each
        padded with its end: a row's predecessors walked back from the other end of the leg."""
        i = np.asarray(i, dtype=np.int64).ravel()
        j = np.asarray(j, dtype=np.int64).ravel()
        K = self.K
        # a leg to an end from a landmark is walked on the end's row, then read backwards
        flip = (i < K) & (j >= K)
        row = np.where(flip, j, i)
        first, cur = self.sources[row], self.sources[np.where(flip, i, j)].copy()
        back = [cur.copy()]
        while np.any(cur != first):
            go = np.nonzero(cur != first)[0]
            r = row[go]
            on_end = r >= K
            nxt = np.empty(len(go), dtype=np.int64)
            nxt[on_end] = self.end_pred[r[on_end] - K, cur[go[on_end]]]
            nxt[~on_end] = self.mark_pred[r[~on_end], cur[go[~on_end]]]
            if np.any(nxt < 0):
                raise ParameterError("roadmap leg between unconnected nodes")
            cur[go] = nxt
            back.append(cur.copy())
        back = np.stack(back, axis=1)                       # (n, L): other end ... row's node, padded with it
        fwd = back[:, ::-1]                                 # row's node (repeated) ... other end
        shift = (fwd == first[:, None]).sum(axis=1) - 1     # leading copies of the row's node to drop
        col = np.minimum(np.arange(fwd.shape[1])[None, :] + shift[:, None], fwd.shape[1] - 1)
        fwd = np.take_along_axis(fwd, col, axis=1)
        return np.where(flip[:, None], back, fwd)


def _hidden_from(grid, p: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Whether the points at offsets ``d`` (grid units) from ``p`` (metres) lie behind a blocked
    cell near ``p`` (:class:`~optplan.world.shadows.Shadows`): the segment to them enters that
    cell's interior, so the exact rule refuses it at any clearance. Others may still be hidden."""
    from ..world.shadows import DIST_SLACK, Shadows, direction

    u = grid.to_grid(np.asarray(p, float)[None])
    sh = Shadows(grid.occ, u, np.zeros((1, 2), dtype=np.int64))
    out = np.zeros(len(d), dtype=bool)
    if sh.empty:
        return out
    far = np.nonzero(np.hypot(d[:, 0], d[:, 1]) > sh.reach[0] + DIST_SLACK)[0]
    out[far] = sh.covers(np.zeros(len(far), dtype=np.int64), direction(d[far]))
    return out


class _NotJoined(Exception):
    """The local graph does not join start and goal (the exact corner legs then decide)."""


def _legs_of(world, start, goal, clearance: float):
    """The leg tables of a query (the last one asked on this world is kept: a plan builds
    its encoding more than once)."""
    key = (float(clearance), tuple(map(float, start)), tuple(map(float, goal)))
    got = _DERIVED.of(world).get("general_legs")
    if got is not None and got[0] == key:
        return got[1]
    legs = None
    if world.is_grid:
        from ..world.roadmap import corner_count, unreachable_cells

        if corner_count(world, clearance) > EXACT_CORNERS:
            if unreachable_cells(world, start, goal):
                from ..errors import InfeasibleQueryError

                raise InfeasibleQueryError("the goal is not reachable from the start through free space "
                                           "(no 4-connected chain of free cells joins them)")
            try:
                legs = _LandmarkLegs(world, start, goal, clearance)
            except _NotJoined:
                legs = None
    if legs is None:
        legs = _CornerLegs(world, start, goal, clearance)
    _DERIVED.of(world)["general_legs"] = (key, legs)
    return legs


@dataclass
class GeneralPath(PathEncoding):
    """Any path class on any map: ``m`` via points joined by geodesic legs through the roadmap.

    ``x = (x1, y1, ..., xm, ym)`` in metres inside the world bounds. Each via point is snapped
    to the nearest node of the world's :class:`~optplan.world.roadmap.Roadmap` that the start
    can reach (start and goal count as nodes: a via point snapped to either adds nothing),
    and consecutive nodes are joined by their shortest way over the roadmap's visible edges.
    So every individual decodes to a collision-free path (no repair, no penalty), the
    metaheuristic chooses the corridor by where it puts the via points, and with ``m`` via
    points every class whose shortest path wraps around at most ``m`` chosen corners in
    sequence is reachable (more ``m``, more windings). The roadmap (corners, edges, all-pairs
    distances) is built once per world and clearance and kept in the world's cache; the
    start and goal rows are built once per query.

    On grid maps with more than :data:`EXACT_CORNERS` convex corners, all-pairs tables over
    the corners would grow as corners squared: there the via points snap to at most
    :data:`LANDMARKS` landmarks spread over the map (and to start and goal), and legs are
    shortest ways over the :class:`~optplan.world.roadmap.LocalGraph` (``exact`` is then
    False). Snapping a via point to the start or goal still gives the shortest way over that
    graph, a few per cent above the exact optimum; refinement closes that in-class gap.

    On circle worlds with many discs the roadmap uses coarser polygons (8-32 vertices per disc,
    about 2000 nodes in all), so decoded paths are up to ``1/cos(pi/ring) - 1`` longer around
    discs than the arcs; refinement or the class search then closes that in-class gap.

    Length is a table sum (``leg_length``), exact for the decoded polyline; :meth:`decode`
    gives paths ``(n, N, 2)`` (repeated goal points pad short ones) for other terms.
    """

    m: int = 3
    clearance: float = 0.0
    penetration_samples = 1

    def __post_init__(self) -> None:
        if int(self.m) < 1:
            raise ParameterError(f"number of via points m must be >= 1, got {self.m}")
        self.m = int(self.m)
        xmin, ymin, xmax, ymax = self.world.bounds
        self.lower = np.tile([xmin, ymin], self.m).astype(float)
        self.upper = np.tile([xmax, ymax], self.m).astype(float)
        legs = self.legs = _legs_of(self.world, self.start, self.goal, self.clearance)
        self.exact = legs.exact
        self.table, self.points = legs.table, legs.points
        S = len(self.points) - 2
        # via points snap only to nodes the start reaches
        self.reachable = np.nonzero(np.isfinite(self.table[S]))[0]
        from scipy.spatial import cKDTree

        self._tree = cKDTree(self.points[self.reachable])

    @property
    def roadmap(self):
        """The world's :class:`~optplan.world.roadmap.Roadmap` (exact legs only)."""
        return self.legs.roadmap

    @property
    def succ(self) -> np.ndarray:
        """Next node tables of the exact legs (``(K, K)`` over the snap nodes)."""
        return self.legs.succ

    def nodes_of(self, X: np.ndarray) -> np.ndarray:
        """Roadmap node sequence ``(n, m + 2)`` of each individual: start, snapped vias, goal."""
        X = np.asarray(X, dtype=float).reshape(-1, self.dim)
        n = len(X)
        snapped = self.reachable[self._tree.query(X.reshape(-1, 2))[1]].reshape(n, self.m)
        S, G = len(self.points) - 2, len(self.points) - 1
        return np.concatenate([np.full((n, 1), S), snapped, np.full((n, 1), G)], axis=1)

    def leg_length(self, X: np.ndarray) -> np.ndarray:
        """Length in metres of each individual's decoded path, ``(n,)`` (table sums only)."""
        idx = self.nodes_of(X)
        return self.table[idx[:, :-1], idx[:, 1:]].sum(axis=1)

    def _walk(self, i: np.ndarray, j: np.ndarray) -> np.ndarray:
        return self.legs.walk(i, j)

    def decode(self, X: np.ndarray, n_points: int | None = None) -> np.ndarray:
        """Paths ``(n, N, 2)``; ``N`` fits the batch's longest legs, or is ``n_points`` when given
        (at least :meth:`points_bound`); short paths end in repeated goal points, and no point
        repeats before them."""
        idx = self.nodes_of(X)
        n = len(idx)
        legs = self._walk(idx[:, :-1].ravel(), idx[:, 1:].ravel())       # (n * (m+1), L)
        if n_points is not None:
            L = (n_points - 1) // (self.m + 1) + 1
            if legs.shape[1] > L:
                raise ParameterError(f"n_points={n_points} is shorter than a decoded leg ({legs.shape[1]} nodes)")
            legs = np.concatenate([legs, np.repeat(legs[:, -1:], L - legs.shape[1], axis=1)], axis=1)
        seq = legs[:, :-1].reshape(n, -1)                                 # each leg without its end
        seq = np.concatenate([seq, self.legs.snap_path[idx[:, -1:]]], axis=1)
        if n_points is not None and seq.shape[1] < n_points:
            seq = np.concatenate([seq, np.repeat(seq[:, -1:], n_points - seq.shape[1], axis=1)], axis=1)
        # a short leg's padding repeats its end inside the path: move repeats to the end, where
        # they change no term (inside, a zero-length segment would hide a turn from turn terms)
        return repeats_to_end(self.legs.path_points[seq], self.goal)

    def points_bound(self) -> int:
        """Points enough for any decoded path: ``(m + 1) * most_edges_per_leg + 1``, the most
        edges found by walking every pair of reachable nodes at once (once per encoding)."""
        bound = getattr(self, "_points_bound", None)
        if bound is None:
            r = self.reachable
            hops = 1
            for k in range(0, len(r), 256):  # blocks of start nodes: memory stays (256 x M)
                i = np.repeat(r[k:k + 256], len(r))
                j = np.tile(r, len(r[k:k + 256]))
                hops = max(hops, self._walk(i, j).shape[1] - 1)
            bound = self._points_bound = (self.m + 1) * hops + 1
        return bound

    def waypoints(self, x: np.ndarray) -> np.ndarray:
        """The decoded path of one individual without repeated points."""
        P = self.decode(np.asarray(x, dtype=float)[None, :])[0]
        keep = np.r_[True, np.any(np.diff(P, axis=0) != 0, axis=1)]
        return P[keep]

    def sample_corridors(self, n: int, rng: np.random.Generator) -> np.ndarray:
        """``n`` individuals, one corridor each: for a node ``v`` drawn uniformly among the
        reachable ones, the ``m`` via points lie on the nodes of the geodesic start -> v -> goal
        (equally spaced by node count), so the individual decodes to exactly that path.

        A population drawn this way holds ``n`` corridors (the classes of the geodesics
        through ``n`` random nodes) instead of ``n`` mostly detouring random chains; it is the
        general encoding's stand-in for the column encoding's collision-free random start."""
        S, G = len(self.points) - 2, len(self.points) - 1
        v = self.reachable[rng.integers(len(self.reachable), size=n)]
        m1 = (self.m - 1) // 2
        m2 = self.m - 1 - m1
        if not self.exact:
            # the nodes along a leg are not snap nodes here: the other via points sit on the ends;
            # the first individual is the shortest way over the graph itself (v = goal)
            v[:1] = G
            nodes = np.concatenate([np.full((n, m1), S), v[:, None], np.full((n, m2), G)], axis=1)
            return self.points[nodes].reshape(n, -1)
        a = self._walk(np.full(n, S), v)                       # (n, La), padded with v
        b = self._walk(v, np.full(n, G))                       # (n, Lb), padded with G
        la = (a != v[:, None]).sum(axis=1) + 1                 # nodes on start -> v, v included
        lb = (b != G).sum(axis=1) + 1                          # nodes on v -> goal, goal included
        # v itself takes the middle slot; the others spread evenly over either part (by node count)
        ka = np.rint(np.arange(1, m1 + 1)[None, :] / (m1 + 1) * (la - 1)[:, None]).astype(np.int64)
        kb = np.rint(np.arange(1, m2 + 1)[None, :] / (m2 + 1) * (lb - 1)[:, None]).astype(np.int64)
        nodes = np.concatenate([np.take_along_axis(a, ka, axis=1), v[:, None],
                                np.take_along_axis(b, kb, axis=1)], axis=1)
        return self.points[nodes].reshape(n, -1)

    def from_path(self, path: np.ndarray) -> np.ndarray:
        """Via points for a path: ``m`` of its points equally spaced by index (interior ones)."""
        P = np.asarray(path, float)
        inner = P[1:-1] if len(P) > 2 else P[[0]]
        pick = inner[np.linspace(0, len(inner) - 1, self.m).round().astype(int)]
        return np.clip(pick.ravel(), self.lower, self.upper)
