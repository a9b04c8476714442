"""Pictures of closed-loop runs: a legend naming every kind of element, the outcome in the
last GIF frame and in the static picture, and the goal drawn where it is."""
from __future__ import annotations

import numpy as np
from PIL import Image

import optplan as op
from optplan.sim.closed_loop import realized_scenario, simulate
from optplan.sim.experiments import plan_global
from optplan.viz.animate import animate_run, outcome_text, plot_run, run_legend
from optplan.viz.plots import new_figure, plot_paths


def _run(name="li2023_exp1", time_limit=None):
    sc = op.load_scenario(name)
    if time_limit is not None:
        from dataclasses import replace

        sc = replace(sc, time_limit=time_limit)
    gp = plan_global(sc, "astar", None, 0)
    res = simulate(sc, global_planner="astar", local_planner="dwa", seed=0, global_plan=gp)
    return realized_scenario(sc, 0, gp), res


def test_static_picture_and_gif_say_how_the_run_ended(tmp_path):
    sc, res = _run(time_limit=3.0)  # stopped early: not reached
    assert res.status in ("timeout", "stuck") and "REACHED" not in outcome_text(res)
    fig = plot_run(sc, res, tmp_path / "run.png")
    title = fig.axes[0].get_title()
    assert outcome_text(res) in title and (tmp_path / "run.png").stat().st_size > 0
    gif = animate_run(sc, res, tmp_path / "run.gif", max_frames=6)
    with Image.open(gif) as im:
        durations = []
        for k in range(im.n_frames):
            im.seek(k)
            durations.append(im.info["duration"])
    assert durations[-1] == 2000 and all(d < 2000 for d in durations[:-1])  # the outcome frame is held


def test_the_legend_names_every_kind_of_element():
    sc, _ = _run(time_limit=1.0)
    fig, ax = new_figure()
    run_legend(ax, sc)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for needed in ("known obstacle", "unknown obstacle (unsensed)", "global path (last)", "driven", "robot",
                   "sensor range", "start", "goal"):
        assert needed in labels
    assert len(labels) >= 9


def test_overlays_draw_the_goal_where_it_is_not_where_the_trajectory_ends():
    world = op.GridMap(np.zeros((5, 5), bool))
    traj = np.array([[0.5, 0.5], [2.0, 2.0]])  # the robot stopped half way
    fig = plot_paths(world, {"run": traj}, start=(0.5, 0.5), goal=(4.5, 4.5))
    goal = [ln for ln in fig.axes[0].get_lines() if ln.get_label() == "goal"][0]
    assert (goal.get_xdata()[0], goal.get_ydata()[0]) == (4.5, 4.5)
