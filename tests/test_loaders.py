"""Map loaders: every format, round trips, and the right error for bad files."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import optplan as op
from optplan.world.loaders import load_scen, save_map


def test_movingai_map_orientation_and_charset(tmp_path):
    f = tmp_path / "m.map"
    f.write_bytes(b"type octile\r\nheight 2\r\nwidth 3\r\nmap\r\n.G@\r\nTS.\r\n")
    g = op.load_map(f)
    # first row of the file is the top row: y = 1
    np.testing.assert_array_equal(g.occ, [[True, False, False], [False, False, True]])


def test_shipped_movingai_maps_load(shared_data):
    g = op.load_map(shared_data / "movingai/dao/den312d.map")
    assert (g.width, g.height) == (65, 81)
    scen = load_scen(shared_data / "movingai/dao/den312d.map.scen")
    assert len(scen) > 100
    for e in scen[:50]:
        assert g.is_free(e.start_world()) and g.is_free(e.goal_world())


def test_scen_accepts_version_1_and_spaces(tmp_path):
    f = tmp_path / "a.scen"
    f.write_text("version 1.0\n0 maps/x.map 3 2 0 0 2 1 2.41421356\n1\tmaps/x.map\t3\t2\t0\t1\t0\t0\t1\n")
    rows = load_scen(f)
    assert rows[0].optimal == pytest.approx(2.41421356) and rows[1].goal_world() == (0.5, 1.5)
    f.write_text("version 2\n")
    with pytest.raises(op.MapFormatError, match="version"):
        load_scen(f)


@pytest.mark.parametrize("content,match", [
    ("", "empty"),
    ("type octile\nheight 3\nwidth 3\nmap\n...\n...\n", "truncated"),
    ("type octile\nheight 2\nwidth 3\nmap\n...\n..\n", "row 2"),
    ("type octile\nwidth 3\nmap\n...\n", "height"),
    ("type octile\nheight x\nwidth 3\nmap\n...\n", "integers"),
])
def test_bad_movingai_files(tmp_path, content, match):
    f = tmp_path / "bad.map"
    f.write_text(content)
    with pytest.raises(op.MapFormatError, match=match):
        op.load_map(f)


def test_binary_and_missing_and_unknown(tmp_path):
    f = tmp_path / "b.txt"
    f.write_bytes(b"0 1\x00\x01")
    with pytest.raises(op.MapFormatError, match="binary"):
        op.load_map(f)
    with pytest.raises(op.MapFormatError, match="does not exist"):
        op.load_map(tmp_path / "nope.map")
    (tmp_path / "x.xyz").write_text("x")
    with pytest.raises(op.MapFormatError, match="unknown map format"):
        op.load_map(tmp_path / "x.xyz")
    (tmp_path / "x.bmp").write_text("x")  # images are read through Pillow; this one is not an image
    with pytest.raises(op.MapFormatError, match="not a readable image"):
        op.load_map(tmp_path / "x.bmp")


def test_text_matrix_errors(tmp_path):
    f = tmp_path / "m.csv"
    f.write_text("0,1\n0\n")
    with pytest.raises(op.MapFormatError, match="different lengths"):
        op.load_map(f)
    f.write_text("0,2\n0,0\n")
    with pytest.raises(op.MapFormatError, match="other than 0 or 1"):
        op.load_map(f)


def _write_pgm(path, img, maxval=255, magic=b"P5", extra=b""):
    h, w = img.shape
    header = magic + b"\n# a comment\n" + f"{w} {h}\n{maxval}\n".encode()
    body = img.astype(np.uint8).tobytes() if magic == b"P5" else " ".join(map(str, img.ravel())).encode()
    path.write_bytes(header + body + extra)


def test_ros_map_server_yaml(tmp_path):
    img = np.array([[254, 0, 205], [254, 254, 254]])  # free, occupied, unknown / free row
    _write_pgm(tmp_path / "m.pgm", img)
    (tmp_path / "m.yaml").write_text("image: m.pgm\nresolution: 0.05\norigin: [-1.0, 2.0, 0.0]\n"
                                     "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")
    from optplan.world.loaders import MapUnknownCellsWarning

    with pytest.warns(MapUnknownCellsWarning, match="1 of 6 cells"):   # said, not silent (issue 47)
        g = op.load_map(tmp_path / "m.yaml")
    assert g.resolution == 0.05 and g.origin == (-1.0, 2.0)
    # top image row is y = 1; unknown (205) is treated as blocked
    np.testing.assert_array_equal(g.occ, [[False, False, False], [False, True, True]])
    (tmp_path / "n.yaml").write_text("image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 1\n"
                                     "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    gn = op.load_map(tmp_path / "n.yaml")
    np.testing.assert_array_equal(gn.occ, [[True, True, True], [True, False, True]])


def test_ascii_pgm_and_wrong_size(tmp_path):
    img = np.array([[0, 255], [255, 255]])
    _write_pgm(tmp_path / "a.pgm", img, magic=b"P2")
    np.testing.assert_array_equal(op.load_map(tmp_path / "a.pgm").occ, [[False, False], [True, False]])
    _write_pgm(tmp_path / "bad.pgm", img, extra=b"\x00\x00")
    with pytest.raises(op.MapFormatError, match="holds"):
        op.load_map(tmp_path / "bad.pgm")
    (tmp_path / "short.pgm").write_bytes(b"P5\n4 4\n255\n" + bytes(10))
    with pytest.raises(op.MapFormatError, match="holds 10 bytes"):
        op.load_map(tmp_path / "short.pgm")


def test_npy_roundtrip_and_bad_npy(tmp_path):
    np.save(tmp_path / "three.npy", np.zeros((2, 2, 2)))
    with pytest.raises(op.MapFormatError, match="2-D"):
        op.load_map(tmp_path / "three.npy")
    (tmp_path / "junk.npy").write_bytes(b"not numpy at all")
    with pytest.raises(op.MapFormatError):
        op.load_map(tmp_path / "junk.npy")


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 12), st.integers(1, 12), st.integers(0, 2**32 - 1),
       st.sampled_from([".map", ".txt", ".csv", ".npy", ".yaml"]))
def test_saved_maps_round_trip(tmp_path_factory, h, w, seed, suffix):
    rng = np.random.default_rng(seed)
    occ = rng.random((h, w)) < 0.4
    occ.flat[rng.integers(occ.size)] = False  # load_map refuses maps without a free cell
    g = op.GridMap(occ, resolution=0.5 if suffix == ".yaml" else 1.0)
    path = save_map(g, tmp_path_factory.mktemp("rt") / f"m{suffix}")
    back = op.load_map(path)
    np.testing.assert_array_equal(back.occ, g.occ)
    assert back.resolution == g.resolution


def test_shipped_maps_by_name():
    from optplan.world import maps

    assert "multialgo20_template" in maps.names()
    g = op.load_map("multialgo20_template")
    assert (g.width, g.height) == (20, 20)
    with pytest.raises(op.MapFormatError, match="shipped maps"):
        op.load_map("no_such_map_name")


def test_inflate_blocks_cells_within_margin():
    g = op.GridMap.from_rows([[0, 0, 0, 0, 0]] * 2 + [[0, 0, 1, 0, 0]] + [[0, 0, 0, 0, 0]] * 2)
    one = g.inflate(0.5)
    # 4-neighbours touch the blocked cell (gap 0); diagonal ones too (gap 0); the border ring too
    assert one.occ.sum() == 25
    inner = op.GridMap(np.pad(g.occ, 3), resolution=1.0).inflate(1.2)
    # square-to-square gap of the (2, 0) neighbour is 1 < 1.2, of (2, 1) is 1 < 1.2, of (2, 2) sqrt 2 > 1.2
    c = np.argwhere(np.pad(g.occ, 3))[0]
    assert inner.occ[c[0], c[1] + 2] and inner.occ[c[0] + 1, c[1] + 2] and not inner.occ[c[0] + 2, c[1] + 2]
    with pytest.raises(op.ParameterError):
        g.inflate(-1)


def test_matrix_orientation_is_said_and_can_be_flipped(tmp_path):
    """A .npy map's first row is the top (image convention); origin='lower' (optplan plan
    --flip) reads a[iy, ix] with iy up, as GridMap.occ holds it (issue 47)."""
    import numpy as np

    from optplan.cli import main

    a = np.zeros((4, 5), bool)
    a[0, 1] = True                        # the first row
    np.save(tmp_path / "m.npy", a)
    top = op.load_map(tmp_path / "m.npy")
    bottom = op.load_map(tmp_path / "m.npy", origin="lower")
    assert top.occ[3, 1] and bottom.occ[0, 1]
    np.testing.assert_array_equal(bottom.occ, a)
    with pytest.raises(op.ParameterError, match="upper"):
        op.load_map(tmp_path / "m.npy", origin="up")
    with pytest.raises(op.ParameterError, match="matrices"):
        op.load_map("arena", origin="lower")
    assert main(["plan", str(tmp_path / "m.npy"), "--flip", "--start", "0.5", "0.5", "--goal", "4.5", "3.5",
                 "--algo", "astar", "--json"]) == 0
    assert main(["plan", str(tmp_path / "m.npy"), "--flip", "--start", "1.5", "0.5", "--goal", "4.5", "3.5",
                 "--algo", "astar"]) == 2      # (1.5, 0.5) is the blocked cell once flipped
