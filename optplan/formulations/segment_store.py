"""Per-segment values of the column-node encoding, computed for the segments a run touches.

Snapped column nodes (:class:`~optplan.formulations.encodings.ColumnNodes`, chen2025
§4.3.1) join cell centres of neighbouring columns, so a map has ``(d - 1) H^2 + 2 H``
possible segments (``d`` columns, ``H`` rows). Tabulating all of them
(:meth:`ColumnNodes.segment_tables`) took minutes and many gigabytes on a 256x256 map;
a run of 15,000 evaluations touches a small share. :class:`ColumnSegments` keeps one
byte per possible segment (unknown / free / blocked) and fills it, with the exact rule
(``segments_free``) and the penetration term, for the segments asked for; its
reachability (:meth:`ColumnSegments.alive`) and the moves out of a row
(:meth:`ColumnSegments.moves`) are what the feasible sampler needs, with the same
answers as the full tables.

The flat layout is the encoding's (``segment_index``): ``[first (H) | inner
((d-1) H H, entry j H H + r1 H + r2) | last (H)]``. Values are computed from the same
coordinates, in batches of one kind (first, inner, last) as the full tables were, so
they are the same numbers.

Where values live: by flat index in arrays of one entry per possible segment (pages the
run never touches are never mapped) while the map has at most :data:`DENSE_SEGMENTS`
possible segments; beyond that (a 1000-column map has 10^9), in slots handed out on first
use by :class:`SlotIndex`, a vectorised open-addressing hash table, so memory follows the
segments a run asks for, not the map.

A necessary condition prunes inner segments before the exact rule: between the centres
of rows ``r1`` and ``r2`` of neighbouring columns, the segment runs through the open
interior of the cells of the first column from ``r1`` to half way and of the second from
half way to ``r2`` (:meth:`ColumnSegments.may_be_free`); if one of them is blocked the
segment is blocked whatever the clearance. Only the exact rule says a segment is free.
"""
from __future__ import annotations

import numpy as np
from ..world.derived import DerivedStore

_DERIVED = DerivedStore("formulations.segment_store")  # this module's data derived from worlds

FREE, BLOCKED = 1, 2
# up to this many possible segments values are kept by flat index (one byte of state and
# eight of each value per possible segment, reserved but mapped only where touched)
DENSE_SEGMENTS = 1 << 26
# the band of BAND rows is decided up front only while it holds at most this many segments
BAND_SEGMENTS = 1 << 23
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)  # Fibonacci hashing's multiplier (2^64 / golden ratio)


def grown(values: np.ndarray, n: int) -> np.ndarray:
    """``values`` with room for at least ``n`` entries (new ones zero), doubling as it grows."""
    if len(values) >= n:
        return values
    out = np.zeros(max(n, 2 * len(values)), dtype=values.dtype)
    out[:len(values)] = values
    return out


class SlotIndex:
    """Where the value of flat segment index ``k`` is kept: ``k`` itself for a small index
    space (``dense``), otherwise a slot number handed out on first use, in order.

    The slots of a big index space come from an open-addressing hash table with linear
    probing, searched for a whole batch of keys at once (one numpy pass per probe step);
    it doubles when half full."""

    def __init__(self, size: int) -> None:
        self.size = int(size)
        self.dense = self.size <= DENSE_SEGMENTS
        if not self.dense:
            self._keys = np.full(1 << 12, -1, dtype=np.int64)
            self._slot = np.zeros(1 << 12, dtype=np.int64)
            self._key_of = np.zeros(1 << 10, dtype=np.int64)
            self.used = 0

    @property
    def n_slots(self) -> int:
        """How many slots value arrays need."""
        return self.size if self.dense else self.used

    def slots(self, idx: np.ndarray) -> np.ndarray:
        """The slots of flat indices ``idx`` (any shape), new keys given new slots."""
        idx = np.asarray(idx, dtype=np.int64)
        if self.dense:
            return idx
        u, inv = np.unique(idx, return_inverse=True)
        found = self._probe(u)
        new = found < 0
        if new.any():
            fresh = np.arange(self.used, self.used + int(new.sum()), dtype=np.int64)
            self.used += len(fresh)
            if 2 * self.used > len(self._keys):
                self._rehash(2 * self.used)
            self._place(u[new], fresh)
            self._key_of = grown(self._key_of, self.used)
            self._key_of[fresh] = u[new]
            found[new] = fresh
        return found[inv].reshape(idx.shape)

    def keys(self, slots: np.ndarray) -> np.ndarray:
        """The flat indices held in ``slots``."""
        return np.asarray(slots, dtype=np.int64) if self.dense else self._key_of[slots]

    def _home(self, keys: np.ndarray) -> np.ndarray:
        bits = len(self._keys).bit_length() - 1
        return ((keys.astype(np.uint64) * _GOLDEN) >> np.uint64(64 - bits)).astype(np.int64)

    def _probe(self, keys: np.ndarray) -> np.ndarray:
        out = np.full(len(keys), -1, dtype=np.int64)
        pos, todo, mask = self._home(keys), np.arange(len(keys)), len(self._keys) - 1
        while todo.size:
            held = self._keys[pos[todo]]
            hit = held == keys[todo]
            out[todo[hit]] = self._slot[pos[todo[hit]]]
            todo = todo[~hit & (held != -1)]          # an empty place ends the search: absent
            pos[todo] = (pos[todo] + 1) & mask
        return out

    def _place(self, keys: np.ndarray, slots: np.ndarray) -> None:
        """Insert keys known to be absent."""
        pos, todo, mask = self._home(keys), np.arange(len(keys)), len(self._keys) - 1
        while todo.size:
            p = pos[todo]
            empty = self._keys[p] == -1
            # the first key waiting for an empty place takes it; the others probe on
            _, first = np.unique(np.where(empty, p, -1), return_index=True)
            first = first[empty[first]]
            self._keys[p[first]], self._slot[p[first]] = keys[todo[first]], slots[todo[first]]
            moved = np.ones(len(todo), dtype=bool)
            moved[first] = False
            todo = todo[moved]
            pos[todo] = (pos[todo] + 1) & mask

    def _rehash(self, at_least: int) -> None:
        size = len(self._keys)
        while size < at_least:
            size *= 2
        held = self._keys != -1
        keys, slots = self._keys[held], self._slot[held]
        self._keys = np.full(size, -1, dtype=np.int64)
        self._slot = np.zeros(size, dtype=np.int64)
        self._place(keys, slots)
# inner segments changing row by at most this many rows are decided in one batch on first
# use (ColumnSegments.prefetch_band): a run asks for most of them, one at a time otherwise
BAND = 8


def _free_runs(occ: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For occupancy columns ``occ`` ``(H, d)``: the lowest and highest row of the free run
    holding each cell, ``(d, H)`` each (a blocked cell: its own row + 1 and row - 1, an
    empty run)."""
    H = occ.shape[0]
    rows = np.arange(H)[:, None]
    below = np.maximum.accumulate(np.where(occ, rows, -1), axis=0)            # last blocked row <= r
    above = np.minimum.accumulate(np.where(occ, rows, H)[::-1], axis=0)[::-1]  # first blocked row >= r
    return (below + 1).T, (above - 1).T


class ColumnSegments:
    """Lazily computed collision (and penetration) values of every column-node segment.

    Args:
        enc: a snapped :class:`ColumnNodes` encoding with ``dim >= 1``.
        clearance: metres, for the exact rule.
        penetration_fn: ``fn(segments (m, 2, 2)) -> (m,)`` or ``None``.
    """

    def __init__(self, enc, clearance: float, penetration_fn=None) -> None:
        self.enc, self.clearance = enc, float(clearance)
        grid = enc.world
        self.H, self.d = grid.height, enc.dim
        H, d = self.H, self.d
        self.n_inner = (d - 1) * H * H
        self.size = 2 * H + self.n_inner
        self.index = SlotIndex(self.size)
        # np.zeros maps untouched pages lazily: memory grows with the segments computed
        self.state = np.zeros(self.index.n_slots if self.index.dense else 1 << 10, dtype=np.int8)
        self.penetration_fn, self.pen, self.pen_known = None, None, None
        if penetration_fn is not None:
            self.attach_penetration(penetration_fn)
        occ = grid.occ[:, enc.columns]
        self.bottom, self.top = _free_runs(occ)
        self.free = ~occ.T                                                      # (d, H)
        self._alive = None
        self._band_done = False

    def attach_penetration(self, penetration_fn) -> None:
        """Also keep penetration values (computed from now on for new segments, and on
        demand for segments known before); the first function attached stays."""
        if self.penetration_fn is None:
            self.penetration_fn = penetration_fn
            self.pen = np.zeros(len(self.state))
            self.pen_known = np.zeros(len(self.state), dtype=bool)

    def slots(self, idx) -> np.ndarray:
        """The slots of flat indices ``idx`` (:class:`SlotIndex`), the value arrays grown to
        hold them."""
        s = self.index.slots(idx)
        n = self.index.n_slots
        if len(self.state) < n:
            self.state = grown(self.state, n)
            if self.pen is not None:
                self.pen, self.pen_known = grown(self.pen, len(self.state)), grown(self.pen_known, len(self.state))
        return s

    # ------------------------------------------------------------ segments
    def _ends(self, idx: np.ndarray, kind: str) -> tuple[np.ndarray, np.ndarray]:
        """Grid-unit end points of the segments ``idx`` of one kind, as the full tables
        built them."""
        grid, enc, H = self.enc.world, self.enc, self.H
        col_x = enc.columns + 0.5
        if kind == "first":
            r = idx
            return (np.repeat(grid.to_grid(enc.start)[None], len(idx), 0),
                    np.stack([np.full(len(idx), col_x[0]), r + 0.5], axis=1))
        if kind == "last":
            r = idx - (H + self.n_inner)
            return (np.stack([np.full(len(idx), col_x[-1]), r + 0.5], axis=1),
                    np.repeat(grid.to_grid(enc.goal)[None], len(idx), 0))
        j, rest = np.divmod(idx - H, H * H)
        r1, r2 = np.divmod(rest, H)
        return (np.stack([col_x[j], r1 + 0.5], axis=1), np.stack([col_x[j + 1], r2 + 0.5], axis=1))

    def may_be_free(self, j: np.ndarray, r1: np.ndarray, r2: np.ndarray) -> np.ndarray:
        """The necessary condition of the module docstring for inner segments from row
        ``r1`` of column ``j`` to row ``r2`` of column ``j + 1`` (broadcast arrays)."""
        s = np.abs(r2 - r1)
        up = r2 >= r1
        # rows the segment's open part in column j (from r1) and in column j+1 (to r2) crosses
        near_end = np.where(up, r1 + s // 2, r1 - s // 2)
        far_end = np.where(up, r1 + (s + 1) // 2, r1 - (s + 1) // 2)
        ok = self.free[j, r1] & self.free[j + 1, r2]
        ok &= np.where(up, self.top[j, r1] >= near_end, self.bottom[j, r1] <= near_end)
        ok &= np.where(up, self.bottom[j + 1, r2] <= far_end, self.top[j + 1, r2] >= far_end)
        return ok

    def fill(self, idx) -> None:
        """Compute the values of the segments ``idx`` (flat indices) not known yet."""
        idx = np.asarray(idx, dtype=np.int64).ravel()
        if not self._band_done:
            self.prefetch_band()
        at = self.slots(idx)            # first: it may grow the value arrays
        todo = idx[self.state[at] == 0]
        if todo.size == 0:
            return
        todo = np.unique(todo)
        H = self.H
        kinds = (("first", todo[todo < H]), ("inner", todo[(todo >= H) & (todo < H + self.n_inner)]),
                 ("last", todo[todo >= H + self.n_inner]))
        grid = self.enc.world
        for kind, k in kinds:
            if k.size == 0:
                continue
            a, b = self._ends(k, kind)
            A, B = grid.to_world(a), grid.to_world(b)
            free = np.zeros(len(k), dtype=bool)
            maybe = np.ones(len(k), dtype=bool)
            if kind == "inner":
                j, rest = np.divmod(k - H, H * H)
                maybe = self.may_be_free(j, *np.divmod(rest, H))
            if maybe.any():
                free[maybe] = np.asarray(grid.segments_free(A[maybe], B[maybe], self.clearance))
            ks = self.index.slots(k)
            self.state[ks] = np.where(free, FREE, BLOCKED)
            if self.pen is not None:
                self.pen[ks] = self.penetration_fn(np.stack([A, B], axis=1))
                self.pen_known[ks] = True

    def prefetch_band(self, rows: int = BAND, chunk: int = 200_000) -> None:
        """Decide at once every inner segment that changes row by at most ``rows`` and
        that :meth:`may_be_free` does not rule out (the others are blocked without a
        check): the moves of paths that wander, which a run asks for most. One exact
        check per chunk instead of one per evaluation that meets a new segment."""
        self._band_done = True
        H, d = self.H, self.d
        if d < 2 or (d - 1) * H * (2 * rows + 1) > BAND_SEGMENTS:
            return   # a big map's band is more than a run asks for: decided on demand
        j, r1, off = np.meshgrid(np.arange(d - 1), np.arange(H), np.arange(-rows, rows + 1), indexing="ij")
        r2 = r1 + off
        inside = (r2 >= 0) & (r2 < H)
        j, r1, r2 = j[inside], r1[inside], r2[inside]
        keep = self.may_be_free(j, r1, r2)
        idx = self._inner_index(j[keep], r1[keep], r2[keep])
        for a in range(0, len(idx), chunk):
            self.fill(idx[a:a + chunk])

    def collisions(self, idx: np.ndarray) -> np.ndarray:
        """1.0 for blocked, 0.0 for free segments ``idx`` (computed when unknown)."""
        self.fill(idx)
        at = self.slots(idx)
        return (self.state.take(at) == BLOCKED).astype(float)

    def penetration(self, idx: np.ndarray) -> np.ndarray:
        """Penetration values of the segments ``idx`` (computed when unknown; needs
        :meth:`attach_penetration`)."""
        self.fill(idx)
        at = self.slots(idx)
        missing = idx[~self.pen_known.take(at)]
        if missing.size:
            missing = np.unique(missing)
            H = self.H
            for kind, k in (("first", missing[missing < H]),
                            ("inner", missing[(missing >= H) & (missing < H + self.n_inner)]),
                            ("last", missing[missing >= H + self.n_inner])):
                if k.size:
                    a, b = self._ends(k, kind)
                    grid = self.enc.world
                    ks = self.index.slots(k)
                    self.pen[ks] = self.penetration_fn(np.stack([grid.to_world(a), grid.to_world(b)], axis=1))
                    self.pen_known[ks] = True
        return self.pen.take(self.slots(idx))  # the slots are known: nothing grows here

    def deltas(self, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(dx, dy)`` in metres of the segments ``idx``, the same numbers as the
        encoding's full-layout ``_segment_deltas`` at those indices."""
        enc, grid, H = self.enc, self.enc.world, self.H
        res, (ox, oy) = grid.resolution, grid.origin
        xs = (enc.columns + 0.5) * res + ox
        ys = (np.arange(H) + 0.5) * res + oy
        idx = np.asarray(idx, dtype=np.int64)
        first, last = idx < H, idx >= H + self.n_inner
        inner = ~(first | last)
        dx, dy = np.empty(idx.shape), np.empty(idx.shape)
        r = idx[first]
        dx[first], dy[first] = xs[0] - enc.start[0], ys[r] - enc.start[1]
        r = idx[last] - (H + self.n_inner)
        dx[last], dy[last] = enc.goal[0] - xs[-1], enc.goal[1] - ys[r]
        j, rest = np.divmod(idx[inner] - H, H * H)
        r1, r2 = np.divmod(rest, H)
        dx[inner], dy[inner] = np.diff(xs)[j], ys[r2] - ys[r1]
        return dx, dy

    # ------------------------------------------------------------ reachability
    def _inner_index(self, j, r1, r2):
        return self.H + j * self.H * self.H + r1 * self.H + r2

    def alive(self) -> np.ndarray:
        """``(d, H)``: row ``r`` of column ``j`` reaches the goal by collision-free moves
        (the backward pass of ``ColumnNodes.feasible_transitions``). A row is alive once
        one move to an alive row of the next column is free; moves are tried nearest
        row first and only where :meth:`may_be_free` allows."""
        if self._alive is not None:
            return self._alive
        H, d = self.H, self.d
        alive = np.zeros((d, H), dtype=bool)
        last = H + self.n_inner + np.arange(H)
        alive[-1] = self.collisions(last) == 0
        rows = np.arange(H)
        for j in range(d - 2, -1, -1):
            # straight on first (one vectorised test for the whole column) ...
            r = np.nonzero(self.free[j] & self.free[j + 1] & alive[j + 1])[0]
            if r.size:
                alive[j, r] = self.collisions(self._inner_index(j, r, r)) == 0
            # ... then the other rows, nearest candidate first; a blocked move tries the next
            rest = np.nonzero(self.free[j] & ~alive[j])[0]
            if rest.size == 0:
                continue
            cand = self.may_be_free(j, rest[:, None], rows[None, :]) & alive[j + 1][None, :]
            cand[np.arange(rest.size), rest] = False                   # straight on was tried
            has = cand.any(axis=1)
            rest, cand = rest[has], cand[has]
            if rest.size == 0:
                continue
            order = np.argsort(np.where(cand, np.abs(rows[None, :] - rest[:, None]), H + 1), axis=1, kind="stable")
            n_cand = cand.sum(axis=1)
            k = 0
            live = np.arange(rest.size)
            while live.size:
                r1, r2 = rest[live], order[live, k]
                ok = self.collisions(self._inner_index(j, r1, r2)) == 0
                alive[j, r1[ok]] = True
                k += 1
                live = live[~ok & (n_cand[live] > k)]
        self._alive = alive
        return alive

    def first_moves(self) -> np.ndarray:
        """``(H,)``: the start's segment to row ``r`` of the first column is free and the
        row is alive (``feasible_transitions()[0]``)."""
        return (self.collisions(np.arange(self.H)) == 0) & self.alive()[0]

    def moves(self, j: int, r1: np.ndarray, centre: np.ndarray | None = None, window: int | None = None) -> np.ndarray:
        """``(len(r1), H)``: the free moves from rows ``r1`` of column ``j`` to alive rows of
        column ``j + 1`` (rows ``r1`` of ``feasible_transitions()[1][j]``).

        With ``centre`` (one per row of ``r1``, a function of that row) and ``window``, only
        the rows within ``window`` of the centre are decided, unless none of them is free
        (then every row is): a big map's sampler weighs far rows by less than
        ``exp(-window / spread)``, and deciding all ``H`` moves of every row of every column
        filled the store with millions of segments no run uses."""
        H = self.H
        rows = np.arange(H)
        u, first, inv = np.unique(np.asarray(r1, dtype=np.int64), return_index=True, return_inverse=True)
        cand = self.may_be_free(j, u[:, None], rows[None, :]) & self.alive()[j + 1][None, :]
        if window is not None and centre is not None:
            near = np.abs(rows[None, :] - np.asarray(centre, float)[first][:, None]) <= window
            has = (cand & near).any(axis=1)
            cand &= near | ~has[:, None]      # a row with no free move in its window keeps every row
        a, b = np.nonzero(cand)
        mask = np.zeros((len(u), H), dtype=bool)
        mask[a, b] = self.collisions(self._inner_index(j, u[a], b)) == 0
        return mask[inv.ravel()]

    def moves_into(self, j: int, r2: np.ndarray) -> np.ndarray:
        """``(len(r2), H)``: the rows of column ``j`` with a free move to rows ``r2`` of
        column ``j + 1``, where those rows are alive (columns ``r2`` of
        ``feasible_transitions()[1][j]``)."""
        H = self.H
        rows = np.arange(H)
        u, inv = np.unique(np.asarray(r2, dtype=np.int64), return_inverse=True)
        cand = self.may_be_free(j, rows[None, :], u[:, None]) & self.alive()[j + 1][u][:, None]
        a, b = np.nonzero(cand)
        mask = np.zeros((len(u), H), dtype=bool)
        mask[a, b] = self.collisions(self._inner_index(j, b, u[a])) == 0
        return mask[inv.ravel()]

    def last_moves(self) -> np.ndarray:
        """``(H,)``: the segment from row ``r`` of the last column to the goal is free
        (``feasible_transitions()[2]``)."""
        return self.collisions(self.H + self.n_inner + np.arange(self.H)) == 0


def column_segments(enc, clearance: float, penetration_fn=None) -> ColumnSegments:
    """The :class:`ColumnSegments` of ``enc`` (its columns, start and goal) for
    ``clearance``, cached on the map (one for the sampler and every program), with
    penetration values once a ``penetration_fn`` is given."""
    key = ("column_segments", float(clearance), enc.columns.tobytes(), np.concatenate([enc.start, enc.goal]).tobytes())
    cache = _DERIVED.of(enc.world)
    store = cache.get(key)
    if store is None:
        store = cache[key] = ColumnSegments(enc, clearance)
    if penetration_fn is not None:
        store.attach_penetration(penetration_fn)
    return store


class SegmentCosts:
    """A program's per-segment objective and violation (and the heading, for turn terms)
    over a :class:`ColumnSegments`, computed for the segments asked for.

    ``cost = length_weight * length + collision_weight * collision + penetration_weight *
    penetration`` (the penalty terms only when ``penalised``) and ``violation = collision
    + penetration`` per segment (penetration 0 unless ``penetration``), the same
    element-wise operations as the full tables, so a population's sums are the same
    numbers.
    """

    def __init__(self, store: ColumnSegments, length_weight: float, collision_weight: float = 0.0,
                 penetration_weight: float = 0.0, penalised: bool = False, penetration: bool = False) -> None:
        self.store, self.uses_penetration = store, penetration
        self.weights = (length_weight, collision_weight, penetration_weight, penalised)
        n = len(store.state)
        self.cost = np.zeros(n)
        self.violation = np.zeros(n)
        self._heading = None
        self.known = np.zeros(n, dtype=bool)

    def fill(self, idx: np.ndarray) -> np.ndarray:
        """Make ``cost``, ``violation`` (and ``heading`` once asked for) hold the segments
        ``idx`` (flat indices); returns their slots, where those arrays hold them."""
        store = self.store
        slots = store.slots(idx)
        if len(self.known) < store.index.n_slots:
            n = len(store.state)
            self.cost, self.violation, self.known = grown(self.cost, n), grown(self.violation, n), grown(self.known, n)
            if self._heading is not None:
                self._heading = grown(self._heading, n)
        need = ~self.known.take(slots)
        if not need.any():
            return slots
        new = np.unique(idx[need])
        coll = store.collisions(new)
        pen = store.penetration(new) if self.uses_penetration else np.zeros(len(new))
        dx, dy = store.deltas(new)
        w_len, w_coll, w_pen, penalised = self.weights
        cost = w_len * np.hypot(dx, dy)
        if penalised:
            cost = cost + w_coll * coll + w_pen * pen
        at = store.index.slots(new)
        self.cost[at] = cost
        self.violation[at] = coll + pen
        if self._heading is not None:
            self._heading[at] = np.arctan2(dy, dx)
        self.known[at] = True
        return slots

    def headings(self, slots: np.ndarray) -> np.ndarray:
        """Headings (radians) of the segments in ``slots`` (as :meth:`fill` returned them)."""
        if self._heading is None:
            # first use: headings of the segments known so far, then kept up by fill
            self._heading = np.zeros(len(self.known))
            known = np.nonzero(self.known)[0]
            dx, dy = self.store.deltas(self.store.index.keys(known))
            self._heading[known] = np.arctan2(dy, dx)
        return self._heading.take(slots)
