"""Option checkers shared by every layer: each takes ``(name, value)`` and returns the
clean value or raises a ParameterError that names the option and what it takes."""
from __future__ import annotations

import math
from typing import Any, Callable, Mapping

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
        try:
            v = float(value) if ok else math.nan
        except OverflowError:  # an int of hundreds of digits
            v = math.nan
        if not ok or not math.isfinite(v) or v < minimum or v > maximum or (strict_minimum and v <= minimum):
            rel = ">" if strict_minimum else ">="
            lo = f" {rel} {minimum:g}" if math.isfinite(minimum) else ""
            hi = f" and <= {maximum:g}" if math.isfinite(maximum) else ""
            raise ParameterError(f"{name} must be a finite number{lo}{hi}{' or None' if optional else ''}, "
                                 f"got {value!r}")
        return v
    return check


def metres(name: str, value, none_means: str | None = None) -> float | None:
    """``value`` as a distance in metres: anything ``float()`` reads as a finite number >= 0
    (``None`` too when ``none_means`` says what it stands for); else a ParameterError
    naming ``name``. The one rule for clearances, radii and tube widths."""
    if value is None and none_means is not None:
        return None
    try:
        r = float(value)
    except (TypeError, ValueError, OverflowError):
        r = math.nan
    if isinstance(value, bool) or not math.isfinite(r) or r < 0:
        alt = f" or None for {none_means}" if none_means is not None else ""
        raise ParameterError(f"{name} must be a finite number >= 0 metres{alt}, got {value!r}")
    return r


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


def function(optional: bool = False) -> Callable[[str, Any], Any]:
    """A callable (``None`` allowed when ``optional``)."""
    def check(name: str, value):
        if value is None and optional:
            return None
        if not callable(value):
            raise ParameterError(f"{name} must be a function{' or None' if optional else ''}, "
                                 f"got {type(value).__name__} {value!r:.60}")
        return value
    return check


def boolean(name: str, value) -> bool:
    """``True`` or ``False`` (a numpy bool too), nothing that merely converts to one."""
    if not isinstance(value, (bool, np.bool_)):
        raise ParameterError(f"{name} must be True or False, got {value!r:.60}")
    return bool(value)


def file_path(name: str, value):
    """A non-empty file name: ``str`` or ``os.PathLike``."""
    import os

    if not isinstance(value, (str, os.PathLike)) or not str(value):
        raise ParameterError(f"{name} must be a file name (str or pathlib.Path), got {value!r:.60}")
    return value


def float_array(name: str, value, shape_text: str = "an array of numbers") -> np.ndarray:
    """``value`` as a float array, or a ParameterError naming ``name`` when it holds no numbers."""
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be {shape_text}, got {value!r:.60}") from None


def anything(name: str, value):
    """Any value (the consumer checks it, e.g. an algorithm's own parameter)."""
    return value


# ------------------------------------------------------------------ resource bounds
# Bounds on what one call may ask for, derived from memory and time rather than from taste:
# a request past them cannot finish on a workstation, so it is refused before any work
# starts, with the numbers in the message.
MEMORY_BUDGET_BYTES = 2 * 1024 ** 3   # what one population may hold (2 GiB)
POPULATION_COPIES = 8                 # float64 (pop, dim) arrays alive at once in a step (X, V, F, trials, ...)
MAX_EVALUATIONS = 10 ** 9             # objective rows per run: ~8 h at the ~3e4 path rows/s of a 20x20 map
MAX_RUNS = 100_000                    # runs per spec: each is a stored row (~1 s to 10 min of work)
MAX_SEED = 2 ** 63 - 1                # seeds are stored as SQLite INTEGERs (signed 64-bit)


def population_budget(pop, iters, max_evals, dim: int = 1) -> None:
    """Refuse a population or budget that cannot fit in memory or finish in hours.

    ``pop * dim * 8 bytes * POPULATION_COPIES`` must stay within
    :data:`MEMORY_BUDGET_BYTES`, and the evaluations asked for (``pop * iters``, or
    ``max_evals``) within :data:`MAX_EVALUATIONS`.
    """
    for name, v in (("pop", pop), ("iters", iters), ("max_evals", max_evals)):
        if v is not None and (isinstance(v, bool) or not isinstance(v, (int, np.integer))):
            raise ParameterError(f"{name} must be an integer, got {v!r}")
    dim = max(int(dim), 1)
    if pop is not None and pop > 0:
        need = int(pop) * dim * 8 * POPULATION_COPIES
        if need > MEMORY_BUDGET_BYTES:
            top = MEMORY_BUDGET_BYTES // (dim * 8 * POPULATION_COPIES)
            if iters and max_evals is None and isinstance(iters, (int, np.integer)) and iters > 0:
                top = min(top, MAX_EVALUATIONS // int(iters))   # the hint must pass the evaluation bound too
            raise ParameterError(f"pop {pop} needs about {need / 1024 ** 3:.3g} GiB for {dim} variables per "
                                 f"individual; the bound is {MEMORY_BUDGET_BYTES / 1024 ** 3:g} GiB, i.e. pop <= {top}"
                                 + (f" with iters={iters}" if iters and max_evals is None else ""))
    evals = max_evals if max_evals is not None else (int(pop) * int(iters) if pop and iters else None)
    if evals is not None and evals > MAX_EVALUATIONS:
        raise ParameterError(f"the budget asks for {evals:.3g} objective evaluations (pop x iters or max_evals); the "
                             f"bound is {MAX_EVALUATIONS:.0e}, several hours of work; lower iters or max_evals")


def seed_bound(name: str, value) -> None:
    """An integer seed must fit the results database's signed 64-bit INTEGER."""
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool) and value > MAX_SEED:
        raise ParameterError(f"{name} must be <= 2**63 - 1 (stored as a 64-bit integer), got {value}")


def settings_key(settings: Mapping[str, Any]) -> tuple[tuple[str, str], ...]:
    """A hashable, order-free key for a solver's settings, used to key cached solver objects by
    the settings they were built with (values compared by their text, so ``1e-6`` and
    ``0.000001`` are the same setting)."""
    return tuple(sorted((str(k), str(v)) for k, v in settings.items()))


MEMORY_BUDGET_GB = 8.0  # default bound on one method's own tables (the machines here have 24 GB)


def memory_budget(what: str, estimate_bytes: float, instead: str) -> None:
    """Refuse, before any work, a method whose own tables would take more memory than the
    budget (``OPTPLAN_MEMORY_GB``, default :data:`MEMORY_BUDGET_GB`): the message gives the
    estimate and what to use ``instead``. For costs inherent to a method only."""
    import os

    try:
        budget = float(os.environ.get("OPTPLAN_MEMORY_GB", MEMORY_BUDGET_GB))
    except ValueError:
        raise ParameterError(f"OPTPLAN_MEMORY_GB must be a number of gigabytes, got "
                             f"{os.environ.get('OPTPLAN_MEMORY_GB')!r}") from None
    if estimate_bytes > budget * 2 ** 30:
        need = (f"{estimate_bytes / 2 ** 30:.1f} GB" if estimate_bytes >= 2 ** 30
                else f"{estimate_bytes / 2 ** 20:.0f} MB")
        raise ParameterError(f"{what} needs about {need} of memory on this map, over the {budget:g} GB budget "
                             f"(OPTPLAN_MEMORY_GB); {instead}")
