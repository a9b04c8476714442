"""Fusion of global and local planning: subgoal selection (key points, turning points,
navigation points), the path switch strategy and re-planning (see ``navigator``)."""
from __future__ import annotations

from .navigator import ON_BLOCKED, PRESET_DEFAULTS, Navigator, preset_defaults
from .path_switch import VirtualPointGraph
from .subgoals import STRATEGIES, SubgoalStrategy, make_strategy, velocity_obstacle_hits

__all__ = ["Navigator", "ON_BLOCKED", "PRESET_DEFAULTS", "STRATEGIES", "SubgoalStrategy", "VirtualPointGraph",
           "make_strategy", "preset_defaults", "velocity_obstacle_hits"]
