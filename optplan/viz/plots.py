"""Static pictures of maps and paths (matplotlib, no screen needed).

Every helper builds a :class:`matplotlib.figure.Figure` directly: pyplot is never
imported and the backend is never switched, so calling a helper inside a notebook or
a GUI program leaves its plotting set-up alone, and saving works on a machine with no
display. Each helper returns its Figure (and writes it when given a file name).
"""
from __future__ import annotations

from pathlib import Path
from typing import Mapping

import numpy as np


def new_figure(figsize: tuple[float, float] = (6.4, 4.8)):
    """A Figure with one Axes, attached to no GUI and registered with no pyplot state;
    returns ``(fig, ax)``."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize)
    return fig, fig.add_subplot()


def draw_world(ax, world) -> None:
    """Draw a GridMap (blocked cells black) or a CircleWorld (grey discs) on ``ax``."""
    from matplotlib.patches import Circle

    xmin, ymin, xmax, ymax = world.bounds
    if world.is_grid:
        ax.imshow(world.occ, origin="lower", cmap="Greys", vmin=0, vmax=1, extent=(xmin, xmax, ymin, ymax),
                  interpolation="nearest")
        if world.width <= 60 and world.height <= 60:
            ax.set_xticks(np.arange(xmin, xmax + 1e-9, world.resolution), minor=True)
            ax.set_yticks(np.arange(ymin, ymax + 1e-9, world.resolution), minor=True)
            ax.grid(which="minor", color="0.85", linewidth=0.4)
    else:
        for (x, y, r), R in zip(world.circles, world.radii):
            if R > r:
                ax.add_patch(Circle((x, y), R, color="0.85", zorder=1))
            ax.add_patch(Circle((x, y), r, color="0.45", zorder=2))
    ax.set_xlim(xmin, xmax)
    ax.set_ylim(ymin, ymax)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def plot_paths(world, paths: Mapping[str, np.ndarray], filename: str | Path | None = None, title: str = "",
               start=None, goal=None):
    """Draw ``world`` with each named ``(N, 2)`` path (metres) overlaid; returns the Figure,
    after writing it as a PNG to ``filename`` when one is given.

    ``start`` and ``goal`` mark the query; by default the first path's ends (give them for
    trajectories, which end where the robot stopped, not at the goal)."""
    fig, ax = new_figure((6.4, 6.4))
    draw_world(ax, world)
    styles = ["-", "--", "-.", ":"]
    for k, (name, path) in enumerate(paths.items()):
        P = np.asarray(path, dtype=float)
        if P.ndim == 2 and len(P):
            ax.plot(P[:, 0], P[:, 1], styles[k % len(styles)], lw=2, marker="o", ms=3, label=name, zorder=5)
    first = next((np.asarray(p) for p in paths.values() if len(p)), None)
    if start is None and first is not None:
        start = first[0]
    if goal is None and first is not None:
        goal = first[-1]
    if start is not None:
        ax.plot(*np.asarray(start, float)[:2], "g^", ms=10, zorder=6, label="start")
    if goal is not None:
        ax.plot(*np.asarray(goal, float)[:2], "r*", ms=13, zorder=6, label="goal")
    ax.legend(loc="best", fontsize=8, framealpha=0.85)
    return finish_figure(fig, filename, title, dpi=120)


def finish_figure(fig, filename: str | Path | None = None, title: str = "", dpi: int = 110):
    """Title the first Axes, lay the figure out and, when ``filename`` is given, write the
    PNG (creating its folder); returns ``fig``."""
    if title:
        fig.axes[0].set_title(title)
    fig.tight_layout()
    if filename is not None:
        filename = Path(filename)
        filename.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(filename, dpi=dpi)
    return fig
