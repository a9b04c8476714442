"""What a newcomer reaches for first: --version, a paper map by name, a Moving AI query,
an evaluation budget, and a spec that uses .scen queries."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import optplan as op
from optplan.cli import main

ARENA = Path(op.__file__).resolve().parent / "data" / "maps" / "arena.map"


def test_version_is_the_package_version(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0 and capsys.readouterr().out.strip() == f"optplan {op.__version__}"


def test_plan_a_paper_map_by_name_with_its_own_start_and_goal(capsys):
    assert main(["plan", "chen2025_20", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    _, s, g = op.world.papermaps.paper_map("chen2025_20")
    assert out["feasible"] and out["path"][0] == list(s) and out["path"][-1] == list(g)


def test_max_evals_is_the_budget(capsys):
    assert main(["plan", "chen2025_20", "--algo", "gwo", "--max-evals", "200", "--pop", "20", "--json"]) == 0
    capsys.readouterr()
    r = op.plan(*op.world.papermaps.paper_map("chen2025_20"), algorithm="gwo", pop=20, iters=None, max_evals=200)
    assert "200" in r.message


def test_a_moving_ai_query_from_the_command_line(tmp_path, capsys):
    (tmp_path / "q.map").write_text("type octile\nheight 3\nwidth 4\nmap\n@...\n....\n....\n")
    (tmp_path / "q.scen").write_text("version 1\n0\tq.map\t4\t3\t0\t2\t3\t0\t3.8284\n")
    assert main(["plan", str(tmp_path / "q.map"), "--scen", str(tmp_path / "q.scen"), "--query", "0",
                 "--algo", "dijkstra", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    # x = column, y = row from the top: (0, 2) is the bottom-left cell, (3, 0) the top-right one
    assert out["path"][0] == [0.5, 0.5] and out["path"][-1] == [3.5, 2.5]
    assert out["length"] == pytest.approx(3.8284, abs=1e-4)


def test_a_spec_runs_scen_queries_and_the_octile_optimum_matches(tmp_path):
    from optplan.bench import run_experiment

    (tmp_path / "q.map").write_text("type octile\nheight 3\nwidth 4\nmap\n@...\n....\n....\n")
    (tmp_path / "q.scen").write_text("version 1\n0\tq.map\t4\t3\t0\t2\t3\t0\t3.8284\n"
                                     "0\tq.map\t4\t3\t1\t0\t3\t2\t2.8284\n")
    spec = tmp_path / "s.yaml"
    spec.write_text("kind: plan\nmaps: [{scen: q.scen}]\nalgorithms: [dijkstra]\nruns: 1\n")
    res = run_experiment(spec, workers=1, progress=False)
    rows = sorted(res.rows.values(), key=lambda r: r["target"])
    assert [r["target"] for r in rows] == ["q_q0", "q_q1"]
    assert all(r["status"] == "ok" for r in rows)
    assert np.allclose([r["length"] for r in rows], [3.8284, 2.8284], atol=1e-4)
    (tmp_path / "q.scen").write_text("version 1\n0\tq.map\t4\t3\t0\t0\t3\t2\t3.6056\n")  # starts on '@'
    with pytest.raises(op.OptplanError, match="query 0 start"):
        run_experiment(spec, workers=1, progress=False)


def test_the_python_keyword_names_are_accepted_as_flags(capsys):
    """``--algorithm``, ``--global-planner`` and ``--local-planner`` (the keywords of op.plan and
    op.simulate) mean what ``--algo``, ``--global`` and ``--local`` mean."""
    assert main(["plan", "chen2025_20", "--algorithm", "dijkstra", "--json"]) == 0
    long = json.loads(capsys.readouterr().out)
    assert main(["plan", "chen2025_20", "--algo", "dijkstra", "--json"]) == 0
    short = json.loads(capsys.readouterr().out)
    assert long["algorithm"] == "dijkstra" and long["path"] == short["path"]
    # the planner name reaches the check of local planners
    assert main(["simulate", "li2023_exp1", "--global-planner", "astar", "--local-planner", "no-such-dwa"]) == 2
    assert "unknown local planner 'no-such-dwa'" in capsys.readouterr().err


@pytest.mark.parametrize("call,meant", [
    (lambda: op.plan(*op.world.papermaps.paper_map("chen2025_20"), algorithm="gwo", itrs=3), "iters"),
    (lambda: op.plan(*op.world.papermaps.paper_map("chen2025_20"), algorithm="gwo", population=3), "pop"),
    (lambda: op.optimize(lambda X: X.sum(1), [(0, 1)] * 3, algorithm="gwo", population=30), "pop"),
    (lambda: op.optimize(lambda X: X.sum(1), [(0, 1)] * 3, algorithm="gwo", a_inital=2.0), "a_initial"),
    (lambda: op.load_scenario({"map": "arena", "start": [1.5, 37.5], "goal": [40.5, 10.5], "robto": {}}), "robot"),
])
def test_a_misspelt_keyword_names_the_one_meant(call, meant):
    with pytest.raises(op.OptplanError, match=rf"\(did you mean '{meant}'\?\)"):
        call()


def test_an_unrelated_keyword_gets_no_guess():
    with pytest.raises(op.ParameterError) as exc:
        op.optimize(lambda X: X.sum(1), [(0, 1)] * 3, algorithm="gwo", colour="red")
    assert "'colour'" in str(exc.value) and "did you mean" not in str(exc.value)


def test_an_occupancy_array_passed_as_the_world_is_pointed_at_gridmap():
    occ = np.zeros((5, 5), bool)
    with pytest.raises(op.ParameterError, match=r"op\.GridMap\(occ"):
        op.plan(occ, (0.5, 0.5), (4.5, 4.5))
    assert op.plan(op.GridMap(occ), (0.5, 0.5), (4.5, 4.5)).length == pytest.approx(4 * np.sqrt(2))


def test_verbosity_flags_and_one_interrupt_line(tmp_path, capsys, monkeypatch):
    """-q keeps stderr to warnings and errors, the default prints the notes through the
    'optplan' logger; an interrupted bench says 'interrupted' once, with how to resume."""
    from optplan.cli import main

    spec = tmp_path / "s.yaml"
    spec.write_text("kind: plan\nmaps: [chen2025_20]\nalgorithms: [astar]\nruns: 1\n")
    db = str(tmp_path / "r.sqlite")
    assert main(["bench", str(spec), "--db", db, "--workers", "1", "-q"]) == 0
    assert capsys.readouterr().err == ""
    assert main(["bench", str(spec), "--db", db, "--workers", "1"]) == 0
    assert "already in the database" in capsys.readouterr().err

    import optplan.bench.command as command

    def interrupted(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(command, "run_spec", interrupted)
    assert main(["bench", str(spec), "--db", db, "--workers", "1"]) == 130
    err = capsys.readouterr().err
    assert err.count("interrupted") == 1 and "rerun the same command" in err


def test_warnings_print_as_one_line(tmp_path, capsys):
    """A ROS map's yaw and unknown cells are warned about on one 'optplan: warning:' line each
    (Python printed the source line of optplan that raised them)."""
    from optplan.cli import main

    (tmp_path / "m.pgm").write_bytes(b"P2\n3 2\n255\n254 0 205\n254 254 254\n")
    (tmp_path / "m.yaml").write_text("image: m.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.3]\n")
    assert main(["plan", str(tmp_path / "m.yaml"), "--start", "0.025", "0.025", "--goal", "0.125", "0.025",
                 "--algo", "astar"]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all(line.startswith("optplan: warning: ") for line in err)
    assert "yaw 0.3" in err[0] and "unknown" in err[1]


def test_bench_help_names_files_that_exist_where_the_package_is_installed(capsys):
    import re
    from pathlib import Path

    from optplan.cli import main

    with pytest.raises(SystemExit):
        main(["bench", "--help"])
    text = capsys.readouterr().out
    readme = re.search(r"Spec format: (\S+)", text).group(1)
    assert Path(readme).is_file()


def test_the_too_few_note_does_not_claim_fixed_sizes():
    from optplan.bench.stats import too_few_note

    note = too_few_note(0.05)
    assert "2 / C(n + m, n)" in note
