"""The ``program`` run kind: which program a spec names, which solvers it runs, and how a run
builds its program.

A spec names its program (``program:``) in one of three ways:

* ``smoothing``: ``op.smoothing_program(world, start, goal, **args)`` (args ``n``,
  ``w_smooth``, ``clearance``);
* a paper program (``hou2024``, ``yang2023``, ``yuan2021``, ``yuan2021-smooth``, ``li2023``,
  ``chen2025``, ``length``): ``op.paper_program(name, world, start, goal, **args)`` (arg
  ``clearance``);
* ``module:function``: a function of an importable module, called as
  ``function(world, start, goal, **args)`` and returning an ``op.PathProgram``.

Importing a module runs its code. Only module *names* are accepted (dotted Python
identifiers, imported with :func:`importlib.import_module` from ``sys.path``): never a file
path, so a spec can only run code that is already installed or on ``PYTHONPATH``.

Solvers are program solver names (``op.PathProgram`` solvers: every metaheuristic, ``ipopt``,
``slsqp``, ``osqp``, ``cvxpy``) or chains (lists of names). Everything here is checked when
the spec is loaded, so a typo is one line before any run starts.
"""
from __future__ import annotations

import importlib
import inspect
import json
import re
from functools import partial
from pathlib import Path
from typing import Any, Callable, Mapping

from ..errors import ParameterError, UnknownAlgorithmError, named_with_hints

SMOOTHING = "smoothing"
# the arguments a spec may give the built-in programs (the rest of their parameters are objects)
SMOOTHING_ARGS = ("n", "w_smooth", "clearance")
PAPER_ARGS = ("clearance",)
CHAIN_SEPARATOR = ">"   # how a chain is written in a record's algorithm and in labels: "pso>ipopt"
_DOTTED = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*\Z")


def paper_program_names() -> list[str]:
    """Names of the paper programs (the fitness presets)."""
    from ..formulations.presets import PRESETS

    return sorted(PRESETS)


def is_user_program(name: str) -> bool:
    """Whether ``name`` is a ``module:function`` reference (not a built-in program)."""
    return ":" in name


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return f"{type(exc).__name__}: {text.splitlines()[0]}" if text else type(exc).__name__


# source hash of each module imported for a program when it was (re)loaded
_LOADED: dict[str, str] = {}


def _source_hash(module) -> str | None:
    origin = getattr(module, "__file__", None)
    if not origin or not Path(origin).is_file():
        return None
    import hashlib

    return hashlib.sha256(Path(origin).read_bytes()).hexdigest()


def _import_current(module: str):
    """Import ``module``; if it was imported before and its source file has changed since,
    reload it, so a run computes with the code its key was made from (a long-lived process
    such as a notebook calling ``run_experiment`` again after an edit)."""
    import sys

    mod = importlib.import_module(module)
    now = _source_hash(mod)
    before = _LOADED.get(module)
    if before is not None and now is not None and now != before and sys.modules.get(module) is mod:
        mod = importlib.reload(mod)
    if now is not None:
        _LOADED[module] = now
    return mod


def _user_function(name: str, where: str) -> Callable:
    module, _, attr = name.partition(":")
    if not _DOTTED.match(module) or not _DOTTED.match(attr):
        raise ParameterError(f"{where}: program {name!r} must be 'module:function' with a module name importable "
                             f"from sys.path (dotted names such as mypkg.programs:corridor; file paths are not "
                             f"accepted)")
    try:
        obj: Any = _import_current(module)
    except ImportError as exc:
        raise ParameterError(f"{where}: cannot import module {module!r} of program {name!r} ({_first_line(exc)}); "
                             f"it must be importable from sys.path (installed, or on PYTHONPATH)") from None
    except Exception as exc:  # the module's own code failed while importing
        raise ParameterError(f"{where}: importing module {module!r} of program {name!r} failed "
                             f"({_first_line(exc)})") from None
    for part in attr.split("."):
        if not hasattr(obj, part):
            raise ParameterError(f"{where}: module {module!r} has no {attr!r} (program {name!r})")
        obj = getattr(obj, part)
    if not callable(obj):
        raise ParameterError(f"{where}: program {name!r} is a {type(obj).__name__}, not a callable; it must be a "
                             f"function(world, start, goal, **args) returning an op.PathProgram")
    return obj


def program_builder(name: str, where: str = "spec") -> Callable:
    """The function that builds program ``name``: called as ``builder(world, start, goal, **args)``.

    Raises:
        UnknownAlgorithmError: a name that is neither ``smoothing``, a paper program nor
            ``module:function``.
        ParameterError: a ``module:function`` that cannot be imported or is not callable.
    """
    if not isinstance(name, str) or not name:
        raise ParameterError(f"{where}: 'program' must be a name ({SMOOTHING}, a paper program or "
                             f"module:function), got {name!r}")
    if is_user_program(name):
        return _user_function(name, where)
    from ..programs import paper_program, smoothing_program

    if name == SMOOTHING:
        return smoothing_program
    if name in paper_program_names():
        return partial(paper_program, name)
    raise UnknownAlgorithmError(f"{where}: unknown program {name!r}; use {SMOOTHING}, a paper program "
                                f"({', '.join(paper_program_names())}) or module:function")


def check_program(name, args, init, where: str = "spec") -> dict[str, Any]:
    """The program identity a spec gives (``{"program", "args", "init"}``), checked: the program
    resolves, ``args`` is plain data its builder accepts, ``init`` is a graph planner or None."""
    from ..registry import GRAPH_METHODS

    builder = program_builder(name, where)
    args = {} if args is None else args
    if not isinstance(args, Mapping):
        raise ParameterError(f"{where}: 'args' must be a mapping of keyword arguments of the program, got {args!r}")
    try:
        json.dumps(args)
    except TypeError:
        raise ParameterError(f"{where}: 'args' must be plain YAML data, got {args!r}") from None
    if not is_user_program(name):
        allowed = SMOOTHING_ARGS if name == SMOOTHING else PAPER_ARGS
        bad = sorted(set(args) - set(allowed))
        if bad:
            raise ParameterError(f"{where}: program {name!r} takes no argument {named_with_hints(bad, allowed)}; its "
                                 f"arguments are {', '.join(allowed)}")
    else:
        try:
            sig = inspect.signature(builder)
        except (TypeError, ValueError):  # no signature to read (some builtins): the run reports it
            sig = None
        if sig is not None:
            try:
                sig.bind(None, None, None, **args)
            except TypeError as exc:
                raise ParameterError(f"{where}: program {name!r} cannot be called as {name.split(':')[1]}(world, "
                                     f"start, goal{''.join(f', {k}=...' for k in args)}): {exc}") from None
    if init is not None and init not in GRAPH_METHODS:
        raise ParameterError(f"{where}: init must be a graph planner ({', '.join(GRAPH_METHODS)}) whose path "
                             f"starts every solver that takes init=, or left out; got {init!r}")
    return {"program": name, "args": dict(args), "init": init}


def build_program(identity: Mapping[str, Any], world, start, goal):
    """The program of a run: its builder called on the target with the spec's args.

    Raises:
        ParameterError: the builder returned something that is not a PathProgram.
    """
    from ..formulations.program import PathProgram

    name = identity["program"]
    prog = program_builder(name)(world, start, goal, **dict(identity.get("args") or {}))
    if not isinstance(prog, PathProgram):
        raise ParameterError(f"program {name!r} returned a {type(prog).__name__}, not an op.PathProgram")
    return prog


def program_module_file(name: str) -> Path | None:
    """The source file of a ``module:function`` program's module (``None`` for the built-in
    programs or when it has none); its content enters the runs' keys."""
    if not is_user_program(name):
        return None
    import importlib.util

    module = name.partition(":")[0]
    try:
        spec = importlib.util.find_spec(module)
    except (ImportError, ValueError):
        return None
    origin = getattr(spec, "origin", None) if spec is not None else None
    return Path(origin) if origin and Path(origin).is_file() else None


# ----------------------------------------------------------------------------- solvers
def solver_stages(entry, where: str = "spec") -> list[str]:
    """The stage names of a solver entry (a name, or a list of names for a chain), checked
    against the registered program solvers."""
    from ..programs import solver_names

    stages = entry if isinstance(entry, list) else [entry]
    if not stages:
        raise ParameterError(f"{where}: a chain needs at least one solver, e.g. [msiar-gwo, ipopt]")
    known = solver_names()
    out = []
    for s in stages:
        if not isinstance(s, str):
            raise ParameterError(f"{where}: a solver is a name or a list of names (a chain), got {s!r}")
        if s.lower() not in known:
            raise UnknownAlgorithmError(f"{where}: unknown program solver {s!r}; known: {', '.join(known)}")
        out.append(s.lower())
    return out


def solver_name(stages: list[str]) -> str:
    """The record name of a solver or chain: ``"ipopt"``, ``"pso>ipopt"``."""
    return CHAIN_SEPARATOR.join(stages)


def solver_of(name: str):
    """What ``get_solver`` takes for a record's solver name: the name, or the chain's list."""
    return name.split(CHAIN_SEPARATOR) if CHAIN_SEPARATOR in name else name


def solver_instance(name: str):
    """A fresh solver (or chain) for a record's solver name."""
    from ..programs import get_solver

    return get_solver(solver_of(name))


def solver_options(name: str) -> set[str]:
    """The options the solver (or chain) of ``name`` takes."""
    return set(solver_instance(name).all_options())


def is_stochastic(name: str) -> bool:
    """Whether the solver (or one stage of the chain) takes a seed."""
    return "seed" in solver_options(name)


def check_solver_params(name: str, params: Mapping[str, Any], where: str = "spec") -> dict[str, Any]:
    """``params`` checked by the solver's own option checkers (unknown names and bad values
    are one-line ParameterErrors); returns them unchanged (plain data for the run key)."""
    try:
        solver_instance(name).check_options(dict(params))
    except ParameterError as exc:
        text = str(exc)
        raise ParameterError(f"{where}: {text}" if text.startswith(name) else f"{where}: {name}: {text}") from None
    return dict(params)


# modules a solver imports on its first solve; a worker imports them before it times any run
SOLVER_MODULES = {"ipopt": ("casadi",), "slsqp": ("casadi", "scipy.optimize"), "osqp": ("casadi", "osqp"),
                  "cvxpy": ("casadi", "cvxpy")}


def solver_modules(names) -> tuple[str, ...]:
    """The third-party modules the solvers (or chains) ``names`` import when they first solve."""
    out: dict[str, None] = {}
    for n in names:
        for stage in n.split(CHAIN_SEPARATOR):
            out.update(dict.fromkeys(SOLVER_MODULES.get(stage, ())))
    return tuple(out)


__all__ = ["program_builder", "check_program", "build_program", "program_module_file", "solver_stages",
           "solver_name", "solver_of", "solver_instance", "solver_options", "is_stochastic", "check_solver_params",
           "solver_modules", "paper_program_names", "SMOOTHING"]
