"""Results to plain JSON values: the one converter the CLI's ``--json`` and the sweep store use."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any


def to_jsonable(obj: Any) -> Any:
    """Numpy arrays and scalars to lists and Python numbers, non-finite floats to None (valid
    JSON), Enums to their values, mappings and sequences recursively.

    >>> import numpy as np
    >>> to_jsonable({"a": np.array([1.0, np.nan]), "b": (np.int64(2),)})
    {'a': [1.0, None], 'b': [2]}
    """
    if isinstance(obj, Mapping):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if hasattr(obj, "value") and hasattr(obj, "name"):  # Enum
        return to_jsonable(obj.value)
    if hasattr(obj, "tolist"):  # numpy arrays and scalars
        return to_jsonable(obj.tolist())
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    return obj


__all__ = ["to_jsonable"]
