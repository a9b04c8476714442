"""IPOPT, SLSQP, OSQP and cvxpy on the refinement's smoothing energy, one program per map.

    python benchmarks/refine_solvers.py                                # chen2025_20 hou2024_env2 li2023_30
    python benchmarks/refine_solvers.py li2023_90 yang2023_env1 --n 80
    python benchmarks/refine_solvers.py room.txt --start 0.5 0.5 --goal 9.5 9.5 --clearance 0.1
    python benchmarks/refine_solvers.py --quick                        # n = 25 on the first map only

For every map the script builds ``op.smoothing_program(world, start, goal, n=N,
w_smooth=W, clearance=C)`` (``sum |dp|^2 + W sum |d2p|^2`` over N points, the exact
collision rule as the constraint) and hands it to ``op.compare`` with the solvers
``ipopt slsqp osqp cvxpy`` (``--solvers`` picks others, chains as ``pso>ipopt``), all
started from the same path (``init=``): the A* path on grids; circle worlds have no grid,
so there it is the exact any-angle (visibility) path. Every result is judged by the same
program, so the cost column means the same for each solver. The table is op.compare's:
feasible runs, best and median cost, median time, median evaluations (IPOPT and SLSQP:
their own function counts; OSQP and cvxpy: QP solves). Infeasible results are listed with
their reason under the table: the QPs refuse a start that is not feasible once fitted to
N points, which happens on circle worlds, whose any-angle path touches the circles.
``--db FILE`` also stores every run in a bench results database (kind ``program``).

Map arguments are paper map names (``optplan/data/maps/paper_maps.yaml``, their start and
goal) or map files / shipped map names, which need ``--start`` and ``--goal``.

What changed: this script used to time the refinement's own smoothers
(``solvers/nlp/smoothing.py``, ``solvers/qp``) in five parts chosen with ``--part``:
IPOPT build, cold and warm times on circle worlds; grid times with the QP polish; one
hand-assembled circle-world NLP solved by IPOPT, SLSQP and the QP; IPOPT option
variants; the QP smoother per map. ``--quick`` meant 3 repetitions instead of 7. It is
now a thin wrapper over ``op.compare`` on the program form of that energy, on any map;
``--part`` went with the parts, and ``--quick`` now means a small problem (25 points, the
first map). The timing parts are in the history (``git show
d680440:benchmarks/refine_solvers.py``). Wall-clock figures depend on machine load.
"""
from __future__ import annotations

import argparse
import sys

import optplan as op
from optplan.world.papermaps import catalogue, paper_map

DEFAULT_MAPS = ("chen2025_20", "hou2024_env2", "li2023_30")
SOLVERS = ("ipopt", "slsqp", "osqp", "cvxpy")


def load_target(name: str, start, goal):
    """``(world, start, goal)`` of a paper map name (its own start and goal unless given) or
    of a map file / shipped map name with ``start`` and ``goal``."""
    if name in catalogue():
        world, s, g = paper_map(name)
        return world, (s if start is None else start), (g if goal is None else goal)
    if start is None or goal is None:
        raise op.ParameterError(f"{name!r} is not a paper map ({', '.join(sorted(catalogue()))}); a map file "
                                f"needs --start X Y and --goal X Y")
    from optplan.world.loaders import load_map

    return load_map(name), start, goal


def seed_path(world, start, goal, clearance: float):
    """The common start of every solver: A* on grids, the any-angle optimum on circle worlds."""
    algorithm = "astar" if hasattr(world, "occ") else "visibility"
    return algorithm, op.plan(world, start, goal, algorithm=algorithm, clearance=clearance)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("maps", nargs="*", help=f"paper map names or map files (default: {' '.join(DEFAULT_MAPS)})")
    ap.add_argument("--start", type=float, nargs=2, metavar=("X", "Y"), help="start (m), for map files")
    ap.add_argument("--goal", type=float, nargs=2, metavar=("X", "Y"), help="goal (m), for map files")
    ap.add_argument("--n", type=int, default=50, help="points of the smoothing program (default 50)")
    ap.add_argument("--w-smooth", type=float, default=0.5, help="weight of the bending term (default 0.5)")
    ap.add_argument("--clearance", type=float, default=0.0, help="required clearance, metres (default 0)")
    ap.add_argument("--solvers", nargs="+", default=list(SOLVERS),
                    help="program solvers; a chain is written a>b (default: ipopt slsqp osqp cvxpy)")
    ap.add_argument("--db", metavar="FILE", help="also store every run in this bench results database")
    ap.add_argument("--quick", action="store_true", help="25 points, first map only")
    a = ap.parse_args(argv)
    maps = a.maps or list(DEFAULT_MAPS)
    n = 25 if a.quick else a.n
    if a.quick:
        maps = maps[:1]
    solvers = [s.split(">") if ">" in s else s for s in a.solvers]
    try:
        for name in maps:
            world, start, goal = load_target(name, a.start, a.goal)
            prog = op.smoothing_program(world, start, goal, n=n, w_smooth=a.w_smooth, clearance=a.clearance)
            planner, seed = seed_path(world, start, goal, a.clearance)
            seed_cost, _, seed_ok = prog.judge(prog.variables.decode(prog.variables.from_path(seed.path)[None])[0])
            print(f"## {name}: start from the {planner} path ({seed.length:.3f} m; fitted to {n} points: cost "
                  f"{seed_cost:.4f}, {'feasible' if seed_ok else 'infeasible'})\n")
            table = op.compare(prog, solvers, seeds=[0], db=a.db, init=seed.path)
            print(table.table())
            for row, res in zip(table.rows, table.results):
                if not res.feasible:
                    print(f"  {row['solver']}: {res.message}")
            print()
    except op.OptplanError as exc:
        print(f"refine_solvers: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
