"""``optplan simulate SCENARIO.yaml``: one closed-loop run from the command line."""
from __future__ import annotations

import json


def add_simulate_arguments(parser) -> None:
    """Arguments of ``optplan simulate``."""
    parser.add_argument("scenario", help="scenario YAML file or the name of a shipped scenario")
    parser.add_argument("--global", dest="global_planner", default="astar",
                        help="global planner (see 'optplan algorithms'); default astar (visibility on circle worlds)")
    parser.add_argument("--local", dest="local_planner", default="dwa",
                        help="local planner: dwa, missa-dwa, idwa, ba-dwa, iga-dwa, qp-dwa; default dwa")
    parser.add_argument("--refine", default="none", choices=["none", "casadi", "qp"], help="refine the global path")
    parser.add_argument("--seed", type=int, default=0, help="random seed (global planner, random obstacles); default 0")
    parser.add_argument("--subgoals", default=None,
                        help="subgoal strategy: goal, key_points, turning_points, navigation_points "
                             "(default: the local planner's paper default)")
    parser.add_argument("--json", action="store_true", help="print exactly one JSON object")
    parser.add_argument("--gif", metavar="FILE.gif", help="write an animation of the run")
    parser.add_argument("--progress", action="store_true", help="print a status line every 10 simulated seconds")
    parser.epilog = "example: optplan simulate hou2024_dynamic1 --global astar --local missa-dwa --gif run.gif"


def run_simulate(args) -> int:
    """Run ``optplan simulate``; returns the exit status (0 also when the goal is missed:
    the outcome is reported, not an error)."""
    from ..world.scenario import load_scenario
    from .closed_loop import simulate

    scenario = load_scenario(args.scenario)
    options = {}
    if args.subgoals:
        options["subgoals"] = args.subgoals
    if args.progress:
        options["progress"] = True
    refine = None if args.refine == "none" else args.refine
    from .closed_loop import realized_scenario
    from .experiments import plan_global

    plan = plan_global(scenario, args.global_planner, refine, args.seed)
    res = simulate(scenario, global_planner=args.global_planner, local_planner=args.local_planner, refine=refine,
                   seed=args.seed, global_plan=plan, **options)
    if args.gif:
        from ..viz.animate import animate_run

        animate_run(realized_scenario(scenario, args.seed, plan), res, args.gif)
    if args.json:
        print(json.dumps(res.to_json_dict()))
        return 0
    print(f"scenario       {scenario.name}")
    print(f"planners       {res.global_planner} + {res.local_planner}" + (f" (refine {res.refine})" if res.refine else ""))
    print(f"status         {res.status}: {res.message}")
    print(f"reached        {res.reached}")
    print(f"collisions     {res.collisions}")
    print(f"time           {res.time_s:.1f} s ({res.steps} steps, {res.mean_step_ms:.2f} ms per local-planner call)")
    print(f"path length    {res.path_length:.3f} m")
    print(f"min clearance  {res.min_clearance:.3f} m")
    print(f"max |accel|    {res.max_abs_accel:.3f} m/s^2, max |ang accel| {res.max_abs_ang_accel:.3f} rad/s^2")
    if args.gif:
        print(f"wrote {args.gif}")
    return 0
