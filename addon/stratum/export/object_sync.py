"""Live edits of instances and lights: what SceneSync.full() placed, and what update() sends
for it when objects moved, changed visibility or holdout, or lights changed.

The depsgraph's object instances are read again, as full() reads them (Cycles' sync_objects
does the same on every update), to tell their structure is unchanged: the same objects drawing
the same data under the same instancers, row for row. Then all their transforms come in one
foreach_get and are compared bit for bit with those sent, so every instance that moved is
found, whichever object or instancer moved it; visibility and holdout are read again only for
the objects Blender reports as changed, and lights only for those objects and light data.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import numpy as np

from .. import native
from .common import (
    ExportSummary,
    FullExportNeeded,
    instance_matrices,
    named_edit,
)
from .instances import (
    InstanceFlags,
    ObjectFlags,
    Placement,
    check_finite,
    identity,
    original_pointer,
    warn_degenerate,
)
from .lights import ConvertedLight, convert_light
from .placement import degenerate
from .updates import Changes

# Per depsgraph row: what it draws (instances.identity) and the original pointer of its
# instancer (0 for none); None for a row full() skipped.
RowSignature = tuple[tuple[int, int], int] | None


def row_signature(ident: tuple[int, int], parent: Any | None) -> RowSignature:
    return (ident, original_pointer(parent))


@dataclass
class ExportedObjects:
    """The rows, instances and lights full() sent, as update() last left them."""

    motion_blur: bool
    rows: list[RowSignature] = field(default_factory=list)
    lights: dict[int, int | None] = field(default_factory=dict)  # row -> light index or None
    sent_lights: list[tuple[Any, ...]] = field(default_factory=list)  # ConvertedLight.key()
    light_programs: dict[int, int] = field(default_factory=dict)  # light index -> program id
    # Per placement (a geometry row), in full()'s order:
    instance_rows: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=np.intp))
    indices: list[int] = field(default_factory=list)  # native instance index; -1: degenerate
    mesh_ids: list[int] = field(default_factory=list)
    names: list[str] = field(default_factory=list)
    flags: list[ObjectFlags] = field(default_factory=list)
    matrices: np.ndarray = field(default_factory=lambda: np.empty((0, 4, 4), np.float32))
    positions: dict[int, int] = field(default_factory=dict)  # row -> placement

    def record(self, placed: list[Placement], indices: list[int], matrices: np.ndarray) -> None:
        """The placements full() made, their native indices and the current frame's
        transforms of every row."""
        self.instance_rows = np.array([p[0] for p in placed], dtype=np.intp)
        self.indices = indices
        self.mesh_ids = [p[1] for p in placed]
        self.names = [p[2] for p in placed]
        self.flags = [p[4] for p in placed]
        self.matrices = matrices[self.instance_rows]
        self.positions = {p[0]: position for position, p in enumerate(placed)}


def object_edits(depsgraph: Any, changes: Changes, exported: ExportedObjects, scene: Any,
                 summary: ExportSummary) -> list[Callable[[], None]]:
    """set_instance and set_light edits for what `changes` reports; FullExportNeeded for what
    they cannot express (sync.py)."""
    if not (changes.objects or changes.light_data or changes.collections or changes.scene):
        return []
    # Holdout collections and the view layer are not per object: read every object again.
    every_object = changes.collections or changes.scene
    flags = InstanceFlags(getattr(depsgraph, "view_layer", None))
    reflagged: dict[int, ObjectFlags] = {}  # placement -> flags now
    lights: list[tuple[int, str, ConvertedLight | None]] = []  # row, name, light now
    rows: list[RowSignature] = []
    for row, instance in enumerate(depsgraph.object_instances):
        is_instance = instance.is_instance
        ob = instance.object
        if ob is None or not (is_instance or instance.show_self):
            rows.append(None)
            continue
        ident = identity(ob)
        parent = instance.parent if is_instance else None
        signature = row_signature(ident, parent)
        rows.append(signature)
        changed = every_object or ident[0] in changes.objects or signature[1] in changes.objects
        if ob.type == "LIGHT":
            if changed or original_pointer(ob.data) in changes.light_data:
                light_flags = flags.get(ob, ident, parent)
                lights.append((row, ob.name,
                               convert_light(ob, instance.matrix_world, light_flags.visibility,
                                             summary, light_flags.lightgroup)))
        elif changed and row in exported.positions:
            reflagged[exported.positions[row]] = flags.get(ob, ident, parent)
    if rows != exported.rows:
        raise FullExportNeeded("objects were added, removed, shown, hidden or instanced "
                               "differently")
    return _light_edits(lights, exported, scene) + \
        _instance_edits(instance_matrices(depsgraph, len(rows)), reflagged, exported, scene,
                        summary)


def _light_edits(lights: list[tuple[int, str, ConvertedLight | None]],
                 exported: ExportedObjects, scene: Any) -> list[Callable[[], None]]:
    edits = []
    for row, name, light in lights:
        index = exported.lights.get(row)
        if (light is None) != (index is None):
            now = "is no longer" if light is None else "is now"
            raise FullExportNeeded(f"Light '{name}' {now} rendered")
        if light is None or index is None:
            continue
        program_id = exported.light_programs.get(index)
        if (light.program is None) != (program_id is None):
            # A program is added to the scene's structure only by a full export.
            now = "no longer depend" if light.program is None else "now depend"
            raise FullExportNeeded(f"Light '{name}': its nodes {now} on the distance to it")
        sent = light.key()
        if sent != exported.sent_lights[index]:
            exported.sent_lights[index] = sent
            edits.append(named_edit(f"Light '{name}'",
                                    partial(_send_light, scene, index, light, program_id)))
    return edits


def _send_light(scene: Any, index: int, light: ConvertedLight, program_id: int | None) -> None:
    """Light `index` made `light`: the light, and its program replaced in place."""
    scene.set_light(index, light.light)
    if light.program is not None and program_id is not None:
        scene.set_shader_program(program_id, light.program.program)
        scene.set_light_program(index, program_id, light.program.register)


def _instance_edits(matrices: np.ndarray, reflagged: dict[int, ObjectFlags],
                    exported: ExportedObjects, scene: Any,
                    summary: ExportSummary) -> list[Callable[[], None]]:
    now = matrices[exported.instance_rows]
    # Bit for bit: a -0.0 that replaced a 0.0 is sent too, as a fresh export would send it.
    moved = (now.view(np.uint32) != exported.matrices.view(np.uint32)).any(axis=(1, 2))
    changed = sorted({*np.flatnonzero(moved).tolist(),
                      *(i for i, f in reflagged.items() if f != exported.flags[i])})
    if not changed:
        return []
    names = exported.names
    if exported.motion_blur:
        raise FullExportNeeded(f"Object '{names[changed[0]]}' changed with motion blur on (its "
                               "transforms over the shutter need other frames evaluated)")
    check_finite(now[changed], [names[i] for i in changed])
    edits = []
    for i, skipped in zip(changed, degenerate(now[changed]).tolist(), strict=True):
        if skipped != (exported.indices[i] < 0):
            scale = "now" if skipped else "no longer"
            raise FullExportNeeded(f"Object '{names[i]}': the scale of its transform along some "
                                   f"axis is {scale} (nearly) zero, which decides whether it "
                                   "is placed")
        flags = reflagged.get(i, exported.flags[i])
        if flags.plain != exported.flags[i].plain:
            raise FullExportNeeded(f"Object '{names[i]}': its ray visibility, holdout or pass "
                                   "index changed between all rays, not held out, index 0 and "
                                   "anything else")
        exported.matrices[i] = now[i]
        exported.flags[i] = flags
        if skipped:
            warn_degenerate(names[i], summary)
            continue
        instance = native.Instance(exported.mesh_ids[i], now[i], None, *flags)
        edits.append(named_edit(f"Object '{names[i]}'",
                                partial(scene.set_instance, exported.indices[i], instance)))
    return edits
