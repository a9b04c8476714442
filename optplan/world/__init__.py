"""Layer 1: what the robot lives in — maps, circle worlds, exact geometry, metrics."""
from .circles import CircleWorld
from .geometry import PathCheck, segments_free, validate_path
from .grid import GridMap
from .protocol import World
from .loaders import ScenEntry, load_map, load_scen, save_map
from .metrics import PathMetrics, path_metrics
from .postprocess import key_points, prune_direct, remove_collinear, spline_resample

__all__ = [
    "CircleWorld", "GridMap", "PathCheck", "PathMetrics", "ScenEntry", "World", "key_points", "load_map",
    "load_scen", "path_metrics", "prune_direct", "remove_collinear", "save_map", "segments_free",
    "spline_resample", "validate_path",
]
