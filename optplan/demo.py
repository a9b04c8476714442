"""``optplan demo``: plan on a shipped map, compare with the exact optimum, draw it."""
from __future__ import annotations

import math
import sys
from pathlib import Path

from .errors import UnknownAlgorithmError
from .planning import plan
from .world.loaders import load_map

DEMO_MAP = "multialgo20_template"
DEMO_START = (0.5, 0.5)
DEMO_GOAL = (19.5, 19.5)
# global planners shown when they are available in this version, with small budgets
DEMO_PLANNERS = (("astar", {}), ("visibility", {}), ("aco", {"pop": 30, "iters": 60}),
                 ("iga", {"pop": 50, "iters": 100}), ("msiar-gwo", {"pop": 30, "iters": 200}),
                 ("gwo", {"pop": 30, "iters": 200}),
                 # the optimisation-refined variants of the same MSIAR-GWO run
                 ("msiar-gwo", {"pop": 30, "iters": 200, "refine": "casadi"}),
                 ("msiar-gwo", {"pop": 30, "iters": 200, "refine": "qp"}))


def format_table(rows: list[dict], columns: list[tuple[str, str, str]]) -> str:
    """Markdown table; ``columns`` are (key, header, format spec)."""
    head = "| " + " | ".join(h for _, h, _ in columns) + " |"
    rule = "|" + "|".join("---" for _ in columns) + "|"
    body = []
    for r in rows:
        cells = []
        for key, _, spec in columns:
            v = r.get(key, "")
            cells.append(format(v, spec) if spec and isinstance(v, (int, float)) else str(v))
        body.append("| " + " | ".join(cells) + " |")
    return "\n".join([head, rule, *body])


# the columns of a table of plan results, in the demo and in `optplan plan` alike
RESULT_COLUMNS = [
    ("algorithm", "algorithm", ""), ("length", "length [m]", ".4f"), ("gap", "gap to exact optimum [%]", ".2f"),
    ("turn", "total turn [deg]", ".1f"), ("turns", "turns", "d"), ("clear", "min clearance [m]", ".3f"),
    ("ms", "time [ms]", ".1f"), ("feasible", "feasible", ""), ("note", "note", ""),
]


def result_row(name: str, r, optimum: float | None, note: str = "") -> dict:
    """One row of :data:`RESULT_COLUMNS` for the PlanResult ``r`` (``optimum``: the exact
    any-angle length, ``None`` when unknown)."""
    gap = 100.0 * (r.length / optimum - 1.0) if optimum and math.isfinite(r.length) else "-"
    return {"algorithm": name, "length": r.length, "gap": gap, "turn": r.turn_angle_deg, "turns": r.n_turns,
            "clear": r.min_clearance, "ms": 1000.0 * r.runtime_s, "feasible": "yes" if r.feasible else "NO",
            "note": note}


def run_demo(out: str | Path = "optplan_demo.png", seed: int = 0, stream=None) -> list[dict]:
    """Run the demo, print the table to ``stream`` (stdout) and write the PNG to ``out``."""
    stream = stream or sys.stdout
    grid = load_map(DEMO_MAP)
    print(f"map {DEMO_MAP}: {grid.width}x{grid.height} cells, start {DEMO_START}, goal {DEMO_GOAL}", file=stream)
    results = {}
    for name, params in DEMO_PLANNERS:
        label = name + (f" + {params['refine']}" if params.get("refine") else "")
        try:
            results[label] = plan(grid, DEMO_START, DEMO_GOAL, algorithm=name, seed=seed, **params)
        except UnknownAlgorithmError:
            continue  # that planner is not part of this version
    optimum = results["visibility"].length
    rows = [result_row(name, r, optimum, "" if r.refined or " + " not in name else "fell back to the seed")
            for name, r in results.items()]
    table = format_table(rows, RESULT_COLUMNS)
    print(table, file=stream)
    print("exact optimum = visibility graph over obstacle corners (any-angle, cell centres); "
          "'+ casadi' / '+ qp' = the msiar-gwo path refined by IPOPT / the OSQP corridor smoother "
          "(times include the metaheuristic; every path passed the exact collision check); "
          "turns = vertices where the heading changes: a refined path is a dense smooth curve, so its "
          "turns are many small ones and its total turn is the figure to compare", file=stream)
    demo_figure(grid, results, optimum, out)
    print(f"wrote {out}", file=stream)
    return rows


def demo_figure(grid, results: dict, optimum: float, out: str | Path | None):
    """The demo's picture: the paths on the map with the exact optimum drawn as a band on top
    (paths that follow it cannot hide it), and the searches' convergence on a linear axis with
    each path's final length after pruning and refinement marked past the curve (the refined
    runs share the msiar-gwo search, so only their marks differ)."""
    import numpy as np

    from .viz.convergence import draw_convergence, post_processing_x
    from .viz.plots import blank_figure, draw_paths, save_figure

    fig = blank_figure((12.5, 6.2))
    ax_map, ax_conv = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.0, 1.05]})
    exact = "exact optimum (visibility)"
    paths = {(exact if k == "visibility" else k): r.path for k, r in results.items()}
    cycle = [f"C{i}" for i in range(10)]
    colours = {k: cycle[i % len(cycle)] for i, k in enumerate(k for k in paths if k != exact)}
    draw_paths(ax_map, grid, paths, DEMO_START, DEMO_GOAL, highlight=exact, legend_loc="upper left",
               colours=colours)
    ax_map.set_title(f"{DEMO_MAP}: paths (every one passed the exact collision check)", fontsize=10)
    searches = {k: r for k, r in results.items() if len(r.history) > 1 and " + " not in k}
    histories = {k: [np.where(np.isfinite(r.history), r.history, np.nan)] for k, r in searches.items()}
    finals = {k: [r.length] for k, r in searches.items()}
    draw_convergence(ax_conv, histories, log=False, finals=finals, reference=(optimum, "exact optimum"),
                     ylabel="best fitness during the search; marks: final path length [m]", colours=colours)
    n_max = max((len(h[0]) for h in histories.values()), default=1)
    for shift, (name, r) in enumerate((k, r) for k, r in results.items() if " + " in k):
        ax_conv.plot([post_processing_x(n_max) + 4 * (shift + 1)], [r.length], "P", color=colours.get(name), ms=8,
                     label=f"{name} (the msiar-gwo search, refined)")
    finite = [v for h in histories.values() for v in h[0] if np.isfinite(v)]
    if finite:  # leave out the first infeasible iterations' huge values, keep the end readable
        ax_conv.set_ylim(optimum * 0.98, min(max(finite), optimum * 1.35))
    ax_conv.legend(fontsize=7)
    ax_conv.set_title("convergence: search, then pruning / refinement", fontsize=10)
    fig.tight_layout()
    if out is not None:
        save_figure(fig, out, 110)
    return fig
