"""TGA and IGA on li2023's own chromosome: a general sequence of grid cells (§3.1).

li2023 §3.1 numbers cells ``N = x + n*y`` (eq 1) and writes a path as the sequence of
the cells it visits, start first, goal last; its example M1 visits column 6 three
times, so a path may double back in x (the column chromosome of
:mod:`optplan.solvers.gridpath.ga_path` cannot). Here a population is an ``(n, L)``
integer array of flat cell numbers, padded with ``-1`` after the goal.

The operators (the paper names them; their details are ours, written so that every
chromosome stays a chain of allowed 8-connected moves, the continuity and eq 3 the paper
asks for):

* random paths (initialisation, §4.1, and regeneration, §4.3): through a random free
  via cell, joined to the start and to the goal by a random descent of the geodesic
  distance to each (each step one of the closer neighbours, drawn with weight = how much
  closer it is);
* crossover at a common cell: two parents that share an interior cell swap the tails
  after it;
* mutation: one interior cell is replaced by another cell adjacent to both of its
  neighbours, or deleted when they are adjacent themselves;
* loops (a cell visited twice) are cut after every operator; a child longer than the
  padded width is discontinuous in the paper's sense: TGA scores it as its fitness says
  (infinite) and IGA's regeneration operator replaces it.

The GA loop itself (selection, the adaptive probabilities of eq 4, elites of eq 5, the
variance-checked initialisation, regeneration, the §4.5 stop) is the one of
:func:`optplan.solvers.gridpath.ga_path.evolve`; the fitness is li2023 eq 2 as the paper
program (:func:`optplan.formulations.paper_programs.paper_program`).
"""
from __future__ import annotations

import time

import numpy as np
from scipy.sparse.csgraph import dijkstra

from ...errors import InfeasibleQueryError, ParameterError, named_with_hints
from ...formulations.paper_programs import paper_program
from ...rng import as_generator
from ..archive import ARCHIVE_EVERY
from ..result import check_alternatives, make_plan_result
from .ga_path import GAParams, check_budget, evolve, ga_result
from .moves import move_table


def drop_loops(C: np.ndarray) -> np.ndarray:
    """Chromosomes ``C`` ``(n, L)`` (``-1`` padded) with every loop cut out: from each cell
    the walk jumps to just after that cell's last visit. The walk is sequential along a
    chromosome; it runs for all chromosomes at once, one position per step."""
    n, L = C.shape
    if L == 0:
        return C
    ncell = int(C.max()) + 1
    last = np.full((n, max(ncell, 1)), -1, dtype=np.int64)
    r, k = np.nonzero(C >= 0)
    np.maximum.at(last, (r, C[r, k]), k)           # last position of every visited cell
    looped = np.zeros(n, dtype=bool)
    looped[r[last[r, C[r, k]] != k]] = True          # rows that revisit a cell
    if not looped.any():
        return C
    out = C.copy()
    rows = np.nonzero(looped)[0]
    sub = C[rows]
    walked = np.full_like(sub, -1)
    idx = np.arange(len(rows))
    at = np.zeros(len(rows), dtype=np.int64)
    length = (sub >= 0).sum(axis=1)
    for j in range(L):
        live = at < length
        if not live.any():
            break
        cell = sub[idx[live], at[live]]
        walked[idx[live], j] = cell
        at[live] = last[rows[live], cell] + 1
    out[rows] = walked
    return out


class CellChromosomes:
    """li2023's cell-sequence operators on one map and query (the ``ops`` of ``evolve``)."""

    def __init__(self, world, start, goal, rng: np.random.Generator, *, preset: str = "li2023",
                 clearance: float = 0.0, width: int | None = None) -> None:
        self.world, self.rng, self.clearance = world, rng, clearance
        self.table = move_table(world, corner_cutting=False, clearance=clearance)
        self.nb = self.table.neighbours
        W = world.width
        sx, sy = world.cell_of(start)
        gx, gy = world.cell_of(goal)
        self.s_cell, self.g_cell = int(sy * W + sx), int(gy * W + gx)
        # geodesic distances (cells) to the start and to the goal: the random descents follow them
        self.d_start, self.d_goal = dijkstra(self.table.csr, indices=[self.s_cell, self.g_cell])
        if not np.isfinite(self.d_start[self.g_cell]):
            raise InfeasibleQueryError("the goal cannot be reached from the start on this grid (8-connected, no "
                                       "corner cutting); free a passage or move the goal")
        self.via_cells = np.nonzero(np.isfinite(self.d_start))[0]
        # a descent visits distinct cells; twice the longest geodesic bounds a random path well
        # in practice (a longer one is re-drawn)
        longest = int(np.ceil(np.max(self.d_start[self.via_cells]) + np.max(self.d_goal[self.via_cells])))
        self.width = int(width) if width is not None else 2 * longest + 4
        self.program = paper_program(preset, world, start, goal, clearance=clearance)
        self.start, self.goal = np.asarray(start, float), np.asarray(goal, float)

    # ------------------------------------------------------------------ decoding
    def lengths(self, C: np.ndarray) -> np.ndarray:
        return (C >= 0).sum(axis=1)

    def paths(self, C: np.ndarray) -> np.ndarray:
        """``(n, L, 2)`` points: the start, the centres of the interior cells, the goal, then
        copies of the goal (zero-length segments, which change no term of eq 2)."""
        n, L = C.shape
        length = self.lengths(C)
        cells = np.where(C >= 0, C, self.g_cell)
        P = self.world.cell_center(np.stack([cells % self.world.width, cells // self.world.width], axis=-1)
                                   .reshape(-1, 2)).reshape(n, L, 2)
        P[:, 0] = self.start
        P[np.arange(L)[None, :] >= (length - 1)[:, None]] = self.goal
        return P

    def path(self, c: np.ndarray) -> np.ndarray:
        """One chromosome's path, without the padding."""
        return self.paths(c[None])[0][: max(int(self.lengths(c[None])[0]), 2)]

    waypoints = path   # the name the population archive decodes rows with (solvers/archive.py)

    # ------------------------------------------------------------ ops of evolve
    def evaluate(self, C: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """li2023 eq 2 of each path; a chromosome that is not a chain from start to goal
        (over-long, the paper's discontinuous individual) violates eq 3 (infinitely)."""
        C = C.astype(np.int64)
        length = self.lengths(C)
        C = C[:, : max(int(length.max(initial=0)), 2)]     # the padding changes no term; skip it
        ok = (length >= 2) & (C[:, 0] == self.s_cell)
        ok &= C[np.arange(len(C)), np.maximum(length - 1, 0)] == self.g_cell
        f = np.full(len(C), np.inf)
        if ok.any():
            f[ok] = self.program.path_costs(self.paths(C[ok]))
        return f, np.where(ok, 0.0, np.inf)

    def canonical(self, C: np.ndarray) -> np.ndarray:
        return C

    def sample(self, k: int) -> np.ndarray:
        """``k`` random paths through random free via cells (the descents run for all paths
        at once, one move per step)."""
        out = np.full((0, self.width), -1, dtype=np.int64)
        for _ in range(20):
            via = self.rng.choice(self.via_cells, size=k - len(out))
            to_start = self._descend(via, self.d_start)
            to_goal = self._descend(via, self.d_goal)
            # the descent to the start reversed, then the via cell and the descent to the goal
            m = self.lengths(to_start)
            back = m[:, None] - 1 - np.arange(to_start.shape[1])[None, :]
            first = np.take_along_axis(to_start, np.maximum(back, 0), axis=1)
            first[back < 0] = -1
            C = self._concat(first, via[:, None], to_goal)
            C = self._fit(drop_loops(C))
            out = np.vstack([out, C[self.lengths(C) > 0]])
            if len(out) >= k:
                break
        if len(out) < k:  # pragma: no cover - the descents are bounded by the width
            raise ParameterError(f"could not draw {k} cell paths within {self.width} cells; pass a larger width")
        return out[:k]

    def _descend(self, cells: np.ndarray, dist: np.ndarray) -> np.ndarray:
        """Random descents of ``dist`` from ``cells`` to its zero (excluded the first cell,
        included the last), ``(k, steps)`` padded with -1."""
        k = len(cells)
        at = cells.copy()
        steps = []
        while True:
            live = dist[at] > 0
            if not live.any():
                break
            nbr = self.nb[at]                                   # (k, 8)
            closer = (nbr >= 0) & (dist[np.maximum(nbr, 0)] < dist[at][:, None]) & live[:, None]
            # a closer neighbour drawn with weight = how much closer it is (keys u ** (1 / w)):
            # paths that follow the geodesic more often than a uniform draw would
            gain = np.where(closer, dist[at][:, None] - dist[np.maximum(nbr, 0)], 0.0)
            pick = np.argmax(np.where(closer, self.rng.random((k, 8)) ** (1.0 / np.maximum(gain, 1e-9)), -1.0), axis=1)
            at = np.where(live, nbr[np.arange(k), pick], at)
            steps.append(np.where(live, at, -1))
        return np.stack(steps, axis=1) if steps else np.full((k, 0), -1, dtype=np.int64)

    def _concat(self, *parts: np.ndarray) -> np.ndarray:
        """Row-wise concatenation of -1 padded chromosome pieces, the padding moved to the end."""
        C = np.concatenate(parts, axis=1)
        order = np.argsort(C < 0, axis=1, kind="stable")
        return np.take_along_axis(C, order, axis=1)

    def _fit(self, C: np.ndarray) -> np.ndarray:
        """``C`` at the population's width; an over-long chromosome becomes all ``-1`` (not a
        path: the GA's fitness rejects it)."""
        n, L = C.shape
        if L < self.width:
            C = np.hstack([C, np.full((n, self.width - L), -1, dtype=np.int64)])
        too_long = (C[:, self.width:] >= 0).any(axis=1)
        C = C[:, : self.width].copy()
        C[too_long] = -1
        return C

    def crossover(self, C: np.ndarray, pc: np.ndarray) -> np.ndarray:
        """Pairs (2i, 2i+1) sharing an interior cell swap their tails after a random shared
        cell, with the mean of their probabilities."""
        C = C.astype(np.int64)
        n, L = C.shape
        half = n // 2
        if half == 0:
            return C.copy()
        a, b = C[0:2 * half:2], C[1:2 * half:2]
        la, lb = self.lengths(a), self.lengths(b)
        ncell = self.world.width * self.world.height
        pos_b = np.full((half, ncell), -1, dtype=np.int64)   # where each cell sits in b (loops are cut)
        r, k = np.nonzero(b >= 0)
        pos_b[r, b[r, k]] = k
        j_of = pos_b[np.arange(half)[:, None], np.maximum(a, 0)]          # (half, L) position in b
        interior = (np.arange(L)[None, :] >= 1) & (np.arange(L)[None, :] < (la - 1)[:, None])
        shared = interior & (j_of >= 1) & (j_of < (lb - 1)[:, None]) & (a >= 0)
        go = (self.rng.random(half) < 0.5 * (pc[0:2 * half:2] + pc[1:2 * half:2])) & shared.any(axis=1)
        i = np.argmax(shared * self.rng.random((half, L)), axis=1)
        j = j_of[np.arange(half), i]
        pos = np.arange(2 * L)[None, :]

        def splice(x, y, cut_x, cut_y):
            src = pos - cut_x[:, None] + cut_y[:, None]             # positions taken from y after the cut
            from_y = np.take_along_axis(np.hstack([y, np.full_like(y, -1)]), np.clip(src, 0, 2 * L - 1), axis=1)
            head = np.hstack([x, np.full_like(x, -1)])
            return np.where(pos < cut_x[:, None], head, from_y)

        kids = self._fit(drop_loops(np.vstack([splice(a, b, i, j), splice(b, a, j, i)])))
        ka, kb = kids[:half], kids[half:]
        out = C.copy()
        out[0:2 * half:2] = np.where(go[:, None], ka, a)
        out[1:2 * half:2] = np.where(go[:, None], kb, b)
        return out

    def mutate(self, C: np.ndarray, pm: np.ndarray) -> np.ndarray:
        """Each mutating chromosome replaces one random interior cell by another cell that
        both of its neighbours can move to, or deletes it when they are adjacent (the path
        stays a chain)."""
        C = C.astype(np.int64)
        out = C.copy()
        length = self.lengths(C)
        who = np.nonzero((self.rng.random(len(C)) < pm) & (length > 2))[0]
        if who.size == 0:
            return out
        k = 1 + np.floor(self.rng.random(who.size) * (length[who] - 2)).astype(np.int64)
        prev, here, nxt = C[who, k - 1], C[who, k], C[who, k + 1]
        cand = self.nb[prev]                                               # (m, 8) moves out of prev
        ok = (cand >= 0) & (cand != here[:, None])
        ok &= (cand[:, :, None] == self.nb[nxt][:, None, :]).any(axis=2)   # nxt can move there too
        ok &= cand != nxt[:, None]
        # a ninth choice: delete the cell when its neighbours are adjacent (-1, compacted below)
        cand = np.hstack([cand, np.full((who.size, 1), -1, dtype=np.int64)])
        ok = np.hstack([ok, (self.nb[prev] == nxt[:, None]).any(axis=1, keepdims=True)])
        pick = np.argmax(ok * self.rng.random(ok.shape), axis=1)
        has = ok.any(axis=1)
        out[who[has], k[has]] = cand[has, pick[has]]
        return drop_loops(self._concat(out))

    def similarity(self, fresh: np.ndarray, best: np.ndarray) -> np.ndarray:
        """li2023 §4.3's distance of each chromosome to the best one: the Euclidean distance of
        their cell coordinates position by position (padded with the goal cell), in cells."""
        W = self.world.width

        def xy(C):
            C = np.where(np.atleast_2d(C) >= 0, np.atleast_2d(C), self.g_cell)
            return np.stack([C % W, C // W], axis=-1).reshape(len(C), -1).astype(float)

        return np.linalg.norm(xy(fresh) - xy(best), axis=1)


def plan_cell_ga(world, start, goal, *, improved: bool, seed=0, pop: int = 50, iters: int | None = 200,
                 clearance: float = 0.0, preset: str = "li2023", postprocess: str | None = None,
                 max_evals: int | None = None, alternatives: int = 0, alternative_separation: float | None = None,
                 **params):
    """``op.plan(..., algorithm="ga" | "iga", encoding="cells")`` on a grid map: TGA or IGA
    (li2023 §3-4) on li2023's cell-sequence chromosome. Options as
    :func:`optplan.solvers.gridpath.ga_path.plan_ga`."""
    t0 = time.perf_counter()
    if not world.is_grid:
        raise ParameterError("encoding='cells' (li2023's cell sequences) needs a grid map")
    check_budget(pop, iters, max_evals)
    if postprocess not in (None, "keypoints", "collinear", "none"):
        raise ParameterError(f"postprocess must be 'keypoints', 'collinear' or 'none', got {postprocess!r}")
    s = world.check_query_point(start, "start", clearance)
    g = world.check_query_point(goal, "goal", clearance)
    known = [f for f in GAParams.__dataclass_fields__ if f != "improved"]
    unknown = sorted(set(params) - set(known))
    if unknown:  # only the unknown ones, each with the name it was likely meant to be
        raise ParameterError(f"unknown GA option(s) {named_with_hints(unknown, known)}; known: {', '.join(known)}")
    p = GAParams(improved=improved, **params)
    name = "iga" if improved else "ga"
    if np.array_equal(world.cell_of(s), world.cell_of(g)):   # one cell: the straight move is the path
        return make_plan_result(world, np.stack([s, g]), name, time.perf_counter() - t0, clearance=clearance)
    rng = as_generator(seed)
    ops = CellChromosomes(world, s, g, rng, preset=preset, clearance=clearance)
    count, separation = check_alternatives(alternatives, alternative_separation)
    snapshots = [] if count else None
    spreads: list = []
    c, fbest, history, nfev, gens = evolve(ops, rng, pop=pop, iters=iters, params=p, max_evals=max_evals,
                                           snapshots=snapshots, archive_every=ARCHIVE_EVERY, spreads=spreads)
    return ga_result(world, ops, c, name, improved, postprocess, clearance, t0, history=history, nfev=nfev,
                     seed=seed, message=f"{gens} generations on li2023's cell-sequence chromosome",
                     snapshots=snapshots, count=count, separation=separation, spreads=spreads)
