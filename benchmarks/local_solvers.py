"""Every local solver on the same worlds, like for like (issue 42).

Solvers: ``dwa`` (Fox's sampled preset), ``qp-dwa`` (sampling + OSQP polish + Ruckig) and
``mpc`` (CasADi NMPC of the default window program, ``optplan.local_terms.default_local_program``).
``dwa:program`` and ``qp-dwa:program`` solve that same window program by sampling, and by
sampling plus one SQP (OSQP) step: the three program solvers side by side. A ``-creep``
suffix (``mpc-creep``, ``qp-dwa:program-creep``) turns off their path creep (``local/creep.py``);
a ``+MODEL`` part (``mpc+straight``, ``qp-dwa:program+bounce-creep``) picks how the program
solvers predict movers (``mover_model``: ``sweep``, the default, ``bounce`` or ``straight``,
``optplan/local/program_planners.py:MoverTracker``). ``--stop-hold S`` adds ``stop_clear(S)``
(``optplan/formulations/local_program.py:StopClear``) to their default program.
Worlds: the BARN-style clutter family (``clutter``: entry corridor, 0.15 m cells, r = 0.2 m,
0.5 m/s), the same with 2 movers (``clutter-movers``), the shipped dynamic scenarios and the
papers' local experiments (``papers``). The
clutter seeds start at 5000 by default: they were not used while the solvers were written.

Columns: success, collisions (runs with any), timeouts, stuck, median time to goal and
path length over the successes, a BARN-style score (success x t_opt / clip(t, 2 t_opt,
8 t_opt), t_opt = the global path's length over v_max, averaged over all runs), the local
planner's step time median and p95 over every step, and how many runs kept the robot's
acceleration limits (|dv/dt| <= a_max, |dw/dt| <= alpha_max). For mpc, the share of steps
that fell back to the best sample.

    python benchmarks/local_solvers.py                       # 20 clutter + 20 clutter-movers seeds, 11 scenarios
    python benchmarks/local_solvers.py --worlds papers hou2024_dynamic1 --solvers dwa qp-dwa mpc
    python benchmarks/local_solvers.py --seeds 5 --solvers mpc --worlds clutter-movers
"""
from __future__ import annotations

import argparse
import time
from collections import defaultdict

import numpy as np

import optplan as op
from optplan.local import make_local_planner
from optplan.local_terms import default_local_program
from optplan.worldgen.clutter import family_scenario

SCENARIOS = ("hou2024_dynamic1", "hou2024_dynamic2", "hou2024_dynamic3", "hou2024_dynamic4")
# the papers' own local experiments (shipped scenarios, seed 0, the scenarios' own mover motion)
PAPER_SCENARIOS = ("hou2024_table4_1", "li2023_exp1", "li2023_exp2_2", "yang2023_fusion", "yang2023_idwa_crossing",
                   "yuan2021_added_obstacles", "yuan2021_path_switch")


STOP_SWEEP = True   # --stop-straight: stop_clear predicts movers straight on over its hold
STOP_COST = 0.0     # --stop-cost W: the default program with W x stop_cost (local_program.StopCost)


def _window(horizon: str, robot) -> float:
    """The default program's window, s: a number, or ``"brake"``: the robot's braking time from
    full speed ``v_max / a_max`` where that is longer than 2 s."""
    return max(2.0, robot.v_max / robot.a_max) if horizon == "brake" else float(horizon)


def _timed_planner(name: str, world: str, seed: int, stop_hold: float = 0.0, horizon: str = "2"):
    """The planner the closed loop would build for ``world`` (family parameters included),
    its ``command`` timed per step (``stop_hold``: the program solvers' default program with
    :func:`~optplan.formulations.local_program.stop_clear` for that many seconds; ``horizon``:
    its window, :func:`_window`)."""
    sc = family_scenario(world, seed) or op.load_scenario(world)
    window = _window(horizon, sc.robot)
    base, no_creep = name.removesuffix("-creep"), name.endswith("-creep")
    extra = {"path_creep": None} if no_creep else {}
    if "+" in base:   # the program solvers' mover model
        base, extra["mover_model"] = base.split("+", 1)
    if stop_hold or window != 2.0 or STOP_COST:
        extra["local_program"] = default_local_program(sc.robot, horizon=window, step=sc.dt, stop_hold=stop_hold,
                                                       stop_sweep=STOP_SWEEP, stop_cost=STOP_COST)
    if base.endswith(":program"):   # the sampling solver of the default window program
        extra.setdefault("local_program", default_local_program(sc.robot, step=sc.dt))
        planner = make_local_planner(base.split(":")[0], sc.robot, sc.dt, **extra)
    elif base == "mpc":
        planner = make_local_planner(base, sc.robot, sc.dt, **extra)
    else:
        planner = make_local_planner(name, sc.robot, sc.dt)
    times, modes = [], []
    inner = planner.command

    def command(ctx):
        t0 = time.perf_counter()
        cmd = inner(ctx)
        times.append((time.perf_counter() - t0) * 1e3)
        modes.append(cmd.info.get("mode"))
        return cmd

    planner.command = command
    return planner, sc, times, modes


def run(solvers, worlds, seeds, seed0, stop_hold: float = 0.0, as_file: bool = False,
        scenario_seeds: int = 1, horizon: str = "2") -> dict:
    rows = defaultdict(lambda: defaultdict(list))
    for world in worlds:
        run_seeds = range(seed0, seed0 + seeds) if family_scenario(world, 0) is not None else range(scenario_seeds)
        for name in solvers:
            for seed in run_seeds:
                planner, sc, times, modes = _timed_planner(name, world, seed, stop_hold, horizon)
                # as_file: the scenario as a file gives it (no family options, e.g. its global clearance)
                r = op.simulate(sc if as_file else world, global_planner="astar", local_planner=planner, seed=seed)
                row = rows[(world, name)]
                row["status"].append(r.status)
                row["collided"].append(r.collisions > 0)
                row["time"].append(r.time_s)
                row["length"].append(r.path_length)
                row["steps_ms"].extend(times)
                row["fallback"].append(sum(m == "fallback-sample" for m in modes) / max(len(modes), 1))
                gp = np.asarray(r.global_path, float)
                t_opt = float(np.hypot(*np.diff(gp, axis=0).T).sum()) / sc.robot.v_max if len(gp) > 1 else 1.0
                ok = r.reached and r.collisions == 0
                row["barn"].append(ok * t_opt / float(np.clip(r.time_s, 2 * t_opt, 8 * t_opt)))
                row["limits"].append(r.max_abs_accel <= sc.robot.a_max * (1 + 1e-6)
                                     and r.max_abs_ang_accel <= sc.robot.alpha_max * (1 + 1e-6))
                row["ok"].append(ok)
                print(f"  {world} {name} seed {seed}: {r.status}, {r.collisions} collisions, {r.time_s:.1f} s, "
                      f"step median {np.median(times):.1f} ms", flush=True)
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solvers", nargs="+", default=["dwa", "qp-dwa", "mpc"])
    ap.add_argument("--worlds", nargs="+", default=["clutter", "clutter-movers", *SCENARIOS, *PAPER_SCENARIOS],
                    help="generated families (seeded), shipped scenarios (seed 0), or 'papers' for the papers' "
                         "local experiments")
    ap.add_argument("--seeds", type=int, default=20, help="seeds per generated family")
    ap.add_argument("--seed0", type=int, default=5000)
    ap.add_argument("--stop-straight", action="store_true",
                    help="with --stop-hold: over the hold, movers run on at constant speed, turning only at ends "
                         "they were seen to turn at (not anywhere past where they were seen)")
    ap.add_argument("--stop-cost", type=float, default=0.0, metavar="W",
                    help="add W x stop_cost (the braking stop's closeness to the movers over 2 s after the window, "
                         "a soft term) to the program solvers' default program")
    ap.add_argument("--horizon", default="2", metavar="S|brake",
                    help="the program solvers' default window, s, or 'brake': the robot's braking time from full "
                         "speed (v_max / a_max) where longer than 2 s (default 2)")
    ap.add_argument("--scenario-seeds", type=int, default=1,
                    help="seeds 0..N-1 of each shipped scenario (their random movers and obstacles; default 1)")
    ap.add_argument("--stop-hold", type=float, default=0.0,
                    help="program solvers: their default program with stop_clear for this many seconds "
                         "(0: the default program as it is)")
    ap.add_argument("--as-file", action="store_true",
                    help="run each generated world as its scenario file would (the Scenario object, without the "
                         "family's options such as its global clearance)")
    args = ap.parse_args(argv)
    global STOP_SWEEP, STOP_COST
    STOP_SWEEP, STOP_COST = not args.stop_straight, args.stop_cost
    args.worlds = [w for name in args.worlds for w in (PAPER_SCENARIOS if name == "papers" else (name,))]
    t0 = time.perf_counter()
    rows = run(args.solvers, args.worlds, args.seeds, args.seed0, args.stop_hold, args.as_file, args.scenario_seeds,
               args.horizon)
    print(f"\nfamilies: seeds {args.seed0}..{args.seed0 + args.seeds - 1}; {time.perf_counter() - t0:.0f} s")
    print("| world | solver | success | collided | timeout | stuck | time to goal s | length m | BARN | "
          "step ms median | p95 | limits held | fallback-to-sample steps |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for (world, name), r in rows.items():
        n = len(r["status"])
        ok = np.array(r["ok"])
        med = lambda a: f"{np.median(np.array(a)[ok]):.1f}" if ok.any() else "-"  # noqa: E731
        steps = np.array(r["steps_ms"])
        print(f"| {world} | {name} | {ok.sum()}/{n} | {sum(r['collided'])} | {r['status'].count('timeout')} | "
              f"{r['status'].count('stuck')} | {med(r['time'])} | {med(r['length'])} | {np.mean(r['barn']):.3f} | "
              f"{np.median(steps):.1f} | {np.percentile(steps, 95):.1f} | {sum(r['limits'])}/{n} | "
              f"{np.mean(r['fallback']) * 100:.1f} % |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
