"""Animations of closed-loop runs (GIF, no screen needed).

The map, paths and markers are drawn once; each frame restores that background and
draws only the moving artists (blitting on the Agg canvas), and the frames are
written with Pillow (a matplotlib dependency). This is about 20x faster than letting
matplotlib's PillowWriter re-render the whole figure for every frame.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..world.files import written_whole


VIDEO_SUFFIXES = (".gif", ".mp4")


def ffmpeg_program() -> str | None:
    """The ffmpeg that MP4 output runs (matplotlib's ``animation.ffmpeg_path``), or ``None``."""
    import shutil

    import matplotlib

    return shutil.which(str(matplotlib.rcParams["animation.ffmpeg_path"]))


def check_video_target(filename: str | Path) -> None:
    """Refuse, before any work, an animation file that cannot be written: a suffix other than
    ``.gif``/``.mp4``, or ``.mp4`` without ffmpeg."""
    from ..errors import OptplanError

    suffix = Path(filename).suffix.lower()
    if suffix not in VIDEO_SUFFIXES:
        raise OptplanError(f"{filename}: an animation is written as .gif or .mp4, not {suffix or 'no suffix'!r}")
    if suffix == ".mp4" and ffmpeg_program() is None:
        raise OptplanError(f"{filename}: MP4 is encoded by ffmpeg, which is not on PATH (or matplotlib's "
                           "animation.ffmpeg_path); install it, or write a .gif")


def animate_run(scenario, result, filename: str | Path, fps: int = 10, max_frames: int = 150,
                title: str | None = None) -> Path:
    """Write a GIF (or, with ffmpeg, an MP4) of ``result`` (a SimResult of ``op.simulate``) in ``scenario``.

    Shows the known map, unknown static obstacles (hatched until sensed, then filled
    blue), the global path (red dashed), the driven trajectory (blue),
    the robot footprint and heading, the sensor range and the moving obstacles.

    Args:
        scenario: the world of the run, with its random parts realised
            (``optplan.sim.closed_loop.realized_scenario``).
        result: its SimResult.
        filename: ``.gif`` or ``.mp4`` to write (MP4 needs ffmpeg; checked first).
        fps: frames per second.
        max_frames: the run is subsampled to at most this many frames.

    Returns:
        The path written.
    """
    from PIL import Image

    from .plots import blank_figure, draw_world
    from ..sim.environment import SimEnvironment

    check_video_target(filename)
    mp4 = Path(filename).suffix.lower() == ".mp4"
    sc = scenario
    if sc.random_obstacles or sc.random_dynamic or sc.timing_jitter:
        from ..errors import ParameterError

        raise ParameterError("animate_run needs the realised scenario of the run; "
                             "use optplan.sim.closed_loop.realized_scenario(scenario, seed, global_plan)")
    env = SimEnvironment(sc)
    traj = np.asarray(result.trajectory)
    frames = np.unique(np.linspace(0, len(traj) - 1, min(max_frames, len(traj))).astype(int))
    # a Figure on its own Agg canvas (blitting needs one): pyplot and the backend are left alone
    fig = blank_figure((6, 6))  # first, so that a matplotlib that cannot start says why
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.patches import Circle, Rectangle

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
    _draw_route(ax, sc, result)
    driven, = ax.plot([], [], "-", color="tab:blue", lw=1.6, zorder=5)
    robot = Circle((0, 0), sc.robot.radius, color="tab:green", zorder=7)
    sensor = Circle((0, 0), sc.sensor_range, fill=False, ls=":", color="tab:green", zorder=2)
    heading, = ax.plot([], [], "-", color="k", lw=1.2, zorder=8)
    ax.add_patch(robot)
    ax.add_patch(sensor)
    movers = [Circle((0, 0), ob.radius, color="tab:pink", alpha=0.9, zorder=6) for ob in sc.dynamic]
    for m in movers:
        ax.add_patch(m)
    run_legend(ax, sc, below=True)
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
        last = f == frames[-1]
        label.set_text(f"{head}  t={t:.1f} s" + (f"  {outcome_text(result)}" if last else ""))
        if last:  # the last frame says how the run ended, in the colour of the outcome
            label.set_color(OUTCOME_COLOURS.get(result.status, "black"))
        fig.canvas.restore_region(background)
        for a in moving:
            ax.draw_artist(a)
        rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
        if mp4:
            images.append(rgb)
            continue
        frame = Image.fromarray(rgb)
        if palette is None:  # one palette for the whole run: quantising against it is cheap
            palette = frame.quantize(colors=96)
        images.append(frame.quantize(palette=palette, dither=Image.Dither.NONE))
    # hold the last frame for two seconds, so the outcome can be read
    if mp4:
        _write_mp4(filename, images + [images[-1]] * (2 * fps), fps)
        return filename
    durations = [int(1000 / fps)] * (len(images) - 1) + [2000]
    with written_whole(filename, "animation") as tmp:
        images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:], duration=durations, loop=0)
    return filename


def _write_mp4(filename: Path, frames: list[np.ndarray], fps: int) -> None:
    """Encode RGB frames ``(h, w, 3)`` as H.264 MP4 by piping them to ffmpeg (even sizes padded)."""
    import subprocess

    from ..errors import OptplanError

    h, w = frames[0].shape[:2]
    with written_whole(filename, "animation") as tmp:
        cmd = [ffmpeg_program(), "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24",
               "-s", f"{w}x{h}", "-r", str(int(fps)), "-i", "-", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
               "-pix_fmt", "yuv420p", "-f", "mp4", str(tmp)]
        run = subprocess.run(cmd, input=b"".join(np.ascontiguousarray(f, np.uint8).tobytes() for f in frames),
                             capture_output=True)
        if run.returncode != 0:
            raise OptplanError(f"ffmpeg could not write {filename}: "
                               f"{run.stderr.decode(errors='replace').strip()[-300:] or 'exit ' + str(run.returncode)}")


OUTCOME_COLOURS = {"reached": "tab:green", "collision": "tab:red", "stuck": "tab:orange", "timeout": "tab:orange"}
OUTCOME_WORDS = {"reached": "REACHED", "collision": "COLLIDED", "stuck": "STUCK", "timeout": "TIMED OUT"}


def outcome_text(result) -> str:
    """How a run ended, in one word or two (``REACHED``, ``COLLIDED``, ``STUCK``, ``TIMED OUT``)
    and its collision count when it had any."""
    word = OUTCOME_WORDS.get(result.status, (result.status or "ended").upper())
    if result.collisions and result.status != "collision":
        word += f", {result.collisions} collision step(s)"
    return word


def _draw_route(ax, sc, result) -> None:
    gp = np.asarray(result.global_path)
    if gp.ndim == 2 and len(gp):
        ax.plot(gp[:, 0], gp[:, 1], "--", color="tab:red", lw=1.2, zorder=4)
    ax.plot(*sc.start[:2], "g^", ms=9, zorder=6)
    ax.plot(*sc.goal, "r*", ms=12, zorder=6)  # the scenario's goal, wherever the robot stopped


def run_legend(ax, sc, below: bool = False) -> None:
    """One legend entry per kind of element a closed-loop picture shows (drawn as proxies,
    so the entries exist even for elements that appear only in later frames); ``below`` puts
    it under the map, where it covers no obstacle (the still picture; an animation's frames
    keep it in the corner of their fixed canvas)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [Patch(facecolor="black", label="known obstacle"),
               Patch(facecolor="none", edgecolor="tab:blue", hatch="///", label="unknown obstacle (unsensed)"),
               Patch(facecolor="tab:blue", label="unknown obstacle (sensed)"),
               Line2D([], [], ls="--", color="tab:red", label="global path (last)"),
               Line2D([], [], color="tab:blue", lw=1.6, label="driven"),
               Line2D([], [], marker="o", ls="", color="tab:green", ms=8, label="robot"),
               Line2D([], [], ls=":", color="tab:green", label="sensor range"),
               Line2D([], [], marker="^", ls="", color="g", label="start"),
               Line2D([], [], marker="*", ls="", color="r", ms=10, label="goal")]
    if sc.dynamic:
        handles.append(Line2D([], [], marker="o", ls="", color="tab:pink", ms=8, label="moving obstacle"))
    if below:
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3, fontsize=6,
                  framealpha=0.8)
    else:
        ax.legend(handles=handles, loc="upper left", fontsize=6, framealpha=0.8)


def plot_run(scenario, result, filename: str | Path | None = None, title: str | None = None, dpi: int = 110):
    """A static picture of a closed-loop run: the map, the obstacles the robot did not know
    (filled), the last global path, the driven trajectory coloured by time, the robot and the
    movers where they were at the end, the steps that collided (red crosses), and the outcome
    in the title. Returns the Figure (written as a PNG when ``filename`` is given).

    ``scenario`` is the realised scenario of the run, as for :func:`animate_run`.
    """
    from matplotlib.patches import Circle, Rectangle

    from .plots import draw_world, finish_figure, new_figure, save_figure
    from ..sim.environment import SimEnvironment

    sc = scenario
    env = SimEnvironment(sc)
    traj = np.asarray(result.trajectory, float)
    fig, ax = new_figure((6.4, 6.4))
    draw_world(ax, sc.world)
    res = getattr(sc.world, "resolution", 1.0)
    for lo in env.cell_lo:
        ax.add_patch(Rectangle(lo, res, res, facecolor="tab:blue", edgecolor="tab:blue", zorder=3))
    for c in env.circles:
        ax.add_patch(Circle(c[:2], c[2], facecolor="tab:blue", zorder=3))
    _draw_route(ax, sc, result)
    if len(traj):
        pts = ax.scatter(traj[:, 1], traj[:, 2], c=traj[:, 0], cmap="viridis", s=4, zorder=5)
        fig.colorbar(pts, ax=ax, fraction=0.046, pad=0.04, label="t [s]")
        t_end, x, y = traj[-1, :3]
        ax.add_patch(Circle((x, y), sc.robot.radius, color="tab:green", zorder=7))
        for row in env.movers(t_end):
            ax.add_patch(Circle((row[0], row[1]), row[4], color="tab:pink", alpha=0.9, zorder=6))
        hits = _collision_steps(env, sc, traj)
        if len(hits):
            ax.plot(traj[hits, 1], traj[hits, 2], "x", color="red", ms=7, zorder=8)
    run_legend(ax, sc, below=True)
    head = title or f"{sc.name or 'scenario'}: {result.global_planner} + {result.local_planner}"
    fig = finish_figure(fig, None, f"{head}: {outcome_text(result)} after {result.time_s:.1f} s", dpi=dpi)
    ax.title.set_color(OUTCOME_COLOURS.get(result.status, "black"))
    if filename is not None:
        save_figure(fig, filename, dpi)
    return fig


def _collision_steps(env, sc, traj: np.ndarray) -> np.ndarray:
    """Indices of the trajectory rows where the robot's disc overlaps a mover (static
    overlaps are drawn by the map itself)."""
    if not sc.dynamic:
        return np.zeros(0, dtype=np.int64)
    hit = []
    for i, (t, x, y) in enumerate(traj[:, :3]):  # pictures only: one row per recorded step
        rows = env.movers(t)
        if len(rows) and np.any(np.hypot(rows[:, 0] - x, rows[:, 1] - y) < rows[:, 4] + sc.robot.radius):
            hit.append(i)
    return np.asarray(hit, dtype=np.int64)


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
