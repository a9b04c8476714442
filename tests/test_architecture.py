"""The package's structure, checked from its source: no import cycles between modules, no
import that goes up the layer order of ``docs/architecture.md``, no private name used
across modules.

Every module of ``optplan`` is parsed with ``ast`` (nothing is imported). An import is any
``import``/``from ... import`` statement, at module level or inside a function (under
``if TYPE_CHECKING:`` too: a type-only import still ties the two modules together), and any
``importlib.import_module("optplan...")`` / ``__import__("optplan...")`` call with a literal
name. ``from package import name`` depends on the submodule ``package.name`` when there is
one, otherwise on the package's ``__init__``, which counts as a module of its own.

A private name is one with a single leading underscore (``_x``, not ``__x__``). It is used
across modules when it is imported from another module (``from .tube import _cells``), read
as an attribute of an imported module (``runner._plan_target``) or fetched with
``getattr(module, "_x")``.

Offences owned by other branches are listed in :data:`KNOWN_OFFENCES`; the test fails on
any offence not in that set *and* on any entry of the set that no longer occurs, so the
list only ever shrinks.
"""
from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
PACKAGE = REPO / "optplan"
ARCHITECTURE_DOC = REPO / "docs" / "architecture.md"

# Offences left to others (issue 25), each with its owner. Each entry is the exact string
# the checks below produce. Remove an entry when its fix lands: the test fails while a
# listed offence no longer occurs.
KNOWN_OFFENCES: dict[str, str] = {}


# ----------------------------------------------------------------- layer order
def layer_table() -> list[tuple[int, str, tuple[str, ...]]]:
    """``(rank, layer, module prefixes)`` rows of the layer table in docs/architecture.md.

    The table is the one whose header is ``| rank | layer | modules | ...``; module prefixes
    are the back-quoted dotted names of its third column."""
    rows, in_table = [], False
    for line in ARCHITECTURE_DOC.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.lstrip().startswith("|"):
            in_table = False
            continue
        if cells[:3] == ["rank", "layer", "modules"]:
            in_table = True
            continue
        if not in_table or set(cells[0]) <= set("-: "):
            continue
        rows.append((int(cells[0]), cells[1], tuple(re.findall(r"`(optplan[\w.]*)`", cells[2]))))
    return rows


def layer_of(module: str, table) -> tuple[int, str]:
    """Rank and name of the layer that holds ``module`` (the longest matching prefix)."""
    best = None
    for rank, name, prefixes in table:
        for p in prefixes:
            # the root package's entry is its ``__init__`` alone; every other entry holds its submodules
            inside = module.startswith(p + ".") and p != "optplan"
            if (module == p or inside) and (best is None or len(p) > best[0]):
                best = (len(p), rank, name)
    if best is None:
        raise AssertionError(f"{module} belongs to no layer of {ARCHITECTURE_DOC.name}; add it to the table")
    return best[1], best[2]


# ------------------------------------------------------------------- the graph
def module_files(package: Path = PACKAGE) -> dict[str, Path]:
    """Dotted module name -> file, for every module of the package (``__init__`` = the package)."""
    out = {}
    for f in sorted(package.rglob("*.py")):
        parts = list(f.relative_to(package.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = f
    return out


@dataclass(frozen=True)
class Use:
    """One dependency of a module: on ``target`` (a module), naming ``name`` of it if any."""

    target: str
    name: str | None
    line: int


def _resolve(module: str, is_package: bool, level: int, base: str | None) -> str:
    if level == 0:
        return base or ""
    parts = module.split(".") if is_package else module.split(".")[:-1]
    parts = parts[:len(parts) - (level - 1)]
    return ".".join(parts + ([base] if base else []))


def _module_names(tree: ast.AST, module: str, is_package: bool, modules) -> dict[str, str]:
    """Local names that are bound to one of ``modules`` anywhere in the file."""
    bound = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.asname:
                    bound[a.asname] = a.name
                else:
                    bound[a.name.split(".")[0]] = a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(module, is_package, node.level, node.module)
            for a in node.names:
                if f"{base}.{a.name}" in modules:
                    bound[a.asname or a.name] = f"{base}.{a.name}"
    return {k: v for k, v in bound.items() if v in modules}


def _is_private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def uses(module: str, path: Path, modules) -> list[Use]:
    """Every dependency of ``module`` on another module of the package."""
    tree = ast.parse(path.read_text(), str(path))
    is_package = path.name == "__init__.py"
    out: list[Use] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name in modules:
                    out.append(Use(a.name, None, node.lineno))
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(module, is_package, node.level, node.module)
            if not (base == "optplan" or base.startswith("optplan.")):
                continue
            for a in node.names:
                sub = f"{base}.{a.name}"
                if sub in modules:
                    out.append(Use(sub, None, node.lineno))
                else:
                    out.append(Use(base, a.name, node.lineno))
        elif isinstance(node, ast.Call):
            f = node.func
            called = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else None
            if called in ("import_module", "__import__") and node.args and isinstance(node.args[0], ast.Constant) \
                    and isinstance(node.args[0].value, str) and node.args[0].value in modules:
                out.append(Use(node.args[0].value, None, node.lineno))
    # private attributes read off imported modules: ``mod._x``, ``pkg.mod._x``, getattr(mod, "_x")
    bound = _module_names(tree, module, is_package, modules)

    def dotted(expr) -> str | None:
        if isinstance(expr, ast.Name):
            return bound.get(expr.id)
        if isinstance(expr, ast.Attribute):
            head = dotted(expr.value)
            if head is not None and f"{head}.{expr.attr}" in modules:
                return f"{head}.{expr.attr}"
        return None

    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and _is_private(node.attr):
            target = dotted(node.value)
            if target is not None:
                out.append(Use(target, node.attr, node.lineno))
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "getattr" \
                and len(node.args) >= 2 and isinstance(node.args[1], ast.Constant) \
                and isinstance(node.args[1].value, str) and _is_private(node.args[1].value):
            target = dotted(node.args[0])
            if target is not None:
                out.append(Use(target, node.args[1].value, node.lineno))
    return [u for u in out if u.target != module]


def dependency_graph(files: dict[str, Path]) -> tuple[dict[str, set[str]], dict[str, list[Use]]]:
    """``module -> modules it depends on`` and ``module -> its uses``."""
    all_uses = {m: uses(m, f, files) for m, f in files.items()}
    return {m: {u.target for u in us} for m, us in all_uses.items()}, all_uses


def strongly_connected(graph: dict[str, set[str]]) -> list[list[str]]:
    """Tarjan's strongly connected components with more than one module, each sorted."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v: str) -> None:  # the graph has ~100 nodes: recursion is fine
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(out)


# ------------------------------------------------------------------- offences
def _short(module: str) -> str:
    return module.removeprefix("optplan.") if module != "optplan" else "optplan"


def offences(files: dict[str, Path] | None = None, table=None) -> set[str]:
    """Every offence of the package, one string each (the form :data:`KNOWN_OFFENCES` uses)."""
    graph, all_uses = dependency_graph(module_files() if files is None else files)
    table = layer_table() if table is None else table
    found = set()
    for comp in strongly_connected(graph):
        found.add("cycle: " + " <-> ".join(_short(m) for m in comp))
    for m, us in all_uses.items():
        rank, layer = layer_of(m, table)
        for u in us:
            t_rank, t_layer = layer_of(u.target, table)
            if t_rank > rank:
                found.add(f"upward import: {_short(m)} ({layer}) imports {_short(u.target)} ({t_layer})")
            if u.name is not None and _is_private(u.name):
                found.add(f"private name: {_short(m)} uses {_short(u.target)}.{u.name}")
    return found


def test_layer_table_covers_the_package_in_the_design_order():
    table = layer_table()
    ranks = [r for r, _, _ in table]
    assert ranks == sorted(ranks) and len(set(ranks)) == len(ranks), "ranks must increase down the table"
    names = [n for _, n, _ in table]
    # DESIGN.md's layers, in its order (world < formulations < solvers < local < nav < sim < bench < viz/cli)
    design = ["world", "formulations", "solvers", "local", "nav", "sim", "bench", "viz/cli"]
    assert [n for n in names if n in design] == design
    files = module_files()
    for m in files:
        layer_of(m, table)  # raises if a module has no layer
    listed = [p for _, _, prefixes in table for p in prefixes]
    assert not [p for p in listed if p not in files], "the table names modules that do not exist"
    assert len(set(listed)) == len(listed), "a module is listed in two layers"


def test_no_cycles_no_upward_imports_no_private_names_across_modules():
    found = offences()
    new = sorted(found - set(KNOWN_OFFENCES))
    gone = sorted(set(KNOWN_OFFENCES) - found)
    msg = []
    if new:
        msg.append("new structural offences (see docs/architecture.md):\n  " + "\n  ".join(new))
    if gone:
        msg.append("fixed, remove from KNOWN_OFFENCES in tests/test_architecture.py:\n  " + "\n  ".join(gone))
    assert not msg, "\n".join(msg)


def test_only_the_derived_store_touches_a_worlds_private_cache():
    """Data derived from a world lives in its builder's DerivedStore (optplan/world/derived.py);
    no other module reads or writes the world's private slot (it declared ``_cache`` fields of
    the two world classes aside)."""
    pkg = PACKAGE
    allowed = {"world/derived.py"}
    bad = []
    for f in sorted(pkg.rglob("*.py")):
        rel = f.relative_to(pkg).as_posix()
        if rel in allowed:
            continue
        for i, line in enumerate(f.read_text().splitlines(), 1):
            if re.search(r"\._cache\b", line):
                bad.append(f"{rel}:{i}: {line.strip()}")
    assert not bad, "use a DerivedStore instead:\n  " + "\n  ".join(bad)


# ------------------------------------------------------------- the checker itself
def _graph_of(tmp_path, files: dict[str, str]):
    for rel, text in files.items():
        p = tmp_path / "optplan" / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    mods = module_files(tmp_path / "optplan")
    return {m: uses(m, f, mods) for m, f in mods.items()}


def test_checker_sees_every_kind_of_import(tmp_path):
    got = _graph_of(tmp_path, {
        "__init__.py": "",
        "a/__init__.py": "from .b import thing\n",
        "a/b.py": "def f():\n    from ..c import d\n    return d._hidden\n",
        "a/e.py": "import importlib\nM = importlib.import_module('optplan.c.d')\nfrom . import b\nx = b._y\n",
        "a/g.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from optplan.a.e import M\n"
                  "import optplan.c.d as dd\nz = getattr(dd, '_w')\nfrom ..c.d import _priv\n",
        "c/__init__.py": "",
        "c/d.py": "from optplan import a\n",
    })
    deps = {m: {(u.target, u.name) for u in us} for m, us in got.items()}
    assert deps["optplan.a"] == {("optplan.a.b", "thing")}
    assert deps["optplan.a.b"] == {("optplan.c.d", None), ("optplan.c.d", "_hidden")}
    assert deps["optplan.a.e"] == {("optplan.c.d", None), ("optplan.a.b", None), ("optplan.a.b", "_y")}
    assert deps["optplan.a.g"] == {("optplan.a.e", "M"), ("optplan.c.d", None), ("optplan.c.d", "_w"),
                                   ("optplan.c.d", "_priv")}
    assert deps["optplan.c.d"] == {("optplan.a", None)}
    graph = {m: {t for t, _ in d} for m, d in deps.items()}
    assert strongly_connected(graph) == [["optplan.a", "optplan.a.b", "optplan.c.d"]]


def test_checker_reports_cycles_upward_imports_and_private_names(tmp_path):
    _graph_of(tmp_path, {
        "__init__.py": "",
        "low/__init__.py": "",
        "low/a.py": "def f():\n    from ..high.b import g\n    return g\n",
        "low/c.py": "from .d import x\n",
        "low/d.py": "from . import c\nfrom .a import _helper\n",
        "high/__init__.py": "",
        "high/b.py": "from ..low import a\ny = a._z\n",
    })
    table = [(0, "low", ("optplan", "optplan.low")), (1, "high", ("optplan.high",))]
    assert offences(module_files(tmp_path / "optplan"), table) == {
        "cycle: high.b <-> low.a",
        "cycle: low.c <-> low.d",
        "upward import: low.a (low) imports high.b (high)",
        "private name: low.d uses low.a._helper",
        "private name: high.b uses low.a._z",
    }


@pytest.mark.parametrize("module,expected", [("optplan.world.grid", "world"), ("optplan.cli", "viz/cli")])
def test_layer_lookup_takes_the_longest_prefix(module, expected):
    assert layer_of(module, layer_table())[1] == expected


if __name__ == "__main__":  # print the offences: python tests/test_architecture.py
    print("\n".join(sorted(offences())))


def test_paper_method_table_is_the_one_source():
    """Every layer's view of a paper's method comes from optplan/papers.py."""
    from optplan.formulations.paper_programs import PAPER_VARIABLES
    from optplan.nav.navigator import preset_defaults
    from optplan.papers import PAPERS, paper_of_algorithm
    from optplan.solvers.paths import GRID_ENCODING, PAPER_OF, POSTPROCESS, algorithm_names

    for key, p in PAPERS.items():
        assert POSTPROCESS[key] == p.postprocess
        assert GRID_ENCODING.get(key, "columns") == p.grid_encoding
        for a in p.algorithms:
            assert a in algorithm_names(), f"{key} lists {a}, which is no planner"
            assert PAPER_OF[a] == key == paper_of_algorithm(a)
        if p.local_preset:
            assert preset_defaults(p.local_preset) == (p.subgoals, p.on_blocked)
    assert PAPER_VARIABLES["yang2023"]().name.startswith("BSpline")
    assert paper_of_algorithm("no-such-planner") == "length"
