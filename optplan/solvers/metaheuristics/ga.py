"""Real-coded genetic algorithm for continuous problems (``ga``).

Binary tournament selection, simulated binary crossover (SBX, distribution
index ``eta_c``), polynomial mutation (``eta_m``, one gene in ``d`` on average)
and elitism (the best ``elites`` individuals survive unchanged). The path GA
and li2023's IGA on grid chromosomes live in ``optplan.solvers.gridpath.ga_path``;
their adaptive probabilities (li2023 eq 4) and elite schedule (eq 5) are the
functions ``adaptive_probabilities`` and ``elite_count`` there.
"""
from __future__ import annotations

import numpy as np

from .engine import Algorithm, State, better, rank


class GA(Algorithm):
    name = "ga"
    crossover_rate = 0.9
    eta_c = 15.0
    eta_m = 20.0
    elites = 2

    def tournament(self, state: State, k: int) -> np.ndarray:
        a, b = state.rng.integers(0, len(state.X), (2, k))
        return np.where(better(state.F[a], state.V[a], state.F[b], state.V[b]), a, b)

    def sbx(self, state: State, P1: np.ndarray, P2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        rng = state.rng
        u = rng.random(P1.shape)
        beta = np.where(u <= 0.5, (2 * u) ** (1 / (self.eta_c + 1)), (1 / (2 * (1 - u))) ** (1 / (self.eta_c + 1)))
        cross = rng.random((len(P1), 1)) < self.crossover_rate
        c1 = 0.5 * ((1 + beta) * P1 + (1 - beta) * P2)
        c2 = 0.5 * ((1 - beta) * P1 + (1 + beta) * P2)
        return np.where(cross, c1, P1), np.where(cross, c2, P2)

    def mutate(self, state: State, X: np.ndarray) -> np.ndarray:
        rng = state.rng
        n, d = X.shape
        u = rng.random((n, d))
        delta = np.where(u < 0.5, (2 * u) ** (1 / (self.eta_m + 1)) - 1, 1 - (2 * (1 - u)) ** (1 / (self.eta_m + 1)))
        hit = rng.random((n, d)) < 1.0 / d
        return X + hit * delta * (state.upper - state.lower)

    def step(self, state: State) -> None:
        n = len(state.X)
        e = min(self.elites, n)
        keep = rank(state.F, state.V)[:e]
        m = n - e
        half = (m + 1) // 2
        P1, P2 = state.X[self.tournament(state, half)], state.X[self.tournament(state, half)]
        c1, c2 = self.sbx(state, P1, P2)
        kids = self.mutate(state, np.vstack([c1, c2])[:m])
        Xk, Fk, Vk = state.eval_new(kids)
        state.X = np.vstack([state.X[keep], Xk])
        state.F = np.concatenate([state.F[keep], Fk])
        state.V = np.concatenate([state.V[keep], Vk])
