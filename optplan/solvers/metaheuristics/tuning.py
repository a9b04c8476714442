"""Offline Q-learning of MSIAR-GWO's convergence-factor exponents (chen2025 §3.1, eq 17).

The agent's state is the pair ``(lambda1, lambda2)`` on the integer grid
``[1, 10]^2``; its nine actions move each exponent by -1, 0 or +1. A state is
scored by running MSIAR-GWO on Step (F6) and Penalized1 (F12) — the two
functions the paper names — and adding each function's best value and standard
deviation over a few runs, normalised by the first state's score. Rewards follow
§3.1: +1 when the action changed the state and the score improved, +1 when the
state stayed and its score is the best seen so far, -1 otherwise. The table is
updated by ``Q(s, a) += tau (r + gamma max_a' Q(s', a') - Q(s, a))`` (eq 17) with
epsilon-greedy exploration. The best-scored state is returned.

We score the shifted versions of both functions (see
``optplan.formulations.functions``): on the origin-centred ones every setting
looks perfect, which would teach the agent nothing.

    python -m optplan.solvers.metaheuristics.tuning      # reruns it and prints the choice
"""
from __future__ import annotations

import itertools

import numpy as np

from ...rng import as_generator

ACTIONS = list(itertools.product((-1, 0, 1), repeat=2))


def score_state(l1: int, l2: int, runs: int = 2, iters: int = 200, pop: int = 30, dim: int = 30) -> np.ndarray:
    """Best value and std on shifted F6 and F12 (summed per function), shape (2,)."""
    from ...formulations.functions import get_function
    from . import optimize

    out = []
    for name in ("F6", "F12"):
        F = get_function(name, shifted=True, dim=dim)
        vals = np.array([optimize(F, F.bounds, algorithm="msiar-gwo", pop=pop, iters=iters, seed=s,
                                  lambda1=float(l1), lambda2=float(l2)).f for s in range(runs)])
        out.append(vals.min() + vals.std())
    return np.array(out)


def tune_lambdas(steps: int = 200, seed=0, runs: int = 2, iters: int = 200, tau: float = 0.1, gamma: float = 0.9,
                 epsilon: float = 0.3, verbose: bool = False) -> tuple[int, int, dict]:
    """Run the Q-learning search; returns ``(lambda1, lambda2, scores_by_state)``."""
    rng = as_generator(seed)
    Q = np.zeros((10, 10, len(ACTIONS)))
    cache: dict[tuple[int, int], float] = {}
    base = None

    def score(s):
        nonlocal base
        if s not in cache:
            raw = score_state(*s, runs=runs, iters=iters)
            base = raw if base is None else base
            cache[s] = float((raw / np.maximum(base, 1e-300)).sum())
        return cache[s]

    state = tuple(int(v) for v in rng.integers(1, 11, 2))
    best_seen = score(state)
    for k in range(steps):
        i, j = state[0] - 1, state[1] - 1
        a = int(rng.integers(len(ACTIONS))) if rng.random() < epsilon else int(np.argmax(Q[i, j]))
        nxt = (int(np.clip(state[0] + ACTIONS[a][0], 1, 10)), int(np.clip(state[1] + ACTIONS[a][1], 1, 10)))
        s_now, s_next = score(state), score(nxt)
        if nxt != state:
            r = 1.0 if s_next < s_now else -1.0
        else:
            r = 1.0 if s_next <= best_seen else -1.0
        best_seen = min(best_seen, s_next)
        Q[i, j, a] += tau * (r + gamma * Q[nxt[0] - 1, nxt[1] - 1].max() - Q[i, j, a])
        state = nxt
        if verbose:
            print(f"step {k + 1}: lambda = {state}, score {s_next:.4f}, reward {r:+.0f}")
    l1, l2 = min(cache, key=cache.get)
    return l1, l2, cache


if __name__ == "__main__":  # pragma: no cover
    l1, l2, scores = tune_lambdas(verbose=True)
    print(f"chosen lambda1 = {l1}, lambda2 = {l2} after scoring {len(scores)} states")
