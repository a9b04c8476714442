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


# =============================================================================================
# The hostile-input suite: hundreds of bad maps, scenarios, specs, databases, command lines and
# API calls. Each must end in one OptplanError (API) or one stderr line and exit status 2
# (command line), within CASE_SECONDS of wall time and CASE_PEAK_BYTES of traced memory: no
# traceback, no other exception, no hang, no blow-up.
# =============================================================================================
import contextlib
from pathlib import Path
import signal
import sqlite3
import struct
import tracemalloc
import zlib

import yaml

from optplan.bench.spec import load_spec
from optplan.bench.store import ResultStore

CASE_SECONDS = 20            # wall time of one case (a hang becomes a failure, not a stuck run)
CASE_PEAK_BYTES = 512 << 20  # traced Python and numpy allocations of one case


@contextlib.contextmanager
def _bounded():
    """Fail a case that runs longer than CASE_SECONDS or allocates more than CASE_PEAK_BYTES."""
    def timeout(signum, frame):
        raise AssertionError(f"the case ran longer than {CASE_SECONDS} s")

    old = signal.signal(signal.SIGALRM, timeout)
    signal.alarm(CASE_SECONDS)
    tracemalloc.start()
    try:
        yield
        _, peak = tracemalloc.get_traced_memory()
        assert peak < CASE_PEAK_BYTES, f"the case allocated {peak / 2**20:.0f} MiB"
    finally:
        tracemalloc.stop()
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def _expect_api_error(call) -> op.OptplanError:
    with _bounded():
        try:
            call()
        except op.OptplanError as exc:
            message = str(exc)
            assert message and "\n" not in message.strip() and len(message) <= 4000, message[:300]
            return exc
        except Exception as exc:  # anything else is a defect
            raise AssertionError(f"{type(exc).__name__} instead of an OptplanError: {exc}") from exc
    raise AssertionError("no error was raised")


def _expect_cli_error(argv, capsys) -> str:
    with _bounded():
        try:
            code = main([str(a) for a in argv])
        except SystemExit as exc:  # argparse's own exits
            code = exc.code
    out, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2, f"exit status {code}; stderr: {err[-500:]}"
    assert len(lines) == 1 and lines[0].startswith("optplan"), f"stderr is not one line: {err[-800:]}"
    assert "Traceback" not in err and len(lines[0]) <= 2200
    return lines[0]


# ------------------------------------------------------------------------------ map files
def _png(width: int, height: int) -> bytes:
    """A PNG whose header declares ``width`` x ``height`` (the raster is one short row)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(b"\x00\xff")) + chunk(b"IEND", b""))


def _npy(arr) -> bytes:
    import io

    buf = io.BytesIO()
    np.save(buf, arr, allow_pickle=True)
    return buf.getvalue()


ROS = "image: m.pgm\nresolution: 0.5\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
BOMB = "".join(f"{k}: &{k} [{', '.join(['*' + p] * 9 if p else ['x'] * 9)}]\n"
               for k, p in zip("abcdefghi", ["", *"abcdefgh"]))

BAD_MAPS = [
    # Moving AI .map
    ("empty", ".map", b""),
    ("whitespace only", ".map", b"   \n\n"),
    ("no map line", ".map", b"type octile\nheight 2\nwidth 2\n..\n..\n"),
    ("no height", ".map", b"type octile\nwidth 2\nmap\n..\n..\n"),
    ("height text", ".map", b"type octile\nheight two\nwidth 2\nmap\n..\n..\n"),
    ("height zero", ".map", b"type octile\nheight 0\nwidth 2\nmap\n"),
    ("height negative", ".map", b"type octile\nheight -3\nwidth 2\nmap\n..\n"),
    ("height 1e308", ".map", b"type octile\nheight 1e308\nwidth 2\nmap\n..\n"),
    ("huge", ".map", b"type octile\nheight 99999999\nwidth 99999999\nmap\n..\n"),
    ("truncated", ".map", b"type octile\nheight 4\nwidth 2\nmap\n..\n..\n"),
    ("ragged", ".map", b"type octile\nheight 2\nwidth 3\nmap\n...\n..\n"),
    ("non latin-1", ".map", "type octile\nheight 1\nwidth 2\nmap\n.\u20ac\n".encode("utf-8")),
    ("emoji row", ".map", "type octile\nheight 2\nwidth 2\nmap\n..\n\U0001F600.\n".encode("utf-8")),
    ("nul bytes", ".map", b"type octile\nheight 1\nwidth 2\nmap\n.\x00\n"),
    ("all blocked", ".map", b"type octile\nheight 2\nwidth 2\nmap\n@@\n@@\n"),
    ("latin-1 width", ".map", b"type octile\nheight 1\nwidth 1\nmap\n\xe9\xe9\n"),
    ("header only", ".map", b"map\n"),
    # text and CSV matrices
    ("txt empty", ".txt", b""),
    ("txt comments only", ".txt", b"# nothing\n# here\n"),
    ("txt value 2", ".txt", b"0 2\n0 0\n"),
    ("txt negative", ".txt", b"0 -1\n0 0\n"),
    ("txt nan", ".txt", b"0 nan\n0 0\n"),
    ("txt inf", ".txt", b"0 inf\n0 0\n"),
    ("txt 1e308", ".txt", b"0 1e308\n0 0\n"),
    ("txt words", ".txt", b"free wall\n"),
    ("txt ragged", ".txt", b"0 0 0\n0 0\n"),
    ("txt all blocked", ".txt", b"1 1\n1 1\n"),
    ("txt binary", ".txt", b"\x00\x01\x02\x03"),
    ("csv ragged", ".csv", b"0,0\n0\n"),
    ("csv half", ".csv", b"0,0.5\n0,0\n"),
    ("csv empty cells", ".csv", b"0,,0\n0,0,0\n"),
    ("csv hex", ".csv", b"0x0,0\n0,0\n"),
    # numpy arrays
    ("npy garbage", ".npy", b"\x93NUMPY garbage"),
    ("npy 1-D", ".npy", _npy(np.zeros(5))),
    ("npy 3-D", ".npy", _npy(np.zeros((2, 2, 2)))),
    ("npy 0-D", ".npy", _npy(np.array(0))),
    ("npy empty", ".npy", _npy(np.zeros((0, 3)))),
    ("npy floats", ".npy", _npy(np.full((2, 2), 0.5))),
    ("npy nan", ".npy", _npy(np.array([[0.0, np.nan]]))),
    ("npy structured", ".npy", _npy(np.zeros((2, 2), dtype=[("a", "i4"), ("b", "f8")]))),
    ("npy object", ".npy", _npy(np.array([[0, None]], dtype=object))),
    ("npy strings", ".npy", _npy(np.array([["0", "1"]]))),
    ("npy complex", ".npy", _npy(np.zeros((2, 2), complex))),
    ("npy all blocked", ".npy", _npy(np.ones((2, 2), bool))),
    ("npy value 7", ".npy", _npy(np.array([[0, 7]]))),
    # PGM images
    ("pgm bad magic", ".pgm", b"P9\n2 2\n255\n0 0 0 0\n"),
    ("pgm no header", ".pgm", b"P2\n"),
    ("pgm maxval 0", ".pgm", b"P2\n2 1\n0\n0 0\n"),
    ("pgm maxval 70000", ".pgm", b"P2\n2 1\n70000\n0 0\n"),
    ("pgm values over maxval", ".pgm", b"P2\n2 1\n10\n0 11\n"),
    ("pgm too few values", ".pgm", b"P2\n3 2\n255\n0 0\n"),
    ("pgm text values", ".pgm", b"P2\n2 1\n255\na b\n"),
    ("pgm negative", ".pgm", b"P2\n2 1\n255\n-1 0\n"),
    ("pgm P5 short raster", ".pgm", b"P5\n4 4\n255\n\x00\x00"),
    ("pgm huge", ".pgm", b"P5\n100000 100000\n255\n\x00"),
    ("pgm all black", ".pgm", b"P2\n2 1\n255\n0 0\n"),
    ("pgm header text", ".pgm", b"P2\nwide 1\n255\n0\n"),
    # ROS map_server YAML
    ("ros missing image", ".yaml", ROS.replace("image: m.pgm\n", "").encode()),
    ("ros image not found", ".yaml", ROS.replace("m.pgm", "nope.pgm").encode()),
    ("ros image is folder", ".yaml", ROS.replace("m.pgm", ".").encode()),
    ("ros image /etc/passwd", ".yaml", ROS.replace("m.pgm", "/etc/passwd").encode()),
    ("ros resolution 0", ".yaml", ROS.replace("0.5", "0").encode()),
    ("ros resolution negative", ".yaml", ROS.replace("0.5", "-1").encode()),
    ("ros resolution 1e308", ".yaml", ROS.replace("0.5", "1e308").encode()),
    ("ros resolution nan", ".yaml", ROS.replace("0.5", ".nan").encode()),
    ("ros resolution text", ".yaml", ROS.replace("0.5", "fine").encode()),
    ("ros origin text", ".yaml", ROS.replace("[0.0, 0.0, 0.0]", "here").encode()),
    ("ros origin short", ".yaml", ROS.replace("[0.0, 0.0, 0.0]", "[1]").encode()),
    ("ros origin inf", ".yaml", ROS.replace("[0.0, 0.0, 0.0]", "[.inf, 0, 0]").encode()),
    ("ros origin huge", ".yaml", ROS.replace("[0.0, 0.0, 0.0]", "[1e308, 1e308, 0]").encode()),
    ("ros thresholds inverted", ".yaml", ROS.replace("0.196", "0.9").encode()),
    ("ros negate text", ".yaml", ROS.replace("negate: 0", "negate: maybe").encode()),
    ("ros mode unknown", ".yaml", (ROS + "mode: fuzzy\n").encode()),
    ("ros syntax error", ".yaml", b"image: [m.pgm\nresolution: 1\n"),
    ("ros top-level list", ".yaml", b"- image\n- m.pgm\n"),
    ("ros alias bomb", ".yaml", (ROS + BOMB).encode()),
    ("ros tab indent", ".yaml", b"image: m.pgm\n\tresolution: 1\n"),
    ("ros binary", ".yaml", b"\x00\x01\x02"),
    ("ros not utf-8", ".yaml", b"image: m\xff.pgm\n"),
    ("ros image png missing", ".yaml", ROS.replace("m.pgm", "m.png").encode()),
    ("ros image txt", ".yaml", ROS.replace("m.pgm", "m.txt").encode()),
    # circle worlds (JSON)
    ("json not json", ".json", b"{bounds: 1"),
    ("json top-level list", ".json", b"[1, 2, 3]"),
    ("json no circles", ".json", b'{"bounds": [0, 0, 10, 10]}'),
    ("json no bounds", ".json", b'{"circles": [[1, 1, 1]]}'),
    ("json circles flat", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [1, 2, 3]}'),
    ("json circle pairs", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [[1, 2]]}'),
    ("json circles dict", ".json", b'{"bounds": [0, 0, 10, 10], "circles": {"a": 1}}'),
    ("json circles text", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [["a", "b", "c"]]}'),
    ("json radius negative", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [[1, 1, -1]]}'),
    ("json radius nan", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [[1, 1, NaN]]}'),
    ("json bounds inverted", ".json", b'{"bounds": [10, 10, 0, 0], "circles": []}'),
    ("json bounds short", ".json", b'{"bounds": [0, 0, 10], "circles": []}'),
    ("json bounds text", ".json", b'{"bounds": "big", "circles": []}'),
    ("json bounds inf", ".json", b'{"bounds": [0, 0, Infinity, 10], "circles": []}'),
    ("json safety negative", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [], "safety": -1}'),
    ("json safety text", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [], "safety": "wide"}'),
    ("json ragged circles", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [[1, 1, 1], [2, 2]]}'),
    ("json nested deep", ".json", b"[" * 100000 + b"]" * 100000),
    ("json not utf-8", ".json", b'{"bounds": [0, 0, 10, 10], "circles": [], "name": "\xff"}'),
    ("json empty", ".json", b""),
    # raster images through Pillow
    ("png garbage", ".png", b"\x89PNG\r\n\x1a\nnot really"),
    ("png huge header", ".png", _png(200000, 200000)),
    ("png truncated", ".png", _png(4, 4)[:30]),
    ("bmp text", ".bmp", b"BM this is not a bitmap"),
    ("jpg empty", ".jpg", b""),
    ("gif garbage", ".gif", b"GIF89a\x00"),
    # names and suffixes
    ("unknown suffix", ".xyz", b"0 0\n"),
    ("no suffix", "", b"0 0\n"),
]


@pytest.mark.parametrize("label,suffix,content", BAD_MAPS, ids=[c[0] for c in BAD_MAPS])
def test_hostile_map_files_raise_map_errors(tmp_path, label, suffix, content):
    (tmp_path / "m.pgm").write_bytes(VALID[".pgm"])
    (tmp_path / "m.txt").write_bytes(b"0 0\n0 0\n")
    p = tmp_path / f"hostile{suffix}"
    p.write_bytes(content)
    _expect_api_error(lambda: op.load_map(p))


CLI_MAP_SAMPLE = [c for i, c in enumerate(BAD_MAPS) if i % 3 == 0]


@pytest.mark.parametrize("label,suffix,content", CLI_MAP_SAMPLE, ids=[c[0] for c in CLI_MAP_SAMPLE])
def test_hostile_map_files_on_the_command_line(tmp_path, capsys, label, suffix, content):
    (tmp_path / "m.pgm").write_bytes(VALID[".pgm"])
    p = tmp_path / f"hostile{suffix}"
    p.write_bytes(content)
    _expect_cli_error(["plan", p, "--start", "0.5", "0.5", "--goal", "1.5", "0.5"], capsys)


def test_map_paths_that_are_not_files(tmp_path, capsys):
    _expect_api_error(lambda: op.load_map(tmp_path))
    _expect_api_error(lambda: op.load_map(tmp_path / "missing.map"))
    _expect_cli_error(["plan", tmp_path, "--start", "0.5", "0.5", "--goal", "1.5", "0.5"], capsys)


# ------------------------------------------------------------------------------ scenarios
SCENARIO = {"map": [[0] * 8 for _ in range(8)], "resolution": 1.0,
            "robot": {"model": "unicycle", "radius": 0.2, "v_max": 1.0, "w_max_deg": 30, "a_max": 0.3,
                      "alpha_max_deg": 50},
            "start": [0.5, 0.5, 45], "goal": [7.5, 7.5], "sensor_range": 3.0, "dt": 0.1, "time_limit": 60}


def _scenario(**changes) -> dict:
    import copy

    d = copy.deepcopy(SCENARIO)
    for k, v in changes.items():
        if v is _DROP:
            d.pop(k, None)
        elif k == "robot_" and isinstance(v, dict):
            d["robot"].update(v)
        else:
            d[k] = v
    return d


_DROP = object()

BAD_SCENARIOS = [
    ("no map", _scenario(map=_DROP)),
    ("no start", _scenario(start=_DROP)),
    ("no goal", _scenario(goal=_DROP)),
    ("unknown key", _scenario(colour="red")),
    ("map missing file", _scenario(map="no_such_map.map")),
    ("map number", _scenario(map=3)),
    ("map ragged rows", _scenario(map=[[0, 0], [0]])),
    ("map values 2", _scenario(map=[[0, 2], [0, 0]])),
    ("map all blocked", _scenario(map=[[1, 1], [1, 1]])),
    ("map empty list", _scenario(map=[])),
    ("map text rows", _scenario(map=[["a", "b"]])),
    ("resolution 0", _scenario(resolution=0)),
    ("resolution negative", _scenario(resolution=-1)),
    ("resolution 1e308", _scenario(resolution=1e308)),
    ("resolution nan", _scenario(resolution=float("nan"))),
    ("resolution text", _scenario(resolution="fine")),
    ("start text", _scenario(start="home")),
    ("start short", _scenario(start=[1])),
    ("start nan", _scenario(start=[float("nan"), 1, 0])),
    ("start outside", _scenario(start=[-5, -5, 0])),
    ("start blocked", _scenario(map=[[0] * 8 for _ in range(7)] + [[1] + [0] * 7])),
    ("goal outside", _scenario(goal=[100, 100])),
    ("goal long", _scenario(goal=[1, 2, 3, 4])),
    ("dt 0", _scenario(dt=0)),
    ("dt negative", _scenario(dt=-0.1)),
    ("dt inf", _scenario(dt=float("inf"))),
    ("dt over time limit", _scenario(dt=100)),
    ("1e7 steps", _scenario(time_limit=1e7, dt=0.1)),
    ("1e12 steps", _scenario(time_limit=1e11, dt=0.1)),
    ("time limit negative", _scenario(time_limit=-1)),
    ("time limit text", _scenario(time_limit="long")),
    ("sensor negative", _scenario(sensor_range=-1)),
    ("sensor text", _scenario(sensor_range="far")),
    ("robot not mapping", _scenario(robot="fast")),
    ("robot unknown key", _scenario(robot_={"colour": "red"})),
    ("robot radius negative", _scenario(robot_={"radius": -0.2})),
    ("robot radius huge", _scenario(robot_={"radius": 1e6})),
    ("robot v_max 0", _scenario(robot_={"v_max": 0})),
    ("robot v_max nan", _scenario(robot_={"v_max": float("nan")})),
    ("robot a_max negative", _scenario(robot_={"a_max": -1})),
    ("robot model unknown", _scenario(robot_={"model": "hovercraft"})),
    ("robot w_max text", _scenario(robot_={"w_max_deg": "quick"})),
    ("unknown obstacles not list", _scenario(unknown_obstacles="many")),
    ("unknown obstacle bad key", _scenario(unknown_obstacles=[{"square": [1, 1]}])),
    ("unknown obstacle cells text", _scenario(unknown_obstacles=[{"cells": "a"}])),
    ("unknown obstacle cell outside", _scenario(unknown_obstacles=[{"cells": [[100, 100]]}])),
    ("unknown circle short", _scenario(unknown_obstacles=[{"circle": [1, 1]}])),
    ("unknown circle radius negative", _scenario(unknown_obstacles=[{"circle": [3, 3, -1]}])),
    ("dynamic not list", _scenario(dynamic_obstacles={"radius": 1})),
    ("dynamic no motion", _scenario(dynamic_obstacles=[{"radius": 0.3}])),
    ("dynamic radius negative", _scenario(dynamic_obstacles=[{"radius": -0.3, "start": [4, 4],
                                                               "velocity": [0, 0]}])),
    ("dynamic radius over half the map", _scenario(dynamic_obstacles=[{"radius": 6.0, "start": [4, 4],
                                                                       "velocity": [0.1, 0]}])),
    ("dynamic speed negative", _scenario(dynamic_obstacles=[{"radius": 0.3, "waypoints": [[2, 2], [5, 5]],
                                                             "speed": -1}])),
    ("dynamic speed nan", _scenario(dynamic_obstacles=[{"radius": 0.3, "waypoints": [[2, 2], [5, 5]],
                                                        "speed": float("nan")}])),
    ("dynamic velocity text", _scenario(dynamic_obstacles=[{"radius": 0.3, "start": [4, 4], "velocity": "east"}])),
    ("random obstacles huge", _scenario(random_obstacles={"count": 10 ** 9, "size": 1})),
    ("random obstacles text", _scenario(random_obstacles="some")),
    ("random dynamic huge", _scenario(random_dynamic={"count": 10 ** 7, "radius": 0.3, "speed": [0.1, 0.2]})),
    ("goal tolerance negative", _scenario(goal_tolerance=-1)),
    ("name list", _scenario(name=["a", "b"])),
]


@pytest.mark.parametrize("label,data", BAD_SCENARIOS, ids=[c[0] for c in BAD_SCENARIOS])
def test_hostile_scenarios_raise_scenario_errors(tmp_path, label, data):
    p = tmp_path / "s.yaml"
    p.write_text(yaml.safe_dump(data))
    _expect_api_error(lambda: op.load_scenario(p))


BAD_SCENARIO_TEXTS = [
    ("syntax error", "map: [[0, 0]\nstart: [0.5, 0.5]\n"),
    ("alias bomb", BOMB),
    ("top-level list", "- map\n- start\n"),
    ("empty", ""),
    ("only a comment", "# nothing\n"),
    ("not utf-8", "map: \xff\n"),
    ("tab indent", "map:\n\t- [0, 0]\n"),
    ("duplicate anchor use", "a: &a [0, 0]\nmap: [*a, *a]\nstart: *b\n"),
    ("binary", "\x00\x01\x02"),
    ("a python tag", "map: !!python/object/apply:os.system ['true']\n"),
]


@pytest.mark.parametrize("label,text", BAD_SCENARIO_TEXTS, ids=[c[0] for c in BAD_SCENARIO_TEXTS])
def test_hostile_scenario_files(tmp_path, capsys, label, text):
    p = tmp_path / "s.yaml"
    p.write_bytes(text.encode("latin-1"))
    _expect_api_error(lambda: op.load_scenario(p))
    _expect_cli_error(["simulate", p], capsys)


# ---------------------------------------------------------------------------------- specs
SPEC = {"kind": "plan", "maps": ["chen2025_20"], "algorithms": ["astar"], "runs": 1}


def _spec(**changes) -> dict:
    d = dict(SPEC)
    for k, v in changes.items():
        if v is _DROP:
            d.pop(k, None)
        else:
            d[k] = v
    return d


BAD_SPECS = [
    ("unknown key", _spec(colour="red")),
    ("unknown kind", _spec(kind="race")),
    ("no targets", _spec(maps=_DROP)),
    ("empty maps", _spec(maps=[])),
    ("unknown paper map", _spec(maps=["chen2099"])),
    ("map entry no start", _spec(maps=[{"map": "arena", "goal": [1, 1]}])),
    ("map entry start text", _spec(maps=[{"map": "arena", "start": "here", "goal": [1, 1]}])),
    ("map entry unknown key", _spec(maps=[{"map": "arena", "start": [1, 1], "goal": [2, 2], "size": 3}])),
    ("map entry missing file", _spec(maps=[{"map": "nope.map", "start": [1, 1], "goal": [2, 2]}])),
    ("map entry start blocked", _spec(maps=[{"map": "arena", "start": [0.5, 0.5], "goal": [40.5, 10.5]}])),
    ("map entry goal outside", _spec(maps=[{"map": "arena", "start": [1.5, 37.5], "goal": [400, 400]}])),
    ("map entry /etc/passwd", _spec(maps=[{"map": "/etc/passwd", "start": [1, 1], "goal": [2, 2]}])),
    ("map entry ../ escape", _spec(maps=[{"map": "../outside.map", "start": [0.5, 0.5], "goal": [1.5, 0.5]}])),
    ("map entry is a number", _spec(maps=[3])),
    ("repeated target names", _spec(maps=["chen2025_20", "chen2025_20"])),
    ("no algorithms", _spec(algorithms=[])),
    ("unknown algorithm", _spec(algorithms=["warp-drive"])),
    ("algorithm entry number", _spec(algorithms=[3])),
    ("algorithm entry no name", _spec(algorithms=[{"label": "x"}])),
    ("algorithm unknown key", _spec(algorithms=[{"name": "gwo", "colour": 1}])),
    ("algorithm params not mapping", _spec(algorithms=[{"name": "gwo", "params": [1]}])),
    ("algorithm runs 0", _spec(algorithms=[{"name": "gwo", "runs": 0}])),
    ("repeated labels", _spec(algorithms=["gwo", "gwo"])),
    ("params typo", _spec(algorithms=["gwo"], params={"itres": 5})),
    ("params typo on astar", _spec(params={"clearence": 0.1})),
    ("params not mapping", _spec(params=[1, 2])),
    ("params set the seed", _spec(params={"seed": 3})),
    ("params pop text", _spec(algorithms=["gwo"], params={"pop": "many"})),
    ("params pop 0", _spec(algorithms=["gwo"], params={"pop": 0})),
    ("params pop 1e9", _spec(algorithms=["gwo"], params={"pop": 10 ** 9})),
    ("params iters 1e12", _spec(algorithms=["gwo"], params={"iters": 10 ** 12})),
    ("params max_evals 1e12", _spec(algorithms=["gwo"], params={"max_evals": 10 ** 12, "iters": None})),
    ("params 2001 entries", _spec(params={f"p{i}": i for i in range(2001)})),
    ("params a set", _spec(params={"pop": {1, 2}})),
    ("runs 0", _spec(runs=0)),
    ("runs negative", _spec(runs=-3)),
    ("runs text", _spec(runs="many")),
    ("runs float", _spec(runs=2.5)),
    ("runs 1e9", _spec(runs=10 ** 9)),
    ("seed negative", _spec(seed=-1)),
    ("seed 2^63", _spec(seed=2 ** 63)),
    ("seed 2^63 - 1 with 2 runs", _spec(seed=2 ** 63 - 1, runs=2)),
    ("seeds repeat", _spec(seeds=[1, 1])),
    ("seeds text", _spec(seeds=["a"])),
    ("seeds huge", _spec(seeds=[2 ** 64])),
    ("refine unknown", _spec(refine=["ipopt-ish"])),
    ("reference unknown", _spec(reference="nobody")),
    ("alpha 2", _spec(alpha=2)),
    ("alpha text", _spec(alpha="small")),
    ("quick not mapping", _spec(quick=[1])),
    ("quick unknown key", _spec(quick={"colour": 1})),
    ("scenarios for kind plan", _spec(scenarios=["x"])),
    ("functions unknown", _spec(kind="optimize", maps=_DROP, functions=["F99"])),
    ("functions dim 0", _spec(kind="optimize", maps=_DROP, functions=["F1"], dim=0)),
    ("program key for kind plan", _spec(program="smoothing")),
    ("simulate unknown scenario", _spec(kind="simulate", maps=_DROP, scenarios=["nowhere"],
                                        local_planners=["dwa"])),
    ("simulate scenario escape", _spec(kind="simulate", maps=_DROP, scenarios=["/etc/hostname"],
                                       local_planners=["dwa"])),
    ("scen file missing", _spec(maps=[{"scen": "nope.scen"}])),
    ("scen queries text", _spec(maps=[{"scen": "q.scen", "map": "q.map", "queries": "all"}])),
    ("scen query out of range", _spec(maps=[{"scen": "q.scen", "map": "q.map", "queries": [5]}])),
    ("scen map of another size", _spec(maps=[{"scen": "q.scen", "map": "arena", "queries": 1}])),
    ("scen bad file", _spec(maps=[{"scen": "bad.scen", "map": "q.map"}])),
    ("bad map file in the folder", _spec(maps=[{"map": "broken.map", "start": [0.5, 0.5], "goal": [1.5, 0.5]}])),
    ("order text", _spec(order="first")),
    ("metric unknown", _spec(metric="lenght")),
    ("metric of another kind", _spec(metric="f_error")),
    ("metric not a name", _spec(metric=[1])),
    ("metric in quick", _spec(quick={"metric": "lenght"})),
]


def _spec_folder(tmp_path: Path) -> Path:
    (tmp_path / "outside.map").write_text("type octile\nheight 1\nwidth 2\nmap\n..\n")
    d = tmp_path / "specs"
    d.mkdir()
    (d / "q.map").write_text("type octile\nheight 2\nwidth 3\nmap\n...\n...\n")
    (d / "q.scen").write_text("version 1\n0\tq.map\t3\t2\t0\t0\t2\t1\t2.4142\n")
    (d / "bad.scen").write_text("version 1\n0\tq.map\t3\n")
    (d / "broken.map").write_text("type octile\nheight 9\nwidth 2\nmap\n..\n")
    return d


@pytest.mark.parametrize("label,data", BAD_SPECS, ids=[c[0] for c in BAD_SPECS])
def test_hostile_specs_are_refused_when_loaded(tmp_path, label, data):
    p = _spec_folder(tmp_path) / "s.yaml"
    p.write_text(yaml.safe_dump(data))
    _expect_api_error(lambda: load_spec(p))


CLI_SPEC_SAMPLE = [c for i, c in enumerate(BAD_SPECS) if i % 2 == 0]


@pytest.mark.parametrize("label,data", CLI_SPEC_SAMPLE, ids=[c[0] for c in CLI_SPEC_SAMPLE])
def test_hostile_specs_on_the_command_line(tmp_path, capsys, label, data):
    p = _spec_folder(tmp_path) / "s.yaml"
    p.write_text(yaml.safe_dump(data))
    _expect_cli_error(["bench", p, "--db", tmp_path / "r.sqlite", "--no-progress", "--workers", "1"], capsys)


BAD_SPEC_TEXTS = [
    ("syntax error", "kind: plan\nmaps: [chen2025_20\nalgorithms: [astar]\n"),
    ("alias bomb", "kind: plan\nmaps: [chen2025_20]\nalgorithms: [astar]\n" + BOMB.replace("a:", "z_a:")),
    ("top-level list", "- kind\n- plan\n"),
    ("empty", ""),
    ("not utf-8", "kind: pl\xffan\n"),
    ("python tag", "kind: !!python/name:os.system\n"),
    ("title field", "kind: plan\nmaps: [chen2025_20]\nalgorithms: [astar]\ntitle: '{runs.foo}'\n"),
    ("title index", "kind: plan\nmaps: [chen2025_20]\nalgorithms: [astar]\ntitle: '{runs[0]}'\n"),
    ("title unknown name", "kind: plan\nmaps: [chen2025_20]\nalgorithms: [astar]\ntitle: '{secret}'\n"),
    ("title dunder", "kind: plan\nmaps: [chen2025_20]\nalgorithms: [astar]\ntitle: '{name.__class__}'\n"),
]


@pytest.mark.parametrize("label,text", BAD_SPEC_TEXTS, ids=[c[0] for c in BAD_SPEC_TEXTS])
def test_hostile_spec_files(tmp_path, capsys, label, text):
    p = tmp_path / "s.yaml"
    p.write_bytes(text.encode("latin-1"))
    _expect_api_error(lambda: load_spec(p).formatted_title())
    _expect_cli_error(["bench", p, "--db", ":memory:", "--no-progress", "--workers", "1"], capsys)


# ------------------------------------------------------------------------------ databases
def _foreign_runs_table(p: Path) -> None:
    con = sqlite3.connect(p)
    con.execute("CREATE TABLE runs (id INTEGER PRIMARY KEY, what TEXT)")
    con.commit()
    con.close()


def _foreign_traces_table(p: Path) -> None:
    ResultStore(p).close()
    con = sqlite3.connect(p)
    con.execute("DROP TABLE traces")
    con.execute("CREATE TABLE traces (k TEXT)")
    con.commit()
    con.close()


BAD_DATABASES = [
    ("text file", lambda p: p.write_text("not a database\n" * 10)),
    ("random bytes", lambda p: p.write_bytes(np.random.default_rng(0).bytes(4096))),
    ("sqlite header only", lambda p: p.write_bytes(b"SQLite format 3\x00" + b"\x00" * 84)),
    ("truncated sqlite", lambda p: (ResultStore(p).close(), p.write_bytes(p.read_bytes()[:200]))),
    ("foreign runs table", _foreign_runs_table),
    ("foreign traces table", _foreign_traces_table),
    ("a folder", lambda p: p.mkdir()),
    ("in a missing folder", lambda p: None),
]


@pytest.mark.parametrize("label,make", BAD_DATABASES, ids=[c[0] for c in BAD_DATABASES])
def test_hostile_databases(tmp_path, capsys, label, make):
    p = tmp_path / ("missing" if label == "in a missing folder" else ".") / "r.sqlite"
    make(p)
    _expect_api_error(lambda: ResultStore(p).count())
    _expect_cli_error(["bench", "chen2025_paths", "--quick", "--db", p, "--no-progress", "--workers", "1"], capsys)


# --------------------------------------------------------------------------- command line
PLAN = ["plan", "chen2025_20"]
BAD_COMMAND_LINES = [
    ["no-such-command"],
    ["plan"],
    ["plan", "chen2025_20", "--start", "1"],
    ["plan", "chen2025_20", "--start", "a", "b", "--goal", "1", "1"],
    [*PLAN, "--start", "nan", "nan", "--goal", "19.5", "19.5"],
    [*PLAN, "--start", "inf", "0", "--goal", "19.5", "19.5"],
    [*PLAN, "--start", "-5", "-5", "--goal", "19.5", "19.5"],
    [*PLAN, "--start", "0.5", "0.5", "--goal", "1e308", "1e308"],
    [*PLAN, "--start", "0.5", "0.5"],
    [*PLAN, "--start", "0.5", "0.5", "--goal", "0.5", "0.5"],
    [*PLAN, "--algo", "warp-drive"],
    [*PLAN, "--algo", ""],
    [*PLAN, "--refine", "ipopt"],
    [*PLAN, "--algo", "gwo", "--pop", "abc"],
    [*PLAN, "--algo", "gwo", "--pop", "0"],
    [*PLAN, "--algo", "gwo", "--pop", "-4"],
    [*PLAN, "--algo", "gwo", "--pop", "1e9"],
    [*PLAN, "--algo", "gwo", "--pop", "1000000000"],
    [*PLAN, "--algo", "gwo", "--iters", "1000000000000"],
    [*PLAN, "--algo", "gwo", "--iters", "-1"],
    [*PLAN, "--algo", "gwo", "--max-evals", "0"],
    [*PLAN, "--algo", "gwo", "--max-evals", "100000000000"],
    [*PLAN, "--algo", "gwo", "--seed", "-1"],
    [*PLAN, "--algo", "gwo", "--seed", str(2 ** 64)],
    [*PLAN, "--algo", "gwo", "--seed", "1.5"],
    [*PLAN, "--clearance", "nan"],
    [*PLAN, "--clearance", "-1"],
    [*PLAN, "--clearance", "inf"],
    [*PLAN, "--clearance", "1e308"],
    [*PLAN, "--clearance", "30"],
    [*PLAN, "--tube-radius", "2"],
    [*PLAN, "--refine-starts", "3"],
    [*PLAN, "--refine", "qp", "--tube-radius", "-1"],
    [*PLAN, "--export", "path.txt"],
    [*PLAN, "--export", "/no/such/folder/deeper/p.csv"],
    [*PLAN, "--plot", "."],
    [*PLAN, "--scen", "nope.scen"],
    [*PLAN, "--scen", "q.scen", "--start", "1", "1", "--goal", "2", "2"],
    ["plan", "q.map", "--scen", "q.scen", "--query", "7"],
    ["plan", "q.map", "--scen", "q.scen", "--query", "-1"],
    ["plan", "arena", "--scen", "q.scen"],
    ["plan", "arena"],
    ["plan", "no_such_map", "--start", "1", "1", "--goal", "2", "2"],
    ["simulate", "no_such_scenario"],
    ["simulate", "li2023_exp1", "--local", "warp-drive"],
    ["simulate", "li2023_exp1", "--global", "warp-drive"],
    ["simulate", "li2023_exp1", "--refine", "fast"],
    ["simulate", "li2023_exp1", "--seed", "-3"],
    ["simulate", "li2023_exp1", "--subgoals", "everywhere"],
    ["simulate", "li2023_exp1", "--export", "run.png"],
    ["simulate", "li2023_exp1", "--gif", "."],
    ["bench", "no_such_spec"],
    ["bench", "chen2025_paths", "--workers", "0"],
    ["bench", "chen2025_paths", "--runs", "0"],
    ["bench", "chen2025_paths", "--executor", "carrier-pigeon"],
    ["bench", "chen2025_paths", "--format", "pdf"],
    ["bench", "chen2025_paths", "--layout", "poster", "--summary-only", "--db", ":memory:"],
    ["bench", "chen2025_paths", "--export-ompl", "r.csv", "--summary-only", "--db", ":memory:"],
    ["reproduce", "nobody2020"],
    ["reproduce", "chen2025", "--part", "nothing", "--quick"],
    ["demo", "--out", "."],
    ["algorithms", "--extra"],
]


@pytest.mark.parametrize("argv", BAD_COMMAND_LINES, ids=[" ".join(a)[:60] for a in BAD_COMMAND_LINES])
def test_hostile_command_lines(tmp_path, capsys, monkeypatch, argv):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "q.map").write_text("type octile\nheight 2\nwidth 3\nmap\n...\n...\n")
    (tmp_path / "q.scen").write_text("version 1\n0\tq.map\t3\t2\t0\t0\t2\t1\t2.4142\n")
    (tmp_path / "r.csv").write_text("x\n")
    _expect_cli_error(argv, capsys)


def test_cli_errors_in_a_real_process_print_one_line(tmp_path):
    import subprocess
    import sys

    root = Path(__file__).resolve().parents[1]
    env = {**__import__("os").environ, "PYTHONPATH": str(root)}
    for argv in (["plan", "chen2025_20", "--algo", "gwo", "--pop", "1000000000"], ["bench", "no_such_spec"],
                 ["plan", "chen2025_20", "--pop", "x"]):
        done = subprocess.run([sys.executable, "-m", "optplan", *argv], cwd=tmp_path, env=env, capture_output=True,
                              text=True, timeout=120)
        assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1, done.stderr


# ------------------------------------------------------------------------------- API calls
WORLD, S, G = paper_map("chen2025_20")
CIRCLES = paper_map("yang2023_env1")[0]


def _f(X):
    return (np.asarray(X) ** 2).sum(axis=1)


BAD_API_CALLS = [
    ("plan world None", lambda: op.plan(None, S, G)),
    ("plan world text", lambda: op.plan("chen2025_20", S, G)),
    ("plan world array", lambda: op.plan(np.zeros((3, 3)), S, G)),
    ("plan start text", lambda: op.plan(WORLD, "home", G)),
    ("plan start None", lambda: op.plan(WORLD, None, G)),
    ("plan start short", lambda: op.plan(WORLD, (1.0,), G)),
    ("plan start long", lambda: op.plan(WORLD, (1.0, 2.0, 3.0), G)),
    ("plan start nan", lambda: op.plan(WORLD, (np.nan, 1.0), G)),
    ("plan start dict", lambda: op.plan(WORLD, {"x": 1}, G)),
    ("plan goal blocked", lambda: op.plan(WORLD, S, (WORLD.occ.nonzero()[1][0] + 0.5, WORLD.occ.nonzero()[0][0] + 0.5))),
    ("plan algorithm int", lambda: op.plan(WORLD, S, G, algorithm=3)),
    ("plan algorithm None", lambda: op.plan(WORLD, S, G, algorithm=None)),
    ("plan algorithm unknown", lambda: op.plan(WORLD, S, G, algorithm="warp")),
    ("plan pop text", lambda: op.plan(WORLD, S, G, algorithm="gwo", pop="30")),
    ("plan pop float", lambda: op.plan(WORLD, S, G, algorithm="gwo", pop=3.5)),
    ("plan pop bool", lambda: op.plan(WORLD, S, G, algorithm="gwo", pop=True)),
    ("plan pop huge", lambda: op.plan(WORLD, S, G, algorithm="gwo", pop=10 ** 9)),
    ("plan iters text", lambda: op.plan(WORLD, S, G, algorithm="gwo", iters="5")),
    ("plan iters huge", lambda: op.plan(WORLD, S, G, algorithm="gwo", pop=10, iters=10 ** 12)),
    ("plan iters negative", lambda: op.plan(WORLD, S, G, algorithm="gwo", iters=-1)),
    ("plan seed text", lambda: op.plan(WORLD, S, G, algorithm="gwo", seed="0", pop=4, iters=2)),
    ("plan seed float", lambda: op.plan(WORLD, S, G, algorithm="gwo", seed=1.5, pop=4, iters=2)),
    ("plan seed 2^64", lambda: op.plan(WORLD, S, G, algorithm="gwo", seed=2 ** 64, pop=4, iters=2)),
    ("plan clearance text", lambda: op.plan(WORLD, S, G, clearance="wide")),
    ("plan clearance None", lambda: op.plan(WORLD, S, G, clearance=None)),
    ("plan clearance inf", lambda: op.plan(WORLD, S, G, clearance=float("inf"))),
    ("plan refine int", lambda: op.plan(WORLD, S, G, refine=3)),
    ("plan refine_options list", lambda: op.plan(WORLD, S, G, refine="qp", refine_options=[1])),
    ("plan refine_options bad", lambda: op.plan(WORLD, S, G, refine="qp", refine_options={"tube_radius": -1})),
    ("plan unknown keyword", lambda: op.plan(WORLD, S, G, algorithm="gwo", pop=4, iters=2, colour="red")),
    ("plan max_evals text", lambda: op.plan(WORLD, S, G, algorithm="gwo", max_evals="10")),
    ("plan astar on circles", lambda: op.plan(CIRCLES, (0.5, 0.5), (9.5, 9.5), algorithm="astar")),
    ("shortest_path method", lambda: op.shortest_path(WORLD, S, G, method="teleport")),
    ("shortest_path method int", lambda: op.shortest_path(WORLD, S, G, method=1)),
    ("shortest_path world None", lambda: op.shortest_path(None, S, G)),
    ("shortest_path start text", lambda: op.shortest_path(WORLD, "a", G)),
    ("shortest_path clearance text", lambda: op.shortest_path(WORLD, S, G, clearance="x")),
    ("optimize bounds shape", lambda: op.optimize(_f, [(0, 1, 2)], pop=4, iters=2)),
    ("optimize bounds inverted", lambda: op.optimize(_f, [(1, 0)], pop=4, iters=2)),
    ("optimize bounds nan", lambda: op.optimize(_f, [(np.nan, 1)], pop=4, iters=2)),
    ("optimize algorithm unknown", lambda: op.optimize(_f, [(0, 1)], algorithm="warp", pop=4, iters=2)),
    ("optimize pop 0", lambda: op.optimize(_f, [(0, 1)], pop=0, iters=2)),
    ("optimize pop text", lambda: op.optimize(_f, [(0, 1)], pop="4", iters=2)),
    ("optimize f wrong shape", lambda: op.optimize(lambda X: np.zeros(3), [(0, 1)], pop=4, iters=2)),
    ("optimize unknown parameter", lambda: op.optimize(_f, [(0, 1)], pop=4, iters=2, colour=1)),
    ("load_map None", lambda: op.load_map(None)),
    ("load_map int", lambda: op.load_map(3)),
    ("load_map list", lambda: op.load_map([[0, 0]])),
    ("load_map empty name", lambda: op.load_map("")),
    ("load_scen missing", lambda: op.load_scen("nope.scen")),
    ("load_scen int", lambda: op.load_scen(3)),
    ("load_scenario int", lambda: op.load_scenario(3)),
    ("load_scenario None", lambda: op.load_scenario(None)),
    ("load_scenario list", lambda: op.load_scenario([1, 2])),
    ("load_scenario bad dict", lambda: op.load_scenario({"map": 1})),
    ("GridMap text", lambda: op.GridMap("grid")),
    ("GridMap 1-D", lambda: op.GridMap(np.zeros(5, bool))),
    ("GridMap empty", lambda: op.GridMap(np.zeros((0, 0), bool))),
    ("GridMap resolution 0", lambda: op.GridMap(np.zeros((2, 2), bool), resolution=0)),
    ("GridMap resolution nan", lambda: op.GridMap(np.zeros((2, 2), bool), resolution=np.nan)),
    ("GridMap resolution text", lambda: op.GridMap(np.zeros((2, 2), bool), resolution="1")),
    ("GridMap origin nan", lambda: op.GridMap(np.zeros((2, 2), bool), origin=(np.nan, 0))),
    ("GridMap origin short", lambda: op.GridMap(np.zeros((2, 2), bool), origin=(0,))),
    ("GridMap from_rows ragged", lambda: op.GridMap.from_rows([[0, 0], [0]])),
    ("GridMap huge", lambda: op.GridMap(np.lib.stride_tricks.as_strided(np.zeros(1, bool), (10 ** 5, 10 ** 5),
                                                                        (0, 0)))),
    ("CircleWorld bounds empty", lambda: op.CircleWorld(bounds=(0, 0, 0, 0), circles=[])),
    ("CircleWorld bounds text", lambda: op.CircleWorld(bounds="box", circles=[])),
    ("CircleWorld circle pairs", lambda: op.CircleWorld(bounds=(0, 0, 1, 1), circles=[(0.5, 0.5)])),
    ("CircleWorld radius 0", lambda: op.CircleWorld(bounds=(0, 0, 1, 1), circles=[(0.5, 0.5, 0)])),
    ("CircleWorld circles text", lambda: op.CircleWorld(bounds=(0, 0, 1, 1), circles="many")),
    ("CircleWorld safety nan", lambda: op.CircleWorld(bounds=(0, 0, 1, 1), circles=[], safety=np.nan)),
    ("validate_path clearance", lambda: op.validate_path(WORLD, [S, G], clearance=-1)),
    ("validate_path clearance text", lambda: op.validate_path(WORLD, [S, G], clearance="x")),
    ("validate_path world None", lambda: op.validate_path(None, [S, G])),
    ("path_metrics world text", lambda: op.path_metrics("world", [S, G])),
    ("simulate None", lambda: op.simulate(None)),
    ("simulate text", lambda: op.simulate("no_such_scenario")),
    ("simulate local unknown", lambda: op.simulate("li2023_exp1", local_planner="warp")),
    ("simulate global unknown", lambda: op.simulate("li2023_exp1", global_planner="warp")),
    ("Waypoints 0", lambda: op.Waypoints(0)),
    ("Waypoints text", lambda: op.Waypoints("3")),
    ("paper_program unknown", lambda: op.paper_program("nobody2020", WORLD, S, G)),
    ("export path text", lambda: op.export_path("path", "p.csv")),
]


# found by a sweep over op.__all__ with wrong types (str for int, None, negative, NaN, lists of the
# wrong shape); each must name the argument in its message
PROG = op.smoothing_program(WORLD, S, G, n=10)
BAD_TYPED_CALLS = [
    ("optimize f text", "f", lambda: op.optimize("sphere", [(0, 1)], pop=4, iters=2)),
    ("optimize f None", "f", lambda: op.optimize(None, [(0, 1)], pop=4, iters=2)),
    ("optimize bounds text", "bounds", lambda: op.optimize(_f, "x", pop=4, iters=2)),
    ("optimize bounds dict", "bounds", lambda: op.optimize(_f, {"a": 1}, pop=4, iters=2)),
    ("optimize init text", "init", lambda: op.optimize(_f, [(0, 1)], pop=4, iters=2, init="x")),
    ("optimize repair int", "repair", lambda: op.optimize(_f, [(0, 1)], pop=4, iters=2, repair=3)),
    ("optimize callback list", "callback", lambda: op.optimize(_f, [(0, 1)], pop=4, iters=2, callback=[1])),
    ("optimize dim text", "dim", lambda: op.optimize(_f, [0, 1], pop=4, iters=2, dim="3")),
    ("optimize dim nan", "dim", lambda: op.optimize(_f, [(0, 1)], pop=4, iters=2, dim=np.nan)),
    ("shortest_path world None", "world", lambda: op.shortest_path(None, S, G)),
    ("shortest_path world list", "world", lambda: op.shortest_path([[1, 2, 3]], S, G)),
    ("shortest_path world file name", "world", lambda: op.shortest_path("chen2025_20", S, G)),
    ("shortest_path points text", "points", lambda: op.shortest_path(WORLD, S, G, method="visibility", points="x")),
    ("shortest_path points None", "points", lambda: op.shortest_path(WORLD, S, G, points=None)),
    ("shortest_path corner_cutting text", "corner_cutting",
     lambda: op.shortest_path(WORLD, S, G, corner_cutting="yes")),
    ("simulate seed text", "seed", lambda: op.simulate("li2023_exp1", seed="0")),
    ("simulate seed nan", "seed", lambda: op.simulate("li2023_exp1", seed=np.nan)),
    ("simulate seed negative", "seed", lambda: op.simulate("li2023_exp1", seed=-1)),
    ("simulate seed list", "seed", lambda: op.simulate("li2023_exp1", seed=[[1, 2, 3]])),
    ("simulate global_planner None", "global_planner", lambda: op.simulate("li2023_exp1", global_planner=None)),
    ("simulate global_planner int", "global_planner", lambda: op.simulate("li2023_exp1", global_planner=3)),
    ("path_metrics path text", "path", lambda: op.path_metrics(WORLD, "x")),
    ("export_path file None", "file", lambda: op.export_path(np.array([S, G]), None)),
    ("export_path file int", "file", lambda: op.export_path(np.array([S, G]), 3)),
    ("export_path frame_id None", "frame_id", lambda: op.export_path(np.array([S, G]), "p.yaml", frame_id=None)),
    ("export_trajectory file list", "file", lambda: op.export_trajectory(np.zeros((3, 6)), [[1, 2, 3]])),
    ("export_trajectory frame_id nan", "frame_id",
     lambda: op.export_trajectory(np.zeros((3, 6)), "t.yaml", frame_id=np.nan)),
    ("save_map grid None", "grid", lambda: op.save_map(None, "m.map")),
    ("save_map grid circles", "grid", lambda: op.save_map(CIRCLES, "m.map")),
    ("save_map path None", "path", lambda: op.save_map(WORLD, None)),
    ("save_map path nan", "path", lambda: op.save_map(WORLD, np.nan)),
    ("smoothing_program w_smooth text", "w_smooth", lambda: op.smoothing_program(WORLD, S, G, w_smooth="x")),
    ("smoothing_program w_smooth nan", "w_smooth", lambda: op.smoothing_program(WORLD, S, G, w_smooth=np.nan)),
    ("smoothing_program clearance None", "clearance", lambda: op.smoothing_program(WORLD, S, G, clearance=None)),
    ("smoothing_program clearance negative", "clearance",
     lambda: op.smoothing_program(WORLD, S, G, clearance=-1)),
    ("paper_program name list", "paper program", lambda: op.paper_program([[1, 2, 3]], WORLD, S, G)),
    ("paper_program world None", "world", lambda: op.paper_program("chen2025", None, S, G)),
    ("paper_program world number", "world", lambda: op.paper_program("chen2025", 3.0, S, G)),
    ("paper_program clearance text", "clearance", lambda: op.paper_program("chen2025", WORLD, S, G, clearance="x")),
    ("RobotSpec v_min text", "v_min", lambda: op.RobotSpec(v_min="x")),
    ("RobotSpec v_min None", "v_min", lambda: op.RobotSpec(v_min=None)),
    ("compare program None", "program", lambda: op.compare(None, ["slsqp"])),
    ("compare program text", "program", lambda: op.compare("smoothing", ["slsqp"])),
    ("compare seeds int", "seeds", lambda: op.compare(PROG, ["slsqp"], seeds=3)),
    ("compare seeds None", "seeds", lambda: op.compare(PROG, ["slsqp"], seeds=None)),
]


@pytest.mark.parametrize("label,name,call", BAD_TYPED_CALLS, ids=[c[0] for c in BAD_TYPED_CALLS])
def test_wrong_types_raise_optplan_errors_naming_the_argument(tmp_path, monkeypatch, label, name, call):
    monkeypatch.chdir(tmp_path)
    exc = _expect_api_error(call)
    assert name in str(exc), str(exc)


@pytest.mark.parametrize("label,call", BAD_API_CALLS, ids=[c[0] for c in BAD_API_CALLS])
def test_hostile_api_calls_raise_optplan_errors(tmp_path, monkeypatch, label, call):
    monkeypatch.chdir(tmp_path)
    _expect_api_error(call)


def test_the_suite_has_at_least_300_cases():
    n = (len(BAD_MAPS) + len(CLI_MAP_SAMPLE) + len(BAD_SCENARIOS) + 2 * len(BAD_SCENARIO_TEXTS) + len(BAD_SPECS)
         + len(CLI_SPEC_SAMPLE) + 2 * len(BAD_SPEC_TEXTS) + 2 * len(BAD_DATABASES) + len(BAD_COMMAND_LINES)
         + len(BAD_API_CALLS) + len(BAD_TYPED_CALLS))
    assert n >= 300, n
