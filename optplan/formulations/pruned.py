"""Column-node fitness scored on the pruned path (the papers' order of operations).

chen2025 §4.3.1 builds a path from one node per column, makes it continuous, runs the
direct-connection test (from each kept node, jump to the farthest later node it can see)
and only then scores it with eq 32 (``O * Tx * Ty + length``). yuan2021 eq 10-13 and hou2024
§4.1 score "the path" of an individual the same way without saying whether it was pruned
first. Scoring the raw zig-zag of column nodes instead (what :class:`PathProblem` does) makes
the penalised landscape far harder: a raw path must have every column-to-column segment free,
while a pruned one only needs the segments it keeps. With the papers' penalty and the
algorithms' own initialisation, scoring the raw nodes leaves 0-3 of 10 runs feasible on
hou2024 environment 1, yuan2021 and chen2025_30; scoring the pruned path is the paper's
protocol and finds feasible paths in (nearly) every run (``examples/*`` and
``docs/fidelity/*.md`` give the figures).

:class:`PrunedColumnFitness` evaluates a whole population at once: one table of "is the
straight segment from node ``a`` at row ``ra`` to node ``b`` at row ``rb`` free" for every
pair of path positions (exact segment rule, built once per map and clearance), then the
greedy pruning runs over path positions (at most ``d + 1`` steps), vectorised over the
population.
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from .encodings import ColumnNodes
from ..world.derived import DerivedStore

_DERIVED = DerivedStore("formulations.pruned")  # this module's data derived from worlds

FITNESS_ON = ("nodes", "pruned")


def check_fitness_on(value) -> str:
    """``"nodes"`` (score the raw column nodes) or ``"pruned"`` (score the pruned path)."""
    if value not in FITNESS_ON:
        raise ParameterError(f"fitness_on must be 'nodes' (score the raw column-node path) or 'pruned' (score "
                             f"the path after the direct-connection test, chen2025 §4.3.1), got {value!r}")
    return value


class PrunedColumnFitness:
    """A :class:`~optplan.formulations.problem.PathProblem` on snapped column nodes, scored on
    the pruned path.

    The objective is the preset's weighted terms (length, and any turn terms) of the pruned
    path plus ``collision_penalty`` per blocked cell that the pruned path's colliding segments
    pass (a segment is kept colliding only when no later node is visible from its anchor).
    The violation is that count, so the feasibility rule can use it too.
    """

    def __init__(self, problem) -> None:
        enc = problem.encoding
        if not isinstance(enc, ColumnNodes) or not enc.snap:
            raise ParameterError("fitness_on='pruned' needs the snapped column-node encoding (encoding='columns')")
        self.problem = problem
        self.encoding = enc
        world = enc.world
        self.height = int(world.height)
        self.n_nodes = enc.dim + 2
        self.free, self.dist, self.pos = self._tables(problem.clearance)
        self.passed = self._cells_passed(problem.clearance)

    def _tables(self, clearance: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        enc, world, H, K = self.encoding, self.encoding.world, self.height, self.n_nodes
        key = ("pruned_column_tables", float(clearance), enc.columns.tobytes(),
               np.concatenate([enc.start, enc.goal]).tobytes())
        cache = _DERIVED.of(world)
        if key in cache:
            return cache[key]
        pos = np.empty((K, H, 2))
        pos[1:-1, :, 0] = ((enc.columns + 0.5) * world.resolution + world.origin[0])[:, None]
        pos[1:-1, :, 1] = ((np.arange(H) + 0.5) * world.resolution + world.origin[1])[None, :]
        pos[0], pos[-1] = enc.start, enc.goal
        a_idx, b_idx = np.triu_indices(K, 1)                  # only later nodes are ever tested
        A = np.broadcast_to(pos[a_idx][:, :, None, :], (len(a_idx), H, H, 2)).reshape(-1, 2)
        B = np.broadcast_to(pos[b_idx][:, None, :, :], (len(a_idx), H, H, 2)).reshape(-1, 2)
        free = np.zeros((K, K, H, H), dtype=bool)
        dist = np.zeros((K, K, H, H))
        free[a_idx, b_idx] = np.asarray(world.segments_free(A, B, clearance)).reshape(len(a_idx), H, H)
        dist[a_idx, b_idx] = np.hypot(*(B - A).T).reshape(len(a_idx), H, H)
        cache[key] = (free, dist, pos)
        return cache[key]

    def _cells_passed(self, clearance: float, step: float = 0.05) -> np.ndarray:
        """Blocked cells entered by the segment from path position ``k`` to ``k + 1``,
        ``(K - 1, H, H)`` (rows of the two ends): the papers' "number of obstacles passed"
        (chen2025 eq 32's O, yuan2021 eq 11's m_ob). Only these segments can be kept while
        colliding: pruning keeps a colliding segment only when no later node is visible.
        Counted on samples ``step`` cells apart; a segment the exact rule blocks counts at
        least 1 (a corner it only clips)."""
        enc, world, H, K = self.encoding, self.encoding.world, self.height, self.n_nodes
        key = ("pruned_column_passed", float(clearance), step, enc.columns.tobytes(),
               np.concatenate([enc.start, enc.goal]).tobytes())
        cache = _DERIVED.of(world)
        if key in cache:
            return cache[key]
        A = self.pos[:-1, :, None, :]                       # (K-1, H, 1, 2)
        B = self.pos[1:, None, :, :]                        # (K-1, 1, H, 2)
        A, B = np.broadcast_arrays(A, B)
        A, B = world.to_grid(A.reshape(-1, 2)), world.to_grid(B.reshape(-1, 2))
        n_s = int(np.ceil(np.hypot(*(B - A).T).max() / step)) + 1
        t = np.linspace(0.0, 1.0, n_s)
        P = A[:, None, :] + t[None, :, None] * (B - A)[:, None, :]       # (m, n_s, 2) grid units
        cells = np.floor(P).astype(np.int64)
        cx = np.clip(cells[..., 0], 0, world.width - 1)
        cy = np.clip(cells[..., 1], 0, H - 1)
        blocked = np.asarray(world.occ)[cy, cx]
        flat = cy * world.width + cx
        new_cell = np.ones_like(blocked)
        new_cell[:, 1:] = flat[:, 1:] != flat[:, :-1]     # a straight line never re-enters a cell
        count = (blocked & new_cell).sum(axis=1).reshape(K - 1, H, H).astype(float)
        k = np.arange(K - 1)
        exact_blocked = ~self.free[k, k + 1]
        count = np.where(exact_blocked, np.maximum(count, 1.0), 0.0)
        cache[key] = count
        return count

    def _node_rows(self, X: np.ndarray) -> np.ndarray:
        """Rows of every path position, ``(n, K)``; start and goal use row 0 of their slot
        (their table entries do not depend on the row)."""
        X = np.asarray(X, dtype=float).reshape(-1, self.encoding.dim)
        R = np.zeros((len(X), self.n_nodes), dtype=np.int64)
        R[:, 1:-1] = self.encoding.rows_of(X)
        return R

    def prune(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Greedy direct-connection pruning of a population.

        Returns ``(kept, length, collisions)``: ``kept`` ``(n, K)`` is True for the path
        positions the pruned path keeps, ``length`` ``(n,)`` and ``collisions`` ``(n,)``, the
        blocked cells the kept colliding segments pass (:meth:`_cells_passed`).
        """
        R = self._node_rows(X)
        n, K = R.shape
        ar, positions = np.arange(n), np.arange(K)
        anchor = np.zeros(n, dtype=np.int64)
        kept = np.zeros((n, K), dtype=bool)
        kept[:, 0] = True
        length, coll = np.zeros(n), np.zeros(n)
        self._headings = np.full((n, K), np.nan)              # heading of each kept segment, by step
        for step in range(K - 1):                            # over path positions, not individuals
            active = anchor < K - 1
            if not active.any():
                break
            ra = R[ar, anchor]
            visible = self.free[anchor[:, None], positions[None, :], ra[:, None], R]   # (n, K)
            seen = visible.any(axis=1)
            farthest = K - 1 - np.argmax(visible[:, ::-1], axis=1)
            nxt = np.where(seen, farthest, np.minimum(anchor + 1, K - 1))
            rb = R[ar, nxt]
            length += np.where(active, self.dist[anchor, nxt, ra, rb], 0.0)
            coll += np.where(active & ~seen, self.passed[np.minimum(anchor, K - 2), ra, rb], 0.0)
            self._headings[:, step] = np.where(active, self._heading(anchor, nxt, ra, rb), np.nan)
            kept[ar[active], nxt[active]] = True
            anchor = np.where(active, nxt, anchor)
        return kept, length, coll

    def _heading(self, a, b, ra, rb) -> np.ndarray:
        d = self.pos[b, rb] - self.pos[a, ra]
        return np.arctan2(d[:, 1], d[:, 0])

    def evaluate(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(objective, violation)`` of a population ``X`` ``(n, d)`` (the engine's view)."""
        problem = self.problem
        preset = problem.preset
        _, length, coll = self.prune(X)
        problem.nfev += len(length)
        f = preset.length * length
        if problem.has_turn_terms:
            f = problem.weighted_turns(self._turn_angles_deg(), base=f)
        if preset.constraint == "penalty":
            f = f + problem.collision_penalty * coll
        return f, coll

    def _turn_angles_deg(self) -> np.ndarray:
        """Heading changes between consecutive kept segments of the last pruned population,
        degrees, 0 where a path has fewer segments (no turn there)."""
        h = self._headings
        turn = np.diff(h, axis=1)
        turn = np.abs(np.degrees((turn + np.pi) % (2 * np.pi) - np.pi))
        return np.where(np.isfinite(turn), turn, 0.0)

    def objective(self, X: np.ndarray) -> np.ndarray:
        """The penalised objective (penalty mode) or the plain cost (feasibility mode)."""
        return self.evaluate(X)[0]

    def path(self, x: np.ndarray) -> np.ndarray:
        """The pruned path of one individual, ``(m, 2)`` metres, start first."""
        kept, _, _ = self.prune(np.asarray(x, dtype=float)[None, :])
        raw = self.encoding.waypoints(x)
        return raw[kept[0]]
