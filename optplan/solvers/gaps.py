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

from ..errors import ParameterError

from ..world.geometry import validate_path
from ..world.metrics import path_length
from ..world.roadmap import h_signature
from .graph import shortest_path
from .homotopy import class_shortest_path

GAP_KEYS = ("exact_length", "class_length", "gap", "class_gap", "in_class_gap", "optimal_class")


def class_gaps(world, start, goal, path, exact=None, clearance: float = 0.0) -> dict:
    """The gap of ``path`` to the exact optimum split into the class gap and the in-class gap.

    ``gap = (L - L*) / L*`` with ``L*`` the exact optimum; ``class_gap = (C - L*) / L*`` with ``C``
    the shortest path in the class of ``path`` (the corridor the planner chose) and
    ``in_class_gap = (L - C) / L*`` (the shape within it), so ``gap = class_gap + in_class_gap``.
    ``optimal_class`` is true when ``path`` has the h-signature of the exact optimum's path; then
    ``C = L*`` by definition. ``exact``: the exact planner's :class:`PlanResult` for these ends
    (computed when ``None``; pass it when judging many paths). All ``None`` for an infeasible path;
    the class keys ``None`` when the class search gives up (too many classes within the path's
    length, on large cluttered maps: :func:`~optplan.solvers.homotopy.class_shortest_path`).
    """
    out = dict.fromkeys(GAP_KEYS)
    P = np.asarray(path, float)
    if len(P) < 2 or not validate_path(world, P, clearance).ok:
        return out
    if exact is None:
        exact = shortest_path(world, start, goal, method="visibility", clearance=clearance)
    L_opt = float(exact.length)
    L = float(path_length(P[None])[0])
    # the signature needs only the components' rays, not the roadmap
    same = bool(np.array_equal(h_signature(world, P, clearance), h_signature(world, exact.path, clearance)))
    if same:
        C = L_opt
    else:
        try:
            _, C, _ = class_shortest_path(world, start, goal, P, clearance)
        except ParameterError:
            # too many classes within the path's length to search (large cluttered maps): the
            # gap stands, its split is not known
            out.update(exact_length=L_opt, gap=(L - L_opt) / L_opt, optimal_class=False)
            return out
        C = max(min(C, L), L_opt)
    out.update(exact_length=L_opt, class_length=C, gap=(L - L_opt) / L_opt, class_gap=(C - L_opt) / L_opt,
               in_class_gap=(L - C) / L_opt, optimal_class=same)
    return out
