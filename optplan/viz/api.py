"""The plotting API: ``op.plot_map``, ``op.plot_paths``, ``op.plot_run``.

Each draws on the matplotlib ``Axes`` it is given (``ax=``) and returns it, so a picture
composes with the user's own figure. Without ``ax`` it makes one through pyplot
(``plt.subplots()``): in Jupyter the figure then shows as any other does, and
``plt.savefig`` / ``plt.show`` work as usual. (The command line's pictures do not go
through pyplot: :mod:`optplan.viz.plots` draws them on figures of their own.)

    ax = op.plot_map(grid)
    op.plot_paths(grid, {"astar": a.path, "msiar-gwo": b.path}, ax=ax, highlight="astar")
    op.plot_run(sim_result, scenario, ax=other_ax)
"""
from __future__ import annotations

from typing import Mapping

import numpy as np

from ..errors import ParameterError
from .plots import draw_paths, draw_world


def _axes(ax, figsize: tuple[float, float] = (6.4, 6.4)):
    """``ax``, or a new one from pyplot."""
    if ax is not None:
        if not hasattr(ax, "plot") or not hasattr(ax, "add_patch"):
            raise ParameterError(f"ax must be a matplotlib Axes, got {type(ax).__name__}")
        return ax
    import matplotlib.pyplot as plt

    return plt.subplots(figsize=figsize)[1]


def plot_map(world, ax=None, title: str = ""):
    """Draw a GridMap (blocked cells black) or a CircleWorld; returns the Axes."""
    ax = _axes(ax)
    draw_world(ax, world)
    if title:
        ax.set_title(title)
    return ax


def plot_paths(world, paths: Mapping[str, np.ndarray] | np.ndarray, ax=None, title: str = "", start=None,
               goal=None, highlight: str | None = None, legend_loc: str = "best"):
    """Draw ``world`` and each named ``(N, 2)`` path (a single array is named ``path``);
    ``highlight`` names one drawn as a wide band (e.g. the exact optimum). Returns the Axes."""
    if not isinstance(paths, Mapping):
        paths = {"path": np.asarray(paths, float)}
    ax = _axes(ax)
    draw_paths(ax, world, paths, start, goal, highlight, legend_loc=legend_loc)
    if title:
        ax.set_title(title)
    return ax


def plot_run(result, scenario=None, ax=None, title: str | None = None):
    """Draw a closed-loop run (an ``op.simulate`` result): the map of ``scenario`` (a
    Scenario or a shipped name; its unknown obstacles filled blue, so pass the realised
    scenario, ``optplan.sim.closed_loop.realized_scenario``, to see the random ones), the
    last global path (red dashes), the driven trajectory coloured by time, start and goal,
    and the outcome in the title. Returns the Axes."""
    from matplotlib.patches import Circle, Rectangle

    from .animate import outcome_text

    traj = np.asarray(getattr(result, "trajectory", None), float)
    if traj.ndim != 2 or traj.shape[1] < 3:
        raise ParameterError("plot_run needs an op.simulate result (its trajectory rows [t, x, y, ...])")
    ax = _axes(ax)
    if scenario is not None:
        from ..world.scenario import load_scenario

        sc = load_scenario(scenario)
        draw_world(ax, sc.world)
        res = getattr(sc.world, "resolution", 1.0)
        origin = np.asarray(getattr(sc.world, "origin", (0.0, 0.0)), float)
        for cell in np.asarray(sc.unknown_cells).reshape(-1, 2):
            ax.add_patch(Rectangle(origin + cell * res, res, res, color="tab:blue", zorder=3))
        for x, y, r in np.asarray(sc.unknown_circles).reshape(-1, 3):
            ax.add_patch(Circle((x, y), r, color="tab:blue", zorder=3))
        ax.plot(*sc.goal[:2], "r*", ms=13, zorder=6, label="goal")
    else:
        ax.set_aspect("equal")
    gp = np.asarray(getattr(result, "global_path", np.zeros((0, 2))), float)
    if gp.ndim == 2 and len(gp):
        ax.plot(gp[:, 0], gp[:, 1], "--", color="tab:red", lw=1.2, zorder=4, label="global path")
    pts = ax.scatter(traj[:, 1], traj[:, 2], c=traj[:, 0], cmap="viridis", s=4, zorder=5, label="driven")
    ax.figure.colorbar(pts, ax=ax, fraction=0.046, pad=0.04, label="t [s]")
    ax.plot(traj[0, 1], traj[0, 2], "g^", ms=10, zorder=6, label="start")
    ax.legend(loc="best", fontsize=7, framealpha=0.85)
    head = title or f"{getattr(result, 'global_planner', '')} + {getattr(result, 'local_planner', '')}"
    ax.set_title(f"{head}: {outcome_text(result)} after {float(getattr(result, 'time_s', 0.0)):.1f} s")
    return ax
