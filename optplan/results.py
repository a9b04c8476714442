"""Result dataclasses shared by every solver.

Each result has ``to_dict()`` returning a JSON-serialisable dict (numpy arrays
become nested lists, numpy scalars become Python numbers).
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np


def jsonable(value: Any) -> Any:
    """Convert numpy containers and scalars (recursively) to plain Python objects."""
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, (np.floating, float)):
        v = float(value)
        # JSON has no NaN/inf; None is the honest "no value".
        return v if np.isfinite(v) else None
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (np.bool_,)):
        return bool(value)
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    return value


class _ToDict:
    JSON_KEYS: tuple[str, ...] = ()  # the command line's ``--json`` keys, where a result has them
    # bulky in-memory fields left out of to_dict (they would swamp JSON output and result stores)
    NOT_IN_DICT: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """All fields (except ``NOT_IN_DICT``) as a JSON-serialisable dict."""
        return {f.name: jsonable(getattr(self, f.name)) for f in fields(self)  # type: ignore[arg-type]
                if f.name not in self.NOT_IN_DICT}

    def to_json_dict(self) -> dict[str, Any]:
        """Exactly the keys of the ``--json`` contract (``JSON_KEYS``), JSON-serialisable."""
        d = self.to_dict()
        return {k: d[k] for k in self.JSON_KEYS}


@dataclass
class OptimizeResult(_ToDict):
    """Outcome of ``optimize`` on a plain objective.

    Attributes:
        x: best point found, shape ``(d,)``.
        f: objective value at ``x``.
        history: best value after each iteration, shape ``(nit + 1,)`` (entry 0 is
            the initial population).
        history_nfev: evaluations spent when each ``history`` entry was recorded.
        nfev: objective evaluations (rows of ``X`` passed to ``f``).
        nit: iterations completed.
        runtime_s: wall time in seconds.
        status: ``"max_iters"``, ``"max_evals"``, ``"stagnation"``, ``"target"`` or ``"callback"``.
        message: human-readable explanation of ``status``.
        algorithm: registry name of the algorithm.
        seed: the seed passed in (``None`` when a Generator was given).
        archive: with ``optimize(..., archive_every=k)``: ``(X, f, violation)``, the
            distinct points of the population snapshots (initial, every ``k``
            iterations, final), best first; ``None`` otherwise. Not in ``to_dict``.
        success: a finite objective value was found at a point with no violation
            (scipy's ``success``); ``False`` when every value was NaN or infinite, or no
            point was feasible, and ``message`` says which.
        fun: the same as ``f`` (scipy's name).
    """

    x: np.ndarray
    f: float
    history: np.ndarray
    history_nfev: np.ndarray
    nfev: int
    nit: int
    runtime_s: float
    status: str
    message: str
    algorithm: str
    seed: int | None = None
    archive: tuple[np.ndarray, np.ndarray, np.ndarray] | None = field(default=None, repr=False)
    success: bool = True

    NOT_IN_DICT = ("archive",)

    @property
    def fun(self) -> float:
        """The objective value at ``x`` (scipy's name for ``f``)."""
        return self.f


class _Deferrable:
    """Fields that a builder may leave to be computed on their first read
    (:func:`defer_fields`). Instances with no deferred field behave exactly like the plain
    dataclass: ``__getattr__`` is only reached for a name missing from the instance."""

    def __getattr__(self, name: str) -> Any:
        deferred = self.__dict__.get("_deferred")
        compute = deferred.get(name) if deferred else None
        if compute is None:
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        value = compute()
        self.__dict__[name] = value
        deferred.pop(name, None)
        return value

    def __getstate__(self) -> dict[str, Any]:
        # pickles and copies hold values, never the computation (nor the world it reads)
        for name in list(self.__dict__.get("_deferred", ())):
            getattr(self, name)
        state = dict(self.__dict__)
        state.pop("_deferred", None)
        return state


_FIELD_NAMES: dict[type, frozenset[str]] = {}


def defer_fields(result, **compute):
    """Let the fields ``compute`` names be computed on their first read, each by its
    zero-argument callable, which must return the value the field would have held. Every
    way of reading the field (attribute, ``to_dict``, ``repr``, ``==``,
    ``dataclasses.replace``, pickling, copying) gives that value; assigning the field
    sets it as usual. Returns ``result``."""
    names = _FIELD_NAMES.get(type(result))
    if names is None:   # fields() builds a tuple on every call: a sizeable part of a small result
        names = _FIELD_NAMES[type(result)] = frozenset(f.name for f in fields(result))
    unknown = set(compute) - names
    if unknown:
        raise TypeError(f"{type(result).__name__} has no field {', '.join(sorted(unknown))}")
    for name in compute:
        result.__dict__.pop(name, None)
    result.__dict__.setdefault("_deferred", {}).update(compute)
    return result


@dataclass
class PlanResult(_Deferrable, _ToDict):
    """Outcome of a global path planner.

    Attributes:
        algorithm: registry name of the planner.
        path: ``(N, 2)`` points in metres, start first, goal last (may be empty if
            nothing was found).
        feasible: the path passed the exact ``validate_path`` check.
        length: path length in metres (``inf`` when there is no path).
        turn_angle_deg: sum of absolute heading changes, degrees.
        n_turns: number of vertices where the heading changes.
        min_clearance: smallest distance from the path to an obstacle, metres (graph search
            computes it on its first read, :func:`defer_fields`: the same value).
        runtime_s: wall time in seconds.
        history: best objective per iteration (empty for graph search).
        refined: ``True`` when a refinement stage changed the path.
        seed: the seed used, if any.
        message: what happened, in words (why infeasible, why refinement fell back).
        nfev: objective evaluations spent (0 for graph search).
        alternatives: other valid paths the planner's population held, best first by
            the planner's own fitness, each outside a band around the best path and
            around every earlier one (``plan_path(..., alternatives=k)``, which
            ``op.plan`` asks for when a multi-start refinement will use them); empty
            for graph search and by default. Not in ``to_dict`` / JSON.
        stages: with ``refine=``: one record per stage (the planner, then the refinement),
            each with the planner's own program cost (``fitness``: the paper's fitness
            the planner optimised, ``op.paper_program``), ``length`` and ``feasible``; the
            refinement's record also has the values before it and ``worse`` (its fitness
            rose). Empty without refinement.
        encoding: the path encoding a metaheuristic searched (``columns``, ``waypoints``,
            ``spline``, ``general``; ``general`` also when ``op.plan`` fell back to it because
            the paper's encoding could not represent a solution); empty for graph search.
        population_spread: per generation (the initial population first), the standard
            deviation of the population's finite objective values (li2023 Fig 14's diversity);
            filled by the GAs (``ga``, ``iga``), empty for every other planner.
    """

    algorithm: str
    path: np.ndarray
    feasible: bool
    length: float
    turn_angle_deg: float
    n_turns: int
    min_clearance: float
    runtime_s: float
    history: np.ndarray = field(default_factory=lambda: np.zeros(0))
    refined: bool = False
    seed: int | None = None
    message: str = ""
    nfev: int = 0
    alternatives: list[np.ndarray] = field(default_factory=list, repr=False)
    stages: list = field(default_factory=list)
    encoding: str = ""
    population_spread: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)

    NOT_IN_DICT = ("alternatives",)
    JSON_KEYS = ("algorithm", "feasible", "path", "length", "turn_angle_deg", "n_turns",
                 "min_clearance", "runtime_s", "refined", "seed", "encoding")


@dataclass
class SimResult(_ToDict):
    """Outcome of one closed-loop run (``op.simulate``).

    Attributes:
        reached: the robot got within the goal tolerance before ``time_limit``.
        collisions: simulation steps on which the robot's footprint overlapped an
            obstacle (static known, static unknown or moving), by the exact check.
        time_s: simulated time until the goal was reached (or the run stopped), seconds.
        path_length: distance driven, metres.
        min_clearance: smallest distance from the footprint to any obstacle, metres
            (negative when it overlapped one).
        max_abs_accel: largest |dv/dt| over the run, m/s^2.
        max_abs_ang_accel: largest |dw/dt| over the run, rad/s^2.
        steps: control steps simulated.
        mean_step_ms: mean wall time of one local-planner call, milliseconds.
        trajectory: rows ``[t, x, y, theta, v, w]`` (seconds, metres, radians, m/s, rad/s).
        status: ``"reached"``, ``"collision"``, ``"timeout"`` or ``"stuck"``.
        message: what happened, in words.
        global_planner, local_planner, refine: what was run.
        global_path: ``(N, 2)`` global path the robot followed (last one if re-planned).
        seed: the seed used.
        replans: number of global re-plans (path switch or stuck recovery).
        max_abs_jerk: largest |d^2v/dt^2| over the run, m/s^3.
        path_switches: how many of the re-plans were yuan2021 §4.2 path switches.
        reroute_s: mean wall time of one answer to a blocked global path (a path switch or a
            re-plan), seconds; ``None`` when no newly sensed obstacle blocked it.
    """

    reached: bool
    collisions: int
    time_s: float
    path_length: float
    min_clearance: float
    max_abs_accel: float
    max_abs_ang_accel: float
    steps: int
    mean_step_ms: float
    trajectory: np.ndarray
    status: str = ""
    message: str = ""
    global_planner: str = ""
    local_planner: str = ""
    refine: str | None = None
    global_path: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    seed: int | None = None
    replans: int = 0
    max_abs_jerk: float = 0.0
    path_switches: int = 0
    reroute_s: float | None = None

    # DESIGN.md's keys, then what a script needs to tell a failed run from a good one and to
    # reproduce it: why the run ended, in words, its seed and the global path it followed
    JSON_KEYS = ("reached", "collisions", "time_s", "path_length", "min_clearance", "max_abs_accel",
                 "max_abs_ang_accel", "steps", "mean_step_ms", "trajectory", "status", "message", "seed",
                 "global_path")


@dataclass
class ProgramResult(_ToDict):
    """Outcome of ``PathProgram.solve`` (any solver or chain).

    Attributes:
        solver: the solver's name (``"msiar-gwo"``, ``"ipopt"``, ``"msiar-gwo>ipopt"``).
        cost: the program's objective at ``path`` (``prog.evaluate(path)[0]``).
        feasible: the exact verdict: every constraint holds and the exact collision test
            accepts the path.
        path: ``(N, 2)`` points, start first, goal last.
        x: the decision vector the path was decoded from.
        violations: one entry per constraint, 0 where it holds.
        status: the solver's status word (``"max_evals"``, ``"Solve_Succeeded"``, ...).
        message: what happened, in words (fallbacks, surrogates, rejected stages).
        nfev: objective evaluations (rows for swarms; the solver's own count for IPOPT,
            SLSQP; QP solves for OSQP/cvxpy), summed over a chain's stages.
        runtime_s: wall time, seconds.
        stages: per stage of a chain (or of ``op.plan(..., refine=...)``): solver, cost
            before and after, feasible, accepted, nfev, runtime_s, message.
        seed: the seed used, if any.
        history: best cost per iteration (swarms; empty otherwise).
        variables: the variables' name (``"Waypoints(6)"``).
    """

    solver: str
    cost: float
    feasible: bool
    path: np.ndarray
    x: np.ndarray
    violations: dict
    status: str
    message: str
    nfev: int
    runtime_s: float
    stages: list = field(default_factory=list)
    seed: int | None = None
    history: np.ndarray = field(default_factory=lambda: np.zeros(0))
    variables: str = ""
