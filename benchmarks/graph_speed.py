"""Graph search timings: A* and Dijkstra against networkx and scipy, and the exact visibility search.

    python benchmarks/graph_speed.py            # every table
    python benchmarks/graph_speed.py --quick    # 32x32 to 128x128 only, fewer repeats
    python benchmarks/graph_speed.py --skip-visibility --repeats 15   # the A* tables, more rounds
    python benchmarks/graph_speed.py --whole     # the whole op.shortest_path call, networkx, scipy

networkx is the anchor for A*: it is not a dependency of optplan. When it is not
importable the script installs it for itself into ``/tmp/networkx-anchor`` (``pip
install --target``, kept out of optplan's environment; ``--anchor-dir`` elsewhere);
``--no-anchors`` leaves its column empty instead.

Table 1 (A*, 8-connected cell centres, no corner cutting): seeded maps from
32x32 to 512x512 (random 20 % and 30 % obstacles, a maze, rooms with doors),
one query between free cells near opposite corners, and seeded city maps
(``optplan.worldgen.city``: blocks of buildings between streets). Columns: our
``shortest_path(method="astar")`` cold (first query on a fresh map: move table
and neighbour structure built); the A* search alone (``astar_cells``, cell to
cell, and ``cell_path``: the path between the two points) and the whole API
call (the path validated by the exact rule and its metrics computed, the exact
``min_clearance`` on its first read, not timed), warm, node to node (cell
centres) and point to point (off-centre points in the same cells);
``method="dijkstra"``; ``networkx.astar_path`` between the same cells (the graph
built once from the same move table, not timed, with the octile heuristic);
scipy's compiled ``csgraph.dijkstra`` (a whole shortest-path tree from the
start: the compiled limit); and the ratios networkx / ours.
Times are the best of interleaved rounds (the two cores are shared).

Table 1b: the same per query over the scenario rows of the Moving AI maps of
``../shared/data`` (room-32-32-4 is the 32x32 map of issue 43). A summary then
gives, per map size, the lowest networkx / API ratio node to node and point to
point over the maps, and scipy's times.

``--whole`` prints only the whole ``op.shortest_path(method="astar")`` call against
networkx's ``astar_path`` and scipy's compiled ``dijkstra`` (the whole tree from the
start cell, and the tree cut at the goal's distance with ``limit``: what a compiled
search that stops at the goal settles), per map kind and size, timed in batches of
calls, then the matrix of networkx / op ratios (issue 43 item 4: >= 2 at every size).

Table 2 (the exact any-angle search ``method="visibility"``): the Moving AI
maps of ``../shared/data`` (the scen row with the longest optimum), seeded
random grids, seeded 256x256 city maps (corner to corner) and seeded circle worlds.
"""
from __future__ import annotations

import argparse
import importlib
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import optplan as op
from optplan.solvers.graph import shortest_path
from optplan.solvers.gridpath.moves import move_table
from optplan.world.loaders import load_scen
from optplan.worldgen.city import city_map

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "movingai"

nx = None  # the anchor, imported by main() (never a dependency of optplan)


def import_networkx(anchor_dir: Path, install: bool):
    """networkx from this environment or ``anchor_dir``, installed there when absent."""
    if str(anchor_dir) not in sys.path:
        sys.path.append(str(anchor_dir))
    try:
        return importlib.import_module("networkx")
    except ImportError:
        if not install:
            return None
    print(f"installing networkx into {anchor_dir} (kept out of optplan's environment) ...", file=sys.stderr)
    try:
        subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--target", str(anchor_dir), "networkx"],
                       check=True)
        importlib.invalidate_caches()
        return importlib.import_module("networkx")
    except (subprocess.CalledProcessError, OSError, ImportError) as exc:
        print(f"could not set up networkx: {exc}", file=sys.stderr)
        return None


def timed(fn, repeats: int):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return float(np.median(times)), out


# ------------------------------------------------------------------ maps
def random_map(n: int, density: float, seed: int) -> np.ndarray:
    return np.random.default_rng(seed).random((n, n)) < density


def maze_map(n: int, seed: int) -> np.ndarray:
    """A perfect maze: corridors one cell wide on odd cells, walls between (iterative DFS)."""
    rng = np.random.default_rng(seed)
    occ = np.ones((n, n), dtype=bool)
    m = (n - 1) // 2  # rooms per side
    seen = np.zeros((m, m), dtype=bool)
    stack = [(0, 0)]
    seen[0, 0] = True
    occ[1, 1] = False
    while stack:
        x, y = stack[-1]
        nbrs = [(x + dx, y + dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
                if 0 <= x + dx < m and 0 <= y + dy < m and not seen[y + dy, x + dx]]
        if not nbrs:
            stack.pop()
            continue
        nx_, ny_ = nbrs[rng.integers(len(nbrs))]
        seen[ny_, nx_] = True
        occ[2 * ny_ + 1, 2 * nx_ + 1] = False
        occ[y + ny_ + 1, x + nx_ + 1] = False  # the wall between
        stack.append((nx_, ny_))
    return occ


def rooms_map(n: int, seed: int, room: int = 8) -> np.ndarray:
    """Square rooms ``room`` cells wide behind one-cell walls, two doors of 2 cells per wall, 5 % clutter."""
    rng = np.random.default_rng(seed)
    occ = rng.random((n, n)) < 0.05
    for k in range(0, n, room):
        occ[k, :] = True
        occ[:, k] = True
    for k in range(0, n, room):
        for j in range(0, n, room):
            for _ in range(2):
                d = j + 1 + rng.integers(max(room - 2, 1))
                occ[k, d:d + 2] = False  # a door in the horizontal wall
                occ[d:d + 2, k] = False  # and in the vertical one
    occ[0, :] = occ[:, 0] = True
    return occ


def far_query(grid):
    """Free cell centres near opposite corners, in the largest connected component."""
    from scipy.ndimage import label

    lab, _ = label(~grid.occ)  # 4-connected = 8-connected without corner cutting
    iy, ix = np.nonzero(lab > 0)
    sizes = np.bincount(lab[iy, ix])
    big = np.argmax(sizes)
    keep = lab[iy, ix] == big
    iy, ix = iy[keep], ix[keep]
    a = np.argmin(ix + iy)
    b = np.argmax(ix + iy)
    return grid.cell_center((ix[a], iy[a])), grid.cell_center((ix[b], iy[b]))


def grid_cases(sizes):
    for n in sizes:
        yield f"random 20 %", op.GridMap(random_map(n, 0.2, 1000 + n))
        yield f"random 30 %", op.GridMap(random_map(n, 0.3, 2000 + n))
        yield "maze", op.GridMap(maze_map(n, 3000 + n))
        yield "rooms", op.GridMap(rooms_map(n, 4000 + n))
        yield "city", city_map(n, seed=7000 + n)


# ------------------------------------------------------------------ anchors
def networkx_graph(grid):
    t = move_table(grid)
    src, k = np.nonzero(t.neighbours >= 0)
    dst = t.neighbours[src, k]
    keep = src < dst
    G = nx.Graph()
    G.add_nodes_from(np.nonzero(~grid.occ.ravel())[0].tolist())
    G.add_weighted_edges_from(zip(src[keep].tolist(), dst[keep].tolist(), t.step_length[k[keep]].tolist()))
    return G


def octile_heuristic(W: int):
    c = math.sqrt(2.0) - 2.0

    def h(a, b):
        dx, dy = abs(a % W - b % W), abs(a // W - b // W)
        return dx + dy + c * min(dx, dy)

    return h


def scipy_graph(grid):
    from scipy.sparse import csr_matrix

    t = move_table(grid)
    src, k = np.nonzero(t.neighbours >= 0)
    n = grid.width * grid.height
    return csr_matrix((t.step_length[k], (src, t.neighbours[src, k])), shape=(n, n))


# ------------------------------------------------------------------ tables
def interleaved(fns: dict, repeats: int) -> dict:
    """Best (minimum) wall time of each callable over ``repeats`` rounds, the callables
    taking turns within a round: the cores are shared, and the minimum is the time the
    work needs when nothing else runs."""
    best = {k: math.inf for k in fns}
    for _ in range(repeats):
        for k, fn in fns.items():
            t = time.perf_counter()
            fn()
            best[k] = min(best[k], time.perf_counter() - t)
    return best


def point_query(grid, s, g):
    """The point-to-point twin of a node-to-node query: off-centre points in the same cells."""
    r = grid.resolution
    return s + np.array([0.23, -0.31]) * r, g + np.array([-0.4, 0.17]) * r


def astar_table(sizes, repeats: int) -> dict:
    """Table 1; returns ``{size: [(map, nx / API node-to-node, nx / API point-to-point,
    scipy tree ms, API node-to-node ms), ...]}`` for the summary."""
    from optplan.solvers.graph.astar import astar_cells, cell_path
    from scipy.sparse.csgraph import dijkstra

    print("## A* on 8-connected grids (one query between far free cells)\n")
    if nx is None:
        print("networkx is not available (--no-anchors, or it could not be installed): its column is empty.\n")
    print(f"times: best of {repeats} interleaved rounds after a first (cold) call on a fresh map. "
          "nodes = `astar_cells` (cell to cell, a list of cells: the job networkx's astar_path does); "
          "search = `cell_path` (between the two exact points: the end cells joined, the path as points); "
          "API = the whole `shortest_path(method=\"astar\")` call (points checked, search, the path checked "
          "by the exact rule, its metrics; `min_clearance` is computed on its first read and not timed), "
          "node to node (cell centres) and point to point (off-centre points in the same cells); "
          "networkx = `astar_path` between the same cells; scipy = csgraph's compiled `dijkstra` "
          "(the whole shortest-path tree from the start cell: the compiled limit)\n")
    print("| map | size | length [m] | cold API [ms] | nodes [ms] | search [ms] | API node-to-node [ms] "
          "| API point-to-point [ms] | dijkstra API [ms] | networkx [ms] | scipy csgraph [ms] "
          "| networkx / nodes | networkx / API node-to-node | networkx / API point-to-point |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    per_size: dict = {}
    for name, grid in grid_cases(sizes):
        s, g = far_query(grid)
        ps, pg = point_query(grid, s, g)
        t0 = time.perf_counter()
        r = shortest_path(grid, s, g, method="astar")
        cold = time.perf_counter() - t0
        rp = shortest_path(grid, ps, pg, method="astar")
        rd = shortest_path(grid, s, g, method="dijkstra")
        assert r.feasible and rp.feasible and rd.feasible, name
        assert abs(rd.length - r.length) < 1e-9, (name, rd.length, r.length)
        W = grid.width
        si, gi = (int(v) for v in (np.floor(grid.to_grid([s, g])) @ [1, W]))
        A = scipy_graph(grid)
        D = dijkstra(A, directed=True, indices=si)
        assert abs(D[gi] * grid.resolution - r.length) < 1e-9
        table = move_table(grid)
        assert abs(astar_cells(table, [si], [gi])[1] * grid.resolution - r.length) < 1e-9, name
        fns = {"api": lambda: shortest_path(grid, s, g, method="astar"),
               "api_p": lambda: shortest_path(grid, ps, pg, method="astar"),
               "dijkstra": lambda: shortest_path(grid, s, g, method="dijkstra"),
               "scipy": lambda: dijkstra(A, directed=True, indices=si),
               "nodes": lambda: astar_cells(table, [si], [gi]),
               "search": lambda: cell_path(grid, s, g)}
        if nx is not None:
            G = networkx_graph(grid)
            h = octile_heuristic(W)
            npath = nx.astar_path(G, si, gi, heuristic=h, weight="weight")
            nlen = nx.path_weight(G, npath, "weight") * grid.resolution
            assert abs(nlen - r.length) < 1e-9, (name, nlen, r.length)
            fns["nx"] = lambda: nx.astar_path(G, si, gi, heuristic=h, weight="weight")
        t = interleaved(fns, repeats)
        cell = lambda k: f"{1e3 * t[k]:.2f}" if k in t else "-"
        ratio = lambda k: f"{t['nx'] / t[k]:.2f}" if "nx" in t and k in t else "-"
        print(f"| {name} | {grid.width}x{grid.height} | {r.length:.4f} | {1e3 * cold:.2f} | {cell('nodes')} "
              f"| {cell('search')} | {cell('api')} | {cell('api_p')} | {cell('dijkstra')} | {cell('nx')} "
              f"| {cell('scipy')} | {ratio('nodes')} | {ratio('api')} | {ratio('api_p')} |", flush=True)
        per_size.setdefault(f"{grid.width}x{grid.height}", []).append(
            (name, t["nx"] / t["api"] if "nx" in t else math.nan, t["nx"] / t["api_p"] if "nx" in t else math.nan,
             1e3 * t["scipy"], 1e3 * t["api"]))
    return per_size


def batched(fns: dict, repeats: int, budget: float = 0.02) -> dict:
    """Per-call time of each callable: :func:`interleaved` over batches of calls that last
    about ``budget`` seconds each (one call when a call takes longer), so that calls of tens
    of microseconds are not timed one by one against the clock's and the loop's overhead."""
    counts = {}
    for k, fn in fns.items():
        t = time.perf_counter()
        fn()
        counts[k] = max(1, int(budget / max(time.perf_counter() - t, 1e-7)))

    def batch(fn, n):
        def run():
            for _ in range(n):
                fn()
        return run

    best = interleaved({k: batch(fn, counts[k]) for k, fn in fns.items()}, repeats)
    return {k: v / counts[k] for k, v in best.items()}


def whole_table(sizes, repeats: int) -> None:
    """The whole ``op.shortest_path(method="astar")`` call against networkx's ``astar_path``
    and scipy's compiled Dijkstra (issue 43 item 4)."""
    from scipy.sparse.csgraph import dijkstra

    print("## The whole op.shortest_path call against networkx and scipy (issue 43 item 4)\n")
    if nx is None:
        print("networkx is not available (--no-anchors, or it could not be installed): its columns are empty.\n")
    print(f"per-call times, best of {repeats} interleaved rounds of ~20 ms batches, warm map. "
          "op = `op.shortest_path(grid, s, g, method=\"astar\")` whole (points checked, search, the path "
          "checked by the exact rule, length; turn metrics and `min_clearance` on their first read, not timed), "
          "node to node (cell centres) and point to point (off-centre points in the same cells); networkx = "
          "`astar_path` between the same cells (the goal of both columns); scipy = csgraph's compiled "
          "`dijkstra` from the start cell (`indices`): the whole tree, and stopped at the goal's distance "
          "(`limit`, the early stop of a search to one goal): the compiled limit\n")
    print("| map | size | op node-to-node [ms] | op point-to-point [ms] | networkx [ms] "
          "| networkx / op node-to-node | networkx / op point-to-point | scipy tree [ms] "
          "| scipy to the goal [ms] | op node-to-node / scipy to the goal |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    ratios: dict = {}
    for name, grid in grid_cases(sizes):
        s, g = far_query(grid)
        ps, pg = point_query(grid, s, g)
        r, rp = op.shortest_path(grid, s, g, method="astar"), op.shortest_path(grid, ps, pg, method="astar")
        assert r.feasible and rp.feasible, name
        W = grid.width
        si, gi = (int(v) for v in (np.floor(grid.to_grid([s, g])) @ [1, W]))
        A = scipy_graph(grid)
        D = dijkstra(A, directed=True, indices=si)
        assert abs(D[gi] * grid.resolution - r.length) < 1e-9, name
        limit = D[gi] * (1 + 1e-12)
        assert dijkstra(A, directed=True, indices=si, limit=limit)[gi] == D[gi]
        fns = {"op": lambda: op.shortest_path(grid, s, g, method="astar"),
               "op_p": lambda: op.shortest_path(grid, ps, pg, method="astar"),
               "tree": lambda: dijkstra(A, directed=True, indices=si),
               "goal": lambda: dijkstra(A, directed=True, indices=si, limit=limit)}
        if nx is not None:
            G = networkx_graph(grid)
            h = octile_heuristic(W)
            npath = nx.astar_path(G, si, gi, heuristic=h, weight="weight")
            assert abs(nx.path_weight(G, npath, "weight") * grid.resolution - r.length) < 1e-9, name
            fns["nx"] = lambda: nx.astar_path(G, si, gi, heuristic=h, weight="weight")
        t = batched(fns, repeats)
        ms = lambda k: f"{1e3 * t[k]:.3f}" if k in t else "-"
        ratio = lambda k: t["nx"] / t[k] if "nx" in t else math.nan
        ratios[(name, W)] = (ratio("op"), ratio("op_p"))
        print(f"| {name} | {W}x{grid.height} | {ms('op')} | {ms('op_p')} | {ms('nx')} | {ratio('op'):.2f} "
              f"| {ratio('op_p'):.2f} | {ms('tree')} | {ms('goal')} | {t['op'] / t['goal']:.1f} |", flush=True)
    names = list(dict.fromkeys(k[0] for k in ratios))
    print("\nnetworkx / op.shortest_path, node to node / point to point (goal: >= 2):\n")
    print("| map | " + " | ".join(f"{n}x{n}" for n in sizes) + " |")
    print("|---|" + "---|" * len(sizes))
    for name in names:
        print(f"| {name} | " + " | ".join(f"{ratios[(name, n)][0]:.2f} / {ratios[(name, n)][1]:.2f}"
                                       for n in sizes) + " |")


def scen_queries(limit: int):
    """The Moving AI maps of ``../shared/data`` with up to ``limit`` of their scenario rows each."""
    for rel, scen in (("mapf/room-32-32-4.map", "mapf/room-32-32-4-random-1.scen"),
                      ("dao/arena.map", "dao/arena.map.scen"), ("dao/den312d.map", "dao/den312d.map.scen")):
        if (DATA / rel).exists():
            grid = op.load_map(DATA / rel)
            rows = [e for e in load_scen(DATA / scen) if (e.start_x, e.start_y) != (e.goal_x, e.goal_y)]
            rows = rows[:: max(len(rows) // limit, 1)][:limit]
            yield Path(rel).stem, grid, [(np.array(e.start_world(grid.resolution)),
                                          np.array(e.goal_world(grid.resolution))) for e in rows]


def scen_table(repeats: int, limit: int, per_size: dict) -> None:
    """Per-query times over Moving AI scenario rows (the measurement of issue 43: a 32x32 map);
    each map's ratios join ``per_size`` under its size."""
    from scipy.sparse.csgraph import dijkstra

    print("\n## A* per query on the Moving AI maps (scenario rows)\n")
    print(f"up to {limit} rows of each map's scenario file (every k-th), each batch timed whole, best of "
          f"{repeats} interleaved rounds, divided by the number of queries; API as in the table above\n")
    print("| map | size | queries | API node-to-node [ms/query] | API point-to-point [ms/query] "
          "| networkx [ms/query] | scipy csgraph [ms/query] | networkx / API node-to-node "
          "| networkx / API point-to-point |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, grid, queries in scen_queries(limit):
        W = grid.width
        cells = [tuple(int(v) for v in (np.floor(grid.to_grid([s, g])) @ [1, W])) for s, g in queries]
        points = [point_query(grid, s, g) for s, g in queries]
        A = scipy_graph(grid)
        for (s, g), (ps, pg) in zip(queries, points):  # warm, and checked
            assert shortest_path(grid, s, g).feasible and shortest_path(grid, ps, pg).feasible

        def api():
            for s, g in queries:
                shortest_path(grid, s, g, method="astar")

        def api_p():
            for s, g in points:
                shortest_path(grid, s, g, method="astar")

        def sp():
            for si, _ in cells:
                dijkstra(A, directed=True, indices=si)

        fns = {"api": api, "api_p": api_p, "scipy": sp}
        if nx is not None:
            G = networkx_graph(grid)
            h = octile_heuristic(W)

            def nxq():
                for si, gi in cells:
                    nx.astar_path(G, si, gi, heuristic=h, weight="weight")

            fns["nx"] = nxq
        t = {k: v / len(queries) for k, v in interleaved(fns, repeats).items()}
        cell = lambda k: f"{1e3 * t[k]:.3f}" if k in t else "-"
        ratio = lambda k: f"{t['nx'] / t[k]:.2f}" if "nx" in t else "-"
        print(f"| {name} | {grid.width}x{grid.height} | {len(queries)} | {cell('api')} | {cell('api_p')} "
              f"| {cell('nx')} | {cell('scipy')} | {ratio('api')} | {ratio('api_p')} |", flush=True)
        per_size.setdefault(f"{grid.width}x{grid.height}", []).append(
            (f"Moving AI {name}", t["nx"] / t["api"] if "nx" in t else math.nan,
             t["nx"] / t["api_p"] if "nx" in t else math.nan, 1e3 * t["scipy"], 1e3 * t["api"]))


def summary(per_size: dict) -> None:
    """Per map size: the lowest networkx / API ratios over the maps, and scipy's times."""
    if not per_size:
        return
    print("\n## Summary per map size (goal, issue 43 item 4: networkx / API >= 2 node to node and point "
          "to point)\n")
    print("| size | lowest networkx / API node-to-node (map) | lowest networkx / API point-to-point (map) "
          "| scipy csgraph [ms] (min-max over maps) | API node-to-node / scipy (min-max) |")
    print("|---|---|---|---|---|")
    for size, rows in per_size.items():
        n2n = min(rows, key=lambda r: r[1])
        p2p = min(rows, key=lambda r: r[2])
        sc = [r[3] for r in rows]
        rel = [r[4] / r[3] for r in rows]
        print(f"| {size} | {n2n[1]:.2f} ({n2n[0]}) | {p2p[2]:.2f} ({p2p[0]}) | {min(sc):.2f}-{max(sc):.2f} "
              f"| {min(rel):.1f}-{max(rel):.1f} |")


def visibility_cases(quick: bool):
    for rel, scen in (("dao/arena.map", "dao/arena.map.scen"), ("dao/den312d.map", "dao/den312d.map.scen"),
                      ("mapf/room-32-32-4.map", "mapf/room-32-32-4-random-1.scen")):
        if (DATA / rel).exists():
            grid = op.load_map(DATA / rel)
            e = max(load_scen(DATA / scen), key=lambda r: r.optimal)
            yield Path(rel).stem, grid, e.start_world(), e.goal_world()
    for n in ((64,) if quick else (64, 128, 256)):
        grid = op.GridMap(random_map(n, 0.2, 5000 + n))
        s, g = far_query(grid)
        yield f"random 20 % (off-centre ends)", grid, s + [0.23, -0.31], g + [-0.4, 0.17]
    for seed in ((0,) if quick else (0, 1, 2)):
        grid = city_map(256, seed=seed)
        s, g = far_query(grid)
        yield f"city (seed {seed})", grid, s, g
    for n in ((100,) if quick else (100, 400)):
        rng = np.random.default_rng(6000 + n)
        side = 10.0 * math.sqrt(n / 25)
        c = np.column_stack([rng.uniform(0, side, (n, 2)), rng.uniform(0.1, 0.4, n)])
        c = c[np.hypot(c[:, 0], c[:, 1]) > c[:, 2] + 0.5]
        c = c[np.hypot(c[:, 0] - side, c[:, 1] - side) > c[:, 2] + 0.5]
        yield f"{len(c)} circles", op.CircleWorld((0, 0, side, side), c), (0.2, 0.2), (side - 0.2, side - 0.2)


def _rss_kib(field: str) -> int | None:
    """``VmRSS`` / ``VmHWM`` of this process in KiB (Linux), or None."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith(field + ":"):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def _visibility_run(world, s, g, conn) -> None:
    """In a child process: one cold visibility query, its time and the growth of the peak
    resident memory over the child's start (tracemalloc would slow numpy-heavy code)."""
    from optplan.world.derived import forget_derived

    forget_derived(world)
    start = _rss_kib("VmRSS")
    t0 = time.perf_counter()
    try:
        r = shortest_path(world, s, g, method="visibility")
        out = (f"{r.length:.4f}", str(r.feasible))
    except op.OptplanError as exc:
        out = (f"{type(exc).__name__}: {exc}", "-")
    t = time.perf_counter() - t0
    peak = _rss_kib("VmHWM")
    conn.send((t, None if start is None or peak is None else (peak - start) * 1024) + out)


def visibility_table(quick: bool, timeout: float) -> None:
    import multiprocessing as mp

    print("\n## Exact any-angle search (method=\"visibility\"), cold, one query per map\n")
    print(f"each query in its own process (forked), stopped after {timeout:g} s; memory = growth of the "
          "process's peak resident set (VmHWM) over its start\n")
    print("| map | size | time [s] | peak memory growth [MB] | length [m] | feasible |")
    print("|---|---|---|---|---|---|")
    ctx = mp.get_context("fork")
    # import what the queries import lazily (scipy.spatial for the clearance metric, ...)
    # before forking, so that no child's time includes a first import
    shortest_path(op.GridMap(np.arange(9).reshape(3, 3) == 4), (0.5, 0.5), (2.5, 2.5), method="visibility")
    shortest_path(op.CircleWorld((0, 0, 4, 4), [(2, 2, 1)]), (0.1, 0.1), (3.9, 3.9), method="visibility")
    for name, world, s, g in visibility_cases(quick):
        size = f"{world.width}x{world.height}" if hasattr(world, "occ") else f"{world.bounds[2]:g} m square"
        here, there = ctx.Pipe(duplex=False)
        proc = ctx.Process(target=_visibility_run, args=(world, s, g, there))
        proc.start()
        if here.poll(timeout):
            t, peak, length, feasible = here.recv()
            mem = "-" if peak is None else f"{peak / 2**20:.0f}"
            print(f"| {name} | {size} | {t:.3f} | {mem} | {length} | {feasible} |", flush=True)
        else:
            print(f"| {name} | {size} | > {timeout:g} (stopped) | - | - | - |", flush=True)
        proc.kill()
        proc.join()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="maps up to 128x128, fewer repeats")
    ap.add_argument("--skip-visibility", action="store_true")
    ap.add_argument("--skip-astar", action="store_true")
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds per visibility query (default 120)")
    ap.add_argument("--repeats", type=int, default=None,
                    help="interleaved rounds of the A* tables (default 5, --quick 3); more on a busy machine")
    ap.add_argument("--whole", action="store_true",
                    help="only the table of the whole op.shortest_path call against networkx and scipy")
    ap.add_argument("--sizes", type=int, nargs="+", default=None, help="map sizes of the A* tables")
    ap.add_argument("--no-anchors", action="store_true", help="do not import or install networkx")
    ap.add_argument("--anchor-dir", type=Path, default=Path("/tmp/networkx-anchor"),
                    help="where networkx is installed when this environment has none")
    a = ap.parse_args()
    global nx
    if not a.skip_astar and not a.no_anchors:
        nx = import_networkx(a.anchor_dir, install=True)
    sizes = tuple(a.sizes) if a.sizes else (32, 64, 128) if a.quick else (32, 64, 128, 256, 512)
    if a.whole:
        whole_table(sizes, a.repeats or (3 if a.quick else 7))
        return
    if not a.skip_astar:
        repeats = a.repeats or (3 if a.quick else 5)
        per_size = astar_table(sizes, repeats)
        scen_table(repeats, 50 if a.quick else 200, per_size)
        summary(per_size)
    if not a.skip_visibility:
        visibility_table(a.quick, a.timeout)


if __name__ == "__main__":
    main()
