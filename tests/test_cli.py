"""The command line: exit codes, one-line errors, the JSON contract, the demo."""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

import optplan as op
from optplan.cli import main

PLAN_KEYS = {"algorithm", "feasible", "path", "length", "turn_angle_deg", "n_turns", "min_clearance",
             "runtime_s", "refined", "seed", "encoding",
             # issue 26: the gap to the exact optimum split into the class gap and the in-class gap
             "exact_length", "class_length", "gap", "class_gap", "in_class_gap", "optimal_class"}


def run_cli(*args):
    proc = subprocess.run([sys.executable, "-m", "optplan", *args], capture_output=True, text=True, timeout=300)
    return proc.returncode, proc.stdout, proc.stderr


def test_plan_json_has_exactly_the_contract_keys(capsys):
    code = main(["plan", "multialgo20_template", "--start", "0.5", "0.5", "--goal", "19.5", "19.5",
                 "--algo", "astar", "--json"])
    out = capsys.readouterr().out.strip().splitlines()
    assert code == 0 and len(out) == 1
    d = json.loads(out[0])
    assert set(d) == PLAN_KEYS
    assert d["feasible"] is True and d["algorithm"] == "astar"
    g = op.load_map("multialgo20_template")
    assert op.validate_path(g, np.array(d["path"]))
    assert d["length"] == pytest.approx(np.hypot(*np.diff(np.array(d["path"]), axis=0).T).sum())


@pytest.mark.parametrize("args,needle", [
    (["plan", "no_such_map", "--start", "0", "0", "--goal", "1", "1"], "does not exist"),
    (["plan", "multialgo20_template", "--start", "0.5", "0.5", "--goal", "25", "25"], "outside the map"),
    (["plan", "multialgo20_template", "--start", "0.5", "0.5", "--goal", "19.5", "19.5", "--algo", "nope"], "unknown"),
])
def test_errors_print_one_line_and_exit_2(args, needle):
    code, out, err = run_cli(*args)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0] and "Traceback" not in err


def test_start_in_obstacle_is_reported(tmp_path, capsys):
    f = tmp_path / "m.txt"
    f.write_text("0 0 0\n0 1 0\n0 0 0\n")
    code = main(["plan", str(f), "--start", "1.5", "1.5", "--goal", "0.5", "0.5"])
    assert code == 2 and "blocked cell" in capsys.readouterr().err


def test_unreachable_goal_is_reported(tmp_path, capsys):
    f = tmp_path / "m.txt"
    f.write_text("0 1 0\n0 1 0\n0 1 0\n")
    code = main(["plan", str(f), "--start", "0.5", "0.5", "--goal", "2.5", "2.5", "--algo", "visibility"])
    assert code == 2 and "unreachable" in capsys.readouterr().err.lower()


def test_algorithms_lists_graph_methods(capsys):
    assert main(["algorithms"]) == 0
    names = capsys.readouterr().out.split()
    assert {"astar", "visibility"} <= set(names)


def test_help_shows_an_example():
    code, out, _ = run_cli("plan", "--help")
    assert code == 0 and "example:" in out


def test_demo_prints_table_and_writes_png(tmp_path, capsys):
    png = tmp_path / "demo.png"
    assert main(["demo", "--out", str(png)]) == 0
    out = capsys.readouterr().out
    assert "| astar |" in out and "| visibility |" in out and "gap to exact optimum" in out
    assert png.stat().st_size > 5000 and png.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("argv", [
    ["plan", "multialgo20_template", "--start", "0.5", "0.5", "--goal", "19.5", "19.5", "--plot", "{file}/x.png"],
    ["plan", "multialgo20_template", "--start", "0.5", "0.5", "--goal", "19.5", "19.5", "--plot", "{dir}"],
    ["simulate", "li2023_exp1", "--gif", "{file}/run.gif"],
    ["demo", "--out", "{file}/demo.png"],
])
def test_unwritable_outputs_are_refused_before_any_work(tmp_path, capsys, argv):
    """An output under a regular file, or a folder given as a file: one line, exit 2, and
    nothing is planned or simulated first."""
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    args = [a.format(file=blocker, dir=tmp_path) for a in argv]
    code = main(args)
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "optplan: error:" in err


def test_demo_figure_shows_the_optimum_on_top_and_post_processing_on_a_linear_axis():
    """The exact optimum is drawn above every other path; the convergence panel is linear and
    marks each path's length after post-processing, so a refined run differs from its search."""
    from optplan import demo
    from optplan.planning import plan

    grid = demo.load_map(demo.DEMO_MAP)
    q = (grid, demo.DEMO_START, demo.DEMO_GOAL)
    results = {"visibility": plan(*q, algorithm="visibility"),
               "msiar-gwo": plan(*q, algorithm="msiar-gwo", seed=0, pop=10, iters=20),
               "msiar-gwo + qp": plan(*q, algorithm="msiar-gwo", seed=0, pop=10, iters=20, refine="qp")}
    fig = demo.demo_figure(grid, results, results["visibility"].length, None)
    ax_map, ax_conv = fig.axes[:2]
    band = [ln for ln in ax_map.lines if ln.get_label() == "exact optimum (visibility)"]
    others = [ln for ln in ax_map.lines if ln.get_label() in ("msiar-gwo", "msiar-gwo + qp")]
    assert band and others and band[0].get_zorder() > max(ln.get_zorder() for ln in others)
    assert ax_conv.get_yscale() == "linear"
    marks = {ln.get_label(): ln.get_ydata()[-1] for ln in ax_conv.lines if len(ln.get_ydata()) == 1}
    refined = [v for k, v in marks.items() if k.startswith("msiar-gwo + qp")]
    assert refined and np.isclose(refined[0], results["msiar-gwo + qp"].length)
    ends = [ln.get_ydata()[-1] for ln in ax_conv.lines if ln.get_marker() == "D" and len(ln.get_ydata()) == 1]
    assert any(np.isclose(v, results["msiar-gwo"].length) for v in ends)


def test_a_closed_output_pipe_prints_no_error(tmp_path):
    """`optplan plan ... | head`: the reader goes away; no 'error' line, status 141 (SIGPIPE)."""
    import os
    from pathlib import Path

    child = ("import os, sys\n"
             "r, w = os.pipe(); os.close(r); os.dup2(w, 1)\n"   # stdout is a pipe nobody reads
             "from optplan.cli import main\n"
             "code = main(['plan', 'chen2025_20', '--algo', 'astar', '--json'])\n"
             "sys.stderr.write(f'status {code}\\n')\n")
    root = Path(__file__).resolve().parents[1]
    env = {**os.environ, "PYTHONPATH": str(root)}
    done = subprocess.run([sys.executable, "-c", child], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=120)
    assert done.stderr.strip() == "status 141", done.stderr


def test_an_mp4_without_ffmpeg_is_refused_before_any_work(tmp_path, capsys, monkeypatch):
    import matplotlib

    monkeypatch.setitem(matplotlib.rcParams, "animation.ffmpeg_path", str(tmp_path / "no-ffmpeg"))
    code = main(["simulate", "li2023_exp1", "--gif", str(tmp_path / "run.mp4")])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and "ffmpeg" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "run.mp4").exists()
    assert main(["simulate", "li2023_exp1", "--gif", str(tmp_path / "run.avi")]) == 2
    assert ".gif or .mp4" in capsys.readouterr().err


def test_an_mp4_gets_every_frame_through_ffmpeg(tmp_path, monkeypatch):
    """MP4 frames are piped to ffmpeg as raw RGB: a stand-in ffmpeg checks the byte count
    against the size and frame rate it is told, and writes the file."""
    import matplotlib

    import optplan as op
    from optplan.sim.closed_loop import realized_scenario
    from optplan.viz.animate import animate_run

    fake = tmp_path / "ffmpeg"
    fake.write_text("#!" + sys.executable + "\n"
                    "import sys\n"
                    "a = sys.argv\n"
                    "w, h = map(int, a[a.index('-s') + 1].split('x'))\n"
                    "data = sys.stdin.buffer.read()\n"
                    "assert len(data) % (w * h * 3) == 0, 'partial frame'\n"
                    "open(a[-1], 'w').write(f'{len(data) // (w * h * 3)} {a[a.index(\"-r\") + 1]}')\n")
    fake.chmod(0o755)
    monkeypatch.setitem(matplotlib.rcParams, "animation.ffmpeg_path", str(fake))
    sc = op.load_scenario("li2023_exp1")
    res = op.simulate(sc, global_planner="astar", local_planner="dwa", seed=0, time_limit=3)
    out = animate_run(realized_scenario(sc, 0, None), res, tmp_path / "run.mp4", fps=10, max_frames=12)
    frames, fps = out.read_text().split()
    # the run's frames and the last one held for two seconds
    assert int(frames) == min(12, len(res.trajectory)) + 20 and fps == "10"


def test_simulate_says_how_a_blocked_path_is_answered(capsys):
    # --on-blocked / --replanner reach op.simulate (the API's on_blocked / replanner options)
    assert main(["simulate", "yuan2021_path_switch", "--local", "ba-dwa", "--on-blocked", "switch"]) == 0
    out = capsys.readouterr().out
    assert "(2 path switches)" in out and "ms per answer to a blocked path" in out
    assert main(["simulate", "yuan2021_path_switch", "--local", "ba-dwa", "--on-blocked", "replan",
                 "--replanner", "global"]) == 0
    out = capsys.readouterr().out
    assert "(0 path switches)" in out and "ms per answer to a blocked path" in out
    code, out, err = run_cli("simulate", "yuan2021_path_switch", "--replanner", "iba")
    assert code == 2 and out == "" and "--replanner" in err and len(err.strip().splitlines()) == 1
