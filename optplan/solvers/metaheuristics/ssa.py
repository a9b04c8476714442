"""Sparrow search (Xue & Shen 2020) and MISSA (hou2024 §2.2).

SSA: the population, sorted by fitness, splits into producers (the best
``producers`` share), scroungers (the rest) and, drawn at random each
iteration, scouts (``scouts`` share) that react to danger. With alarm ``R2``
and safety threshold ``ST`` (hou2024 eq 4-6):

* producers: ``X exp(-i / (alpha T))`` when ``R2 < ST``, else ``X + Q L``;
* scroungers: the worse half ``Q exp((X_worst - X) / i^2)``, the others
  ``X_p + |X - X_p| A+ L``. Read literally (``A`` a 1 x d row of random signs, ``A+`` its
  pseudo-inverse, ``L`` a row of ones) the step is one number, the signed mean of
  ``|X - X_p|``, added to every coordinate (``scrounger_step="pseudo-inverse"``).
  Where the standard version differs: by default (``"per-dimension"``, as mealpy's
  OriginalSSA) the step is ``|X - X_p|`` times one normal draw, so each coordinate
  keeps its own distance to the producer. With the literal step every scrounger
  moves along the diagonal, and SSA stalled on shifted 30-d functions far behind
  mealpy's SSA (``benchmarks/engine_speed.py``). MISSA replaces this move (eq 17)
  and is not affected;
* scouts: ``X_best + beta |X - X_best|`` if not the best, else
  ``X + k |X - X_worst| / (f_i - f_w + eps)``.
Each sparrow keeps the better of its old and new position. Defaults follow
hou2024 Table 1 (ST = 0.8, producers 0.3, scouts 0.2).

One iteration evaluates the flock once (hou2024 §2.2.5, steps 3-6: producers,
scroungers and scouts move, then "compute the fitness value for each sparrow").
As in Xue & Shen's reference implementation, a scout's eq-6 position is computed
from its position and fitness at the start of the iteration and replaces its
producer/scrounger move, so every sparrow has one candidate per iteration. Two
simplifications of that implementation remain: the scroungers follow the new
position of the top-ranked producer (the reference code first evaluates the
producers and follows the best of them), and the best/worst used by the scouts
are those of the start of the iteration.

MISSA changes (hou2024 §2.2):

* eq 9, logistic-tent chaotic initialisation;
* eq 10-12, elite opposition for the producers with dynamic bounds
  ``[min_j, max_j]`` of the current population: ``k (da + db) - X`` with
  ``k ~ U(0, 1)``, out-of-range values redrawn uniformly in ``[da, db]``;
* eq 13-14, producers move by ``w sin(r1) |r2 X_best - X|`` (``R2 < ST``) or
  ``w cos(r1) |r2 X_best - X|`` with ``w = tanh(2 (1 - sin(pi t / T)))``,
  ``r1 ~ U(0, 2 pi)``, ``r2 ~ U(0, 2)``;
* eq 15-17, the better scroungers jump around the best producer,
  ``X_p + X_p * Levy(d)`` (Mantegna, scale 0.01);
* eq 18, Cauchy-t perturbation of the best:
  ``X_best (1 + l1 Cauchy) + l2 t(T)``, ``l1 = 1 - t^2/T^2``, ``l2 = t^2/T^2``
  (the t draw uses ``T`` degrees of freedom), kept only if better.
"""
from __future__ import annotations

import numpy as np

from ...errors import ParameterError
from .engine import Algorithm, State, better, rank
from .operators import levy, logistic_tent


class SSA(Algorithm):
    """Basic sparrow search."""

    name = "ssa"
    safety_threshold = 0.8
    producers = 0.3
    scouts = 0.2
    scrounger_step = "per-dimension"     # or "pseudo-inverse": hou2024 eq 5 read literally

    def roles(self, state: State):
        n = len(state.X)
        order = rank(state.F, state.V)
        n_prod = max(1, int(round(self.producers * n)))
        return order, n_prod

    def producer_move(self, state: State, Xp: np.ndarray, ranks: np.ndarray) -> np.ndarray:
        """hou2024 eq 4."""
        rng = state.rng
        k = len(Xp)
        alarm = rng.random()
        if alarm < self.safety_threshold:
            alpha = rng.random((k, 1)) + 1e-12
            return Xp * np.exp(-(ranks[:, None] + 1) / (alpha * state.horizon))
        return Xp + rng.normal(size=(k, 1))

    def scrounger_move(self, state: State, Xs: np.ndarray, ranks: np.ndarray, best_producer: np.ndarray,
                       worst: np.ndarray) -> np.ndarray:
        """hou2024 eq 5."""
        rng = state.rng
        n = len(state.X)
        k, d = Xs.shape
        hungry = (ranks + 1) > n / 2
        far = rng.normal(size=(k, 1)) * np.exp((worst - Xs) / ((ranks[:, None] + 1.0) ** 2))
        if self.scrounger_step == "per-dimension":
            near = best_producer + np.abs(Xs - best_producer) * rng.normal(size=(k, 1))
        elif self.scrounger_step == "pseudo-inverse":
            signs = rng.choice([-1.0, 1.0], size=(k, d))
            near = best_producer + (np.abs(Xs - best_producer) * signs).mean(axis=1, keepdims=True)
        else:
            raise ParameterError(f"scrounger_step must be 'per-dimension' or 'pseudo-inverse', "
                                 f"got {self.scrounger_step!r}")
        return np.where(hungry[:, None], far, near)

    def scout_move(self, state: State, idx: np.ndarray, best: np.ndarray, worst: np.ndarray,
                   f_best: float, f_worst: float) -> np.ndarray:
        """hou2024 eq 6."""
        rng = state.rng
        X, F = state.X[idx], state.F[idx]
        k, d = X.shape
        is_best = F <= f_best
        towards = best + rng.normal(size=(k, 1)) * np.abs(X - best)
        denom = np.where(np.isfinite(F - f_worst), F - f_worst, 0.0) + 1e-50
        away = X + rng.uniform(-1, 1, (k, 1)) * np.abs(X - worst) / denom[:, None]
        return np.where(is_best[:, None], away, towards)

    def move_producers_and_scroungers(self, state: State, order: np.ndarray, n_prod: int) -> np.ndarray:
        X = state.X
        n = len(X)
        new = X.copy()
        prod, scr = order[:n_prod], order[n_prod:]
        new[prod] = self.producer_move(state, X[prod], np.arange(n_prod))
        best_prod = new[prod][0]
        worst = X[order[-1]]
        new[scr] = self.scrounger_move(state, X[scr], np.arange(n_prod, n), best_prod, worst)
        return new

    def step(self, state: State) -> None:
        order, n_prod = self.roles(state)
        new = self.move_producers_and_scroungers(state, order, n_prod)
        # scouts: a random share of the flock; their danger move replaces their role move
        n = len(state.X)
        k = max(1, int(round(self.scouts * n)))
        idx = state.rng.choice(n, size=k, replace=False)
        best, worst = state.X[order[0]], state.X[order[-1]]
        new[idx] = self.scout_move(state, idx, best, worst, state.F[order[0]], state.F[order[-1]])
        Xn, Fn, Vn = state.eval_new(new)
        state.greedy(Xn, Fn, Vn)


class MISSA(SSA):
    """MISSA (hou2024 §2.2); states only what it changes from SSA."""

    name = "missa"
    chaos_r = 3.9

    def initial_population(self, state: State, n: int) -> np.ndarray:
        """Eq 9: logistic-tent chaotic initialisation."""
        return state.lower + logistic_tent(state.rng, (n, state.dim), self.chaos_r) * (state.upper - state.lower)

    def elite_opposition(self, state: State, prod: np.ndarray) -> None:
        """Eq 10-12 on the producers (greedy)."""
        rng = state.rng
        da, db = state.X.min(axis=0), state.X.max(axis=0)
        k = rng.random((len(prod), 1))
        opp = k * (da + db) - state.X[prod]
        out = (opp < da) | (opp > db)
        opp = np.where(out, da + rng.random(opp.shape) * (db - da), opp)
        Xo, Fo, Vo = state.eval_new(opp)
        state.greedy(Xo, Fo, Vo, prod)

    def producer_move(self, state: State, Xp: np.ndarray, ranks: np.ndarray) -> np.ndarray:
        """Eq 13-14: sine-cosine steps towards the best, weight w(t)."""
        rng = state.rng
        k, d = Xp.shape
        w = np.tanh(2 * (1 - np.sin(np.pi * state.progress)))
        r1 = rng.uniform(0, 2 * np.pi, (k, d))
        r2 = rng.uniform(0, 2, (k, d))
        gap = np.abs(r2 * state.best_x - Xp)
        trig = np.sin(r1) if rng.random() < self.safety_threshold else np.cos(r1)
        return Xp + w * trig * gap

    def scrounger_move(self, state: State, Xs, ranks, best_producer, worst) -> np.ndarray:
        """Eq 17: Levy jumps around the best producer for the better half."""
        rng = state.rng
        n = len(state.X)
        k, d = Xs.shape
        hungry = (ranks + 1) > n / 2
        out = np.empty_like(Xs)
        # draw each half's random numbers only for the sparrows that use them
        h = hungry.nonzero()[0]
        out[h] = rng.normal(size=(h.size, 1)) * np.exp((worst - Xs[h]) / ((ranks[h, None] + 1.0) ** 2))
        fed = (~hungry).nonzero()[0]
        out[fed] = best_producer + best_producer * levy(rng, (fed.size, d), 1.5, 0.01)
        return out

    def cauchy_t(self, state: State) -> None:
        """Eq 18: perturb the best sparrow, keep it if better."""
        rng = state.rng
        t, T = state.it, state.horizon
        l1, l2 = 1 - (t / T) ** 2, (t / T) ** 2
        b = rank(state.F, state.V)[0]
        cand = state.X[b] * (1 + l1 * rng.standard_cauchy(state.dim)) + l2 * rng.standard_t(T, state.dim)
        Xc, Fc, Vc = state.eval_new(cand[None, :])
        state.greedy(Xc, Fc, Vc, [b])

    def step(self, state: State) -> None:
        order, n_prod = self.roles(state)
        self.elite_opposition(state, order[:n_prod])
        super().step(state)
        self.cauchy_t(state)
