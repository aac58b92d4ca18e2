"""Python values as C arguments: range-checked integers, array pointers, dataclasses or dicts
copied into ctypes structs, 4x4 matrices."""

from __future__ import annotations

import ctypes
from collections.abc import Mapping
from dataclasses import asdict, is_dataclass
from typing import Any

import numpy as np

_UINT32_MAX = 0xFFFFFFFF


def _uint32(value: Any, what: str) -> int:
    """value as a C uint32_t, or ValueError naming it (ctypes would wrap negatives silently)."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise ValueError(f"{what} = {value!r} is not an integer")
    if not 0 <= int(value) <= _UINT32_MAX:
        raise ValueError(f"{what} = {value} is out of range [0, {_UINT32_MAX}]")
    return int(value)


def _float_ptr(arr: np.ndarray) -> Any:
    return arr.ctypes.data_as(ctypes.POINTER(ctypes.c_float))


def _uint_ptr(arr: np.ndarray) -> Any:
    return arr.ctypes.data_as(ctypes.POINTER(ctypes.c_uint32))


def _fields(value: Any) -> dict[str, Any]:
    if is_dataclass(value) and not isinstance(value, type):
        return asdict(value)
    if isinstance(value, Mapping):
        return dict(value)
    raise TypeError(f"expected a dict or dataclass, got {type(value).__name__}")


def _set_struct(struct: ctypes.Structure, values: Mapping[str, Any], what: str) -> None:
    known = {name for name, _ in struct._fields_}
    for key, value in values.items():
        if key not in known:
            raise ValueError(f"{what}: unknown field {key!r} (known: {sorted(known)})")
        current = getattr(struct, key)
        if isinstance(current, ctypes.Array):
            seq = np.asarray(value, dtype=np.float64).ravel()
            if seq.size != len(current):
                raise ValueError(f"{what}.{key}: expected {len(current)} values, got {seq.size}")
            for i, v in enumerate(seq):
                current[i] = float(v)
        else:
            setattr(struct, key, value)


def _matrix16(matrix: Any, what: str) -> np.ndarray:
    m = np.ascontiguousarray(np.asarray(matrix, dtype=np.float32).reshape(-1))
    if m.size != 16:
        raise ValueError(f"{what}: expected a 4x4 matrix (16 floats), got {m.size} values")
    return m

