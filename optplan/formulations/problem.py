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
from . import terms
from .encodings import PathEncoding
from .presets import FitnessPreset, get_preset


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
        from ..world.fields import distance_function

        self._distance = distance_function(self.encoding.world)
        pen = self.preset.collision_penalty
        if pen == "goal_product":
            world = self.encoding.world
            tx, ty = world.cell_of(self.encoding.goal) + 1 if hasattr(world, "occ") else self.encoding.goal
            pen = float(tx * ty)
        self._collision_penalty = float(pen)

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
        p = self.preset
        f = p.length * terms.length(paths)
        if p.turn_angle:
            f = f + p.turn_angle * terms.turn_angle(paths)
        if p.turn_count:
            f = f + p.turn_count * terms.turn_count(paths)
        if p.turn_cost:
            f = f + p.turn_cost * terms.turn_cost_quantised(paths)
        return f

    # ------------------------------------------------------------ solver view
    @property
    def _wants_penetration(self) -> bool:
        return bool(self.preset.penetration_penalty) or self.preset.constraint == "feasibility"

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

    def evaluate(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(objective, violation)`` for a population ``X`` of shape ``(n, d)``."""
        X = np.asarray(X, dtype=float)
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
