"""``op.compare``: one program, many solvers, many seeds, one table.

Every run is judged by the same program (``prog.evaluate``) and the exact
collision test, so the columns mean the same for a swarm, IPOPT, a QP and a
chain. With ``db=`` the runs also go to the bench result store (kind
``program``), where ``optplan bench`` tables and CSV export can read them.
"""
from __future__ import annotations

import hashlib
import json
import math
import statistics
from dataclasses import dataclass, field

from ..errors import ParameterError

COLUMNS = ("solver", "seed", "cost", "feasible", "nfev", "runtime_s", "violation", "status")


@dataclass
class Comparison:
    """Rows of ``op.compare`` (one per solver and seed) and their summary per solver."""

    program: str
    rows: list = field(default_factory=list)
    results: list = field(default_factory=list, repr=False)

    def summary(self) -> list[dict]:
        """Per solver: runs, feasible share, best / median cost over feasible runs, median time and nfev."""
        out = []
        for name in dict.fromkeys(r["solver"] for r in self.rows):
            rs = [r for r in self.rows if r["solver"] == name]
            ok = [r["cost"] for r in rs if r["feasible"]]
            out.append({"solver": name, "runs": len(rs), "feasible": sum(r["feasible"] for r in rs),
                        "best_cost": min(ok) if ok else math.inf,
                        "median_cost": statistics.median(ok) if ok else math.inf,
                        "median_runtime_s": statistics.median(r["runtime_s"] for r in rs),
                        "median_nfev": statistics.median(r["nfev"] for r in rs)})
        return out

    def table(self) -> str:
        """The summary as a text table."""
        head = f"{'solver':<22} {'runs':>4} {'feasible':>8} {'best cost':>11} {'median cost':>12} " \
               f"{'median s':>9} {'median nfev':>11}"
        lines = [f"program: {self.program}", head, "-" * len(head)]
        for s in self.summary():
            lines.append(f"{s['solver']:<22} {s['runs']:>4} {s['feasible']:>8} {s['best_cost']:>11.4f} "
                         f"{s['median_cost']:>12.4f} {s['median_runtime_s']:>9.3f} {s['median_nfev']:>11.0f}")
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.table()


def _solver_label(solver) -> str:
    if isinstance(solver, str):
        return solver
    if isinstance(solver, (list, tuple)):
        return ">".join(_solver_label(s[0] if isinstance(s, tuple) else s) for s in solver)
    return getattr(solver, "name", repr(solver))


def compare(program, solvers, seeds=(0,), db=None, progress: bool = False, **options) -> Comparison:
    """Solve ``program`` with every solver for every seed; return a :class:`Comparison`.

    Args:
        program: an ``op.PathProgram``.
        solvers: names, chains (lists of names) or solver instances.
        seeds: seeds of the stochastic solvers (deterministic ones run once).
        db: a SQLite file (or ``ResultStore``) to store every run in (kind ``program``).
        progress: print a line per run to stderr.
        **options: passed to every solver that has them (e.g. ``max_evals=6000``).
    """
    import sys

    from ..formulations.program import get_solver

    if isinstance(solvers, (str, bytes)) or not hasattr(solvers, "__iter__"):
        raise ParameterError("solvers must be a list of solver names, chains or instances")
    from ..formulations.program import PathProgram

    if not isinstance(program, PathProgram):
        raise ParameterError(f"program must be an op.PathProgram (e.g. op.smoothing_program(world, start, goal)), "
                             f"got {type(program).__name__}")
    if isinstance(seeds, (str, bytes)) or not hasattr(seeds, "__iter__"):
        raise ParameterError(f"seeds must be a list of integer seeds, e.g. range(5), got {seeds!r:.60}")
    seeds = list(seeds)
    if not seeds:
        raise ParameterError("seeds must name at least one seed")
    out = Comparison(program=repr(program))
    store = None
    if db is not None:
        from .store import ResultStore

        store = db if isinstance(db, ResultStore) else ResultStore(db)
    for solver in solvers:
        instance = get_solver(solver)
        known = instance.all_options()
        own = {k: v for k, v in options.items() if k in known}
        stochastic = "seed" in known
        for seed in (seeds if stochastic else seeds[:1]):
            kw = dict(own, seed=seed) if stochastic else own
            r = instance.solve(program, **kw)
            row = {"solver": _solver_label(solver), "seed": seed if stochastic else None, "cost": r.cost,
                   "feasible": r.feasible, "nfev": r.nfev, "runtime_s": r.runtime_s,
                   "violation": float(sum(r.violations.values())), "status": r.status}
            out.rows.append(row)
            out.results.append(r)
            if progress:
                print(f"compare: {row['solver']} seed {row['seed']}: cost {r.cost:.4f}, feasible {r.feasible}, "
                      f"{r.runtime_s:.2f} s", file=sys.stderr)
            if store is not None:
                _store(store, program, row, r, own)
    return out


def world_digest(world) -> str:
    """A hash of what a world is (occupancy, resolution and origin of a grid; bounds, circles
    and safety distance of a circle world), not of its caches or name."""
    import numpy as np

    h = hashlib.sha256(type(world).__name__.encode())
    for attr in ("occ", "resolution", "origin", "bounds", "circles", "safety"):
        value = getattr(world, attr, None)
        if value is not None:
            a = np.ascontiguousarray(np.asarray(value, dtype=float))
            h.update(f"{attr}{a.shape}".encode())
            h.update(a.tobytes())
    return h.hexdigest()[:20]


def _option_value(v):
    """An option as plain data for the key: a start result by its path, arrays as lists."""
    from ..results import jsonable

    return jsonable(getattr(v, "path", v))


def _store(store, program, row: dict, r, options: dict) -> None:
    params = {k: v for k, v in options.items() if isinstance(v, (int, float, str, bool)) or v is None}
    others = {k: _option_value(v) for k, v in options.items() if k not in params}
    # the program's text does not say on which map, between which points, or from which start
    # (init=): all of them enter the key, or runs of one program on two maps overwrite each other
    ident = json.dumps({"program": repr(program), "world": world_digest(program.world),
                        "start": [float(c) for c in program.start], "goal": [float(c) for c in program.goal],
                        "solver": row["solver"], "seed": row["seed"], "params": params,
                        "others": hashlib.sha256(json.dumps(others, sort_keys=True, default=str).encode()).hexdigest()},
                       sort_keys=True)
    key = hashlib.sha256(ident.encode()).hexdigest()[:32]
    record = {"key": key, "experiment": "compare", "kind": "program", "target": program.name,
              "algorithm": row["solver"], "label": row["solver"], "refine": None, "local_planner": None,
              "seed": row["seed"], "params": params, "target_spec": {"program": repr(program)}}
    metrics = {"cost": r.cost, "feasible": r.feasible, "nfev": r.nfev, "runtime_s": r.runtime_s,
               "violation": row["violation"], "solver_status": r.status}
    store.write(record, {"status": "ok", "wall_s": r.runtime_s, "metrics": metrics,
                         "traces": {"path": r.path.tolist(), "history": r.history.tolist(), "x": r.x.tolist()}})
