"""Issue 48's hostile inputs: special files, lying headers, booleans and huge numbers where
numbers go, duplicate YAML keys, and objectives that give no answer. Each ends in one
OptplanError line (or a result that says it has no answer), never a hang or a traceback."""
from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

import optplan as op

ROS_META = "resolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"


def _cli(*args, timeout=60):
    return subprocess.run([sys.executable, "-m", "optplan", *args], capture_output=True, text=True, timeout=timeout)


@pytest.mark.parametrize("suffix", [".pgm", ".yaml", ".json", ".npy", ".map", ".txt"])
def test_a_fifo_as_a_map_is_refused_at_once(tmp_path, suffix):
    fifo = tmp_path / f"pipe{suffix}"
    os.mkfifo(fifo)
    with pytest.raises(op.MapFormatError, match="named pipe"):
        op.load_map(fifo)          # a read would block forever: this must return at once


@pytest.mark.parametrize("image", ["pipe.pgm", "/dev/zero", "zero.pgm", "a\0b.pgm"])
def test_a_ros_yaml_naming_a_special_file_is_refused(tmp_path, image):
    os.mkfifo(tmp_path / "pipe.pgm")
    os.symlink("/dev/zero", tmp_path / "zero.pgm")
    meta = tmp_path / "map.yaml"
    meta.write_text(f"image: {image!r}\n".replace("\\x00", "\\0").replace("'", '"') + ROS_META)
    with pytest.raises(op.MapFormatError, match="pipe|device|NUL|neither"):
        op.load_map(meta)


def test_devices_are_refused_directly_and_by_symlink(tmp_path):
    os.symlink("/dev/urandom", tmp_path / "noise.pgm")
    for path in ("/dev/zero", tmp_path / "noise.pgm"):
        with pytest.raises(op.MapFormatError, match="device"):
            op.load_map(path)


def test_the_cli_reports_a_fifo_in_one_line(tmp_path):
    os.mkfifo(tmp_path / "m.yaml")
    done = _cli("plan", str(tmp_path / "m.yaml"), "--start", "1", "1", "--goal", "2", "2")
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "named pipe" in done.stderr


def test_a_movingai_header_that_says_fewer_rows_than_the_file_holds_is_refused(tmp_path):
    p = tmp_path / "m.map"
    p.write_text("type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n...\n")
    with pytest.raises(op.MapFormatError, match="header says 2 rows, the file has 3"):
        op.load_map(p)


def test_booleans_and_huge_numbers_are_not_numbers(tmp_path):
    (tmp_path / "m.pgm").write_bytes(b"P2\n3 2\n255\n254 0 254\n254 254 0\n")
    meta = tmp_path / "m.yaml"
    meta.write_text("image: m.pgm\n" + ROS_META.replace("resolution: 0.05", "resolution: true"))
    with pytest.raises(op.MapFormatError, match="true/false"):
        op.load_map(meta)
    scen = tmp_path / "s.yaml"
    scen.write_text("map: [[0, 0, 0], [0, 0, 0]]\nstart: [0.5, 0.5, 0]\ngoal: [2.5, 1.5]\n"
                    f"sensor_range: {'9' * 400}\n")
    with pytest.raises(op.ScenarioError, match="400 digits"):
        op.load_scenario(scen)
    with pytest.raises(op.ParameterError, match="clearance"):
        op.plan(op.GridMap(np.zeros((4, 4), bool)), (0.5, 0.5), (3.5, 3.5), algorithm="astar", clearance=10 ** 400)


@pytest.mark.parametrize("text", [
    "map: [[0, 0], [0, 0]]\nstart: [0.5, 0.5, 0]\ngoal: [1.5, 1.5]\ngoal: [0.5, 1.5]\n",
    "map: [[0, 0], [0, 0]]\nstart: [0.5, 0.5, 0]\ngoal: [1.5, 1.5]\nrobot: {radius: 0.1, radius: 0.2}\n",
])
def test_a_key_given_twice_in_a_scenario_is_refused(tmp_path, text):
    p = tmp_path / "s.yaml"
    p.write_text(text)
    with pytest.raises(op.ScenarioError, match="given twice"):
        op.load_scenario(p)


# ------------------------------------------------------------------ op.optimize
BOX = [(-5.0, 5.0)] * 3


@pytest.mark.parametrize("value", [np.nan, -np.inf, np.inf])
def test_an_objective_without_a_finite_value_gives_no_answer(value):
    r = op.optimize(lambda X: np.full(len(X), value), BOX, algorithm="gwo", iters=5, seed=0)
    assert r.success is False and "no answer" in r.message and r.fun == r.f


def test_a_finite_run_succeeds_and_a_feasibility_failure_does_not():
    ok = op.optimize(lambda X: (X ** 2).sum(1), BOX, algorithm="gwo", iters=20, seed=0)
    assert ok.success and ok.fun < 1.0
    never = op.optimize(lambda X: ((X ** 2).sum(1), np.ones(len(X))), BOX, algorithm="gwo", iters=5, seed=0)
    assert not never.success and "no feasible point" in never.message


@pytest.mark.parametrize("f,match", [
    (lambda X: (X ** 2).sum(1) + 1j, "complex"),
    (lambda X: np.array(["a"] * len(X)), "must return numbers"),
    (lambda x: "a", "must return numbers"),
])
def test_objectives_of_the_wrong_type_are_refused(f, match):
    with pytest.raises(op.ParameterError, match=match):
        op.optimize(f, BOX, algorithm="pso", iters=5, seed=0)


def test_nan_init_and_overflowing_bounds_are_refused_before_the_run():
    calls = []

    def f(X):
        calls.append(len(X))
        return (X ** 2).sum(1)

    with pytest.raises(op.ParameterError, match="init"):
        op.optimize(f, BOX, algorithm="gwo", iters=5, init=np.full((30, 3), np.nan))
    with pytest.raises(op.ParameterError, match="too wide"):
        op.optimize(f, [(-1e308, 1e308)] * 3, algorithm="gwo", iters=5)
    assert calls == []


def test_scipy_style_objectives_and_bounds():
    from scipy.optimize import Bounds

    ref = op.optimize(lambda X: (X ** 2).sum(1), BOX, algorithm="pso", seed=0)
    for bounds in (Bounds([-5] * 3, [5] * 3), BOX, ([-5.0] * 3, [5.0] * 3), np.array(BOX)):
        for f in (lambda x: float(x @ x), lambda X: (X ** 2).sum(1)):
            r = op.optimize(f, bounds, algorithm="pso", seed=0)
            assert r.success and r.fun == ref.fun and np.array_equal(r.x, ref.x)
    # a function of one point that indexes its coordinates (d = 2, so X[0] has the batch's shape)
    r = op.optimize(lambda x: (x[0] - 1) ** 2 + (x[1] + 2) ** 2, [(-5, 5)] * 2, algorithm="pso", seed=0)
    assert r.success and np.allclose(r.x, [1, -2], atol=1e-3)


# ------------------------------------------------------------------ outputs whole or not at all
def test_a_full_disk_leaves_no_partial_export_and_names_the_file(tmp_path, monkeypatch):
    import numpy as np_

    target = tmp_path / "path.csv"
    target.write_text("old contents\n")

    def savetxt(fname, *a, **k):
        with open(fname, "w") as fh:
            fh.write("x,y\n0.5,")          # half a file, then the disk is full
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(np_, "savetxt", savetxt)
    with pytest.raises(op.OptplanError, match=f"{target}.*No space left"):
        op.export_path(np.array([[0.5, 0.5], [1.5, 1.5]]), target)
    assert target.read_text() == "old contents\n"          # the old file is untouched
    assert sorted(p.name for p in tmp_path.iterdir()) == ["path.csv"]   # no temporary left


def test_the_cli_reports_a_write_failure_in_one_line_with_the_path(tmp_path, monkeypatch):
    from optplan.cli import main
    import matplotlib.figure

    def savefig(self, fname, *a, **k):
        with open(fname, "wb") as fh:
            fh.write(b"\x89PNG")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", savefig)
    out = tmp_path / "p.png"
    code = main(["plan", "chen2025_20", "--algo", "astar", "--plot", str(out)])
    assert code == 2 and not out.exists() and list(tmp_path.iterdir()) == []


# ------------------------------------------------------------------ inherent costs: refused up front
def test_a_method_whose_own_tables_exceed_the_memory_budget_is_refused_with_the_figure(monkeypatch):
    monkeypatch.setenv("OPTPLAN_MEMORY_GB", "0.01")
    grid = op.GridMap(np.zeros((400, 400), bool))
    with pytest.raises(op.ParameterError, match=r"about \d+ MB .* 0.01 GB budget.*astar"):
        op.shortest_path(grid, (0.5, 0.5), (399.5, 399.5), method="dijkstra")
    with pytest.raises(op.ParameterError, match="ACO with"):
        op.plan(grid, (0.5, 0.5), (399.5, 399.5), algorithm="aco", iters=2)
    # A* keeps one byte a cell: it plans under the same budget
    assert op.shortest_path(grid, (0.5, 0.5), (399.5, 399.5), method="astar").feasible
    # a swarm whose fitness samples the distance field is refused before the sampler runs
    import tracemalloc

    tracemalloc.start()
    try:
        with pytest.raises(op.ParameterError, match="distance field"):
            op.plan(grid, (0.5, 0.5), (399.5, 399.5), algorithm="gwo", encoding="paper", max_evals=100, iters=None,
                    pop=10)
        assert tracemalloc.get_traced_memory()[1] < 20e6
    finally:
        tracemalloc.stop()
    # the default (general) encoding needs no distance field: it plans under the same budget
    r = op.plan(grid, (0.5, 0.5), (399.5, 399.5), algorithm="gwo", max_evals=100, iters=None, pop=10)
    assert r.feasible and r.encoding == "general"


def test_every_case_of_the_hostile_input_script_ends_in_one_line():
    """benchmarks/hostile_inputs.py: 50 hostile command lines, each handled (no traceback,
    hang or partial output)."""
    from pathlib import Path

    script = Path(__file__).resolve().parents[1] / "benchmarks" / "hostile_inputs.py"
    done = subprocess.run([sys.executable, str(script), "--timeout", "60"], capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stdout[-3000:]
    assert " 0 traceback, 0 hang, 0 partial, 0 other" in done.stdout


def test_every_listed_map_name_loads_and_the_readmes_scenario_ships():
    """Issue 47: 'paper_maps' (the catalogue) was offered as a map and failed; the README's
    `--scen arena.map.scen` named a file that did not ship."""
    from optplan.world import maps
    from optplan.cli import main

    assert "paper_maps" not in maps.names()
    for name in maps.names():
        op.load_map(name)
    assert main(["plan", "arena.map", "--scen", "arena.map.scen", "--query", "40", "--json"]) == 0


def test_the_population_hint_names_a_value_that_is_accepted():
    """Issue 47: the 'pop <= N' hint of a population too large for memory named values the
    evaluation bound then refused."""
    import re

    from optplan.checks import population_budget

    with pytest.raises(op.ParameterError) as exc:
        population_budget(10 ** 12, 500, None, dim=10)
    top = int(re.search(r"pop <= (\d+)", str(exc.value)).group(1))
    population_budget(top, 500, None, dim=10)            # accepted
