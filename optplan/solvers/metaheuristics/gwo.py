"""Grey wolf optimiser (Mirjalili 2014) and MSIAR-GWO (chen2025 §3).

GWO, canonical: the three leaders alpha, beta, delta are the best three points
found so far; every wolf moves to the mean of three points, each pulled towards
one leader: ``X_k = X_l - A * |C * X_l - X|`` with ``A = 2 a r1 - a``,
``C = 2 r2`` and ``a`` falling linearly from 2 to 0 (chen2025 eq 1-7, as in
Mirjalili 2014). Where this standard version differs from that description: a wolf
keeps its old position when the new one is worse (``greedy = True``, as mealpy's
OriginalGWO does). Without it, wolves that overshoot are lost and the pack drifts;
at 15,030 evaluations on the shifted sphere and Rastrigin it finished behind
mealpy's GWO (``benchmarks/engine_speed.py``). ``greedy=False`` is Mirjalili's
replacement rule.

MSIAR-GWO changes, in the order of chen2025 §3 (the extracted text lost minus
signs, fractions and exponents; each reconstruction is written out):

* eq 16, nonlinear convergence factor:
  ``a = a_final + (a_initial - a_final) * (1 - (t / T)^lambda1)^lambda2``,
  with ``lambda1, lambda2`` chosen offline by the Q-learning of §3.1
  (:func:`tune_lambdas`, rerunnable; its result is stored as the default).
* eq 20-23, dynamic leader weights plus guided perturbation:
  ``X' = (W_a X1 + W_b X2 + W_d X3) / (W_a + W_b + W_d)
          + l1 * (mu1 * rho1 * (X_r - X) + mu2 * (1 - rho1) * (X_alpha - X))``,
  ``rho1 = 1 - t / T``, ``l1 = 0.3``, ``X_r`` a random wolf better than ``X``,
  ``W_k = (f_a + f_b + f_d) / f_k`` (eq 21-23). Eq 21-23 need positive fitness; we
  apply them to ``f_k - f_a + |f_a|`` (identical when ``f_a >= 0``).
* eq 24-28, when ``a < 1``: ARO detour foraging as a second candidate ``Y``, with
  the energy ``E = 4 (1 - t / T) ln(1 / r)`` (ARO eq 15):
  ``E > 1``: ``Y = X_r + Levy(d) * R * (X - X_r) + round(0.5 (0.05 + r1)) n2``;
  ``E <= 1``: ``Y = X_alpha + l2 * R * B * (X - B * X_alpha) + round(0.5 (0.05 + r2)) n3``,
  ``R = S * c`` (ARO's running operator: ``S = (e - e^(((t-1)/T)^2)) sin(2 pi r)``,
  ``c`` a random 0/1 mask of ``ceil(r d)`` dimensions), Levy by Mantegna with
  scale 0.005 and eta = 1.5 (eq 25-26), ``B`` the standard normal density at a
  standard normal draw (eq 27), ``l2 = 10``; the better of ``X'`` and ``Y`` is kept
  (eq 28).
* eq 29-31, stochastic-centroid opposition: ``n ~ U{1..N}``, ``M`` the mean of the
  best ``n`` wolves, the worst 10 % get ``2 M - X`` when that is better.
"""
from __future__ import annotations

import numpy as np

from .engine import Algorithm, State, better, pick, rank
from .operators import levy, running_operator


class GWO(Algorithm):
    """Canonical grey wolf optimiser."""

    name = "gwo"
    BATCHABLE = True           # every rule below also takes a leading run axis
    min_pop = 3
    a_initial = 2.0
    a_final = 0.0
    greedy = True

    # -- leaders: the best three points ever seen
    def setup(self, state: State) -> None:
        order = rank(state.F, state.V)[..., :3]
        self.leaders = pick(state.X, order).copy()
        self.leader_f = pick(state.F, order).copy()
        self.leader_v = pick(state.V, order).copy()

    def update_leaders(self, X, F, V) -> None:
        if F.ndim == 2:
            # a batched run: every run takes the rule its single run takes (the two rules
            # break ties differently, so a run must not follow its neighbours' choice)
            if not (V.any() or self.leader_v.any()):
                self._top_three_by_value(X, F)
                return
            ranked = V.any(axis=-1) | self.leader_v.any(axis=-1)
            if not ranked.all():
                self._top_three_by_value(X, F, np.flatnonzero(~ranked))
            self._top_three_ranked(X, F, V, np.flatnonzero(ranked))
            return
        if not (V.any() or self.leader_v.any()):
            # unconstrained: only the new top three can displace a leader
            if F.min() >= self.leader_f[2]:
                return
            top = np.argpartition(F, 2)[:3] if len(F) > 3 else np.arange(len(F))
            allF = np.concatenate((self.leader_f, F[top]))
            order = np.argsort(allF, kind="stable")[:3]   # = rank() when nothing is violated
            self.leaders, self.leader_f = np.concatenate((self.leaders, X[top]))[order], allF[order]
            return
        allX = np.vstack([self.leaders, X])
        allF = np.concatenate([self.leader_f, F])
        allV = np.concatenate([self.leader_v, V])
        order = rank(allF, allV)[:3]
        self.leaders, self.leader_f, self.leader_v = allX[order], allF[order], allV[order]

    def _top_three_by_value(self, X, F, runs: np.ndarray | None = None) -> None:
        """The unconstrained single-run rule above for the batched ``runs`` (all when
        ``None``): each run's new top three (``argpartition`` picks the same rows of a
        row as of the run alone) against its leaders, in a stable sort."""
        # ndarray methods and plain fancy indexing (pick): the numpy functions' Python
        # wrappers (take_along_axis above all) cost more than the work at these sizes
        Fr, lf = (F, self.leader_f) if runs is None else (F[runs], self.leader_f[runs])
        move = np.minimum.reduce(Fr, axis=-1) < lf[:, 2]
        if not move.all():
            if not move.any():
                return
            runs = np.flatnonzero(move) if runs is None else runs[move]
            Fr, lf = F[runs], self.leader_f[runs]
        rows = np.arange(len(F)) if runs is None else runs
        n = Fr.shape[-1]
        top = Fr.argpartition(2, axis=-1)[:, :3] if n > 3 else np.broadcast_to(np.arange(n), Fr.shape)
        allF = np.concatenate([lf, pick(Fr, top)], axis=-1)
        order = allF.argsort(axis=-1, kind="stable")[:, :3]
        allX = np.concatenate([self.leaders if runs is None else self.leaders[runs], X[rows[:, None], top]], axis=-2)
        if runs is None:
            self.leaders, self.leader_f = pick(allX, order), pick(allF, order)
        else:
            self.leaders[runs], self.leader_f[runs] = pick(allX, order), pick(allF, order)

    def _top_three_ranked(self, X, F, V, runs: np.ndarray) -> None:
        """The constrained single-run rule for the batched ``runs``: the best three of
        leaders and wolves under the feasibility rule."""
        allX = np.concatenate([self.leaders[runs], X[runs]], axis=-2)
        allF = np.concatenate([self.leader_f[runs], F[runs]], axis=-1)
        allV = np.concatenate([self.leader_v[runs], V[runs]], axis=-1)
        order = rank(allF, allV)[..., :3]
        self.leaders[runs], self.leader_f[runs], self.leader_v[runs] = (
            pick(allX, order), pick(allF, order), pick(allV, order))

    def convergence_factor(self, state: State) -> float:
        """Linear from ``a_initial`` to ``a_final`` (Mirjalili 2014)."""
        return self.a_initial + (self.a_final - self.a_initial) * state.progress

    def hunt(self, state: State, a: float) -> np.ndarray:
        """The three leader-pulled points ``X1, X2, X3``, shape ``([R,] 3, n, d)`` (eq 3-7),
        in a work array that the next call overwrites."""
        X = state.X
        runs, (n, d) = X.shape[:-2], X.shape[-2:]
        r = state.rng.random((2, 3, n, d))                   # ([R,] 2, 3, n, d)
        # each half of the draws is copied into a contiguous work array first: arithmetic
        # reading a batched run's strided views of the draws runs at half speed or less
        A = state.work("gwo.A", runs + (3, n, d))
        np.copyto(A, r[..., 0, :, :, :])
        A *= 2 * a
        A -= a                                                # A = 2 a r1 - a
        L = self.leaders[..., :, None, :]                     # ([R,] 3, 1, d)
        gap = state.work("gwo.pulled", runs + (3, n, d))
        np.copyto(gap, r[..., 1, :, :, :])
        # C L = (2 r2) L computed as r2 (2 L): both round the exact 2 r2 L once, one pass fewer
        gap *= 2 * L
        gap -= X[..., None, :, :]
        np.abs(gap, out=gap)
        gap *= A
        return np.subtract(L, gap, out=gap)                   # L - A |C L - X|

    def combine(self, state: State, pulled: np.ndarray) -> np.ndarray:
        """The mean of the three leader-pulled points (eq 7)."""
        total = np.add.reduce(pulled, axis=-3)     # what pulled.mean does, without its Python wrapper
        total /= 3.0
        return total

    def step(self, state: State) -> None:
        a = self.convergence_factor(state)
        X, F, V = state.eval_new(self.combine(state, self.hunt(state, a)))
        if self.greedy:
            state.greedy(X, F, V)
        else:
            state.X, state.F, state.V = X, F, V
        self.update_leaders(X, F, V)


# chosen by tuning.tune_lambdas() with its defaults (seed 0; shifted Step and Penalized1):
# (1, 2), i.e. a = 2 (1 - t/T)^2. Rerun with `python -m optplan.solvers.metaheuristics.tuning`.
LAMBDA1_DEFAULT = 1.0
LAMBDA2_DEFAULT = 2.0


class MSIARGWO(GWO):
    """MSIAR-GWO (chen2025 §3); states only what it changes from GWO."""

    name = "msiar-gwo"
    lambda1 = LAMBDA1_DEFAULT
    lambda2 = LAMBDA2_DEFAULT
    l1 = 0.3
    l2 = 10.0
    levy_scale = 0.005
    levy_beta = 1.5
    worst_fraction = 0.1

    def convergence_factor(self, state: State) -> float:
        """Eq 16 (reconstructed, see module docstring)."""
        t = state.progress
        return self.a_final + (self.a_initial - self.a_final) * (1 - t ** self.lambda1) ** self.lambda2

    def leader_weights(self) -> np.ndarray:
        """Eq 21-23 on positivised leader fitness; normalised to sum to 1."""
        f = self.leader_f
        g = f - f[0] + abs(f[0]) + 1e-300
        w = g.sum() / g
        return w / w.sum()

    def random_better(self, state: State) -> np.ndarray:
        """For every wolf, a random wolf with better fitness (alpha when none is)."""
        n = len(state.X)
        order = rank(state.F, state.V)
        pos = np.empty(n, dtype=np.int64)
        pos[order] = np.arange(n)
        # pick uniformly among the pos[i] wolves ranked above wolf i
        pick = np.floor(state.rng.random(n) * pos).astype(np.int64)
        Xr = state.X[order[pick]]
        Xr[pos == 0] = self.leaders[0]
        return Xr

    def combine(self, state: State, pulled: np.ndarray) -> np.ndarray:
        """Eq 20: weighted leaders plus the guided perturbation."""
        w = self.leader_weights()
        rho1 = 1 - state.progress
        n, d = state.X.shape
        mu = state.rng.random((2, n, 1))
        self._Xr = self.random_better(state)
        guide = mu[0] * rho1 * (self._Xr - state.X) + mu[1] * (1 - rho1) * (self.leaders[0] - state.X)
        return np.tensordot(w, pulled, axes=1) + self.l1 * guide

    def detour(self, state: State, X: np.ndarray) -> np.ndarray:
        """Eq 24-27: Levy detour (E > 1) or Brownian detour around alpha (E <= 1)."""
        rng = state.rng
        n, d = X.shape
        E = 4 * (1 - state.progress) * np.log(1 / np.maximum(rng.random((n, 1)), 1e-300))
        R = running_operator(rng, state.it, state.horizon, n, d)
        jitter = np.round(0.5 * (0.05 + rng.random((n, 1)))) * rng.normal(size=(n, d))
        Xr = self._Xr
        far = Xr + levy(rng, (n, d), self.levy_beta, self.levy_scale) * R * (X - Xr) + jitter
        B = np.exp(-rng.normal(size=(n, d)) ** 2 / 2) / np.sqrt(2 * np.pi)
        alpha = self.leaders[0]
        near = alpha + self.l2 * R * B * (X - B * alpha) + jitter
        return np.where(E > 1, far, near)

    def centroid_opposition(self, state: State) -> None:
        """Eq 29-31: the worst 10 % are mirrored through the centroid of a random elite."""
        n = len(state.X)
        order = rank(state.F, state.V)
        k = max(1, int(round(self.worst_fraction * n)))
        top = int(state.rng.integers(1, n + 1))
        M = state.X[order[:top]].mean(axis=0)
        worst = order[-k:]
        Xo, Fo, Vo = state.eval_new(2 * M - state.X[worst])
        state.greedy(Xo, Fo, Vo, worst)

    def step(self, state: State) -> None:
        a = self.convergence_factor(state)
        old_X = state.X
        X, F, V = state.eval_new(self.combine(state, self.hunt(state, a)))
        if a < 1:
            Y, FY, VY = state.eval_new(self.detour(state, old_X))
            take = better(FY, VY, F, V)       # eq 28: keep the better candidate
            X[take], F[take], V[take] = Y[take], FY[take], VY[take]
        state.X, state.F, state.V = X, F, V
        self.centroid_opposition(state)
        self.update_leaders(state.X, state.F, state.V)


class IGWO(GWO):
    """Improved GWO of Nadimi-Shahraki et al. 2021: dimension learning-based hunting.

    Each wolf gets two candidates: the GWO move ``X_gwo`` and ``X_dlh``, built
    dimension by dimension from a random neighbour (a wolf within the radius
    ``|X - X_gwo|``) and a random wolf: ``X_dlh_j = X_j + r (X_nbr_j - X_rand_j)``.
    The better candidate replaces the wolf when it improves on it.
    """

    name = "igwo"

    def step(self, state: State) -> None:
        rng = state.rng
        a = self.convergence_factor(state)
        X = state.X
        n, d = X.shape
        X_gwo = state.prepare(self.combine(state, self.hunt(state, a)))
        radius = np.linalg.norm(X - X_gwo, axis=1)
        dist = np.linalg.norm(X[:, None, :] - X[None, :, :], axis=2)
        near = dist <= radius[:, None]
        # one random neighbour per wolf and per dimension (the wolf itself is always a neighbour)
        keys = rng.random((n, d, n)) * near[:, None, :]
        nbr = np.argmax(keys, axis=2)
        rnd = rng.integers(0, n, size=(n, d))
        X_dlh = X + rng.random((n, d)) * (X[nbr, np.arange(d)] - X[rnd, np.arange(d)])
        Fg, Vg = state.evaluate(X_gwo)
        X_dlh, Fd, Vd = state.eval_new(X_dlh)
        take = better(Fd, Vd, Fg, Vg)
        Xc = np.where(take[:, None], X_dlh, X_gwo)
        Fc, Vc = np.where(take, Fd, Fg), np.where(take, Vd, Vg)
        state.greedy(Xc, Fc, Vc)
        self.update_leaders(state.X, state.F, state.V)
