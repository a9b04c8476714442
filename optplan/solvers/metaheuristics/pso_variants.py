"""IPSO1, the improved PSO yang2023 compares IPSO with in §7.1 (Tables 1-3, Fig 12, its [18]).

W. Li, M. Tan, L. Wang, Q. Z. Wang, "A cubic spline method combing improved particle swarm
optimization for robot path planning in dynamic uncertain environment", International Journal
of Advanced Robotic Systems 17(1) (2020), doi:10.1177/1729881419891661. yang2023 §1 sums it up:
"hierarchical random disturbance to increase population diversity and improve the algorithm's
local search capability by modifying particle positions. Additionally, a random positive
feedback factor"; §4.2 says the factor adjusts a particle "based on [its] fitness after
iteration compared with that before iteration". The article's text was not available here
(issue 44 item 5: the documentation, web-page and public-code corpora); what is known of its
rules and what is reconstructed, rule by rule, in the order of a step:

* **velocity with the positive feedback factor** (Li 2020 eq 7-8, as a public C++
  implementation that names those equations writes them):
  ``V = w V + c1 r1 (P_best - X) + c2 r2 (G_best - X) + theta``, then after the move
  ``theta = theta / t + r3 V`` for a particle whose fitness improved and
  ``theta = theta / t - r3 V`` for one that did not (``t`` the iteration, ``r3 ~ U(0, 1)^d``,
  ``theta = 0`` at the start). "Improved" is the C++ code's reading: the new position beats the
  particle's personal best. (yang2023 §4.2's wording, "fitness after iteration compared with
  that before iteration", suggests the fitness before the move; with that reading about half of
  the moves count as improvements, each of them amplifies the velocity by up to ``1 + r3``, and
  the swarm never settles: 50-190 on a 10-dimensional shifted sphere after 300 iterations where
  the personal-best reading reaches 1e-8.)
* **inertia and learning factors**: *reconstructed* as the PSO baseline's, ``w`` falling
  linearly from 0.9 to 0.4 and ``c1 = c2 = 1.5`` (yang2023 §7.1 runs all four algorithms
  with these values; Li 2020's own schedule was not recovered). Velocities are clamped and the
  walls absorb as in :class:`.pso.PSO`.
* **hierarchical random disturbance**: *reconstructed* from yang2023's summary alone. After
  the move the swarm is split by fitness into three tiers (the split yang2023 §4.1-4.3 uses
  itself): the best third tries a small disturbance ``X + s_good (ub - lb) N(0, 1)`` and keeps
  it only if it is better (local search), the worst third is moved by a large one
  ``X + s_poor (ub - lb) N(0, 1)`` whatever it gives (diversity), the middle third is left
  alone. ``s_good = 0.01``, ``s_poor = 0.1`` are ours. This costs ``2/3`` of a population of
  evaluations per iteration (IPSO's own extra steps cost about 0.6).

IPSO2 (yang2023's [19], Tan et al. 2022) is not implemented: only yang2023's one-sentence
summary of it was found ("evolutionary capabilities ... the evolutionary ratio"), no formula.
"""
from __future__ import annotations

import numpy as np

from .engine import State, better, rank
from .pso import PSO


class IPSO1(PSO):
    """IPSO1 (Li et al. 2020): positive feedback in the velocity, tiered random disturbance."""

    name = "ipso1"
    disturb_good = 0.01          # reconstructed (module docstring)
    disturb_poor = 0.1           # reconstructed (module docstring)

    def setup(self, state: State) -> None:
        super().setup(state)
        self.theta = np.zeros_like(state.X)

    def velocity(self, state: State, w) -> np.ndarray:
        """PSO's velocity plus the positive feedback factor ``theta``."""
        return super().velocity(state, w) + self.theta

    def positive_feedback(self, state: State) -> None:
        """Li 2020 eq 7-8: ``theta / t`` plus ``r V`` where the move beat the particle's
        personal best, minus ``r V`` where it did not (call before :meth:`remember`)."""
        improved = better(state.F, state.V, self.PF, self.PV)
        sign = np.where(improved, 1.0, -1.0)[:, None]
        r = state.rng.random(state.X.shape)
        self.theta = self.theta / state.it + sign * r * self.V

    def disturb(self, state: State) -> None:
        """The tiered random disturbance (reconstructed, module docstring)."""
        rng = state.rng
        n, d = state.X.shape
        order = rank(state.F, state.V)
        third = n // 3
        if third == 0:
            return
        good, poor = order[:third], order[n - third:]
        span = state.upper - state.lower
        Xg, Fg, Vg = state.eval_new(state.X[good] + self.disturb_good * span * rng.normal(size=(third, d)))
        state.greedy(Xg, Fg, Vg, good)
        Xp, Fp, Vp = state.eval_new(state.X[poor] + self.disturb_poor * span * rng.normal(size=(third, d)))
        state.X[poor], state.F[poor], state.V[poor] = Xp, Fp, Vp

    def step(self, state: State) -> None:
        self.move(state, self.velocity(state, self.inertia(state)))
        self.positive_feedback(state)
        self.remember(state)
        self.disturb(state)
        self.remember(state)
