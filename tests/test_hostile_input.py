"""Hostile input: every bad file or query gives one clear OptplanError, never a crash.

The fuzz tests feed random and mutated bytes to every map loader; the contract is
that each input either loads into a valid map or raises ``MapFormatError``.
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import optplan as op
from optplan.cli import main
from optplan.world.papermaps import paper_map

SUFFIXES = (".map", ".txt", ".csv", ".npy", ".pgm", ".yaml", ".json")

VALID = {
    ".map": b"type octile\nheight 3\nwidth 4\nmap\n..@.\n.@..\n....\n",
    ".txt": b"0 0 1\n0 1 0\n0 0 0\n",
    ".csv": b"0,0,1\n0,1,0\n0,0,0\n",
    ".pgm": b"P2\n3 2\n255\n254 0 254\n254 254 0\n",
    ".yaml": b"image: m.pgm\nresolution: 0.5\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
             b"occupied_thresh: 0.65\nfree_thresh: 0.196\n",
    ".json": b'{"bounds": [0, 0, 10, 10], "circles": [[5, 5, 1]], "safety": 0.1}',
}

FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


def _load_or_map_error(path):
    """Load ``path``; a MapFormatError is an accepted outcome, anything else fails the test."""
    try:
        world = op.load_map(path)
    except op.MapFormatError as exc:
        assert str(exc), "an error must say what was wrong"
        return None
    if isinstance(world, op.GridMap):
        assert world.occ.dtype == bool and world.occ.ndim == 2 and not world.occ.all()
    else:
        assert isinstance(world, op.CircleWorld)
    return world


@FUZZ
@given(suffix=st.sampled_from(SUFFIXES), data=st.binary(max_size=400))
def test_random_bytes_load_or_raise_map_format_error(tmp_path, suffix, data):
    p = tmp_path / f"fuzz{suffix}"
    p.write_bytes(data)
    if suffix == ".yaml":  # give the metadata an image to point at
        (tmp_path / "m.pgm").write_bytes(VALID[".pgm"])
    _load_or_map_error(p)


@FUZZ
@given(suffix=st.sampled_from(sorted(VALID)), cut=st.integers(0, 200), flips=st.lists(
    st.tuples(st.integers(0, 200), st.integers(0, 255)), max_size=4))
def test_truncated_and_corrupted_valid_files(tmp_path, suffix, cut, flips):
    raw = bytearray(VALID[suffix])
    for pos, byte in flips:
        raw[pos % len(raw)] = byte
    raw = bytes(raw[: max(cut, 0)] if cut < len(raw) else raw)
    p = tmp_path / f"mut{suffix}"
    p.write_bytes(raw)
    (tmp_path / "m.pgm").write_bytes(VALID[".pgm"])
    _load_or_map_error(p)


@pytest.mark.parametrize("suffix", sorted(VALID))
def test_the_unmutated_fixtures_load(tmp_path, suffix):
    p = tmp_path / f"ok{suffix}"
    p.write_bytes(VALID[suffix])
    (tmp_path / "m.pgm").write_bytes(VALID[".pgm"])
    assert _load_or_map_error(p) is not None


@pytest.mark.parametrize("suffix,content", [
    (".txt", b"1 1\n1 1\n"),
    (".map", b"type octile\nheight 2\nwidth 2\nmap\n@@\nTT\n"),
])
def test_map_with_no_free_cell_is_refused(tmp_path, suffix, content):
    p = tmp_path / f"full{suffix}"
    p.write_bytes(content)
    with pytest.raises(op.MapFormatError, match="every cell"):
        op.load_map(p)


def test_huge_declared_map_is_refused_without_allocating(tmp_path):
    p = tmp_path / "huge.map"
    p.write_text("type octile\nheight 100000\nwidth 100000\nmap\n....\n")
    with pytest.raises(op.MapFormatError, match="exceeds the limit"):
        op.load_map(p)


@pytest.mark.parametrize("algorithm", ["astar", "visibility", "gwo"])
def test_start_equal_to_goal_is_an_error(algorithm):
    world, s, _ = paper_map("chen2025_20")
    with pytest.raises(op.InfeasibleQueryError, match="same point"):
        op.plan(world, s, s, algorithm=algorithm, pop=5, iters=5)


def test_start_equal_to_goal_on_a_circle_world():
    world, s, _ = paper_map("yang2023_env1")
    with pytest.raises(op.InfeasibleQueryError, match="same point"):
        op.shortest_path(world, s, s, method="visibility")


@pytest.mark.parametrize("kwargs,needle", [
    ({"pop": 0}, "pop"), ({"iters": -1}, "iters"), ({"clearance": float("nan")}, "clearance"),
    ({"clearance": -0.5}, "clearance"), ({"seed": -1}, "seed"), ({"refine": "ipopt"}, "refine"),
    ({"algorithm": "no-such"}, "unknown"),
])
def test_bad_parameters_raise_parameter_errors(kwargs, needle):
    world, s, g = paper_map("chen2025_20")
    args = {"algorithm": "gwo", "pop": 5, "iters": 5, **kwargs}
    with pytest.raises(op.OptplanError, match=needle):
        op.plan(world, s, g, **args)


def test_cli_reports_equal_start_goal_on_one_line(capsys):
    code = main(["plan", "multialgo20_template", "--start", "0.5", "0.5", "--goal", "0.5", "0.5"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "same point" in err[0]


def test_unreachable_goal_on_a_walled_map():
    rows = [[0, 0, 1, 0, 0]] * 5  # a full wall between the two halves
    world = op.GridMap.from_rows(np.array(rows))
    for method in ("astar", "visibility"):
        with pytest.raises(op.InfeasibleQueryError):
            op.shortest_path(world, (0.5, 0.5), (4.5, 4.5), method=method)
