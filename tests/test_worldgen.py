"""Experiment generation (``optplan.worldgen``): the paper-map recipes and scenario realisation."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op
from optplan.world.maps import MAPS_DIR
from optplan.worldgen.papermaps import GENERATED, block_grid
from optplan.worldgen.scenarios import realize


@pytest.mark.parametrize("name", [n for n, (kind, _) in GENERATED.items() if kind == "grid"])
def test_grid_recipes_rebuild_the_shipped_maps(name):
    _, params = GENERATED[name]
    shipped = op.load_map(MAPS_DIR / f"{name}.txt")
    assert np.array_equal(block_grid(**params), shipped.occ)


def test_a_scenario_without_seeded_parts_is_realised_as_it_is():
    sc = op.load_scenario("li2023_exp1")
    assert not sc.random_obstacles and not sc.random_dynamic and not sc.timing_jitter
    assert realize(sc, 5) is sc
