"""Each paper's path fitness as data: weights on the shared terms of
:mod:`optplan.formulations.terms`, plus how constraints are handled.

``penalty`` mode adds ``collision_penalty * collisions + penetration_penalty *
penetration`` to the weighted terms (the papers' choice); ``feasibility`` mode
keeps the weighted terms as the objective and hands the violation to the solver,
which ranks feasible before infeasible, then by violation, then by objective.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from ..errors import UnknownAlgorithmError


@dataclass(frozen=True)
class FitnessPreset:
    """Weights of one paper's path fitness.

    Attributes:
        name: registry key.
        source: paper section / equation.
        length, turn_angle, turn_count, turn_cost: weights on the shared terms.
        collision_penalty: added per colliding segment (penalty mode); ``"goal_product"``
            uses the goal's grid coordinates ``Tx * Ty`` as chen2025 eq 32 does.
        penetration_penalty: weight of the smooth penetration integral.
        constraint: ``"penalty"`` or ``"feasibility"``.
    """

    name: str
    source: str
    length: float = 1.0
    turn_angle: float = 0.0
    turn_count: float = 0.0
    turn_cost: float = 0.0
    collision_penalty: float | str = 100.0
    penetration_penalty: float = 100.0
    constraint: str = "penalty"

    def with_constraint(self, mode: str) -> "FitnessPreset":
        return replace(self, constraint=mode)


PRESETS: dict[str, FitnessPreset] = {
    p.name: p
    for p in (
        FitnessPreset("length", "shortest collision-free path", collision_penalty=100.0),
        FitnessPreset("hou2024", "hou2024 §4.1: path length with an obstacle penalty (Tables 2-3 report length)",
                      collision_penalty=100.0),
        FitnessPreset("yang2023", "yang2023 eq 2-5: spline length, grown circles as hard obstacles",
                      collision_penalty=100.0, penetration_penalty=100.0),
        FitnessPreset("yuan2021", "yuan2021 eq 10-13: eta*L + lambda*phi*m_ob + mu*(m1*pi/4 + m2*pi/2); "
                      "eta = lambda = 1, phi = 100, mu = 0 for the shortest-path experiment (§5.1 (1))",
                      turn_cost=0.0, collision_penalty=100.0),
        FitnessPreset("yuan2021-smooth", "yuan2021 eq 13 with the smoothing term on (mu = 1)", turn_cost=1.0,
                      collision_penalty=100.0),
        FitnessPreset("yuan2021-mu0.1", "yuan2021 eq 13 with the Table 2 weights eta = lambda = 1, mu = 0.1 "
                      "(§5.1 (2))", turn_cost=0.1, collision_penalty=100.0),
        FitnessPreset("li2023", "li2023 eq 2-3: alpha*l + beta*theta + gamma*turns, alpha = 1, beta = 0.1, "
                      "gamma = 0.1 (the paper leaves the weights open); eq 3 as a hard constraint",
                      turn_angle=0.1, turn_count=0.1, collision_penalty=100.0, penetration_penalty=0.0),
        FitnessPreset("chen2025", "chen2025 eq 32: O * (Tx * Ty) + length", collision_penalty="goal_product",
                      penetration_penalty=0.0),
    )
}


def collision_penalty_on(preset: FitnessPreset, world, goal) -> float:
    """What penalty mode adds per colliding segment on ``world``: the preset's value, or
    chen2025 eq 32's goal product ``Tx * Ty`` (grid coordinates of the goal, from 1)."""
    pen = preset.collision_penalty
    if pen == "goal_product":
        tx, ty = world.cell_of(goal) + 1 if world.is_grid else goal
        pen = float(tx * ty)
    return float(pen)


def uses_penetration(preset: FitnessPreset) -> bool:
    """Whether a fitness measures how deep a path enters obstacles (a penalty on it, or the
    feasibility rule's violation), which samples the map's distance field."""
    return bool(preset.penetration_penalty) or preset.constraint == "feasibility"


def get_preset(name: str | FitnessPreset) -> FitnessPreset:
    """Look up a preset by name (or pass one through)."""
    if isinstance(name, FitnessPreset):
        return name
    try:
        return PRESETS[name]
    except KeyError:
        raise UnknownAlgorithmError(f"unknown fitness preset {name!r}; known: {', '.join(sorted(PRESETS))}") from None
