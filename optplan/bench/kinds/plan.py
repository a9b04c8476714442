"""Kind ``plan``: ``op.plan`` on a map (a paper map name, ``{map, start, goal}`` or a ``.scen``
file's queries); a success is a feasible path; every run also stores its gap split and where
its convergence history went (:func:`history_metrics`)."""
from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any, ClassVar, Mapping

import numpy as np

from ...errors import ScenarioError
from ..spec_fields import (MAP_KEYS, TargetSpec, as_list, check_keys, check_map_target, keyword_names, point,
                           scen_targets, spec_file)
from ..global_runs import convergence_iteration
from .base import RunKind

# the gap split stored with every plan run (issue 26); None for an infeasible path
SPLIT_METRICS = ("class_gap", "in_class_gap", "optimal_class")


def history_metrics(history) -> dict[str, float | None]:
    """What a plan run stores of its convergence history (best objective per iteration; empty
    for graph search, which then stores ``None``):

    * ``convergence_iter``: the first iteration within 1e-9 of the run's final value (yang2023
      Table 3, li2023 Fig 13's generations);
    * ``fitness_final``: the history's last value, the best value of the objective the planner
      optimised (the paper's fitness under the run's preset, scored as the planner scores it,
      before any post-processing or refinement): where the papers' convergence curves end
      (li2023 Fig 13, chen2025 Figs 18-20). Comparable between runs that optimise the same
      objective only (same preset and protocol options).
    """
    h = np.asarray(history, float)
    if not len(h):
        return {"convergence_iter": None, "fitness_final": None}
    return {"convergence_iter": float(convergence_iteration(h)), "fitness_final": float(h[-1])}


def plan_target(target_json: str):
    """``(world, start, goal)`` of a plan target, cached per process by the content of its
    files as well as by its description, so an edited map file is read again."""
    return _load_plan_target(target_json, PlanKind().inputs_digest(json.loads(target_json)))


@functools.lru_cache(maxsize=32)
def _load_plan_target(target_json: str, inputs: str):
    import numpy as np

    t = json.loads(target_json)
    if "paper_map" in t:
        from ...world.papermaps import paper_map

        return paper_map(t["paper_map"])
    from ...world.loaders import load_map

    return load_map(t["map"]), np.array(t["start"], float), np.array(t["goal"], float)


def map_targets(raw_items: list, base_dir: Path, where: str, from_file: bool) -> list[TargetSpec]:
    """The ``maps:`` of a plan or program spec: paper map names, ``{name, map, start, goal}``
    entries and ``{scen, map, queries}`` entries, each loaded and its query checked now."""
    from ...world.papermaps import catalogue

    cat = catalogue()
    out = []
    for it in raw_items:
        if isinstance(it, str):
            if it not in cat:
                raise ScenarioError(f"{where}: unknown paper map {it!r}; use a name from "
                                    f"optplan/data/maps/paper_maps.yaml ({', '.join(sorted(cat))}) or "
                                    f"{{name:, map: FILE, start: [x, y], goal: [x, y]}}")
            out.append(TargetSpec(it, {"paper_map": it}))
        elif isinstance(it, dict) and "scen" in it:
            out += scen_targets(it, base_dir, from_file, where)
        elif isinstance(it, dict):
            check_keys(it, MAP_KEYS - {"scen", "queries"}, f"{where} map entry")
            if "map" not in it or "start" not in it or "goal" not in it:
                raise ScenarioError(f"{where}: a map entry needs 'map', 'start' and 'goal' (or 'scen'), got {it}")
            start, goal = point(it["start"], "start", where), point(it["goal"], "goal", where)
            m = spec_file(it["map"], base_dir, from_file, "map", where)
            nm = str(it.get("name") or Path(m).stem)
            check_map_target(m, start, goal, f"{where} map {nm!r}")
            out.append(TargetSpec(nm, {"map": m, "start": start, "goal": goal}))
        else:
            raise ScenarioError(f"{where}: a map is a paper map name or a mapping, got {it!r}")
    return out


def path_planner_names() -> list[str]:
    """Every global planner ``op.plan`` runs: graph methods and path metaheuristics."""
    from ...registry import GRAPH_METHODS
    from ...solvers.paths import algorithm_names

    return sorted(set(GRAPH_METHODS) | set(algorithm_names()))


class PlanKind(RunKind):
    """``op.plan`` runs on maps.

    Extra metrics: the gap split (``class_gap``, ``in_class_gap``, ``optimal_class``, issue 26)
    and, from the convergence history (:func:`history_metrics`), ``convergence_iter`` and
    ``fitness_final`` (the best fitness the planner reached, the end of its convergence curve);
    ``fitness_spread``: the population's fitness standard deviation averaged over the generations
    (``PlanResult.population_spread``, li2023 Fig 14; ``None`` for planners that do not report it).
    """

    name: ClassVar[str] = "plan"
    target_key: ClassVar[str] = "maps"
    default_metric: ClassVar[str] = "length"
    result_type: ClassVar[str] = "PlanResult"
    extra_metrics: ClassVar[tuple[str, ...]] = (*SPLIT_METRICS, "convergence_iter", "fitness_final", "fitness_spread")
    refines: ClassVar[bool] = True
    final_metric: ClassVar[str | None] = "length"

    def targets(self, raw: dict, base_dir: Path, where: str, from_file: bool) -> list[TargetSpec]:
        return map_targets(as_list(raw.get(self.target_key), self.target_key, where), base_dir, where, from_file)

    def check_pairs(self, targets: list[TargetSpec], algorithms: list, where: str) -> None:
        """A planner that declares it needs a grid (``optplan algorithms --details``) is refused
        on a circle-world target when the spec is loaded, not when its runs fail."""
        from ...solvers.catalog import planner_capabilities

        grid_only = {a.name: planner_capabilities(a.name).grid_only for a in algorithms}
        grid_only = {n: why for n, why in grid_only.items() if why}
        if not grid_only:
            return
        for t in targets:
            world = plan_target(json.dumps(dict(t.spec), sort_keys=True))[0]
            if not world.is_grid:
                name, why = next(iter(grid_only.items()))
                raise ScenarioError(f"{where}: algorithm {name!r} needs a grid map ({why}); target {t.name!r} is a "
                                    f"circle world")

    def input_files(self, target_spec: Mapping[str, Any], program: Mapping[str, Any] | None = None) -> list:
        """The map file (and a ROS map's image)."""
        from ..inputs import map_target_files

        return map_target_files(target_spec)

    def input_entries(self, target_spec: Mapping[str, Any]) -> list[list[str]]:
        """A paper map's catalogue entry (file, start, goal)."""
        from ..inputs import map_target_entries

        return map_target_entries(target_spec)

    def known_algorithms(self) -> list[str]:
        return path_planner_names()

    def accepted_params(self, algorithm: str) -> set[str] | None:
        from ...planning import plan
        from ...registry import GRAPH_METHODS
        from ...solvers.graph import shortest_path
        from ...solvers.metaheuristics import get_algorithm
        from ...solvers.paths import plan_path

        if algorithm in GRAPH_METHODS:   # a metaheuristic's options fail every graph-search run
            return keyword_names(plan) | keyword_names(shortest_path)
        names = keyword_names(plan) | keyword_names(plan_path)
        try:
            return names | set(get_algorithm(algorithm).defaults())
        except Exception:  # a planner that is not an engine algorithm (ACO, the path GAs): not listed
            return None

    def run(self, rec) -> tuple[Any, dict]:
        from ...planning import plan

        world, start, goal = plan_target(json.dumps(rec.target_spec, sort_keys=True))
        res = plan(world, start, goal, algorithm=rec.algorithm, refine=rec.refine, seed=rec.seed, **rec.params)
        extra = _gap_split(world, start, goal, res, float(rec.params.get("clearance", 0.0)))
        extra.update(history_metrics(res.history))
        spread = res.population_spread
        extra["fitness_spread"] = float(spread.mean()) if len(spread) else None
        return res, extra

    def successful(self, row: Mapping[str, Any]) -> bool:
        return bool(row.get("feasible"))


def _gap_split(world, start, goal, res, clearance: float) -> dict:
    """The run's class gap (the corridor), in-class gap (the shape) and whether its class is
    the optimum's (1/0), from :func:`optplan.solvers.gaps.class_gaps`."""
    from ...solvers.gaps import class_gaps

    d = class_gaps(world, start, goal, res.path, clearance=clearance)
    return {k: (None if d[k] is None else float(d[k])) for k in SPLIT_METRICS}
