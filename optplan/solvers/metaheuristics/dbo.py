"""Dung beetle optimiser (Xue & Shen 2022), a baseline of chen2025.

The population splits into rollers (20 %), brood balls (20 %), small beetles
(25 %) and thieves (the rest). Rollers move away from the worst point with a
light-dependent step (``X + alpha k X_prev_gap + b |X - X_worst|``) or, with
probability ``1 - p_dance``, dance: ``X + tan(theta) |X - X_prev|``. Brood balls
are placed inside a breeding region around the current best, small beetles
forage in a region around the best ever, thieves steal near the best ever.

As required by the issue, the breeding and foraging regions are symmetric
boxes around their centre whose half-width shrinks with ``R = 1 - t / T``:
``[c - R (ub - lb) / 2, c + R (ub - lb) / 2]`` clipped to the bounds (the
original multiplies the centre's coordinates by ``1 -/+ R``, which makes the
region depend on where the origin is).

``origin_pull=True`` runs the original's rules instead, for reproducing results
on functions whose optimum is the origin (chen2025 Tables 4-6): the regions
``[c (1 - R), c (1 + R)]`` clipped to the bounds, a brood ball clipped to its
region as the original clips (lower bound first, so a region that the product
turned upside down for negative coordinates still gives a point), and the
rollers deflected by ``k x(t-1)``, the previous position itself. Both shrink
towards 0 as ``R`` does, which pulls the search to the origin.
"""
from __future__ import annotations

import numpy as np

from .engine import Algorithm, State, rank


class DBO(Algorithm):
    name = "dbo"
    min_pop = 5
    share_roll = 0.2
    share_brood = 0.2
    share_small = 0.25
    k_deflect = 0.1
    b_light = 0.3
    p_dance = 0.9
    s_steal = 0.5
    origin_pull = False

    def setup(self, state: State) -> None:
        self.X_prev = state.X.copy()

    def region(self, state: State, centre: np.ndarray, R: float) -> tuple[np.ndarray, np.ndarray]:
        if self.origin_pull:   # the original's: the centre's coordinates scaled by 1 -/+ R
            return np.maximum(centre * (1 - R), state.lower), np.minimum(centre * (1 + R), state.upper)
        half = R * (state.upper - state.lower) / 2
        return np.maximum(centre - half, state.lower), np.minimum(centre + half, state.upper)

    @staticmethod
    def clip(x: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        """``x`` inside ``[lo, hi]``, the lower bound applied first (the original's order: with
        ``lo > hi`` the upper one wins)."""
        return np.where(x > hi, hi, np.where(x < lo, lo, x))

    def step(self, state: State) -> None:
        rng = state.rng
        X = state.X
        n, d = X.shape
        order = rank(state.F, state.V)
        n_roll = max(1, int(round(self.share_roll * n)))
        n_brood = max(1, int(round(self.share_brood * n)))
        n_small = max(1, int(round(self.share_small * n)))
        roll = order[:n_roll]
        brood = order[n_roll:n_roll + n_brood]
        small = order[n_roll + n_brood:n_roll + n_brood + n_small]
        thief = order[n_roll + n_brood + n_small:]
        best_now, worst = X[order[0]], X[order[-1]]
        best_ever = state.best_x
        R = 1 - state.progress
        new = X.copy()
        # rolling (light decides the direction) or dancing
        k = len(roll)
        dance = rng.random(k) > self.p_dance
        alpha = np.where(rng.random((k, 1)) > 0.5, 1.0, -1.0)
        # the deflection: the step since the last iteration (origin-free) or the original's previous position
        deflect = self.X_prev[roll] if self.origin_pull else X[roll] - self.X_prev[roll]
        rolling = X[roll] + alpha * self.k_deflect * deflect + self.b_light * np.abs(X[roll] - worst)
        theta = rng.uniform(0, np.pi, (k, 1))
        theta = np.where(np.isclose(theta, np.pi / 2), 0.0, theta)
        dancing = X[roll] + np.tan(theta) * np.abs(X[roll] - self.X_prev[roll])
        new[roll] = np.where(dance[:, None], dancing, rolling)
        # brood balls inside the breeding region around the current best
        lo, hi = self.region(state, best_now, R)
        b1, b2 = rng.random((2, len(brood), d))
        new[brood] = self.clip(best_now + b1 * (X[brood] - lo) + b2 * (X[brood] - hi), lo, hi)
        # small beetles forage in the region around the best ever
        lo2, hi2 = self.region(state, best_ever, R)
        c1 = rng.normal(size=(len(small), 1))
        c2 = rng.random((len(small), d))
        new[small] = X[small] + c1 * (X[small] - lo2) + c2 * (X[small] - hi2)
        # thieves steal near the best ever
        g = rng.normal(size=(len(thief), d))
        new[thief] = best_ever + self.s_steal * g * (np.abs(X[thief] - best_now) + np.abs(X[thief] - best_ever))
        self.X_prev = X.copy()
        Xn, Fn, Vn = state.eval_new(new)
        state.greedy(Xn, Fn, Vn)
