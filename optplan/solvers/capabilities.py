"""What each global planner can do, declared by the planner's own module and read by
``op.plan``, ``op.algorithms(world)``, ``optplan algorithms --details`` and the option checks.

A planner declares one :class:`PlannerCapabilities`: the graph methods in
:mod:`optplan.solvers.graph`, ACO, IACO and the path GAs in their modules of
:mod:`optplan.solvers.gridpath`, and every metaheuristic through
:meth:`optplan.solvers.metaheuristics.engine.Algorithm.capabilities`;
:func:`optplan.solvers.catalog.planner_capabilities` collects them. A new planner is one
class (or one module) and one registry entry; nothing else lists it.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class PlannerCapabilities:
    """One global planner's capabilities.

    Attributes:
        name: the ``algorithm=`` name.
        kind: ``graph`` (exact search on a graph), ``aco`` (ants on the cell graph),
            ``cell-ga`` (a GA on its own cell chromosome) or ``swarm`` (a metaheuristic over
            an encoding's variables).
        grid_only: why the planner needs an occupancy grid, or ``None`` (any world).
        stochastic: whether its result depends on ``seed``.
        alternatives: whether it can also return other valid paths of its population
            (``alternatives=k``).
        exact: whether it returns the exact optimum of its own graph.
    """

    name: str
    kind: str
    grid_only: str | None = None
    stochastic: bool = True
    alternatives: bool = False
    exact: bool = False

    def runs_on(self, world) -> bool:
        """Whether the planner takes ``world``."""
        return self.grid_only is None or bool(world.is_grid)

    def describe(self) -> str:
        """The capabilities in a few words (``optplan algorithms --details``)."""
        words = [self.kind, "grid only" if self.grid_only else "any world",
                 "stochastic" if self.stochastic else "deterministic"]
        if self.exact:
            words.append("exact")
        if self.alternatives:
            words.append("alternatives")
        return ", ".join(words)
