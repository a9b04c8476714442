"""The ``optplan`` command line. Errors print one line and exit with status 2;
``optplan simulate`` exits with status 1 when the robot did not reach the goal without a
collision (the outcome is still printed in full)."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .errors import OptplanError

EXIT_ERROR = 2          # an OptplanError (bad file, bad parameter, ...): its message is printed
EXIT_GOAL_MISSED = 1    # simulate: the run ended without reaching the goal collision-free
EXIT_INTERNAL = 3       # an exception that is not an OptplanError: a bug, printed on one line

# Subcommands whose arguments and handler live with their layer: each module defines
# ``add_<name>_arguments(parser)`` and ``run_<name>(args) -> int``. ``simulate`` lives here
# instead, because it draws (--gif) and the simulator layer must not import optplan.viz.
EXAMPLES = {
    "plan": "example: optplan plan arena --start 1.5 37.5 --goal 40.5 10.5 --algo visibility --plot arena.png",
    "algorithms": "example: optplan algorithms --details",
    "demo": "example: optplan demo --out demo.png",
    "simulate": "example: optplan simulate hou2024_dynamic1 --global astar --local missa-dwa --gif run.gif   "
                "(exit status: 0 goal reached with no collision, 1 not (stuck, timeout or collision), 2 error)",
}


def _load_world(spec: str, flip: bool = False):
    from .world.loaders import load_map

    return load_map(spec, origin="lower" if flip else "upper")


def _cmd_plan(args) -> int:
    from .planning import plan
    from .demo import format_table

    world = _load_world(args.map, getattr(args, "flip", False))
    start, goal = _plan_query(args, world)
    extra = _plan_extra_params(args)
    refine = None if args.refine == "none" else args.refine
    refine_options = {}
    if args.tube_radius is not None:
        if refine is None:
            raise OptplanError("--tube-radius only applies to a refinement; add --refine casadi or --refine qp")
        refine_options["tube_radius"] = args.tube_radius
    if args.refine_starts is not None:
        if refine is None:
            raise OptplanError("--refine-starts only applies to a refinement; add --refine casadi or --refine qp")
        refine_options["starts"] = args.refine_starts
    if args.encoding is not None:
        extra["encoding"] = args.encoding
    iters = extra.pop("iters", args.iters)
    res = plan(world, start, goal, algorithm=args.algo, refine=refine, seed=args.seed,
               pop=args.pop, iters=iters, clearance=args.clearance, refine_options=refine_options, **extra)
    _export_plan(args, res)
    if args.plot:
        from .viz.plots import plot_paths

        name = args.algo + (f" + {refine}" if refine else "")    # the refined path is what is drawn
        plot_paths(world, {name: res.path}, args.plot, title=f"{name} on {Path(args.map).name}")
    if args.json:
        from .solvers.gaps import class_gaps

        # the gap to the exact optimum, split into the corridor (class) and the shape (in class)
        out = res.to_json_dict()
        out.update(class_gaps(world, res.path[0] if len(res.path) else args.start,
                              res.path[-1] if len(res.path) else args.goal, res.path, clearance=args.clearance))
        print(json.dumps(out))
    else:
        from .demo import RESULT_COLUMNS, result_row
        from .solvers.gaps import class_gaps

        # the same columns as the demo's table, the gap against the exact any-angle optimum
        optimum = None
        if len(res.path):
            try:
                optimum = class_gaps(world, res.path[0], res.path[-1], res.path, clearance=args.clearance).get(
                    "exact_length")
            except OptplanError:
                optimum = None
        name = args.algo + (f" + {refine}" if refine else "")
        print(format_table([result_row(name, res, optimum)], RESULT_COLUMNS))
        if res.encoding:
            print(f"encoding: {res.encoding}")
        if res.message:
            print(res.message)
        if args.plot:
            print(f"wrote {args.plot}")
        if args.export:
            print(f"wrote {args.export}")
    return 0


def _add_plan_extra_arguments(p) -> None:
    p.add_argument("--max-evals", type=int, default=None, metavar="N",
                   help="budget of a metaheuristic in objective evaluations (instead of --iters)")
    p.add_argument("--export", "--out", dest="export", metavar="FILE",
                   help="write the path as .csv (x,y, 6 decimals), .json (exact), .geojson (a LineString in the "
                        "map frame) or .yaml (nav_msgs/Path-like)")
    p.add_argument("--scen", metavar="FILE.scen", help="take start and goal from a Moving AI scenario file")
    p.add_argument("--query", type=int, default=0, metavar="K", help="which query of --scen (0 = first; default 0)")
    p.add_argument("--params", metavar="JSON", help="more op.plan options as one JSON object, e.g. "
                   "'{\"encoding\": \"general\", \"w\": 0.6}' (the planner's own parameters included)")


def _check_seed(seed: int) -> None:
    from .checks import seed_bound

    if seed < 0:
        raise OptplanError(f"--seed must be an integer >= 0, got {seed}")
    seed_bound("--seed", seed)


def _json_params(text: str | None, flag: str) -> dict:
    """The options of ``--params '{"key": value}'``: one JSON object (what the Python call
    takes as keyword arguments), checked by the call itself with the same named errors."""
    if text is None:
        return {}
    try:
        value = json.loads(text)
    except ValueError as exc:
        raise OptplanError(f"{flag} must be one JSON object such as '{{\"pop\": 40}}': {exc}") from None
    if not isinstance(value, dict):
        raise OptplanError(f"{flag} must be one JSON object such as '{{\"pop\": 40}}', got {type(value).__name__}")
    return value


def _plan_extra_params(args) -> dict:
    extra = _json_params(getattr(args, "params", None), "--params")
    if args.max_evals is None:
        return extra
    if args.max_evals < 1:
        raise OptplanError(f"--max-evals must be a positive integer, got {args.max_evals}")
    return {**extra, "max_evals": args.max_evals, "iters": None}


def _plan_query(args, world) -> tuple:
    """Start and goal of ``optplan plan``: --start/--goal, else the --scen query, else a
    paper map's own pair."""
    if args.scen is not None:
        if args.start is not None or args.goal is not None:
            raise OptplanError("give either --scen (start and goal from the scenario file) or --start/--goal, not both")
        from .world.loaders import scen_query

        return scen_query(world, args.scen, args.query)
    if args.start is not None and args.goal is not None:
        return tuple(args.start), tuple(args.goal)
    from .world.papermaps import catalogue

    paper = catalogue().get(args.map)
    if paper is None or args.start is not None or args.goal is not None:
        raise OptplanError(f"give --start X Y and --goal X Y in metres (or --scen FILE.scen); only paper maps "
                           f"({', '.join(sorted(catalogue()))}) have a default pair")
    return paper.start, paper.goal


def _export_plan(args, res) -> None:
    if args.export:
        from .world.export import export_path

        export_path(res.path, args.export)


def _export_simulation(args, res) -> None:
    if getattr(args, "export", None):
        from .world.export import export_trajectory

        export_trajectory(res.trajectory, args.export)


def _plot_simulation(args, realized_scenario, scenario, plan, res) -> None:
    if args.plot:
        from .viz.animate import plot_run

        plot_run(realized_scenario(scenario, args.seed, plan), res, args.plot)


def _add_simulate_arguments(parser) -> None:
    parser.add_argument("scenario", help="scenario YAML file, the name of a shipped scenario, or a generated "
                                            "family drawn from --seed (clutter, clutter-movers)")
    parser.add_argument("--global", "--global-planner", dest="global_planner", default="astar", metavar="NAME",
                        help="global planner (see 'optplan algorithms'); default astar (visibility on circle worlds)")
    parser.add_argument("--local", "--local-planner", dest="local_planner", default="dwa", metavar="NAME",
                        help="local planner: dwa, missa-dwa, idwa, ba-dwa, iga-dwa, qp-dwa, mpc; default dwa")
    parser.add_argument("--refine", default="none", choices=_refine_choices(), help="refine the global path")
    parser.add_argument("--seed", type=int, default=0, help="random seed (global planner, random obstacles); default 0")
    parser.add_argument("--subgoals", default=None,
                        help="subgoal strategy: goal, key_points, turning_points, navigation_points "
                             "(default: the local planner's paper default)")
    parser.add_argument("--on-blocked", default=None, choices=("switch", "replan", "ignore"),
                        help="when a newly sensed obstacle blocks the global path: switch paths (yuan2021 §4.2), "
                             "re-plan, or leave it to the local planner (default: the local planner's paper default)")
    parser.add_argument("--replanner", default=None, choices=("exact", "global"),
                        help="who re-plans: exact graph search (default) or the global planner with its options")
    parser.add_argument("--movers", default=None, choices=("shuttle", "once"),
                        help="motion of the scenario's random movers: back and forth for the whole run, or "
                             "once across the path, as the papers draw them (default: the scenario's)")
    parser.add_argument("--json", action="store_true", help="print exactly one JSON object")
    parser.add_argument("--gif", metavar="FILE.gif|FILE.mp4", help="write an animation of the run (.mp4 needs ffmpeg)")
    parser.add_argument("--progress", action="store_true", help="print a status line every 10 simulated seconds")
    parser.add_argument("--export", metavar="FILE",
                        help="write the trajectory as .csv (t,x,y,theta,v,w; 6 decimals), .json (exact), .geojson "
                             "(a LineString in the map frame, times and headings as properties) or .yaml "
                             "(nav_msgs/Path-like)")
    parser.add_argument("--plot", metavar="FILE.png", help="write a static picture of the run")
    parser.add_argument("--params", metavar="JSON", help="options of the local planner as one JSON object (what "
                        "planner_params takes, over the scenario file's planner_params), e.g. '{\"max_iter\": 30}'")
    parser.add_argument("--global-params", metavar="JSON", help="op.plan options of the global planner as one JSON "
                        "object (over the scenario file's global_options), e.g. '{\"pop\": 40, \"iters\": 100}'")
    parser.add_argument("--local-program", metavar="NAME", help="a named window program solved by the "
                        "local planner: 'default' (dwa samples it, qp-dwa samples and polishes it with one QP, mpc "
                        "solves it by NMPC; mpc's own default) or a paper preset's (dwa, idwa, missa-dwa, ...: "
                        "sampled by dwa, exactly the preset's planner)")


def _cmd_simulate(args) -> int:
    """Run ``optplan simulate``; returns the exit status: 0 when the robot reached the goal
    with no collision, :data:`EXIT_GOAL_MISSED` (1) when it did not (stuck, timed out or
    collided; the outcome is printed all the same)."""
    from .sim.closed_loop import realized_scenario, scenario_for, simulate, with_mover_motion
    from .sim.experiments import plan_global

    _check_seed(args.seed)
    scenario = with_mover_motion(scenario_for(args.scenario, args.seed), args.movers)
    options = {}
    from .worldgen.clutter import family_options

    # the scenario file's planner_params (op.simulate lays them under these), then --params
    local_params = _json_params(args.params, "--params")
    global_params = _json_params(args.global_params, "--global-params")
    if local_params:
        options["planner_params"] = local_params
    if args.subgoals:
        options["subgoals"] = args.subgoals
    for name in ("on_blocked", "replanner"):
        if getattr(args, name):
            options[name] = getattr(args, name)
    if args.local_program:
        options["local_program"] = args.local_program
    # the local planner, its parameters and its program are checked before the global plan is made
    from .local import make_local_planner

    make_local_planner(args.local_planner, scenario.robot, scenario.dt,
                       **{**scenario.planner_params.get(str(args.local_planner).lower(), {}), **local_params},
                       **({"local_program": args.local_program} if args.local_program else {}))
    if args.progress:
        options["progress"] = True
    refine = None if args.refine == "none" else args.refine
    global_options = {**(family_options(args.scenario).get("global_options") or {}), **scenario.global_options,
                      **global_params}
    plan = plan_global(scenario, args.global_planner, refine, args.seed, global_options or None)
    res = simulate(scenario, global_planner=args.global_planner, local_planner=args.local_planner, refine=refine,
                   seed=args.seed, global_plan=plan, **options)
    if args.gif:
        from .viz.animate import animate_run

        animate_run(realized_scenario(scenario, args.seed, plan), res, args.gif)
    _plot_simulation(args, realized_scenario, scenario, plan, res)
    _export_simulation(args, res)
    status = 0 if res.reached and res.collisions == 0 else EXIT_GOAL_MISSED
    if args.json:
        print(json.dumps(res.to_json_dict()))
        return status
    print(f"scenario       {scenario.name}")
    print(f"planners       {res.global_planner} + {res.local_planner}" + (f" (refine {res.refine})" if res.refine else ""))
    print(f"status         {res.status}: {res.message}")
    print(f"reached        {res.reached}")
    print(f"collisions     {res.collisions}")
    print(f"time           {res.time_s:.1f} s ({res.steps} steps, {res.mean_step_ms:.2f} ms per local-planner call)")
    print(f"path length    {res.path_length:.3f} m")
    print(f"min clearance  {res.min_clearance:.3f} m")
    print(f"max |accel|    {res.max_abs_accel:.3f} m/s^2, max |ang accel| {res.max_abs_ang_accel:.3f} rad/s^2")
    if res.replans:
        print(f"re-plans       {res.replans} ({res.path_switches} path switches)" +
              (f"; {1e3 * res.reroute_s:.1f} ms per answer to a blocked path" if res.reroute_s is not None else ""))
    for written in (args.gif, args.plot, args.export):
        if written:
            print(f"wrote {written}")
    return status


def _refine_choices() -> list[str]:
    from .solvers.refine import METHODS

    return ["none", *METHODS]


def _cmd_algorithms(args) -> int:
    from .registry import algorithms

    if not getattr(args, "details", False):
        for name in algorithms():
            print(name)
        return 0
    from .local import algorithm_names as local_names
    from .solvers.catalog import planner_capabilities

    local = set(local_names())
    width = max(len(n) for n in algorithms())
    for name in algorithms():
        what = "local planner" if name in local else planner_capabilities(name).describe()
        print(f"{name:<{width}}  {what}")
    return 0


def _cmd_demo(args) -> int:
    from .demo import run_demo

    run_demo(args.out, seed=args.seed)
    return 0


# ----------------------------------------------------------- bench and reproduce
BENCH_EPILOG = """examples:
  optplan bench chen2025_paths --quick --db results.sqlite          # a shipped spec, reduced
  optplan bench my_spec.yaml --workers 8 --csv runs.csv --plots figs/
  optplan bench my_spec.yaml --executor dask://10.0.0.5:8786 --db results.sqlite
  optplan bench programs_example --db programs.sqlite                # kind program: one program, many solvers
Rerunning the same command skips the runs already in --db (resume after an interruption).
Spec format: {specs}/README.md"""

REPRODUCE_EPILOG = """examples:
  optplan reproduce chen2025 --quick
  optplan reproduce hou2024 --runs 10 --workers 2 --db hou2024.sqlite   # resumable
  optplan reproduce yuan2021 --part global --update-docs   # rewrite its marked tables in README/docs
Shipped specs: {specs}/PAPER_*.yaml"""


def _common_run_arguments(p: argparse.ArgumentParser) -> None:
    from .bench.runner import EXECUTORS_HELP

    p.add_argument("--executor", default="local", metavar="EXEC",
                   help=f"where runs execute: {EXECUTORS_HELP} (default local: a process pool)")
    p.add_argument("--workers", type=int, default=None, metavar="N",
                   help="worker processes for local/dask-local (default: CPU count, 1 with --quick; 1 runs in "
                        "this process)")
    p.add_argument("--runs", type=int, default=None, metavar="N", help="seeds per (target, algorithm), overriding "
                   "the spec")
    p.add_argument("--quick", action="store_true", help="apply the spec's quick overrides (few runs, short budgets)")
    p.add_argument("--format", choices=["markdown", "latex"], default="markdown", help="table format")
    p.add_argument("--plots", metavar="DIR", help="write box plots, convergence curves and path overlays here")
    p.add_argument("--csv", metavar="OUT.csv", help="export the runs of the spec(s) to a CSV file")
    p.add_argument("--export-ompl", metavar="DIR", help="write the runs as OMPL benchmark logs (one per experiment "
                   "and target) into DIR, for ompl_benchmark_statistics.py and Planner Arena")
    p.add_argument("--retry-failed", action="store_true", help="rerun runs stored as failed (default: keep them)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")


def add_bench_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``optplan bench``."""
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    from .bench.spec import SPECS_DIR

    parser.epilog = BENCH_EPILOG.format(specs=SPECS_DIR)   # where the installed package keeps them
    parser.add_argument("spec", help="experiment spec YAML file, or the name of a shipped spec")
    parser.add_argument("--db", default="results.sqlite", metavar="FILE",
                        help="SQLite results database (default results.sqlite; ':memory:' keeps nothing)")
    parser.add_argument("--layout", default=None, help="table layout (default: the spec's 'report', else summary)")
    parser.add_argument("--summary-only", action="store_true", help="print the tables of what --db holds, run nothing")
    _common_run_arguments(parser)


def add_reproduce_arguments(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``optplan reproduce``."""
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    from .bench.spec import SPECS_DIR

    parser.epilog = REPRODUCE_EPILOG.format(specs=SPECS_DIR)
    from .bench.command import PAPERS

    parser.add_argument("paper", choices=PAPERS, help="which paper's experiments to run")
    parser.add_argument("--part", default=None, help="only this part (e.g. global, local, functions, paths)")
    parser.add_argument("--db", default=":memory:", metavar="FILE",
                        help="keep results in this SQLite file and resume from it (default: in memory, fresh)")
    parser.add_argument("--update-docs", action="store_true",
                        help="rewrite the marked results tables of README.md and docs/fidelity/*.md that this "
                             "run prints (those whose recorded command runs the same runs) from this run; a --db "
                             "holding runs of older code writes their numbers")
    _common_run_arguments(parser)



class _OneLineParser(argparse.ArgumentParser):
    """argparse with usage errors on one line (status 2), like every other optplan error."""

    def error(self, message: str):  # noqa: D401 - argparse's hook
        self.exit(EXIT_ERROR, f"{self.prog}: error: {one_line(message)} (see '{self.prog} --help')\n")


def _add_version_argument(parser) -> None:
    from . import __version__

    parser.add_argument("--version", action="version", version=f"optplan {__version__}")


def build_parser() -> argparse.ArgumentParser:
    """The ``optplan`` argument parser with every subcommand (each with an example in its help)."""
    parser = _OneLineParser(
        prog="optplan",
        description="Mobile-robot path planning as constrained programs.",
        epilog="example: optplan demo      (see 'optplan COMMAND --help' for each command)",
    )
    _add_version_argument(parser)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    p = sub.add_parser("plan", help="plan a global path on a map", epilog=EXAMPLES["plan"])
    p.add_argument("map", help="map file (.map, .yaml, .pgm, .npy, .txt, .csv, circle-world .json) or a shipped map "
                   "name; a file's first row is the top of the map (x to the right, y up), unless --flip")
    p.add_argument("--flip", action="store_true", help="the first row of a .npy/.txt/.csv matrix is the bottom "
                   "row (an array a[iy, ix] with iy up, as matplotlib's imshow(origin='lower') draws it)")
    p.add_argument("--start", nargs=2, type=float, metavar=("X", "Y"),
                   help="start in metres (default: a paper map's own start, or the --scen query's)")
    p.add_argument("--goal", nargs=2, type=float, metavar=("X", "Y"),
                   help="goal in metres (default: a paper map's own goal, or the --scen query's)")
    p.add_argument("--algo", "--algorithm", dest="algo", default="astar", metavar="NAME",
                   help="planner name (see 'optplan algorithms'); default astar")
    p.add_argument("--refine", default="none", choices=_refine_choices(), help="refinement stage")
    p.add_argument("--tube-radius", type=float, default=None, metavar="M",
                   help="metres around the path in which refinement may pass obstacles on the other side "
                        "(0: purely local; default: casadi twice the widest obstacle, qp 0)")
    p.add_argument("--refine-starts", type=int, default=None, metavar="K",
                   help="refine the planner's best path and up to K-1 other distinct paths of its population, "
                        "keep the shortest (1: best path only; default: casadi 3, qp 1)")
    p.add_argument("--encoding", default=None, choices=["general", "paper", "columns", "waypoints", "spline", "cells"],
                   help="path encoding of a metaheuristic (default: general, every path class on every map, "
                        "the best measured; 'paper': the paper's own, replaced by general when it cannot "
                        "represent a solution; 'cells': li2023's chromosome for ga/iga)")
    p.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    p.add_argument("--pop", type=int, default=30, help="population size of metaheuristics")
    p.add_argument("--iters", type=int, default=500, help="iterations of metaheuristics")
    p.add_argument("--clearance", type=float, default=0.0, help="required clearance in metres")
    p.add_argument("--json", action="store_true", help="print exactly one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="write a picture of the path")
    _add_plan_extra_arguments(p)
    p.set_defaults(func=_cmd_plan)

    a = sub.add_parser("algorithms", help="list every registered planner", epilog=EXAMPLES["algorithms"])
    a.add_argument("--details", action="store_true",
                   help="also say what each global planner can do (kind, grid only, stochastic, exact, alternatives)")
    a.set_defaults(func=_cmd_algorithms)

    m = sub.add_parser("simulate", help="run a robot through a scenario (global + local planner)",
                       epilog=EXAMPLES["simulate"])
    _add_simulate_arguments(m)
    m.set_defaults(func=_cmd_simulate)

    from .bench.command import run_bench, run_reproduce

    c = sub.add_parser("bench", help="run an experiment spec (maps x algorithms x seeds) into SQLite")
    add_bench_arguments(c)
    c.set_defaults(func=run_bench)
    c = sub.add_parser("reproduce", help="run a paper's shipped experiments and print its tables")
    add_reproduce_arguments(c)
    c.set_defaults(func=run_reproduce)

    d = sub.add_parser("demo", help="plan on a shipped map, print a table, write a PNG", epilog=EXAMPLES["demo"])
    d.add_argument("--out", default="optplan_demo.png", help="PNG to write (default optplan_demo.png)")
    d.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    d.set_defaults(func=_cmd_demo)
    for command in sub.choices.values():
        _add_verbosity_arguments(command)
    return parser


def _add_verbosity_arguments(parser) -> None:
    group = parser.add_mutually_exclusive_group()
    group.add_argument("-v", "--verbose", action="store_true",
                       help="also print the 'optplan' logger's debug messages on stderr")
    group.add_argument("-q", "--quiet", action="store_true",
                       help="print only warnings and errors on stderr (no notes, no progress bars)")


def _set_up_logging(args) -> None:
    """The 'optplan' logger to stderr for this command: notes (INFO) by default, debug
    messages with -v, warnings only with -q. A program that imports optplan configures the
    logger itself (optplan only adds a NullHandler to it)."""
    import logging

    log = logging.getLogger("optplan")
    for h in list(log.handlers):
        if getattr(h, "_optplan_cli", False):
            log.removeHandler(h)
    handler = logging.StreamHandler(sys.stderr)
    handler._optplan_cli = True
    handler.setFormatter(logging.Formatter("%(message)s"))
    log.addHandler(handler)
    log.setLevel(logging.DEBUG if getattr(args, "verbose", False) else
                 logging.WARNING if getattr(args, "quiet", False) else logging.INFO)
    log.propagate = False
    if getattr(args, "quiet", False) and hasattr(args, "no_progress"):
        args.no_progress = True
    import warnings

    def show(message, category, filename, lineno, file=None, line=None):
        # one line, like the errors: what Python prints by default names a source line of optplan
        log.warning(f"optplan: warning: {one_line(message)}")

    warnings.showwarning = show


# options that name a file or folder the command writes
OUTPUT_OPTIONS = ("plot", "gif", "csv", "out", "plots", "export", "export_ompl")
PICTURE_OPTIONS = ("plot", "out")  # of those, the ones matplotlib writes (format from the suffix)


def _check_outputs(args) -> None:
    """Refuse an output path that cannot be written before any work is done, so a long
    run does not end in an error with nothing to show for it."""
    import os

    for name in OUTPUT_OPTIONS:
        value = getattr(args, name, None)
        if not value:
            continue
        target = Path(value)
        folder = name in ("plots", "export_ompl")
        flag = name.replace("_", "-")
        if target.is_dir() and not folder:
            raise OptplanError(f"--{flag} {value} is a folder; give a file name")
        if name == "export" and target.suffix.lower() not in (".csv", ".yaml", ".yml", ".json", ".geojson"):
            raise OptplanError(f"--export {value}: use a .csv, .json, .geojson or .yaml file name")
        if name in PICTURE_OPTIONS:
            from .viz.plots import figure_format

            figure_format(target)
        if name == "gif":
            from .viz.animate import check_video_target

            try:
                check_video_target(target)
            except OptplanError as exc:
                raise OptplanError(f"--gif {exc}") from None
        if name == "csv" and target.suffix.lower() != ".csv":
            raise OptplanError(f"--csv {value}: give a .csv file name")
        parent = target if folder else target.parent
        existing = next((d for d in (parent, *parent.parents) if d.exists()), None)
        if existing is None or not existing.is_dir() or not os.access(existing, os.W_OK):
            raise OptplanError(f"--{flag} {value}: cannot write there ({existing or parent} is not a writable folder)")
    layout = getattr(args, "layout", None)
    if layout is not None:
        from .bench.reports import LAYOUTS

        if layout not in LAYOUTS:
            raise OptplanError(f"--layout {layout!r} is not a table layout; known: {', '.join(LAYOUTS)}")


MAX_MESSAGE_CHARS = 2000  # an error names what was wrong; it never echoes a whole input back


def one_line(message) -> str:
    """An error message on one line of at most :data:`MAX_MESSAGE_CHARS` characters
    (white space runs collapsed, the middle of a long message elided)."""
    text = " ".join(str(message).split())
    if len(text) > MAX_MESSAGE_CHARS:
        half = MAX_MESSAGE_CHARS // 2 - 10
        text = f"{text[:half]} [... {len(text) - 2 * half} characters ...] {text[-half:]}"
    return text


def main(argv: list[str] | None = None) -> int:
    """Run the command line with ``argv`` (default ``sys.argv[1:]``); returns the exit status
    (0 success, 1 a simulation that missed the goal or collided, 2 an OptplanError whose
    message was printed on one line, 3 an internal error (a bug; one line, the traceback with
    ``OPTPLAN_TRACEBACK=1``), 130 interrupted, 141 the reader of the output went away, as in
    ``optplan ... | head``, which prints nothing more)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help()
        return 2
    try:
        _set_up_logging(args)
        _check_outputs(args)
        return int(args.func(args) or 0)
    except OptplanError as exc:
        print(f"optplan: error: {one_line(exc)}", file=sys.stderr)
        return EXIT_ERROR
    except BrokenPipeError:  # the reader of our output went away (`optplan ... | head`): not an error
        import os

        # stdout is dead: point it at devnull so the interpreter's final flush stays quiet
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141  # what a shell reports for a process ended by SIGPIPE
    except OSError as exc:  # a file the user named could not be read or written
        where = f" {exc.filename}" if getattr(exc, "filename", None) else ""
        print(f"optplan: error: cannot access{where}: {exc.strerror or exc}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt as exc:
        hint = str(exc)
        print(f"optplan: interrupted{'; ' + hint if hint else ''}", file=sys.stderr)
        return 130
    except Exception as exc:  # a bug, not a bad input: say so on one line, keep the details on request
        import os

        if os.environ.get("OPTPLAN_TRACEBACK"):
            raise
        print(f"optplan: internal error: {type(exc).__name__}: {one_line(exc)} (this is a bug in optplan; "
              f"rerun with OPTPLAN_TRACEBACK=1 for the traceback and report it)", file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
