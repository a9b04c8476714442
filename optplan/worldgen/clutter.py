"""Seeded clutter worlds of the kind the BARN benchmark uses, and the ``clutter`` scenarios.

The obstacle field is grown by the cellular-automaton procedure of Perille et al. 2020
("Benchmarking Metric Ground Navigation", SSRR, §III): every cell of a square field is
filled at random with a fill probability, then a few smoothing iterations apply the same
rule to every cell at once: a cell with at least ``fill_threshold`` of its 8 neighbours
filled becomes filled, one with at most ``clear_threshold`` becomes free, the others
keep their state. A world is kept only if the robot's footprint has a path through it
(A* with the robot radius as clearance, the exact segment rule); otherwise the same
generator draws again, so a seed always gives the same world.

Layout (x is the direction of travel): an entry corridor ``entry`` cells long, the
``field x field`` obstacle field, then open ground up to the goal, ``goal_ahead`` metres
beyond the start. The corridor and the field are closed by walls along their two long
sides, so the field cannot be bypassed; the ground beyond it is open.

``clutter_scenario(seed, movers=2)`` adds moving discs that drive back and forth across
the global path (the scenario's ``random_dynamic`` draw of
:mod:`optplan.worldgen.scenarios`, realised by ``op.simulate`` with the same seed).
``op.simulate("clutter", seed=N)`` and ``optplan simulate clutter --seed N`` run the
family by name (:data:`FAMILIES`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InfeasibleQueryError, ParameterError, ScenarioError
from ..rng import as_generator
from ..world.grid import GridMap
from ..world.robot import RobotSpec
from ..world.scenario import Scenario

# the robot of issue 27: a Jackal-sized disc with BARN's limits
BARN_ROBOT = RobotSpec(model="unicycle", radius=0.2, v_max=0.5, w_max=math.radians(90.0), a_max=1.0,
                       alpha_max=math.radians(180.0))


@dataclass(frozen=True)
class ClutterRecipe:
    """Parameters of the cellular automaton and of the layout.

    Attributes:
        field: side of the square obstacle field, cells.
        resolution: cell side, metres.
        entry: length of the entry corridor before the field, cells.
        goal_ahead: distance from the start to the goal along x, metres.
        fill: range of the initial fill probability (one value drawn per world).
        smoothing: range (inclusive) of the number of smoothing iterations.
        fill_threshold: filled neighbours (of 8) that make a cell filled.
        clear_threshold: filled neighbours at or below which a cell becomes free.
        max_draws: draws tried before a seed is declared to give no passable world.
    """

    field: int = 30
    resolution: float = 0.15
    entry: int = 10
    goal_ahead: float = 10.0
    fill: tuple[float, float] = (0.15, 0.30)
    smoothing: tuple[int, int] = (2, 4)
    fill_threshold: int = 5
    clear_threshold: int = 1
    max_draws: int = 200

    def __post_init__(self) -> None:
        if self.field < 5 or self.entry < 3:
            raise ParameterError(f"clutter field must be >= 5 cells and entry >= 3 cells, got {self.field}, {self.entry}")
        if not (0.0 <= self.fill[0] <= self.fill[1] < 1.0):
            raise ParameterError(f"clutter fill must be a range inside [0, 1), got {self.fill!r}")
        if not (0 <= self.smoothing[0] <= self.smoothing[1]):
            raise ParameterError(f"clutter smoothing must be a range of iteration counts, got {self.smoothing!r}")
        if not (0 <= self.clear_threshold < self.fill_threshold <= 8):
            raise ParameterError("clutter thresholds need 0 <= clear_threshold < fill_threshold <= 8, got "
                                 f"{self.clear_threshold}, {self.fill_threshold}")

    @property
    def start(self) -> np.ndarray:
        """Start point (metres): in the entry corridor, 4 cells from its mouth, on the centre line."""
        return np.array([4.0 * self.resolution, self.field * self.resolution / 2])

    @property
    def goal(self) -> np.ndarray:
        """Goal point (metres), ``goal_ahead`` beyond the start."""
        return self.start + np.array([self.goal_ahead, 0.0])

    @property
    def width(self) -> int:
        """Map length along x, cells (the goal at least 4 cells from the far border)."""
        return int(math.ceil(self.goal[0] / self.resolution)) + 4


def smooth(occ: np.ndarray, iterations: int, fill_threshold: int = 5, clear_threshold: int = 1) -> np.ndarray:
    """``iterations`` synchronous cellular-automaton steps (Perille et al. 2020 §III):
    a cell with ``>= fill_threshold`` filled 8-neighbours becomes filled, one with
    ``<= clear_threshold`` becomes free. Beyond the first and last rows lie the field's
    walls (filled); beyond the first and last columns lie the open entry and exit (free)."""
    out = np.asarray(occ, dtype=bool).copy()
    for _ in range(int(iterations)):
        padded = np.pad(out, ((1, 1), (0, 0)), constant_values=True)
        padded = np.pad(padded, ((0, 0), (1, 1)), constant_values=False).astype(np.int8)
        h, w = out.shape
        n = sum(padded[1 + dy:1 + dy + h, 1 + dx:1 + dx + w].astype(np.int64)
                for dy in (-1, 0, 1) for dx in (-1, 0, 1) if dy or dx)
        out = np.where(n >= fill_threshold, True, np.where(n <= clear_threshold, False, out))
    return out


def clutter_field(rng, recipe: ClutterRecipe) -> np.ndarray:
    """One draw of the ``field x field`` obstacle field (``occ[iy, ix]``, before the walls)."""
    fill = rng.uniform(*recipe.fill)
    iters = int(rng.integers(recipe.smoothing[0], recipe.smoothing[1] + 1))
    occ = rng.random((recipe.field, recipe.field)) < fill
    return smooth(occ, iters, recipe.fill_threshold, recipe.clear_threshold)


def lay_out(field: np.ndarray, recipe: ClutterRecipe) -> np.ndarray:
    """The whole map: corridor, field (both walled along their long sides), open ground."""
    occ = np.zeros((recipe.field, recipe.width), dtype=bool)
    x0, x1 = recipe.entry, recipe.entry + recipe.field
    occ[:, x0:x1] = field
    occ[0, :x1] = True
    occ[-1, :x1] = True
    return occ


def clutter_grid(seed=0, recipe: ClutterRecipe | None = None, robot: RobotSpec = BARN_ROBOT) -> GridMap:
    """The clutter world of ``seed``: the first draw whose field ``robot`` can cross.

    Raises:
        ScenarioError: no draw in ``recipe.max_draws`` left a way through (raise the
            fill range's upper end less, or allow more draws).
    """
    from ..solvers.graph import shortest_path

    recipe = recipe or ClutterRecipe()
    rng = as_generator(seed)
    for _ in range(recipe.max_draws):
        grid = GridMap(lay_out(clutter_field(rng, recipe), recipe), recipe.resolution,
                       name=f"clutter-{seed}" if isinstance(seed, (int, np.integer)) else "clutter")
        if not (grid.is_free(recipe.start[None], robot.radius)[0] and grid.is_free(recipe.goal[None], robot.radius)[0]):
            continue
        try:
            res = shortest_path(grid, recipe.start, recipe.goal, method="astar", clearance=robot.radius)
        except InfeasibleQueryError:
            continue
        if res.feasible:
            return grid
    raise ScenarioError(f"no passable clutter world in {recipe.max_draws} draws for seed {seed!r}; "
                        "lower the fill range or raise max_draws")


def clutter_scenario(seed=0, movers: int = 0, recipe: ClutterRecipe | None = None,
                     robot: RobotSpec = BARN_ROBOT) -> Scenario:
    """The clutter scenario of ``seed`` with issue 27's settings: 2.5 m sensor range,
    dt 0.1 s, goal reached within 1 m in 100 s; ``movers`` discs (r 0.15 m, 0.2-0.4 m/s,
    tracks 1.5-3 m across the global path) drawn by ``op.simulate`` from the same seed."""
    if isinstance(movers, bool) or not isinstance(movers, (int, np.integer)) or movers < 0:
        raise ParameterError(f"movers must be an int >= 0, got {movers!r}")
    recipe = recipe or ClutterRecipe()
    grid = clutter_grid(seed, recipe, robot)
    dyn = {"count": int(movers), "radius": 0.15, "speed": (0.2, 0.4), "length": (1.5, 3.0),
           "keep_away": 1.5} if movers else None
    name = f"clutter{'-movers' if movers else ''}-{seed}" if isinstance(seed, (int, np.integer)) else "clutter"
    return Scenario(grid, robot, np.append(recipe.start, 0.0), recipe.goal, sensor_range=2.5, dt=0.1,
                    time_limit=100.0, goal_tolerance=1.0, random_dynamic=dyn, name=name,
                    description=f"seeded clutter world (Perille et al. 2020 cellular automaton), {movers} mover(s)")


# generated scenario families, by name: seed -> Scenario
FAMILIES = {
    "clutter": lambda seed: clutter_scenario(seed, movers=0),
    "clutter-movers": lambda seed: clutter_scenario(seed, movers=2),
}

# The global path of a clutter world is planned with 0.15 m to spare beyond the footprint
# where the clutter leaves such a route, else with the footprint alone (the navigator's
# clearance ladder: requested, robot radius, zero). An A* path between 0.15 m cell centres
# that only keeps the radius runs 2.5 cm from the cells on both sides of every gap it
# threads, which no sampled local planner with a 2 cm safety margin can follow; about half
# of the worlds (23 of development seeds 0-49) have a wider way round.
GLOBAL_CLEARANCE_EXTRA = 0.15


def family_options(name: str) -> dict:
    """``op.simulate`` options a generated family uses unless the caller gives its own: the
    global path's clearance only. No local planner parameters: qp-dwa's clutter mechanisms
    (issue 27) are its defaults wherever the global path is tight
    (``optplan.local.qp_dwa.path_is_tight``), so a scenario file of the same world gets them too."""
    if not isinstance(name, str) or name.lower() not in FAMILIES:
        return {}
    return {"global_options": {"clearance": BARN_ROBOT.radius + GLOBAL_CLEARANCE_EXTRA}}


def family_scenario(name: str, seed) -> Scenario | None:
    """The scenario of the generated family ``name`` for ``seed`` (``None``: not a family name)."""
    make = FAMILIES.get(str(name).lower()) if isinstance(name, str) else None
    return None if make is None else make(seed)
