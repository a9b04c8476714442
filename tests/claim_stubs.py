"""Stand-ins for the parts of a bench spec that ``claims.judge`` reads (shared by the claim tests)."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass
class StubTarget:
    name: str


@dataclass
class StubSpec:
    name: str
    targets: list
    kind: str = "simulate"
    alpha: float = 0.05
