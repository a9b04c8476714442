"""Random search: the baseline every algorithm must beat at the same budget."""
from __future__ import annotations

from .engine import Algorithm, State


class RandomSearch(Algorithm):
    """Each iteration draws ``pop`` uniform points; the best ever is kept."""

    name = "random"
    min_pop = 1

    def step(self, state: State) -> None:
        X, F, V = state.eval_new(self.initial_population(state, state.pop))
        state.X, state.F, state.V = X, F, V
