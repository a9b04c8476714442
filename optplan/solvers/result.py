"""Turning a solver's raw path into a checked :class:`PlanResult`.

Every planner ends here: the path is validated by the one exact rule
(``validate_path``) and its metrics are computed the same way for all.
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ..results import PlanResult
from ..world.geometry import validate_path
from ..world.metrics import path_metrics


def make_plan_result(world, path, algorithm: str, runtime_s: float, *, clearance: float = 0.0,
                     history=None, seed=None, nfev: int = 0, message: str = "", refined: bool = False) -> PlanResult:
    """Validate ``path`` exactly and package it with its metrics.

    An empty or invalid path yields ``feasible=False`` and a message that says why.
    """
    P = np.asarray(path, dtype=float).reshape(-1, 2) if path is not None else np.zeros((0, 2))
    if len(P) == 0:
        return PlanResult(algorithm, P, False, float("inf"), float("nan"), 0, float("nan"), runtime_s,
                          np.asarray(history if history is not None else [], float), refined, seed,
                          message or "no path found", nfev)
    check = validate_path(world, P, clearance)
    m = path_metrics(world, P)
    msg = message
    if not check:
        msg = (msg + "; " if msg else "") + f"infeasible: {check.reason}"
    return PlanResult(algorithm, P, bool(check), m.length, m.turn_angle_deg, m.n_turns, m.min_clearance, runtime_s,
                      np.asarray(history if history is not None else [], float), refined, seed, msg, nfev)


def check_optional_metres(value, name: str, meaning: str) -> float | None:
    """``value`` as a float (metres) or ``None``; a ParameterError naming ``name`` (and
    what ``None`` means, ``meaning``) for anything else than ``None`` or a finite number >= 0."""
    if value is None:
        return None
    try:
        r = float(value)
    except (TypeError, ValueError):
        r = float("nan")
    if isinstance(value, bool) or not np.isfinite(r) or r < 0:
        raise ParameterError(f"{name} must be a finite number >= 0 metres or None for {meaning}, got {value!r}")
    return r


def check_alternatives(count, separation) -> tuple[int, float | None]:
    """``(count, separation)`` of a planner's ``alternatives`` request, checked: an
    integer >= 0 and ``None`` or a finite number >= 0 metres (ParameterError otherwise)."""
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 0:
        raise ParameterError(f"alternatives must be an integer >= 0 (how many other paths of the population "
                             f"to return), got {count!r}")
    return int(count), check_optional_metres(separation, "alternative_separation", "the default tube radius")


class Band:
    """The cells within ``separation`` metres of a path (the refinement's tube around it,
    :func:`optplan.solvers.tube._cells_within`) on a grid of ``h``-metre cells over the
    world: the map's own cells, or a circle world's bounds at its raster step.

    ``separation = 0`` means "this exact path": :meth:`holds` is then equality.
    """

    def __init__(self, world, path, separation: float, h: float | None = None):
        from .tube import _cells_within, raster_step

        self.path = np.asarray(path, float).reshape(-1, 2)
        self.separation = float(separation)
        if hasattr(world, "occ"):
            self.h, self.origin = float(world.resolution), np.asarray(world.origin, float)
            self.width, self.height = world.width, world.height
        else:
            xmin, ymin, xmax, ymax = world.bounds
            self.h = float(h) if h is not None else raster_step(world)
            self.origin = np.array([xmin, ymin], float)
            self.width = int(np.ceil((xmax - xmin) / self.h - 1e-9))
            self.height = int(np.ceil((ymax - ymin) / self.h - 1e-9))
        self.mask = (_cells_within(self.width, self.height, self.h, self.origin, self.path, self.separation)
                     if self.separation > 0 else None)

    def holds(self, path: np.ndarray) -> bool:
        """Whether all of ``path`` (sampled every half cell) lies in the band's cells."""
        P = np.asarray(path, float).reshape(-1, 2)
        if self.mask is None:
            return P.shape == self.path.shape and bool(np.allclose(P, self.path))
        from .tube import _densify

        c = np.floor((_densify(P, 0.5 * self.h) - self.origin) / self.h).astype(np.int64)
        # a point on the top or right edge of the map belongs to the last cell
        c = np.minimum(np.maximum(c, 0), [self.width - 1, self.height - 1])
        return bool(self.mask[c[:, 1], c[:, 0]].all())


def population_alternatives(world, candidates, best_path, count: int, separation: float, clearance: float = 0.0,
                            finish=None, best_raw=None) -> list[np.ndarray]:
    """Up to ``count`` valid, mutually distinct paths from a planner's population.

    Args:
        world: GridMap or CircleWorld.
        candidates: iterable of ``(N, 2)`` paths in metres, best first by the planner's
            own fitness (typically a lazy decoding of ``OptimizeResult.archive``, so
            rows after the last pick are never decoded).
        best_path: the planner's result path; alternatives must differ from it.
        count: how many to return at most.
        separation: metres; a candidate is kept only when it leaves the
            ``separation`` band (:class:`Band`) around ``best_path`` and around every
            path kept before it. With the refinement's tube radius this means "not
            inside each other's tube", so each start can reach corridors the others
            cannot. ``0``: any path that differs.
        clearance: metres, for the exact ``validate_path`` every kept path passes.
        finish: optional post-processing ``raw path -> path`` (the planner's
            shortcutting). It can be costly, so a raw candidate inside the band of
            ``best_raw`` or of a kept candidate's raw path is skipped before it runs;
            the finished path is then checked against the finished ones.
        best_raw: the raw (unfinished) form of ``best_path``; default ``best_path``.

    Returns:
        The kept (finished) paths, best first; never a path that fails ``validate_path``.
    """
    if count <= 0:
        return []
    kept: list[np.ndarray] = []
    done, raw_done = [], []
    if best_path is not None and len(best_path) > 0:
        done.append(Band(world, best_path, separation))
        raw_done.append(Band(world, best_raw if best_raw is not None else best_path, separation))
    for raw in candidates:
        R = np.asarray(raw, float).reshape(-1, 2)
        if len(R) < 2:
            continue
        if finish is not None:
            if any(b.holds(R) for b in raw_done):
                continue  # a near-copy of a path already taken: not worth finishing
            P = np.asarray(finish(R), float).reshape(-1, 2)
        else:
            P = R
        if len(P) < 2 or any(b.holds(P) for b in done):
            continue
        if not validate_path(world, P, clearance):
            continue
        kept.append(P)
        done.append(Band(world, P, separation))
        raw_done.append(Band(world, R, separation))
        if len(kept) == count:
            break
    return kept
