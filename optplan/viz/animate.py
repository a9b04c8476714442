"""Animations of closed-loop runs (GIF, no screen needed).

The map, paths and markers are drawn once; each frame restores that background and
draws only the moving artists (blitting on the Agg canvas), and the frames are
written with Pillow (a matplotlib dependency). This is about 20x faster than letting
matplotlib's PillowWriter re-render the whole figure for every frame.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np


def animate_run(scenario, result, filename: str | Path, fps: int = 10, max_frames: int = 150,
                title: str | None = None) -> Path:
    """Write a GIF of ``result`` (a SimResult of ``op.simulate``) in ``scenario``.

    Shows the known map, unknown static obstacles (hatched until sensed, then filled
    blue), the global path (red dashed), the driven trajectory (blue),
    the robot footprint and heading, the sensor range and the moving obstacles.

    Args:
        scenario: the world of the run, with its random parts realised
            (``optplan.sim.closed_loop.realized_scenario``).
        result: its SimResult.
        filename: ``.gif`` to write.
        fps: frames per second of the GIF.
        max_frames: the run is subsampled to at most this many frames.

    Returns:
        The path written.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, Rectangle
    from PIL import Image

    from .plots import draw_world
    from ..sim.environment import SimEnvironment

    sc = scenario
    if sc.random_obstacles or sc.random_dynamic or sc.timing_jitter:
        from ..errors import ParameterError

        raise ParameterError("animate_run needs the realised scenario of the run; "
                             "use optplan.sim.closed_loop.realized_scenario(scenario, seed, global_plan)")
    env = SimEnvironment(sc)
    traj = np.asarray(result.trajectory)
    frames = np.unique(np.linspace(0, len(traj) - 1, min(max_frames, len(traj))).astype(int))
    # a Figure on its own Agg canvas (blitting needs one): pyplot and the backend are left alone
    fig = Figure(figsize=(6, 6))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    draw_world(ax, sc.world)
    res = getattr(sc.world, "resolution", 1.0)
    unknown = []
    for lo in env.cell_lo:
        patch = Rectangle(lo, res, res, facecolor="none", edgecolor="tab:blue", hatch="///", lw=0.5, zorder=3)
        ax.add_patch(patch)
        unknown.append(patch)
    for c in env.circles:
        patch = Circle(c[:2], c[2], facecolor="none", edgecolor="tab:blue", hatch="///", lw=0.5, zorder=3)
        ax.add_patch(patch)
        unknown.append(patch)
    gp = np.asarray(result.global_path)
    if gp.ndim == 2 and len(gp):
        ax.plot(gp[:, 0], gp[:, 1], "--", color="tab:red", lw=1.2, zorder=4, label="global path (last)")
    ax.plot(*sc.start[:2], "g^", ms=9, zorder=6)
    ax.plot(*sc.goal, "r*", ms=12, zorder=6)
    driven, = ax.plot([], [], "-", color="tab:blue", lw=1.6, zorder=5, label="driven")
    robot = Circle((0, 0), sc.robot.radius, color="tab:green", zorder=7)
    sensor = Circle((0, 0), sc.sensor_range, fill=False, ls=":", color="tab:green", zorder=2)
    heading, = ax.plot([], [], "-", color="k", lw=1.2, zorder=8)
    ax.add_patch(robot)
    ax.add_patch(sensor)
    movers = [Circle((0, 0), ob.radius, color="tab:pink", alpha=0.9, zorder=6) for ob in sc.dynamic]
    for m in movers:
        ax.add_patch(m)
    ax.legend(loc="upper left", fontsize=7, framealpha=0.8)
    head = title or f"{sc.name or 'scenario'}: {result.global_planner} + {result.local_planner}"
    label = ax.set_title(head)
    filename = Path(filename)
    filename.parent.mkdir(parents=True, exist_ok=True)
    moving = [driven, robot, sensor, heading, label, *movers, *unknown]
    for a in moving:
        a.set_animated(True)
    fig.set_dpi(80)
    fig.canvas.draw()
    background = fig.canvas.copy_from_bbox(fig.bbox)
    images = []
    palette = None
    sensed_cells = np.zeros(len(env.cell_lo), bool)
    sensed_circles = np.zeros(len(env.circles), bool)
    for f in frames:
        t, x, y, th = traj[f, :4]
        for k in range(len(env.cell_lo)):
            if not sensed_cells[k]:
                gap = np.maximum(np.maximum(env.cell_lo[k] - (x, y), (x, y) - env.cell_lo[k] - res), 0)
                sensed_cells[k] = np.hypot(*gap) <= sc.sensor_range
        if len(env.circles):
            sensed_circles |= np.hypot(env.circles[:, 0] - x, env.circles[:, 1] - y) - env.circles[:, 2] <= sc.sensor_range
        for patch, seen in zip(unknown, np.r_[sensed_cells, sensed_circles]):
            if seen:
                patch.set_facecolor("tab:blue")
                patch.set_hatch("")
        driven.set_data(traj[:f + 1, 1], traj[:f + 1, 2])
        robot.center = (x, y)
        sensor.center = (x, y)
        L = max(2.5 * sc.robot.radius, 0.3)
        heading.set_data([x, x + L * np.cos(th)], [y, y + L * np.sin(th)])
        rows = env.movers(t)
        for m, row in zip(movers, rows):
            m.center = (row[0], row[1])
        label.set_text(f"{head}  t={t:.1f} s")
        fig.canvas.restore_region(background)
        for a in moving:
            ax.draw_artist(a)
        frame = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy())
        if palette is None:  # one palette for the whole run: quantising against it is cheap
            palette = frame.quantize(colors=96)
        images.append(frame.quantize(palette=palette, dither=Image.Dither.NONE))
    images[0].save(filename, save_all=True, append_images=images[1:], duration=int(1000 / fps), loop=0)
    return filename


def write_run_gif(scenario, local_planner: str, filename: str | Path, global_planner: str = "astar", seed: int = 0,
                  global_options: dict | None = None, **options) -> str:
    """Simulate one run (``options`` go to ``op.simulate``) and write its animation; returns
    a one-line summary (the example scripts' ``--gif``)."""
    from ..sim.closed_loop import realized_scenario, simulate
    from ..sim.experiments import plan_global
    from ..world.scenario import load_scenario

    sc = load_scenario(scenario)
    gp = plan_global(sc, global_planner, None, seed, global_options)
    res = simulate(sc, global_planner=global_planner, local_planner=local_planner, seed=seed, global_plan=gp, **options)
    animate_run(realized_scenario(sc, seed, gp), res, filename)
    return f"wrote {filename}: {sc.name}, {global_planner} + {local_planner}, seed {seed}: {res.message}"
