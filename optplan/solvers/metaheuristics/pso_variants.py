"""IPSO1 and IPSO2, the improved PSOs yang2023 compares IPSO with in §7.1 (Tables 1-3, Fig 12, its [18], [19]).

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

IPSO2, yang2023's second baseline ([19]), is :class:`IPSO2` below: a *reconstruction*, since the
rule of its source was not found (see that class).
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


def fitness_ratio(a, b) -> np.ndarray:
    """``min(|a|, |b|) / max(|a|, |b|)`` elementwise, in [0, 1]: the ratio both factors of Yang et al.
    2007 (§3, the evolution speed factor ``h`` and the aggregation degree ``s``) are built from.

    For positive fitness (a path length, a sphere) it is their ``|min(a, b) / max(a, b)|``; taking
    the magnitudes first is ours, so that a negative objective reads the same way. Conventions
    (ours): equal values give 1 (``0 / 0`` and ``inf / inf`` too: nothing changed), a finite value
    against an infinite one gives 0 (the largest change)."""
    a, b = np.abs(a), np.abs(b)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = lo / hi
    return np.where(lo == hi, 1.0, r)


class IPSO2(PSO):
    """IPSO2 (yang2023's [19]): a RECONSTRUCTION of Tan et al. 2022's adaptive PSO.

    [19] is Z. Tan, H. G. Liang, D. Zhang, Q. G. Wang, "Path planning of surgical needle: a new
    adaptive intelligent particle swarm optimization method", Transactions of the Institute of
    Measurement and Control 44(4) (2022) 766-774. Its rules were not found (issue 44 item 5;
    docs/fidelity/yang2023.md). What is known is yang2023 §1's summary: the "evolutionary
    capabilities" of the particles and of the population say how good they are, and the inertia
    weight and the learning factors are set "based on the evolutionary ratio". This class fills
    that outline with the closest published rule we could find and marks what is ours. Yang 2007's
    article itself was not readable here beyond its abstract (which names both factors and a
    weight that is "a function of" them); ``h`` and ``s`` are as a public Java re-implementation
    quotes them from the article, and the weight's form as the CIlib library implements the rule
    (``DAPSOInertiaStrategy``, citing the article):

    * **evolution speed of a particle** (Yang, Yuan, Yuan, Mao 2007, "A modified particle swarm
      optimizer with dynamic adaptation", Applied Mathematics and Computation 189, 1205-1213, §3):
      ``h_i = |min(F(pbest_i, t-1), F(pbest_i, t)) / max(...)|``, in (0, 1]: 1 when the personal
      best did not move, small when it fell a lot. Computed after each move (:meth:`remember`) and
      used by the next one; 1 before the first move. (:func:`fitness_ratio` for our handling of
      negative and infinite values; under the feasibility rule ``h`` reads the objective values
      of the personal bests only, whichever way they moved.)
    * **aggregation degree of the swarm** (Yang 2007 §3): ``s = |min(F_tbest, F_mean) / max(...)|``
      with ``F_tbest`` the best and ``F_mean`` the mean fitness of the current positions (this
      iteration's, not the best ever found); near 1 when the swarm has gathered. Infinite values
      (points beyond an evaluation budget) are left out of both.
    * **inertia weight per particle** (Yang 2007 §3): ``w_i = w_ini - alpha (1 - h_i) + beta s``. A
      particle whose best is falling fast gets less inertia (it refines where it is), a stalled
      particle in a gathered swarm more (it keeps exploring). The article's constants could not be
      confirmed; CIlib's defaults are ``w_ini = 1, alpha = 1, beta = 0.1``. **Ours**: ``beta = 0.1``
      as CIlib's, and ``w_ini = 0.8``, ``alpha = 0.4`` so that ``w_i`` spans exactly yang2023 §7.1's
      ``[w_min, w_max] = [0.4, 0.9]`` (the range all four algorithms are run with there); it is
      clipped to that range too.
    * **learning factors per particle** (**ours**; Yang 2007 keeps them fixed, and Tan 2022's rule is
      the part we could not recover). A particle's share of the swarm's progress this iteration,
      ``u_i = (1 - h_i) / max_j (1 - h_j)`` in [0, 1] (0 for all when no personal best improved),
      is set against the swarm's mean share ``u_mean``, and the difference moves weight between
      the two pulls: ``c1_i = c1 + c_shift (u_i - u_mean)``, ``c2_i = c2 - c_shift (u_i - u_mean)``.
      A particle evolving more slowly than the swarm as a whole leans on the social term, one
      evolving faster on its own memory; the swarm's mean factors stay ``c1``, ``c2``, and
      ``c1_i + c2_i = c1 + c2`` always. ``c_shift = 0.5`` is ours (the factors stay within
      ``c1 +- 0.5``); ``c1 = c2 = 1.5`` are yang2023 §7.1's. (Shifting every stalled particle
      towards the social term, not only those below the swarm's mean, made the swarm collapse
      onto a wall point now and then on shifted functions: the mean is kept for that reason.)
    * everything else is :class:`.pso.PSO`'s: velocity ``w V + c1 r1 (P - X) + c2 r2 (G - X)``,
      clamped to ``v_max_frac`` of the box, absorbing walls, one evaluation per particle and
      iteration (PSO's budget: 15,050 evaluations at yang2023's 50 x 300).

    The fitness ratios depend on where the objective's zero lies (a constant added to every value
    moves ``h`` and ``s`` towards 1); on yang2023's path lengths, which are far from 0, ``h`` stays
    near 1 for most particles and the inertia mostly follows ``s``. That is a property of the
    published rule, kept as it is.
    """

    name = "ipso2"
    BATCHABLE = True           # every rule below also takes a leading run axis
    w_ini = 0.8                # ours (class docstring); Yang 2007's form
    alpha = 0.4                # ours
    beta = 0.1                 # CIlib's value for Yang 2007's rule
    c_shift = 0.5              # ours: how far the learning factors may move from c1, c2

    def setup(self, state: State) -> None:
        super().setup(state)
        self.h = np.ones_like(state.F)

    def aggregation(self, state: State) -> np.ndarray:
        """Yang 2007's aggregation degree ``s`` of the current positions, shape ``([R,] 1)``."""
        F = state.F
        finite = np.isfinite(F)
        count = finite.sum(axis=-1, keepdims=True)
        best = np.min(np.where(finite, F, np.inf), axis=-1, keepdims=True)
        mean = np.where(finite, F, 0.0).sum(axis=-1, keepdims=True) / np.maximum(count, 1)
        return fitness_ratio(best, np.where(count > 0, mean, np.inf))

    def inertia(self, state: State) -> np.ndarray:
        """Yang 2007's ``w_i = w_ini - alpha (1 - h_i) + beta s``, clipped to ``[w_min, w_max]``;
        shape ``([R,] n, 1)``."""
        w = self.w_ini - self.alpha * (1.0 - self.h) + self.beta * self.aggregation(state)
        return np.minimum(np.maximum(w, self.w_min), self.w_max)[..., None]

    def learning_factors(self) -> tuple[np.ndarray, np.ndarray]:
        """Our rule (class docstring): ``(c1_i, c2_i)``, each of shape ``([R,] n, 1)``."""
        gain = 1.0 - self.h
        top = gain.max(axis=-1, keepdims=True)
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.where(top > 0, gain / top, 0.0)
        shift = self.c_shift * (u - u.mean(axis=-1, keepdims=True))
        return (self.c1 + shift)[..., None], (self.c2 - shift)[..., None]

    def velocity(self, state: State, w) -> np.ndarray:
        """PSO's velocity with each particle's own learning factors."""
        n, d = state.X.shape[-2:]
        r = state.rng.random((2, n, d))                       # ([R,] 2, n, d)
        c1, c2 = self.learning_factors()
        return (w * self.V + c1 * r[..., 0, :, :] * (self.P - state.X)
                + c2 * r[..., 1, :, :] * (self.gbest() - state.X))

    def remember(self, state: State) -> None:
        """Update the personal bests, then each particle's evolution speed ``h`` (Yang 2007)."""
        before = self.PF.copy()
        super().remember(state)
        self.h = fitness_ratio(before, self.PF)
