"""Map and scenario-list loaders.

Every format is read with its first row as the *top* row of the map (image
convention) and flipped so that ``occ[iy, ix]`` has ``iy`` growing upwards.

Supported by :func:`load_map` (dispatch on the suffix):

* ``.map`` — Moving AI benchmark format (``type``/``height``/``width``/``map``
  header; ``.``, ``G`` and ``S`` are free, every other character blocked).
* ``.yaml`` — ROS ``map_server`` metadata pointing at a ``.pgm`` (P2 or P5) image, or
  at a PNG/BMP/other image read with Pillow (installed with matplotlib); ``mode``
  (``trinary``, ``scale``, ``raw``), ``negate``, ``occupied_thresh``, ``free_thresh``,
  ``resolution`` and ``origin`` are honoured. Cells that are neither free nor occupied
  (unknown) are blocked. An origin yaw other than 0 cannot be applied to an
  axis-aligned grid: it is ignored with a :class:`MapOriginYawWarning`, as most ROS
  nodes ignore it.
* ``.pgm`` — the image alone (resolution 1, thresholds 0.65 / 0.196); ``.png``,
  ``.bmp``, ``.gif``, ``.tif``, ``.jpg`` likewise through Pillow.
* ``.npy`` — a 2-D array of 0/1 or booleans.
* ``.txt`` / ``.csv`` — a 0/1 matrix, values separated by spaces, tabs or commas.
"""
from __future__ import annotations

import io
import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..checks import file_path
from ..errors import MapFormatError, ParameterError
from .files import read_file, regular_file, written_whole
from .grid import MAX_GRID_CELLS, GridMap

MAX_CELLS = MAX_GRID_CELLS  # refuse maps larger than this (about 7000 x 7000) before reading them
MAX_FILE_BYTES = 512 * 1024 * 1024


def _read_text(path: Path) -> str:
    data = read_file(path, "map file", MAX_FILE_BYTES)
    if not data:
        raise MapFormatError(f"map file {path} is empty")
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


def _check_path_arg(path, fn: str) -> None:
    if not isinstance(path, (str, os.PathLike)) or (isinstance(path, str) and not path.strip()):
        raise MapFormatError(f"{fn} needs a file path or a shipped map name, got {path!r}"
                             + (" (to build a map from a matrix use op.GridMap.from_rows)" if isinstance(
                                 path, (list, tuple)) or hasattr(path, "shape") else ""))


# ------------------------------------------------------------------ YAML
MAX_YAML_BYTES = 16 * 1024 * 1024  # scenario, spec and map metadata files are small
MAX_YAML_NODES = 1_000_000  # values after expanding aliases: a "billion laughs" file is refused


def _yaml_error_line(path, exc) -> str:
    """One line naming the place and the problem of a YAML syntax error."""
    mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
    where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark is not None else ""
    problem = getattr(exc, "problem", None) or getattr(exc, "context", None) or type(exc).__name__
    return f"{path}: not valid YAML{where}: {' '.join(str(problem).split())[:200]}"


def _expanded_size(root) -> int:
    """Number of values ``root`` stands for once every alias is expanded (memoised per
    node, so a small file that expands to 10^18 values is counted without expanding it)."""
    import yaml

    sizes: dict[int, int] = {}
    order, stack = [], [root]
    while stack:  # post-order without recursion: deep nesting must not overflow the stack
        node = stack.pop()
        if id(node) in sizes:
            continue
        sizes[id(node)] = -1
        order.append(node)
        if isinstance(node, yaml.SequenceNode):
            stack.extend(node.value)
        elif isinstance(node, yaml.MappingNode):
            for k, v in node.value:
                stack.extend((k, v))
    for node in reversed(order):
        if isinstance(node, yaml.SequenceNode):
            children = node.value
        elif isinstance(node, yaml.MappingNode):
            children = [n for kv in node.value for n in kv]
        else:
            children = []
        sizes[id(node)] = 1 + sum(max(sizes[id(c)], 1) for c in children)
    return sizes[id(root)]


def _first_duplicate_key(root):
    """The first key written twice in one mapping of the document (YAML keeps the last and
    drops the others silently), as ``(key, line)``; ``None`` without one."""
    import yaml

    seen_nodes, stack = set(), [root]
    while stack:
        node = stack.pop()
        if id(node) in seen_nodes:
            continue
        seen_nodes.add(id(node))
        if isinstance(node, yaml.SequenceNode):
            stack.extend(node.value)
        elif isinstance(node, yaml.MappingNode):
            keys = set()
            for k, v in node.value:
                if isinstance(k, yaml.ScalarNode) and k.tag != "tag:yaml.org,2002:merge":
                    if k.value in keys:
                        return k.value, k.start_mark.line + 1
                    keys.add(k.value)
                stack.extend((k, v))
    return None


def read_yaml(path: str | os.PathLike, what: str = "YAML file", error=MapFormatError):
    """Parse a YAML file safely and within bounds, raising ``error`` with one line.

    Refuses files over :data:`MAX_YAML_BYTES`, documents that expand (through aliases)
    to more than :data:`MAX_YAML_NODES` values, and reports a syntax error as its line,
    column and problem. Scenario files, experiment specs and ROS map metadata all go
    through it.
    """
    import yaml

    p = Path(path)
    data = read_file(p, what, MAX_YAML_BYTES, error)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(f"{what} {p} is not UTF-8 text (byte {exc.start}); save it as UTF-8") from None
    loader = None
    try:
        loader = yaml.SafeLoader(text)
        node = loader.get_single_node()
        if node is None:
            return None
        n = _expanded_size(node)
        if n > MAX_YAML_NODES:
            raise error(f"{what} {p} expands to {n:.3g} values through YAML aliases; the limit is "
                        f"{MAX_YAML_NODES} (a file like this exhausts memory; write the values out)")
        twice = _first_duplicate_key(node)
        if twice is not None:
            raise error(f"{p}: line {twice[1]}: the key {twice[0]!r} is given twice in one mapping; "
                        "YAML would keep only the last, so write it once")
        return loader.construct_document(node)
    except yaml.YAMLError as exc:
        raise error(_yaml_error_line(p, exc)) from None
    except RecursionError:
        raise error(f"{what} {p} is nested too deeply to read") from None
    finally:
        if loader is not None:
            loader.dispose()


def _safe_yaml(path: Path):
    return read_yaml(path, "map metadata", MapFormatError)


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
    if len(rows) != h:
        raise MapFormatError(f"{path}: the header says {h} rows, the file has {len(rows)}"
                             + (" (truncated)" if len(rows) < h else "; fix the height line"))
    bad = [k for k, r in enumerate(rows) if len(r) != w]
    if bad:
        raise MapFormatError(f"{path}: row {bad[0] + 1} has {len(rows[bad[0]])} characters, header says width {w}")
    try:
        raw = "".join(rows).encode("latin-1")
    except UnicodeEncodeError as exc:
        bad_char = exc.object[exc.start]
        raise MapFormatError(f"{path}: the map holds the character {bad_char!r} (U+{ord(bad_char):04X}); a Moving AI "
                             "map uses one byte per cell ('.', 'G', 'S' free; '@', 'O', 'T', 'W' blocked)") from None
    chars = np.frombuffer(raw, dtype=np.uint8).reshape(h, w)
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
    _check_path_arg(path, "load_scen")
    path = Path(path)
    if not os.path.lexists(path):
        from . import maps

        shipped = maps.find(str(path))        # a scenario shipped beside its map (arena.map.scen)
        if shipped is None or shipped.suffix != ".scen":
            raise MapFormatError(f"scenario file {path} does not exist (shipped: arena.map.scen, beside the arena map)")
        path = shipped
    data = read_file(path, "scenario file", MAX_FILE_BYTES)
    if b"\x00" in data:
        raise MapFormatError(f"scenario file {path} contains binary data; expected a Moving AI .scen text file")
    lines = [ln for ln in data.decode("latin-1").replace("\r", "").split("\n") if ln.strip()]
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


def scen_query(world: GridMap, scen: str | os.PathLike, index: int) -> tuple[tuple[float, float], tuple[float, float]]:
    """Start and goal (metres, cell centres) of query ``index`` of a ``.scen`` file on ``world``.

    Raises:
        MapFormatError: the file is malformed, ``index`` is out of range, or the query was
            written for a map of another size.
    """
    entries = load_scen(scen)
    if not entries:
        raise MapFormatError(f"{scen}: the scenario file holds no queries")
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < len(entries):
        raise MapFormatError(f"{scen}: query {index!r} does not exist; it holds queries 0..{len(entries) - 1}")
    e = entries[int(index)]
    if not isinstance(world, GridMap) or (e.width, e.height) != (world.width, world.height):
        size = f"{world.width} x {world.height}" if isinstance(world, GridMap) else "a circle world"
        raise MapFormatError(f"{scen}: query {index} is for a {e.width} x {e.height} map ({e.map_name}); "
                             f"this map is {size}")
    iy_s, iy_g = e.height - 1 - e.start_y, e.height - 1 - e.goal_y
    s, g = world.cell_center(np.array([[e.start_x, iy_s], [e.goal_x, iy_g]]))
    return (float(s[0]), float(s[1])), (float(g[0]), float(g[1]))


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
    data = read_file(path, "map file", MAX_FILE_BYTES)
    try:
        arr = np.load(io.BytesIO(data), allow_pickle=False)
    except Exception as exc:  # numpy raises several types for corrupt files
        raise MapFormatError(f"{path}: not a readable .npy array ({exc})") from None
    if arr.ndim != 2:
        raise MapFormatError(f"{path}: expected a 2-D array, got shape {arr.shape}")
    _check_size(*arr.shape, path)
    if arr.dtype != bool and (arr.dtype.kind not in "iuf" or not np.all(np.isin(arr, (0, 1)))):
        raise MapFormatError(f"{path}: values must be 0/1 or booleans")
    return GridMap.from_rows(arr.astype(bool), name=path.stem)


# ------------------------------------------------------------------ ROS map_server
def _read_pgm(path: Path) -> np.ndarray:
    """Read a P2 (ASCII) or P5 (binary) PGM; returns uint values, top row first."""
    data = read_file(path, "image", MAX_FILE_BYTES)
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


IMAGE_SUFFIXES = (".png", ".bmp", ".gif", ".tif", ".tiff", ".jpg", ".jpeg", ".webp")
ROS_MODES = ("trinary", "scale", "raw")


class MapOriginYawWarning(UserWarning):
    """A ROS map's origin has a yaw that an axis-aligned grid cannot represent."""


class MapUnknownCellsWarning(UserWarning):
    """A ROS map holds cells that are neither free nor occupied (unknown); they are blocked."""


def _read_image(path: Path) -> tuple[np.ndarray, int]:
    """Read a raster image with Pillow: grey values (colour channels averaged, as ROS
    map_server does; fully transparent pixels count as unknown, value -1), top row
    first, and the largest value (255)."""
    try:
        from PIL import Image
    except ImportError:
        raise MapFormatError(f"{path}: reading {path.suffix} images needs Pillow; install it with "
                             "pip install 'optplan[images]' (or pip install pillow), or convert the image to .pgm") from None
    data = read_file(path, "image", MAX_FILE_BYTES)
    try:
        with Image.open(io.BytesIO(data)) as im:
            w, h = im.size
            _check_size(h, w, path)  # before decoding: a small file may declare a huge raster
            rgba = np.asarray(im.convert("RGBA"), dtype=np.int64)
    except MapFormatError:
        raise
    except (OSError, ValueError, SyntaxError, Image.DecompressionBombError) as exc:
        raise MapFormatError(f"{path}: not a readable image ({type(exc).__name__}: {exc})") from None
    grey = np.rint(rgba[..., :3].mean(axis=-1)).astype(np.int64)
    grey[rgba[..., 3] == 0] = -1
    return grey, 255


def _read_raster(path: Path) -> tuple[np.ndarray, int]:
    if path.suffix.lower() == ".pgm":
        return _read_pgm(path)
    if path.suffix.lower() in IMAGE_SUFFIXES:
        return _read_image(path)
    raise MapFormatError(f"{path}: image {path.name} is neither a .pgm nor one of {', '.join(IMAGE_SUFFIXES)}; "
                         "convert it to PGM or PNG")


def _grid_from_image(img: np.ndarray, maxval: int, negate: bool, occ_t: float, free_t: float,
                     resolution: float, origin, name: str, mode: str = "trinary") -> GridMap:
    if mode == "raw":
        # map_server raw: the pixel value is the occupancy value itself; 0 is free
        free = img == 0
    else:
        # trinary and scale: p = (maxval - v) / maxval is the occupancy probability (negate
        # flips it); below free_thresh is free. Unknown pixels (-1) and the intermediate
        # values that scale keeps as probabilities are blocked: a planner must not rely on them.
        p = img / maxval if negate else (maxval - img) / maxval
        free = (p < free_t) & (img >= 0)
        unknown = int(((p <= occ_t) & ~free).sum() + (img < 0).sum())
        if unknown:
            import warnings

            warnings.warn(f"{name}: {unknown} of {img.size} cells are neither free nor occupied (unknown, "
                          f"between free_thresh {free_t:g} and occupied_thresh {occ_t:g}); they are planned as "
                          "blocked", MapUnknownCellsWarning, stacklevel=4)
    return GridMap.from_rows(~free, resolution, origin, name)


def _load_ros_yaml(path: Path) -> GridMap:
    import warnings

    meta = _safe_yaml(path)
    if not isinstance(meta, dict) or "image" not in meta:
        raise MapFormatError(f"{path}: a ROS map YAML needs keys image, resolution, origin")
    numbers = [meta.get("resolution", 1.0), meta.get("occupied_thresh", 0.65), meta.get("free_thresh", 0.196),
               *(meta.get("origin") if isinstance(meta.get("origin"), (list, tuple)) else [])]
    if any(isinstance(v, bool) for v in numbers):
        raise MapFormatError(f"{path}: resolution, origin and thresholds must be numbers, not true/false")
    try:
        res = float(meta.get("resolution", 1.0))
        origin = meta.get("origin", [0.0, 0.0, 0.0])
        ox, oy = float(origin[0]), float(origin[1])
        yaw = float(origin[2]) if len(origin) > 2 else 0.0
        negate = bool(int(meta.get("negate", 0)))
        occ_t = float(meta.get("occupied_thresh", 0.65))
        free_t = float(meta.get("free_thresh", 0.196))
    except (TypeError, ValueError, IndexError, OverflowError):
        raise MapFormatError(f"{path}: resolution, origin, negate and thresholds must be numbers") from None
    if not all(np.isfinite(v) for v in (res, ox, oy, yaw)):
        raise MapFormatError(f"{path}: resolution and origin must be finite numbers")
    if not 0 <= free_t <= occ_t <= 1:
        raise MapFormatError(f"{path}: need 0 <= free_thresh <= occupied_thresh <= 1, got {free_t}, {occ_t}")
    mode = str(meta.get("mode", "trinary")).lower()
    if mode not in ROS_MODES:
        raise MapFormatError(f"{path}: mode must be one of {', '.join(ROS_MODES)}, got {meta.get('mode')!r}")
    if yaw != 0.0:
        warnings.warn(f"{path}: origin yaw {yaw:g} rad is ignored; the grid stays axis-aligned with its "
                      f"lower-left corner at ({ox:g}, {oy:g}) (rotate the image to apply a yaw)",
                      MapOriginYawWarning, stacklevel=3)
    image = Path(str(meta["image"]))
    if not image.is_absolute():
        image = path.parent / image
    img, maxval = _read_raster(image)
    return _grid_from_image(img, maxval, negate, occ_t, free_t, res, (ox, oy), path.stem, mode)


def _load_pgm(path: Path) -> GridMap:
    img, maxval = _read_raster(path)
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
    **{suffix: _load_pgm for suffix in IMAGE_SUFFIXES},
}


MATRIX_SUFFIXES = (".npy", ".txt", ".csv")
ORIGINS = ("upper", "lower")


def load_map(path: str | os.PathLike, origin: str = "upper") -> "GridMap | CircleWorld":
    """Load an occupancy grid (or a circle world), choosing the reader from the file suffix.

    Orientation: x grows along a row (to the right), y upwards. Every format's first row is
    the *top* row of the map (image convention, ``origin="upper"``, as ``matplotlib.imshow``
    draws an array by default): a ``.npy`` array ``a`` is read so that ``a[0]`` is the top,
    ``a[-1]`` the bottom row, and column ``j`` is ``x`` in ``[j, j + 1)`` cells. For a matrix
    whose first row is the bottom (``a[iy, ix]`` with ``iy`` up, as ``GridMap.occ`` holds it
    and ``imshow(origin="lower")`` draws it), pass ``origin="lower"`` (``optplan plan --flip``).

    Args:
        path: ``.map`` (Moving AI), ``.yaml`` + ``.pgm`` (ROS map_server), ``.pgm``,
            ``.npy``, ``.txt`` or ``.csv`` (0/1 matrix), or ``.json`` (a circle world,
            returned as a :class:`CircleWorld`), ``.png``/``.bmp``/other images through
            Pillow. Names of maps shipped with optplan (``optplan.world.maps.names()``)
            and of the paper maps (``chen2025_20``, ...; ``optplan.world.papermaps``) are
            accepted too.
        origin: ``"upper"`` (default) or ``"lower"``: where the first row of a ``.npy``,
            ``.txt`` or ``.csv`` matrix lies (the other formats fix it themselves).

    Raises:
        MapFormatError: missing, empty, truncated, binary or malformed file, or a map
            with no free cell.
        ParameterError: an unknown ``origin``, or ``"lower"`` for a format that fixes it.
    """
    _check_path_arg(path, "load_map")
    if origin not in ORIGINS:
        raise ParameterError(f"origin must be 'upper' (first row on top, the default) or 'lower' (first row at "
                             f"the bottom), got {origin!r}")
    p = Path(path)
    if not p.exists():
        from . import maps

        shipped = maps.find(str(path))
        if shipped is None:  # a paper map's name, as experiment specs use them?
            shipped = maps.paper_map_file(str(path))
        if shipped is None:
            raise MapFormatError(f"map file {path} does not exist (shipped maps: {', '.join(maps.names())}; "
                                 f"paper maps: see optplan/data/maps/paper_maps.yaml)")
        p = shipped
    regular_file(p, "map file")
    loader = _LOADERS.get(p.suffix.lower())
    if loader is None:
        raise MapFormatError(f"{p}: unknown map format {p.suffix!r}; use one of {', '.join(sorted(_LOADERS))}")
    if origin == "lower" and p.suffix.lower() not in MATRIX_SUFFIXES:
        raise ParameterError(f"origin='lower' is for 0/1 matrices ({', '.join(MATRIX_SUFFIXES)}); a {p.suffix} file "
                             "fixes its own orientation")
    try:
        world = loader(p)
    except ParameterError as exc:  # e.g. a resolution of 0 in the file: the file is at fault
        raise MapFormatError(f"{p}: {exc}") from None
    if origin == "lower":
        world = GridMap(world.occ[::-1], world.resolution, world.origin, world.name)
    if isinstance(world, GridMap) and world.occ.all():
        raise MapFormatError(f"{p}: every cell of this {world.width} x {world.height} map is blocked; "
                             "nothing can be planned on it (is the map inverted? 0 = free, 1 = blocked)")
    return world


def save_map(grid: GridMap, path: str | os.PathLike) -> Path:
    """Write ``grid`` in the format given by the suffix (``.map``, ``.txt``, ``.csv``,
    ``.npy``, or ``.yaml`` which also writes a ``.pgm`` beside it). Returns the path."""
    if not isinstance(grid, GridMap):
        raise ParameterError(f"grid must be an op.GridMap (only grid maps have a file format), got "
                             f"{type(grid).__name__}")
    p = Path(file_path("path", path))
    rows = grid.to_rows()
    suffix = p.suffix.lower()
    if suffix == ".map":
        body = "\n".join("".join("@" if v else "." for v in r) for r in rows)
        with written_whole(p, "map") as tmp:
            tmp.write_text(f"type octile\nheight {grid.height}\nwidth {grid.width}\nmap\n{body}\n")
    elif suffix in (".txt", ".csv"):
        sep = "," if suffix == ".csv" else " "
        with written_whole(p, "map") as tmp:
            tmp.write_text("\n".join(sep.join(str(int(v)) for v in r) for r in rows) + "\n")
    elif suffix == ".npy":
        with written_whole(p, "map") as tmp:
            np.save(tmp, rows.astype(bool))
    elif suffix in (".yaml", ".yml"):
        pgm = p.with_suffix(".pgm")
        img = np.where(rows, 0, 254).astype(np.uint8)
        with written_whole(pgm, "map image") as tmp:
            tmp.write_bytes(f"P5\n{grid.width} {grid.height}\n255\n".encode() + img.tobytes())
        with written_whole(p, "map") as tmp:
            tmp.write_text(
            f"image: {pgm.name}\nresolution: {grid.resolution!r}\norigin: [{grid.origin[0]!r}, {grid.origin[1]!r}, 0.0]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
        )
    else:
        raise MapFormatError(f"{p}: cannot save format {p.suffix!r}; use .map, .txt, .csv, .npy or .yaml")
    return p
