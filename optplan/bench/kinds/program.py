"""Kind ``program``: a path program (``program:``, see :mod:`optplan.bench.programs`) built on
each map and solved by program solvers and chains (``prog.solve``); a success is a
feasible path."""
from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any, ClassVar, Mapping

from ...errors import ParameterError, ScenarioError
from ..spec_fields import ALGO_KEYS, AlgorithmSpec, TargetSpec, as_list, check_keys, check_params
from .base import RunKind
from .plan import PlanKind, map_targets, plan_target

PROGRAM_KEYS = ("program", "args", "init")   # kind program only


class ProgramKind(RunKind):
    """Path programs on maps, one run per solver or chain and seed."""

    name: ClassVar[str] = "program"
    target_key: ClassVar[str] = "maps"
    default_metric: ClassVar[str] = "cost"
    result_type: ClassVar[str] = "ProgramResult"
    extra_metrics: ClassVar[tuple[str, ...]] = ("violation",)
    own_keys: ClassVar[tuple[str, ...]] = PROGRAM_KEYS
    final_metric: ClassVar[str | None] = "cost"

    def targets(self, raw: dict, base_dir: Path, where: str, from_file: bool) -> list[TargetSpec]:
        return map_targets(as_list(raw.get(self.target_key), self.target_key, where), base_dir, where, from_file)

    def known_algorithms(self) -> list[str]:
        from ...formulations.program import solver_names

        return sorted(solver_names())

    def algorithms(self, raw: dict, shared: Mapping[str, Any], where: str) -> tuple[list[AlgorithmSpec], dict]:
        from ..programs import check_program

        if not raw.get("program"):
            raise ScenarioError(f"{where}: a program spec names its program: 'program: smoothing', a paper "
                                f"program (li2023, chen2025, ...) or 'program: module:function'")
        program = check_program(raw["program"], raw.get("args"), raw.get("init"), where)
        return _parse_solvers(raw.get("algorithms"), shared, where), program

    def input_files(self, target_spec: Mapping[str, Any], program: Mapping[str, Any] | None = None) -> list:
        """The map files as for ``plan``, then for a ``module:function`` program its module's
        source file (not the modules it imports; the built-in programs are optplan's code)."""
        files = PlanKind().input_files(target_spec)
        if program and ":" in str(program.get("program", "")):
            from ..programs import program_module_file

            files.append(("program module", program_module_file(str(program["program"]))))
        return files

    def input_entries(self, target_spec: Mapping[str, Any]) -> list[list[str]]:
        return PlanKind().input_entries(target_spec)

    def run(self, rec) -> tuple[Any, dict]:
        """Build the run's program on its map and solve it; the seed goes to solvers that take
        one, the ``init`` path to solvers that take a start."""
        from ..programs import build_program, solver_instance

        target_json = json.dumps(rec.target_spec, sort_keys=True)
        world, start, goal = plan_target(target_json)
        prog = build_program(rec.program, world, start, goal)
        solver = solver_instance(rec.algorithm)
        known = solver.all_options()
        options = dict(rec.params)
        if "seed" in known:
            options["seed"] = rec.seed
        planner = rec.program.get("init")
        if planner and "init" in known:
            options["init"] = _init_path(target_json, PlanKind().inputs_digest(rec.target_spec), planner,
                                         prog.clearance).copy()
        res = prog.solve(solver, **options)
        extra: dict[str, Any] = {"violation": float(sum(res.violations.values())), "program_name": prog.name}
        if res.stages:
            from ...results import jsonable

            extra["stages"] = json.dumps(jsonable(res.stages))
        return res, extra

    def successful(self, row: Mapping[str, Any]) -> bool:
        return bool(row.get("feasible"))


@functools.lru_cache(maxsize=32)
def _init_path(target_json: str, inputs: str, planner: str, clearance: float):
    """The path of graph planner ``planner`` on a plan target with this content, at this
    clearance: the start every solver of a ``program`` run with ``init:`` gets; planned once
    per worker process (graph search is deterministic)."""
    from ...planning import plan

    world, start, goal = plan_target(target_json)
    res = plan(world, start, goal, algorithm=planner, clearance=clearance)
    if not res.feasible:
        from ...errors import InfeasibleQueryError

        raise InfeasibleQueryError(f"the {planner} path that should start the solvers is infeasible "
                                   f"({res.message})")
    return res.path


def _parse_solvers(items, shared: Mapping, where: str) -> list[AlgorithmSpec]:
    """The solver entries of a program spec: a name, a list of names (a chain), or
    ``{name: name-or-list, label:, params:, runs:}``. Each solver gets the shared options it
    takes (as ``op.compare`` does) and its own, all checked by the solver now; a shared
    option that no solver takes is an error. Deterministic solvers (no seed) run once per
    map unless the entry gives ``runs``."""
    from ..programs import check_solver_params, is_stochastic, solver_name, solver_options, solver_stages

    items = as_list(items, "algorithms", where)
    if not items:
        raise ScenarioError(f"{where}: no 'algorithms' given; list program solvers or chains, e.g. "
                            f"[msiar-gwo, ipopt, [msiar-gwo, ipopt]] (op.PathProgram's solvers)")
    if "init" in shared:
        raise ScenarioError(f"{where}: 'init' is set by the spec's 'init:' key (a graph planner), not by 'params'")
    out, used = [], set()
    for it in items:
        if isinstance(it, (str, list)):
            it = {"name": it}
        if not isinstance(it, dict) or "name" not in it:
            raise ScenarioError(f"{where}: a solver is a name, a list of names (a chain) or "
                                f"{{name:, label:, params:, runs:}}, got {it!r}")
        check_keys(it, ALGO_KEYS, f"{where} solver {it.get('name')!r}")
        nm = solver_name(solver_stages(it["name"], where))
        own = it.get("params") or {}
        if not isinstance(own, dict):
            raise ScenarioError(f"{where}: params of {nm!r} must be a mapping")
        if "init" in own:
            raise ScenarioError(f"{where}: 'init' is set by the spec's 'init:' key (a graph planner), not by "
                                f"the params of {nm!r}")
        check_params(own, where)
        known = solver_options(nm)
        used |= known
        params = check_solver_params(nm, {**{k: v for k, v in shared.items() if k in known}, **own}, where)
        runs = it.get("runs")
        if runs is not None and (not isinstance(runs, int) or isinstance(runs, bool) or runs < 1):
            raise ParameterError(f"{where}: runs of {nm!r} must be a positive integer, got {runs!r}")
        if runs is None and not is_stochastic(nm):
            runs = 1   # no seed: every seed would give the same run
        out.append(AlgorithmSpec(nm, str(it.get("label") or nm), params, runs))
    unused = sorted(set(shared) - used)
    if unused:
        raise ParameterError(f"{where}: no solver of this spec has option {', '.join(map(repr, unused))} "
                             f"(op.show_options(name) lists a solver's options)")
    labels = [a.label for a in out]
    if len(set(labels)) != len(labels):
        raise ScenarioError(f"{where}: solver labels repeat ({', '.join(labels)}); give repeated solvers "
                            f"distinct 'label's")
    return out
