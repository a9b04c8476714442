"""The run kinds of a benchmark spec, one module each behind :class:`~.base.RunKind`, and
their registry: ``KINDS[name]`` is the kind's instance."""
from __future__ import annotations

from ...errors import ScenarioError
from .base import RunKind
from .optimize import OptimizeKind
from .plan import PlanKind
from .program import ProgramKind
from .simulate import SimulateKind

KINDS: dict[str, RunKind] = {k.name: k for k in (PlanKind(), SimulateKind(), OptimizeKind(), ProgramKind())}


def get_kind(name: str) -> RunKind:
    """The registered run kind ``name``."""
    kind = KINDS.get(name) if isinstance(name, str) else None
    if kind is None:
        raise ScenarioError(f"kind must be one of {', '.join(KINDS)}, got {name!r}")
    return kind


__all__ = ["KINDS", "RunKind", "get_kind"]
