"""The clearance model that gradient solvers see (CasADi).

Verdicts are never taken here: every result is judged by the exact segment rule.
This model only has to be smooth and close, so that the solver's answer usually
passes that rule on the first try.

* Circle worlds: every segment's exact distance to the centre of each grown
  circle (all of them, or with many circles the nearest few to each segment),
  and every interior vertex inside the border: segment-exact, no samples.
* Grid maps: every segment's distance to the convex obstacle corners nearest it
  (where a straight piece can cut in between samples), and the distance from
  samples along each segment (closer than half a cell) to the blocked boundary
  boxes nearest them (maximal rectangles of blocked cells), for walls between
  corners; the map border. Maxima are
  smoothed (:func:`soft_plus`), which gradient solvers need, and the bound adds
  back what the smoothing overshoots.

Which obstacles each piece is kept off is read off the current path
(:func:`active_sets`) and re-read when a solve is repeated. As an objective term on
grids, clearance reads the distance field's cubic spline from a strip around the
start path (:func:`field_strip`, a parameter of the problem), so the set-up does not
grow with the map.
"""
from __future__ import annotations

import numpy as np

from ..world.polyline import segment_point_distances
from .namespaces import Sym
from ..world.derived import DerivedStore

_DERIVED = DerivedStore("formulations.clearance_model")  # this module's data derived from worlds


# grids: the distance spline is handed to a gradient solver for the tiles within this many
# cells of the start path plus the farthest a solve may move it (the solver's strip)
STRIP_CELLS = 6.0


def field_strip(ctx, path: np.ndarray, radius: float, capacity: int | None = None) -> tuple[np.ndarray, int]:
    """The numbers the symbolic distance field reads near ``path`` (``(N, 2)`` metres):
    the path-local strip of :func:`optplan.world.fields.distance_spline` within ``radius``
    metres, padded to ``capacity`` blocks; ``(values, blocks needed)``."""
    from ..world.fields import distance_spline

    return distance_spline(ctx.world).strip(path, radius, capacity)


def sample_points(P: Sym, per_segment: int):
    """CasADi columns ``(qx, qy)`` of the interior vertices and ``per_segment - 1`` points
    inside every segment of the symbolic path ``P`` ``(N, 2)``."""
    import casadi as ca

    m = P.m
    xs, ys = m[:, 0], m[:, 1]
    qx = [xs[1:-1]] if P.shape[0] > 2 else []
    qy = [ys[1:-1]] if P.shape[0] > 2 else []
    for j in range(1, per_segment):
        t = j / per_segment
        qx.append((1 - t) * xs[:-1] + t * xs[1:])
        qy.append((1 - t) * ys[:-1] + t * ys[1:])
    if not qx:
        return ca.DM.zeros(0, 1), ca.DM.zeros(0, 1)
    return ca.vertcat(*qx), ca.vertcat(*qy)


def symbolic_signed_distance(P: Sym, ctx, per_segment: int) -> Sym:
    """Signed distance at the sample points, as one symbolic vector (for clearance used as
    an objective term). Circles: the smallest distance over circles and border (piecewise smooth).

    Grids: the distance field's cubic spline read from a path-local strip
    (:meth:`optplan.world.fields.DistanceSpline.symbolic`), a parameter of the problem
    (:meth:`ProgramContext.field_parameter`): neither the set-up nor the derivatives grow
    with the map. Away from the strip the distance reads as the strip's radius."""
    import casadi as ca

    qx, qy = sample_points(P, per_segment)
    M = qx.shape[0]
    if ctx.is_grid:
        from ..world.fields import distance_spline

        d = distance_spline(ctx.world).symbolic(qx, qy, ctx.field_parameter())
        return Sym(d, (M,))
    xmin, ymin, xmax, ymax = ctx.world.bounds
    d = ca.fmin(ca.fmin(qx - xmin, xmax - qx), ca.fmin(qy - ymin, ymax - qy))
    circles, radii = ctx.world.circles, ctx.world.radii
    for (cx, cy, _), R in zip(circles, radii):
        d = ca.fmin(d, ca.sqrt((qx - cx) ** 2 + (qy - cy) ** 2 + 1e-12) - R)
    return Sym(d, (M,))


SMOOTHING = 0.02   # width of the smooth max(x, 0) below, in cells (grids) or parameter units


def soft_plus(ca, x, eps: float):
    """A smooth ``max(x, 0)``: ``(x + sqrt(x^2 + eps^2)) / 2``, above it by at most ``eps / 2``.
    Gradient solvers converge far better on it than on the kinked maximum."""
    return 0.5 * (x + ca.sqrt(x * x + eps * eps))


def _segment_point_dist2(ca, ax, ay, bx, by, qx, qy):
    """Squared distance from segments ``a -> b`` to points ``q`` (CasADi columns, element-wise),
    with the projection parameter clamped smoothly to [0, 1]."""
    ux, uy = bx - ax, by - ay
    t = ((qx - ax) * ux + (qy - ay) * uy) / (ux * ux + uy * uy + 1e-12)
    t = 1 - soft_plus(ca, 1 - soft_plus(ca, t, SMOOTHING), SMOOTHING)
    ex, ey = qx - ax - t * ux, qy - ay - t * uy
    return ex * ex + ey * ey


def clearance_rows(P: Sym, ctx, clearance: float, per_segment: int, sym, shapes: dict):
    """Constraint rows ``g >= 0`` that keep the path ``clearance + margin`` from obstacles.

    Obstacle data and the margin are CasADi *parameters*, so one built solver serves every
    later solve whose active sets have the same ``shapes`` (``{"boxes": (M, K), ...}``, from
    :func:`active_sets`). Returns ``(g, p, fill)``: the rows, the parameter column and
    ``fill(margin, active) -> values of p``.

    * Circle worlds: every segment's exact distance to each grown circle's centre
      (``active["circles"]``: ``(S, K)`` circles per segment; absent: all), and every
      interior vertex inside the border. Segment-exact: no samples needed.
    * Grids: every segment's exact distance to the convex obstacle corners near it
      (``active["corners"]``, ``(S, K)``), which is where a straight piece between two
      samples could cut in, plus the samples' distance to the blocked boundary cells
      near them (``active["boxes"]``, ``(M, K)``) for walls between corners, and the border.
    """
    import casadi as ca

    m = P.m
    ax, ay, bx, by = m[:-1, 0], m[:-1, 1], m[1:, 0], m[1:, 1]
    S = P.shape[0] - 1
    qx, qy = sample_points(P, per_segment)
    xmin, ymin, xmax, ymax = ctx.world.bounds
    blocks = {"border": 1, "need": 1}
    if ctx.is_grid:
        if "boxes" in shapes:
            blocks["boxes"] = 4 * int(np.prod(shapes["boxes"]))
        if "corners" in shapes:
            blocks["corners"] = 2 * int(np.prod(shapes["corners"]))
    elif len(ctx.world.circles):
        k = shapes.get("circles", (S, len(ctx.world.circles)))[1]
        blocks["circles"] = 3 * S * k
    p = sym.sym("obstacles", sum(blocks.values()))
    at, off = {}, 0
    for name, size in blocks.items():
        at[name] = p[off:off + size]
        off += size
    border, need = at["border"], at["need"]
    # the map is convex: vertices inside the border keep every segment inside it
    vx, vy = m[1:-1, 0], m[1:-1, 1]
    rows = [vx - xmin - border, xmax - vx - border, vy - ymin - border, ymax - vy - border] if S > 1 else []
    eps = SMOOTHING * ctx.cell
    if ctx.is_grid:
        if "boxes" in at:
            Mb, K = shapes["boxes"]
            blk = ca.reshape(at["boxes"], Mb, 4 * K)
            for k in range(K):
                lox, loy, hix, hiy = (blk[:, 4 * k + j] for j in range(4))
                dx = soft_plus(ca, lox - qx, eps) + soft_plus(ca, qx - hix, eps)
                dy = soft_plus(ca, loy - qy, eps) + soft_plus(ca, qy - hiy, eps)
                rows.append(dx * dx + dy * dy - need * need)
        if "corners" in at:
            Sc, K = shapes["corners"]
            blk = ca.reshape(at["corners"], Sc, 2 * K)
            for k in range(K):
                rows.append(_segment_point_dist2(ca, ax, ay, bx, by, blk[:, 2 * k], blk[:, 2 * k + 1]) - need * need)
    elif "circles" in at:
        K = blocks["circles"] // (3 * S)
        blk = ca.reshape(at["circles"], S, 3 * K)
        for k in range(K):
            cx, cy, R = blk[:, 3 * k], blk[:, 3 * k + 1], blk[:, 3 * k + 2]
            rows.append(_segment_point_dist2(ca, ax, ay, bx, by, cx, cy) - (R + need) ** 2)
    g = ca.vertcat(*rows) if rows else sym.zeros(0, 1)

    def fill(margin: float, active: dict) -> np.ndarray:
        vals = [np.array([clearance + margin])]
        if ctx.is_grid:
            # 0 clearance still keeps out of cell interiors; the smooth box distance overshoots
            # by up to one smoothing width, which the bound adds back
            vals.append(np.array([max(clearance, 1e-3 * ctx.cell) + margin + eps]))
            if "boxes" in at:
                b = boundary_boxes(ctx.world)[active["boxes"]]          # (M, K, 4)
                vals.append(b.reshape(b.shape[0], -1).ravel(order="F"))
            if "corners" in at:
                c = convex_corners(ctx.world)[active["corners"]]       # (S, K, 2)
                vals.append(c.reshape(c.shape[0], -1).ravel(order="F"))
        else:
            vals.append(np.array([clearance + margin]))
            if "circles" in at:
                circles, radii = ctx.world.circles, ctx.world.radii
                ids = active.get("circles")
                if ids is None:
                    ids = np.broadcast_to(np.arange(len(circles)), (S, len(circles)))
                data = np.stack([circles[ids, 0], circles[ids, 1], radii[ids]], axis=2)   # (S, K, 3)
                vals.append(data.reshape(S, -1).ravel(order="F"))
        return np.concatenate(vals)

    return g, p, fill


def active_shapes(active: dict | None) -> dict:
    """The shapes of an active-set dict (what a built solver depends on)."""
    return {k: tuple(v.shape) for k, v in (active or {}).items() if v is not None}


def convex_corners(grid) -> np.ndarray:
    """``(V, 2)`` grid vertices (metres) where a path can wrap round an obstacle: exactly one
    of the four cells around the vertex is blocked, or two diagonal ones are (the map's
    outside counts as blocked); cached on the map."""
    key = "convex_corners"
    out = _DERIVED.of(grid).get(key)
    if out is None:
        pad = np.pad(np.asarray(grid.occ, bool), 1, constant_values=True)
        a, b = pad[:-1, :-1], pad[:-1, 1:]      # cells below-left, below-right of vertex (iy, ix)
        c, d = pad[1:, :-1], pad[1:, 1:]        # above-left, above-right
        count = a.astype(int) + b + c + d
        diagonal = (count == 2) & ((a & d) | (b & c))
        iy, ix = np.nonzero((count == 1) | diagonal)
        r = float(grid.resolution)
        out = np.stack([grid.origin[0] + ix * r, grid.origin[1] + iy * r], axis=1)
        _DERIVED.of(grid)[key] = out
    return out


def active_sets(ctx, path: np.ndarray, per_segment: int, k: int = 3) -> dict:
    """Which obstacles each segment / sample of ``path`` is kept off (the nearest ``k``)."""
    out = {}
    if ctx.is_grid:
        corners = convex_corners(ctx.world)
        if len(corners):
            kk = min(k, len(corners))
            d = segment_point_distances(path, corners)
            out["corners"] = np.argsort(d, axis=1)[:, :kk]
        samples = numeric_sample_points(path, per_segment)
        if len(samples):
            out["boxes"] = nearest_box_ids(ctx.world, samples, k)
        return out
    circles = ctx.world.circles
    if len(circles) > ALL_CIRCLES:
        d = segment_point_distances(path, circles[:, :2]) - ctx.world.radii[None]
        out["circles"] = np.argsort(d, axis=1)[:, :k]
    return out


ALL_CIRCLES = 40   # up to this many circles every segment is kept off every circle


def numeric_sample_points(path: np.ndarray, per_segment: int) -> np.ndarray:
    """The points :func:`sample_points` uses, for a numeric path ``(N, 2)``: ``(M, 2)``."""
    P = np.asarray(path, float)
    parts = [P[1:-1]]
    for j in range(1, per_segment):
        t = j / per_segment
        parts.append((1 - t) * P[:-1] + t * P[1:])
    return np.vstack(parts)


def boundary_boxes(grid) -> np.ndarray:
    """``(M, 4)`` boxes ``(xmin, ymin, xmax, ymax)``, metres, that together cover exactly the
    blocked cells: maximal runs of blocked cells in each row, merged with the identical runs
    of the rows above. A wall is one box, not a row of neighbouring cells, so the boxes
    nearest a sample are different obstacles and a gradient solver gets no near-duplicate
    constraint rows (which slow IPOPT down and stall it). Cached on the map."""
    key = "obstacle_boxes"
    boxes = _DERIVED.of(grid).get(key)
    if boxes is None:
        occ = np.asarray(grid.occ, bool)
        edge = np.diff(np.pad(occ.astype(np.int8), ((0, 0), (1, 1))), axis=1)
        open_runs: dict[tuple[int, int], int] = {}     # (x0, x1) -> first row of the open box
        out = []
        for iy in range(occ.shape[0] + 1):
            if iy < occ.shape[0]:
                x0s, x1s = np.flatnonzero(edge[iy] == 1), np.flatnonzero(edge[iy] == -1)
                runs = set(zip(x0s.tolist(), x1s.tolist()))
            else:
                runs = set()
            for run in [r for r in open_runs if r not in runs]:
                out.append((run[0], open_runs.pop(run), run[1], iy))
            for run in runs:
                open_runs.setdefault(run, iy)
        r = float(grid.resolution)
        ox, oy = (float(v) for v in grid.origin)
        b = np.asarray(out, float).reshape(-1, 4)
        boxes = np.stack([ox + b[:, 0] * r, oy + b[:, 1] * r, ox + b[:, 2] * r, oy + b[:, 3] * r], axis=1)
        _DERIVED.of(grid)[key] = boxes
    return boxes


def point_box_distances(points: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """``(M, B)`` Euclidean distances from points to axis-aligned boxes (0 inside)."""
    q = np.asarray(points, float)[:, None, :]
    lo, hi = boxes[None, :, :2], boxes[None, :, 2:]
    e = np.maximum(np.maximum(lo - q, q - hi), 0.0)
    return np.hypot(e[..., 0], e[..., 1])


def nearest_box_ids(grid, points: np.ndarray, k: int) -> np.ndarray | None:
    """``(M, k)`` indices of the ``k`` obstacle boxes nearest each point by exact distance
    (``None`` when the map has no blocked cell)."""
    boxes = boundary_boxes(grid)
    if not len(boxes):
        return None
    k = min(k, len(boxes))
    pts = np.asarray(points, float)
    out = np.empty((len(pts), k), dtype=np.int64)
    step = max(1, 2_000_000 // len(boxes))       # bounded memory on large maps
    for i in range(0, len(pts), step):
        d = point_box_distances(pts[i:i + step], boxes)
        out[i:i + step] = np.argpartition(d, k - 1, axis=1)[:, :k] if k < len(boxes) else np.argsort(d, axis=1)
    return out
