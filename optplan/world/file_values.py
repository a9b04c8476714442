"""Checks of the values read from a scenario file: each returns the clean value or raises a
ScenarioError that names the key and what it takes (``dynamic_obstacles[2].speed must be >= 0``)."""
from __future__ import annotations

import math

import numpy as np

from ..errors import ScenarioError, named_with_hints


def file_number(value, key: str, *, positive: bool = False, non_negative: bool = False) -> float:
    """A finite number (``positive``: > 0, ``non_negative``: >= 0) as a float."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ScenarioError(f"{key} must be a number, got {value!r}")
    try:
        v = float(value)
    except OverflowError:  # an integer of hundreds of digits
        raise ScenarioError(f"{key} must be a finite number, got an integer of {len(str(value))} digits") from None
    if not math.isfinite(v):
        raise ScenarioError(f"{key} must be a finite number, got {value!r}")
    if positive and v <= 0:
        raise ScenarioError(f"{key} must be > 0, got {value!r}")
    if non_negative and v < 0:
        raise ScenarioError(f"{key} must be >= 0, got {value!r}")
    return v


def file_vector(value, key: str, lengths: tuple[int, ...] = (2,)) -> np.ndarray:
    """A list of one of ``lengths`` numbers as a float array."""
    if not isinstance(value, (list, tuple, np.ndarray)) or len(value) not in lengths:
        want = " or ".join(str(n) for n in lengths)
        raise ScenarioError(f"{key} must be a list of {want} numbers, got {value!r}")
    return np.array([file_number(v, f"{key}[{i}]") for i, v in enumerate(value)], dtype=float)


def file_points(value, key: str, min_len: int = 1) -> np.ndarray:
    """A list of at least ``min_len`` ``[x, y]`` pairs as an ``(n, 2)`` float array."""
    if not isinstance(value, (list, tuple)) or len(value) < min_len:
        raise ScenarioError(f"{key} must be a list of at least {min_len} [x, y] pairs, got {value!r}")
    return np.array([file_vector(p, f"{key}[{i}]") for i, p in enumerate(value)], dtype=float).reshape(-1, 2)


def file_mapping(value, key: str, allowed: tuple[str, ...]) -> dict:
    """A mapping whose keys are all in ``allowed`` (returned unchanged)."""
    if not isinstance(value, dict):
        raise ScenarioError(f"{key} must be a mapping with keys {', '.join(allowed)}, got {value!r}")
    unknown = sorted(set(map(str, value)) - set(allowed))
    if unknown:
        raise ScenarioError(f"unknown key(s) {named_with_hints(unknown, allowed)} in {key}; known: {', '.join(allowed)}")
    return value


def file_range(value, key: str) -> tuple[float, float]:
    """``[low, high]`` with ``0 <= low <= high`` (one number ``v`` means ``[v, v]``)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        v = file_number(value, key, non_negative=True)
        return (v, v)
    lo, hi = file_vector(value, key)
    if lo < 0 or hi < lo:
        raise ScenarioError(f"{key} must be [low, high] with 0 <= low <= high, got {value!r}")
    return (float(lo), float(hi))
