"""The seeded recipes that made the generated paper maps of ``optplan/data/maps/``.

* Grids: axis-aligned blocks dropped at random until the paper's apparent obstacle
  density is reached, with start and goal corners kept free and the start-goal
  connection checked.
* Circle worlds: non-overlapping discs, keeping the first seed whose exact optimum
  detour (tangent graph, :mod:`optplan.solvers.tangent_graph`) lies in the band the
  paper's reported lengths imply.

``python -m optplan.worldgen.papermaps`` regenerates the generated files (it is
deterministic) and prints each map's exact optimum. Reading the maps is
:mod:`optplan.world.papermaps` (``paper_map``, ``catalogue``).
"""
from __future__ import annotations

import argparse

import numpy as np

from ..world.maps import MAPS_DIR


def block_grid(size: int, density: float, max_block: int, seed: int, keep_free: int = 2) -> np.ndarray:
    """Random axis-aligned blocks (1..max_block cells a side) until ``density`` is reached;
    the ``keep_free`` x ``keep_free`` corners at bottom-left and top-right stay free and the
    two corners stay 4-connected (the seed is advanced until they are)."""
    from scipy.ndimage import label

    for attempt in range(1000):
        rng = np.random.default_rng(seed + 7919 * attempt)
        occ = np.zeros((size, size), dtype=bool)
        while occ.mean() < density:
            w, h = rng.integers(1, max_block + 1, size=2)
            x, y = rng.integers(0, size - w + 1), rng.integers(0, size - h + 1)
            occ[y:y + h, x:x + w] = True
            occ[:keep_free, :keep_free] = False
            occ[-keep_free:, -keep_free:] = False
        lab, _ = label(~occ)
        if lab[0, 0] == lab[-1, -1] != 0:
            return occ
    raise RuntimeError("no connected map found")  # pragma: no cover


def circle_world(size: float, n: int, r_range: tuple[float, float], detour_band: tuple[float, float],
                 seed: int, safety: float = 0.0, gap: float = 0.3):
    """Non-overlapping discs in ``[0, size]^2``; the first seed (from ``seed``) whose exact
    optimum from (0, 0) to (size, size) exceeds the straight line by a ratio inside
    ``detour_band`` is kept. Returns ``(circles, optimum, seed_used)``."""
    from ..solvers.tangent_graph import tangent_shortest_path
    from ..world.circles import CircleWorld

    straight = np.hypot(size, size)
    for s in range(seed, seed + 5000):
        rng = np.random.default_rng(s)
        circles = []
        tries = 0
        while len(circles) < n and tries < 5000:
            tries += 1
            r = rng.uniform(*r_range)
            c = rng.uniform(r + 0.5, size - r - 0.5, size=2)
            if np.hypot(*c) < r + 1.0 or np.hypot(*(c - size)) < r + 1.0:
                continue
            if all(np.hypot(*(c - q[:2])) > r + q[2] + gap for q in circles):
                circles.append(np.array([c[0], c[1], r]))
        w = CircleWorld((0, 0, size, size), np.array(circles), safety)
        try:
            L, _ = tangent_shortest_path(w, np.zeros(2), np.full(2, float(size)))
        except Exception:
            continue
        if detour_band[0] <= L / straight - 1 <= detour_band[1]:
            return np.round(np.array(circles), 3), L, s
    raise RuntimeError("no circle world in the band")  # pragma: no cover


GENERATED = {
    # name: (kind, parameters)
    "hou2024_base50": ("grid", dict(size=50, density=0.16, max_block=5, seed=2024)),
    "yang2023_fusion25": ("grid", dict(size=25, density=0.14, max_block=3, seed=2023)),
    "yuan2021_25": ("grid", dict(size=25, density=0.2, max_block=3, seed=2021)),
    "li2023_11": ("grid", dict(size=11, density=0.2, max_block=2, seed=11, keep_free=1)),
    "li2023_30": ("grid", dict(size=30, density=0.22, max_block=4, seed=30)),
    "li2023_60": ("grid", dict(size=60, density=0.22, max_block=6, seed=60)),
    "li2023_90": ("grid", dict(size=90, density=0.22, max_block=8, seed=90)),
    "chen2025_30": ("grid", dict(size=30, density=0.2, max_block=3, seed=2025)),
    "yang2023_env1": ("circles", dict(size=10, n=7, r_range=(0.5, 1.2), detour_band=(0.022, 0.034), seed=1)),
    "yang2023_env2": ("circles", dict(size=15, n=12, r_range=(0.5, 1.4), detour_band=(0.003, 0.012), seed=1)),
}


def regenerate(write: bool = True) -> None:
    """Rebuild the generated maps (deterministic) and print their sizes."""
    import json

    from ..world.grid import GridMap
    from ..world.loaders import save_map

    for name, (kind, p) in GENERATED.items():
        if kind == "grid":
            occ = block_grid(**p)
            g = GridMap(occ, name=name)
            if write:
                save_map(g, MAPS_DIR / f"{name}.txt")
            print(f"{name}: {g.width}x{g.height}, density {occ.mean():.3f}")
        else:
            circles, L, used = circle_world(**p)
            doc = {"name": name, "bounds": [0, 0, p["size"], p["size"]], "safety": 0.0,
                   "circles": circles.tolist(),
                   "note": f"seeded recipe optplan.worldgen.papermaps.circle_world(seed={used}); exact optimum {L:.6f} m"}
            if write:
                (MAPS_DIR / f"{name}.json").write_text(json.dumps(doc, indent=1) + "\n")
            print(f"{name}: {len(circles)} circles, seed {used}, optimum {L:.4f} (straight {np.hypot(p['size'], p['size']):.4f})")


if __name__ == "__main__":  # pragma: no cover
    ap = argparse.ArgumentParser(description="regenerate the generated paper maps")
    ap.add_argument("--dry-run", action="store_true")
    regenerate(write=not ap.parse_args().dry_run)
