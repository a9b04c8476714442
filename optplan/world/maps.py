"""Maps shipped inside the package (see ``optplan/data/maps/README.md``)."""
from __future__ import annotations

from pathlib import Path

MAPS_DIR = Path(__file__).resolve().parent.parent / "data" / "maps"
_SUFFIXES = (".map", ".txt", ".csv", ".npy", ".yaml", ".json")


PAPER_CATALOGUE = MAPS_DIR / "paper_maps.yaml"


def names() -> list[str]:
    """Names of the shipped maps (file stems; the paper-map catalogue is not a map)."""
    return sorted(p.stem for p in MAPS_DIR.iterdir() if p.suffix in _SUFFIXES and p != PAPER_CATALOGUE)


def find(name: str) -> Path | None:
    """Path of a shipped map given its stem or file name, or ``None``."""
    direct = MAPS_DIR / name
    if direct.is_file() and direct != PAPER_CATALOGUE:
        return direct
    for suffix in _SUFFIXES:
        cand = MAPS_DIR / f"{name}{suffix}"
        if cand.is_file() and cand != PAPER_CATALOGUE:
            return cand
    return None


def paper_map_file(name: str) -> Path | None:
    """The shipped file of a paper map (``chen2025_20``, ...; see ``paper_maps.yaml``), or ``None``."""
    import yaml

    entry = (yaml.safe_load(PAPER_CATALOGUE.read_text()) or {}).get(str(name))
    return MAPS_DIR / entry["file"] if isinstance(entry, dict) and "file" in entry else None
