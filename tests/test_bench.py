"""Experiment specs, the runner, the results database, summaries and the bench/reproduce commands."""
from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from optplan.bench.runner import execute_run, run_records
from optplan.bench.spec import load_spec
from optplan.bench.store import ResultStore
from optplan.bench.summary import load_results, summary_tables
from optplan.cli import main
from optplan.errors import ParameterError, ScenarioError, UnknownAlgorithmError

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

SMALL = {
    "name": "small", "kind": "plan", "maps": ["chen2025_20"],
    "algorithms": ["msiar-gwo", "gwo", {"name": "pso", "label": "pso-broken", "params": {"postprocess": "no_such_param"}}],
    "params": {"pop": 20, "iters": 25}, "runs": 3, "reference": "msiar-gwo",
}
# metrics that depend on the clock or the process, not on the seed
CLOCK = {"runtime_s", "wall_s", "worker", "finished_at", "mean_step_ms", "reroute_s"}


def same_numbers(rows_a: dict, rows_b: dict) -> None:
    assert rows_a.keys() == rows_b.keys()
    for k in rows_a:
        a = {c: v for c, v in rows_a[k].items() if c not in CLOCK}
        b = {c: v for c, v in rows_b[k].items() if c not in CLOCK}
        assert a == b, k


# ----------------------------------------------------------------------------- specs
def test_expansion_gives_distinct_stable_keys_and_own_seeds():
    spec = load_spec(SMALL)
    recs = spec.expand()
    assert len(recs) == 9 and [r.seed for r in recs[:3]] == [0, 1, 2]
    assert len({r.key for r in recs}) == 9
    assert [r.key for r in load_spec(SMALL).expand()] == [r.key for r in recs]  # stable across loads
    # the key describes the run, not its presentation: label and experiment name do not enter it
    relabelled = load_spec({**SMALL, "name": "other", "algorithms": [{"name": "msiar-gwo", "label": "M"}],
                            "reference": "M"})
    assert relabelled.expand()[0].key == recs[0].key
    # a budget change is a different run
    assert load_spec({**SMALL, "params": {"pop": 20, "iters": 26}}).expand()[0].key != recs[0].key


def test_quick_runs_and_per_algorithm_overrides():
    raw = {**SMALL, "algorithms": ["gwo", {"name": "astar", "runs": 1}], "reference": None,
           "quick": {"runs": 2, "params": {"iters": 5}}}
    full, quick = load_spec(raw), load_spec(raw, quick=True)
    assert full.runs == 3 and quick.runs == 2
    assert quick.algorithms[0].params == {"pop": 20, "iters": 5}
    assert [r.algorithm for r in quick.expand()] == ["gwo", "gwo", "astar"]
    assert load_spec(raw, quick=True, runs=4).runs == 4
    assert load_spec({**raw, "seeds": [7, 3], "runs": None}).seeds == [7, 3]


def test_shipped_specs_load_for_every_paper():
    from optplan.bench.spec import shipped_specs

    papers = ("hou2024", "yang2023", "yuan2021", "li2023", "chen2025")
    names = shipped_specs()
    for paper in papers:
        assert any(n.startswith(paper) for n in names), paper
    for n in names:
        spec = load_spec(n, quick=True)
        assert spec.expand()
        if n.split("_")[0] in papers:   # the others are examples (programs_example.yaml), in no paper
            assert spec.paper == n.split("_")[0]
        else:
            assert spec.paper is None


def test_benchmark_specs_load_and_the_held_out_seeds_are_disjoint_from_the_main_ones():
    bench = EXAMPLES.parent / "benchmarks"
    specs = {p.stem: load_spec(p) for p in sorted(bench.glob("*.yaml"))}
    assert {"dynamic_qp_dwa", "dynamic_qp_dwa_heldout", "dynamic_presets"} <= set(specs)
    main, held = specs["dynamic_qp_dwa"], specs["dynamic_qp_dwa_heldout"]
    assert len(held.seeds) == len(main.seeds) == 50 and not set(held.seeds) & set(main.seeds)
    same_runs = [(r.target, r.local_planner, r.params) for r in main.expand()]
    assert same_runs == [(r.target, r.local_planner, r.params) for r in held.expand()]  # only the seeds differ
    assert {r.target for r in specs["dynamic_presets"].expand()} == {r.target for r in main.expand()}


@pytest.mark.parametrize("change,error,needle", [
    ({"algoritms": ["gwo"]}, ScenarioError, "unknown key(s) 'algoritms'"),
    ({"algorithms": ["nope"]}, UnknownAlgorithmError, "unknown algorithm 'nope'"),
    ({"algorithms": ["dwa"]}, UnknownAlgorithmError, "unknown algorithm 'dwa'"),  # a local planner is no global one
    ({"runs": 0}, ParameterError, "runs must be a positive integer"),
    ({"seed": -1}, ParameterError, "non-negative"),
    ({"reference": "woa"}, ParameterError, "reference 'woa' is not one of"),
    ({"maps": ["atlantis"]}, ScenarioError, "unknown paper map 'atlantis'"),
    ({"maps": [{"map": "arena", "start": [1.5, 37.5]}]}, ScenarioError, "needs 'map', 'start' and 'goal'"),
    ({"functions": ["F1"]}, ScenarioError, "'functions' belongs to kind 'optimize'"),
    ({"refine": ["smooth"]}, ParameterError, "refine must be one of"),
    ({"params": {"pop": 0}}, ParameterError, "pop must be a positive integer"),
    ({"params": {"seed": 3}}, ScenarioError, "set by the spec grid"),
    ({"algorithms": ["gwo", "gwo"], "reference": None}, ScenarioError, "labels repeat"),
    ({"kind": "simulate", "maps": None, "scenarios": ["s.yaml"], "local_planners": ["dwa"]}, ScenarioError,
     "scenario 's.yaml' is neither a file"),
])
def test_bad_specs_say_what_is_wrong(change, error, needle):
    with pytest.raises(error) as exc:
        load_spec({**SMALL, **change})
    assert needle in str(exc.value)


def test_bad_spec_files(tmp_path):
    with pytest.raises(ScenarioError, match="not found"):
        load_spec(tmp_path / "missing.yaml")
    (tmp_path / "bad.yaml").write_text("kind: plan\nmaps: [chen2025_20\n")
    with pytest.raises(ScenarioError, match="not valid YAML"):
        load_spec(tmp_path / "bad.yaml")
    (tmp_path / "sc.yaml").write_text("map: [[0, 0], [0, 0]]\n")
    (tmp_path / "loop.yaml").write_text("kind: simulate\nscenarios: [sc.yaml]\nalgorithms: [astar]\n")
    with pytest.raises(ScenarioError, match="needs 'local_planners'"):
        load_spec(tmp_path / "loop.yaml")
    (tmp_path / "list.yaml").write_text("- a\n- b\n")
    with pytest.raises(ScenarioError, match="must be a YAML mapping"):
        load_spec(tmp_path / "list.yaml")


# ----------------------------------------------------------------------------- runner and store
def test_pool_and_in_process_runs_give_the_same_numbers_and_failures_are_recorded(tmp_path):
    recs = load_spec(SMALL).expand()
    serial, pooled = ResultStore(tmp_path / "a.sqlite"), ResultStore(tmp_path / "b.sqlite")
    rep = run_records(recs, serial, workers=1, progress=False)
    assert (rep.ran, rep.failed) == (9, 3)
    rep = run_records(recs, pooled, workers=2, progress=False)
    assert (rep.ran, rep.failed) == (9, 3)
    rows = serial.rows()
    same_numbers(rows, pooled.rows())
    broken = [r for r in rows.values() if r["label"] == "pso-broken"]
    assert all(r["status"] == "failed" and "no_such_param" in r["error"] for r in broken)
    ok = [r for r in rows.values() if r["status"] == "ok"]
    assert len(ok) == 6 and all(r["feasible"] == 1 and r["length"] > 27.59 for r in ok)
    # every stored path passes the exact check and its length is the stored one
    import optplan as op
    from optplan.world.papermaps import paper_map

    world = paper_map("chen2025_20")[0]
    for k, t in serial.traces([r["key"] for r in ok]).items():
        path = np.asarray(t["path"])
        assert op.validate_path(world, path)
        assert np.isclose(np.linalg.norm(np.diff(path, axis=0), axis=1).sum(), rows[k]["length"])
        assert len(t["history"]) == 26  # initial population + 25 iterations


def test_rerun_skips_stored_runs_and_csv_has_parameter_and_metric_columns(tmp_path):
    db = tmp_path / "r.sqlite"
    spec = load_spec({**SMALL, "algorithms": ["gwo"], "reference": None})
    recs = spec.expand()
    with ResultStore(db) as store:
        assert run_records(recs[:1], store, workers=1, progress=False).ran == 1
    with ResultStore(db) as store:
        first = store.rows()
        rep = run_records(recs, store, workers=1, progress=False)
        assert (rep.skipped, rep.ran) == (1, 2)
        assert store.rows(first)[recs[0].key]["finished_at"] == first[recs[0].key]["finished_at"]
        assert run_records(recs, store, workers=1, progress=False).ran == 0
        assert store.to_csv(tmp_path / "out.csv") == 3
    with open(tmp_path / "out.csv") as fh:
        table = list(csv.DictReader(fh))
    assert {"key", "seed", "status", "param_pop", "param_iters", "length", "feasible", "nfev"} <= set(table[0])
    assert sorted(int(r["seed"]) for r in table) == [0, 1, 2] and {r["param_iters"] for r in table} == {"25"}


def test_a_rerun_says_when_stored_runs_were_made_by_other_code(tmp_path, monkeypatch):
    """The database keys a run on its spec and inputs, not on the code: a rerun after an edit
    reuses the old results, and says so."""
    import optplan.bench.store as store_module

    db = tmp_path / "r.sqlite"
    recs = load_spec({**SMALL, "algorithms": ["gwo"], "reference": None}).expand()
    with ResultStore(db) as store:
        run_records(recs[:2], store, workers=1, progress=False)
        assert set(r["code"] for r in store.rows().values()) == {store_module.code_fingerprint()}
        same = run_records(recs, store, workers=1, progress=False)
        assert (same.skipped, same.other_code) == (2, 0) and "other optplan code" not in same.describe()
    monkeypatch.setattr(store_module, "code_fingerprint", lambda: "edited")
    with ResultStore(db) as store:
        rep = run_records(recs, store, workers=1, progress=False)
    assert (rep.skipped, rep.other_code, rep.ran) == (3, 3, 0)
    assert "3 of the runs already stored were made by other optplan code" in rep.describe()


def test_execute_run_reports_exceptions_as_failed_runs():
    rec = load_spec({**SMALL, "algorithms": [{"name": "gwo", "params": {"postprocess": "no_such_param"}}],
                     "reference": None}).expand()[0]
    out = execute_run(rec.to_dict())
    assert out["status"] == "failed" and out["error"].startswith("ParameterError") and out["key"] == rec.key


def test_optimize_runs_store_error_to_the_known_optimum():
    spec = load_spec({"kind": "optimize", "functions": ["F15"], "algorithms": ["gwo"], "runs": 2,
                      "params": {"pop": 20, "max_evals": 600, "iters": None}})
    store = ResultStore()
    run_records(spec.expand(), store, workers=1, progress=False)
    rows = list(store.rows().values())
    assert all(r["nfev"] == 600 and r["f_error"] == pytest.approx(r["f"] - 0.39788735772973816) for r in rows)
    assert all(0 <= r["f_error"] < 0.05 for r in rows)


# ----------------------------------------------------------------------------- summaries
def test_summary_tables_have_gap_reference_and_tally():
    spec = load_spec({**SMALL, "runs": 5})
    store = ResultStore()
    run_records(spec.expand(), store, workers=1, progress=False)
    res = load_results(spec, store)
    per_map, tally = summary_tables(res)
    md = per_map.markdown()
    assert "best gap [%]" in md and "exact optimum (any-angle, same start/goal): 27.5990 m" in md
    # issue 26: the gap split into the class gap and the in-class gap, and the optimal-class share
    col = {h: i for i, h in enumerate(per_map.header)}
    for r in per_map.rows:
        if r[col["mean gap [%]"]] != "-":
            split = float(r[col["mean class gap [%]"]]) + float(r[col["mean in-class gap [%]"]])
            assert split == pytest.approx(float(r[col["mean gap [%]"]]), abs=0.02)
            assert "/" in r[col["optimal class"]]
    row = {r[0]: r for r in per_map.rows}
    assert row["msiar-gwo"][-1] == "ref" and row["pso-broken"][1:4] == ["5/5", "5", "0/5"]
    assert row["gwo"][-1] in "+=-"
    lengths = res.values(res.groups("chen2025_20")[("gwo", None, None)])
    assert row["gwo"][5] == f"{lengths.mean():.4f}"
    assert [r[0] for r in tally.rows] == ["gwo", "pso-broken"]
    tex = per_map.latex()
    assert r"\begin{tabular}" in tex and r"\toprule" in tex and "pso-broken" in tex
    assert r"best gap [\%]" in tex  # LaTeX specials escaped


def test_plots_are_written(tmp_path):
    from optplan.bench import render_report, run_experiment
    from optplan.viz.experiment_plots import experiment_plots

    res = run_experiment({**SMALL, "algorithms": ["gwo", "msiar-gwo"]}, workers=1, progress=False)
    assert len(res.rows) == 6 and res.missing == 0
    tex = render_report(res, fmt="latex")
    assert tex.startswith("% small") and r"\end{table}" in tex and "##" not in tex
    files = experiment_plots(res, tmp_path)
    assert sorted(f.name for f in files) == ["small_chen2025_20_box.png", "small_chen2025_20_convergence.png",
                                             "small_chen2025_20_paths.png"]
    assert all(f.stat().st_size > 5000 for f in files)


# ----------------------------------------------------------------------------- command line
def test_bench_command_writes_db_csv_and_latex(tmp_path, capsys):
    spec = tmp_path / "s.yaml"
    spec.write_text("kind: plan\nmaps: [chen2025_20]\nalgorithms: [gwo, msiar-gwo]\nparams: {pop: 20, iters: 20}\n"
                    "runs: 3\nreference: gwo\n")
    db, out = tmp_path / "r.sqlite", tmp_path / "r.csv"
    args = [str(spec), "--db", str(db), "--workers", "1", "--csv", str(out), "--no-progress"]
    assert main(["bench", *args]) == 0
    cap = capsys.readouterr()
    assert "| msiar-gwo | 3/3 | 0 | 3/3 |" in cap.out and "6 ran (0 failed)" in cap.err
    assert len(out.read_text().splitlines()) == 7
    assert main(["bench", *args, "--format", "latex"]) == 0
    cap = capsys.readouterr()
    assert r"\begin{tabular}" in cap.out and "6 already in the database, 0 ran" in cap.err


def test_bench_command_errors_exit_2(tmp_path, capsys):
    spec = tmp_path / "s.yaml"
    spec.write_text("kind: plan\nmaps: [chen2025_20]\nalgorithms: [gwo]\nrunz: 3\n")
    assert main(["bench", str(spec), "--db", str(tmp_path / "r.sqlite")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "unknown key(s) 'runz'" in err
    spec.write_text("kind: plan\nmaps: [chen2025_20]\nalgorithms: [gwo]\nruns: 1\n")
    assert main(["bench", str(spec), "--db", str(tmp_path / "r.sqlite"), "--executor", "spark://x"]) == 2
    assert "unknown executor 'spark://x'" in capsys.readouterr().err
    assert main(["reproduce", "chen2025", "--part", "nope"]) == 2
    assert "its parts: functions, paths" in capsys.readouterr().err


def test_reproduce_prints_the_example_scripts_numbers(tmp_path, capsys):
    """``optplan reproduce chen2025 --quick --part paths`` and the example script agree run for run
    (every cell except the wall times)."""
    assert main(["reproduce", "chen2025", "--quick", "--part", "paths", "--workers", "1", "--no-progress"]) == 0
    ours = capsys.readouterr().out
    ex = subprocess.run([sys.executable, str(EXAMPLES / "chen2025_msiar_gwo.py"), "--part", "paths", "--quick",
                         "--out", str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert ex.returncode == 0, ex.stderr[-2000:]
    for needle in ("Tables 9-11 analog", "Table 8 analog", "### chen2025_20", "exact optimum", "p vs msiar-gwo"):
        assert needle in ours

    def cells(text):
        rows, head = [], None
        for line in text.splitlines():
            if line.startswith("|") and not line.startswith("|---"):
                c = [x.strip() for x in line.strip("|").split("|")]
                if c[0] in ("algorithm", "map"):
                    head = c
                rows.append(tuple(v for v, h in zip(c, head) if "time" not in h))
        return sorted(rows)

    # 12 algorithm rows (A* is Table 8's; msiar-gwo-evals at GWO's evaluations; agwo and rsmgwo), one Table 8
    # row and 61 claims (§4.3.2's seven lead trends and their combination among them; with their three header rows)
    assert cells(ours) == cells(ex.stdout) and len(cells(ours)) == 77


def test_closed_loop_runs_through_simulate(tmp_path):
    (tmp_path / "tiny.yaml").write_text(
        "map: [[0,0,0,0,0,0],[0,0,1,1,0,0],[0,0,0,0,0,0],[0,0,0,0,0,0]]\nresolution: 1.0\n"
        "robot: {model: unicycle, radius: 0.2, v_max: 1.0, w_max_deg: 60, a_max: 0.5, alpha_max_deg: 90}\n"
        "start: [0.5, 0.5, 0]\ngoal: [5.5, 3.5]\nsensor_range: 3.0\ndt: 0.1\ntime_limit: 6\n")
    spec_file = tmp_path / "loop.yaml"
    spec_file.write_text("kind: simulate\nscenarios: [tiny.yaml]\nalgorithms: [astar]\nlocal_planners: [dwa, idwa]\n"
                         "runs: 2\nreport: closed-loop\nreference: {algorithm: astar, local_planner: idwa}\n")
    spec = load_spec(spec_file)
    store = ResultStore()
    rep = run_records(spec.expand(), store, workers=1, progress=False)
    rows = store.rows()
    assert rep.ran == 4 and all(r["status"] == "ok" for r in rows.values()), [r["error"] for r in rows.values()]
    # the runner shares one global plan per seed between local planners: no number changes
    import optplan as op

    for rec in spec.expand()[:2]:
        direct = op.simulate(str(tmp_path / "tiny.yaml"), global_planner="astar", local_planner=rec.local_planner,
                             seed=rec.seed)
        row = rows[rec.key]
        assert (row["time_s"], row["path_length"], row["steps"], row["result_status"]) == \
            (direct.time_s, direct.path_length, direct.steps, direct.status)
        assert bool(row["reached"]) == direct.reached and row["collisions"] == direct.collisions
    traj = next(iter(store.traces([rec.key]).values()))["trajectory"]
    assert len(traj[0]) == 6
    from optplan.bench.reports import render_report

    res = load_results(spec, store)
    text = render_report(res)
    assert "### tiny" in text and "collision-free" in text and "astar/dwa" in text
    local = render_report(res, layout="local")
    assert "| tiny | dwa | 2 |" in local and "| tiny | idwa | 2 |" in local


@pytest.mark.slow
def test_full_chen2025_paths_reproduction(tmp_path, capsys):
    """Full Tables 8-11 analog (480 runs): every run feasible and
    MSIAR-GWO's best path within 1 % of the exact optimum and shorter than A* on every map.
    The CI version is test_reproduce_prints_the_example_scripts_numbers."""
    assert main(["reproduce", "chen2025", "--part", "paths", "--no-progress", "--db", str(tmp_path / "c.sqlite")]) == 0
    out = capsys.readouterr().out
    assert out.count("| 20/20 |") == 24   # 8 rows (6 paper-protocol, 2 -fair) x 3 maps
    table8 = [line for line in out.splitlines() if line.startswith("| chen2025_")]
    assert len(table8) == 3
    for line in table8:
        astar, best, optimum = (float(c) for c in line.strip("|").split("|")[1:4])
        assert optimum <= best < min(1.01 * optimum, astar)


def test_closed_loop_report_pools_scenarios_and_pairs_runs_by_seed(tmp_path):
    """The "all scenarios" table of the closed-loop report: success pooled over scenarios with
    its Wilson interval, and the McNemar test on runs paired by scenario and seed (rows are
    written by hand here, so every count is known)."""
    from optplan.bench.reports import closed_loop_overall, render_report
    from optplan.bench.summary import ExperimentResults

    spec_file = tmp_path / "pooled.yaml"
    spec_file.write_text("kind: simulate\nscenarios: [li2023_exp2_2, yang2023_idwa_crossing]\nalgorithms: [astar]\n"
                         "local_planners: [dwa, qp-dwa]\nruns: 4\nreport: closed-loop\n"
                         "reference: {algorithm: astar, local_planner: qp-dwa}\n")
    spec = load_spec(spec_file)
    recs = spec.expand()
    rows = {}
    for r in recs:
        # qp-dwa succeeds everywhere; dwa only on seed 0 of each scenario and collides on seed 1;
        # run 3 of dwa on the second scenario was never stored
        first = r.target == "li2023_exp2_2"
        k = sorted({x.seed for x in recs if x.target == r.target}).index(r.seed)
        if r.local_planner == "dwa" and not first and k == 3:
            continue
        good = r.local_planner == "qp-dwa" or k == 0
        rows[r.key] = {"status": "ok", "reached": good or k == 1, "collisions": 0 if good else int(k == 1),
                       "result_status": "reached" if good or k == 1 else "timeout"}
    res = ExperimentResults(spec, recs, rows)
    table = closed_loop_overall(res)
    by_name = {row[0]: row for row in table.rows}
    dwa, qp = by_name["astar/dwa"], by_name["astar/qp-dwa"]
    assert dwa[1:4] == ["7/8", "2/7", "28.6"] and dwa[5:8] == ["4/7", "5/7", "3/7"]
    assert qp[1:4] == ["8/8", "8/8", "100.0"] and qp[8] == "ref"
    # the 7 shared pairs: qp-dwa alone succeeds in 5, dwa alone in none
    assert dwa[8] == "5 / 0" and float(dwa[9]) == pytest.approx(2 * 0.5 ** 5)
    lo, hi = (float(x) for x in dwa[4].split("-"))
    assert (lo, hi) == pytest.approx((8.2, 64.1), abs=0.1)  # Wilson 95 % for 2/7
    assert "### all scenarios" in render_report(res)


# ----------------------------------------------------------------------------- stale results
def _write_rows(path: Path, wall: bool) -> None:
    rows = [[0] * 10 for _ in range(10)]
    if wall:  # a wall across the middle with a gap at the right edge: a long detour
        rows[5] = [1] * 9 + [0]
    path.write_text("\n".join(" ".join(map(str, r)) for r in rows) + "\n")


def test_editing_the_map_file_between_two_runs_makes_the_second_recompute(tmp_path):
    # the key used to hash the file's path, so a rerun served the result of the old map
    map_file = tmp_path / "room.txt"
    _write_rows(map_file, wall=False)
    raw = {"kind": "plan", "algorithms": ["astar"], "runs": 1,
           "maps": [{"name": "room", "map": str(map_file), "start": [0.5, 0.5], "goal": [0.5, 9.5]}]}
    store = ResultStore(tmp_path / "runs.sqlite")
    first = load_spec(raw).expand()
    assert run_records(first, store, workers=1, progress=False).ran == 1
    assert run_records(load_spec(raw).expand(), store, workers=1, progress=False).ran == 0  # unchanged: resumed
    _write_rows(map_file, wall=True)
    second = load_spec(raw).expand()
    assert second[0].key != first[0].key
    assert run_records(second, store, workers=1, progress=False).ran == 1
    rows = store.rows([first[0].key, second[0].key])
    assert rows[first[0].key]["length"] == pytest.approx(9.0)
    assert rows[second[0].key]["length"] > 17.0  # planned on the edited map, not on a cached copy
    _write_rows(map_file, wall=False)  # back to the old content: the old stored result is valid again
    assert [r.key for r in load_spec(raw).expand()] == [first[0].key]


def test_a_simulate_key_follows_the_scenario_and_the_map_it_references(tmp_path):
    map_file = tmp_path / "room.txt"
    _write_rows(map_file, wall=False)
    scenario = tmp_path / "s.yaml"
    text = "map: room.txt\nstart: [0.5, 0.5, 90]\ngoal: [0.5, 9.5]\ntime_limit: 60\n"
    scenario.write_text(text)
    raw = {"kind": "simulate", "scenarios": [str(scenario)], "algorithms": ["astar"], "local_planners": ["dwa"],
           "runs": 1}
    store = ResultStore(tmp_path / "runs.sqlite")
    first = load_spec(raw).expand()
    assert run_records(first, store, workers=1, progress=False).ran == 1
    _write_rows(map_file, wall=True)
    second = load_spec(raw).expand()
    assert second[0].key != first[0].key
    assert run_records(second, store, workers=1, progress=False).ran == 1
    rows = store.rows([first[0].key, second[0].key])
    # driven on the walled map (a cached copy of the open one would repeat the first run exactly)
    assert abs(rows[second[0].key]["path_length"] - rows[first[0].key]["path_length"]) > 0.5
    scenario.write_text(text.replace("time_limit: 60", "time_limit: 50"))
    assert load_spec(raw).expand()[0].key not in (first[0].key, second[0].key)


def test_the_inputs_of_shipped_targets_and_ros_maps_are_found(tmp_path):
    from optplan.bench.kinds import get_kind
    from optplan.world.loaders import load_map, save_map

    def input_files(kind, target):
        return get_kind(kind).input_files(target)

    def inputs_digest(kind, target):
        return get_kind(kind).inputs_digest(target)

    files = input_files("simulate", {"scenario": "hou2024_dynamic1"})
    assert [role for role, _ in files] == ["scenario", "map"] and all(p is not None and p.is_file() for _, p in files)
    assert [role for role, _ in input_files("plan", {"paper_map": "chen2025_20"})] == ["map"]
    assert inputs_digest("optimize", {"function": "F1"}) == ""
    save_map(load_map("arena"), tmp_path / "arena.yaml")   # metadata + a .pgm image beside it
    target = {"map": str(tmp_path / "arena.yaml"), "start": [1.5, 37.5], "goal": [40.5, 10.5]}
    assert [p.name for _, p in input_files("plan", target)] == ["arena.yaml", "arena.pgm"]
    before = inputs_digest("plan", target)
    image = tmp_path / "arena.pgm"
    data = bytearray(image.read_bytes())
    data[-1] ^= 0xFF   # one pixel of the image changes; the metadata file does not
    image.write_bytes(bytes(data))
    assert inputs_digest("plan", target) != before


def test_gap_is_measured_against_the_optimum_at_the_runs_clearance():
    """A spec planning with params.clearance compares its lengths with the optimum at that
    clearance: the visibility planner itself then has gap 0 (against the clearance-0 optimum
    it would look several per cent worse)."""
    from optplan.bench.experiment import run_experiment
    from optplan.bench.summary import exact_optimum_of

    spec = {"kind": "plan", "maps": ["chen2025_20"], "algorithms": [{"name": "visibility", "runs": 1}],
            "params": {"clearance": 0.3}, "runs": 1}
    res = run_experiment(spec, workers=1, progress=False)
    table = summary_tables(res)[0]
    col = table.header.index("mean gap [%]")
    assert table.rows[0][col] == "0.00"
    target = res.spec.targets[0].spec
    assert exact_optimum_of(target, 0.3) > exact_optimum_of(target)
    assert any("at clearance 0.3 m" in n for n in table.notes)


def test_a_metaheuristic_option_shared_with_a_graph_search_is_refused_at_load(tmp_path):
    """A* takes none of the swarms' options; shared with it, every A* run would fail, so the spec
    is refused when it is loaded, naming them."""
    f = tmp_path / "mixed.yaml"
    f.write_text("kind: plan\nmaps: [chen2025_20]\nalgorithms: [gwo, {name: astar, runs: 1}]\n"
                 "params: {pop: 10, iters: 5, constraint: penalty}\nruns: 1\n")
    with pytest.raises(ScenarioError, match="astar does not take the parameter.*constraint"):
        load_spec(f)
    f.write_text("kind: plan\nmaps: [chen2025_20]\n"
                 "algorithms: [{name: gwo, params: {constraint: penalty}}, {name: astar, runs: 1}]\n"
                 "params: {pop: 10, iters: 5}\nruns: 1\n")
    assert {r.algorithm for r in load_spec(f).expand()} == {"gwo", "astar"}


def test_a_noisy_function_run_repeats_whatever_ran_before_it_in_the_process(tmp_path):
    """F7 adds noise; each run draws it from its own seeded generator, so a run gives the same
    value first in a worker or after other runs (the executor and worker count change nothing)."""
    from optplan.bench.kinds.optimize import OptimizeKind

    f = tmp_path / "f7.yaml"
    f.write_text("kind: optimize\nfunctions: [F7]\nalgorithms: [gwo]\nparams: {pop: 10, iters: 20}\nruns: 3\n")
    recs = load_spec(f).expand()
    first = OptimizeKind().run(recs[2])[0].f
    for r in recs[:2]:
        OptimizeKind().run(r)
    assert OptimizeKind().run(recs[2])[0].f == first


def test_a_metric_first_stored_as_none_keeps_the_later_runs_numbers(tmp_path):
    # a closed loop stores reroute_s only when a path was blocked: the column must not turn the
    # later runs' numbers into strings because its first value was None
    record = {"key": "k0", "experiment": "e", "kind": "simulate", "target": "t", "algorithm": "iba", "label": "iba",
              "refine": None, "local_planner": "ba-dwa", "seed": 0, "params": {}, "target_spec": {}}
    with ResultStore(tmp_path / "r.sqlite") as store:
        store.write(record, {"status": "ok", "metrics": {"reroute_s": None, "note": None}})
        store.write({**record, "key": "k1", "seed": 1}, {"status": "ok", "metrics": {"reroute_s": 0.0348, "note": "x"}})
        rows = store.rows()
    assert rows["k0"]["reroute_s"] is None and rows["k1"]["reroute_s"] == 0.0348
    assert rows["k1"]["note"] == "x"
