"""The fields of an experiment spec that every run kind reads the same way: key checks, file
names confined to the spec's folder, map and ``.scen`` targets, shared parameters, refine
modes and local planners, and the target and algorithm entries they become."""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from ..checks import metres, population_budget
from ..errors import ParameterError, ScenarioError, UnknownAlgorithmError, named_with_hints

ALGO_KEYS = {"name", "label", "params", "runs"}
MAX_PARAMS = 200  # per algorithm entry; every parameter is a column of the results table
MAP_KEYS = {"name", "map", "start", "goal", "scen", "queries"}


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



def check_keys(d: Mapping, allowed: set, where: str) -> None:
    """Refuse keys of ``d`` outside ``allowed``, naming them and the allowed ones."""
    unknown = sorted(set(d) - allowed)
    if unknown:
        raise ScenarioError(f"{where}: unknown key(s) {named_with_hints(unknown, allowed)}; allowed: "
                            f"{', '.join(sorted(allowed))}")



def as_list(value, what: str, where: str) -> list:
    """``value`` as a list (one scalar or mapping becomes a list of one; ``None`` an empty list)."""
    if value is None:
        return []
    if isinstance(value, (str, int, float, dict)):
        return [value]
    if isinstance(value, list):
        return value
    raise ScenarioError(f"{where}: '{what}' must be a list, got {type(value).__name__}")



def spec_file(name, base_dir: Path, from_file: bool, what: str, where: str) -> str:
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



def check_map_target(m: str, start, goal, where: str):
    """Load a map target now, so a bad map or query stops the spec before any run."""
    from ..errors import OptplanError
    from ..world.loaders import load_map

    from ..world.queries import grid_reachable

    try:
        world = load_map(m)
        if start is not None:
            world.check_query_point(start, "start")
            world.check_query_point(goal, "goal")
    except OptplanError as exc:
        raise ScenarioError(f"{where}: {exc}") from None
    if start is not None and world.is_grid and not grid_reachable(world, start, goal):
        raise ScenarioError(f"{where}: the goal {tuple(goal)} cannot be reached from the start {tuple(start)} (no free "
                            "passage joins them); every run would fail, so none is started")
    return world



def scen_targets(it: dict, base_dir: Path, from_file: bool, where: str) -> list[TargetSpec]:
    """Targets from a Moving AI ``.scen`` file: ``{scen: FILE.scen, map: FILE.map,
    queries: [0, 5] | N}`` (``map`` defaults to the file the scenario names, next to it;
    ``queries`` to every query, an integer N to the first N)."""
    from ..errors import OptplanError
    from ..world.loaders import load_scen, scen_query

    check_keys(it, MAP_KEYS - {"start", "goal"}, f"{where} scen entry")
    scen = spec_file(it["scen"], base_dir, from_file, "scen file", where)
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
        m = spec_file(m, base_dir, from_file, "map", where)
    q = it.get("queries", len(entries))
    if isinstance(q, int) and not isinstance(q, bool) and q >= 1:
        picks = list(range(min(q, len(entries))))
    elif isinstance(q, list) and q and all(isinstance(i, int) and not isinstance(i, bool) for i in q):
        picks = q
    else:
        raise ScenarioError(f"{where}: 'queries' is a positive count or a list of query indices, got {q!r}")
    world = check_map_target(m, None, None, f"{where} map {m!r}")
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



def point(v, what: str, where: str) -> list[float]:
    """``[x, y]`` in metres as two floats."""
    if not isinstance(v, (list, tuple)) or len(v) < 2 or not all(isinstance(c, (int, float)) for c in v[:2]):
        raise ScenarioError(f"{where}: {what} must be [x, y] in metres, got {v!r}")
    return [float(v[0]), float(v[1])]



def check_params(params: Mapping, where: str) -> None:
    """Check a ``params:`` mapping: bounded size, no grid keys, positive budgets, plain YAML data."""
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
        if _holds_nan(v):
            raise ParameterError(f"{where}: parameter {k!r} is or holds .nan, which no option takes; every run "
                                 "would fail, so none is started")
    if "clearance" in params:
        metres(f"{where}: clearance", params["clearance"])


def _holds_nan(value) -> bool:
    """Whether a YAML value (numbers, lists, mappings) is or holds a NaN."""
    if isinstance(value, float):
        return value != value
    if isinstance(value, dict):
        return any(_holds_nan(v) for v in value.values())
    if isinstance(value, (list, tuple)):
        return any(_holds_nan(v) for v in value)
    return False



def keyword_names(fn) -> set[str]:
    """The keyword parameter names of ``fn``."""
    import inspect

    return {n for n, p in inspect.signature(fn).parameters.items()
            if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}



def refine_name(r, where: str) -> str | None:
    """A ``refine:`` entry as the refine mode (``None`` for none)."""
    if r is None or r is False or r == "none":
        return None
    from ..solvers.refine import METHODS

    names = ("none", *METHODS)
    if r not in names:
        raise ParameterError(f"{where}: refine must be one of {', '.join(names)}, got {r!r}")
    return str(r)



def check_local(lp, where: str) -> str:
    """A ``local_planners:`` entry as a registered local planner name."""
    if not isinstance(lp, str):
        raise ScenarioError(f"{where}: a local planner is a name, got {lp!r}")
    from ..local import algorithm_names

    names = list(algorithm_names())
    if lp.lower() not in names:
        raise UnknownAlgorithmError(f"{where}: unknown local planner {lp!r}; known: {', '.join(names)}")
    return lp.lower()


def check_param_names(kind, algorithm: str, params: Mapping, where: str) -> None:
    """A misspelt parameter is found when the spec is loaded, not when every run fails
    (``kind.accepted_params`` lists what a run of that kind takes)."""
    try:  # op.plan's and op.optimize's default budget where the spec gives none
        population_budget(params.get("pop", 30), params.get("iters", 500), params.get("max_evals"))
    except ParameterError as exc:
        raise ParameterError(f"{where} {algorithm}: {exc}") from None
    known = kind.accepted_params(algorithm)
    if known is None:
        return
    known -= {"world", "start", "goal", "f", "bounds", "algorithm", "seed", "refine", "callback"}
    unknown = sorted(set(params) - known)
    if unknown:
        raise ScenarioError(f"{where}: {algorithm} does not take the parameter(s) {named_with_hints(unknown, known)}; "
                            f"it takes {', '.join(sorted(known))}")


def parse_algorithms(kind, items, shared: Mapping, where: str) -> list[AlgorithmSpec]:
    """The ``algorithms:`` entries of a spec of ``kind`` (a name or ``{name:, label:, params:,
    runs:}``), each checked against ``kind.known_algorithms()`` and its parameters."""
    items = as_list(items, "algorithms", where)
    if not items:
        raise ScenarioError(f"{where}: no 'algorithms' given; list at least one (see 'optplan algorithms')")
    known = kind.known_algorithms()
    out = []
    for it in items:
        if isinstance(it, str):
            it = {"name": it}
        if not isinstance(it, dict) or "name" not in it:
            raise ScenarioError(f"{where}: an algorithm is a name or {{name:, label:, params:, runs:}}, got {it!r}")
        check_keys(it, ALGO_KEYS, f"{where} algorithm {it.get('name')!r}")
        nm = str(it["name"]).lower()
        if nm not in known:
            raise UnknownAlgorithmError(f"{where}: unknown algorithm {it['name']!r} for kind {kind.name}; known: "
                                        f"{', '.join(known)}")
        own = it.get("params") or {}
        if not isinstance(own, dict):
            raise ScenarioError(f"{where}: params of {nm!r} must be a mapping")
        check_params(own, where)
        runs = it.get("runs")
        if runs is not None and (not isinstance(runs, int) or isinstance(runs, bool) or runs < 1):
            raise ParameterError(f"{where}: runs of {nm!r} must be a positive integer, got {runs!r}")
        check_param_names(kind, nm, {**shared, **own}, where)
        out.append(AlgorithmSpec(nm, str(it.get("label") or nm), {**shared, **own}, runs))
    labels = [a.label for a in out]
    if len(set(labels)) != len(labels):
        raise ScenarioError(f"{where}: algorithm labels repeat ({', '.join(labels)}); give repeated algorithms "
                            f"distinct 'label's")
    return out
