"""Write docs/api.md, the API reference, from the docstrings of optplan's public names.

    python docs/make_api.py            # rewrite docs/api.md
    python docs/make_api.py --check    # exit 1 if docs/api.md is not current

``tests/test_api_docs.py`` runs the check, so the reference cannot drift from the code.
"""
from __future__ import annotations

import inspect
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "api.md"

# extra modules whose public functions users call directly (beyond ``import optplan as op``)
MODULES = ("optplan.terms", "optplan.bench", "optplan.world.export", "optplan.world.loaders")


def _signature(obj) -> str:
    try:
        sig = str(inspect.signature(obj))
    except (TypeError, ValueError):
        return ""
    return re.sub(r" at 0x[0-9a-fA-F]+", "", sig)


def _doc(obj) -> str:
    doc = inspect.getdoc(obj) or "(no docstring)"
    return doc.strip()


def _entry(name: str, obj, level: str = "###") -> list[str]:
    kind = "class" if inspect.isclass(obj) else "function" if callable(obj) else "value"
    lines = [f"{level} `{name}{_signature(obj) if kind != 'value' else ''}`", "", f"*{kind}*", "", _doc(obj), ""]
    if inspect.isclass(obj):
        for attr, member in sorted(vars(obj).items()):
            if attr.startswith("_") or not (inspect.isfunction(member) or isinstance(member, (classmethod, property))):
                continue
            target = member.__func__ if isinstance(member, classmethod) else member
            target = target.fget if isinstance(target, property) else target
            sig = "" if isinstance(member, property) else _signature(target)
            first = (inspect.getdoc(target) or "").split("\n\n")[0].replace("\n", " ")
            lines.append(f"- `{attr}{sig}`: {first}")
        lines.append("")
    return lines


def render() -> str:
    """The text of docs/api.md."""
    sys.path.insert(0, str(ROOT))
    import importlib

    import optplan as op

    lines = ["# API reference", "",
             "Generated from the docstrings by `python docs/make_api.py`; do not edit by hand.", "",
             f"optplan {op.__version__}. `import optplan as op` gives every name in the first section.", "",
             "## `optplan`", ""]
    for name in sorted(op.__all__):
        lines += _entry(f"op.{name}", getattr(op, name))
    for modname in MODULES:
        mod = importlib.import_module(modname)
        names = getattr(mod, "__all__", None) or [n for n, v in vars(mod).items()
                                                  if not n.startswith("_") and getattr(v, "__module__", "") == modname
                                                  and (inspect.isfunction(v) or inspect.isclass(v))]
        lines += [f"## `{modname}`", "", (inspect.getdoc(mod) or "").split("\n\n")[0], ""]
        for name in sorted(names):
            lines += _entry(f"{modname}.{name}", getattr(mod, name))
    return "\n".join(lines).rstrip() + "\n"


def main(argv: list[str]) -> int:
    text = render()
    if "--check" in argv:
        if not OUT.is_file() or OUT.read_text() != text:
            print("docs/api.md is out of date; run: python docs/make_api.py", file=sys.stderr)
            return 1
        return 0
    OUT.write_text(text)
    print(f"wrote {OUT} ({len(text.splitlines())} lines)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
