"""Column-node segment values computed on demand equal the full per-map tables, and a
planning run with them is the run with the full tables."""
import numpy as np
import pytest

import optplan as op
from optplan.formulations import terms
from optplan.formulations.encodings import ColumnNodes
from optplan.formulations.segment_store import ColumnSegments, column_segments
from optplan.world.fields import distance_function
from optplan.world.papermaps import paper_map
from optplan.worldgen.city import city_map


def _cases():
    w, s, g = paper_map("chen2025_20")
    yield w, s, g
    w, s, g = paper_map("hou2024_env2")
    yield w, s, g
    c = city_map(40, seed=5)
    free = np.argwhere(~c.occ)
    yield c, c.cell_center(free[0][::-1]), c.cell_center(free[-1][::-1])


@pytest.mark.parametrize("clearance", [0.0, 0.3])
def test_every_segment_value_and_move_mask_equals_the_full_tables(clearance):
    for world, s, g in _cases():
        enc = ColumnNodes(world, np.asarray(s, float), np.asarray(g, float))
        dist = distance_function(world)
        pen_fn = lambda seg: terms.penetration(world, seg, clearance, enc.penetration_samples, distance=dist)  # noqa: E731
        full = enc.segment_tables(clearance, pen_fn)
        store = ColumnSegments(enc, clearance, pen_fn)
        every = np.arange(store.size)
        order = np.random.default_rng(0).permutation(every)       # filled in a scrambled order
        for part in np.array_split(order, 7):
            store.fill(part)
        np.testing.assert_array_equal(store.collisions(every), enc.flat_table(full))
        np.testing.assert_array_equal(store.penetration(every), enc.flat_table(full, "_pen"))
        dx, dy = store.deltas(every)
        np.testing.assert_array_equal(np.hypot(dx, dy), enc.segment_lengths())
        first, pruned, last = enc.feasible_transitions(clearance)
        lazy = ColumnSegments(enc, clearance)
        np.testing.assert_array_equal(lazy.first_moves(), first)
        H = world.height
        for j in range(enc.dim - 1):
            np.testing.assert_array_equal(lazy.moves(j, np.arange(H)), pruned[j])
            np.testing.assert_array_equal(lazy.moves_into(j, np.arange(H)), pruned[j].T)
        np.testing.assert_array_equal(lazy.last_moves(), last)
        # the reachability pass and the band decide a small share of the segments
        assert (lazy.state != 0).mean() < 0.5


def test_the_necessary_condition_never_rejects_a_free_segment():
    world = city_map(40, seed=8)
    enc = ColumnNodes(world, np.array([0.5, 0.5]), np.array([39.5, 39.5]))
    full = enc.segment_tables(0.0)["inner"]                       # (d-1, H, H), 1 = blocked
    store = ColumnSegments(enc, 0.0)
    j, r1, r2 = np.meshgrid(np.arange(enc.dim - 1), np.arange(40), np.arange(40), indexing="ij")
    maybe = store.may_be_free(j, r1, r2)
    assert not np.any((full == 0) & ~maybe)
    assert maybe.mean() < 0.5                                     # and it prunes


@pytest.mark.parametrize("preset", ["chen2025", "hou2024", "yuan2021", "li2023"])
@pytest.mark.parametrize("constraint", ["feasibility", "penalty"])
def test_population_scores_equal_the_full_table_sums(preset, constraint):
    from optplan.formulations.problem import PathProblem

    world, s, g = paper_map("hou2024_env1")
    enc = ColumnNodes(world, np.asarray(s, float), np.asarray(g, float))
    prob = PathProblem(enc, preset, clearance=0.2, constraint=constraint)
    rng = np.random.default_rng(4)
    X = np.vstack([rng.uniform(enc.lower, enc.upper, (300, enc.dim)), enc.sample_feasible(50, rng, 0.2)])
    f, v = prob.evaluate(X)
    # the full tables, summed as the scorer did before the values were computed on demand
    pen_fn = lambda seg: terms.penetration(world, seg, 0.2, enc.penetration_samples, distance=prob._distance)  # noqa: E731
    full = enc.segment_tables(0.2, pen_fn if prob._wants_penetration else None)
    coll = enc.flat_table(full)
    pen = enc.flat_table(full, "_pen") if prob._wants_penetration else np.zeros_like(coll)
    cost = prob.preset.length * enc.segment_lengths()
    if constraint == "penalty":
        cost = cost + prob._collision_penalty * coll + prob.preset.penetration_penalty * pen
    idx = enc.segment_index(enc.rows_of(X))
    f_ref = np.add.reduce(cost.take(idx), axis=1)
    if prob.has_turn_terms:
        f_ref = f_ref + prob.weighted_turns(terms.heading_changes_deg(enc.segment_headings().take(idx)))
    np.testing.assert_array_equal(f, f_ref)
    np.testing.assert_array_equal(v, np.add.reduce((coll + pen).take(idx), axis=1))
    assert (v > 0).any() and (v == 0).any()


@pytest.mark.parametrize("algorithm", ["ga", "iga"])
def test_path_gas_decide_segments_on_demand_not_in_full_tables(algorithm):
    world = city_map(48, seed=2)
    free = np.argwhere(~world.occ)
    s, g = world.cell_center(free[0][::-1]), world.cell_center(free[-1][::-1])
    r = op.plan(world, s, g, algorithm=algorithm, seed=3, pop=12, iters=15)
    assert r.feasible and bool(op.validate_path(world, r.path))
    from optplan.world.derived import derived_keys

    assert not any(isinstance(k, tuple) and k[0] in ("column_tables", "column_transitions")
                   for _, k in derived_keys(world))


def test_hashed_slots_give_the_same_scores_as_the_flat_layout(monkeypatch):
    """Beyond DENSE_SEGMENTS possible segments the values live in hashed slots (a 1000-column
    map has 10^9 segments): scores, moves and the planned path are the same numbers."""
    from optplan.formulations import segment_store as S
    from optplan.formulations.problem import PathProblem

    def run():
        world, s, g = paper_map("hou2024_env1")    # a new map: nothing cached from the other run
        enc = ColumnNodes(world, np.asarray(s, float), np.asarray(g, float))
        prob = PathProblem(enc, "hou2024", clearance=0.2, constraint="penalty")
        rng = np.random.default_rng(9)
        X = np.vstack([rng.uniform(enc.lower, enc.upper, (400, enc.dim)), enc.sample_feasible(40, rng, 0.2)])
        f, v = prob.evaluate(X)
        f2, v2 = prob.evaluate(X[::-1])            # a second pass reads what the first stored
        store = column_segments(enc, 0.2)
        assert store.index.dense == (S.DENSE_SEGMENTS > 0)
        return f, v, f2, v2, store.moves(3, np.arange(world.height))

    dense = run()
    monkeypatch.setattr(S, "DENSE_SEGMENTS", 0)
    hashed = run()
    for a, b in zip(dense, hashed):
        np.testing.assert_array_equal(a, b)


def test_slot_index_hands_out_one_slot_per_key():
    from optplan.formulations.segment_store import SlotIndex

    index = SlotIndex(10 ** 12)
    assert not index.dense
    rng = np.random.default_rng(1)
    keys = rng.integers(0, 10 ** 12, 50_000)
    first = index.slots(keys)
    again = index.slots(keys[::-1])[::-1]
    np.testing.assert_array_equal(first, again)
    assert index.used == len(np.unique(keys)) and set(np.unique(first)) == set(range(index.used))
    np.testing.assert_array_equal(index.keys(first), keys)


def test_a_tall_maps_sampler_decides_only_moves_near_its_aim(monkeypatch):
    """On a map taller than SAMPLE_WINDOW_ROWS the sampler decides the moves within
    SAMPLE_WINDOW rows of its aim (all H rows per column filled the store with millions of
    segments on a 1000 x 1000 map); the paths it draws stay collision-free."""
    from optplan.formulations import encodings as E

    def decided():
        occ = np.zeros((300, 40), bool)
        occ[100:200, 10:12] = True
        world = op.GridMap(occ)                       # a new map: a store of its own
        enc = ColumnNodes(world, np.array([0.5, 150.5]), np.array([39.5, 150.5]))
        X = enc.sample_feasible(20, np.random.default_rng(0))
        for x in X:
            assert op.validate_path(world, enc.decode(x[None])[0])
        return int((column_segments(enc, 0.0).state != 0).sum())

    windowed = decided()
    monkeypatch.setattr(E, "SAMPLE_WINDOW_ROWS", 10 ** 9)
    every_row = decided()
    # every row: up to 20 walkers x 39 steps x 300 rows beyond the band; the window: x 129
    assert every_row - windowed > 20 * 39 * (300 - 2 * E.SAMPLE_WINDOW - 1) // 4
