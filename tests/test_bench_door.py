"""optplan bench at the door (issue 48): a foreign database is refused untouched, spec
problems stop it before any run, and two processes on one database share the work."""
from __future__ import annotations

import re
import sqlite3
import subprocess
import sys

import pytest

SPEC = """kind: plan
maps: [chen2025_20]
algorithms: [gwo, pso]
params: {pop: 10, iters: 40}
runs: 8
"""


def _bench(*args, timeout=300):
    return subprocess.run([sys.executable, "-m", "optplan", "bench", *args, "--no-progress"], capture_output=True,
                          text=True, timeout=timeout)


def test_a_foreign_sqlite_file_is_refused_and_left_as_it_was(tmp_path):
    other = tmp_path / "other.sqlite"
    conn = sqlite3.connect(other)
    conn.execute("CREATE TABLE people (name TEXT)")
    conn.commit()
    conn.close()
    before = other.read_bytes()
    (tmp_path / "s.yaml").write_text(SPEC)
    done = _bench(str(tmp_path / "s.yaml"), "--db", str(other))
    assert done.returncode == 2 and "not an optplan results database" in done.stderr and "people" in done.stderr
    assert other.read_bytes() == before


@pytest.mark.parametrize("change,args,match", [
    ("params: {pop: 10, iters: 40, clearance: .nan}", (), "nan"),
    ("params: {pop: 10, iters: 40}", ("--layout", "nosuch"), "not a table layout"),
    ("params: {pop: 10, iters: 40}", ("--csv", "out.txt"), ".csv"),
])
def test_spec_and_option_problems_stop_before_any_run(tmp_path, change, args, match):
    (tmp_path / "s.yaml").write_text(SPEC.replace("params: {pop: 10, iters: 40}", change))
    db = tmp_path / "r.sqlite"
    done = _bench(str(tmp_path / "s.yaml"), "--db", str(db), *args)
    assert done.returncode == 2 and match in done.stderr
    assert not db.exists() or sqlite3.connect(db).execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 0


def test_an_unreachable_goal_in_a_spec_stops_it_before_any_run(tmp_path):
    (tmp_path / "wall.txt").write_text("0 0 1 0 0\n0 0 1 0 0\n0 0 1 0 0\n")
    (tmp_path / "s.yaml").write_text("kind: plan\nmaps: [{name: w, map: wall.txt, start: [0.5, 0.5], "
                                     "goal: [4.5, 0.5]}]\nalgorithms: [astar]\nruns: 1\n")
    done = _bench(str(tmp_path / "s.yaml"), "--db", str(tmp_path / "r.sqlite"))
    assert done.returncode == 2 and "cannot be reached" in done.stderr
    assert not (tmp_path / "r.sqlite").exists()


def test_two_processes_on_one_database_compute_each_run_once(tmp_path):
    (tmp_path / "s.yaml").write_text(SPEC)
    db = tmp_path / "r.sqlite"
    cmd = [sys.executable, "-m", "optplan", "bench", str(tmp_path / "s.yaml"), "--db", str(db), "--no-progress",
           "--workers", "1"]
    procs = [subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(2)]
    outs = [p.communicate(timeout=600) for p in procs]
    assert all(p.returncode == 0 for p in procs), [o[1] for o in outs]
    ran = [int(re.search(r"(\d+) ran", err).group(1)) for _, err in outs]
    assert sum(ran) == 16, [o[1] for o in outs]            # 2 algorithms x 8 seeds, each computed once
    assert outs[0][0] == outs[1][0]                          # both print the tables of all 16 runs
    alone = _bench(str(tmp_path / "s.yaml"), "--db", str(tmp_path / "alone.sqlite"), "--workers", "1")
    assert alone.stdout == outs[0][0]                        # the same tables as one process
    conn = sqlite3.connect(db)
    assert conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 16
    assert conn.execute("SELECT COUNT(*) FROM claims").fetchone()[0] == 0
