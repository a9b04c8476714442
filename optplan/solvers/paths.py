"""Global path planning with metaheuristics: formulation + solver + exact check.

``plan_path`` builds a :class:`PathProblem` (an encoding and a paper's fitness
preset) and the paper's program over the matching variables
(:func:`~optplan.formulations.paper_programs.planner_program`, the problem its checked
acceleration), solves it with the program swarm solver of the chosen algorithm,
decodes the best individual, applies the paper's post-processing, and returns a
:class:`PlanResult` validated by the exact segment rule. Pruned-path scoring keeps the
problem's own fitness (``_planner_program`` says why). Grid-graph planners
(``aco``) and cell-sequence GAs are dispatched here as well.
"""
from __future__ import annotations

import time

import numpy as np

from ..errors import InfeasibleQueryError, ParameterError, UnknownAlgorithmError
from ..papers import LENGTH, PAPERS
from ..formulations.encodings import ColumnNodes, FreeWaypoints, GeneralPath, SplinePath
from ..formulations.problem import PathProblem
from ..formulations.pruned import PrunedColumnFitness, check_fitness_on
from ..world.postprocess import key_points, prune_direct, remove_collinear
from .archive import ARCHIVE_EVERY, archive_alternatives
from .result import check_alternatives, make_plan_result

# derived from the one table of paper methods (optplan/papers.py)
PAPER_OF = {a: p.key for p in PAPERS.values() for a in p.algorithms}
POSTPROCESS = {**{k: p.postprocess for k, p in PAPERS.items()}, LENGTH.key: LENGTH.postprocess}
GRAPH_PLANNERS = ("aco", "iaco", "ga", "iga")  # grid-graph / cell-sequence planners of their own
# the path model a paper's planners use on grid maps when no encoding is given
# (yang2023: a cubic spline through free points, eq 1-4, §2.2, also in §7.3)
GRID_ENCODING = {k: p.grid_encoding for k, p in PAPERS.items() if p.grid_encoding != "columns"}
ENCODINGS = ("columns", "waypoints", "spline", "general")
# what a metaheuristic plans with when no encoding is given: the general encoding, the best
# measured (benchmarks/general_planning.py --part defaults); "paper" names each paper's own
# (GRID_ENCODING on grids, spline handles on circle worlds), as optplan reproduce uses it
DEFAULT_ENCODING = "general"
PAPER_ENCODING = "paper"


def algorithm_names() -> list[str]:
    """Global path planners available through ``op.plan``."""
    return sorted(set(_metaheuristic_names()) | set(GRAPH_PLANNERS))


def _metaheuristic_names() -> list[str]:
    from . import metaheuristics

    fn = getattr(metaheuristics, "algorithm_names", None)
    return list(fn()) if fn is not None else []


def make_problem(world, start, goal, *, preset: str, encoding: str | None = None, clearance: float = 0.0,
                 constraint: str | None = None, waypoints: int = 3, samples: int = 100) -> PathProblem:
    """The default formulation: column nodes on grids, spline handles on circle worlds."""
    s, g = np.asarray(start, float), np.asarray(goal, float)
    if encoding is None:
        encoding = "columns" if world.is_grid else "spline"
    if encoding == "columns":
        enc = ColumnNodes(world, s, g)
    elif encoding == "waypoints":
        enc = FreeWaypoints(world, s, g, m=waypoints)
    elif encoding == "spline":
        enc = SplinePath(world, s, g, m=waypoints, samples=samples)
    elif encoding == "general":
        enc = GeneralPath(world, s, g, m=waypoints, clearance=clearance)
    else:
        raise ParameterError(f"encoding must be one of {', '.join(ENCODINGS)}, got {encoding!r}")
    return PathProblem(enc, preset, clearance=clearance, constraint=constraint)


def postprocess_path(world, path: np.ndarray, mode: str, clearance: float = 0.0) -> np.ndarray:
    """``none``, ``collinear`` (li2023 §4.4 step 1), ``keypoints`` (li2023 §4.4) or
    ``prune`` (chen2025 §4.3.1)."""
    if mode == "none":
        return path
    if mode == "collinear":
        return remove_collinear(path)
    if mode == "keypoints":
        return key_points(world, path, clearance)
    if mode == "prune":
        return prune_direct(world, path, clearance)
    raise ParameterError(f"postprocess must be none, collinear, keypoints or prune; got {mode!r}")


def plan_path(world, start, goal, *, algorithm: str, seed=0, pop: int = 30, iters: int = 500,
              clearance: float = 0.0, preset: str | None = None, encoding: str | None = None,
              constraint: str | None = "feasibility", postprocess: str | None = None, max_evals: int | None = None,
              waypoints: int = 3, init: str | None = "auto", alternatives: int = 0,
              alternative_separation: float | None = None, fitness_on: str = "nodes", **params):
    """Plan with a metaheuristic (or ACO / the path GAs) and return a validated PlanResult.

    ``preset`` defaults to the algorithm's paper (:data:`PAPER_OF`). ``constraint``
    defaults to the feasibility rule (feasible beats infeasible, then less
    violation, then the paper's cost), which finds feasible paths far more often
    than the papers' penalties on our maps; ``constraint="penalty"`` gives the
    paper's penalised fitness exactly (the program's clearance constraint carries the
    paper's penalty weights, :meth:`~optplan.terms.Constraint.penalised`).

    ``encoding`` defaults to ``"general"`` (:class:`GeneralPath`: ``waypoints`` via points
    joined by geodesic roadmap legs), which represents every path class on every map and was
    the best measured (:data:`DEFAULT_ENCODING`). ``"paper"`` is the paper's own: one node per
    column on grids (spline handles for the yang2023 planners ``pso``/``ipso``,
    :data:`GRID_ENCODING`) and spline handles on circle worlds. ``ga``/``iga`` also take
    ``"cells"`` on grids: li2023's own chromosome, a general cell sequence
    (:mod:`optplan.solvers.gridpath.cell_ga`), and ``"paper"`` gives them li2023's chromosome
    (one cell per column, or the cell sequence where that cannot represent a solution). By
    default ``ga`` is a vector GA over the general encoding and ``iga`` runs li2023's GA loop
    (eq 4-5, §4.1-4.5) on the general encoding's via points
    (:mod:`optplan.solvers.gridpath.via_ga`). When the paper's encoding (``"paper"``) cannot
    represent a solution — no collision-free path with one node per column exists, or the
    paper encoding's best path is infeasible — the run is done again with the general encoding (same budget) and the result says so (``encoding``,
    ``message``); an explicitly requested encoding is never replaced. Under ``max_evals``
    (a hard cap on evaluations) an infeasible result is not re-planned; its message
    names the general encoding instead.

    ``init``: ``"feasible"`` starts from collision-free random paths (column nodes;
    it stands in for the papers' obstacle-free decoders and gives every algorithm the
    same start) or, with the general encoding, from one random corridor per individual
    (:meth:`GeneralPath.sample_corridors`), ``"own"`` uses the algorithm's initialiser
    (e.g. MISSA's chaotic map), ``"auto"`` (default) is ``"feasible"`` for column nodes
    and the general encoding and ``"own"`` otherwise.

    ``fitness_on``: ``"nodes"`` (default) scores the raw column-node path; ``"pruned"``
    scores the path after the direct-connection test, the order of chen2025 §4.3.1 (nodes,
    pruning, then eq 32) and the papers' protocol (:mod:`optplan.formulations.pruned`); the
    returned path is then the pruned path that was scored. Column nodes only.

    ``alternatives``: also return up to that many other valid paths of the run's
    population (snapshots every :data:`ARCHIVE_EVERY` iterations and the final one,
    best first by fitness) in ``result.alternatives``, each leaving the
    ``alternative_separation``-metre band (default: the casadi refinement's tube
    radius) around the best path and the earlier ones. No extra evaluations; the
    best path is unchanged; the decoding time is part of ``runtime_s``. ACO returns none.
    """
    name = algorithm.lower()
    alternatives, alternative_separation = check_alternatives(alternatives, alternative_separation)
    if name in ("ga", "iga") and encoding is None:
        encoding = DEFAULT_ENCODING   # as every metaheuristic: ga as a vector GA, iga's loop on via points
    if name in ("ga", "iga") and encoding == PAPER_ENCODING:
        encoding = None   # li2023's GAs on their own chromosome
    if name == "iga" and encoding == "general":
        from .gridpath.via_ga import plan_via_ga

        return plan_via_ga(world, start, goal, improved=True, seed=seed, pop=pop, iters=iters, clearance=clearance,
                           preset=preset or "li2023", postprocess=postprocess, max_evals=max_evals,
                           waypoints=waypoints, alternatives=alternatives,
                           alternative_separation=alternative_separation, **params)
    s = world.check_query_point(start, "start", clearance)
    g = world.check_query_point(goal, "goal", clearance)
    if name in ("aco", "iaco"):  # an ant colony keeps pheromone, not a population of paths: no alternatives
        from .gridpath.aco import plan_aco
        from .gridpath.iaco import plan_iaco

        colony = plan_aco if name == "aco" else plan_iaco
        t0 = time.perf_counter()
        result = colony(world, s, g, seed=seed, pop=pop, iters=iters, clearance=clearance, max_evals=max_evals,
                        **params)
        if postprocess in (None, "none") or not result.feasible:
            return result
        # the ants' 8-connected cell path, post-processed like a metaheuristic's (e.g. hou2024's
        # MISSA path is pruned; judging ACO raw against it compares representations, not searches)
        path = postprocess_path(world, result.path, postprocess, clearance)
        return make_plan_result(world, path, name, time.perf_counter() - t0, clearance=clearance,
                                history=result.history, seed=result.seed, nfev=result.nfev,
                                message="; ".join(m for m in (result.message, f"postprocess={postprocess}") if m))
    if name in ("ga", "iga") and world.is_grid and encoding is None and not _columns_represent(world, s, g, clearance):
        # one cell per column cannot hold a path here (it must turn back in x): li2023's own
        # chromosome, a general cell sequence, can, as the metaheuristics fall back to 'general'
        from .gridpath.cell_ga import plan_cell_ga

        result = plan_cell_ga(world, s, g, improved=name == "iga", seed=seed, pop=pop, iters=iters,
                              clearance=clearance, preset=preset or "li2023", postprocess=postprocess,
                              max_evals=max_evals, alternatives=alternatives,
                              alternative_separation=alternative_separation, **params)
        result.encoding = "cells"
        result.message = "; ".join(m for m in (
            "no collision-free path with one cell per column exists between start and goal: planned with "
            "encoding='cells' (li2023's general cell sequence) instead", result.message) if m)
        return result
    if name in ("ga", "iga") and world.is_grid and encoding in (None, "columns"):
        from .gridpath.ga_path import plan_ga

        try:
            return plan_ga(world, s, g, improved=name == "iga", seed=seed, pop=pop, iters=iters, clearance=clearance,
                           preset=preset or "li2023", postprocess=postprocess, max_evals=max_evals,
                           alternatives=alternatives, alternative_separation=alternative_separation, **params)
        except InfeasibleQueryError as exc:
            if "one node per column" not in str(exc):
                raise
            raise InfeasibleQueryError(f"no collision-free path with one cell per column exists between start and "
                                       f"goal, so encoding='columns' cannot represent a solution; use "
                                       f"encoding='cells' (li2023's general cell sequence), which {name} takes, or "
                                       f"leave encoding unset to fall back to it") from None
    if name in ("ga", "iga") and encoding == "cells":
        from .gridpath.cell_ga import plan_cell_ga

        return plan_cell_ga(world, s, g, improved=name == "iga", seed=seed, pop=pop, iters=iters, clearance=clearance,
                            preset=preset or "li2023", postprocess=postprocess, max_evals=max_evals,
                            alternatives=alternatives, alternative_separation=alternative_separation, **params)
    from . import metaheuristics

    if name == "iga" and encoding is not None:
        raise ParameterError(f"iga evolves li2023's grid chromosomes or the general encoding's via points: "
                             f"encoding='general' (the default), 'paper' / 'columns' (one cell per column) or "
                             f"'cells' (the paper's general cell sequence), not encoding={encoding!r}. Use 'ga' "
                             "(the vector GA) for other encodings")
    if name not in _metaheuristic_names():
        raise UnknownAlgorithmError(f"unknown path planner {algorithm!r}; known: {', '.join(algorithm_names())}")
    paper = PAPER_OF.get(name, "length")
    preset = preset or paper
    t0 = time.perf_counter()
    # the paper's own encoding may be replaced by the general one when it cannot represent a
    # solution; an encoding named explicitly is never replaced
    chosen = encoding not in (None, PAPER_ENCODING)
    if encoding is None:
        encoding = DEFAULT_ENCODING
    elif encoding == PAPER_ENCODING:
        encoding = GRID_ENCODING.get(paper, "columns") if world.is_grid else "spline"
    if encoding not in ENCODINGS:
        raise ParameterError(f"encoding must be one of {', '.join((*ENCODINGS, PAPER_ENCODING))}, got {encoding!r}")
    note = ""
    if world.is_grid and encoding != "general":
        from ..formulations.presets import get_preset, uses_penetration
        from ..world.fields import check_field_memory

        fitness = get_preset(preset)
        if uses_penetration(fitness.with_constraint(constraint) if constraint is not None else fitness):
            check_field_memory(world)   # before any work: the sampler and the segment store come first
    if encoding == "columns" and not chosen and not _columns_represent(world, s, g, clearance):
        encoding = "general"
        note = ("no collision-free path with one node per column exists between start and goal: planned with "
                "encoding='general' instead")
    problem = make_problem(world, s, g, preset=preset, encoding=encoding, clearance=clearance,
                           constraint=constraint, waypoints=waypoints)
    if problem.encoding.dim == 0:
        path = np.stack([s, g])
        return make_plan_result(world, path, name, time.perf_counter() - t0, clearance=clearance,
                                seed=seed if isinstance(seed, int) else None, message="start and goal in adjacent columns")
    bounds = np.stack([problem.lower, problem.upper], axis=1)
    repair = getattr(problem.encoding, "repair", None)
    pruned = None
    if check_fitness_on(fitness_on) == "pruned":
        if alternatives:
            raise ParameterError("fitness_on='pruned' does not offer alternatives (refine a pruned path with "
                                 "refine_options={'starts': 1})")
        pruned = PrunedColumnFitness(problem)
    if init == "auto":
        init = "feasible" if isinstance(problem.encoding, (ColumnNodes, GeneralPath)) else "own"
    init_mode = init
    if init == "feasible":
        if isinstance(problem.encoding, GeneralPath):
            init = problem.encoding.sample_corridors
        elif not isinstance(problem.encoding, ColumnNodes):
            raise ParameterError("init='feasible' needs the column-node or the general encoding")
        else:
            init = lambda n, rng: problem.encoding.sample_feasible(n, rng, clearance)  # noqa: E731
    elif init == "own":
        init = None
    else:
        raise ParameterError(f"init must be 'auto', 'feasible' or 'own', got {init!r}")
    scored = pruned if pruned is not None else problem
    program = _planner_program(problem, preset, pruned, init_mode, params)
    if program is not None:
        # the paper's program, solved through the program solver contract; the planner's
        # fitness (segment or leg tables) is its checked acceleration, so the numbers are the
        # tables' exactly, and penalty mode is the program's paper penalty
        from .programs.swarm import SwarmSolver

        opt = SwarmSolver(name).search(program, pop=pop, iters=iters, seed=seed, max_evals=max_evals,
                                       constraint=problem.preset.constraint,
                                       start="variables" if init_mode == "feasible" else "algorithm",
                                       archive_every=ARCHIVE_EVERY if alternatives else None, **params)
    else:
        opt = metaheuristics.optimize(scored.evaluate if problem.preset.constraint == "feasibility" else
                                      scored.objective, bounds, algorithm=name, pop=pop, iters=iters, seed=seed,
                                      max_evals=max_evals, repair=repair, init=init,
                                      archive_every=ARCHIVE_EVERY if alternatives else None, **params)
    if pruned is not None:  # the path that was scored; further post-processing only on request
        raw, mode = pruned.path(opt.x), postprocess or "none"
    else:
        raw = problem.encoding.waypoints(opt.x)
        mode = postprocess or POSTPROCESS.get(preset if isinstance(preset, str) else "length", "collinear")
    path = postprocess_path(world, raw, mode, clearance)
    others = []
    if alternatives:
        X, _, V = opt.archive
        others = archive_alternatives(world, X, V, problem.encoding,
                                      lambda raw: postprocess_path(world, raw, mode, clearance), opt.x, path,
                                      alternatives, alternative_separation, clearance)
    result = make_plan_result(world, path, name, time.perf_counter() - t0, clearance=clearance, history=opt.history,
                              seed=seed if isinstance(seed, int) else None, nfev=opt.nfev,
                              message=opt.message)
    result.alternatives = others
    result.encoding = encoding
    if note:
        result.message = "; ".join(m for m in (note, result.message) if m)
    if not result.feasible and not chosen and encoding != "general" and max_evals is not None:
        result.message = "; ".join(m for m in (result.message, f"encoding={encoding!r} found no collision-free path "
                                   "within max_evals; encoding='general' represents every path class") if m)
    elif not result.feasible and not chosen and encoding != "general":
        # the paper's encoding found no collision-free path: plan again where every class is
        # representable (only under an iteration budget: max_evals is a hard cap on evaluations)
        again = plan_path(world, s, g, algorithm=name, seed=seed, pop=pop, iters=iters, clearance=clearance,
                          preset=preset, encoding="general", constraint=constraint, postprocess=postprocess,
                          max_evals=max_evals, waypoints=waypoints, init="auto", alternatives=alternatives,
                          alternative_separation=alternative_separation, **params)
        again.message = "; ".join(m for m in (f"encoding={encoding!r} gave an infeasible path "
                                             f"({result.message or 'collision'}): planned again with "
                                             "encoding='general'", again.message) if m)
        again.nfev += result.nfev
        again.runtime_s += result.runtime_s
        return again
    return result


# optimize keywords a program solver does not take as options: such a run calls optimize directly
_ENGINE_ONLY = ("seeds", "dim")


def _planner_program(problem, preset, pruned, init_mode: str, params):
    """The paper program the run optimises (:func:`planner_program`), or ``None`` where the
    planner's fitness is not a program: pruned-path scoring (its path has as many vertices
    as the pruning keeps, and its violation counts the blocked cells a kept segment passes,
    chen2025's O, not the clearance constraint's colliding segments), a preset given as an
    object, or engine-only keywords (several seeds in one call, ``dim``)."""
    if pruned is not None or init_mode not in ("feasible", "own") or any(k in params for k in _ENGINE_ONLY):
        return None
    from ..formulations.paper_programs import planner_program

    return planner_program(problem, preset)


def _columns_represent(world, s, g, clearance: float) -> bool:
    """Whether some collision-free path with one node per column joins start and goal."""
    enc = ColumnNodes(world, s, g)
    if enc.dim == 0:
        return bool(world.segments_free(s[None], g[None], clearance)[0])
    from ..formulations.segment_store import column_segments

    # decided on demand (the full tables, feasible_transitions, took 70 s and 9 GB on 256x256)
    return bool(column_segments(enc, clearance).first_moves().any())
