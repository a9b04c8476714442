"""The plotting API (issue 47 item 5): op.plot_map / plot_paths / plot_run take ax= and
return the Axes; without ax they draw through pyplot, so Jupyter shows the figure."""
from __future__ import annotations

import numpy as np
import pytest

import optplan as op


@pytest.fixture(autouse=True)
def _agg(monkeypatch):
    import matplotlib

    matplotlib.use("agg")
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


def test_the_plot_helpers_draw_on_the_given_axes_and_return_it(tmp_path):
    import matplotlib.pyplot as plt

    grid = op.load_map("chen2025_30")
    r = op.shortest_path(grid, (0.5, 0.5), (29.5, 29.5), method="visibility")
    fig, (a, b) = plt.subplots(1, 2)
    assert op.plot_map(grid, ax=a) is a
    assert op.plot_paths(grid, {"visibility": r.path}, ax=b, highlight="visibility") is b
    assert len(b.lines) >= 2 and b.get_legend() is not None
    np.testing.assert_allclose(b.lines[0].get_xydata(), r.path)
    fig.savefig(tmp_path / "two.png")
    assert (tmp_path / "two.png").stat().st_size > 1000


def test_without_axes_the_figure_is_made_through_pyplot():
    import matplotlib.pyplot as plt

    grid = op.load_map("chen2025_30")
    before = len(plt.get_fignums())
    ax = op.plot_paths(grid, np.array([[0.5, 0.5], [3.5, 0.5]]))
    assert len(plt.get_fignums()) == before + 1 and ax.figure is plt.gcf()


def test_plot_run_draws_the_trajectory_and_the_outcome():
    res = op.simulate("hou2024_dynamic1", local_planner="qp-dwa", seed=0, time_limit=5)
    ax = op.plot_run(res, "hou2024_dynamic1")
    xy = ax.collections[-1].get_offsets()
    np.testing.assert_allclose(xy, np.asarray(res.trajectory)[:, 1:3])
    assert "after 5.0 s" in ax.get_title()
    with pytest.raises(op.ParameterError, match="Axes"):
        op.plot_map(op.load_map("chen2025_30"), ax="nope")
