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
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping

from ..checks import MAX_RUNS, population_budget, seed_bound
from ..errors import ParameterError, ScenarioError, UnknownAlgorithmError

SPECS_DIR = Path(__file__).resolve().parent.parent / "data" / "specs"

KINDS = ("plan", "simulate", "optimize", "program")
TARGET_KEY = {"plan": "maps", "simulate": "scenarios", "optimize": "functions", "program": "maps"}
DEFAULT_METRIC = {"plan": "length", "simulate": "time_s", "optimize": "f", "program": "cost"}
# numbers a run stores beside its result's own fields (bench/runner.py computes them)
SPLIT_METRICS = ("class_gap", "in_class_gap", "optimal_class")
EXTRA_METRICS = {"plan": SPLIT_METRICS, "simulate": ("success",), "optimize": ("f_error", "f_opt"),
                 "program": ("violation",)}
RESULT_OF_KIND = {"plan": "PlanResult", "simulate": "SimResult", "optimize": "OptimizeResult",
                  "program": "ProgramResult"}
PROGRAM_KEYS = ("program", "args", "init")   # kind program only
REFINE_NAMES = ("none", "casadi", "qp")

TOP_KEYS = {"name", "title", "paper", "part", "report", "kind", "maps", "scenarios", "functions", "shifted", "dim",
            "algorithms", "params", "refine", "local_planners", "runs", "seed", "seeds", "reference", "metric",
            "alpha", "quick", "notes", "order", *PROGRAM_KEYS}
QUICK_KEYS = {"runs", "params", "maps", "scenarios", "functions", "algorithms", "refine", "local_planners", "seeds",
              "title", "reference", "args"}
ALGO_KEYS = {"name", "label", "params", "runs"}
MAX_PARAMS = 200  # per algorithm entry; every parameter is a column of the results table
MAP_KEYS = {"name", "map", "start", "goal", "scen", "queries"}


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
            references; :func:`optplan.bench.inputs.inputs_digest`), so that editing one of
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


@dataclass(frozen=True)
class AlgorithmSpec:
    """One algorithm entry: registry ``name``, table ``label``, merged ``params``, optional own ``runs``."""

    name: str
    label: str
    params: Mapping[str, Any]
    runs: int | None = None


@dataclass(frozen=True)
class TargetSpec:
    """One map, scenario or function: a short ``name`` and what identifies it."""

    name: str
    spec: Mapping[str, Any]


@dataclass
class ExperimentSpec:
    """A checked experiment spec (see the module docstring for the YAML keys)."""

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
        from .inputs import inputs_digest

        out = []
        for t in self.targets:
            # read now: the files as this expansion sees them
            inputs = inputs_digest(self.kind, t.spec, self.program or None)
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
    _check_keys(raw, TOP_KEYS, where)
    if raw.get("quick") is not None:  # checked whether or not --quick is asked for
        if not isinstance(raw["quick"], dict):
            raise ScenarioError(f"{where}: 'quick' must be a mapping of overrides")
        _check_keys(raw["quick"], QUICK_KEYS, f"{where} quick:")
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


def _check_keys(d: Mapping, allowed: set, where: str) -> None:
    unknown = sorted(set(d) - allowed)
    if unknown:
        raise ScenarioError(f"{where}: unknown key(s) {', '.join(map(repr, unknown))}; allowed: "
                            f"{', '.join(sorted(allowed))}")


def _as_list(value, what: str, where: str) -> list:
    if value is None:
        return []
    if isinstance(value, (str, int, float, dict)):
        return [value]
    if isinstance(value, list):
        return value
    raise ScenarioError(f"{where}: '{what}' must be a list, got {type(value).__name__}")


def _parse(raw: dict, path: Path | None, where: str) -> ExperimentSpec:
    name = str(raw.get("name") or (path.stem if path else "experiment"))
    kind = raw.get("kind")
    if kind is None:
        present = ["program"] if raw.get("program") else \
            [k for k, key in TARGET_KEY.items() if k != "program" and raw.get(key)]
        if len(present) != 1:
            raise ScenarioError(f"{where}: say what to run with 'kind: plan|simulate|optimize|program' and give its "
                                f"targets ('maps', 'scenarios' or 'functions')")
        kind = present[0]
    if kind not in KINDS:
        raise ScenarioError(f"{where}: kind must be one of {', '.join(KINDS)}, got {kind!r}")
    for other_kind, key in TARGET_KEY.items():
        if key != TARGET_KEY[kind] and raw.get(key):
            raise ScenarioError(f"{where}: '{key}' belongs to kind {other_kind!r}, but this spec is kind {kind!r}")
    if kind != "program":
        given = [k for k in PROGRAM_KEYS if raw.get(k) is not None]
        if given:
            raise ScenarioError(f"{where}: {', '.join(map(repr, given))} "
                                f"{'applies' if len(given) == 1 else 'apply'} only to kind program")
    base_dir = path.parent if path else Path.cwd()
    targets = _parse_targets(kind, raw, base_dir, where, path is not None)

    shared = raw.get("params") or {}
    if not isinstance(shared, dict):
        raise ScenarioError(f"{where}: 'params' must be a mapping of keyword arguments, e.g. {{pop: 30, iters: 500}}")
    _check_params(shared, where)
    program: dict[str, Any] = {}
    if kind == "program":
        from .programs import check_program

        if not raw.get("program"):
            raise ScenarioError(f"{where}: a program spec names its program: 'program: smoothing', a paper "
                                f"program (li2023, chen2025, ...) or 'program: module:function'")
        program = check_program(raw["program"], raw.get("args"), raw.get("init"), where)
        algos = _parse_solvers(raw.get("algorithms"), shared, where)
    else:
        algos = _parse_algorithms(kind, raw.get("algorithms"), shared, where)

    refine = [_refine_name(r, where) for r in _as_list(raw.get("refine", [None]), "refine", where)] or [None]
    if kind in ("optimize", "program") and refine != [None]:
        raise ScenarioError(f"{where}: 'refine' applies to op.plan's paths; a{'n' if kind == 'optimize' else ''} "
                            f"{kind} spec cannot refine (a program chains solvers instead: [msiar-gwo, ipopt])")
    local = _as_list(raw.get("local_planners"), "local_planners", where)
    if kind == "simulate":
        if not local:
            raise ScenarioError(f"{where}: a simulate spec needs 'local_planners', e.g. [dwa, qp-dwa]")
        local = [_check_local(lp, where) for lp in local]
    elif local:
        raise ScenarioError(f"{where}: 'local_planners' only apply to kind simulate")
    else:
        local = [None]

    seeds = _parse_seeds(raw, where)
    metric = raw.get("metric") or DEFAULT_METRIC[kind]
    if metric not in metric_names(kind):
        raise ParameterError(f"{where}: unknown metric {metric!r} for kind {kind}; valid: "
                             f"{', '.join(metric_names(kind))}")
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
        _check_keys(reference, {"algorithm", "refine", "local_planner"}, f"{where} reference:")
        reference = {"algorithm": ref_label, "refine": _refine_name(reference.get("refine"), where),
                     "local_planner": reference.get("local_planner")}
    _check_title(raw.get("title"), {"runs", "name", *shared}, where)
    return ExperimentSpec(
        name=name, kind=kind, targets=targets, algorithms=algos, refine=refine, local_planners=local, seeds=seeds,
        reference=reference, metric=metric, alpha=float(alpha), title=str(raw.get("title") or ""),
        paper=raw.get("paper"), part=raw.get("part"), report=str(raw.get("report") or "summary"),
        notes=str(raw.get("notes") or ""), params=dict(shared), source=path, order=_order(raw.get("order", 0), where),
        program=program)


def metric_names(kind: str) -> list[str]:
    """The numbers a run of ``kind`` stores, any of which a spec's ``metric:`` may name: the
    numeric fields of the kind's result, the extra numbers the runner adds, and ``wall_s``."""
    import dataclasses

    from .. import results

    cls = getattr(results, RESULT_OF_KIND[kind])
    numeric = {"bool", "int", "float", "float | None", "int | None"}
    names = [f.name for f in dataclasses.fields(cls) if f.type in numeric and f.name != "seed"]
    return sorted({*names, *EXTRA_METRICS[kind], "wall_s"})


def _parse_targets(kind: str, raw: dict, base_dir: Path, where: str, from_file: bool = False) -> list[TargetSpec]:
    key = TARGET_KEY[kind]
    items = _as_list(raw.get(key), key, where)
    if not items:
        raise ScenarioError(f"{where}: no '{key}' given; list at least one")
    out = []
    if kind in ("plan", "program"):
        from ..world.papermaps import catalogue

        cat = catalogue()
        for it in items:
            if isinstance(it, str):
                if it not in cat:
                    raise ScenarioError(f"{where}: unknown paper map {it!r}; use a name from "
                                        f"optplan/data/maps/paper_maps.yaml ({', '.join(sorted(cat))}) or "
                                        f"{{name:, map: FILE, start: [x, y], goal: [x, y]}}")
                out.append(TargetSpec(it, {"paper_map": it}))
            elif isinstance(it, dict) and "scen" in it:
                out += _scen_targets(it, base_dir, from_file, where)
            elif isinstance(it, dict):
                _check_keys(it, MAP_KEYS - {"scen", "queries"}, f"{where} map entry")
                if "map" not in it or "start" not in it or "goal" not in it:
                    raise ScenarioError(f"{where}: a map entry needs 'map', 'start' and 'goal' (or 'scen'), got {it}")
                start, goal = _point(it["start"], "start", where), _point(it["goal"], "goal", where)
                m = _spec_file(it["map"], base_dir, from_file, "map", where)
                nm = str(it.get("name") or Path(m).stem)
                _check_map_target(m, start, goal, f"{where} map {nm!r}")
                out.append(TargetSpec(nm, {"map": m, "start": start, "goal": goal}))
            else:
                raise ScenarioError(f"{where}: a map is a paper map name or a mapping, got {it!r}")
    elif kind == "simulate":
        for it in items:
            if not isinstance(it, str):
                raise ScenarioError(f"{where}: a scenario is a shipped scenario name or a YAML file path, got {it!r}")
            resolved = base_dir / it
            sc = _spec_file(it, base_dir, from_file, "scenario", where) if resolved.is_file() else it
            if not resolved.is_file():
                from ..world.scenario import scenario_names
                from ..worldgen.clutter import FAMILIES  # generated families: a new world per seed

                if Path(it).stem not in scenario_names() and it not in FAMILIES:
                    raise ScenarioError(f"{where}: scenario {it!r} is neither a file (relative to the spec), a "
                                        f"shipped scenario ({', '.join(scenario_names()) or 'none shipped'}) nor "
                                        f"a generated family ({', '.join(FAMILIES)})")
            out.append(TargetSpec(Path(it).stem if it.endswith((".yaml", ".yml")) else it, {"scenario": sc}))
    else:
        from ..formulations.functions import NAMES

        shifted = bool(raw.get("shifted", False))
        dim = raw.get("dim")
        if dim is not None and (not isinstance(dim, int) or dim < 1):
            raise ParameterError(f"{where}: dim must be a positive integer, got {dim!r}")
        for it in items:
            fname = str(it).upper()
            if fname not in NAMES:
                raise ScenarioError(f"{where}: unknown benchmark function {it!r}; known: {', '.join(NAMES)}")
            out.append(TargetSpec(fname, {"function": fname, "shifted": shifted, "dim": dim}))
    names = [t.name for t in out]
    if len(set(names)) != len(names):
        raise ScenarioError(f"{where}: target names repeat ({', '.join(names)}); give each map entry a 'name'")
    return out


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


def _spec_file(name, base_dir: Path, from_file: bool, what: str, where: str) -> str:
    """The absolute path of a file a spec names (relative to the spec's folder), or the name
    itself when no such file exists (a shipped map). A spec file may only read files in its
    own folder and below: ``../`` and absolute paths leading elsewhere are refused, so a
    spec from somewhere else cannot make bench read arbitrary files."""
    if not isinstance(name, str) or not name:
        raise ScenarioError(f"{where}: a {what} is a file name or a shipped name, got {name!r}")
    resolved = base_dir / name
    if not resolved.exists():
        return name
    real, root = resolved.resolve(), base_dir.resolve()
    if from_file and real != root and root not in real.parents:
        raise ScenarioError(f"{where}: {what} {name!r} lies outside the spec's folder {root}; a spec may only "
                            f"name files in its own folder (copy the file next to the spec)")
    if not real.is_file():
        raise ScenarioError(f"{where}: {what} {name!r} is not a file")
    return str(real)


def _check_map_target(m: str, start, goal, where: str):
    """Load a map target now, so a bad map or query stops the spec before any run."""
    from ..errors import OptplanError
    from ..world.loaders import load_map

    try:
        world = load_map(m)
        if start is not None:
            world.check_query_point(start, "start")
            world.check_query_point(goal, "goal")
    except OptplanError as exc:
        raise ScenarioError(f"{where}: {exc}") from None
    return world


def _scen_targets(it: dict, base_dir: Path, from_file: bool, where: str) -> list[TargetSpec]:
    """Targets from a Moving AI ``.scen`` file: ``{scen: FILE.scen, map: FILE.map,
    queries: [0, 5] | N}`` (``map`` defaults to the file the scenario names, next to it;
    ``queries`` to every query, an integer N to the first N)."""
    from ..errors import OptplanError
    from ..world.loaders import load_scen, scen_query

    _check_keys(it, MAP_KEYS - {"start", "goal"}, f"{where} scen entry")
    scen = _spec_file(it["scen"], base_dir, from_file, "scen file", where)
    try:
        entries = load_scen(scen)
    except OptplanError as exc:
        raise ScenarioError(f"{where}: {exc}") from None
    if not entries:
        raise ScenarioError(f"{where}: {scen} holds no queries")
    m = it.get("map")
    if m is None:  # the scenario's own map name, looked up next to the .scen file
        m = str(Path(scen).parent / Path(entries[0].map_name).name)
        if not Path(m).is_file():
            raise ScenarioError(f"{where}: {scen} names map {entries[0].map_name!r}, which is not next to it; "
                                f"give 'map:'")
    else:
        m = _spec_file(m, base_dir, from_file, "map", where)
    q = it.get("queries", len(entries))
    if isinstance(q, int) and not isinstance(q, bool) and q >= 1:
        picks = list(range(min(q, len(entries))))
    elif isinstance(q, list) and q and all(isinstance(i, int) and not isinstance(i, bool) for i in q):
        picks = q
    else:
        raise ScenarioError(f"{where}: 'queries' is a positive count or a list of query indices, got {q!r}")
    world = _check_map_target(m, None, None, f"{where} map {m!r}")
    stem = str(it.get("name") or Path(scen).name.split(".")[0])
    out = []
    for i in picks:
        try:
            start, goal = scen_query(world, scen, i)
            world.check_query_point(start, f"query {i} start")
            world.check_query_point(goal, f"query {i} goal")
        except OptplanError as exc:
            raise ScenarioError(f"{where}: {exc}") from None
        out.append(TargetSpec(f"{stem}_q{i}", {"map": m, "start": list(start), "goal": list(goal)}))
    return out


def _point(v, what: str, where: str) -> list[float]:
    if not isinstance(v, (list, tuple)) or len(v) < 2 or not all(isinstance(c, (int, float)) for c in v[:2]):
        raise ScenarioError(f"{where}: {what} must be [x, y] in metres, got {v!r}")
    return [float(v[0]), float(v[1])]


def _check_params(params: Mapping, where: str) -> None:
    if len(params) > MAX_PARAMS:
        raise ScenarioError(f"{where}: {len(params)} parameters; the bound is {MAX_PARAMS} (each becomes a column of "
                            f"the results database, and SQLite allows 2000 columns per table)")
    for k, v in params.items():
        if k in ("seed", "algorithm", "refine", "local_planner", "global_planner"):
            raise ScenarioError(f"{where}: {k!r} is set by the spec grid ('seeds', 'algorithms', 'refine', "
                                f"'local_planners'), not by 'params'")
        if k in ("pop", "iters", "max_evals") and v is not None and (not isinstance(v, int) or isinstance(v, bool)
                                                                     or v < 1):
            raise ParameterError(f"{where}: {k} must be a positive integer (or null), got {v!r}")
    try:
        population_budget(params.get("pop"), params.get("iters"), params.get("max_evals"))
    except ParameterError as exc:
        raise ParameterError(f"{where}: {exc}") from None
    for k, v in params.items():
        try:
            json.dumps(v)
        except TypeError:
            raise ScenarioError(f"{where}: parameter {k!r} must be plain YAML data, got {v!r}") from None


def _keyword_names(fn) -> set[str]:
    import inspect

    return {n for n, p in inspect.signature(fn).parameters.items()
            if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}


def accepted_params(kind: str, algorithm: str) -> set[str] | None:
    """Keyword names a run of ``kind`` with ``algorithm`` accepts as ``params``, or ``None``
    when they cannot be listed (then the run itself checks them)."""
    if kind not in ("plan", "optimize"):
        return None
    from ..solvers.metaheuristics import get_algorithm, optimize

    if kind == "optimize":
        names = _keyword_names(optimize)
    else:
        from ..planning import plan
        from ..registry import GRAPH_METHODS
        from ..solvers.graph import shortest_path
        from ..solvers.paths import plan_path

        names = _keyword_names(plan) | _keyword_names(plan_path)
        if algorithm in GRAPH_METHODS:
            return names | _keyword_names(shortest_path)
    try:
        return names | set(get_algorithm(algorithm).defaults())
    except Exception:  # a planner that is not an engine algorithm (ACO, the path GAs): not listed
        return None


def _check_param_names(kind: str, algorithm: str, params: Mapping, where: str) -> None:
    """A misspelt parameter is found when the spec is loaded, not when every run fails."""
    import difflib

    try:  # op.plan's and op.optimize's default budget where the spec gives none
        population_budget(params.get("pop", 30), params.get("iters", 500), params.get("max_evals"))
    except ParameterError as exc:
        raise ParameterError(f"{where} {algorithm}: {exc}") from None
    known = accepted_params(kind, algorithm)
    if known is None:
        return
    known -= {"world", "start", "goal", "f", "bounds", "algorithm", "seed", "refine", "callback"}
    unknown = sorted(set(params) - known)
    if unknown:
        hints = [f"{u!r} (did you mean {difflib.get_close_matches(u, known, 1)[0]!r}?)"
                 if difflib.get_close_matches(u, known, 1) else repr(u) for u in unknown]
        raise ScenarioError(f"{where}: {algorithm} does not take the parameter(s) {', '.join(hints)}; it takes "
                            f"{', '.join(sorted(known))}")


def _known_algorithms(kind: str) -> list[str]:
    if kind == "optimize":
        from ..solvers.metaheuristics import algorithm_names

        return list(algorithm_names())
    from ..registry import GRAPH_METHODS
    from ..solvers.paths import algorithm_names

    return sorted(set(GRAPH_METHODS) | set(algorithm_names()))


def _parse_algorithms(kind: str, items, shared: Mapping, where: str) -> list[AlgorithmSpec]:
    items = _as_list(items, "algorithms", where)
    if not items:
        raise ScenarioError(f"{where}: no 'algorithms' given; list at least one (see 'optplan algorithms')")
    known = _known_algorithms(kind)
    out = []
    for it in items:
        if isinstance(it, str):
            it = {"name": it}
        if not isinstance(it, dict) or "name" not in it:
            raise ScenarioError(f"{where}: an algorithm is a name or {{name:, label:, params:, runs:}}, got {it!r}")
        _check_keys(it, ALGO_KEYS, f"{where} algorithm {it.get('name')!r}")
        nm = str(it["name"]).lower()
        if nm not in known:
            raise UnknownAlgorithmError(f"{where}: unknown algorithm {it['name']!r} for kind {kind}; known: "
                                        f"{', '.join(known)}")
        own = it.get("params") or {}
        if not isinstance(own, dict):
            raise ScenarioError(f"{where}: params of {nm!r} must be a mapping")
        _check_params(own, where)
        runs = it.get("runs")
        if runs is not None and (not isinstance(runs, int) or isinstance(runs, bool) or runs < 1):
            raise ParameterError(f"{where}: runs of {nm!r} must be a positive integer, got {runs!r}")
        _check_param_names(kind, nm, {**shared, **own}, where)
        out.append(AlgorithmSpec(nm, str(it.get("label") or nm), {**shared, **own}, runs))
    labels = [a.label for a in out]
    if len(set(labels)) != len(labels):
        raise ScenarioError(f"{where}: algorithm labels repeat ({', '.join(labels)}); give repeated algorithms "
                            f"distinct 'label's")
    return out


def _parse_solvers(items, shared: Mapping, where: str) -> list[AlgorithmSpec]:
    """The solver entries of a program spec: a name, a list of names (a chain), or
    ``{name: name-or-list, label:, params:, runs:}``. Each solver gets the shared options it
    takes (as ``op.compare`` does) and its own, all checked by the solver now; a shared
    option that no solver takes is an error. Deterministic solvers (no seed) run once per
    map unless the entry gives ``runs``."""
    from .programs import check_solver_params, is_stochastic, solver_name, solver_options, solver_stages

    items = _as_list(items, "algorithms", where)
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
        _check_keys(it, ALGO_KEYS, f"{where} solver {it.get('name')!r}")
        nm = solver_name(solver_stages(it["name"], where))
        own = it.get("params") or {}
        if not isinstance(own, dict):
            raise ScenarioError(f"{where}: params of {nm!r} must be a mapping")
        if "init" in own:
            raise ScenarioError(f"{where}: 'init' is set by the spec's 'init:' key (a graph planner), not by "
                                f"the params of {nm!r}")
        _check_params(own, where)
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


def _refine_name(r, where: str) -> str | None:
    if r is None or r is False or r == "none":
        return None
    if r not in REFINE_NAMES:
        raise ParameterError(f"{where}: refine must be one of {', '.join(REFINE_NAMES)}, got {r!r}")
    return str(r)


def _check_local(lp, where: str) -> str:
    if not isinstance(lp, str):
        raise ScenarioError(f"{where}: a local planner is a name, got {lp!r}")
    from ..local import algorithm_names

    names = list(algorithm_names())
    if lp.lower() not in names:
        raise UnknownAlgorithmError(f"{where}: unknown local planner {lp!r}; known: {', '.join(names)}")
    return lp.lower()


def _order(v, where: str) -> int:
    if not isinstance(v, int) or isinstance(v, bool):
        raise ScenarioError(f"{where}: order (position among a paper's specs) must be an integer, got {v!r}")
    return v


def _parse_seeds(raw: dict, where: str) -> list[int]:
    if "seeds" in raw and raw["seeds"] is not None:
        seeds = _as_list(raw["seeds"], "seeds", where)
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
