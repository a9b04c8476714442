"""Kind ``simulate``: ``op.simulate`` on a scenario (closed loop: global planner, optional
refinement, local planner); a success reaches the goal without a collision; every run also
stores how much the driven path turns (:func:`heading_change_per_m`)."""
from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any, ClassVar, Mapping

import numpy as np

from ...errors import ScenarioError
from ..spec_fields import TargetSpec, as_list, spec_file
from .base import RunKind
from .plan import path_planner_names


def heading_change_per_m(trajectory, path_length: float) -> float | None:
    """The smoothness of a driven path: the total absolute change of the robot's heading
    (degrees; each step's change wrapped to [-180, 180)) per metre driven, from the
    trajectory's heading column (rows ``[t, x, y, theta, ...]``). Lower is smoother; a turn
    on the spot counts in full (it is the robot's heading, not the path's). ``None`` when the
    robot did not move."""
    traj = np.asarray(trajectory, float)
    if traj.ndim != 2 or len(traj) < 2 or not path_length > 0:
        return None
    dtheta = np.diff(traj[:, 3])
    dtheta = (dtheta + np.pi) % (2 * np.pi) - np.pi
    return float(np.degrees(np.abs(dtheta).sum()) / path_length)


class SimulateKind(RunKind):
    """Closed-loop runs on scenario files, shipped scenarios or generated families.

    Extra metrics: ``success`` (reached without a collision) and ``heading_change_per_m``
    (:func:`heading_change_per_m`, the smoothness of the driven path: li2023 Experiment I).
    """

    name: ClassVar[str] = "simulate"
    target_key: ClassVar[str] = "scenarios"
    default_metric: ClassVar[str] = "time_s"
    result_type: ClassVar[str] = "SimResult"
    extra_metrics: ClassVar[tuple[str, ...]] = ("success", "heading_change_per_m")
    refines: ClassVar[bool] = True
    uses_local_planners: ClassVar[bool] = True

    def targets(self, raw: dict, base_dir: Path, where: str, from_file: bool) -> list[TargetSpec]:
        out = []
        for it in as_list(raw.get(self.target_key), self.target_key, where):
            if not isinstance(it, str):
                raise ScenarioError(f"{where}: a scenario is a shipped scenario name or a YAML file path, got {it!r}")
            resolved = base_dir / it
            sc = spec_file(it, base_dir, from_file, "scenario", where) if resolved.is_file() else it
            if not resolved.is_file():
                from ...world.scenario import scenario_names
                from ...worldgen.clutter import FAMILIES  # generated families: a new world per seed

                if Path(it).stem not in scenario_names() and it not in FAMILIES:
                    raise ScenarioError(f"{where}: scenario {it!r} is neither a file (relative to the spec), a "
                                        f"shipped scenario ({', '.join(scenario_names()) or 'none shipped'}) nor "
                                        f"a generated family ({', '.join(FAMILIES)})")
            out.append(TargetSpec(Path(it).stem if it.endswith((".yaml", ".yml")) else it, {"scenario": sc}))
        return out

    def known_algorithms(self) -> list[str]:
        return path_planner_names()

    def run(self, rec) -> tuple[Any, dict]:
        from ...sim import simulate

        target_json = json.dumps(rec.target_spec, sort_keys=True)
        inputs = _scenario_inputs(target_json)
        scenario = scenario_target(target_json, inputs)
        params = dict(rec.params)
        plan = _shared_global_plan(target_json, inputs, rec.algorithm, rec.refine, rec.seed,
                                   json.dumps(params.get("global_options") or {}, sort_keys=True))
        if plan is not None and "global_plan" not in params:
            params["global_plan"] = plan
        res = simulate(scenario, global_planner=rec.algorithm, local_planner=rec.local_planner, refine=rec.refine,
                       seed=rec.seed, **params)
        extra = {"success": bool(res.reached and res.collisions == 0),
                 "heading_change_per_m": heading_change_per_m(res.trajectory, res.path_length)}
        return res, extra

    def successful(self, row: Mapping[str, Any]) -> bool:
        return bool(row.get("reached")) and not row.get("collisions")

    def input_files(self, target_spec: Mapping[str, Any], program: Mapping[str, Any] | None = None) -> list:
        """The scenario file and the map it names."""
        from ..inputs import scenario_target_files

        return scenario_target_files(target_spec)


def _scenario_inputs(target_json: str) -> str:
    return SimulateKind().inputs_digest(json.loads(target_json))


def scenario_target(target_json: str, inputs: str | None = None):
    """The scenario of a simulate target, cached per process by the content of its files
    (``inputs``, computed when not given) as well as by its description."""
    return _load_scenario_target(target_json, _scenario_inputs(target_json) if inputs is None else inputs)


@functools.lru_cache(maxsize=16)
def _load_scenario_target(target_json: str, inputs: str):
    """The Scenario of a file or shipped name; a generated family's name stays a name (its
    world depends on the run's seed: ``optplan.sim.closed_loop.scenario_for``)."""
    from ...world.scenario import load_scenario
    from ...worldgen.clutter import FAMILIES

    name = json.loads(target_json)["scenario"]
    return name if isinstance(name, str) and name in FAMILIES else load_scenario(name)


@functools.lru_cache(maxsize=64)
def _shared_global_plan(target_json: str, inputs: str, algorithm: str, refine: str | None, seed: int,
                        options_json: str):
    """The global plan of one (scenario with these file contents, planner, refine, seed), made once
    per worker process and shared by the runs that differ only in the local planner
    (``optplan.sim.experiments.plan_global``); planning is seeded, so sharing changes no number,
    it only saves the metaheuristic's time."""
    from ...sim.closed_loop import scenario_for
    from ...sim.experiments import plan_global
    from ...worldgen.clutter import family_options

    target = scenario_target(target_json, inputs)
    options = json.loads(options_json) or family_options(target).get("global_options")
    return plan_global(scenario_for(target, seed), algorithm, refine, seed, options)
