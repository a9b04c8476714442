"""Maps shipped inside the package (see ``optplan/data/maps/README.md``)."""
from __future__ import annotations

from pathlib import Path

MAPS_DIR = Path(__file__).resolve().parent.parent / "data" / "maps"
_SUFFIXES = (".map", ".txt", ".csv", ".npy", ".yaml", ".json")


def names() -> list[str]:
    """Names of the shipped maps (file stems)."""
    return sorted(p.stem for p in MAPS_DIR.iterdir() if p.suffix in _SUFFIXES)


def find(name: str) -> Path | None:
    """Path of a shipped map given its stem or file name, or ``None``."""
    direct = MAPS_DIR / name
    if direct.is_file():
        return direct
    for suffix in _SUFFIXES:
        cand = MAPS_DIR / f"{name}{suffix}"
        if cand.is_file():
            return cand
    return None
