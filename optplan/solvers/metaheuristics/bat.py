"""Bat algorithm (Yang 2010) and IBA (yuan2021 §2.2).

BA (yuan2021 eq 1-5): frequency ``f = f_min + (f_max - f_min) beta``, velocity
``V = V + (X_best - X) f``, position ``X + V``; with probability ``1 - r_i`` a bat
instead walks locally around the best, ``X_best + eps * <A>`` (``eps ~ U(-1, 1)``,
``<A>`` the mean loudness). A new position is accepted if it is better and
``rand < A_i``; then loudness shrinks (``A_i = alpha A_i``) and the pulse rate grows
(``r_i = r0 (1 - exp(-gamma t))``). The velocity pulls towards the best as
yuan2021 eq 2 and eq 7 write it, ``(x_* - x_i) f_i``; Yang's 2010 original prints
the opposite sign ``(x_i - x_*) f_i``.

IBA changes:

* eq 6-7, logarithmically decreasing inertia on the velocity:
  ``w = w_max - a (w_max - w_min) log_T(t) + b sigma randn`` (``sigma`` the spread of
  ``w`` around its mean; we use the fixed ``sigma`` parameter);
* eq 9, Cauchy disturbance in the local walk:
  ``X_best + n * Cauchy * rand + eps <A>`` with ``n = c (T - t) / T``.
"""
from __future__ import annotations

import numpy as np

from .engine import Algorithm, State


class BA(Algorithm):
    """Basic bat algorithm."""

    name = "ba"
    f_min = 0.0
    f_max = 2.0
    loudness0 = 0.9
    pulse0 = 0.5
    alpha = 0.9
    gamma = 0.9
    walk_scale = 0.01   # local walk step as a share of the box width

    def setup(self, state: State) -> None:
        n = len(state.X)
        self.Vel = np.zeros_like(state.X)
        self.A = np.full(n, self.loudness0)
        self.r = np.full(n, self.pulse0)

    def inertia(self, state: State) -> float:
        return 1.0

    def local_walk(self, state: State, k: int) -> np.ndarray:
        eps = state.rng.uniform(-1, 1, (k, state.dim))
        return state.best_x + eps * self.A.mean() * self.walk_scale * (state.upper - state.lower)

    def step(self, state: State) -> None:
        rng = state.rng
        n, d = state.X.shape
        freq = self.f_min + (self.f_max - self.f_min) * rng.random((n, 1))
        self.Vel = self.inertia(state) * self.Vel + (state.best_x - state.X) * freq   # eq 2 / eq 7
        cand = state.X + self.Vel
        walk = rng.random(n) > self.r
        if walk.any():
            cand[walk] = self.local_walk(state, int(walk.sum()))
        Xn, Fn, Vn = state.eval_new(cand)
        accept = ((Fn <= state.F) & (Vn <= state.V)) & (rng.random(n) < self.A)
        state.X[accept], state.F[accept], state.V[accept] = Xn[accept], Fn[accept], Vn[accept]
        self.A[accept] *= self.alpha
        self.r[accept] = self.pulse0 * (1 - np.exp(-self.gamma * state.it))


class IBA(BA):
    """IBA (yuan2021 §2.2); states only what it changes from BA."""

    name = "iba"
    w_max = 0.9
    w_min = 0.4
    log_factor = 1.0      # eq 6 "a"
    noise_factor = 0.1    # eq 6 "b"
    sigma = 0.1           # eq 6 "sigma"
    cauchy_factor = 0.1   # eq 9 "c", as a share of the box width

    def inertia(self, state: State) -> float:
        """Eq 6: logarithmic decrease with a small normal disturbance."""
        T = state.horizon
        t = max(state.it, 1)
        return (self.w_max - self.log_factor * (self.w_max - self.w_min) * np.log(t) / np.log(max(T, 2))
                + self.noise_factor * self.sigma * state.rng.normal())

    def local_walk(self, state: State, k: int) -> np.ndarray:
        """Eq 9: Cauchy disturbance of the best, fading with time."""
        rng = state.rng
        n_t = self.cauchy_factor * (1 - state.progress) * (state.upper - state.lower)
        jump = n_t * rng.standard_cauchy((k, state.dim)) * rng.random((k, state.dim))
        return super().local_walk(state, k) + jump
