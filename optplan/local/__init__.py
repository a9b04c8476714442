"""Local planners: the dynamic window approach and the papers' variants (DESIGN.md layer 4).

``make_local_planner(name, robot, dt, **params)`` builds one of ``algorithm_names()``;
the closed loop calls ``reset(state, global_path)`` once and ``command(ctx)`` every
control period (see ``optplan.local.base``).

Modules: ``base`` (the contract with the closed loop, capabilities), ``window`` (dynamic
window, admissibility), ``rollout`` (all samples x horizon at once), ``critics`` (one cost
term per class), ``hooks`` (the contract between the core and its mechanisms),
``mechanisms`` (adaptive velocity, velocity obstacles, brake-and-wait, initial heading),
``sweep_gate`` (qp-dwa's sweep gate), ``dwa`` (the planner core), ``presets`` (the papers'
planners as data), ``preset_programs`` (those presets as window programs), ``qp_dwa`` (QP refinement + Ruckig), ``reference`` (a loop-based
textbook DWA for checking and benchmarking).
"""
from __future__ import annotations

from typing import Any

from ..errors import ParameterError, UnknownAlgorithmError
from ..world.robot import RobotSpec
from .base import LocalContext, LocalPlanner
from .dwa import DWAPlanner, Preset, Term
from .preset_programs import PresetProgram
from .presets import PRESETS

__all__ = ["make_local_planner", "algorithm_names", "local_program", "LocalContext", "LocalPlanner", "DWAPlanner",
           "Preset", "Term", "PRESETS"]


# solvers of a window program (optplan.formulations.local_program) other than the presets
PROGRAM_SOLVERS = ("mpc",)
# baselines that are no DWA: the global path driven blind (optplan/local/follow.py)
BASELINES = ("follow",)


def algorithm_names() -> list[str]:
    """Names of the local planners."""
    return [*PRESETS, *PROGRAM_SOLVERS, *BASELINES]


def make_local_planner(name: str, robot: RobotSpec, dt: float, **params: Any) -> LocalPlanner:
    """Build the local planner ``name`` for ``robot`` with control period ``dt`` (s).

    ``params`` override the planner's options (``n_v``, ``n_w``, ``horizon``, ...), its term
    weights (``weights={...}``) or a term's / mechanism's parameters (see ``DWAPlanner``).

    Raises:
        UnknownAlgorithmError: ``name`` is not a local planner.
        ParameterError: a parameter is unknown or out of range.
    """
    key = str(name).lower()
    program = params.pop("local_program", None)
    if program is not None:
        # a preset named as the program takes the parameters (they are the preset's)
        takes = isinstance(program, str) and program.lower() in PRESETS and program.lower() not in _named_programs()
        program = local_program(program, robot, dt, **(params if takes else {}))
        params = {} if takes else params
    if isinstance(program, PresetProgram):
        return _preset_solver(key, program, robot, dt, params)
    if key in BASELINES:
        if program is not None:
            raise ParameterError(f"{name!r} follows the global path and solves no window program")
        from .follow import PathFollower

        return _built(PathFollower, key, robot, dt, **params)
    if key == "mpc":
        from .program_planners import MPCPlanner

        return _built(MPCPlanner, key, robot, dt, program=program, **params)
    if program is not None:
        from .program_planners import ProgramQPDWA, ProgramSampler

        solvers = {"dwa": ProgramSampler, "qp-dwa": ProgramQPDWA}
        if key not in solvers:
            raise ParameterError(f"local_program= is solved by 'dwa' (sampling), 'qp-dwa' (sampling + QP polish) "
                                 f"and 'mpc' (NMPC); {name!r} is a paper preset: its own program is "
                                 f"local_program={name!r}")
        return _built(solvers[key], key, robot, dt, program=program, **params)
    preset = PRESETS.get(key)
    if preset is None:
        raise UnknownAlgorithmError(f"unknown local planner {name!r}; choose one of {', '.join(algorithm_names())}")
    if preset.refine == "qp":
        from .qp_dwa import QPDWAPlanner

        return QPDWAPlanner(preset, robot, dt, **params)
    return DWAPlanner(preset, robot, dt, **params)


def local_program(name: "str | LocalProgram", robot: RobotSpec, dt: float, **params: Any) -> "LocalProgram":
    """A named window program built for ``robot`` and control period ``dt`` (s): ``"default"``
    (what ``mpc`` solves unless given one), or a paper preset's (``"dwa"``, ``"idwa"``,
    ``"missa-dwa"``, ... :data:`PRESETS`, a :class:`~optplan.local.preset_programs.PresetProgram`;
    ``params``: the preset's parameters, as for ``make_local_planner``). A
    :class:`~optplan.formulations.local_program.LocalProgram` is returned as it is.

    Raises:
        ParameterError: an unknown name, or parameters given to a program that takes none.
    """
    from ..formulations.local_program import LocalProgram, named_local_program

    if isinstance(name, LocalProgram):
        if params:
            raise ParameterError(f"parameters {sorted(params)} are for a named program, not an op.LocalProgram")
        return name
    if isinstance(name, str) and name.lower() in PRESETS and name.lower() not in _named_programs():
        return make_local_planner(name.lower(), robot, dt, **params).program
    if params:
        raise ParameterError(f"the local program {name!r} takes no parameters, got {sorted(params)}")
    try:
        return named_local_program(name, robot, dt)
    except ParameterError as e:
        raise ParameterError(f"{e}; the papers' presets are named programs too: {', '.join(PRESETS)}") from None


def _named_programs() -> dict:
    from ..formulations.local_program import LOCAL_PROGRAMS

    return LOCAL_PROGRAMS


def _preset_solver(key: str, program: PresetProgram, robot: RobotSpec, dt: float, params: dict) -> LocalPlanner:
    """The solver ``key`` of a preset's program: ``dwa`` samples it (the preset's own planner,
    with the program's added terms), ``qp-dwa`` samples and polishes ``qp-dwa``'s program."""
    if params:
        raise ParameterError(f"parameters {sorted(params)} go into the program: op.local_program({program.name!r}, "
                             f"robot, dt, **params)")
    preset = program.preset
    if key == "dwa" or (key == preset.name and preset.refine is None):   # the preset samples its own program
        return DWAPlanner(preset, robot, dt, program=program, **program.params)
    if key in ("qp-dwa", preset.name) and preset.refine == "qp":
        from .qp_dwa import QPDWAPlanner

        return QPDWAPlanner(preset, robot, dt, program=program, **program.params)
    if key == "mpc":
        raise ParameterError(f"mpc needs a symbolic view of every term; the critics of {program.name!r} "
                             f"({', '.join(t.name for _, t in program.objective)}) are scaled over each step's "
                             "samples and have none: sample it with 'dwa', or write the objective with "
                             "optplan.local_terms for mpc")
    raise ParameterError(f"the program {program.name!r} (a paper preset) is solved by 'dwa' (sampling)"
                         + (" and 'qp-dwa' (its QP polish)" if preset.refine == "qp" else "")
                         + f", not by {key!r}")


def _built(cls, name: str, robot: RobotSpec, dt: float, **params: Any):
    """``cls(robot, dt, **params)``, an unknown parameter named with the known ones."""
    import inspect

    from ..errors import named_with_hints

    known = [p for p in inspect.signature(cls).parameters if p not in ("robot", "dt")]
    unknown = sorted(set(params) - set(known))
    if unknown:
        raise ParameterError(f"unknown parameter {named_with_hints(unknown, known)} for local planner {name!r}; "
                             f"known: {', '.join(known)}")
    return cls(robot, dt, **params)
