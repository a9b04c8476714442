"""Bench specs of kind ``program``: a program named by the spec (``smoothing``, a paper
program or ``module:function``) built on each map and solved by program solvers and
chains through the runner and the results database."""
from __future__ import annotations

import json
import textwrap

import numpy as np
import pytest

from optplan.bench.runner import execute_run, run_records
from optplan.bench.spec import load_spec
from optplan.bench.store import ResultStore
from optplan.cli import main
from optplan.errors import ParameterError, ScenarioError, UnknownAlgorithmError

# a user program: a short, smooth path over dense points with clearance; WEIGHT is edited below
MODULE = '''
import optplan as op
from optplan import terms as T

WEIGHT = {weight}


def corridor(world, start, goal, n=12, clearance=0.0):
    prog = op.PathProgram(world, start, goal, variables=op.Points(n), name="corridor")
    prog.minimize(WEIGHT * (T.squared_length() + 0.5 * T.bending()))
    prog.subject_to(T.clearance() >= clearance)
    return prog


NOT_CALLABLE = 3


def not_a_program(world, start, goal):
    return "a path, honest"
'''

ROOM = "\n".join(" ".join("1" if (r == 4 and c < 6) else "0" for c in range(8)) for r in range(8)) + "\n"

SPEC = """\
name: tiny_programs
kind: program
program: {program}
args: {{n: 12}}
init: astar
maps:
  - li2023_11
  - {{name: room, map: room.txt, start: [0.5, 0.5], goal: [0.5, 7.5]}}
algorithms:
  - ipopt
  - osqp
  - {{name: pso, params: {{pop: 10}}}}
  - [pso, osqp]
params: {{max_evals: 200}}
runs: 2
reference: ipopt
"""


@pytest.fixture
def user_module(tmp_path, monkeypatch):
    """A module ``tiny_user_programs`` importable from sys.path, and a spec file using it."""
    import sys

    name = f"tiny_user_programs_{tmp_path.name.replace('-', '_')}"
    (tmp_path / f"{name}.py").write_text(MODULE.format(weight="1.0"))
    (tmp_path / "room.txt").write_text(ROOM)
    (tmp_path / "spec.yaml").write_text(SPEC.format(program=f"{name}:corridor"))
    monkeypatch.syspath_prepend(str(tmp_path))
    yield name, tmp_path
    sys.modules.pop(name, None)


def test_a_program_spec_runs_end_to_end_stores_its_rows_and_resumes(user_module):
    import optplan as op
    from optplan.bench.runner import plan_target

    name, folder = user_module
    spec = load_spec(folder / "spec.yaml")
    recs = spec.expand()
    # deterministic solvers once per map; pso and the chain (its first stage takes a seed) on both seeds
    per_map = [(r.algorithm, r.seed) for r in recs if r.target == "room"]
    assert per_map == [("ipopt", 0), ("osqp", 0), ("pso", 0), ("pso", 1), ("pso>osqp", 0), ("pso>osqp", 1)]
    assert len(recs) == 12 and len({r.key for r in recs}) == 12
    by = {(r.target, r.algorithm, r.seed): r for r in recs}
    # each solver gets the shared options it takes: ipopt has no max_evals
    assert by["room", "ipopt", 0].params == {} and by["room", "pso", 0].params == {"pop": 10, "max_evals": 200}
    assert by["room", "pso>osqp", 1].params == {"max_evals": 200}
    assert all(r.program == {"program": f"{name}:corridor", "args": {"n": 12}, "init": "astar"} for r in recs)

    db = folder / "runs.sqlite"
    with ResultStore(db) as store:
        rep = run_records(recs, store, workers=1, progress=False)
        assert (rep.ran, rep.failed) == (12, 0)
        rows = store.rows()
        traces = store.traces(list(rows))
    assert all(r["status"] == "ok" and r["kind"] == "program" for r in rows.values()), \
        [r["error"] for r in rows.values()]
    for rec in recs:
        row, trace = rows[rec.key], traces[rec.key]
        assert json.loads(row["program"]) == rec.program
        assert row["feasible"] == 1 and row["violation"] == 0.0 and row["nfev"] >= 1
        assert {"cost", "runtime_s", "nfev", "violation", "feasible"} <= set(row)
        # the stored path is the one the stored cost is of, under a program built the same way
        world, start, goal = plan_target(json.dumps(rec.target_spec, sort_keys=True))
        prog = op.PathProgram(world, start, goal, variables=op.Points(12))
        from optplan import terms as T

        prog.minimize(T.squared_length() + 0.5 * T.bending())
        path = np.asarray(trace["path"])
        assert prog.evaluate(path)[0] == pytest.approx(row["cost"], rel=1e-9) and op.validate_path(world, path)
    chain = rows[by["li2023_11", "pso>osqp", 1].key]
    assert [s["solver"] for s in json.loads(chain["stages"])] == ["pso", "osqp"]
    assert rows[by["room", "ipopt", 0].key]["param_max_evals"] is None

    # a stored run has the numbers of the same solve done by hand (seed, options and init path)
    rec = by["room", "pso", 1]
    world, start, goal = plan_target(json.dumps(rec.target_spec, sort_keys=True))
    import importlib

    direct = importlib.import_module(name).corridor(world, start, goal, n=12).solve(
        "pso", seed=1, pop=10, max_evals=200, init=op.plan(world, start, goal, algorithm="astar").path)
    assert rows[rec.key]["cost"] == direct.cost and rows[rec.key]["nfev"] == direct.nfev == 200

    # resume: the same spec again computes nothing, from Python and from the command line
    with ResultStore(db) as store:
        again = run_records(load_spec(folder / "spec.yaml").expand(), store, workers=1, progress=False)
        assert (again.skipped, again.ran) == (12, 0)
        assert {k: r["finished_at"] for k, r in store.rows().items()} == \
            {k: r["finished_at"] for k, r in rows.items()}


def test_the_bench_command_prints_a_table_per_map_and_resumes(user_module, capsys):
    name, folder = user_module
    args = ["bench", str(folder / "spec.yaml"), "--db", str(folder / "r.sqlite"), "--workers", "1", "--no-progress"]
    assert main(args) == 0
    cap = capsys.readouterr()
    assert "12 ran (0 failed)" in cap.err
    assert "### li2023_11" in cap.out and "### room" in cap.out
    assert "| solver | runs | failed | feasible | best cost | median cost | median time [s] | median nfev |" \
        in cap.out
    lines = [ln for ln in cap.out.splitlines() if ln.startswith("| ipopt |")]
    assert len(lines) == 2 and all(ln.endswith("| - | ref |") and "| 1/1 | 0 | 1/1 |" in ln for ln in lines)
    assert any(ln.startswith("| pso>osqp | 2/2 | 0 | 2/2 |") for ln in cap.out.splitlines())
    assert main(args) == 0
    assert "12 already in the database, 0 ran" in capsys.readouterr().err


def test_editing_the_program_module_or_its_args_reruns_with_the_new_code(user_module):
    name, folder = user_module
    spec_file = folder / "spec.yaml"
    raw_one = {"kind": "program", "program": f"{name}:corridor", "init": "astar", "args": {"n": 12},
               "maps": ["li2023_11"], "algorithms": ["ipopt"]}
    store = ResultStore()
    first = load_spec(raw_one).expand()
    run_records(first, store, workers=1, progress=False)
    (folder / f"{name}.py").write_text(MODULE.format(weight="2.00"))   # the objective doubles
    second = load_spec(raw_one).expand()
    assert second[0].key != first[0].key
    assert run_records(second, store, workers=1, progress=False).ran == 1
    rows = store.rows()
    # computed with the edited code, although this process had imported the old one
    assert rows[second[0].key]["cost"] == pytest.approx(2 * rows[first[0].key]["cost"], rel=1e-6)
    assert load_spec({**raw_one, "args": {"n": 14}}).expand()[0].key != second[0].key
    assert spec_file.exists()


def test_a_builder_that_returns_no_program_is_a_failed_run_with_its_reason(user_module):
    name, _ = user_module
    rec = load_spec({"kind": "program", "program": f"{name}:not_a_program", "maps": ["li2023_11"],
                     "algorithms": ["pso"], "params": {"max_evals": 50}}).expand()[0]
    out = execute_run(rec.to_dict())
    assert out["status"] == "failed" and "returned a str, not an op.PathProgram" in out["error"]


BASE = {"kind": "program", "program": "smoothing", "maps": ["li2023_11"], "algorithms": ["ipopt", "pso"],
        "runs": 1}


@pytest.mark.parametrize("change,error,needle", [
    ({"algorithms": ["nope"]}, UnknownAlgorithmError, "unknown program solver 'nope'; known:"),
    ({"algorithms": [["pso", "nope"]]}, UnknownAlgorithmError, "unknown program solver 'nope'"),
    ({"algorithms": [{"name": "ipopt", "params": {"max_evals": 10}}]}, ParameterError,
     "ipopt has no option 'max_evals'"),
    ({"params": {"max_evalz": 10}}, ParameterError, "no solver of this spec has option 'max_evalz'"),
    ({"algorithms": [{"name": "ipopt", "params": {"max_iter": 0}}]}, ParameterError, "ipopt: max_iter must be"),
    ({"program": "no_such_module_anywhere:f"}, ParameterError, "cannot import module 'no_such_module_anywhere'"),
    ({"program": "json:no_such_function"}, ParameterError, "module 'json' has no 'no_such_function'"),
    ({"program": "json:decoder"}, ParameterError, "is a module, not a callable"),
    ({"program": "./progs.py:corridor"}, ParameterError, "file paths are not accepted"),
    ({"program": "/tmp/progs:corridor"}, ParameterError, "file paths are not accepted"),
    ({"program": "atlantis"}, UnknownAlgorithmError, "unknown program 'atlantis'"),
    ({"program": None}, ScenarioError, "a program spec names its program"),
    ({"args": {"m": 3}}, ParameterError, "program 'smoothing' takes no argument 'm'"),
    ({"program": "li2023", "args": {"n": 3}}, ParameterError, "program 'li2023' takes no argument 'n'"),
    ({"program": "json:dumps", "args": {"zz": 1}}, ParameterError, "cannot be called as dumps(world, start, goal"),
    ({"init": "pso"}, ParameterError, "init must be a graph planner"),
    ({"params": {"init": "astar"}}, ScenarioError, "set by the spec's 'init:' key"),
    ({"refine": ["qp"]}, ScenarioError, "a program spec cannot refine"),
    ({"algorithms": ["pso", "pso"]}, ScenarioError, "labels repeat"),
    ({"reference": "gwo"}, ParameterError, "reference 'gwo' is not one of"),
    ({"kind": "plan", "algorithms": ["astar"]}, ScenarioError, "'program' applies only to kind program"),
])
def test_bad_program_specs_are_one_line_errors_at_load_time(change, error, needle):
    with pytest.raises(error) as exc:
        load_spec({**BASE, **change})
    assert needle in str(exc.value) and "\n" not in str(exc.value)


def test_a_bad_program_spec_runs_nothing_and_exits_2(tmp_path, capsys):
    spec = tmp_path / "s.yaml"
    spec.write_text("kind: program\nprogram: smoothing\nmaps: [li2023_11]\nalgorithms: [ipopt, [pso, ipop]]\n")
    db = tmp_path / "r.sqlite"
    assert main(["bench", str(spec), "--db", str(db), "--workers", "1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "unknown program solver 'ipop'" in err
    assert not db.exists()


def test_the_kind_is_read_from_program_and_plan_specs_keep_their_keys():
    assert load_spec({k: v for k, v in BASE.items() if k != "kind"}).kind == "program"
    # a plan key hashes the fields it hashed before program runs existed: stored databases still resume
    import hashlib

    plan = load_spec({"kind": "plan", "maps": ["li2023_11"], "algorithms": ["astar"]}).expand()[0]
    ident = {"kind": "plan", "target": {"paper_map": "li2023_11"}, "algorithm": "astar", "refine": None,
             "local_planner": None, "seed": 0, "params": {}, "inputs": plan.inputs}
    blob = json.dumps(ident, sort_keys=True, separators=(",", ":"), default=str)
    assert plan.program == {} and plan.key == hashlib.sha256(blob.encode()).hexdigest()[:20]
    # the program identity enters program keys only
    a = load_spec(BASE).expand()[0]
    b = load_spec({**BASE, "args": {"n": 20}}).expand()[0]
    c = load_spec({**BASE, "init": "astar"}).expand()[0]
    assert len({a.key, b.key, c.key}) == 3


def test_the_shipped_example_program_spec_expands_as_documented():
    spec = load_spec("programs_example")
    assert spec.kind == "program" and spec.program["program"] == "chen2025"
    recs = spec.expand()
    assert {r.target for r in recs} == {"chen2025_20", "li2023_11"}
    assert sorted({r.algorithm for r in recs}) == ["msiar-gwo", "msiar-gwo>ipopt", "pso"]
    assert len(recs) == 2 * 3 * 2   # every solver here takes a seed
    quick = load_spec("programs_example", quick=True).expand()
    assert {r.target for r in quick} == {"li2023_11"} and quick[0].params == {"max_evals": 600}


def test_refine_solvers_benchmark_compares_the_solvers_on_paper_maps_and_map_files(tmp_path):
    import os
    import subprocess
    import sys
    from pathlib import Path

    repo = Path(__file__).resolve().parents[1]
    script = repo / "benchmarks" / "refine_solvers.py"
    # the script imports this checkout's optplan, not whichever one is installed
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(repo), os.environ.get("PYTHONPATH")]))}
    (tmp_path / "room.txt").write_text(ROOM)
    run = subprocess.run([sys.executable, str(script), "li2023_11", str(tmp_path / "room.txt"), "--start", "0.5",
                          "0.5", "--goal", "0.5", "7.5", "--n", "15", "--solvers", "ipopt", "osqp", "pso>osqp",
                          "--db", str(tmp_path / "r.sqlite")], capture_output=True, text=True, timeout=300, env=env)
    assert run.returncode == 0, run.stderr[-2000:]
    out = run.stdout
    assert "## li2023_11: start from the astar path" in out and "room.txt: start from the astar path" in out
    assert "smoothing(n=15, w=0.5)" in out
    rows = [ln.split() for ln in out.splitlines() if ln.split()[:1] in (["ipopt"], ["osqp"], ["pso>osqp"])]
    assert [r[0] for r in rows] == ["ipopt", "osqp", "pso>osqp"] * 2 and all(r[2] == "1" for r in rows)
    with ResultStore(tmp_path / "r.sqlite") as store:
        assert store.count() == 6
    bad = subprocess.run([sys.executable, str(script), str(tmp_path / "room.txt")], capture_output=True, text=True,
                         timeout=120, env=env)
    assert bad.returncode == 2 and "needs --start X Y and --goal X Y" in bad.stderr


def test_compare_keys_its_stored_runs_by_map_and_start_too():
    # the key used to be the program's text, solver, seed and scalar options: the same program on
    # two maps, or from two init paths, overwrote one stored run
    import optplan as op

    store = ResultStore()
    rows = np.zeros((8, 8), int)
    walled = rows.copy()
    walled[4, :6] = 1
    for grid in (op.GridMap.from_rows(rows), op.GridMap.from_rows(walled)):
        prog = op.smoothing_program(grid, (0.5, 0.5), (0.5, 7.5), n=10)
        seed = op.plan(grid, (0.5, 0.5), (0.5, 7.5), algorithm="astar").path
        op.compare(prog, ["pso"], seeds=[0], db=store, max_evals=40, init=seed)
        op.compare(prog, ["pso"], seeds=[0], db=store, max_evals=40, init=seed.copy())   # the same start
        op.compare(prog, ["pso"], seeds=[0], db=store, max_evals=40)                              # none
    assert store.count() == 4


def test_each_seed_reaches_the_swarm_and_a_paper_program_is_the_one_op_paper_program_builds():
    import optplan as op
    from optplan.world.papermaps import paper_map

    spec = load_spec({"kind": "program", "program": "li2023", "maps": ["li2023_11"], "algorithms": ["gwo"],
                      "params": {"pop": 12, "max_evals": 120}, "seeds": [3, 4]})
    store = ResultStore()
    run_records(spec.expand(), store, workers=1, progress=False)
    prog = op.paper_program("li2023", *paper_map("li2023_11"))
    rows, traces = store.rows(), store.traces(list(store.rows()))
    for rec in spec.expand():
        direct = prog.solve("gwo", seed=rec.seed, pop=12, max_evals=120)
        assert rows[rec.key]["cost"] == direct.cost and traces[rec.key]["x"] == direct.x.tolist()
        assert traces[rec.key]["history"] == direct.history.tolist()
    assert len({json.dumps(t["x"]) for t in traces.values()}) == 2   # two seeds, two different runs
