"""Convergence curves: median best value per iteration with the inter-quartile band."""
from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

import numpy as np


def plot_convergence(histories: Mapping[str, Sequence[np.ndarray]], filename: str | Path | None = None,
                     title: str = "", log: bool = True, f_opt: float | None = None,
                     finals: Mapping[str, Sequence[float]] | None = None, reference: tuple[float, str] | None = None,
                     ylabel: str | None = None):
    """Draw each algorithm's median curve (runs padded with their last value); returns the
    Figure, after writing it as a PNG to ``filename`` when one is given.

    ``finals`` are each algorithm's values after the search (e.g. the path length after
    pruning and refinement), drawn as a marker one step past the curve, so two runs that
    share a search but differ in post-processing do not draw the same curve; ``reference``
    is ``(value, label)`` of a horizontal line (e.g. the exact optimum).
    """
    from .plots import finish_figure, new_figure

    fig, ax = new_figure((6.4, 4.2))
    draw_convergence(ax, histories, log, f_opt, finals, reference, ylabel)
    return finish_figure(fig, filename, title)


def post_processing_x(n_iterations: int) -> float:
    """Where a convergence plot draws the values after post-processing: a little past the
    search's last iteration."""
    return n_iterations + max(1, n_iterations // 40)


def draw_convergence(ax, histories: Mapping[str, Sequence[np.ndarray]], log: bool = True, f_opt: float | None = None,
                     finals: Mapping[str, Sequence[float]] | None = None, reference: tuple[float, str] | None = None,
                     ylabel: str | None = None, colours: Mapping[str, str] | None = None) -> None:
    """The drawing of :func:`plot_convergence` on a given Axes (``colours`` by name)."""
    finals, colours = finals or {}, colours or {}
    n_max = max((len(h) for runs in histories.values() for h in runs), default=1)
    styles = ["-", "--", "-.", ":"]
    for k, (name, runs) in enumerate(histories.items()):
        n = max(len(h) for h in runs)
        H = np.array([np.concatenate([h, np.full(n - len(h), h[-1])]) for h in runs], dtype=float)
        if f_opt is not None:
            H = H - f_opt  # error to the known optimum
        if log:
            H = np.maximum(H, 1e-300)
        med = np.median(H, axis=0)
        lo, hi = np.percentile(H, [25, 75], axis=0)
        it = np.arange(n)
        line, = ax.plot(it, med, styles[k % len(styles)], label=name, lw=1.5, color=colours.get(name))
        ax.fill_between(it, lo, hi, alpha=0.2, color=line.get_color())
        end = np.asarray(finals.get(name, ()), dtype=float)
        end = end[np.isfinite(end)]
        if len(end):
            x_end = post_processing_x(n_max)
            ax.plot([n - 1, x_end], [med[-1], np.median(end)], ":", color=line.get_color(), lw=1.0)
            ax.plot([x_end], [np.median(end)], "D", color=line.get_color(), ms=5)
    if reference is not None:
        ax.axhline(reference[0], color="0.3", ls="--", lw=1.0, label=reference[1])
    if finals:
        ax.plot([], [], "D", color="0.4", ms=5, label="after post-processing")
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("iteration")
    ax.set_ylabel(ylabel or ("best value" + (" - optimum" if f_opt is not None else "")))
    ax.legend(fontsize=7)
