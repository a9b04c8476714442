"""Convergence curves: median best value per iteration with the inter-quartile band."""
from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

import numpy as np


def plot_convergence(histories: Mapping[str, Sequence[np.ndarray]], filename: str | Path | None = None,
                     title: str = "", log: bool = True, f_opt: float | None = None):
    """Draw each algorithm's median curve (runs padded with their last value); returns the
    Figure, after writing it as a PNG to ``filename`` when one is given."""
    from .plots import finish_figure, new_figure

    fig, ax = new_figure((6.4, 4.2))
    for name, runs in histories.items():
        n = max(len(h) for h in runs)
        H = np.array([np.concatenate([h, np.full(n - len(h), h[-1])]) for h in runs], dtype=float)
        if f_opt is not None:
            H = H - f_opt  # error to the known optimum
        if log:
            H = np.maximum(H, 1e-300)
        med = np.median(H, axis=0)
        lo, hi = np.percentile(H, [25, 75], axis=0)
        it = np.arange(n)
        ax.plot(it, med, label=name, lw=1.5)
        ax.fill_between(it, lo, hi, alpha=0.2)
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("iteration")
    ax.set_ylabel("best value" + (" - optimum" if f_opt is not None else ""))
    ax.legend(fontsize=7)
    return finish_figure(fig, filename, title)
