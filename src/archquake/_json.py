"""Results to plain JSON values: the one converter the CLI's ``--json`` and the sweep store use."""

from __future__ import annotations

import json
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


def canonical_json(obj: Any) -> str:
    """Sorted keys, no whitespace, reals as floats (so 1 and 1.0 agree), NaN rejected: the text
    a case's id hashes (`archquake.sweeps.Case.case_id`) and its specs cache.

    >>> canonical_json({"b": 1, "a": [-0.0, 2.5]})
    '{"a":[0.0,2.5],"b":1}'
    """
    return json.dumps(_floats(obj), sort_keys=True, separators=(",", ":"), allow_nan=False)



def _floats(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {k: _floats(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_floats(v) for v in obj]
    if isinstance(obj, float) and obj == 0.0:
        return 0.0  # -0.0 and 0.0 are the same input
    return obj



__all__ = ["canonical_json", "to_jsonable"]
