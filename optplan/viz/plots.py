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

from ..errors import ParameterError
from ..world.files import written_whole


def _figure_class():
    """matplotlib's Figure. A matplotlib that cannot start (it refuses an ``MPLBACKEND`` it does
    not know when it is imported) is a ParameterError that says how to fix it, not an internal
    error."""
    try:
        from matplotlib.figure import Figure
    except ValueError as exc:
        if "backend" not in str(exc):
            raise
        raise ParameterError(f"matplotlib cannot start: {exc}. optplan draws without a screen and uses no "
                             "backend: unset MPLBACKEND, or set it to one matplotlib knows, such as 'agg'") from None
    return Figure


def blank_figure(figsize: tuple[float, float] = (6.4, 4.8)):
    """A Figure attached to no GUI and registered with no pyplot state."""
    return _figure_class()(figsize=figsize)


def figure_format(filename: str | Path) -> str:
    """The picture format of ``filename`` (its suffix, lower case; ``""`` for none, which
    writes matplotlib's default, PNG), refused with a ParameterError when matplotlib cannot
    write it."""
    suffix = Path(filename).suffix.lower().lstrip(".")
    _figure_class()  # matplotlib starts, or says why it cannot
    from matplotlib.backend_bases import FigureCanvasBase

    known = FigureCanvasBase.get_supported_filetypes()
    if suffix and suffix not in known:
        raise ParameterError(f"{filename}: matplotlib writes no .{suffix} pictures; use one of "
                             f"{', '.join('.' + k for k in sorted(known))}")
    return suffix


def save_figure(fig, filename: str | Path, dpi: int = 110) -> Path:
    """Write ``fig`` to ``filename`` (format from its suffix, checked; its folder created)."""
    filename = Path(filename)
    figure_format(filename)
    filename.parent.mkdir(parents=True, exist_ok=True)
    with written_whole(filename, "picture") as tmp:
        fig.savefig(tmp, dpi=dpi, format=figure_format(filename) or None)
    return filename


def new_figure(figsize: tuple[float, float] = (6.4, 4.8)):
    """:func:`blank_figure` with one Axes; returns ``(fig, ax)``."""
    fig = blank_figure(figsize)
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
               start=None, goal=None, highlight: str | None = None):
    """Draw ``world`` with each named ``(N, 2)`` path (metres) overlaid; returns the Figure,
    after writing it as a PNG to ``filename`` when one is given.

    ``start`` and ``goal`` mark the query; by default the first path's ends (give them for
    trajectories, which end where the robot stopped, not at the goal). ``highlight`` names
    one path (e.g. the exact optimum) drawn as a wide band above the others, so paths that
    follow it closely cannot hide it."""
    fig, ax = new_figure((8.0, 6.4))
    draw_paths(ax, world, paths, start, goal, highlight, legend_loc="outside")
    return finish_figure(fig, filename, title, dpi=120)


def draw_paths(ax, world, paths: Mapping[str, np.ndarray], start=None, goal=None, highlight: str | None = None,
               legend_loc: str = "best", colours: Mapping[str, str] | None = None) -> None:
    """The drawing of :func:`plot_paths` on a given Axes (``colours`` by path name, e.g. to
    match another panel)."""
    colours = colours or {}
    draw_world(ax, world)
    styles = ["-", "--", "-.", ":"]
    k = 0
    for name, path in paths.items():
        P = np.asarray(path, dtype=float)
        if not (P.ndim == 2 and len(P)):
            continue
        if name == highlight:  # a translucent band on top: visible, and what it covers shows through
            ax.plot(P[:, 0], P[:, 1], "-", color="gold", lw=7, alpha=0.55, solid_capstyle="round", label=name,
                    zorder=7)
            ax.plot(P[:, 0], P[:, 1], "o", color="darkgoldenrod", ms=6, zorder=7)
            continue
        ax.plot(P[:, 0], P[:, 1], styles[k % len(styles)], lw=1.6, marker="o", ms=2.5, label=name, zorder=5,
                color=colours.get(name))
        k += 1
    first = next((np.asarray(p) for p in paths.values() if len(p)), None)
    if start is None and first is not None:
        start = first[0]
    if goal is None and first is not None:
        goal = first[-1]
    if start is not None:
        ax.plot(*np.asarray(start, float)[:2], "g^", ms=10, zorder=6, label="start")
    if goal is not None:
        ax.plot(*np.asarray(goal, float)[:2], "r*", ms=13, zorder=6, label="goal")
    if legend_loc == "outside":   # beside the map, where it covers no obstacle
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7, framealpha=0.85, borderaxespad=0.0)
    else:
        ax.legend(loc=legend_loc, fontsize=7, framealpha=0.85)


def finish_figure(fig, filename: str | Path | None = None, title: str = "", dpi: int = 110):
    """Title the first Axes, lay the figure out and, when ``filename`` is given, write the
    PNG (creating its folder); returns ``fig``."""
    if title:
        fig.axes[0].set_title(title)
    fig.tight_layout()
    if filename is not None:
        save_figure(fig, filename, dpi)
    return fig
