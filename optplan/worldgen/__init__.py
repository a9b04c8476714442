"""Experiment generation: the seeded parts of worlds that need a planner to make.

It sits above the solvers in the layer order (``docs/architecture.md``) because what it
draws is checked with them: the random obstacles and movers of a scenario are placed on
the run's global path (or the known map's shortest path) and must leave the goal
reachable (:mod:`optplan.worldgen.scenarios`), and the generated circle worlds of the
paper maps keep the seed whose exact optimum lies in a band (:mod:`optplan.worldgen.papermaps`).
The schemas (scenario files, the map catalogue) stay in :mod:`optplan.world`.
"""
