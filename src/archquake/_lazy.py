"""Names of a package loaded on first access (PEP 562), so that importing the package is cheap.

>>> import types
>>> pkg = types.ModuleType("pkg")
>>> pkg.__getattr__, pkg.__dir__ = attach(pkg, {"sqrt": "math"})
>>> pkg.__getattr__("sqrt")(4.0), "sqrt" in vars(pkg), "sqrt" in pkg.__dir__()
(2.0, True, True)
"""

from __future__ import annotations

import importlib
import types
from collections.abc import Callable, Mapping
from typing import Any


def attach(module: types.ModuleType, names: Mapping[str, str]
           ) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The ``__getattr__`` and ``__dir__`` of a module whose ``names`` load on first access.

    Parameters
    ----------
    module : module
        The package (``sys.modules[__name__]``).
    names : mapping of str to str
        Public name -> the module that defines it.

    Returns
    -------
    (__getattr__, __dir__)
        The first imports a name's module on first access and keeps the value in ``module``'s
        namespace (later accesses do not call it); unknown names raise AttributeError.
    """

    def __getattr__(name: str) -> Any:
        source = names.get(name)
        if source is None:
            raise AttributeError(f"module {module.__name__!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(source), name)
        setattr(module, name, value)
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(module)) | set(names))

    return __getattr__, __dir__


__all__ = ["attach"]
