"""The gap of a path to the exact optimum, split into "wrong corridor" and "wrong shape".

For a feasible path of length ``L`` between start and goal, ``L*`` the exact optimum
(:func:`optplan.shortest_path` with ``method="visibility"``) and ``C`` the shortest path in
the path's own h-signature class (:mod:`optplan.solvers.homotopy`):

* class gap ``(C - L*) / L*``: what the global planner decided (the corridor);
* in-class gap ``(L - C) / L*``: what a local refinement can still fix (the shape);

and the two add up to the gap ``(L - L*) / L*``.
"""
from __future__ import annotations

import numpy as np

from ..world.geometry import validate_path
from ..world.metrics import path_length
from .graph import shortest_path
from .homotopy import class_shortest_path

GAP_KEYS = ("exact_length", "class_length", "gap", "class_gap", "in_class_gap", "optimal_class")


def class_gaps(world, start, goal, path, exact_length: float | None = None, clearance: float = 0.0) -> dict:
    """The gap of ``path`` to the exact optimum split into the class gap and the in-class gap.

    ``gap = (L - L*) / L*`` with ``L*`` the exact optimum; ``class_gap = (C - L*) / L*`` with ``C``
    the shortest path in the class of ``path`` (the corridor the planner chose) and
    ``in_class_gap = (L - C) / L*`` (the shape within it), so ``gap = class_gap + in_class_gap``.
    ``optimal_class`` is true when the class optimum equals the exact optimum (to 1e-6 relative).
    All ``None`` for an infeasible path.
    """
    out = dict.fromkeys(GAP_KEYS)
    P = np.asarray(path, float)
    if len(P) < 2 or not validate_path(world, P, clearance).ok:
        return out
    if exact_length is None:
        exact_length = float(shortest_path(world, start, goal, method="visibility", clearance=clearance).length)
    L = float(path_length(P[None])[0])
    _, C, _ = class_shortest_path(world, start, goal, P, clearance)
    C = min(C, L)
    out.update(exact_length=exact_length, class_length=C, gap=(L - exact_length) / exact_length,
               class_gap=(C - exact_length) / exact_length, in_class_gap=(L - C) / exact_length,
               optimal_class=bool(C <= exact_length * (1 + 1e-6) + 1e-9))
    return out
