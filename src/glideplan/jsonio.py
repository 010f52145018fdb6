"""JSON of results: the one encoder the CLI (`--json`), the explorer and the writers share.

`to_json(data)` writes dicts, lists, NumPy arrays and scalars, `Status` (its value) and any
object with `to_dict()`; non-finite floats become `null` (JSON has no NaN or infinity).
"""

from __future__ import annotations

import json
import math
import pathlib
from typing import Any

import numpy as np

__all__ = ["clean", "json_default", "to_json", "write_json"]


def json_default(obj: Any) -> Any:
    """Make NumPy scalars and arrays, results (`to_dict()`) and enums JSON-serialisable."""
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if hasattr(obj, "to_dict"):
        return obj.to_dict()
    if hasattr(obj, "value"):
        return obj.value
    raise TypeError(f"cannot serialise {type(obj).__name__}")


def clean(obj: Any) -> Any:
    """`obj` with non-finite floats as None and arrays/NumPy scalars as plain Python."""
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, dict):
        return {k: clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [clean(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return clean(obj.tolist())
    if isinstance(obj, np.generic):
        return clean(obj.item())
    return obj


def to_json(data: Any) -> str:
    """The JSON text (indented by 2) of `data`."""
    return json.dumps(clean(data), default=json_default, indent=2)


def write_json(data: Any, filename: pathlib.Path | str) -> None:
    """Write `to_json(data)` and a newline to `filename`."""
    pathlib.Path(filename).write_text(to_json(data) + "\n")
