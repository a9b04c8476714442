"""Local planners: the dynamic window approach and the papers' variants (DESIGN.md layer 4).

``make_local_planner(name, robot, dt, **params)`` builds one of ``algorithm_names()``;
the closed loop calls ``reset(state, global_path)`` once and ``command(ctx)`` every
control period (see ``optplan.local.base``).

Modules: ``base`` (the contract with the closed loop, capabilities), ``window`` (dynamic
window, admissibility), ``rollout`` (all samples x horizon at once), ``critics`` (one cost
term per class), ``hooks`` (the contract between the core and its mechanisms),
``mechanisms`` (adaptive velocity, velocity obstacles, brake-and-wait, initial heading),
``sweep_gate`` (qp-dwa's sweep gate), ``dwa`` (the planner core), ``presets`` (the papers'
planners as data), ``qp_dwa`` (QP refinement + Ruckig), ``reference`` (a loop-based
textbook DWA for checking and benchmarking).
"""
from __future__ import annotations

from typing import Any

from ..errors import ParameterError, UnknownAlgorithmError
from ..world.robot import RobotSpec
from .base import LocalContext, LocalPlanner
from .dwa import DWAPlanner, Preset, Term
from .presets import PRESETS

__all__ = ["make_local_planner", "algorithm_names", "LocalContext", "LocalPlanner", "DWAPlanner", "Preset",
           "Term", "PRESETS"]


# solvers of a window program (optplan.formulations.local_program) other than the presets
PROGRAM_SOLVERS = ("mpc",)


def algorithm_names() -> list[str]:
    """Names of the local planners."""
    return [*PRESETS, *PROGRAM_SOLVERS]


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
        from ..formulations.local_program import named_local_program

        program = named_local_program(program, robot, dt)
    if key == "mpc":
        from .program_planners import MPCPlanner

        return _built(MPCPlanner, key, robot, dt, program=program, **params)
    if program is not None:
        from .program_planners import ProgramQPDWA, ProgramSampler

        solvers = {"dwa": ProgramSampler, "qp-dwa": ProgramQPDWA}
        if key not in solvers:
            raise ParameterError(f"local_program= is solved by 'dwa' (sampling), 'qp-dwa' (sampling + QP polish) "
                                 f"and 'mpc' (NMPC); {name!r} runs its own critics (a paper preset as a window "
                                 "program is not built yet)")
        return _built(solvers[key], key, robot, dt, program=program, **params)
    preset = PRESETS.get(key)
    if preset is None:
        raise UnknownAlgorithmError(f"unknown local planner {name!r}; choose one of {', '.join(algorithm_names())}")
    if preset.refine == "qp":
        from .qp_dwa import QPDWAPlanner

        return QPDWAPlanner(preset, robot, dt, **params)
    return DWAPlanner(preset, robot, dt, **params)


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
