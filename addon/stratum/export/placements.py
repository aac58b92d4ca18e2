"""What SceneSync.full() places, row by row of depsgraph.object_instances, and sending it.

A scene of 10 000 instances of one object has 10 000 rows that differ only in their transform:
what a row places is a template per row signature (what it draws, under which instancer),
made on the first row of that signature -- the mesh sent, the object's name and flags read --
and reused by the others. The transforms come afterwards for all rows in one foreach_get
(common.instance_matrices), and the static, plainly visible placements go to the native scene
in one call (Scene.add_instances).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import native
from .common import ExportCancelled, ExportError, ExportSummary
from .geometry import LIGHT_ID, object_geometry
from .instances import InstanceFlags, Placement
from .materials import MaterialTable
from .meshes import GEOMETRY_TYPES
from .object_sync import ExportedObjects
from .unsupported import UnsupportedObjects

UNSEEN = object()  # the template of a row signature not met yet
LIGHT_ROW = object()  # the template of a light's rows (each row sends its own light)


@dataclass
class Geometry:
    """What full() needs to add the geometry of an object it meets."""

    objects: dict[tuple[int, int], tuple[int, int]]  # identity -> (mesh id, triangles)
    mesh_ids: dict[tuple[Any, ...], tuple[int, int]]  # meshes.mesh_key -> (mesh id, triangles)
    depsgraph: Any
    scene: Any
    materials: MaterialTable
    unsupported: UnsupportedObjects
    summary: ExportSummary
    should_stop: Callable[[], bool] | None
    surfaces: bool = True  # the view layer's Filter > Surfaces (view_layer.py)


def row_template(ob: Any, ident: tuple[int, int], parent: Any | None, geometry: Geometry,
                 flags: InstanceFlags) -> Any:
    """What the rows of `ob` under `parent` place: (mesh id, object name, triangles, flags),
    LIGHT_ROW or None (nothing to draw); the mesh is added on first sight of its geometry."""
    g = geometry
    found = g.objects.get(ident)
    if found is None:
        if not g.surfaces and ob.type in GEOMETRY_TYPES:
            found = (-1, 0)
        elif g.unsupported.skip(ob):
            found = (-1, 0)
        else:
            found = object_geometry(ob, g.depsgraph, g.scene, g.materials, g.mesh_ids, g.summary)
        g.objects[ident] = found
        # A big mesh takes a tenth of a second or more to read out of Blender: Esc is honoured
        # after each one, not only every 256 instances.
        if g.should_stop is not None and found[1] > 0 and g.should_stop():
            raise ExportCancelled("export cancelled")
    mesh_id, triangles = found
    if mesh_id == LIGHT_ID:
        return LIGHT_ROW
    if mesh_id < 0:
        return None
    return (mesh_id, ob.name, triangles, flags.get(ob, ident, parent))


def place(placed: list[Placement], kept: list[bool], matrices: np.ndarray, scene: Any,
          summary: ExportSummary, exported: ExportedObjects) -> None:
    """Sends the kept placements: one add_instance_ex each for those that move, are hidden
    from some rays, held out or have a pass index, in order, then the rest in one
    add_instances; records them in `exported`."""
    plain = [keep and p[5] is None and p[4].plain for p, keep in zip(placed, kept, strict=True)]
    indices = [-1] * len(placed)
    sent = 0
    for position, (p, keep, is_plain) in enumerate(zip(placed, kept, plain, strict=True)):
        if not keep or is_plain:
            continue
        row, mesh_id, name, _, flags, moved = p
        start_m, end_m = moved if moved is not None else (matrices[row], None)
        summary.moving_instances += moved is not None
        try:
            scene.add_instance_ex(native.Instance(mesh_id, start_m, end_m, *flags))
        except native.StratumError as exc:
            raise ExportError(f"Object '{name}': {exc}") from exc
        indices[position] = sent
        sent += 1
    plain_positions = [position for position, is_plain in enumerate(plain) if is_plain]
    try:
        scene.add_instances(np.fromiter((placed[i][1] for i in plain_positions), np.uint32,
                                        len(plain_positions)),
                            matrices[[placed[i][0] for i in plain_positions]])
    except native.StratumError as exc:
        where = f"Object '{placed[plain_positions[exc.index]][2]}'" \
            if exc.index is not None else "Instances"
        raise ExportError(f"{where}: {exc}") from exc
    for offset, position in enumerate(plain_positions):
        indices[position] = sent + offset
    kept_placements = [p for p, keep in zip(placed, kept, strict=True) if keep]
    summary.instanced_triangles += sum(p[3] for p in kept_placements)
    for name, count in Counter(p[2] for p in kept_placements).items():
        summary.object_instances[name] = summary.object_instances.get(name, 0) + count
    summary.object_triangles.update((p[2], p[3]) for p in kept_placements)
    summary.instances = sent + len(plain_positions)
    exported.record(placed, indices, matrices)
