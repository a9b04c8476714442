"""Errors raised by optplan.

Every error is an :class:`OptplanError`; its message says what was wrong and
how to fix it. The command line prints the message on one line and exits 2.
"""
from __future__ import annotations

import difflib
from collections.abc import Iterable


class OptplanError(Exception):
    """Base class of every error optplan raises on purpose."""


class MapFormatError(OptplanError):
    """A map file (or in-memory map) could not be read or is malformed."""


class InfeasibleQueryError(OptplanError):
    """Start or goal is outside the map, blocked, or the goal is unreachable."""


class UnknownAlgorithmError(OptplanError):
    """An algorithm, local planner or method name is not registered."""


class ParameterError(OptplanError):
    """A parameter is out of range, of the wrong type, NaN or infinite."""


class ScenarioError(OptplanError):
    """A scenario file is malformed (missing or unknown keys, wrong types)."""


def named_with_hints(unknown: Iterable, known: Iterable) -> str:
    """``'lenght' (did you mean 'length'?), 'colour'``: the unknown names, each with the known
    name it was most likely meant to be, for every "unknown option/key" message."""
    known = sorted(map(str, known))
    out = []
    for name in map(str, unknown):
        # a close spelling, the name a shortened one begins (local -> local_planner), or the
        # short name a longer one begins with (population -> pop)
        close = (difflib.get_close_matches(name, known, 1) or [k for k in known if k.startswith(name + "_")][:1]
                 or sorted((k for k in known if len(k) >= 3 and name.startswith(k)), key=len)[-1:])
        out.append(f"{name!r} (did you mean {close[0]!r}?)" if close else repr(name))
    return ", ".join(out)
