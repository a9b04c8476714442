"""The files a run reads, and one content hash of them for its key.

A run's key (:attr:`optplan.bench.spec.RunRecord.key`) must change whenever what the run
computes could change. The target's description names its map or scenario by path or
by shipped name, so editing the file in place would leave the key as it was and a rerun
would serve the stored, stale result. Each run kind lists the files its runs read
(:meth:`optplan.bench.kinds.base.RunKind.input_files`) and :func:`files_digest` hashes their
*content*:

* ``plan`` on ``{map, start, goal}``: the map file, and for a ROS ``.yaml`` map its image;
* ``plan`` on a paper map: its catalogue entry (file, start, goal) and its map file;
* ``simulate``: the scenario file and the map it names (relative to the scenario, a
  shipped map name, or inline rows, which are part of the scenario file already);
* ``optimize``: nothing (benchmark functions are code);
* ``program``: the map files as for ``plan``, and for a ``module:function`` program the
  source file of that module (not of the modules it imports; the built-in programs are
  optplan's code, like every solver).

The files are resolved by the same rules as the loaders (``load_map``, ``load_scenario``).
A file that cannot be found or read is hashed as missing, so the run itself reports the
problem.
"""
from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import Any, Mapping


def _file_hash(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _map_file(spec: str, base_dir: Path | None = None) -> Path | None:
    """The file ``load_map`` (or a scenario's ``map:`` relative to ``base_dir``) reads for ``spec``."""
    from ..world import maps

    p = Path(spec)
    if not p.is_absolute() and base_dir is not None and (base_dir / p).exists():
        p = base_dir / p
    if p.is_file():
        return p
    return maps.find(str(spec)) if not p.exists() else None


def _map_files(spec: str, base_dir: Path | None = None) -> list[tuple[str, Path | None]]:
    """``(role, path)`` of a map and what it references (the image of a ROS map YAML)."""
    path = _map_file(spec, base_dir)
    out: list[tuple[str, Path | None]] = [("map", path)]
    if path is not None and path.suffix.lower() in (".yaml", ".yml"):
        try:
            from ..world.loaders import read_yaml

            meta = read_yaml(path, "map metadata")
            image = Path(str(meta["image"]))
        except Exception:  # unreadable metadata: the loader reports it when the run starts
            return out
        out.append(("map image", image if image.is_absolute() else path.parent / image))
    return out


def _scenario_files(spec: str) -> list[tuple[str, Path | None]]:
    from ..world.scenario import SCENARIOS_DIR

    p = Path(spec)
    if not p.is_file():
        shipped = SCENARIOS_DIR / (p.name if p.suffix == ".yaml" else f"{p.name}.yaml")
        p = shipped if shipped.is_file() else None
    out: list[tuple[str, Path | None]] = [("scenario", p)]
    if p is None:
        return out
    try:
        from ..world.loaders import read_yaml

        data = read_yaml(p, "scenario file")
    except Exception:  # unreadable: load_scenario reports it when the run starts
        return out
    m = data.get("map") if isinstance(data, dict) else None
    if isinstance(m, str):
        out += _map_files(m, p.parent)
    return out


def map_target_files(target_spec: Mapping[str, Any]) -> list[tuple[str, Path | None]]:
    """``(role, path)`` of the files a map target (``{map: ...}`` or ``{paper_map: ...}``) reads."""
    if "map" in target_spec:
        return _map_files(str(target_spec["map"]))
    if "paper_map" in target_spec:
        from ..world.papermaps import MAPS_DIR, catalogue

        entry = catalogue().get(str(target_spec["paper_map"]))
        return [] if entry is None else _map_files(str(MAPS_DIR / entry.file))
    return []


def scenario_target_files(target_spec: Mapping[str, Any]) -> list[tuple[str, Path | None]]:
    """``(role, path)`` of the files a scenario target reads (the scenario and its map)."""
    return _scenario_files(str(target_spec["scenario"])) if "scenario" in target_spec else []


def map_target_entries(target_spec: Mapping[str, Any]) -> list[list[str]]:
    """What a paper-map target takes from the catalogue besides its file (start and goal)."""
    if "paper_map" not in target_spec:
        return []
    from ..world.papermaps import catalogue

    entry = catalogue().get(str(target_spec["paper_map"]))
    if entry is None:
        return []
    return [["paper map entry", json.dumps([entry.file, list(entry.start), list(entry.goal)])]]


def files_digest(files: list[tuple[str, Path | None]], entries: list[list[str]] = ()) -> str:
    """One SHA-256 over the content of ``files`` (in reading order) and then ``entries``
    (``""`` when both are empty). Paths are left out: moving an unchanged file keeps the key,
    editing one changes it."""
    parts = []
    for role, path in files:
        try:
            parts.append([role, _file_hash(path) if path is not None else "missing"])
        except OSError:
            parts.append([role, "unreadable"])
    parts += [list(e) for e in entries]
    if not parts:
        return ""
    return hashlib.sha256(json.dumps(parts).encode()).hexdigest()[:20]
