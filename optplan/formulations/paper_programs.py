"""Each paper's path fitness as a program, and the smoothing energy as one.

The weights come from the fitness presets (:mod:`optplan.formulations.presets`,
one table, cited there); here they become objective terms, and the papers'
obstacle handling becomes the constraint ``clearance >= c`` (solved with the
feasibility rule by default; a swarm's ``constraint="penalty"`` gives the
penalised form).
"""
from __future__ import annotations

from ..checks import number
from ..errors import UnknownAlgorithmError
from ..world.queries import check_world
from ..papers import method_of
from . import expressions as T
from .presets import PRESETS, collision_penalty_on, get_preset
from .program import PathProgram
from .variables import BSpline, ColumnNodes, Points, Variables

# the variables each paper plans with on grids (circle worlds: always the spline), from
# the table of paper methods (optplan/papers.py)
GRID_VARIABLES = {"columns": ColumnNodes, "spline": lambda: BSpline(ctrl=3, samples=100)}
PAPER_VARIABLES = {k: GRID_VARIABLES[method_of(k).grid_encoding] for k in PRESETS}


def fitness_expression(preset) -> T.Expr:
    """The weighted terms of a fitness preset as one objective expression."""
    p = get_preset(preset)
    expr = p.length * T.length()
    if p.turn_angle:
        expr = expr + p.turn_angle * T.turn_angles().sum()
    if p.turn_count:
        expr = expr + p.turn_count * T.turn_count()
    if p.turn_cost:
        expr = expr + p.turn_cost * T.turn_cost()
    return expr


def paper_program(name: str, world, start, goal, variables: Variables | None = None,
                  clearance: float = 0.0, program_class=PathProgram, paper_penalty: bool = False,
                  per_segment: int | None = None) -> PathProgram:
    """The path fitness of paper ``name`` (``hou2024``, ``yang2023``, ``yuan2021``,
    ``yuan2021-smooth``, ``li2023``, ``chen2025`` or ``length``) as a program: its weighted
    terms minimised subject to ``clearance() >= clearance`` (the exact collision rule).

    ``variables`` defaults to the paper's encoding (column nodes on grids; a cubic
    B-spline for yang2023 and on circle worlds). ``paper_penalty=True`` attaches the
    paper's penalty weights to the clearance constraint (:meth:`Constraint.penalised`), so
    a swarm solving it with ``constraint="penalty"`` minimises the paper's penalised
    fitness; ``per_segment`` is the clearance term's samples per segment (also those of the
    penetration integral in its violation and penalty)."""
    if not isinstance(name, str) or name not in PRESETS:
        raise UnknownAlgorithmError(f"unknown paper program {name!r}; known: {', '.join(sorted(PRESETS))}")
    check_world(world)
    clearance = number(minimum=0.0)("clearance", clearance)
    if variables is None:
        on_grid = world.is_grid
        variables = PAPER_VARIABLES.get(name, ColumnNodes)() if on_grid else BSpline(ctrl=3, samples=100)
    prog = program_class(world, start, goal, variables=variables, name=name)
    prog.minimize(fitness_expression(name))
    con = T.clearance(per_segment) >= float(clearance)
    if paper_penalty:
        p = get_preset(name)
        con = con.penalised(collision_penalty_on(p, world, prog.goal), p.penetration_penalty)
    prog.subject_to(con)
    return prog


def smoothing_energy(w_smooth: float = 0.5) -> T.Expr:
    """The refinement's energy ``sum |dp|^2 + w_smooth * sum |d2p|^2`` as one expression: the
    objective of :func:`smoothing_program`, and the energy the CasADi smoother
    (:func:`optplan.solvers.nlp.smooth_path`) minimises (it reads this expression's
    symbolic view)."""
    return T.squared_length() + float(w_smooth) * T.bending()


def smoothing_program(world, start, goal, n: int = 50, w_smooth: float = 0.5, clearance: float = 0.0,
                      program_class=PathProgram) -> PathProgram:
    """The refinement's energy (:func:`smoothing_energy`) over ``n`` dense points, subject
    to ``clearance() >= clearance``: quadratic, so IPOPT, SLSQP, OSQP and cvxpy all take it."""
    w_smooth = number(minimum=0.0)("w_smooth", w_smooth)
    clearance = number(minimum=0.0)("clearance", clearance)
    prog = program_class(world, start, goal, variables=Points(n), name=f"smoothing(n={n}, w={w_smooth:g})")
    prog.minimize(smoothing_energy(w_smooth))
    prog.subject_to(T.clearance() >= float(clearance))
    return prog


def li2023_cell_program(world, start, goal, via: int = 4, clearance: float = 0.0,
                        program_class=PathProgram) -> PathProgram:
    """li2023's fitness (eq 2, constraint eq 3) over li2023's own representation, a general
    sequence of 8-adjacent grid cells (:class:`~optplan.formulations.variables.CellSequence`
    through ``via`` free via cells), which may visit a column several times (li2023's
    example M1); the spec ``li2023_cells`` runs it (``optplan reproduce li2023 --part cells``)."""
    from .variables import CellSequence

    return paper_program("li2023", world, start, goal, variables=CellSequence(via), clearance=clearance,
                         program_class=program_class)


def planner_variables(encoding) -> Variables | None:
    """The program variables that decode like a planner's encoding (same bounds, same
    paths), or ``None`` for an encoding without a variable twin."""
    from . import encodings as E
    from .variables import GeneralVias, SplineThrough, Waypoints

    if isinstance(encoding, E.ColumnNodes):
        return ColumnNodes() if encoding.snap else None
    if isinstance(encoding, E.SplinePath):
        return SplineThrough(encoding.m, encoding.samples)
    if isinstance(encoding, E.FreeWaypoints):
        return Waypoints(encoding.m)
    if isinstance(encoding, E.GeneralPath):
        return GeneralVias(encoding.m, encoding.clearance, corridor_start=True)
    return None


def planner_program(problem, preset, program_class=PathProgram) -> PathProgram | None:
    """The paper program a planner optimises, with the planner's fitness (``problem``, a
    :class:`~optplan.formulations.problem.PathProblem`: the column nodes' segment tables,
    the general encoding's leg tables) as its checked acceleration
    (:meth:`PathProgram.accelerate`): the swarm evaluates ``problem``, verified to give the
    program's own cost and violation and, in penalty mode, the paper's penalised fitness
    (the program's clearance constraint carries the paper's penalty weights). ``None``
    where the planner's fitness is not such a program: a preset given as an object, an
    encoding without a variable twin, or no free variable."""
    from . import encodings as E
    from .problem import PathProblem

    enc = problem.encoding
    variables = planner_variables(enc)
    if not (isinstance(preset, str) and preset in PRESETS and variables is not None and enc.dim):
        return None
    penalty = problem.preset.constraint == "penalty"
    prog = paper_program(preset, enc.world, enc.start, enc.goal, variables=variables, clearance=problem.clearance,
                         program_class=program_class, paper_penalty=penalty,
                         per_segment=None if enc.penetration_samples == 8 else enc.penetration_samples)
    if not penalty:
        return prog.accelerate(problem.evaluate, name=_acceleration_name(enc))
    # penalty mode: the problem's first output is the penalised fitness; its feasibility twin
    # (same tables) serves the program's (cost, violation)
    twin = PathProblem(enc, problem.preset, clearance=problem.clearance, constraint="feasibility")
    return prog.accelerate(twin.evaluate, name=_acceleration_name(enc), penalised=problem.objective)


def _acceleration_name(enc) -> str:
    from . import encodings as E

    if isinstance(enc, E.ColumnNodes):
        return "column segment tables"
    if isinstance(enc, E.GeneralPath):
        return "roadmap leg tables"
    return f"{type(enc).__name__} fitness"
