"""Experiment specs: a YAML grid of targets x algorithms x refine modes x local planners x seeds.

A spec describes one experiment; :func:`load_spec` checks it and
:meth:`ExperimentSpec.expand` turns it into independent :class:`RunRecord` s, each
fully described (what to load, which solver with which parameters, which seed)
so that any process on any machine can execute it, and each with a stable
``key`` (a hash of everything that determines its result) under which the
results database stores it. Four kinds of run exist:

* ``plan``: ``op.plan`` on a map (a paper map name, or ``{map, start, goal}``);
* ``simulate``: ``op.simulate`` on a scenario (closed loop: global planner,
  optional refinement, local planner);
* ``optimize``: ``op.optimize`` on a benchmark function F1-F18 (chen2025 §4.1);
* ``program``: a path program (``program:``, see :mod:`optplan.bench.programs`) built on
  each map and solved by program solvers and chains (``prog.solve``).

Example (the keys are described in ``optplan/data/specs/README.md``)::

    name: chen2025_paths
    kind: plan
    maps: [chen2025_20, chen2025_30]
    algorithms: [msiar-gwo, gwo, {name: aro, params: {pop: 40}}]
    params: {pop: 30, iters: 500}        # shared by every algorithm
    runs: 20                             # seeds 0..19 (or  seeds: [3, 5, 8])
    reference: msiar-gwo                 # the statistics compare everything against it
    quick: {runs: 3, params: {iters: 60}, maps: [chen2025_20]}

A ``program`` spec names its program and lists program solvers and chains::

    kind: program
    program: smoothing                   # or a paper program, or module:function
    args: {n: 40}
    init: astar                          # start of every solver that takes init=
    maps: [chen2025_20]
    algorithms: [ipopt, osqp, [msiar-gwo, ipopt]]
"""
from __future__ import annotations

import copy
import hashlib
import json
import os
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping

from ..checks import MAX_RUNS, seed_bound
from ..errors import ParameterError, ScenarioError
from .kinds import KINDS as RUN_KINDS
from .kinds import get_kind
from .spec_fields import AlgorithmSpec, TargetSpec, as_list, check_keys, check_params, refine_name

SPECS_DIR = Path(__file__).resolve().parent.parent / "data" / "specs"

KINDS = tuple(RUN_KINDS)   # the registered run kinds (optplan/bench/kinds)
TOP_KEYS = {"name", "title", "paper", "part", "report", "kind", "maps", "scenarios", "functions", "shifted", "dim",
            "algorithms", "params", "refine", "local_planners", "runs", "seed", "seeds", "reference", "metric",
            "alpha", "quick", "notes", "order", "as_printed", *{k for kind in RUN_KINDS.values() for k in kind.own_keys}}
QUICK_KEYS = {"runs", "params", "maps", "scenarios", "functions", "algorithms", "refine", "local_planners", "seeds",
              "title", "reference", "args"}


# ----------------------------------------------------------------------------- records
@dataclass(frozen=True)
class RunRecord:
    """One independent run, fully described (JSON-serialisable via :meth:`to_dict`).

    Attributes:
        experiment: name of the spec it came from (informational, not part of ``key``).
        kind: ``"plan"``, ``"simulate"``, ``"optimize"`` or ``"program"``.
        target: short name of the map, scenario or function (table rows use it).
        target_spec: everything needed to load the target, e.g. ``{"paper_map": "chen2025_20"}``.
        algorithm: registry name of the (global) solver; for ``program`` runs a program solver
            or a chain written ``"pso>ipopt"``.
        label: the name the tables show (several labels may share one algorithm).
        refine: ``None``, ``"casadi"`` or ``"qp"``.
        local_planner: local planner name (``simulate`` runs), else ``None``.
        seed: the run's own seed.
        params: keyword arguments for the solver (``pop``, ``iters``, ``max_evals``, ...).
        inputs: content hash of every file the run reads (map, scenario, what the scenario
            references; :meth:`optplan.bench.kinds.base.RunKind.inputs_digest`), so that editing one of
            them gives the run a new key; ``""`` when it reads none. For a ``module:function``
            program, the module's source file is one of them.
        program: ``program`` runs: ``{"program": name or "module:function", "args": {...},
            "init": graph planner or None}``; empty for the other kinds.
    """

    experiment: str
    kind: str
    target: str
    target_spec: Mapping[str, Any]
    algorithm: str
    label: str
    refine: str | None
    local_planner: str | None
    seed: int
    params: Mapping[str, Any] = field(default_factory=dict)
    inputs: str = ""
    program: Mapping[str, Any] = field(default_factory=dict)

    @property
    def key(self) -> str:
        """Stable identifier: the same run description on the same input files always gives
        the same key, and an edited map or scenario file gives a new one.

        Labels and the experiment name are presentation and are left out, so two
        specs that ask for the same run share its stored result.
        """
        ident = {"kind": self.kind, "target": dict(self.target_spec), "algorithm": self.algorithm,
                 "refine": self.refine, "local_planner": self.local_planner, "seed": self.seed,
                 "params": dict(self.params)}
        if self.inputs:
            ident["inputs"] = self.inputs
        if self.program:
            ident["program"] = dict(self.program)
        blob = json.dumps(ident, sort_keys=True, separators=(",", ":"), default=str)
        return hashlib.sha256(blob.encode()).hexdigest()[:20]

    def to_dict(self) -> dict[str, Any]:
        return {"experiment": self.experiment, "kind": self.kind, "target": self.target,
                "target_spec": dict(self.target_spec), "algorithm": self.algorithm, "label": self.label,
                "refine": self.refine, "local_planner": self.local_planner, "seed": self.seed,
                "params": dict(self.params), "inputs": self.inputs, "program": dict(self.program), "key": self.key}

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "RunRecord":
        return cls(d["experiment"], d["kind"], d["target"], dict(d["target_spec"]), d["algorithm"], d["label"],
                   d["refine"], d["local_planner"], int(d["seed"]), dict(d["params"]), str(d.get("inputs") or ""),
                   dict(d.get("program") or {}))


@dataclass
class ExperimentSpec:
    """A checked experiment spec (see the module docstring for the YAML keys). ``as_printed``
    names the spec that runs the paper's setting of what this one changes (``optplan reproduce``
    then lists the claims whose verdicts differ between the two)."""

    name: str
    kind: str
    targets: list[TargetSpec]
    algorithms: list[AlgorithmSpec]
    refine: list[str | None]
    local_planners: list[str | None]
    seeds: list[int]
    reference: str | dict | None
    metric: str
    alpha: float = 0.05
    title: str = ""
    paper: str | None = None
    part: str | None = None
    report: str = "summary"
    notes: str = ""
    params: Mapping[str, Any] = field(default_factory=dict)
    source: Path | None = None
    order: int = 0
    program: Mapping[str, Any] = field(default_factory=dict)
    as_printed: str | None = None

    @property
    def runs(self) -> int:
        return len(self.seeds)

    @property
    def labels(self) -> list[str]:
        return [a.label for a in self.algorithms]

    def formatted_title(self) -> str:
        """``title`` with ``{runs}`` and the shared parameters (``{pop}``, ``{iters}``, ...) filled in."""
        values = {"runs": self.runs, "name": self.name, **{k: v for k, v in self.params.items()}}
        try:
            return self.title.format(**values) if self.title else self.name
        except (KeyError, IndexError, ValueError):
            return self.title

    def expand(self) -> list[RunRecord]:
        """Every run of the grid, in a fixed order: target, algorithm, refine, then seed and local
        planner (local planner innermost, so that runs sharing a global plan run close together)."""
        kind = get_kind(self.kind)
        out = []
        for t in self.targets:
            # read now: the files as this expansion sees them
            inputs = kind.inputs_digest(t.spec, self.program or None)
            for a in self.algorithms:
                seeds = self.seeds if a.runs is None else [self.seeds[0] + k for k in range(a.runs)]
                for r in self.refine:
                    for s in seeds:
                        for lp in self.local_planners:
                            out.append(RunRecord(self.name, self.kind, t.name, dict(t.spec), a.name, a.label, r, lp,
                                                 int(s), dict(a.params), inputs, dict(self.program)))
        return out


# ----------------------------------------------------------------------------- loading
def spec_path(name_or_path: str | Path) -> Path:
    """Resolve a spec file: an existing path, or the stem of a shipped spec in ``optplan/data/specs``."""
    p = Path(name_or_path)
    if p.is_file():
        return p
    if os.path.lexists(p):
        from ..world.files import regular_file

        regular_file(p, "spec file", ScenarioError)   # says what it is (a FIFO, a device, a folder)
    for cand in (SPECS_DIR / f"{name_or_path}.yaml", SPECS_DIR / str(name_or_path)):
        if cand.is_file():
            return cand
    shipped = ", ".join(shipped_specs()) or "none"
    raise ScenarioError(f"spec file {str(name_or_path)!r} not found; give a path to a YAML file or the name of a "
                        f"shipped spec ({shipped})")


def shipped_specs(paper: str | None = None) -> list[str]:
    """Names of the specs shipped in ``optplan/data/specs`` (optionally only one paper's)."""
    if not SPECS_DIR.is_dir():
        return []
    names = sorted(p.stem for p in SPECS_DIR.glob("*.yaml"))
    return [n for n in names if paper is None or n.split("_")[0] == paper]


def load_spec(source: str | Path | Mapping[str, Any], quick: bool = False, runs: int | None = None) -> ExperimentSpec:
    """Read and check an experiment spec.

    Args:
        source: a YAML file path, the name of a shipped spec, or an already-parsed dict.
        quick: apply the spec's ``quick:`` overrides (fewer runs, smaller budgets).
        runs: override the number of seeds per (target, algorithm) (after ``quick``).

    Raises:
        ScenarioError: unreadable file, unknown or missing keys, wrong types.
        ParameterError: bad values (non-positive runs, negative seeds, unknown reference).
        UnknownAlgorithmError: an algorithm or local planner name that is not registered.
    """
    path = None
    if isinstance(source, Mapping):
        raw = copy.deepcopy(dict(source))
    else:
        from ..world.loaders import read_yaml

        path = spec_path(source)
        raw = read_yaml(path, "spec", ScenarioError)  # bounded: size, alias expansion, one-line errors
        if not isinstance(raw, dict):
            raise ScenarioError(f"spec {path} must be a YAML mapping (name:, kind:, maps:, algorithms:, ...), "
                                f"got {type(raw).__name__}")
    where = f"spec {path}" if path else "spec"
    check_keys(raw, TOP_KEYS, where)
    if raw.get("quick") is not None:  # checked whether or not --quick is asked for
        if not isinstance(raw["quick"], dict):
            raise ScenarioError(f"{where}: 'quick' must be a mapping of overrides")
        check_keys(raw["quick"], QUICK_KEYS, f"{where} quick:")
    if quick and raw.get("quick"):
        q = raw["quick"]
        for k, v in q.items():
            if k in ("params", "args"):
                raw[k] = {**(raw.get(k) or {}), **(v or {})}
            else:
                raw[k] = v
            if k == "seeds":
                raw.pop("runs", None)
            if k == "runs":
                raw.pop("seeds", None)
    if runs is not None:
        raw["runs"] = runs
        raw.pop("seeds", None)
    return _parse(raw, path, where)


def _parse(raw: dict, path: Path | None, where: str) -> ExperimentSpec:
    name = str(raw.get("name") or (path.stem if path else "experiment"))
    kind_name = raw.get("kind")
    if kind_name is None:
        # a kind's first own key names it (program:); else the one kind whose targets are given
        present = [k.name for k in RUN_KINDS.values() if k.own_keys and raw.get(k.own_keys[0])] or \
            [k.name for k in RUN_KINDS.values() if not k.own_keys and raw.get(k.target_key)]
        if len(present) != 1:
            raise ScenarioError(f"{where}: say what to run with 'kind: {'|'.join(RUN_KINDS)}' and give its "
                                f"targets ('maps', 'scenarios' or 'functions')")
        kind_name = present[0]
    if not isinstance(kind_name, str) or kind_name not in RUN_KINDS:
        raise ScenarioError(f"{where}: kind must be one of {', '.join(RUN_KINDS)}, got {kind_name!r}")
    kind = RUN_KINDS[kind_name]
    for other in RUN_KINDS.values():
        if other.target_key != kind.target_key and raw.get(other.target_key):
            raise ScenarioError(f"{where}: '{other.target_key}' belongs to kind {other.name!r}, but this spec is "
                                f"kind {kind.name!r}")
    for other in RUN_KINDS.values():
        given = [k for k in other.own_keys if k not in kind.own_keys and raw.get(k) is not None]
        if given:
            raise ScenarioError(f"{where}: {', '.join(map(repr, given))} "
                                f"{'applies' if len(given) == 1 else 'apply'} only to kind {other.name}")
    base_dir = path.parent if path else Path.cwd()
    if not as_list(raw.get(kind.target_key), kind.target_key, where):
        raise ScenarioError(f"{where}: no '{kind.target_key}' given; list at least one")
    targets = kind.targets(raw, base_dir, where, path is not None)
    names = [t.name for t in targets]
    if len(set(names)) != len(names):
        raise ScenarioError(f"{where}: target names repeat ({', '.join(names)}); give each map entry a 'name'")

    shared = raw.get("params") or {}
    if not isinstance(shared, dict):
        raise ScenarioError(f"{where}: 'params' must be a mapping of keyword arguments, e.g. {{pop: 30, iters: 500}}")
    check_params(shared, where)
    algos, program = kind.algorithms(raw, shared, where)
    kind.check_pairs(targets, algos, where)

    refine = [refine_name(r, where) for r in as_list(raw.get("refine", [None]), "refine", where)] or [None]
    if not kind.refines and refine != [None]:
        raise ScenarioError(f"{where}: 'refine' applies to op.plan's paths; a{'n' if kind.name == 'optimize' else ''} "
                            f"{kind.name} spec cannot refine (a program chains solvers instead: [msiar-gwo, ipopt])")
    local = kind.local_planners(raw, where)

    seeds = _parse_seeds(raw, where)
    metric = raw.get("metric") or kind.default_metric
    if metric not in kind.metric_names():
        raise ParameterError(f"{where}: unknown metric {metric!r} for kind {kind.name}; valid: "
                             f"{', '.join(kind.metric_names())}")
    alpha = raw.get("alpha", 0.05)
    if not isinstance(alpha, (int, float)) or not 0 < alpha < 1:
        raise ParameterError(f"{where}: alpha must be a number in (0, 1), got {alpha!r}")
    reference = raw.get("reference")
    labels = [a.label for a in algos]
    ref_label = reference.get("algorithm") if isinstance(reference, dict) else reference
    if ref_label is not None and ref_label not in labels:
        raise ParameterError(f"{where}: reference {ref_label!r} is not one of the algorithm labels "
                             f"({', '.join(labels)})")
    if isinstance(reference, dict):
        check_keys(reference, {"algorithm", "refine", "local_planner"}, f"{where} reference:")
        reference = {"algorithm": ref_label, "refine": refine_name(reference.get("refine"), where),
                     "local_planner": reference.get("local_planner")}
    _check_title(raw.get("title"), {"runs", "name", *shared}, where)
    return ExperimentSpec(
        name=name, kind=kind.name, targets=targets, algorithms=algos, refine=refine, local_planners=local, seeds=seeds,
        reference=reference, metric=metric, alpha=float(alpha), title=str(raw.get("title") or ""),
        paper=raw.get("paper"), part=raw.get("part"), report=str(raw.get("report") or "summary"),
        notes=str(raw.get("notes") or ""), params=dict(shared), source=path, order=_order(raw.get("order", 0), where),
        program=program, as_printed=_as_printed(raw.get("as_printed"), name, where))


def _as_printed(value, name: str, where: str) -> str | None:
    """``as_printed:``: the name of the spec that runs the paper's setting of what this one changes."""
    if value is None:
        return None
    if not isinstance(value, str) or not value.strip() or value == name:
        raise ScenarioError(f"{where}: as_printed names the spec that runs the paper's setting (another spec's name), "
                            f"got {value!r}")
    return value


def _check_title(title, allowed: set, where: str) -> None:
    """A title may name ``{runs}``, ``{name}`` and the shared parameters, nothing else (no
    attributes, indices or unknown names: the title is filled in with str.format)."""
    import string

    if title is None:
        return
    if not isinstance(title, str):
        raise ScenarioError(f"{where}: title must be text, got {title!r}")
    try:
        fields = [f for _, f, _, _ in string.Formatter().parse(title) if f is not None]
    except ValueError as exc:
        raise ScenarioError(f"{where}: title {title!r} is not a valid template ({exc}); write braces as {{{{ }}}}") \
            from None
    bad = [f for f in fields if f not in allowed]
    if bad:
        raise ScenarioError(f"{where}: title names {{{bad[0]}}}; a title may use {{runs}}, {{name}} and the shared "
                            f"params ({', '.join(sorted(allowed - {'runs', 'name'})) or 'none given'})")


def _order(v, where: str) -> int:
    if not isinstance(v, int) or isinstance(v, bool):
        raise ScenarioError(f"{where}: order (position among a paper's specs) must be an integer, got {v!r}")
    return v


def _parse_seeds(raw: dict, where: str) -> list[int]:
    if "seeds" in raw and raw["seeds"] is not None:
        seeds = as_list(raw["seeds"], "seeds", where)
        if not seeds or not all(isinstance(s, int) and not isinstance(s, bool) and s >= 0 for s in seeds):
            raise ParameterError(f"{where}: seeds must be a non-empty list of non-negative integers, got {seeds!r}")
        if len(set(seeds)) != len(seeds):
            raise ParameterError(f"{where}: seeds repeat: {seeds!r}")
        if len(seeds) > MAX_RUNS:
            raise ParameterError(f"{where}: {len(seeds)} seeds; the bound is {MAX_RUNS} runs per spec")
        for s in seeds:
            seed_bound(f"{where}: seed", s)
        return [int(s) for s in seeds]
    runs = raw.get("runs", 1)
    seed0 = raw.get("seed", 0)
    if not isinstance(runs, int) or isinstance(runs, bool) or runs < 1:
        raise ParameterError(f"{where}: runs must be a positive integer, got {runs!r}")
    if not isinstance(seed0, int) or isinstance(seed0, bool) or seed0 < 0:
        raise ParameterError(f"{where}: seed (the first run's seed) must be a non-negative integer, got {seed0!r}")
    if runs > MAX_RUNS:
        raise ParameterError(f"{where}: runs {runs} exceeds the bound of {MAX_RUNS} runs per spec (each run is a "
                             f"stored row and seconds to minutes of work); split the experiment")
    seed_bound(f"{where}: seed + runs - 1", seed0 + runs - 1)
    return list(range(seed0, seed0 + runs))


def with_runs(spec: ExperimentSpec, runs: int) -> ExperimentSpec:
    """A copy of ``spec`` with ``runs`` seeds starting at its first seed."""
    if runs < 1:
        raise ParameterError(f"runs must be a positive integer, got {runs}")
    return replace(spec, seeds=[spec.seeds[0] + k for k in range(runs)])


__all__ = ["RunRecord", "ExperimentSpec", "AlgorithmSpec", "TargetSpec", "load_spec", "spec_path",
           "shipped_specs", "with_runs", "SPECS_DIR", "KINDS"]
