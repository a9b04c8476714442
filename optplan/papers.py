"""Each reproduced paper's whole method, in one table.

Every layer that needs to know "what does paper X do" reads it here: the global
planners it proposes and compares, its fitness preset, the path model it plans
with on grid maps, its post-processing of the global path, its local planner
preset and how that preset is guided (subgoals) and what it does when the global
path is blocked. The layers turn the names into objects (the fitness presets in
``formulations/presets.py``, the encodings in ``formulations/encodings.py``, the
local presets in ``local/presets.py``); adding a paper is one entry here plus
those objects.

``length`` is not a paper: it is the plain shortest-path fitness, used by planners
that belong to no paper.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class PaperMethod:
    """One paper's method.

    Attributes:
        key: the short name used everywhere (``hou2024``, ...); also its fitness preset.
        title: the paper's title (full references: ``docs/``).
        algorithms: global planners whose default fitness and post-processing are this paper's.
        grid_encoding: path model on grid maps (``columns``: one node per column;
            ``spline``: cubic spline through free handles); circle worlds always use the spline.
        postprocess: ``none``, ``collinear``, ``keypoints`` or ``prune`` (see ``solvers/paths.py``).
        local_preset: the paper's local planner preset (``None``: none).
        subgoals: how that preset is guided along the global path (``nav/subgoals.py``).
        on_blocked: what it does when the global path is blocked (``switch``, ``replan``, ``ignore``).
        sections: where the paper states the above, for the fidelity notes.
    """

    key: str
    title: str
    algorithms: tuple[str, ...]
    grid_encoding: str = "columns"
    postprocess: str = "collinear"
    local_preset: str | None = None
    subgoals: str = "key_points"
    on_blocked: str = "ignore"
    sections: str = ""


PAPERS: dict[str, PaperMethod] = {p.key: p for p in (
    PaperMethod("hou2024", "Dynamic Path Planning for Mobile Robots by Integrating Improved Sparrow Search "
                "Algorithm and Dynamic Window Approach", ("ssa", "missa"), postprocess="collinear",
                local_preset="missa-dwa", subgoals="key_points", sections="§3.1-3.2, §4.1"),
    PaperMethod("yang2023", "Mobile Robot Path Planning Based on Improved Particle Swarm Optimization and "
                "Improved Dynamic Window Approach", ("pso", "ipso", "ipso1", "ipso2"), grid_encoding="spline", postprocess="none",
                local_preset="idwa", subgoals="navigation_points", sections="§2.2 eq 1-4, §6, §7.3"),
    PaperMethod("yuan2021", "Path Planning for Mobile Robot Based on Improved Bat Algorithm", ("ba", "iba"),
                postprocess="collinear", local_preset="ba-dwa", subgoals="turning_points", on_blocked="switch",
                sections="eq 10-13, §4.1-4.2"),
    PaperMethod("li2023", "A Robot Path Planning Method Based on Improved Genetic Algorithm and Improved "
                "Dynamic Window Approach", ("ga", "iga"), postprocess="keypoints", local_preset="iga-dwa",
                subgoals="key_points", sections="§3-4, §4.4, §5.5"),
    PaperMethod("chen2025", "Research on Mobile Robot Path Planning Based on MSIAR-GWO Algorithm",
                ("gwo", "msiar-gwo", "woa", "aro", "dbo", "igwo", "agwo", "rsmgwo", "random"), postprocess="prune",
                sections="§4.3.1"),
)}

# the plain shortest-path fitness of planners that belong to no paper
LENGTH = PaperMethod("length", "shortest path (no paper)", (), postprocess="collinear")

# local planners that are not a paper's: how the navigation layer guides them
LOCAL_GUIDANCE = {
    "dwa": ("goal", "ignore"),          # Fox et al. 1997: no global guidance
    "qp-dwa": ("key_points", "replan"),  # optplan's own: key points + exact re-plan
    "mpc": ("key_points", "replan"),     # optplan's own NMPC, guided like qp-dwa
    "follow": ("goal", "ignore"),        # the global path driven blind: it never re-plans
}
DEFAULT_GUIDANCE = ("key_points", "replan")
# metres beyond the robot radius a local planner asks its global path to keep (the navigator's
# clearance ladder falls back below it where no such path exists): mpc needs room beside the path
# to let movers pass; with the bare radius it reached 47 of 50 held-out clutter worlds with movers
# (docs/measurements.md). On 1 m grids every cell path keeps 0.5 m, so their paths do not change.
GLOBAL_CLEARANCE_EXTRA = {"mpc": 0.15}


def method_of(key: str) -> PaperMethod:
    """The method of paper ``key`` (``length`` for the plain shortest path)."""
    return PAPERS.get(key, LENGTH)


def paper_of_algorithm(algorithm: str) -> str:
    """The paper whose fitness a global planner uses by default (``length`` if none)."""
    for p in PAPERS.values():
        if algorithm in p.algorithms:
            return p.key
    return LENGTH.key


def global_clearance_extra(local_name: str) -> float:
    """Metres beyond the robot radius the global path of ``local_name`` keeps by default
    (:data:`GLOBAL_CLEARANCE_EXTRA`; 0 for every other planner)."""
    return GLOBAL_CLEARANCE_EXTRA.get(local_name, 0.0)


def local_guidance(local_name: str) -> tuple[str, str]:
    """``(subgoal strategy, on_blocked)`` of a local planner: its paper's, or the toolkit's. A
    preset's twin as printed (``idwa-printed``, optplan/local/presets.py) is guided as the preset:
    the twin differs from it in the local planner only."""
    local_name = local_name.removesuffix("-printed")
    for p in PAPERS.values():
        if p.local_preset == local_name:
            return p.subgoals, p.on_blocked
    return LOCAL_GUIDANCE.get(local_name, DEFAULT_GUIDANCE)
