"""Particle swarm optimisation and IPSO (yang2023 §3-4).

PSO (yang2023 eq 6-7): ``V = w V + c1 r1 (P_best - X) + c2 r2 (G_best - X)``,
``X = X + V``, inertia falling linearly from ``w_max`` to ``w_min``, velocities
clamped to ``v_max_frac`` of the box; yang2023 §7.1 settings are the defaults
(c1 = c2 = 1.5, w in [0.4, 0.9]).

Bounds: absorbing walls (``walls="absorb"``). A particle whose move leaves the box
is clipped to the wall and loses the velocity component that took it out. yang2023
does not say how bounds are handled; with clipping alone (``walls="clip"``) a
particle keeps pushing outwards and stays stuck on the wall for many iterations,
which is what stalled PSO on shifted functions whose optimum lies near a wall
(``benchmarks/engine_speed.py`` shows the effect against mealpy's and niapy's PSO).
IPSO keeps clipping, as before, so its paper reproduction is unchanged.

IPSO changes, in the order of yang2023 §4:

* eq 8, adaptive inertia per particle, read as the text of §4.1 says (poor
  particles get more inertia, good ones less): better than average ->
  ``w_min + (w_max - w_min) (F_i - F_g) / (F_ave - F_g)``, from w_min at the best
  particle up to w_max at the average; average or worse -> w_max. As printed,
  eq 8 puts ``(F_ave - F_g) / (F_i - F_g)`` in the better-than-average case; that
  ratio is > 1 there, so every particle would get w >= w_max (after clipping a
  constant 0.9, no adaptation at all), which contradicts the text. For the worse
  case the printed ``(F_i - F_g) / (F_ave - F_g)`` is >= 1 and also gives w_max.
* eq 9, velocity rule by performance: poor particles (worst third, F > F_bad)
  damp the social term by ``eta ~ U(0, 1)``; good particles (best third, F < F_good)
  damp the cognitive term; the rest use the plain rule.
* eq 10, positive feedback: after the move, a particle that improved takes an
  extra step ``theta = V`` along its velocity if it is still worse than average, or
  ``0.5 * rand * theta`` if it is better than average; the extra step is kept
  only if it improves again (both cost evaluations). The printed first case
  (no improvement) duplicates the second; we read it as "no extra step".
* §4.3, re-initialisation: the worst ``reinit_fraction`` of particles are redrawn
  uniformly each iteration (their personal bests are kept).
* §4.4 and eq 11, escaping local optima: after ``stall`` iterations without a new
  global best, the best point gets a random perturbation of length
  ``delta = beta * rand`` per coordinate (beta 0.2 when the best lies in a good
  region, i.e. improved within the last ``2 * stall`` iterations, else 0.5),
  scaled by a tenth of the box width so that it means the same on every
  problem, and a random crossover (one coordinate copied from a random
  particle); each is kept only if it improves.

IPSO1 (Li 2020) and IPSO2 (Tan 2022), yang2023's baselines, are in ``pso_variants.py``: IPSO1
partly reconstructed, IPSO2 a reconstruction (its own rules were not found; it follows the
evolution-speed / aggregation-degree PSO of Yang et al. 2007, with learning factors of ours).
"""
from __future__ import annotations

import numpy as np

from ...errors import ParameterError
from .engine import Algorithm, State, better, pick, rank


class PSO(Algorithm):
    """Standard PSO with linearly decreasing inertia."""

    name = "pso"
    BATCHABLE = True           # every rule below also takes a leading run axis
    c1 = 1.5
    c2 = 1.5
    w_max = 0.9
    w_min = 0.4
    v_max_frac = 0.2
    walls = "absorb"           # or "clip" (see the module docstring)

    def setup(self, state: State) -> None:
        self.V = np.zeros_like(state.X)
        self.P, self.PF, self.PV = state.X.copy(), state.F.copy(), state.V.copy()
        self.v_max = self.v_max_frac * (state.upper - state.lower)

    def gbest(self) -> np.ndarray:
        """The best personal best, shape ``([R,] 1, d)``."""
        return pick(self.P, rank(self.PF, self.PV)[..., :1])

    def inertia(self, state: State) -> np.ndarray | float:
        return self.w_max - (self.w_max - self.w_min) * state.progress

    def velocity(self, state: State, w) -> np.ndarray:
        n, d = state.X.shape[-2:]
        r = state.rng.random((2, n, d))                       # ([R,] 2, n, d)
        return (w * self.V + self.c1 * r[..., 0, :, :] * (self.P - state.X)
                + self.c2 * r[..., 1, :, :] * (self.gbest() - state.X))

    def remember(self, state: State) -> None:
        win = better(state.F, state.V, self.PF, self.PV)
        self.P[win], self.PF[win], self.PV[win] = state.X[win], state.F[win], state.V[win]

    def move(self, state: State, V: np.ndarray) -> None:
        """Clamp the velocity, move, and absorb at the walls (see the module docstring)."""
        V = np.minimum(np.maximum(V, -self.v_max), self.v_max)
        X = state.X + V
        if self.walls == "absorb":
            self.V = np.where((X < state.lower) | (X > state.upper), 0.0, V)
        elif self.walls == "clip":
            self.V = V
        else:
            raise ParameterError(f"walls must be 'absorb' or 'clip', got {self.walls!r}")
        state.X, state.F, state.V = state.eval_new(X)

    def step(self, state: State) -> None:
        self.move(state, self.velocity(state, self.inertia(state)))
        self.remember(state)


class IPSO(PSO):
    """IPSO (yang2023 §4); states only what it changes from PSO."""

    name = "ipso"
    walls = "clip"             # IPSO as before the wall rule (yang2023 gives none)
    reinit_fraction = 0.1
    stall = 10

    def setup(self, state: State) -> None:
        super().setup(state)
        self.best_seen, self.since_best, self.last_good = state.best_f, 0, 0

    def inertia(self, state: State) -> np.ndarray:
        """Eq 8 (see the module docstring): w_min at the best particle rising linearly to
        w_max at the swarm's average fitness; w_max for average or worse particles."""
        F = np.where(np.isfinite(state.F), state.F, np.nan)
        Fg, Fa = np.nanmin(F), np.nanmean(F)
        span = self.w_max - self.w_min
        with np.errstate(divide="ignore", invalid="ignore"):
            good = self.w_min + span * (F - Fg) / (Fa - Fg)
        w = np.where(F < Fa, good, self.w_max)
        return np.clip(np.nan_to_num(w, nan=self.w_max), self.w_min, self.w_max)[:, None]

    def velocity(self, state: State, w) -> np.ndarray:
        """Eq 9: poor particles damp the social pull, good ones the cognitive pull."""
        n, d = state.X.shape
        r = state.rng.random((2, n, d))
        eta = state.rng.random((n, 1))
        order = rank(state.F, state.V)
        pos = np.empty(n, dtype=np.int64)
        pos[order] = np.arange(n)
        poor = (pos >= 2 * n // 3)[:, None]
        good = (pos < n // 3)[:, None]
        k1 = np.where(good, eta, 1.0)
        k2 = np.where(poor, eta, 1.0)
        return (w * self.V + k1 * self.c1 * r[0] * (self.P - state.X)
                + k2 * self.c2 * r[1] * (self.gbest() - state.X))

    def positive_feedback(self, state: State, F_before: np.ndarray, V_before: np.ndarray) -> None:
        """Eq 10: improved particles take one more (shorter, if already good) step."""
        improved = better(state.F, state.V, F_before, V_before)
        idx = np.nonzero(improved)[0]
        if idx.size == 0:
            return
        Fa = np.mean(state.F[np.isfinite(state.F)]) if np.isfinite(state.F).any() else np.inf
        scale = np.where(state.F[idx] < Fa, 0.5 * state.rng.random(idx.size), 1.0)[:, None]
        Xn, Fn, Vn = state.eval_new(state.X[idx] + scale * self.V[idx])
        state.greedy(Xn, Fn, Vn, idx)

    def reinitialise(self, state: State) -> None:
        """§4.3: redraw the worst particles (velocities reset)."""
        n = len(state.X)
        k = int(round(self.reinit_fraction * n))
        if k == 0:
            return
        worst = rank(state.F, state.V)[-k:]
        Xn, Fn, Vn = state.eval_new(self.initial_population(state, k))
        state.X[worst], state.F[worst], state.V[worst] = Xn, Fn, Vn
        self.V[worst] = 0.0

    def escape(self, state: State) -> None:
        """§4.4, eq 11: perturb and cross over the global best when it stalls."""
        rng = state.rng
        g = rank(self.PF, self.PV)[0]
        beta = 0.2 if state.it - self.last_good <= 2 * self.stall else 0.5
        width = (state.upper - state.lower) / 10
        cand = np.vstack([
            self.P[g] + beta * rng.uniform(-1, 1, state.dim) * width,
            self.P[g].copy(),
        ])
        j = rng.integers(state.dim)
        cand[1, j] = state.X[rng.integers(len(state.X)), j]
        Xc, Fc, Vc = state.eval_new(cand)
        for x, f, v in zip(Xc, Fc, Vc):
            if better(f, v, self.PF[g], self.PV[g]):
                self.P[g], self.PF[g], self.PV[g] = x, f, v

    def step(self, state: State) -> None:
        F0, V0 = state.F.copy(), state.V.copy()
        self.move(state, self.velocity(state, self.inertia(state)))
        self.positive_feedback(state, F0, V0)
        self.remember(state)
        self.reinitialise(state)
        self.remember(state)
        if state.best_f < self.best_seen:
            self.best_seen, self.since_best, self.last_good = state.best_f, 0, state.it
        else:
            self.since_best += 1
        if self.since_best >= self.stall:
            self.escape(state)
            self.since_best = 0
