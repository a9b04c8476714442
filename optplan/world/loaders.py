"""Map and scenario-list loaders.

Every format is read with its first row as the *top* row of the map (image
convention) and flipped so that ``occ[iy, ix]`` has ``iy`` growing upwards.

Supported by :func:`load_map` (dispatch on the suffix):

* ``.map`` — Moving AI benchmark format (``type``/``height``/``width``/``map``
  header; ``.``, ``G`` and ``S`` are free, every other character blocked).
* ``.yaml`` — ROS ``map_server`` metadata pointing at a ``.pgm`` (P2 or P5) image;
  ``negate``, ``occupied_thresh``, ``free_thresh``, ``resolution`` and ``origin``
  are honoured. Cells that are neither free nor occupied (unknown) are blocked.
* ``.pgm`` — the image alone (resolution 1, thresholds 0.65 / 0.196).
* ``.npy`` — a 2-D array of 0/1 or booleans.
* ``.txt`` / ``.csv`` — a 0/1 matrix, values separated by spaces, tabs or commas.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import MapFormatError, ParameterError
from .grid import GridMap

MAX_CELLS = 50_000_000  # refuse maps larger than this (about 7000 x 7000)
MAX_FILE_BYTES = 512 * 1024 * 1024


def _read_text(path: Path) -> str:
    try:
        size = path.stat().st_size
    except OSError as exc:
        raise MapFormatError(f"cannot read map file {path}: {exc.strerror or exc}") from None
    if size == 0:
        raise MapFormatError(f"map file {path} is empty")
    if size > MAX_FILE_BYTES:
        raise MapFormatError(f"map file {path} is {size} bytes; the limit is {MAX_FILE_BYTES}")
    data = path.read_bytes()
    if b"\x00" in data:
        raise MapFormatError(f"map file {path} contains binary data; expected a text map")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def _check_size(h: int, w: int, path) -> None:
    if h <= 0 or w <= 0:
        raise MapFormatError(f"{path}: map size must be positive, got height {h}, width {w}")
    if h * w > MAX_CELLS:
        raise MapFormatError(f"{path}: map of {h} x {w} cells exceeds the limit of {MAX_CELLS} cells")


# ------------------------------------------------------------------ Moving AI
def _load_movingai(path: Path) -> GridMap:
    text = _read_text(path).replace("\r", "")
    lines = text.split("\n")
    header: dict[str, str] = {}
    i = 0
    while i < len(lines):
        tokens = lines[i].split()
        i += 1
        if not tokens:
            continue
        key = tokens[0].lower()
        if key == "map":
            break
        header[key] = tokens[1] if len(tokens) > 1 else ""
    else:
        raise MapFormatError(f"{path}: no 'map' line; a Moving AI .map needs 'type', 'height', 'width' and 'map' header lines")
    try:
        h, w = int(header["height"]), int(header["width"])
    except KeyError as exc:
        raise MapFormatError(f"{path}: header lacks '{exc.args[0]}'") from None
    except ValueError:
        raise MapFormatError(f"{path}: height and width must be integers, got {header.get('height')!r}, {header.get('width')!r}") from None
    _check_size(h, w, path)
    rows = [ln.strip() for ln in lines[i:]]
    rows = [r for r in rows if r]
    if len(rows) < h:
        raise MapFormatError(f"{path}: truncated map: header says {h} rows, file has {len(rows)}")
    rows = rows[:h]
    bad = [k for k, r in enumerate(rows) if len(r) != w]
    if bad:
        raise MapFormatError(f"{path}: row {bad[0] + 1} has {len(rows[bad[0]])} characters, header says width {w}")
    chars = np.frombuffer("".join(rows).encode("latin-1"), dtype=np.uint8).reshape(h, w)
    free = np.isin(chars, np.frombuffer(b".GS", dtype=np.uint8))
    return GridMap((~free)[::-1].copy(), 1.0, (0.0, 0.0), path.stem)


@dataclass(frozen=True)
class ScenEntry:
    """One row of a Moving AI ``.scen`` file (raw values: ``x`` = column,
    ``y`` = row counted from the top, ``optimal`` = octile optimum)."""

    bucket: int
    map_name: str
    width: int
    height: int
    start_x: int
    start_y: int
    goal_x: int
    goal_y: int
    optimal: float

    def start_world(self, resolution: float = 1.0) -> tuple[float, float]:
        """Start cell centre in world metres (y up)."""
        return ((self.start_x + 0.5) * resolution, (self.height - 1 - self.start_y + 0.5) * resolution)

    def goal_world(self, resolution: float = 1.0) -> tuple[float, float]:
        """Goal cell centre in world metres (y up)."""
        return ((self.goal_x + 0.5) * resolution, (self.height - 1 - self.goal_y + 0.5) * resolution)


def load_scen(path: str | os.PathLike) -> list[ScenEntry]:
    """Read a Moving AI scenario file (``version 1`` or ``version 1.0``; tab or space separated)."""
    path = Path(path)
    lines = [ln for ln in _read_text(path).replace("\r", "").split("\n") if ln.strip()]
    if not lines or not re.fullmatch(r"version\s+1(\.0+)?", lines[0].strip(), flags=re.I):
        raise MapFormatError(f"{path}: first line must be 'version 1' or 'version 1.0'")
    out = []
    for n, ln in enumerate(lines[1:], start=2):
        parts = re.split(r"\t+| +", ln.strip())
        if len(parts) != 9:
            raise MapFormatError(f"{path}: line {n} has {len(parts)} fields, expected 9 "
                                 "(bucket map width height start_x start_y goal_x goal_y optimal)")
        try:
            out.append(ScenEntry(int(parts[0]), parts[1], *(int(v) for v in parts[2:8]), float(parts[8])))
        except ValueError:
            raise MapFormatError(f"{path}: line {n} has a non-numeric field: {ln.strip()!r}") from None
    return out


# ------------------------------------------------------------------ matrices
def _load_matrix_text(path: Path) -> GridMap:
    text = _read_text(path).replace("\r", "")
    rows = []
    for n, ln in enumerate(text.split("\n"), start=1):
        s = ln.strip()
        if not s or s.startswith("#"):
            continue
        toks = [t for t in re.split(r"[\s,;]+", s) if t]
        try:
            vals = [int(float(t)) if float(t) in (0.0, 1.0) else None for t in toks]
        except ValueError:
            raise MapFormatError(f"{path}: line {n} has a non-numeric value; expected 0/1 separated by spaces or commas") from None
        if any(v is None for v in vals):
            raise MapFormatError(f"{path}: line {n} has a value other than 0 or 1")
        rows.append(vals)
    if not rows:
        raise MapFormatError(f"{path}: no matrix rows found")
    widths = {len(r) for r in rows}
    if len(widths) != 1:
        raise MapFormatError(f"{path}: rows have different lengths {sorted(widths)}; a map must be rectangular")
    _check_size(len(rows), len(rows[0]), path)
    return GridMap.from_rows(np.array(rows, dtype=np.uint8), name=path.stem)


def _load_npy(path: Path) -> GridMap:
    try:
        arr = np.load(path, allow_pickle=False)
    except Exception as exc:  # numpy raises several types for corrupt files
        raise MapFormatError(f"{path}: not a readable .npy array ({exc})") from None
    if arr.ndim != 2:
        raise MapFormatError(f"{path}: expected a 2-D array, got shape {arr.shape}")
    _check_size(*arr.shape, path)
    if arr.dtype != bool and not np.all(np.isin(arr, (0, 1))):
        raise MapFormatError(f"{path}: values must be 0/1 or booleans")
    return GridMap.from_rows(arr.astype(bool), name=path.stem)


# ------------------------------------------------------------------ ROS map_server
def _read_pgm(path: Path) -> np.ndarray:
    """Read a P2 (ASCII) or P5 (binary) PGM; returns uint values, top row first."""
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise MapFormatError(f"cannot read image {path}: {exc.strerror or exc}") from None
    if not data:
        raise MapFormatError(f"image {path} is empty")
    magic = data[:2]
    if magic not in (b"P2", b"P5"):
        raise MapFormatError(f"{path}: not a PGM image (magic {magic!r}); expected P2 or P5")
    # header: magic, width, height, maxval separated by whitespace, with # comments
    fields: list[int] = []
    pos = 2
    while len(fields) < 3:
        while pos < len(data) and data[pos : pos + 1].isspace():
            pos += 1
        if pos < len(data) and data[pos : pos + 1] == b"#":
            while pos < len(data) and data[pos : pos + 1] not in (b"\n", b"\r"):
                pos += 1
            continue
        start = pos
        while pos < len(data) and not data[pos : pos + 1].isspace():
            pos += 1
        if start == pos:
            raise MapFormatError(f"{path}: truncated PGM header")
        try:
            fields.append(int(data[start:pos]))
        except ValueError:
            raise MapFormatError(f"{path}: bad PGM header value {data[start:pos]!r}") from None
    w, h, maxval = fields
    _check_size(h, w, path)
    if not 0 < maxval < 65536:
        raise MapFormatError(f"{path}: PGM maxval must be in 1..65535, got {maxval}")
    if magic == b"P5":
        pos += 1  # exactly one whitespace byte before the raster
        dtype = np.dtype(">u2") if maxval > 255 else np.dtype(np.uint8)
        raster = data[pos:]
        need = w * h * dtype.itemsize
        if len(raster) != need:
            raise MapFormatError(f"{path}: PGM says {w} x {h} pixels ({need} bytes) but holds {len(raster)} bytes")
        img = np.frombuffer(raster, dtype=dtype).reshape(h, w)
    else:
        vals = data[pos:].split()
        if len(vals) != w * h:
            raise MapFormatError(f"{path}: PGM says {w} x {h} pixels but holds {len(vals)} values")
        try:
            img = np.array([int(v) for v in vals], dtype=np.int64).reshape(h, w)
        except ValueError:
            raise MapFormatError(f"{path}: P2 PGM pixel values must be non-negative integers") from None
    if img.min() < 0 or img.max() > maxval:
        raise MapFormatError(f"{path}: PGM pixel values must lie in 0..{maxval} (the header's maxval)")
    return img.astype(np.int64), maxval


def _grid_from_image(img: np.ndarray, maxval: int, negate: bool, occ_t: float, free_t: float,
                     resolution: float, origin, name: str) -> GridMap:
    # map_server: p = (maxval - v) / maxval is the occupancy probability (negate flips it)
    p = img / maxval if negate else (maxval - img) / maxval
    free = p < free_t
    return GridMap.from_rows(~free, resolution, origin, name)


def _load_ros_yaml(path: Path) -> GridMap:
    import yaml

    try:
        meta = yaml.safe_load(_read_text(path))
    except yaml.YAMLError as exc:
        raise MapFormatError(f"{path}: not valid YAML ({exc})") from None
    if not isinstance(meta, dict) or "image" not in meta:
        raise MapFormatError(f"{path}: a ROS map YAML needs keys image, resolution, origin")
    try:
        res = float(meta.get("resolution", 1.0))
        origin = meta.get("origin", [0.0, 0.0, 0.0])
        ox, oy = float(origin[0]), float(origin[1])
        negate = bool(int(meta.get("negate", 0)))
        occ_t = float(meta.get("occupied_thresh", 0.65))
        free_t = float(meta.get("free_thresh", 0.196))
    except (TypeError, ValueError, IndexError):
        raise MapFormatError(f"{path}: resolution, origin, negate and thresholds must be numbers") from None
    if not 0 <= free_t <= occ_t <= 1:
        raise MapFormatError(f"{path}: need 0 <= free_thresh <= occupied_thresh <= 1, got {free_t}, {occ_t}")
    image = Path(str(meta["image"]))
    if not image.is_absolute():
        image = path.parent / image
    if image.suffix.lower() != ".pgm":
        raise MapFormatError(f"{path}: image {image.name} is not a .pgm; convert it to PGM")
    img, maxval = _read_pgm(image)
    return _grid_from_image(img, maxval, negate, occ_t, free_t, res, (ox, oy), path.stem)


def _load_pgm(path: Path) -> GridMap:
    img, maxval = _read_pgm(path)
    return _grid_from_image(img, maxval, False, 0.65, 0.196, 1.0, (0.0, 0.0), path.stem)


def _load_circles(path: Path):
    from .circles import CircleWorld

    return CircleWorld.from_json(path)


_LOADERS = {
    ".json": _load_circles,
    ".map": _load_movingai,
    ".txt": _load_matrix_text,
    ".csv": _load_matrix_text,
    ".npy": _load_npy,
    ".yaml": _load_ros_yaml,
    ".yml": _load_ros_yaml,
    ".pgm": _load_pgm,
}


def load_map(path: str | os.PathLike) -> GridMap:
    """Load an occupancy grid, choosing the reader from the file suffix.

    Args:
        path: ``.map`` (Moving AI), ``.yaml`` + ``.pgm`` (ROS map_server), ``.pgm``,
            ``.npy``, ``.txt`` or ``.csv`` (0/1 matrix), or ``.json`` (a circle world,
            returned as a :class:`CircleWorld`). Names of maps shipped with
            optplan (``optplan.world.maps.names()``) are accepted too.

    Raises:
        MapFormatError: missing, empty, truncated, binary or malformed file, or a map
            with no free cell.
    """
    p = Path(path)
    if not p.exists():
        from . import maps

        shipped = maps.find(str(path))
        if shipped is None:
            raise MapFormatError(f"map file {path} does not exist (shipped maps: {', '.join(maps.names())})")
        p = shipped
    if p.is_dir():
        raise MapFormatError(f"{p} is a folder, not a map file")
    loader = _LOADERS.get(p.suffix.lower())
    if loader is None:
        raise MapFormatError(f"{p}: unknown map format {p.suffix!r}; use one of {', '.join(sorted(_LOADERS))}")
    try:
        world = loader(p)
    except ParameterError as exc:  # e.g. a resolution of 0 in the file: the file is at fault
        raise MapFormatError(f"{p}: {exc}") from None
    if isinstance(world, GridMap) and world.occ.all():
        raise MapFormatError(f"{p}: every cell of this {world.width} x {world.height} map is blocked; "
                             "nothing can be planned on it (is the map inverted? 0 = free, 1 = blocked)")
    return world


def save_map(grid: GridMap, path: str | os.PathLike) -> Path:
    """Write ``grid`` in the format given by the suffix (``.map``, ``.txt``, ``.csv``,
    ``.npy``, or ``.yaml`` which also writes a ``.pgm`` beside it). Returns the path."""
    p = Path(path)
    rows = grid.to_rows()
    suffix = p.suffix.lower()
    if suffix == ".map":
        body = "\n".join("".join("@" if v else "." for v in r) for r in rows)
        p.write_text(f"type octile\nheight {grid.height}\nwidth {grid.width}\nmap\n{body}\n")
    elif suffix in (".txt", ".csv"):
        sep = "," if suffix == ".csv" else " "
        p.write_text("\n".join(sep.join(str(int(v)) for v in r) for r in rows) + "\n")
    elif suffix == ".npy":
        np.save(p, rows.astype(bool))
    elif suffix in (".yaml", ".yml"):
        pgm = p.with_suffix(".pgm")
        img = np.where(rows, 0, 254).astype(np.uint8)
        pgm.write_bytes(f"P5\n{grid.width} {grid.height}\n255\n".encode() + img.tobytes())
        p.write_text(
            f"image: {pgm.name}\nresolution: {grid.resolution!r}\norigin: [{grid.origin[0]!r}, {grid.origin[1]!r}, 0.0]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
        )
    else:
        raise MapFormatError(f"{p}: cannot save format {p.suffix!r}; use .map, .txt, .csv, .npy or .yaml")
    return p
