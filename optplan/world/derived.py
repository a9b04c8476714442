"""Data derived from a world, kept for the world's lifetime and owned by its builder.

Distance fields, segment tables, roadmaps and similar precomputations are built once per map
and reused by every run on it. Each module that builds such data owns one
:class:`DerivedStore` and keeps its entries there under keys of its own choosing. The store
files them in the world under the store's name, so that:

- two builders never share or overwrite each other's keys;
- everything a world holds is dropped with the world (no process-global tables to clear);
- this module is the only one that touches the world's private slot
  (``tests/test_architecture.py`` checks it).

Built solver objects are not derived data and are not kept here: the solvers own them.
"""
from __future__ import annotations

from typing import Any


class DerivedStore:
    """One builder's data derived from worlds (see the module docstring)."""

    def __init__(self, name: str) -> None:
        self.name = str(name)

    def of(self, world) -> dict:
        """This builder's entries for ``world`` (a dict, created empty on first use)."""
        slot = world._cache
        entries = slot.get(self.name)
        if entries is None:
            entries = slot[self.name] = {}
        return entries

    def __repr__(self) -> str:
        return f"DerivedStore({self.name!r})"


def forget_derived(world) -> None:
    """Drop everything derived from ``world`` (for benchmarks that time cold starts)."""
    world._cache.clear()


def derived_keys(world) -> list[tuple[str, Any]]:
    """``(builder name, key)`` of every entry derived from ``world`` (what a world holds)."""
    return [(name, key) for name, entries in world._cache.items() for key in entries]
