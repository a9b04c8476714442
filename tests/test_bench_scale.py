"""The issue's figures: a Dask cluster gets exactly the local executor's numbers, and an
experiment killed midway resumes with only its missing runs."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from optplan.bench.runner import run_records
from optplan.bench.spec import load_spec
from optplan.bench.store import ResultStore

CLOCK = {"runtime_s", "wall_s", "worker", "finished_at", "mean_step_ms", "reroute_s"}

SPEC = {
    "name": "dask_vs_local", "kind": "plan", "maps": ["chen2025_20", "yang2023_env1"],
    "algorithms": ["msiar-gwo", "pso", {"name": "gwo", "label": "gwo-broken", "params": {"postprocess": "no_such_param"}}],
    "params": {"pop": 16, "iters": 20}, "runs": 3, "reference": "msiar-gwo",
}


def numbers(store: ResultStore) -> dict:
    return {k: {c: v for c, v in r.items() if c not in CLOCK} for k, r in store.rows().items()}


def test_dask_local_cluster_gets_exactly_the_local_numbers():
    distributed = pytest.importorskip("distributed")
    recs = load_spec(SPEC).expand()
    local = ResultStore()
    assert run_records(recs, local, workers=1, progress=False).failed == 6
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, host="127.0.0.1",
                                  protocol="tcp", dashboard_address=None) as cluster:
        host_port = cluster.scheduler_address.split("://", 1)[1]
        remote = ResultStore()
        rep = run_records(recs, remote, executor=f"dask://{host_port}", progress=False)
    assert (rep.ran, rep.failed) == (18, 6)
    assert numbers(remote) == numbers(local)
    traces_local, traces_remote = local.traces(local.rows()), remote.traces(remote.rows())
    assert traces_local == traces_remote  # paths and convergence histories too


def test_killed_experiment_resumes_with_only_the_missing_runs(tmp_path):
    # runs of ~0.1-0.5 s so that the kill lands in the middle of the experiment
    spec_file = tmp_path / "slow.yaml"
    spec_file.write_text("name: slow\nkind: plan\nmaps: [chen2025_40]\nalgorithms: [gwo]\n"
                         "params: {pop: 40, iters: 1000}\nruns: 10\n")
    db = tmp_path / "slow.sqlite"
    cmd = [sys.executable, "-m", "optplan", "bench", str(spec_file), "--db", str(db), "--workers", "1",
           "--no-progress"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        stored = 0
        while time.monotonic() < deadline and proc.poll() is None:
            if db.exists():
                with ResultStore(db) as s:
                    stored = s.count()
                if stored >= 3:
                    break
            time.sleep(0.05)
        assert proc.poll() is None, "the experiment finished before it could be killed"
        os.killpg(proc.pid, signal.SIGKILL)  # no chance to clean up
    finally:
        proc.wait(timeout=30)
        proc.stdout.close()
        proc.stderr.close()
    import sqlite3

    with sqlite3.connect(db) as con:  # the killed writer left a sound database
        assert con.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    with ResultStore(db) as s:
        before = s.rows()
    assert 3 <= len(before) < 10 and all(r["status"] == "ok" for r in before.values())

    rerun = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert rerun.returncode == 0, rerun.stderr[-2000:]
    assert f"10 runs: {len(before)} already in the database, {10 - len(before)} ran (0 failed)" in rerun.stderr
    with ResultStore(db) as s:
        after = s.rows()
    assert len(after) == 10 and sorted(r["seed"] for r in after.values()) == list(range(10))
    for k, row in before.items():  # the runs stored before the kill were not run again
        assert after[k]["finished_at"] == row["finished_at"] and after[k]["wall_s"] == row["wall_s"]
    # and the resumed experiment has the numbers of an uninterrupted one (first and last run)
    fresh = ResultStore()
    recs = load_spec(spec_file).expand()
    run_records([recs[0], recs[-1]], fresh, workers=1, progress=False)
    for k, row in numbers(fresh).items():
        assert {c: v for c, v in after[k].items() if c not in CLOCK} == row
