"""Repeated closed-loop runs and the paper-style tables of the example scripts' ``--part local``.

:func:`run_local` runs every scenario x local planner over seeds ``0 .. runs-1``. For
one scenario and seed the global plan (the slow part with a metaheuristic) is made
once and shared by every local planner, so the planners are compared on the same
global path and the same random obstacles. :func:`local_table` prints one row per
scenario and planner: success (goal reached with no collision), runs that reached
the goal, runs with a collision, timeouts, stuck runs, the means of time, path
length and local-planner step time over the successful runs (all runs when none
succeeded, marked so), and the BARN score (:func:`barn_score`). Nothing is hidden:
failing planners get their rows too. Generated scenario families (``"clutter"``,
``"clutter-movers"``) are drawn anew for every seed.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass, field

import numpy as np

from ..results import SimResult


@dataclass
class LocalRuns:
    """All runs of one local planner on one scenario."""

    scenario: str
    planner: str
    results: list[SimResult] = field(default_factory=list)
    error: str = ""
    optimal_times: list[float] = field(default_factory=list)  # OT of each run, s (see barn_score)

    @property
    def barn_scores(self) -> list[float]:
        """:func:`barn_score` of each run (runs without a known OT are left out)."""
        return [barn_score(r, ot) for r, ot in zip(self.results, self.optimal_times)]

    @property
    def successes(self) -> list[SimResult]:
        return [r for r in self.results if r.reached and r.collisions == 0]


def barn_score(result: SimResult, optimal_time: float) -> float:
    """The BARN benchmark's score of one run (Perille et al. 2020; issue 27's form):
    ``1{success} * OT / clip(AT, 2 OT, 8 OT)``, with ``AT`` the run's time and ``OT`` the
    optimal traversal time (the shortest path for the footprint over ``v_max``). A run that
    reaches the goal without collision in at most twice OT scores 0.5; slower runs score
    less, down to 0.125 at 8 OT and beyond; failed runs score 0."""
    if not (result.reached and result.collisions == 0) or not optimal_time > 0:
        return 0.0
    return float(optimal_time / np.clip(result.time_s, 2 * optimal_time, 8 * optimal_time))


def optimal_time(plan_result, robot) -> float:
    """BARN's OT of a run, s: the length of its initial global plan (A* with the robot radius
    as clearance in the closed loop) over ``robot.v_max``."""
    return float(plan_result.length) / float(robot.v_max)


def plan_global(scenario, global_planner: str = "astar", refine=None, seed: int = 0, global_options: dict | None = None):
    """The global plan ``op.simulate`` would make for ``scenario`` and ``seed`` (a PlanResult to
    pass back as ``global_plan=``, so several local planners share it)."""
    from ..nav.navigator import Navigator

    nav = Navigator(scenario.world, scenario.robot, scenario.start[:2], scenario.goal, global_planner=global_planner,
                    refine=refine, seed=seed, global_options=dict(global_options or {}))
    return nav.plan_initial()


_plan_once = plan_global  # the benchmark runner's name for it


def run_local(scenarios, planners, runs: int, global_planner: str = "astar", refine=None, seed0: int = 0,
              global_options: dict | None = None, progress: bool = True, **options) -> list[LocalRuns]:
    """Run each scenario with each local planner for ``runs`` seeds.

    Args:
        scenarios: names or paths of scenario files (or Scenario objects).
        planners: local planner names.
        runs: seeds ``seed0 .. seed0 + runs - 1``.
        global_planner, refine, global_options: the shared global plan of each seed.
        progress: a counter on stderr.
        **options: passed to ``op.simulate`` for every run.

    Returns:
        One :class:`LocalRuns` per scenario and planner, in that order.
    """
    from ..errors import OptplanError
    from ..worldgen.clutter import FAMILIES, family_options
    from .closed_loop import scenario_for, simulate

    out: list[LocalRuns] = []
    for spec in scenarios:
        generated = isinstance(spec, str) and spec.lower() in FAMILIES
        sc = None if generated else scenario_for(spec)
        name = spec.lower() if generated else sc.name
        sets = {p: LocalRuns(name, p) for p in planners}
        for k in range(runs):
            seed = seed0 + k
            if generated:
                sc = scenario_for(spec, seed)
            gp = plan_global(sc, global_planner, refine, seed,
                             global_options if global_options is not None or not generated
                             else family_options(spec).get("global_options"))
            for p in planners:
                if sets[p].error:
                    continue
                try:
                    sets[p].results.append(simulate(sc, global_planner=global_planner, local_planner=p, refine=refine,
                                                    seed=seed, global_plan=gp, **options))
                    sets[p].optimal_times.append(optimal_time(gp, sc.robot))
                except (ImportError, OptplanError) as exc:  # a planner that cannot run gets an honest row
                    sets[p].error = f"{type(exc).__name__}: {exc}"
            if progress:
                print(f"\r  {sc.name}: {k + 1}/{runs} seeds", end="", file=sys.stderr, flush=True)
        if progress:
            print(file=sys.stderr)
        out.extend(sets.values())
    return out


def local_table(sets: list[LocalRuns], title: str = "") -> str:
    """Markdown table of :func:`run_local` results."""
    lines = []
    if title:
        lines += [f"## {title}", ""]
    lines += ["| scenario | local planner | runs | success [%] | reached | with collision | timeouts | stuck | "
              "mean time [s] | mean path length [m] | mean step [ms] | min clearance [m] | BARN score |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in sets:
        if s.error and not s.results:
            lines.append(f"| {s.scenario} | {s.planner} | 0 | - | - | - | - | - | - | - | - | not run: "
                         f"{s.error.splitlines()[0][:80]} | - |")
            continue
        n = len(s.results)
        ok = s.successes
        pool, mark = (ok, "") if ok else (s.results, "*")
        reached = sum(r.reached for r in s.results)
        coll = sum(r.collisions > 0 for r in s.results)
        timeouts = sum(r.status == "timeout" for r in s.results)
        stuck = sum(r.status == "stuck" for r in s.results)
        t = np.mean([r.time_s for r in pool]) if pool else np.nan
        L = np.mean([r.path_length for r in pool]) if pool else np.nan
        ms = np.mean([r.mean_step_ms for r in s.results]) if n else np.nan
        mc = min(r.min_clearance for r in s.results) if n else np.nan
        scores = s.barn_scores
        barn = f"{np.mean(scores):.3f}" if scores else "-"
        lines.append(f"| {s.scenario} | {s.planner} | {n} | {100 * len(ok) / max(n, 1):.1f} | {reached} | {coll} | "
                     f"{timeouts} | {stuck} | {t:.1f}{mark} | {L:.2f}{mark} | {ms:.2f} | {mc:.3f} | {barn} |")
    lines += ["", "success = goal reached with no collision; time and length are means over successful runs "
                  "(* = no run succeeded: mean over all runs); min clearance is the worst over all runs; "
                  "BARN score = mean over all runs of 1{success} OT / clip(time, 2 OT, 8 OT), OT = initial "
                  "global path length / v_max (at most 0.5)."]
    return "\n".join(lines)


def path_switches(result: SimResult) -> int:
    """Path switches (yuan2021 §4.2) of a run: its ``path_switches`` field, or for a result
    rebuilt from a database written before that field existed, the count in its message."""
    if result.path_switches:
        return int(result.path_switches)
    import re

    m = re.search(r"(\d+) path switch", result.message)
    return int(m.group(1)) if m else 0


def available_planners(wanted=None) -> list[str]:
    """Local planner names from ``optplan.local`` (all of them, or those of ``wanted`` that exist;
    unknown ones are kept so their rows say why they did not run)."""
    from ..local import algorithm_names

    return list(wanted) if wanted else list(algorithm_names())


def paper_local(title: str, scenarios, runs: int, planners=None, global_planner: str = "astar",
                global_options: dict | None = None, **options) -> list[LocalRuns]:
    """Run :func:`run_local` and print its table under ``title`` (the example scripts' helper)."""
    names = available_planners(planners)
    print(f"global planner: {global_planner} {global_options or ''}; seeds 0..{runs - 1}; "
          f"local planners: {', '.join(names)}\n", flush=True)
    sets = run_local(scenarios, names, runs, global_planner=global_planner, global_options=global_options, **options)
    print(local_table(sets, title))
    print(flush=True)
    return sets

