"""How many points a smoother gives a path (``optplan.solvers.smoother.default_points``)."""
from __future__ import annotations

import numpy as np

from optplan.solvers.smoother import MAX_SEGMENT_SPACINGS, default_points


def straight(length: float) -> np.ndarray:
    return np.array([[0.0, 0.0], [length, 0.0]])


def test_short_and_medium_paths_keep_the_old_rule():
    # one point per spacing, a multiple of 10, between 20 and 100 (the rule every shipped map used)
    assert default_points(straight(1.0), 0.25) == 20
    assert default_points(straight(12.3), 0.25) == 10 * np.ceil((12.3 / 0.25 + 1) / 10)
    for length in (30.0, 100.0, 198.0):     # 100 points are enough up to 99 segments of 8 spacings
        assert default_points(straight(length), 0.25) == 100


def test_long_paths_get_points_per_length_so_segments_stay_short():
    for length in (250.0, 423.3, 1000.0):
        n = default_points(straight(length), 0.25)
        assert n > 100 and n % 10 == 0
        assert length / (n - 1) <= MAX_SEGMENT_SPACINGS * 0.25
        assert length / (n - 11) > MAX_SEGMENT_SPACINGS * 0.25   # and no more than needed
