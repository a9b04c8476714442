"""qp-dwa's defaults against its clutter mechanisms (issue 43 item 1): success, collisions,
timeouts, stuck runs and time to goal, per suite of worlds and per setting.

Settings (``planner_params`` of qp-dwa, nothing else changes between them):

* ``default``: qp-dwa as shipped, no parameters;
* ``none``: the clutter mechanisms off (``path_samples`` empty, the path critics judged to the
  trajectory's end, no path creep);
* ``all``: all of them on wherever the robot is (issue 27's clutter parameters);
* ``samples``, ``until_stop``, ``creep``: one of them on, the others off.

Suites (every world is given as a Scenario object, as a scenario file would give it: no family
name, so no family parameters; A* global path unless the suite's paper spec names another):

* ``clutter`` / ``clutter-movers``: the BARN-style clutter worlds of
  :mod:`optplan.worldgen.clutter` (r 0.2 m, 0.15 m cells, 0.5 m/s), without and with 2 movers;
  ``--clutter-seeds`` (development used 3000-3099 and issue 27's 0-99; report held-out seeds);
* ``dynamic``: every shipped dynamic scenario of ``benchmarks/dynamic_qp_dwa.yaml``
  (``--dynamic-seeds``: 0:50 is that spec, 50:100 its held-out twin);
* ``paper``: the papers' local specs that run qp-dwa (``optplan/data/specs/*_local_*.yaml``)
  with their global planners, options and seeds;
* ``open``: open ground: an empty 20 m x 20 m map with 0 or 4 crossing movers, and the same map
  with 12 unknown 1 m blocks on the path and 4 movers (``--open-seeds``).

Runs are appended to ``--out`` (JSON lines) and skipped when already there; the table is
printed from the file. One process, one run at a time.

    python benchmarks/qp_dwa_defaults.py --suites clutter,clutter-movers --clutter-seeds 5000:5100 \\
        --settings default,none,all --out /tmp/qp_dwa_defaults.jsonl
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

# the clutter mechanisms, each on and off, as planner_params of qp-dwa
ON = {"samples": {"path_samples": (0.5, 1.0)},
      "until_stop": {"path_progress": {"until_stop": True}, "path_heading": {"until_stop": True},
                     "path_deviation": {"until_stop": True}},
      "creep": {"path_creep": {}}}
OFF = {"samples": {"path_samples": ()},
       "until_stop": {"path_progress": {"until_stop": False}, "path_heading": {"until_stop": False},
                      "path_deviation": {"until_stop": False}},
       "creep": {"path_creep": False}}


def setting_params(name: str) -> dict:
    """qp-dwa's ``planner_params`` of a setting (see the module docstring)."""
    if name == "default":
        return {}
    if name == "none":
        return {k: v for part in OFF.values() for k, v in part.items()}
    if name == "all":
        return {k: v for part in ON.values() for k, v in part.items()}
    if name in ON:
        return {k: v for m in ON for k, v in (ON if m == name else OFF)[m].items()}
    if name.startswith("{"):
        return json.loads(name)
    raise SystemExit(f"unknown setting {name!r}: default, none, all, {', '.join(ON)} or a JSON object")


DYNAMIC = ["hou2024_dynamic1", "hou2024_dynamic2", "hou2024_dynamic3", "hou2024_dynamic4",
           "li2023_exp2_2", "li2023_exp2_3", "li2023_exp2_4", "li2023_exp2_5",
           "yang2023_idwa_crossing", "yang2023_fusion"]
PAPER_SPECS = ["hou2024_local_dynamic", "hou2024_local_table4", "li2023_local_exp1", "li2023_local_exp2",
               "yang2023_local_crossing", "yang2023_local_fusion", "yuan2021_local_added", "yuan2021_local_switch"]
OPEN = ["open", "open-movers", "sparse-movers"]


def paper_targets() -> list[tuple[str, str, dict, list[int]]]:
    """``(scenario, global planner, simulate params, seeds)`` of every paper local spec running qp-dwa."""
    from optplan.world.loaders import read_yaml
    from importlib import resources

    out = []
    for name in PAPER_SPECS:
        spec = read_yaml(resources.files("optplan") / "data" / "specs" / f"{name}.yaml")
        if "qp-dwa" not in spec.get("local_planners", []):
            continue
        seeds = list(range(int(spec.get("seed", 0)), int(spec.get("seed", 0)) + int(spec.get("runs", 1))))
        for sc in spec["scenarios"]:
            for alg in spec["algorithms"]:
                out.append((sc, alg, dict(spec.get("params") or {}), seeds))
    return out


def open_scenario(name: str):
    """Open ground: an empty 20 m x 20 m map (1 m cells), the robot of li2023 Experiment II
    (r 0.2 m, 1 m/s, a_max 0.2); ``-movers``: 4 movers (r 0.35 m, 0.2-0.5 m/s, 2-4 m tracks)
    across the path; ``sparse``: 12 unknown 1 m blocks drawn on the path."""
    from optplan.world.grid import GridMap
    from optplan.world.robot import RobotSpec
    from optplan.world.scenario import Scenario

    robot = RobotSpec(model="unicycle", radius=0.2, v_max=1.0, w_max=math.radians(40), a_max=0.2,
                      alpha_max=math.radians(40))
    dyn = {"count": 4, "radius": 0.35, "speed": (0.2, 0.5), "length": (2.0, 4.0), "keep_away": 1.5} \
        if name.endswith("movers") else None
    obs = {"count": 12, "size": 1, "keep_away": 2.0} if name.startswith("sparse") else None
    return Scenario(GridMap(np.zeros((20, 20), dtype=bool), 1.0, name="empty20"), robot, (1.5, 1.5, 0.0),
                    (18.5, 18.5), sensor_range=3.0, dt=0.1, time_limit=120.0, random_dynamic=dyn,
                    random_obstacles=obs, name=name)


def tasks_of(suites, clutter_seeds, dynamic_seeds, open_seeds):
    """``(suite, scenario, seed, global planner, params)`` of every world to run."""
    out = []
    for suite in suites:
        if suite in ("clutter", "clutter-movers"):
            out += [(suite, suite, s, "astar", {}) for s in clutter_seeds]
        elif suite == "dynamic":
            out += [(suite, sc, s, "astar", {}) for sc in DYNAMIC for s in dynamic_seeds]
        elif suite == "paper":
            out += [(suite, sc, s, alg, params) for sc, alg, params, seeds in paper_targets() for s in seeds]
        elif suite == "open":
            out += [(suite, sc, s, "astar", {}) for sc in OPEN for s in open_seeds]
        else:
            raise SystemExit(f"unknown suite {suite!r}")
    return out


def scenario_of(suite: str, name: str, seed: int):
    from optplan.world.scenario import load_scenario
    from optplan.worldgen.clutter import clutter_scenario

    if suite.startswith("clutter"):
        return clutter_scenario(seed, movers=2 if suite == "clutter-movers" else 0)
    if suite == "open":
        return open_scenario(name)
    return load_scenario(name)


def run_world(task, settings: list[str], family_global: bool) -> list[dict]:
    """Every setting on one world, sharing its global plan: one row per run."""
    from optplan.sim.closed_loop import simulate
    from optplan.sim.experiments import plan_global
    from optplan.worldgen.clutter import BARN_ROBOT, GLOBAL_CLEARANCE_EXTRA

    suite, name, seed, alg, params = task
    sc = scenario_of(suite, name, seed)
    params = dict(params)
    if family_global and suite.startswith("clutter"):
        params["global_options"] = {"clearance": BARN_ROBOT.radius + GLOBAL_CLEARANCE_EXTRA}
    gp = plan_global(sc, alg, None, seed, {**sc.global_options, **(params.get("global_options") or {})})
    rows = []
    for setting in settings:
        tight = [0]

        def count(t, state, info, tight=tight):
            tight[0] += bool(info["command"].info.get("tight"))

        t0 = time.perf_counter()
        res = simulate(sc, global_planner=alg, local_planner="qp-dwa", seed=seed, global_plan=gp,
                       planner_params=setting_params(setting), progress=count, **params)
        rows.append({"suite": suite, "scenario": name, "seed": seed, "setting": setting,
                     "global": "family" if family_global and suite.startswith("clutter") else "default",
                     "status": res.status, "reached": bool(res.reached), "collisions": int(res.collisions),
                     "time_s": float(res.time_s), "path_length": float(res.path_length),
                     "min_clearance": float(res.min_clearance), "tight_steps": tight[0],
                     "wall_s": time.perf_counter() - t0})
    return rows


def table(rows: list[dict], settings: list[str]) -> str:
    """Markdown table: one row per suite, global clearance and setting."""
    out = ["| suite | global clearance | setting | runs | success [%] | with collision | timeouts | stuck | "
           "mean time to goal [s] | mean time, runs all settings reach [s] |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for suite in sorted({r["suite"] for r in rows}):
        for glob in sorted({r["global"] for r in rows if r["suite"] == suite}):
            rs = [r for r in rows if r["suite"] == suite and r["global"] == glob]
            ok = {}
            for r in rs:
                ok.setdefault((r["scenario"], r["seed"]), {})[r["setting"]] = r["reached"] and r["collisions"] == 0
            common = {k for k, v in ok.items() if all(v.get(s, False) for s in settings)}
            for setting in settings:
                sr = [r for r in rs if r["setting"] == setting]
                if not sr:
                    continue
                good = [r for r in sr if r["reached"] and r["collisions"] == 0]
                both = [r["time_s"] for r in good if (r["scenario"], r["seed"]) in common]
                mean = f"{np.mean([r['time_s'] for r in good]):.1f}" if good else "-"
                out.append(f"| {suite} | {glob} | {setting} | {len(sr)} | {100 * len(good) / len(sr):.1f} "
                           f"({len(good)}) | {sum(r['collisions'] > 0 for r in sr)} | "
                           f"{sum(r['status'] == 'timeout' for r in sr)} | {sum(r['status'] == 'stuck' for r in sr)} | "
                           f"{mean} | {f'{np.mean(both):.2f} ({len(both)})' if both else '-'} |")
    out += ["", "success = goal reached with no collision; time to goal over successful runs; the last column "
                "over the worlds every listed setting reaches (their number in brackets)."]
    return "\n".join(out)


def scenario_table(rows: list[dict], settings: list[str]) -> str:
    """Per scenario: successes of each setting (the suites with named scenarios)."""
    names = sorted({(r["suite"], r["scenario"]) for r in rows if not r["suite"].startswith("clutter")})
    if not names:
        return ""
    out = ["| suite | scenario | " + " | ".join(settings) + " |", "|---|---|" + "---|" * len(settings)]
    for suite, name in names:
        cells = []
        for s in settings:
            sr = [r for r in rows if r["suite"] == suite and r["scenario"] == name and r["setting"] == s]
            good = sum(r["reached"] and r["collisions"] == 0 for r in sr)
            cells.append(f"{good}/{len(sr)}" if sr else "-")
        out.append(f"| {suite} | {name} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def seeds_of(text: str) -> list[int]:
    if not text:
        return []
    lo, hi = (int(x) for x in text.split(":"))
    return list(range(lo, hi))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--suites", default="clutter,clutter-movers,dynamic,paper,open")
    ap.add_argument("--settings", default="default,none,all")
    ap.add_argument("--clutter-seeds", default="5000:5100", help="A:B (seeds A..B-1)")
    ap.add_argument("--dynamic-seeds", default="0:50")
    ap.add_argument("--open-seeds", default="0:20")
    ap.add_argument("--family-global", action="store_true",
                    help="clutter worlds planned with the family's global clearance (radius + 0.15 m)")
    ap.add_argument("--out", default="", help="JSON lines file to append to / resume from")
    ap.add_argument("--table-only", action="store_true", help="print the tables of --out and exit")
    a = ap.parse_args(argv)
    suites = [s.strip() for s in a.suites.split(",") if s.strip()]
    settings = [s.strip() for s in a.settings.split(",") if s.strip()]
    for s in settings:
        setting_params(s)
    glob = "family" if a.family_global else "default"
    tasks = tasks_of(suites, seeds_of(a.clutter_seeds), seeds_of(a.dynamic_seeds), seeds_of(a.open_seeds))
    path = Path(a.out) if a.out else None
    rows: list[dict] = []
    if path is not None and path.exists():
        rows = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    if not a.table_only:
        done = {(r["suite"], r["scenario"], r["seed"], r["setting"], r["global"]) for r in rows}
        sink = path.open("a") if path is not None else None
        for k, task in enumerate(tasks):
            g = glob if task[0].startswith("clutter") else "default"
            todo = [s for s in settings if (task[0], task[1], task[2], s, g) not in done]
            if todo:
                new = run_world(task, todo, a.family_global)
                rows += new
                if sink is not None:
                    sink.write("".join(json.dumps(r) + "\n" for r in new))
                    sink.flush()
            print(f"\r{k + 1}/{len(tasks)} worlds", end="", file=sys.stderr, flush=True)
        print(file=sys.stderr)
    keys = {(t[0], t[1], t[2]) for t in tasks}
    wanted = [r for r in rows if (r["suite"], r["scenario"], r["seed"]) in keys and r["setting"] in settings
              and (r["global"] == glob or not r["suite"].startswith("clutter"))]
    print(f"qp-dwa settings {', '.join(settings)}; clutter seeds {a.clutter_seeds}, dynamic seeds "
          f"{a.dynamic_seeds}, open seeds {a.open_seeds}; times are simulated seconds")
    print(table(wanted, settings))
    per = scenario_table(wanted, settings)
    if per:
        print("\n" + per)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
