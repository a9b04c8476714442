"""Two grey wolf variants chen2025 compares MSIAR-GWO with: AGWO and RSMGWO (§4.1-4.3,
Tables 4-11). chen2025 names both but gives neither a reference nor an equation; which
published algorithms they are is argued in ``docs/fidelity/chen2025.md`` (issue 44 item 5).
Both share GWO's leaders (the best three points ever seen) and its pull
``X_k = X_l - A |C X_l - X|``, ``A = 2 a r1 - a``, ``C = 2 r2`` (:class:`.gwo.GWO`); each
states only what it changes.

AGWO, the *augmented* grey wolf optimiser: M. H. Qais, H. M. Hasanien, S. Alghuwainem,
"Augmented grey wolf optimizer for grid-connected PMSG-based wind energy conversion systems",
Applied Soft Computing 69 (2018) 504-515. Two changes to GWO:

* the convergence factor falls *randomly* from 2 to about 1, never to 0:
  ``a = 2 - cos(r) t / T`` with one ``r ~ U(0, 1)`` per iteration (so ``a`` ends in
  ``[2 - cos 0, 2 - cos 1] = [1, 1.46]``): ``|A| > 1`` stays possible to the end;
* only the alpha and beta wolves lead: ``X' = (X_1 + X_2) / 2``.

Reconstructed: the article itself was not available here; both rules are as the public
implementations built on it write them (the AGWO-CS code of Sharma, Kapoor and Dhiman 2021,
IEEE ICSCCC, doi:10.1109/ICSCCC51823.2021.9478142, which calls them AGWO's equations, and
other AGWO codes that carry the same ``a`` line). A wolf *replaces* its position (no greedy
selection), as in those codes (``gwo.GWO`` keeps the better of old and new by default;
``greedy=True`` gives AGWO the same rule). The first author published his own MATLAB code on
MathWorks File Exchange ("Augmented GWO algorithm", Mohammed Qais, 2018); it was not read here.

RSMGWO: X. Zhang, X. Wang, H. Chen, D. Wang, Z. Fu, "Improved GWO for large-scale function
optimization and MLP optimization in cancer identification", Neural Computing and
Applications 32 (2020) 1305-1325, doi:10.1007/s00521-019-04483-4. Its abstract names three
strategies, in this order each iteration (the rules are as the authors' public MATLAB code,
dated 2018, writes them; the article's text was not available here):

* **modified evolutionary population dynamics** (EPD, after Saremi, Mirjalili & Lewis 2015):
  the worst quarter of the pack is repositioned before the hunt: with probability 1/4 each
  around alpha, beta or delta, ``L + (ub - L) r b`` or ``L - (L - lb) r b`` (either side
  with probability 1/2, ``r ~ U(0, 1)^d``), else uniformly in the box. *Reconstructed:* the
  code multiplies by a factor ``ba`` it never defines; we take ``b = 1`` (the rule without
  the factor, ``epd_scale``). Checked on the functions as printed (8 seeds, 30 x 500):
  ``b = 1`` gives F8 -12569 (std 0.4), F12 3e-6, F13 3e-5, against chen2025 Table 5's
  RSMGWO -12564 (std 7.6), 1.1e-5, 9.7e-5; ``b = a / 2`` (``epd_scale=0.5,
  epd_shrinks=True``) gives F8 -12125 (std 1170) and F12-F13 within the same decade.
  The repositioned wolves then hunt like the others from where the EPD put them (the code's
  order), so the EPD sets how far their next step reaches;
* **strengthening the hierarchy**: the wolf that holds the alpha rank in the pack rebuilds
  itself from alpha's coordinates in random order, ``X_j = alpha_c`` with ``c`` a random
  dimension; where ``c = j`` (probability 1/d) it takes a DE-like step
  ``X_j + 3.5 a r (X_r1,j - X_r2,j)`` (two random other wolves) or, with probability 1/2,
  beta's GWO pull. The beta-rank wolf takes alpha's pull in about a third of its dimensions
  (``r >= 0.67``) and the mean of alpha's and beta's coordinates at a random dimension in the
  others; the delta-rank wolf the mean of alpha's and beta's pulls in about two thirds
  (``r >= 0.33``) and the mean of the three leaders' coordinates at a random dimension in the
  others; every other wolf hunts as in GWO ("the global-best search way based on random
  dimensions and the original search way of GWO");
* **random opposition learning**: one random wolf other than those three is replaced by the
  opposite of alpha, ``lb + ub - X_alpha``.

Where the code and the description differ we read the description: the code indexes the
alpha-, beta- and delta-rank wolves by their rows *before* it sorts the pack for the EPD (so
after the sort it updates whichever wolves sit there); here they are the pack's three best
wolves, as the strategy's name (strengthening the hierarchy) says. The code updates the wolves
one after the other in place; here every rule reads the pack as it was after the EPD
(vectorised). Positions are replaced (no greedy selection), as in the code.

Why these are chen2025's AGWO and RSMGWO, and how well they match its Tables 4-6, is in
``docs/fidelity/chen2025.md``: RSMGWO's profile matches (it alone reaches F8's optimum, as
chen2025 Table 5 shows), AGWO's matches on F5-F18 but not on the unimodal F1-F4, where
chen2025's AGWO converges about a hundred decades further than these rules do.
"""
from __future__ import annotations

import numpy as np

from .engine import State, rank
from .gwo import GWO


class AGWO(GWO):
    """Augmented GWO (Qais et al. 2018): random ``a`` from 2 to ~1, alpha and beta lead."""

    name = "agwo"
    greedy = False
    a_final = 1.0                # where a would end with cos(r) = 1

    def convergence_factor(self, state: State) -> float:
        """``a = 2 - cos(r) t / T``, one ``r ~ U(0, 1)`` per iteration (written
        ``a_initial - cos(r) (a_initial - a_final) t / T``)."""
        return self.a_initial - np.cos(state.rng.random()) * (self.a_initial - self.a_final) * state.progress

    def combine(self, state: State, pulled: np.ndarray) -> np.ndarray:
        """The mean of the alpha and beta pulls (delta does not lead)."""
        return (pulled[0] + pulled[1]) / 2.0


class RSMGWO(GWO):
    """RSMGWO (Zhang et al. 2020): modified EPD, strengthened hierarchy, random opposition."""

    name = "rsmgwo"
    min_pop = 5                  # three ranked wolves, one opposite wolf, two others to differ
    greedy = False
    epd_fraction = 0.25          # the share of the pack the EPD repositions
    epd_scale = 1.0              # the code's undefined factor b (reconstructed, module docstring)
    epd_shrinks = False          # True: b = epd_scale * a instead
    de_factor = 3.5              # the alpha wolf's DE-like step
    beta_share = 0.67            # beta wolf: alpha's pull where r >= this
    delta_share = 0.33           # delta wolf: alpha's and beta's pulls where r >= this

    def evolutionary_dynamics(self, state: State, order: np.ndarray, a: float) -> np.ndarray:
        """The pack with its worst quarter repositioned around a random leader or anywhere."""
        rng = state.rng
        n, d = state.X.shape
        k = int(round(self.epd_fraction * n))
        X = state.X.copy()
        if k == 0:
            return X
        worst = order[n - k:]
        lo, hi = state.lower, state.upper
        which = np.minimum((rng.random(k) * 4).astype(np.int64), 3)     # alpha, beta, delta, anywhere
        L = self.leaders[np.minimum(which, 2)]
        r = rng.random((k, d)) * (self.epd_scale * a if self.epd_shrinks else self.epd_scale)
        up = rng.random((k, 1)) < 0.5
        near = np.where(up, L + (hi - L) * r, L - (L - lo) * r)
        anywhere = lo + rng.random((k, d)) * (hi - lo)
        X[worst] = np.where((which == 3)[:, None], anywhere, near)
        return X

    def _pull(self, rng, leader: np.ndarray, x: np.ndarray, a: float) -> np.ndarray:
        """GWO's pull of one wolf ``x`` towards one leader, per dimension."""
        d = len(x)
        A = a * (2 * rng.random(d) - 1)
        C = 2 * rng.random(d)
        return leader - A * np.abs(C * leader - x)

    def step(self, state: State) -> None:
        rng = state.rng
        a = self.convergence_factor(state)
        n, d = state.X.shape
        order = rank(state.F, state.V)
        before = state.X
        X = self.evolutionary_dynamics(state, order, a)
        state.X = X                                   # hunt() reads the pack after the EPD
        new = self.combine(state, self.hunt(state, a)).copy()      # every wolf as in GWO
        alpha, beta, delta = self.leaders
        ia, ib, idl = order[:3]
        cols = rng.integers(0, d, size=(3, d))        # the random dimension per coordinate
        # alpha-rank wolf: alpha's coordinates in random order; where the drawn one is its own,
        # a DE-like step or beta's pull
        xa = alpha[cols[0]].copy()
        own = cols[0] == np.arange(d)
        if own.any():
            p, q = rng.choice(np.delete(np.arange(n), ia), 2, replace=False)
            de = X[ia] + self.de_factor * a * rng.random(d) * (X[p] - X[q])
            pull_beta = self._pull(rng, beta, X[ia], a)
            xa[own] = np.where(rng.random(d) <= 0.5, de, pull_beta)[own]
        new[ia] = xa
        # beta-rank wolf: alpha's pull in about a third of the dimensions
        keep = rng.random(d) >= self.beta_share
        new[ib] = np.where(keep, self._pull(rng, alpha, X[ib], a), (alpha[cols[1]] + beta[cols[1]]) / 2)
        # delta-rank wolf: the mean of alpha's and beta's pulls in about two thirds
        keep = rng.random(d) >= self.delta_share
        both = (self._pull(rng, alpha, X[idl], a) + self._pull(rng, beta, X[idl], a)) / 2
        new[idl] = np.where(keep, both, (alpha[cols[2]] + beta[cols[2]] + delta[cols[2]]) / 3)
        # random opposition learning: one random other wolf becomes alpha's opposite
        rest = order[3:]
        new[rest[rng.integers(0, len(rest))]] = state.lower + state.upper - alpha
        Xn, F, V = state.eval_new(new)
        if self.greedy:                               # against the wolves before the EPD
            state.X = before
            state.greedy(Xn, F, V)
        else:
            state.X, state.F, state.V = Xn, F, V
        self.update_leaders(Xn, F, V)
