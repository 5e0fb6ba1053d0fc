"""A public attribute renamed: its former name kept for one release, with a DeprecationWarning.

>>> import warnings
>>> from dataclasses import dataclass
>>> @dataclass(frozen=True)
... class Pair:
...     fourlink: float
...     analytical = renamed("analytical", "fourlink", "Pair")
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     value = Pair(1.0).analytical
>>> value, caught[0].category.__name__
(1.0, 'DeprecationWarning')
>>> str(caught[0].message)
'Pair.analytical is deprecated and will be removed in the next release: use Pair.fourlink'
"""

from __future__ import annotations

import warnings
from typing import Any


def renamed(old: str, new: str, owner: str) -> Any:
    """A read-only property named ``old`` that warns and returns the attribute ``new``.

    Parameters
    ----------
    old : str
        The former name (the class attribute this property is assigned to).
    new : str
        The attribute's name now.
    owner : str
        The class's name, as the warning names it.

    Returns
    -------
    property
        Not a dataclass field (assign it without an annotation), so that the constructor and
        ``to_dict()`` know only the new name.
    """

    def get(self: Any) -> Any:
        warnings.warn(f"{owner}.{old} is deprecated and will be removed in the next release: "
                      f"use {owner}.{new}", DeprecationWarning, stacklevel=2)
        return getattr(self, new)

    get.__name__ = old
    get.__doc__ = f"Deprecated: ``{new}`` under its former name (a DeprecationWarning)."
    return property(get)


__all__ = ["renamed"]
