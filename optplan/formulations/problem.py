"""A path planning problem as a constrained program over a population.

``PathProblem`` ties an encoding (decision vector -> path) to a fitness preset
(weights on shared terms + constraint handling). Solvers see only
``objective(X)`` and, in feasibility mode, ``violation(X)``; they never write a
fitness function of their own.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError
from ..world.metrics import turn_angles_deg
from . import terms
from .encodings import PathEncoding
from .presets import FitnessPreset, collision_penalty_on, get_preset, uses_penetration
from ..world.derived import DerivedStore

_DERIVED = DerivedStore("formulations.problem")  # this module's data derived from worlds


@dataclass
class PathProblem:
    """Encoding + fitness.

    Args:
        encoding: a :class:`PathEncoding`.
        preset: a :class:`FitnessPreset` or its name.
        clearance: required distance from obstacles, metres.
        constraint: override the preset's ``"penalty"`` / ``"feasibility"`` mode.
    """

    encoding: PathEncoding
    preset: FitnessPreset | str = "length"
    clearance: float = 0.0
    constraint: str | None = None
    nfev: int = field(default=0, init=False)

    def __post_init__(self) -> None:
        self.preset = get_preset(self.preset)
        if self.constraint is not None:
            self.preset = self.preset.with_constraint(self.constraint)
        if self.preset.constraint not in ("penalty", "feasibility"):
            raise ParameterError(f"constraint must be 'penalty' or 'feasibility', got {self.preset.constraint!r}")
        c = float(self.clearance)
        if not np.isfinite(c) or c < 0:
            raise ParameterError(f"clearance must be a finite number >= 0 metres, got {self.clearance!r}")
        self.clearance = c
        self._collision_penalty = collision_penalty_on(self.preset, self.encoding.world, self.encoding.goal)
        world = self.encoding.world
        if self._wants_penetration and world.is_grid and not hasattr(self.encoding, "leg_length"):
            # the penetration term samples the map's distance field: a map it cannot fit is
            # refused now, not after the sampler and the first evaluations have run
            from ..world.fields import check_field_memory

            check_field_memory(world)

    @property
    def collision_penalty(self) -> float:
        """What the penalty mode adds per colliding segment (the preset's value, or chen2025
        eq 32's goal product ``Tx * Ty`` resolved on this map)."""
        return self._collision_penalty

    @property
    def _distance(self):
        """Signed distance callable of the world (built on first use: sampling the
        field of a large grid takes a while and many presets never need it)."""
        fn = getattr(self, "_distance_fn", None)
        if fn is None:
            from ..world.fields import distance_function

            fn = self._distance_fn = distance_function(self.encoding.world)
        return fn

    # ------------------------------------------------------------------ pieces
    @property
    def lower(self) -> np.ndarray:
        return self.encoding.lower

    @property
    def upper(self) -> np.ndarray:
        return self.encoding.upper

    def decode(self, X: np.ndarray) -> np.ndarray:
        return self.encoding.decode(X)

    def cost_terms(self, paths: np.ndarray) -> np.ndarray:
        """Weighted path-quality terms (no constraint part), ``(n,)``."""
        f = self.preset.length * terms.length(paths)
        turns = self.turn_terms(paths)
        return f if turns is None else f + turns

    @property
    def has_turn_terms(self) -> bool:
        """Whether the preset weights any turn term (angle, count or cost)."""
        p = self.preset
        return bool(p.turn_angle or p.turn_count or p.turn_cost)

    def turn_terms(self, paths: np.ndarray) -> np.ndarray | None:
        """Weighted terms of consecutive segment pairs (turn angle, count, cost), ``(n,)``;
        ``None`` when the preset has none."""
        if not self.has_turn_terms:
            return None
        return self.weighted_turns(turn_angles_deg(paths))

    def weighted_turns(self, ang_deg: np.ndarray, base=0.0) -> np.ndarray:
        """``base`` plus the preset's weighted turn terms of the heading changes ``ang_deg``
        (degrees, ``(n, N-2)``), added one after the other."""
        p = self.preset
        f = base
        if p.turn_angle:
            f = f + p.turn_angle * terms.turn_angle_of_angles(ang_deg)
        if p.turn_count:
            f = f + p.turn_count * terms.turn_count_of_angles(ang_deg)
        if p.turn_cost:
            f = f + p.turn_cost * terms.turn_cost_of_angles(ang_deg)
        return f

    # ------------------------------------------------------------ solver view
    @property
    def _wants_penetration(self) -> bool:
        return uses_penetration(self.preset)

    def _constraint_parts(self, X: np.ndarray, paths: np.ndarray) -> tuple[np.ndarray, np.ndarray | float]:
        """Collision count and penetration; table lookups when the encoding offers them."""
        enc = self.encoding
        if getattr(enc, "snap", False) and hasattr(enc, "segment_tables"):
            pen_fn = None
            if self._wants_penetration:
                pen_fn = lambda seg: terms.penetration(enc.world, seg, self.clearance, enc.penetration_samples, distance=self._distance)  # noqa: E731
            tables = enc.segment_tables(self.clearance, pen_fn)
            rows = enc.rows_of(X)
            coll = enc.lookup_rows(tables, rows)
            pen = enc.lookup_rows(tables, rows, "_pen") if pen_fn is not None else 0.0
            return coll, pen
        coll = terms.collisions(enc.world, paths, self.clearance)
        pen = (terms.penetration(enc.world, paths, self.clearance, enc.penetration_samples, distance=self._distance)
               if self._wants_penetration else 0.0)
        return coll, pen

    def _segment_costs(self):
        """Per-segment ``(objective, violation)`` of snapped column nodes
        (:class:`~optplan.formulations.segment_store.SegmentCosts`), or ``None`` for other
        encodings.

        Length, collision count and penetration are sums over segments drawn from a
        finite set, so their weighted per-segment values are kept per map, clearance and
        preset (cached on the world) and a population is scored by one gather per array.
        They are computed for the segments the population visits, not for every segment
        of the map (``(d - 1) H^2`` of them: minutes and gigabytes on a 256x256 map).
        """
        enc = self.encoding
        if not (getattr(enc, "snap", False) and hasattr(enc, "segment_index")) or enc.dim == 0:
            return None
        cached = getattr(self, "_fused", None)
        if cached is not None:
            return cached
        key = ("column_cost_tables", self.clearance, self.preset, self._collision_penalty,
               enc.columns.tobytes(), np.concatenate([enc.start, enc.goal]).tobytes())
        cache = _DERIVED.of(enc.world)
        if key not in cache:
            from .segment_store import SegmentCosts, column_segments

            pen_fn = None
            if self._wants_penetration:
                pen_fn = lambda seg: terms.penetration(enc.world, seg, self.clearance, enc.penetration_samples, distance=self._distance)  # noqa: E731
            store = column_segments(enc, self.clearance, pen_fn)
            cache[key] = SegmentCosts(store, self.preset.length, self._collision_penalty,
                                      self.preset.penetration_penalty, self.preset.constraint == "penalty",
                                      penetration=pen_fn is not None)
        self._fused = cache[key]
        return self._fused

    def evaluate(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(objective, violation)`` for a population ``X`` of shape ``(n, d)``."""
        X = np.asarray(X, dtype=float)
        fused = self._segment_costs()
        if fused is not None:
            enc = self.encoding
            X = X.reshape(-1, enc.dim)
            self.nfev += len(X)
            slots = fused.fill(enc.segment_index(enc.rows_of(X)))
            # method calls and ufunc reductions: no Python wrappers in this hot path
            f = np.add.reduce(fused.cost.take(slots), axis=1)
            v = np.add.reduce(fused.violation.take(slots), axis=1)
            if self.has_turn_terms:
                # segment headings are kept too: turn terms without decoding paths
                f = f + self.weighted_turns(terms.heading_changes_deg(fused.headings(slots)))
            return f, v
        enc = self.encoding
        if hasattr(enc, "leg_length") and not self.has_turn_terms:
            # general encoding: legs are visible roadmap edges, so the path is collision-free by
            # construction and its length is a table sum
            X = X.reshape(-1, enc.dim)
            self.nfev += len(X)
            return self.preset.length * enc.leg_length(X), np.zeros(len(X))
        paths = self.decode(X)
        self.nfev += len(paths)
        cost = self.cost_terms(paths)
        coll, pen = self._constraint_parts(X, paths)
        if self.preset.constraint == "penalty":
            return cost + self._collision_penalty * coll + self.preset.penetration_penalty * pen, coll + pen
        return cost, coll + pen

    def objective(self, X: np.ndarray) -> np.ndarray:
        """Penalised objective (penalty mode) or the plain cost (feasibility mode)."""
        return self.evaluate(X)[0]

    def violation(self, X: np.ndarray) -> np.ndarray:
        return self.evaluate(X)[1]
