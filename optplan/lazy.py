"""Lazy re-exports: a package names what it offers without importing heavy layers up front."""
from __future__ import annotations

import importlib
from typing import Any, Callable


def lazy_exports(package: str, names: dict[str, str], namespace: dict,
                 eager: list[str] = ()) -> tuple[Callable[[str], Any], Callable[[], list[str]], list[str]]:
    """Module ``__getattr__``, ``__dir__`` and ``__all__`` for ``package``.

    ``names`` maps each public name to the module that defines it; the first access imports
    that module and caches the value in ``namespace`` (the package's ``globals()``).
    ``eager`` lists names the package already defines itself.
    """
    public = sorted(list(names) + list(eager))

    def __getattr__(name: str) -> Any:
        module = names.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return public

    return __getattr__, __dir__, public
