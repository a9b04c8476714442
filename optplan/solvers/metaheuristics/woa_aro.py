"""Whale optimisation (Mirjalili & Lewis 2016) and artificial rabbits optimisation
(Wang et al. 2022), the baselines of chen2025 Tables 4-11.

WOA: ``a`` falls from 2 to 0; with ``p < 0.5`` a whale encircles the best
(``|A| < 1``) or a random whale (``|A| >= 1``): ``X_ref - A |C X_ref - X|``; with
``p >= 0.5`` it spirals towards the best: ``|X_best - X| e^(b l) cos(2 pi l) + X_best``.
Where this standard version differs from Mirjalili & Lewis: a whale keeps its old
position when the new one is worse (``greedy = True``, as mealpy's OriginalWOA does);
with plain replacement the pod loses its good points and ended far behind mealpy's
WOA on the shifted sphere (``benchmarks/engine_speed.py``). ``greedy=False`` is the
original replacement rule.

ARO: energy ``E = 4 (1 - t/T) ln(1/r)``. ``E > 1``: detour foraging towards a
random other rabbit, ``X_j + R (X_i - X_j) + round(0.5 (0.05 + r1)) n1``;
``E <= 1``: random hiding in a burrow near itself,
``X_i + R (r4 b - X_i)`` with ``b = X_i + H g X_i``, ``H = (T - t + 1)/T * r``, ``g`` a
one-hot random dimension. ``R = S c`` is the running operator. Greedy selection.
"""
from __future__ import annotations

import numpy as np

from .engine import Algorithm, State
from .operators import running_operator


class WOA(Algorithm):
    """Whale optimisation with greedy selection (see the module docstring)."""

    name = "woa"
    spiral_b = 1.0
    greedy = True

    def step(self, state: State) -> None:
        rng = state.rng
        n, d = state.X.shape
        a = 2 * (1 - state.progress)
        A = 2 * a * rng.random((n, 1)) - a
        C = 2 * rng.random((n, 1))
        p = rng.random((n, 1))
        l = rng.uniform(-1, 1, (n, 1))
        best = state.best_x
        ref = np.where(np.abs(A) < 1, best, state.X[rng.integers(0, n, n)])
        encircle = ref - A * np.abs(C * ref - state.X)
        spiral = np.abs(best - state.X) * np.exp(self.spiral_b * l) * np.cos(2 * np.pi * l) + best
        X, F, V = state.eval_new(np.where(p < 0.5, encircle, spiral))
        if self.greedy:
            state.greedy(X, F, V)
        else:
            state.X, state.F, state.V = X, F, V


class ARO(Algorithm):
    name = "aro"

    def step(self, state: State) -> None:
        rng = state.rng
        n, d = state.X.shape
        X = state.X
        E = 4 * (1 - state.progress) * np.log(1 / np.maximum(rng.random((n, 1)), 1e-300))
        R = running_operator(rng, state.it, state.horizon, n, d)
        # detour foraging: towards a random other rabbit
        j = (np.arange(n) + rng.integers(1, n, n)) % n
        detour = X[j] + R * (X - X[j]) + np.round(0.5 * (0.05 + rng.random((n, 1)))) * rng.normal(size=(n, d))
        # random hiding around a burrow of its own
        H = (state.horizon - state.it + 1) / state.horizon * rng.random((n, 1))
        g = np.zeros((n, d))
        g[np.arange(n), rng.integers(0, d, n)] = 1.0
        burrow = X + H * g * X
        hide = X + R * (rng.random((n, 1)) * burrow - X)
        Xn, Fn, Vn = state.eval_new(np.where(E > 1, detour, hide))
        state.greedy(Xn, Fn, Vn)
