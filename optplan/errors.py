"""Errors raised by optplan.

Every error is an :class:`OptplanError`; its message says what was wrong and
how to fix it. The command line prints the message on one line and exits 2.
"""
from __future__ import annotations


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
