"""A "tube" stage for the smoothers: let refinement change homotopy class near the seed.

Both smoothers (:mod:`optplan.solvers.nlp`, :mod:`optplan.solvers.qp`) are local:
they pull a seed taut around the obstacles it already passes, on the side it
already passes them. The papers' planners often return seeds that wrap an
obstacle on the long side, so the detour stays (``examples/refined_vs_pure.py``;
the figures are in ``docs/measurements.md``).

The tube stage looks for a shorter way *near* the seed:

1. the tube is every point within ``radius`` metres of the seed polyline;
2. everything outside the tube is blocked and the exact any-angle search
   (:func:`optplan.solvers.graph.visibility_path`, a visibility graph over
   convex cell corners) finds the shortest path inside it. On a grid the tube is
   the set of cells whose centres lie within ``radius`` of the seed, on the map
   inflated by the clearance. A circle world is first rasterised at a fine
   resolution (about 0.05-0.1 m), every cell that touches a circle grown by the
   clearance counted as blocked, so the raster path is collision-free in the
   circle world too, only slightly longer than its class's optimum;
3. that path seeds the same smoother; of the two smoothed paths (from the
   original seed and from the tube seed) the shorter one that passed the exact
   ``validate_path`` is kept.

A tube of radius ``R`` is a neighbourhood of the seed, not a global re-plan: it
only offers the classes whose shortest path stays within ``R`` of the seed.
With ``R`` as large as the map it becomes the exact planner, so ``R`` should be
small, on the scale of an obstacle (the seed must move about one obstacle width
to pass it on the other side). :func:`default_tube_radius` states the default
and why. When the tube search fails (the start or goal cell is blocked by the
rasterisation, or the tube holds no path) the stage keeps the original seed's
smoothing and says so in the message; it never raises for that.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import InfeasibleQueryError, ParameterError
from ..world.geometry import validate_path
from ..world.grid import GridMap
from ..world.metrics import path_length
from ..world.polyline import densify
from .graph import visibility_path
from ..world.derived import DerivedStore

_DERIVED = DerivedStore("solvers.tube")  # this module's data derived from worlds

# default tube radius in widths of the widest obstacle (see default_tube_radius)
DEFAULT_WIDTHS = 2.0
# finest raster for circle worlds: at most this many cells along the longer side, and
# never coarser than RASTER_MAX_STEP metres
RASTER_CELLS = 200
RASTER_MAX_STEP = 0.1
# relative length difference below which the tube path does not replace the seed's result
TIE = 1e-9
# point-to-segment distances evaluated per block (bounds memory on large maps)
_BLOCK = 2_000_000


@dataclass
class TubeSeed:
    """The shortest path inside the tube around a seed (:func:`tube_path`).

    Attributes:
        path: ``(N, 2)`` path in metres from the seed's start to its goal, or ``None``
            when the search failed.
        length: its length in metres (``inf`` when there is none).
        message: empty on success, otherwise why there is no tube path.
        grid: the search grid: the map (or the circle world's raster) with every
            cell outside the tube blocked.
        search_time_s: wall time of building the tube and searching it, seconds.
    """

    path: np.ndarray | None
    length: float
    message: str
    grid: GridMap | None = field(default=None, repr=False)
    search_time_s: float = 0.0

    @property
    def found(self) -> bool:
        """Whether a path inside the tube was found."""
        return self.path is not None


def obstacle_width(world) -> float:
    """Width (metres) of the widest obstacle: the diameter of the largest disc inside
    the blocked region, the map border not counted.

    Circle worlds: the largest grown diameter ``2 (r + safety)``. Grids: about
    ``2 e - 1`` cells, where ``e`` is the largest distance (in cells, centre to
    centre) from a blocked cell to a free one, so a wall ``w`` cells thick
    (``w`` odd) measures ``w`` cells. ``0`` when there is no obstacle.
    """
    if world.is_grid:
        cached = _DERIVED.of(world).get("obstacle_width")
        if cached is None:
            from scipy.ndimage import distance_transform_edt

            if not world.occ.any():
                cached = 0.0
            else:
                depth = float(distance_transform_edt(np.pad(world.occ, 1)).max())
                cached = (2.0 * depth - 1.0) * world.resolution
            _DERIVED.of(world)["obstacle_width"] = cached
        return cached
    return 2.0 * float(world.radii.max()) if len(world.circles) else 0.0


def default_tube_radius(world) -> float:
    """Default tube radius (metres) of ``refine="casadi"``: ``DEFAULT_WIDTHS`` times
    :func:`obstacle_width`.

    Why the widest obstacle: a seed that passes an obstacle on the long side
    reaches the short side by moving about one obstacle width; a tube twice as
    wide also holds the way round it. The obstacle scale, not the map size, sets
    the radius, so the stage stays a neighbourhood of the seed on large maps.
    Two widths is where ``benchmarks/refine_tube.py`` shows the largest gain
    (``docs/measurements.md``); pass a larger ``tube_radius`` to trade locality
    for more repaired seeds.
    """
    return DEFAULT_WIDTHS * obstacle_width(world)


def distance_to_polyline(points, polyline) -> np.ndarray:
    """Euclidean distance (metres) from each of ``points`` ``(M, 2)`` to the polyline
    ``(S + 1, 2)``: the minimum over its segments, evaluated in blocks of points."""
    Q = np.asarray(points, float).reshape(-1, 2)
    P = np.asarray(polyline, float).reshape(-1, 2)
    A, D = P[:-1], np.diff(P, axis=0)
    if len(A) == 0:  # one point
        return np.hypot(*(Q - P[0]).T)
    L2 = np.einsum("ij,ij->i", D, D)
    inv = np.where(L2 > 0, 1.0 / np.where(L2 > 0, L2, 1.0), 0.0)
    out = np.empty(len(Q))
    step = max(1, _BLOCK // len(A))
    for a in range(0, len(Q), step):
        q = Q[a:a + step, None, :] - A[None]                       # (m, S, 2)
        t = np.clip(np.einsum("msj,sj->ms", q, D) * inv, 0.0, 1.0)
        r = q - t[..., None] * D[None]
        out[a:a + step] = np.sqrt(np.einsum("msj,msj->ms", r, r).min(axis=1))
    return out


def cells_within(width: int, height: int, resolution: float, origin, seed: np.ndarray, radius: float) -> np.ndarray:
    """``(height, width)`` mask of the cells whose centres lie within ``radius`` metres of ``seed``.

    Exact, but only a thin band of cells is measured against every segment: the
    cells the seed crosses are marked (from points ``h / 2`` apart) and a
    Euclidean distance transform gives each cell centre's distance ``e`` to the
    nearest marked centre. The true distance ``d`` to the polyline satisfies
    ``e - h/4 - h sqrt(2)/2 <= d <= e + h sqrt(2)/2``, so cells with ``e`` clearly
    below or above ``radius`` are decided without measuring.
    """
    from scipy.ndimage import distance_transform_edt

    h = float(resolution)
    O = np.asarray(origin, float)
    g = np.floor((densify(seed, h / 2) - O) / h).astype(np.int64)
    g = g[(g[:, 0] >= 0) & (g[:, 0] < width) & (g[:, 1] >= 0) & (g[:, 1] < height)]
    if len(g) == 0:  # a seed outside the map: measure everything
        marked_distance = np.zeros((height, width))
    else:
        marked = np.zeros((height, width), dtype=bool)
        marked[g[:, 1], g[:, 0]] = True
        marked_distance = distance_transform_edt(~marked) * h
    slack = h * np.sqrt(0.5)
    mask = marked_distance <= radius - slack
    iy, ix = np.nonzero((marked_distance > radius - slack) & (marked_distance <= radius + slack + h / 4))
    if len(ix):
        centres = (np.stack([ix, iy], axis=1) + 0.5) * h + O
        mask[iy, ix] = distance_to_polyline(centres, seed) <= radius
    return mask


def raster_step(world, resolution: float | None = None) -> float:
    """Cell size (metres) of a circle world's raster: ``resolution`` when given, else
    the longer side / ``RASTER_CELLS``, at most ``RASTER_MAX_STEP``."""
    if resolution is not None:
        h = float(resolution)
        if not np.isfinite(h) or h <= 0:
            raise ParameterError(f"raster resolution must be a positive number of metres, got {resolution!r}")
        return h
    xmin, ymin, xmax, ymax = world.bounds
    return min(RASTER_MAX_STEP, max(xmax - xmin, ymax - ymin) / RASTER_CELLS)


def rasterise_circles(world, resolution: float, clearance: float = 0.0, within=None) -> GridMap:
    """A GridMap over ``world.bounds`` whose blocked cells are those that touch (or lie
    within ``clearance`` of) a grown circle, or stick out of the bounds.

    ``within``: optional ``(seed, radius)``; then only the cells in the seed's
    bounding box grown by ``radius`` are measured (the rest are blocked anyway
    by the tube). A path that is free on this grid is free in ``world``.
    """
    xmin, ymin, xmax, ymax = world.bounds
    h = float(resolution)
    W, H = int(np.ceil((xmax - xmin) / h - 1e-9)), int(np.ceil((ymax - ymin) / h - 1e-9))
    occ = np.ones((H, W), dtype=bool)
    ix0, iy0, ix1, iy1 = 0, 0, W, H
    if within is not None:
        seed, radius = within
        lo = np.floor((seed.min(axis=0) - radius - (xmin, ymin)) / h).astype(int) - 1
        hi = np.ceil((seed.max(axis=0) + radius - (xmin, ymin)) / h).astype(int) + 1
        ix0, iy0 = max(lo[0], 0), max(lo[1], 0)
        ix1, iy1 = min(hi[0], W), min(hi[1], H)
    if ix1 <= ix0 or iy1 <= iy0:
        return GridMap(occ, h, (xmin, ymin), f"{world.name} raster")
    x0 = xmin + h * np.arange(ix0, ix1)
    y0 = ymin + h * np.arange(iy0, iy1)
    # cells must lie inside the bounds shrunk by the clearance
    inside_x = (x0 >= xmin + clearance - 1e-12) & (x0 + h <= xmax - clearance + 1e-12)
    inside_y = (y0 >= ymin + clearance - 1e-12) & (y0 + h <= ymax - clearance + 1e-12)
    blocked = ~(inside_y[:, None] & inside_x[None, :])
    if len(world.circles):
        # square-to-centre distance per axis, separable: (circles, columns) and (circles, rows)
        cx, cy = world.circles[:, 0:1], world.circles[:, 1:2]
        dx = np.maximum(np.maximum(x0[None, :] - cx, cx - (x0[None, :] + h)), 0.0)
        dy = np.maximum(np.maximum(y0[None, :] - cy, cy - (y0[None, :] + h)), 0.0)
        reach2 = (world.radii + clearance) ** 2
        for k in range(len(world.circles)):  # a loop over obstacles (few), each step vectorised over cells
            blocked |= dy[k][:, None] ** 2 + dx[k][None, :] ** 2 <= reach2[k] * (1 + 1e-12)
    occ[iy0:iy1, ix0:ix1] = blocked
    return GridMap(occ, h, (xmin, ymin), f"{world.name} raster {h:g} m")


class Band:
    """The cells within ``separation`` metres of a path (the refinement's tube around it,
    :func:`cells_within`) on a grid of ``h``-metre cells over the
    world: the map's own cells, or a circle world's bounds at its raster step.

    ``separation = 0`` means "this exact path": :meth:`holds` is then equality.
    """

    def __init__(self, world, path, separation: float, h: float | None = None):
        self.path = np.asarray(path, float).reshape(-1, 2)
        self.separation = float(separation)
        if world.is_grid:
            self.h, self.origin = float(world.resolution), np.asarray(world.origin, float)
            self.width, self.height = world.width, world.height
        else:
            xmin, ymin, xmax, ymax = world.bounds
            self.h = float(h) if h is not None else raster_step(world)
            self.origin = np.array([xmin, ymin], float)
            self.width = int(np.ceil((xmax - xmin) / self.h - 1e-9))
            self.height = int(np.ceil((ymax - ymin) / self.h - 1e-9))
        self.mask = (cells_within(self.width, self.height, self.h, self.origin, self.path, self.separation)
                     if self.separation > 0 else None)

    def holds(self, path: np.ndarray) -> bool:
        """Whether all of ``path`` (sampled every half cell) lies in the band's cells."""
        P = np.asarray(path, float).reshape(-1, 2)
        if self.mask is None:
            return P.shape == self.path.shape and bool(np.allclose(P, self.path))
        c = np.floor((densify(P, 0.5 * self.h) - self.origin) / self.h).astype(np.int64)
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


def tube_grid(world, seed, radius: float, clearance: float = 0.0, resolution: float | None = None) -> GridMap:
    """The search grid of the tube: cells outside ``radius`` metres of ``seed`` blocked.

    Grids: the map inflated by ``clearance`` (cell-wise, as the exact planner
    does). Circle worlds: :func:`rasterise_circles` at :func:`raster_step`.
    """
    P = np.asarray(seed, float)
    if world.is_grid:
        base = world.inflate(clearance) if clearance > 0 else world
        mask = cells_within(base.width, base.height, base.resolution, base.origin, P, radius)
        return GridMap(base.occ | ~mask, base.resolution, base.origin, f"{world.name} tube {radius:g} m")
    h = raster_step(world, resolution)
    raster = rasterise_circles(world, h, clearance, within=(P, radius))
    mask = cells_within(raster.width, raster.height, h, raster.origin, P, radius)
    return GridMap(raster.occ | ~mask, h, raster.origin, f"{world.name} tube {radius:g} m")


def _end_cell(grid: GridMap, p: np.ndarray) -> np.ndarray:
    """The cell holding ``p``; a point on the map's top or right edge belongs to the last cell."""
    return np.clip(grid.cell_of(p), 0, [grid.width - 1, grid.height - 1])


def tube_path(world, seed, radius: float, clearance: float = 0.0, resolution: float | None = None) -> TubeSeed:
    """Shortest any-angle path from ``seed[0]`` to ``seed[-1]`` that stays in the tube.

    Args:
        world: GridMap or CircleWorld.
        seed: ``(M, 2)`` collision-free path in metres.
        radius: tube radius in metres (``> 0``).
        clearance: required distance to obstacles, metres.
        resolution: raster cell size for circle worlds, metres (default :func:`raster_step`).

    Returns:
        :class:`TubeSeed`; ``found`` is False (with the reason) when the start or goal
        cell is blocked on the search grid or the tube holds no path. The path runs
        through the centres of the start and goal cells, joined to the real end points.
    """
    t0 = time.perf_counter()
    r = float(radius)
    if not np.isfinite(r) or r <= 0:
        raise ParameterError(f"tube radius must be a positive number of metres, got {radius!r}")
    P = np.asarray(seed, float)
    grid = tube_grid(world, P, r, clearance, resolution)
    ends = []
    for p, what in ((P[0], "start"), (P[-1], "goal")):
        c = _end_cell(grid, p)
        if grid.occ[c[1], c[0]]:
            return TubeSeed(None, float("inf"), f"tube search skipped: the {what} cell (ix={c[0]}, iy={c[1]}) is "
                            f"blocked on the {grid.resolution:g} m search grid (by an obstacle or its clearance, "
                            "or outside the tube)", grid, time.perf_counter() - t0)
        ends.append(grid.cell_center(c))
    try:
        path, _ = visibility_path(grid, ends[0], ends[1], "centres")
    except InfeasibleQueryError:
        return TubeSeed(None, float("inf"), f"tube search found no path within {r:g} m of the seed", grid,
                        time.perf_counter() - t0)
    # join the real end points to their cell centres (a straight piece inside a free cell)
    if not np.allclose(path[0], P[0]):
        path = np.vstack([P[0], path])
    if not np.allclose(path[-1], P[-1]):
        path = np.vstack([path, P[-1]])
    path[0], path[-1] = P[0], P[-1]
    return TubeSeed(path, float(path_length(path)), "", grid, time.perf_counter() - t0)


def refine_in_tube(world, seed, smoother, radius: float, clearance: float = 0.0, resolution: float | None = None,
                   **options):
    """Smooth ``seed`` and the shortest path in its tube; keep the shorter valid result.

    Args:
        world: GridMap or CircleWorld.
        seed: ``(M, 2)`` path in metres.
        smoother: ``smoother(world, path, clearance, **options) -> SmoothResult``
            (:func:`optplan.solvers.nlp.smooth_path` or
            :func:`optplan.solvers.qp.smooth_path_qp`).
        radius: tube radius, metres; ``0`` smooths the seed alone (purely local).
        clearance: required distance to obstacles, metres.
        resolution: raster cell size for circle worlds, metres.
        **options: passed to ``smoother``. A ``warm_start`` is used for the
            original seed only (it belongs to that solve). With the CasADi smoother the
            tube path gets the seed's number of points (one NLP for both solves) unless
            ``n_points`` is given.

    Returns:
        A ``SmoothResult``: the shorter of the two smoothed paths among those whose
        ``success`` says they passed ``validate_path``; ``solve_time_s``,
        ``iterations`` and ``rounds`` count both solves and the tube search. The
        message says which seed won, or why the tube gave nothing. When neither
        smoothing succeeds, the original seed's failed result is returned, as
        without a tube.
    """
    from dataclasses import replace

    from .nlp.smoothing import check_seed_ends

    t0 = time.perf_counter()
    r = float(radius)
    if not np.isfinite(r) or r < 0:
        raise ParameterError(f"tube_radius must be a finite number >= 0 metres, got {radius!r}")
    P, refused = check_seed_ends(world, seed, clearance)
    if refused is not None:  # bad shape or a blocked end: no smoother, and no tube, can help
        return refused
    own = smoother(world, P, clearance, **options)
    if r == 0:
        return own
    tube = tube_path(world, P, r, clearance, resolution)
    if not tube.found:
        note = tube.message
        return replace(own, solve_time_s=time.perf_counter() - t0,
                       message="; ".join(m for m in (own.message, note) if m))
    rest = {k: v for k, v in options.items() if k != "warm_start"}
    if own.warm is not None and "n_points" not in rest:
        # the CasADi smoother: smooth the tube path with the seed's point count, so both solves
        # use one built NLP (building one costs about as much as solving it on a 256x256 map);
        # the tube path is no longer than the seed, so it gets at least its default density
        rest["n_points"] = len(own.warm.points)
    other = smoother(world, tube.path, clearance, **rest)
    total = dict(solve_time_s=time.perf_counter() - t0, iterations=own.iterations + other.iterations,
                 rounds=own.rounds + other.rounds)
    own_len = float(path_length(own.path)) if own.success else float("inf")
    other_len = float(path_length(other.path)) if other.success else float("inf")
    # a tie (both solves ended on the same path, up to rounding) keeps the seed's result, so
    # the choice does not depend on the last bits of two solves
    if other.success and other_len < own_len - TIE * max(own_len, 1.0):
        what = (f"tube {r:g} m: the path in the tube was shorter ({other_len:.4f} m vs {own_len:.4f} m from the seed)"
                if own.success else f"tube {r:g} m: the seed's smoothing failed ({own.message}); used the tube path")
        return replace(other, message="; ".join(m for m in (what, other.message) if m), **total)
    note = (f"tube {r:g} m: the seed's class was kept ({own_len:.4f} m <= {other_len:.4f} m in the tube)"
            if other.success else f"tube {r:g} m: smoothing the tube path failed ({other.message})")
    return replace(own, message="; ".join(m for m in (own.message, note) if m), **total)
