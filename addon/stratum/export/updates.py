"""What changed since the last sync, read from a depsgraph's updates.

`depsgraph.updates` lists the data-blocks an evaluation changed, with what changed about each
(transform, geometry, shading), and only while that evaluation is being reported: inside a
RenderEngine's view_update() or a bpy.app.handlers.depsgraph_update_post handler. After
Depsgraph.update() returns it is empty again (Blender 3.4 and 5.0 alike), so whoever wants the
changes after the fact keeps them as IdUpdate records (collect_updates), which hold the
original data-blocks: those stay valid after the evaluation, its evaluated copies may not.

Blender lists the users of a changed data-block too (an object whose light, mesh or material
slots changed comes with a geometry update; since 5.0 the objects and meshes using a changed
material come with a shading update), so data-blocks that reach the export only through
others (node groups, actions, ...) need no handling of their own.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import bpy

from .meshes import GEOMETRY_TYPES

# The data of GEOMETRY_TYPES objects (Curve covers text and surfaces).
_GEOMETRY_DATA = (bpy.types.Mesh, bpy.types.Curve, bpy.types.MetaBall)


@dataclass(frozen=True)
class IdUpdate:
    """One entry of depsgraph.updates: the original data-block and what changed about it."""

    id: Any
    transform: bool
    geometry: bool
    shading: bool


def collect_updates(depsgraph: Any) -> list[IdUpdate]:
    """The depsgraph's updates as records that outlive the evaluation reporting them."""
    return [IdUpdate(getattr(u.id, "original", None) or u.id, bool(u.is_updated_transform),
                     bool(u.is_updated_geometry), bool(u.is_updated_shading))
            for u in depsgraph.updates]


@dataclass
class Changes:
    """Updates sorted by what the export does with them. Data-blocks are keyed by the pointer
    of their original."""

    objects: set[int] = field(default_factory=set)  # their instances and lights are re-read
    light_data: set[int] = field(default_factory=set)  # the lights showing them are re-read
    materials: dict[int, Any] = field(default_factory=dict)  # pointer -> original material
    images: dict[int, Any] = field(default_factory=dict)  # pointer -> original image
    worlds: bool = False
    scene: bool = False  # the scene's own settings (active camera, world, motion blur, ...)
    collections: bool = False  # membership or holdout of collections
    geometry: str = ""  # an object whose geometry changed (a full export), or ""


def sort_updates(updates: Iterable[IdUpdate]) -> Changes:
    changes = Changes()
    for update in updates:
        block = update.id
        pointer = block.as_pointer()
        if isinstance(block, bpy.types.Object):
            if update.geometry and block.type in GEOMETRY_TYPES and not changes.geometry:
                changes.geometry = f"Object '{block.name}'"
            changes.objects.add(pointer)
        elif isinstance(block, _GEOMETRY_DATA):
            if update.geometry and not changes.geometry:
                changes.geometry = f"{type(block).__name__} '{block.name}'"
        elif isinstance(block, bpy.types.Light):
            changes.light_data.add(pointer)
        elif isinstance(block, bpy.types.Material):
            changes.materials[pointer] = block
        elif isinstance(block, bpy.types.Image):
            changes.images[pointer] = block
        elif isinstance(block, bpy.types.World):
            changes.worlds = True
        elif isinstance(block, bpy.types.Scene):
            changes.scene = True
        elif isinstance(block, bpy.types.Collection):
            changes.collections = True
    return changes
