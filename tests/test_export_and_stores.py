"""Exports (paths, trajectories, OMPL benchmark logs), new map inputs (images, ROS modes,
paper map names), and the results database under two writers and foreign files."""
from __future__ import annotations

import math
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

import optplan as op
from optplan.bench.ompl import export_ompl
from optplan.bench.store import ResultStore
from optplan.world.export import export_path, export_trajectory, read_path_csv
from optplan.world.loaders import MapOriginYawWarning

ROOT = Path(__file__).resolve().parents[1]


# ------------------------------------------------------------------ paths and trajectories
def test_path_csv_and_ros_yaml_round_trip(tmp_path):
    path = np.array([[0.5, 0.5], [3.25, 0.5], [3.25, 4.125], [3.25, 4.125], [0.1 + 0.2, 7.0]])
    np.testing.assert_array_equal(read_path_csv(export_path(path, tmp_path / "p.csv", precision=None)), path)
    np.testing.assert_allclose(read_path_csv(export_path(path, tmp_path / "p6.csv")), path, atol=5e-7)
    assert "0.300000" in (tmp_path / "p6.csv").read_text()          # 6 decimals, not 0.30000000000000004
    msg = yaml.safe_load(export_path(path, tmp_path / "p.yaml", frame_id="odom").read_text())
    assert msg["header"]["frame_id"] == "odom" and len(msg["poses"]) == len(path)
    xy = np.array([[p["pose"]["position"]["x"], p["pose"]["position"]["y"]] for p in msg["poses"]])
    np.testing.assert_array_equal(xy, path)
    q = np.array([[p["pose"]["orientation"]["z"], p["pose"]["orientation"]["w"]] for p in msg["poses"]])
    heading = 2 * np.arctan2(q[:, 0], q[:, 1])
    # each pose faces along the segment that leaves it; the repeated point keeps the last direction
    last = math.atan2(7.0 - 4.125, 0.1 + 0.2 - 3.25)
    np.testing.assert_allclose(heading, [0.0, math.pi / 2, math.pi / 2, last, last], atol=1e-12)
    np.testing.assert_allclose(np.hypot(q[:, 0], q[:, 1]), 1.0)
    assert [p["header"]["seq"] for p in msg["poses"]] == list(range(len(path)))


def test_trajectory_export_keeps_time_and_heading(tmp_path):
    traj = np.array([[0.0, 1.0, 2.0, 0.0, 0.0, 0.0], [0.1, 1.05, 2.0, 0.3, 0.5, 3.0], [1.25, 1.5, 2.5, -2.0, 0.4, -1.0]])
    np.testing.assert_array_equal(read_path_csv(export_trajectory(traj, tmp_path / "t.csv", precision=None)), traj)
    msg = yaml.safe_load(export_trajectory(traj, tmp_path / "t.yml").read_text())
    stamps = [p["header"]["stamp"]["secs"] + p["header"]["stamp"]["nsecs"] * 1e-9 for p in msg["poses"]]
    np.testing.assert_allclose(stamps, traj[:, 0], atol=1e-9)
    q = [(p["pose"]["orientation"]["z"], p["pose"]["orientation"]["w"]) for p in msg["poses"]]
    np.testing.assert_allclose([2 * math.atan2(z, w) for z, w in q], traj[:, 3], atol=1e-12)


@pytest.mark.parametrize("call,needle", [
    (lambda d: export_path([[0, 0], [1, 1]], d / "p.txt"), ".csv, .json, .geojson or .yaml"),
    (lambda d: export_path([[0, 0], [1, 1]], d / "p.csv", precision=-1), "precision"),
    (lambda d: export_path([[0, 0, 0]], d / "p.csv"), "2 columns"),
    (lambda d: export_path([[0, 0], [np.nan, 1]], d / "p.csv"), "finite"),
    (lambda d: export_trajectory(np.zeros((3, 5)), d / "t.csv"), "6 columns"),
    (lambda d: export_path([[0, 0], [1, 1]], d / "p.yaml", frame_id="a: b"), "frame_id"),
])
def test_bad_exports_raise_parameter_errors(tmp_path, call, needle):
    with pytest.raises(op.ParameterError, match=needle):
        call(tmp_path)


def test_cli_plan_and_simulate_export(tmp_path):
    from optplan.cli import main

    out = tmp_path / "astar.csv"
    assert main(["plan", "chen2025_20", "--export", str(out), "--json"]) == 0
    P = read_path_csv(out)
    world, s, g = op.world.papermaps.paper_map("chen2025_20")
    assert op.validate_path(world, P)
    np.testing.assert_array_equal(P[0], s)
    np.testing.assert_array_equal(P[-1], g)
    traj = tmp_path / "run.yaml"
    code = main(["simulate", "hou2024_dynamic1", "--export", str(traj), "--json"])
    assert code in (0, 1)
    msg = yaml.safe_load(traj.read_text())
    assert len(msg["poses"]) >= 2 and msg["header"]["frame_id"] == "map"


# ------------------------------------------------------------------ OMPL benchmark logs
def _read_ompl_log(text: str) -> dict:
    """A reader written from OMPL's log grammar (not OMPL's script): planners -> runs."""
    lines = iter(text.splitlines())
    out = {"planners": {}}
    assert next(lines).split()[1] == "version"
    assert next(lines).startswith("Experiment ")
    assert next(lines).startswith("Running on ") and next(lines).startswith("Starting at ")
    for _ in range(2):  # setup and cpuinfo blocks
        assert next(lines) == "<<<|"
        while next(lines) != "|>>>":
            pass
    assert next(lines).endswith(" is the random seed")
    assert next(lines).endswith(" seconds per run") and next(lines).endswith(" MB per run")
    assert next(lines).endswith(" runs per planner")
    assert next(lines).endswith(" seconds spent to collect the data")
    n_planners = int(next(lines).split()[0])
    for _ in range(n_planners):
        name = next(lines)
        for _ in range(int(next(lines).split()[0])):
            assert " = " in next(lines)
        props = []
        for _ in range(int(next(lines).split()[0])):
            *words, typ = next(lines).split()
            assert typ in ("BOOLEAN", "INTEGER", "REAL")
            props.append(" ".join(words))
        runs = []
        for _ in range(int(next(lines).split()[0])):
            line = next(lines)
            assert line.endswith("; ")
            cells = line.split("; ")[:-1]
            assert len(cells) == len(props)
            runs.append(dict(zip(props, cells)))
        assert next(lines) == "."
        out["planners"][name] = runs
    assert next(lines, None) is None
    return out


def test_bench_results_export_as_ompl_logs(tmp_path):
    from optplan.bench import run_experiment

    db = tmp_path / "r.sqlite"
    run_experiment({"kind": "plan", "maps": ["chen2025_20"], "algorithms": ["astar", "gwo"], "runs": 2,
                    "params": {"pop": 5, "iters": 5}}, db=db, workers=1, progress=False)
    with ResultStore(db) as store:
        files = export_ompl(store, tmp_path / "ompl")
    assert len(files) == 1
    log = _read_ompl_log(files[0].read_text())
    assert set(log["planners"]) == {"astar", "gwo"}
    astar = log["planners"]["astar"]
    assert len(astar) == 2 and all(r["solved"] == "1" and r["correct solution"] == "1" for r in astar)
    world, s, g = op.world.papermaps.paper_map("chen2025_20")
    best = op.shortest_path(world, s, g, method="astar").length
    assert float(astar[0]["solution length"]) == pytest.approx(best)
    assert {r["seed"] for r in log["planners"]["gwo"]} == {"0", "1"} or len(log["planners"]["gwo"]) == 2


def test_bench_cli_export_ompl_and_empty_database(tmp_path, capsys):
    from optplan.cli import main

    spec = tmp_path / "s.yaml"
    spec.write_text("kind: plan\nmaps: [chen2025_20]\nalgorithms: [astar]\nruns: 1\n")
    assert main(["bench", str(spec), "--db", str(tmp_path / "r.sqlite"), "--workers", "1", "--no-progress",
                 "--export-ompl", str(tmp_path / "logs")]) == 0
    assert len(list((tmp_path / "logs").glob("*.log"))) == 1
    with ResultStore(tmp_path / "empty.sqlite") as store, pytest.raises(op.ParameterError, match="no runs"):
        export_ompl(store, tmp_path / "none")


# ------------------------------------------------------------------ results database
def _record(key: str, **params) -> dict:
    return {"key": key, "experiment": "e", "kind": "plan", "target": "m", "algorithm": "astar", "label": "astar",
            "refine": None, "local_planner": None, "seed": 0, "params": params, "target_spec": {}}


def test_two_writers_adding_the_same_new_column_do_not_collide(tmp_path):
    db = tmp_path / "shared.sqlite"
    a, b = ResultStore(db), ResultStore(db)  # two connections, as two bench processes have
    a.write(_record("k1"), {"status": "ok", "metrics": {"length": 1.0, "new_metric": 2}})
    # b's view of the columns is stale: it adds 'new_metric' too and must not fail
    b.write(_record("k2"), {"status": "ok", "metrics": {"length": 3.0, "new_metric": 4}})
    assert {r["new_metric"] for r in a.rows().values()} == {2, 4}
    a.close(), b.close()


def test_two_bench_processes_on_one_new_database(tmp_path):
    script = (f"import sys; sys.path.insert(0, {str(ROOT)!r})\n"
              "from optplan.bench import run_experiment\n"
              "run_experiment({'kind': 'plan', 'maps': ['chen2025_20'], 'algorithms': [sys.argv[2]], 'runs': 3,"
              " 'params': {'pop': 4, 'iters': 3}}, db=sys.argv[1], workers=1, progress=False)\n")
    (tmp_path / "w.py").write_text(script)
    db = str(tmp_path / "new.sqlite")
    procs = [subprocess.Popen([sys.executable, str(tmp_path / "w.py"), db, algo], stderr=subprocess.PIPE, text=True)
             for algo in ("gwo", "pso")]
    errs = [p.communicate(timeout=300)[1] for p in procs]
    assert [p.returncode for p in procs] == [0, 0], errs
    with ResultStore(db) as store:
        rows = store.rows().values()
    assert len(rows) == 6 and all(r["status"] == "ok" for r in rows)


def test_a_lock_reported_at_once_while_setting_up_is_waited_out(tmp_path, monkeypatch):
    """SQLite can report a lock on a new database at once instead of waiting for it (two bench
    processes creating one file; seen once in CI): the store's set-up tries again; another
    error is not retried."""
    import optplan.bench.store as store_module

    real_connect, attempts = sqlite3.connect, []

    class LockedOnce:
        def __init__(self, conn):
            self._conn = conn

        def execute(self, sql, *args):
            attempts.append(sql)
            if len(attempts) == 1:
                raise sqlite3.OperationalError("database is locked")
            return self._conn.execute(sql, *args)

        def __getattr__(self, name):
            return getattr(self._conn, name)

        def __setattr__(self, name, value):
            if name == "_conn":
                object.__setattr__(self, name, value)
            else:
                setattr(self._conn, name, value)

    monkeypatch.setattr(store_module.sqlite3, "connect", lambda *a, **k: LockedOnce(real_connect(*a, **k)))
    store = ResultStore(tmp_path / "new.sqlite")
    assert attempts[:2] == ["PRAGMA journal_mode=WAL"] * 2 and "traces" in attempts[-1]
    store.write(_record("k1"), {"status": "ok", "metrics": {"length": 1.0}})
    assert list(store.rows()) == ["k1"]
    store.close()

    class Broken(LockedOnce):
        def execute(self, sql, *args):
            raise sqlite3.OperationalError("disk I/O error")

    monkeypatch.setattr(store_module.sqlite3, "connect", lambda *a, **k: Broken(real_connect(*a, **k)))
    with pytest.raises(op.ParameterError, match="disk I/O error"):
        ResultStore(tmp_path / "other.sqlite")


def test_a_foreign_database_with_a_runs_table_is_refused(tmp_path):
    db = tmp_path / "foreign.sqlite"
    con = sqlite3.connect(db)
    con.execute("CREATE TABLE runs (id INTEGER, name TEXT)")
    con.commit(), con.close()
    with pytest.raises(op.ParameterError, match="not an optplan results database"):
        ResultStore(db)


def test_run_experiment_with_workers_from_a_script_without_a_main_guard(tmp_path):
    script = (f"import sys; sys.path.insert(0, {str(ROOT)!r})\n"
              "from optplan.bench import run_experiment\n"
              "print('SCRIPT RAN', flush=True)\n"
              "res = run_experiment({'kind': 'plan', 'maps': ['chen2025_20'], 'algorithms': ['astar', 'gwo'],"
              " 'runs': 2, 'params': {'pop': 4, 'iters': 3}}, db='r.sqlite', workers=2, progress=False)\n"
              "print('STATUS', sorted({r['status'] for r in res.rows.values()}), len(res.rows), flush=True)\n")
    (tmp_path / "unguarded.py").write_text(script)
    done = subprocess.run([sys.executable, "unguarded.py"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.count("SCRIPT RAN") == 1, done.stdout  # the workers did not re-run the script
    assert "STATUS ['ok'] 4" in done.stdout


# ------------------------------------------------------------------ map inputs
def test_png_and_bmp_maps_through_pillow(tmp_path):
    from PIL import Image

    rows = np.array([[0, 0, 1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], bool)  # top row first, 1 = blocked
    img = np.where(rows, 0, 254).astype(np.uint8)
    for suffix in (".png", ".bmp"):
        Image.fromarray(img).save(tmp_path / f"m{suffix}")
        g = op.load_map(tmp_path / f"m{suffix}")
        np.testing.assert_array_equal(g.to_rows(), rows)
    Image.fromarray(np.stack([img] * 3, axis=-1)).save(tmp_path / "rgb.png")
    np.testing.assert_array_equal(op.load_map(tmp_path / "rgb.png").to_rows(), rows)
    (tmp_path / "m.yaml").write_text("image: m.png\nresolution: 0.5\norigin: [1.0, 2.0, 0.0]\n")
    g = op.load_map(tmp_path / "m.yaml")
    assert g.resolution == 0.5 and tuple(g.origin) == (1.0, 2.0)
    np.testing.assert_array_equal(g.to_rows(), rows)


def test_image_without_pillow_names_the_extra(tmp_path, monkeypatch):
    from PIL import Image

    Image.fromarray(np.full((2, 2), 254, np.uint8)).save(tmp_path / "m.png")
    monkeypatch.setitem(sys.modules, "PIL", None)  # as if Pillow were not installed
    with pytest.raises(op.MapFormatError, match=r"optplan\[images\]"):
        op.load_map(tmp_path / "m.png")


def test_ros_yaml_yaw_warns_and_mode_is_honoured(tmp_path):
    # values 0 (occupied), 100 (free in raw mode? no: raw means the value itself), 254 (free)
    (tmp_path / "m.pgm").write_bytes(b"P2\n3 1\n255\n0 100 254\n")
    base = "image: m.pgm\nresolution: 1.0\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    from optplan.world.loaders import MapUnknownCellsWarning

    (tmp_path / "tri.yaml").write_text(base + "origin: [0.0, 0.0, 0.0]\n")
    with pytest.warns(MapUnknownCellsWarning, match="1 of 3"):        # 100 is neither free nor occupied
        np.testing.assert_array_equal(op.load_map(tmp_path / "tri.yaml").to_rows(), [[True, True, False]])
    (tmp_path / "raw.yaml").write_text(base + "origin: [0.0, 0.0, 0.0]\nmode: raw\n")
    np.testing.assert_array_equal(op.load_map(tmp_path / "raw.yaml").to_rows(), [[False, True, True]])
    (tmp_path / "bad.yaml").write_text(base + "origin: [0.0, 0.0, 0.0]\nmode: fuzzy\n")
    with pytest.raises(op.MapFormatError, match="mode must be one of"):
        op.load_map(tmp_path / "bad.yaml")
    (tmp_path / "yaw.yaml").write_text(base + "origin: [0.0, 0.0, 0.7]\n")
    with pytest.warns(MapOriginYawWarning, match="yaw 0.7"), pytest.warns(MapUnknownCellsWarning):
        op.load_map(tmp_path / "yaw.yaml")


def test_paper_map_names_are_map_names():
    world, s, g = op.world.papermaps.paper_map("chen2025_20")
    same = op.load_map("chen2025_20")
    np.testing.assert_array_equal(same.occ, world.occ)
    assert isinstance(op.load_map("yang2023_env1"), op.CircleWorld)


def _descendants(pid: int) -> set[int]:
    """Every live process below ``pid`` (from /proc)."""
    children: dict[int, list[int]] = {}
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                ppid = int(next(ln for ln in (d / "status").read_text().splitlines()
                                if ln.startswith("PPid:")).split()[1])
            except (OSError, StopIteration, ValueError):
                continue
            children.setdefault(ppid, []).append(int(d.name))
    out, todo = set(), [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            if c not in out:
                out.add(c)
                todo.append(c)
    return out


def _alive(pid: int) -> bool:
    try:
        state = next(ln for ln in Path(f"/proc/{pid}/status").read_text().splitlines() if ln.startswith("State:"))
    except (OSError, StopIteration):
        return False
    return " Z " not in state and "zombie" not in state


@pytest.mark.skipif(not Path("/proc").is_dir(), reason="needs /proc")
def test_kill_9_of_a_bench_leaves_no_orphan_workers(tmp_path):
    import os
    import signal
    import time

    script = (f"import sys; sys.path.insert(0, {str(ROOT)!r})\n"
              "from optplan.bench import run_experiment\n"
              "run_experiment({'kind': 'plan', 'maps': ['chen2025_30'], 'algorithms': ['gwo'], 'runs': 8,"
              " 'params': {'pop': 40, 'iters': 100000}}, db='r.sqlite', workers=2, progress=False)\n")
    (tmp_path / "long.py").write_text(script)
    proc = subprocess.Popen([sys.executable, "long.py"], cwd=tmp_path)
    workers: set[int] = set()
    try:
        deadline = time.time() + 120
        while time.time() < deadline and len(workers) < 3:  # forkserver + 2 workers at least
            time.sleep(0.5)
            workers = _descendants(proc.pid)
        assert len(workers) >= 3, "the pool did not start"
        time.sleep(2)
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)
        deadline = time.time() + 30
        while time.time() < deadline and any(_alive(p) for p in workers):
            time.sleep(0.5)
        assert not [p for p in workers if _alive(p)], "workers outlived the killed bench"
    finally:
        if proc.poll() is None:
            proc.kill()
        for p in workers | _descendants(proc.pid):  # never leave a worker of this test behind
            if _alive(p):
                with __import__("contextlib").suppress(ProcessLookupError):
                    os.kill(p, signal.SIGKILL)


def test_a_failing_write_is_one_optplan_error_and_keeps_the_stored_runs(tmp_path):
    db = tmp_path / "r.sqlite"
    store = ResultStore(db)
    store.write(_record("k1"), {"status": "ok", "metrics": {"length": 1.0}})
    store.conn.execute("PRAGMA query_only = ON")  # every write now fails, as on a full or read-only disk
    with pytest.raises(op.OptplanError, match="cannot store run k2"):
        store.write(_record("k2"), {"status": "ok", "metrics": {"length": 2.0, "other": 3}})
    store.conn.execute("PRAGMA query_only = OFF")
    assert set(store.rows()) == {"k1"} and not store.conn.in_transaction
    store.close()


@pytest.mark.parametrize("spec,pipelines", [
    ({"kind": "plan", "maps": ["chen2025_20"], "algorithms": ["astar", "gwo"], "refine": ["none", "qp"],
      "runs": 2, "params": {"pop": 5, "iters": 5}}, 4),
    ({"kind": "simulate", "scenarios": ["yuan2021_added_obstacles"], "algorithms": ["astar"],
      "refine": ["none", "qp"], "local_planners": ["dwa", "qp-dwa"], "runs": 1,
      "params": {"time_limit": 5}}, 4),
])
def test_ompls_own_importer_reads_the_export(tmp_path, spec, pipelines):
    """ompl.tools.readBenchmarkLog (what ompl_benchmark_statistics.py and Planner Arena run)
    loads the logs: one OMPL planner per pipeline, every stored run present (issue 47: a
    duplicated 'seed' column was refused, and refine/local pipelines were merged into one)."""
    import sqlite3

    ompl_tools = pytest.importorskip("ompl.tools")
    from optplan.bench import run_experiment

    db = tmp_path / "r.sqlite"
    run_experiment(spec, db=db, workers=1, progress=False)
    with ResultStore(db) as store:
        files = export_ompl(store, tmp_path / "ompl")
        stored = store.count()
    out = tmp_path / "benchmark.db"
    ompl_tools.readBenchmarkLog(str(out), [str(f) for f in files], False)
    conn = sqlite3.connect(out)
    assert conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == stored
    assert conn.execute("SELECT COUNT(*) FROM plannerConfigs").fetchone()[0] == pipelines


def test_paths_leave_as_json_and_geojson_exactly(tmp_path):
    import json

    path = np.array([[0.5, 0.5], [0.1 + 0.2, 7.0], [1e-17, 3.141592653589793]])
    doc = json.loads(export_path(path, tmp_path / "p.json", frame_id="odom").read_text())
    assert doc["frame_id"] == "odom" and np.array_equal(np.array(doc["points"]), path)
    geo = json.loads(export_path(path, tmp_path / "p.geojson").read_text())
    assert geo["type"] == "Feature" and geo["geometry"]["type"] == "LineString"
    assert np.array_equal(np.array(geo["geometry"]["coordinates"]), path)
    assert geo["properties"]["length_m"] == pytest.approx(np.hypot(*np.diff(path, axis=0).T).sum())
    traj = np.array([[0.0, 1.0, 2.0, 0.0, 0.0, 0.0], [0.1, 1.05, 2.0, 0.3, 0.5, 3.0]])
    rows = json.loads(export_trajectory(traj, tmp_path / "t.json").read_text())["rows"]
    assert np.array_equal(np.array(rows), traj)
    from optplan.cli import main

    assert main(["plan", "chen2025_20", "--algo", "astar", "--out", str(tmp_path / "a.geojson")]) == 0
    assert json.loads((tmp_path / "a.geojson").read_text())["geometry"]["type"] == "LineString"
