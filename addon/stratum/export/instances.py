"""How a depsgraph object instance is placed: what it draws (its identity), which rays see it,
whether it is held out (Object > Visibility in Cycles) and its pass index, and whether its
transform can be rendered (placement.py)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from .. import native
from .common import ExportError, ExportSummary
from .lights import object_visibility
from .placement import degenerate, first_non_finite


class ObjectFlags(NamedTuple):
    """What an instance carries besides its mesh and transform."""

    visibility: int  # native VISIBLE_* bits
    holdout: bool
    pass_index: int  # Object > Relations > Pass Index (the IndexOB pass)
    lightgroup: int = 0  # its emission's light group (lightgroup_number)

    @property
    def plain(self) -> bool:
        """Seen by every ray, not held out, pass index 0, in no light group: full() sends
        those in bulk, after all others."""
        return (self.visibility == native.VISIBLE_ALL and not self.holdout
                and self.pass_index == 0 and self.lightgroup == 0)


# (row, mesh id, object name, triangles, flags, (open, close) or None)
Placement = tuple[int, int, str, int, ObjectFlags, Any]


def holdout(ob: Any, view_layer: Any) -> bool:
    """Object > Visibility > Holdout, or a holdout collection in the view layer."""
    if getattr(ob, "is_holdout", False):
        return True
    original = getattr(ob, "original", None) or ob
    try:
        return bool(original.holdout_get(view_layer=view_layer))
    except (TypeError, RuntimeError, AttributeError):
        return False


def identity(ob: Any) -> tuple[int, int]:
    """What an object draws: its original object and its evaluated data. Stable across the
    temporary objects depsgraph iteration hands out for instances (their pointers are reused)."""
    original = getattr(ob, "original", None) or ob
    data = ob.data
    return (original.as_pointer(), data.as_pointer() if data is not None else 0)


def original_pointer(ob: Any | None) -> int:
    """The pointer of the original data-block of `ob` (0 for None): what depsgraph updates
    name."""
    if ob is None:
        return 0
    return (getattr(ob, "original", None) or ob).as_pointer()


def lightgroup_numbers(view_layer: Any) -> dict[str, int]:
    """The native light group of each of the view layer's light groups (Cycles' Combined_<name>
    passes, in its order): 1, 2, ...; a name not listed is in none (0)."""
    groups = getattr(view_layer, "lightgroups", None) or ()
    return {group.name: k for k, group in enumerate(groups, start=1)}


class InstanceFlags:
    """ObjectFlags per (object identity, instancer), cached: 10 000 instances of one object
    should not read its properties 10 000 times."""

    def __init__(self, view_layer: Any) -> None:
        self._view_layer = view_layer
        self._lightgroups = lightgroup_numbers(view_layer)
        self._cache: dict[tuple[tuple[int, int], int], ObjectFlags] = {}

    def get(self, ob: Any, ident: tuple[int, int], parent: Any | None) -> ObjectFlags:
        key = (ident, parent.as_pointer() if parent is not None else 0)
        found = self._cache.get(key)
        if found is None:
            # Cycles (blender/object.cpp): an instance is visible to the rays both it and its
            # instancer are visible to, held out if either is and a shadow catcher if either
            # is; its pass index is its own object's.
            visibility = object_visibility(ob)
            held_out = holdout(ob, self._view_layer)
            if parent is not None:
                catcher = (visibility | object_visibility(parent)) & native.VISIBLE_SHADOW_CATCHER
                visibility = (visibility & object_visibility(parent)) | catcher
                held_out = held_out or holdout(parent, self._view_layer)
            # Cycles: the object's light group, else its instancer's.
            group = getattr(ob, "lightgroup", "") or getattr(parent, "lightgroup", "")
            found = ObjectFlags(visibility, held_out, int(getattr(ob, "pass_index", 0)),
                                self._lightgroups.get(group, 0))
            self._cache[key] = found
        return found


def check_finite(transforms: np.ndarray, names: Sequence[str]) -> None:
    """ExportError naming the object of the first transform (N, 4, 4) with a NaN or infinite
    element; names[i] is the object of transforms[i]."""
    finite = np.isfinite(transforms).all(axis=(1, 2))
    if not finite.all():
        i = int(np.flatnonzero(~finite)[0])
        element, value = first_non_finite(transforms[i]) or (0, 0.0)
        raise ExportError(f"Object '{names[i]}': transform element {element} = {value:g} is "
                          "not finite")


def warn_degenerate(name: str, summary: ExportSummary) -> None:
    summary.warn(f"Object '{name}': its transform has (nearly) zero scale along some axis (a "
                 "linear part too close to singular to trace); skipped")


def renderable(placed: list[Placement], matrices: np.ndarray,
               summary: ExportSummary) -> list[bool]:
    """Per placement, whether its transforms can be rendered. A NaN or infinite element is an
    ExportError naming the object; a degenerate transform (placement.py) is skipped
    with a warning naming the object."""
    if not placed:
        return []
    first = matrices[[p[0] for p in placed]]
    moving = [i for i, p in enumerate(placed) if p[5] is not None]
    ends = np.empty((0, 4, 4), dtype=np.float32)
    if moving:
        first[moving] = np.stack([placed[i][5][0] for i in moving])
        ends = np.stack([placed[i][5][1] for i in moving])
    check_finite(first, [p[2] for p in placed])
    check_finite(ends, [placed[i][2] for i in moving])
    skip = degenerate(first)
    skip[moving] |= degenerate(ends)
    for i in np.flatnonzero(skip):
        warn_degenerate(placed[i][2], summary)
    return [not s for s in skip.tolist()]


def _rotate(x: int, k: int) -> int:
    return ((x << k) | (x >> (32 - k))) & 0xFFFFFFFF


def object_random_id(name: str) -> int:
    """Cycles' random_id of an object that is not an instance: lookup3's hash_uint2 of the
    name's hash_string (i = 37 i + byte over the UTF-8 name) and 0, the value Object Info's
    Random scales (measured: Cycles 3.4 renders Random 0.1357643 for "Plane", which this gives).
    Instances carry their own (DepsgraphObjectInstance.random_id)."""
    key = 0
    for byte in name.encode("utf-8"):
        key = (key * 37 + byte) & 0xFFFFFFFF
    mask = 0xFFFFFFFF
    a = b = c = (0xDEADBEEF + (2 << 2) + 13) & mask
    a = (a + key) & mask
    # lookup3's final(a, b, c)
    c ^= b
    c = (c - _rotate(b, 14)) & mask
    a ^= c
    a = (a - _rotate(c, 11)) & mask
    b ^= a
    b = (b - _rotate(a, 25)) & mask
    c ^= b
    c = (c - _rotate(b, 16)) & mask
    a ^= c
    a = (a - _rotate(c, 4)) & mask
    b ^= a
    b = (b - _rotate(a, 14)) & mask
    c ^= b
    c = (c - _rotate(b, 24)) & mask
    return c
