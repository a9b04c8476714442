"""A chain of solvers on one program: each stage starts from the best result so far.

A stage's result replaces the running best only when it is better under the
program's own ranking (feasible first, then less violation, then lower cost),
so a chain never ends worse than its first stage; every stage is listed in
``result.stages`` with its cost before and after and whether it was kept.
Options given to the chain go to every stage that has them (an option no
stage has is a ParameterError); ``(name, {options})`` gives one stage its own.
"""
from __future__ import annotations

import time
from dataclasses import replace

from ...errors import ParameterError
from ...formulations.program import ProgramSolver, get_solver
from .common import better


class ChainSolver(ProgramSolver):
    capabilities = frozenset({"chain"})

    def __init__(self, stages) -> None:
        if not stages:
            raise ParameterError("a chain needs at least one stage, e.g. ['msiar-gwo', 'ipopt']")
        self.stages = []
        for st in stages:
            if isinstance(st, tuple):
                if len(st) != 2 or not isinstance(st[1], dict):
                    raise ParameterError(f"a chain stage is a name, a solver or (name, {{options}}); got {st!r}")
                solver = get_solver(st[0])
                solver.settings.update(solver.check_options(st[1]))
            else:
                solver = get_solver(st)
            self.stages.append(solver)
        self.name = ">".join(s.name for s in self.stages)
        self.settings = {}

    def all_options(self):
        out = {}
        for s in self.stages:
            for k, o in s.all_options().items():
                out.setdefault(k, o)
        return out

    def solve(self, program, **options):
        self.check_options(options)
        t0 = time.perf_counter()
        best, records, nfev = None, [], 0
        for i, stage in enumerate(self.stages):
            own = {k: v for k, v in options.items() if k in stage.all_options()}
            if best is not None and "init" in stage.all_options():
                own["init"] = best
            r = stage.solve(program, **own)
            nfev += r.nfev
            kept = best is None or better(r, best)
            records.append({"stage": i + 1, "solver": stage.name,
                            "cost_before": None if best is None else best.cost, "cost": r.cost,
                            "feasible": r.feasible, "accepted": kept, "nfev": r.nfev,
                            "runtime_s": r.runtime_s, "message": r.message})
            if kept:
                best = r
        rejected = [f"stage {rec['stage']} ({rec['solver']}) was not better and was not kept"
                    for rec in records[1:] if not rec["accepted"]]
        msg = "; ".join(m for m in (best.message, *rejected) if m)
        return replace(best, solver=self.name, nfev=nfev, runtime_s=time.perf_counter() - t0, stages=records,
                       message=msg)
