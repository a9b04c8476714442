"""The interface of a run kind: what a spec of that kind lists, how it is checked, how one
run executes and what counts as a success. One class per kind (``plan.py``,
``simulate.py``, ``optimize.py``, ``program.py``) and one registry (``kinds/__init__.py``);
a new kind is one module and one registry entry."""
from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any, ClassVar, Mapping

from ..spec_fields import AlgorithmSpec, TargetSpec, as_list, check_local, parse_algorithms


class RunKind:
    """One kind of benchmark run.

    Class attributes:
        name: the spec's ``kind:``.
        target_key: the spec key that lists the targets (``maps``, ``scenarios``, ``functions``).
        default_metric: the tables' statistic when the spec names none.
        result_type: name of the result class in :mod:`optplan.results` a run returns.
        extra_metrics: numbers :meth:`run` stores beside the result's own fields.
        own_keys: spec keys only this kind reads (others are refused for it).
        refines: whether ``refine:`` applies.
        uses_local_planners: whether ``local_planners:`` is required (else refused).
        final_metric: the value after post-processing that plots mark past a convergence curve.
    """

    name: ClassVar[str]
    target_key: ClassVar[str]
    default_metric: ClassVar[str]
    result_type: ClassVar[str]
    extra_metrics: ClassVar[tuple[str, ...]] = ()
    own_keys: ClassVar[tuple[str, ...]] = ()
    refines: ClassVar[bool] = False
    uses_local_planners: ClassVar[bool] = False
    final_metric: ClassVar[str | None] = None

    # ------------------------------------------------------------------ inputs
    def input_files(self, target_spec: Mapping[str, Any],
                    program: Mapping[str, Any] | None = None) -> list[tuple[str, Path | None]]:
        """``(role, path)`` of every file a run on ``target_spec`` reads, in reading order
        (``path`` ``None`` for a file that cannot be found); none by default."""
        return []

    def input_entries(self, target_spec: Mapping[str, Any]) -> list[list[str]]:
        """What a run reads from a catalogue besides files (hashed after them); none by default."""
        return []

    def inputs_digest(self, target_spec: Mapping[str, Any], program: Mapping[str, Any] | None = None) -> str:
        """One content hash of what a run on ``target_spec`` reads (part of its run key)."""
        from ..inputs import files_digest

        return files_digest(self.input_files(target_spec, program), self.input_entries(target_spec))

    # ------------------------------------------------------------------ validate
    def targets(self, raw: dict, base_dir: Path, where: str, from_file: bool) -> list[TargetSpec]:
        """The spec's targets, each checked now (a bad map stops the spec before any run)."""
        raise NotImplementedError

    def known_algorithms(self) -> list[str]:
        """Names the spec's ``algorithms:`` may use."""
        raise NotImplementedError

    def accepted_params(self, algorithm: str) -> set[str] | None:
        """Keyword names a run with ``algorithm`` takes as ``params`` (``None``: cannot be
        listed; the run itself checks them)."""
        return None

    def algorithms(self, raw: dict, shared: Mapping[str, Any], where: str) -> tuple[list[AlgorithmSpec], dict]:
        """The checked algorithm entries and the kind's own run description (``{}`` unless the
        kind has one, e.g. a program)."""
        return parse_algorithms(self, raw.get("algorithms"), shared, where), {}

    def check_pairs(self, targets: list[TargetSpec], algorithms: list[AlgorithmSpec], where: str) -> None:
        """Refuse, at load, an algorithm that cannot run on one of the targets (none by default)."""

    def local_planners(self, raw: dict, where: str) -> list[str | None]:
        """The local planners of the grid (``[None]`` for kinds without a closed loop)."""
        from ...errors import ScenarioError

        local = as_list(raw.get("local_planners"), "local_planners", where)
        if self.uses_local_planners:
            if not local:
                raise ScenarioError(f"{where}: a {self.name} spec needs 'local_planners', e.g. [dwa, qp-dwa]")
            return [check_local(lp, where) for lp in local]
        if local:
            raise ScenarioError(f"{where}: 'local_planners' only apply to kind simulate")
        return [None]

    def metric_names(self) -> list[str]:
        """The numbers a run stores, any of which a spec's ``metric:`` may name: the numeric
        fields of the result, :attr:`extra_metrics`, and ``wall_s``."""
        from ... import results

        numeric = {"bool", "int", "float", "float | None", "int | None"}
        fields = dataclasses.fields(getattr(results, self.result_type))
        names = [f.name for f in fields if f.type in numeric and f.name != "seed"]
        return sorted({*names, *self.extra_metrics, "wall_s"})

    # ----------------------------------------------------------------------- run
    def run(self, rec) -> tuple[Any, dict]:
        """Execute one :class:`~optplan.bench.spec.RunRecord`: ``(result, extra metrics)``."""
        raise NotImplementedError

    # ----------------------------------------------------------------- summarise
    def successful(self, row: Mapping[str, Any]) -> bool:
        """Whether a stored ``ok`` row counts as a success in the tables."""
        return True
