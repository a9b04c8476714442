"""Plot helpers: they build their own Figure (no pyplot, no backend switch), return it, and
write PNGs on a machine with no display; and the simulator layer never imports viz."""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure

import optplan
from optplan.viz.experiment_plots import box_plot
from optplan.viz.convergence import plot_convergence
from optplan.viz.plots import plot_paths
from optplan.world.loaders import load_map

PACKAGE = Path(optplan.__file__).resolve().parent


def _helpers(tmp_path: Path | None):
    grid = load_map("multialgo20_template")
    path = np.array([[0.5, 0.5], [10.0, 10.0], [19.5, 19.5]])
    name = (lambda n: tmp_path / n) if tmp_path is not None else (lambda n: None)
    return [
        (lambda: plot_paths(grid, {"a": path}, name("paths.png"), title="paths")),
        (lambda: plot_convergence({"a": [np.array([3.0, 2.0, 1.0]), np.array([4.0, 1.0])]}, name("conv.png"))),
        (lambda: box_plot({"a": [1.0, 2.0, 3.0], "b": []}, name("box.png"), reference_line=1.5)),
    ]


@pytest.fixture
def svg_backend():
    """A backend other than Agg, as a notebook or a GUI program would have set one."""
    before = matplotlib.get_backend()
    matplotlib.use("svg")
    yield
    matplotlib.use(before)


def test_plot_helpers_return_a_figure_and_leave_the_backend_alone(svg_backend, tmp_path):
    for draw in _helpers(tmp_path):
        fig = draw()
        assert isinstance(fig, Figure)
        assert matplotlib.get_backend() == "svg"
    for name in ("paths.png", "conv.png", "box.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for draw in _helpers(None):  # no file name: only the figure
        assert isinstance(draw(), Figure)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["box.png", "conv.png", "paths.png"]


def test_plotting_imports_no_pyplot(tmp_path):
    # in a fresh interpreter, since another test may have imported pyplot in this one
    code = f"""
import sys, matplotlib
matplotlib.use("svg")
from optplan.viz.plots import plot_paths
from optplan.world.loaders import load_map
plot_paths(load_map("arena"), {{"a": [[1.5, 37.5], [40.5, 10.5]]}}, {str(tmp_path / "a.png")!r})
print(matplotlib.get_backend(), "matplotlib.pyplot" in sys.modules)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["svg", "False"]


def test_a_backend_matplotlib_does_not_know_is_an_error_that_says_so(tmp_path):
    """matplotlib refuses to import with an unknown MPLBACKEND; optplan, which needs no backend,
    reports that as the user's setting (exit 2, one line), not as an internal error."""
    import os

    env = {**os.environ, "MPLBACKEND": "no-such-backend"}
    out = tmp_path / "p.png"
    proc = subprocess.run([sys.executable, "-m", "optplan", "plan", "arena", "--start", "1.5", "37.5", "--goal",
                           "40.5", "10.5", "--plot", str(out)], capture_output=True, text=True, env=env)
    assert proc.returncode == 2 and "internal error" not in proc.stderr
    assert "unset MPLBACKEND" in proc.stderr and "no-such-backend" in proc.stderr
    env["MPLBACKEND"] = "agg"  # a valid one is fine, whatever it is
    proc = subprocess.run([sys.executable, "-m", "optplan", "plan", "arena", "--start", "1.5", "37.5", "--goal",
                           "40.5", "10.5", "--plot", str(out)], capture_output=True, text=True, env=env)
    assert proc.returncode == 0 and out.read_bytes()[:4] == b"\x89PNG"


def test_a_picture_format_matplotlib_cannot_write_is_refused_before_any_work(tmp_path, capsys):
    from optplan.cli import main

    assert main(["plan", "arena", "--start", "1.5", "37.5", "--goal", "40.5", "10.5", "--plot",
                 str(tmp_path / "p.xyz")]) == 2
    err = capsys.readouterr()
    assert "matplotlib writes no .xyz pictures" in err.err and ".svg" in err.err and err.out == ""
    assert main(["demo", "--out", str(tmp_path / "d.bmpx")]) == 2  # the demo refuses it before planning
    assert capsys.readouterr().out == ""
    from optplan.viz.plots import new_figure, save_figure

    fig, _ = new_figure()
    assert save_figure(fig, tmp_path / "new" / "folder" / "f.svg").read_text().lstrip().startswith("<?xml")


def _imported_modules(path: Path) -> set[str]:
    """Absolute names of the modules ``path`` imports (relative imports resolved)."""
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    package = parts[:-1]  # the package a module (or an __init__) belongs to
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = package[:len(package) - node.level + 1] if node.level else []
            mod = ".".join(base + ([node.module] if node.module else []))
            out.add(mod)
            out |= {f"{mod}.{a.name}" for a in node.names}
    return out


def test_the_simulator_layer_never_imports_viz_or_the_command_line():
    # DESIGN.md "Layers": sim (6) sits above bench (7), viz and cli (8); data flows one way
    below = ("optplan.viz", "optplan.cli", "optplan.bench", "optplan.demo")
    bad = {str(p.relative_to(PACKAGE.parent)): sorted(m for m in _imported_modules(p) if m.startswith(below))
           for p in sorted((PACKAGE / "sim").rglob("*.py"))}
    assert not {k: v for k, v in bad.items() if v}
    assert "optplan.world.scenario" in _imported_modules(PACKAGE / "sim" / "environment.py")  # the check sees imports


def test_plot_titles_name_the_refinement_box_plots_have_units_and_legends_leave_the_map(tmp_path):
    """Issue 47 polish: 'plan --refine casadi --plot' titled the refined path without '+ casadi';
    box plots had no unit; the legend sat on the map."""
    import optplan as op
    from optplan.cli import main
    from optplan.viz.experiment_plots import metric_label
    from optplan.viz.plots import plot_paths

    assert metric_label("length") == "length [m]" and metric_label("time_s") == "time_s [s]"
    assert metric_label("cost") == "cost"
    grid = op.load_map("chen2025_30")
    fig = plot_paths(grid, {"a": np.array([[0.5, 0.5], [5.5, 0.5]])})
    ax = fig.axes[0]
    fig.canvas.draw()
    legend = ax.get_legend().get_window_extent()
    assert legend.x0 >= ax.get_window_extent().x1 - 1       # beside the axes, not on the map
    import optplan.viz.plots as plots

    seen = {}
    real = plots.plot_paths

    def spy(world, paths, filename=None, title="", **kw):
        seen["title"] = title
        return real(world, paths, filename, title, **kw)

    plots.plot_paths = spy
    try:
        assert main(["plan", "chen2025_20", "--algo", "astar", "--refine", "qp", "--plot",
                     str(tmp_path / "p.png")]) == 0
    finally:
        plots.plot_paths = real
    assert seen["title"].startswith("astar + qp")
