"""The graph-search modules import one way and use no other module's private names (issue 25).

Computed from the source (``ast``), imports inside functions included: a lazy
import is still a dependency.
"""
from __future__ import annotations

import ast
from pathlib import Path

import optplan

PKG = Path(optplan.__file__).resolve().parent
OWN = ["solvers/graph/__init__.py", "solvers/graph/astar.py", "solvers/graph/visibility.py", "solvers/result.py",
       "solvers/tube.py", "solvers/tangent_graph.py", "solvers/gridpath/moves.py"]


def module_name(rel: str) -> str:
    parts = ["optplan", *Path(rel).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports(rel: str):
    """``(module, names)`` for every import in the file, relative imports resolved."""
    path = PKG / rel
    here = module_name(rel)
    package = here if rel.endswith("__init__.py") else here.rsplit(".", 1)[0]
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, []
        elif isinstance(node, ast.ImportFrom):
            base = package
            for _ in range(node.level - 1):
                base = base.rsplit(".", 1)[0]
            mod = (f"{base}.{node.module}" if node.module else base) if node.level else node.module
            yield mod, [a.name for a in node.names]


def test_no_import_cycle_among_the_graph_modules():
    own = {module_name(r): r for r in OWN}
    edges = {m: set() for m in own}
    for m, rel in own.items():
        for target, names in imports(rel):
            for cand in [target] + [f"{target}.{n}" for n in names]:
                if cand in own and cand != m:
                    edges[m].add(cand)
    # depth-first search for a back edge
    state: dict[str, int] = {}

    def visit(m, stack):
        state[m] = 1
        for t in edges[m]:
            assert state.get(t) != 1, "import cycle: " + " -> ".join(stack + [m, t])
            if t not in state:
                visit(t, stack + [m])
        state[m] = 2

    for m in own:
        if m not in state:
            visit(m, [])
    # the result helpers sit below every planner
    assert edges["optplan.solvers.result"] == set()


def test_no_private_names_imported_across_modules():
    for rel in OWN:
        for target, names in imports(rel):
            private = [n for n in names if n.startswith("_") and n != "__future__"]
            assert not private, f"{rel} imports private {private} from {target}"
            assert not any(p.startswith("_") for p in target.split(".")[1:]), f"{rel} imports {target}"
