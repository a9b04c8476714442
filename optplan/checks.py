"""Option checkers shared by every layer: each takes ``(name, value)`` and returns the
clean value or raises a ParameterError that names the option and what it takes."""
from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np

from .errors import ParameterError


def integer(minimum: int = 0, maximum: int | None = None, optional: bool = False) -> Callable[[str, Any], Any]:
    """An integer in ``[minimum, maximum]`` (``None`` allowed when ``optional``)."""
    def check(name: str, value):
        if value is None and optional:
            return None
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum \
                or (maximum is not None and value > maximum):
            top = f" and <= {maximum}" if maximum is not None else ""
            raise ParameterError(f"{name} must be an integer >= {minimum}{top}"
                                 f"{' or None' if optional else ''}, got {value!r}")
        return int(value)
    return check


def number(minimum: float = -math.inf, maximum: float = math.inf, optional: bool = False,
           strict_minimum: bool = False) -> Callable[[str, Any], Any]:
    """A finite real number in the range (``None`` allowed when ``optional``)."""
    def check(name: str, value):
        if value is None and optional:
            return None
        ok = not isinstance(value, bool) and isinstance(value, (int, float, np.integer, np.floating))
        v = float(value) if ok else math.nan
        if not ok or not math.isfinite(v) or v < minimum or v > maximum or (strict_minimum and v <= minimum):
            rel = ">" if strict_minimum else ">="
            lo = f" {rel} {minimum:g}" if math.isfinite(minimum) else ""
            hi = f" and <= {maximum:g}" if math.isfinite(maximum) else ""
            raise ParameterError(f"{name} must be a finite number{lo}{hi}{' or None' if optional else ''}, "
                                 f"got {value!r}")
        return v
    return check


def choice(*values) -> Callable[[str, Any], Any]:
    """One of ``values`` (compared with ``in``)."""
    def check(name: str, value):
        if value not in values:
            raise ParameterError(f"{name} must be one of {', '.join(map(repr, values))}; got {value!r}")
        return value
    return check


def mapping(name_of_contents: str) -> Callable[[str, Any], Any]:
    """A dict (e.g. a solver's own settings), copied."""
    def check(name: str, value):
        if value is None:
            return {}
        if not isinstance(value, dict) or not all(isinstance(k, str) for k in value):
            raise ParameterError(f"{name} must be a dict of {name_of_contents}, got {value!r}")
        return dict(value)
    return check


def seed(name: str, value):
    """An int >= 0, None or a numpy Generator (as :func:`optplan.rng.as_generator` takes)."""
    from .rng import as_generator

    as_generator(value) if not isinstance(value, np.random.Generator) else None
    return value


def anything(name: str, value):
    """Any value (the consumer checks it, e.g. an algorithm's own parameter)."""
    return value
