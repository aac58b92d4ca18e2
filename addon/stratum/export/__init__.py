"""Scene export: evaluated depsgraph -> native.Scene, numpy arrays only.

    summary = export_scene(depsgraph, native_scene, should_stop, frame_set)

Every mesh is sent once per distinct evaluated geometry (and material assignment) and placed by
one instance per depsgraph object instance (objects, collection instances, particle and
geometry-nodes instances). Instances carry the object's ray visibility and holdout (Object >
Visibility in Cycles) and, with motion blur, the transforms at shutter open and close.
Collections excluded from the view layer or disabled for render never reach
depsgraph.object_instances, so nothing else is needed for them. Objects Stratum does not render
are reported once per kind (unsupported.py); transforms are checked before they reach the
native scene (stratum/placement.py).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np

from .. import native
from ..placement import degenerate, first_non_finite
from .camera import convert_camera
from .common import ExportCancelled, ExportError, ExportSummary, instance_matrices
from .lights import convert_light, object_visibility
from .materials import MaterialTable, convert_material
from .meshes import (
    GEOMETRY_TYPES,
    mesh_arrays,
    mesh_key,
    object_mesh_arrays,
    slot_material_ids,
    triangle_material_ids,
)
from .motion import instance_key, shutter_transforms
from .unsupported import UnsupportedObjects
from .world import convert_environment, convert_world

__all__ = [
    "ExportCancelled",
    "ExportError",
    "ExportSummary",
    "convert_material",
    "export_scene",
    "mesh_arrays",
]


def _holdout(ob: Any, view_layer: Any) -> bool:
    """Object > Visibility > Holdout, or a holdout collection in the view layer."""
    if getattr(ob, "is_holdout", False):
        return True
    original = getattr(ob, "original", None) or ob
    try:
        return bool(original.holdout_get(view_layer=view_layer))
    except (TypeError, RuntimeError, AttributeError):
        return False


def _identity(ob: Any) -> tuple[int, int]:
    """What an object draws: its original object and its evaluated data. Stable across the
    temporary objects depsgraph iteration hands out for instances (their pointers are reused)."""
    original = getattr(ob, "original", None) or ob
    data = ob.data
    return (original.as_pointer(), data.as_pointer() if data is not None else 0)


class _InstanceFlags:
    """Visibility and holdout per (object identity, instancer), cached: 10 000 instances of
    one object should not read its properties 10 000 times."""

    def __init__(self, view_layer: Any) -> None:
        self._view_layer = view_layer
        self._cache: dict[tuple[tuple[int, int], int], tuple[int, bool]] = {}

    def get(self, ob: Any, ident: tuple[int, int], parent: Any | None) -> tuple[int, bool]:
        key = (ident, parent.as_pointer() if parent is not None else 0)
        found = self._cache.get(key)
        if found is None:
            # Cycles (blender/object.cpp): an instance is visible to the rays both it and its
            # instancer are visible to, and held out if either is.
            visibility = object_visibility(ob)
            holdout = _holdout(ob, self._view_layer)
            if parent is not None:
                visibility &= object_visibility(parent)
                holdout = holdout or _holdout(parent, self._view_layer)
            found = (visibility, holdout)
            self._cache[key] = found
        return found


def export_scene(
    depsgraph: Any,
    scene: Any,
    should_stop: Callable[[], bool] | None = None,
    frame_set: Callable[[int, float], None] | None = None,
) -> ExportSummary:
    """Exports the evaluated scene of `depsgraph` into `scene` (a native.Scene).

    Raises ExportError (message names the object) for data that cannot be rendered and
    ExportCancelled if should_stop() becomes true. Unsupported features that have a fallback
    are collected in summary.warnings (one per material node / light / world / object).
    frame_set(frame, subframe) re-evaluates the depsgraph at another time (RenderEngine.frame_set
    during a render); it is needed for motion blur only."""
    start = time.perf_counter()
    summary = ExportSummary()
    bl_scene = depsgraph.scene_eval if hasattr(depsgraph, "scene_eval") else depsgraph.scene
    materials = MaterialTable(scene, summary)
    mesh_ids: dict[tuple[Any, ...], tuple[int, int]] = {}  # key -> (mesh id, triangles)
    motion = shutter_transforms(depsgraph, bl_scene, frame_set, summary.warn)

    try:
        # Blender clamps lens to >= 1 mm, so a zero focal length comes only from files other
        # tools wrote; the native side rejects it (and any other bad value) by name.
        scene.set_camera(convert_camera(bl_scene, depsgraph))
    except native.StratumError as exc:
        raise ExportError(f"Camera '{bl_scene.camera.name}': {exc}") from exc
    try:
        scene.set_background(convert_world(bl_scene, summary))
        environment = convert_environment(bl_scene, summary)
        if environment is not None:
            scene.set_environment(environment.rgb, environment.strength, environment.rotation)
    except native.StratumError as exc:
        raise ExportError(f"World '{getattr(bl_scene.world, 'name', '')}': {exc}") from exc

    flags = _InstanceFlags(getattr(depsgraph, "view_layer", None))
    unsupported = UnsupportedObjects()
    # Per geometry identity (original object, evaluated data): (mesh id, triangles); LIGHT_ID
    # for lights, -1 for nothing to draw.
    objects: dict[tuple[int, int], tuple[int, int]] = {}
    placed: list[Placement] = []
    index = -1
    for index, instance in enumerate(depsgraph.object_instances):
        if should_stop is not None and index % 256 == 0 and should_stop():
            raise ExportCancelled("export cancelled")
        is_instance = instance.is_instance
        # instance.object is what is drawn: for an instance, a temporary object (valid during
        # this iteration only) that carries the instance's own data -- a geometry-nodes
        # instance of mesh data has no object of its own (instance_object is its instancer).
        ob = instance.object
        # show_self is off for an instancer whose own geometry is hidden in renders (Cycles
        # skips those too: blender/object.cpp).
        if ob is None or not (is_instance or instance.show_self):
            continue
        ident = _identity(ob)
        found = objects.get(ident)
        if found is None:
            found = (-1, 0) if unsupported.skip(ob) else \
                _object_geometry(ob, depsgraph, scene, materials, mesh_ids, summary)
            objects[ident] = found
            # A big mesh takes a tenth of a second or more to read out of Blender: Esc is
            # honoured after each one, not only every 256 instances.
            if should_stop is not None and found[1] > 0 and should_stop():
                raise ExportCancelled("export cancelled")
        mesh_id = found[0]
        parent = instance.parent if is_instance else None
        if mesh_id == LIGHT_ID:
            _add_light(ob, instance, flags.get(ob, ident, parent)[0], scene, summary)
        elif mesh_id >= 0:
            moved = motion.get(instance_key(instance, ob)) if motion else None
            visibility, holdout = flags.get(ob, ident, parent)
            placed.append((index, mesh_id, ob.name, found[1], visibility, holdout, moved))
    unsupported.report(summary)
    matrices = instance_matrices(depsgraph, index + 1)
    placed = _renderable(placed, matrices, summary)

    plain_ids: list[int] = []
    plain_rows: list[int] = []
    plain_names: list[str] = []
    for row, mesh_id, name, n_tri, visibility, holdout, moved in placed:
        if moved is None and visibility == native.VISIBLE_ALL and not holdout:
            plain_ids.append(mesh_id)
            plain_rows.append(row)
            plain_names.append(name)
        else:
            start_m, end_m = moved if moved is not None else (matrices[row], None)
            summary.moving_instances += moved is not None
            try:
                scene.add_instance_ex(native.Instance(mesh_id, start_m, end_m, visibility,
                                                      holdout))
            except native.StratumError as exc:
                raise ExportError(f"Object '{name}': {exc}") from exc
        summary.instanced_triangles += n_tri
        summary.object_instances[name] = summary.object_instances.get(name, 0) + 1
        summary.object_triangles[name] = n_tri
    try:
        scene.add_instances(np.asarray(plain_ids, dtype=np.uint32), matrices[plain_rows])
    except native.StratumError as exc:
        where = f"Object '{plain_names[exc.index]}'" if exc.index is not None else "Instances"
        raise ExportError(f"{where}: {exc}") from exc
    summary.instances = len(placed)

    summary.textures = materials.textures.count
    summary.export_seconds = time.perf_counter() - start
    return summary


LIGHT_ID = -2
# (row, mesh id, object name, triangles, visibility, holdout, (open, close) or None)
Placement = tuple[int, int, str, int, int, bool, Any]


def _renderable(placed: list[Placement], matrices: np.ndarray,
                summary: ExportSummary) -> list[Placement]:
    """The placements whose transforms can be rendered. A NaN or infinite element is an
    ExportError naming the object; a degenerate transform (stratum/placement.py) is skipped
    with a warning naming the object."""
    if not placed:
        return placed
    first = matrices[[p[0] for p in placed]]
    moving = [i for i, p in enumerate(placed) if p[6] is not None]
    ends = np.empty((0, 4, 4), dtype=np.float32)
    if moving:
        first[moving] = np.stack([placed[i][6][0] for i in moving])
        ends = np.stack([placed[i][6][1] for i in moving])
    for transforms, owners in ((first, range(len(placed))), (ends, moving)):
        finite = np.isfinite(transforms).all(axis=(1, 2))
        if not finite.all():
            i = int(np.flatnonzero(~finite)[0])
            element, value = first_non_finite(transforms[i]) or (0, 0.0)
            raise ExportError(f"Object '{placed[owners[i]][2]}': transform element {element} = "
                              f"{value:g} is not finite")
    skip = degenerate(first)
    skip[moving] |= degenerate(ends)
    for i in np.flatnonzero(skip):
        summary.warn(f"Object '{placed[i][2]}': its transform has (nearly) zero scale along some "
                     "axis (a linear part too close to singular to trace); skipped")
    return [p for p, s in zip(placed, skip, strict=True) if not s]


def _object_geometry(ob: Any, depsgraph: Any, scene: Any, materials: MaterialTable,
                     mesh_ids: dict[tuple[Any, ...], tuple[int, int]],
                     summary: ExportSummary) -> tuple[int, int]:
    """(mesh id, triangles) of an evaluated object, its mesh added on first sight of its
    geometry; (LIGHT_ID, 0) for a light, (-1, 0) for nothing to draw."""
    kind = ob.type
    if kind == "LIGHT":
        return (LIGHT_ID, 0)
    if kind not in GEOMETRY_TYPES:
        return (-1, 0)
    slot_ids = slot_material_ids(ob, materials.id_for)
    key = mesh_key(ob, tuple(int(i) for i in slot_ids))
    found = mesh_ids.get(key)
    if found is None:
        found = _add_mesh(ob, depsgraph, scene, materials, summary)
        mesh_ids[key] = found
    return found


def _add_light(ob: Any, instance: Any, visibility: int, scene: Any,
               summary: ExportSummary) -> None:
    light = convert_light(ob, instance.matrix_world, visibility, summary)
    if light is None:
        return
    try:
        scene.add_light(light)
    except native.StratumError as exc:
        raise ExportError(f"Light '{ob.name}': {exc}") from exc
    summary.lights += 1


def _add_mesh(ob: Any, depsgraph: Any, scene: Any, materials: MaterialTable,
              summary: ExportSummary) -> tuple[int, int]:
    """(mesh id, triangles) of an object's evaluated geometry; (-1, 0) when it has none."""
    slot_ids = slot_material_ids(ob, materials.id_for)
    uv_map = next((materials.uv_maps.get(int(i), "") for i in slot_ids
                   if materials.uv_maps.get(int(i))), "")
    textured = bool(materials.textured.intersection(int(i) for i in slot_ids))
    normal_mapped = bool(materials.normal_mapped.intersection(int(i) for i in slot_ids))
    arrays = object_mesh_arrays(ob, depsgraph, uv_map, len(slot_ids), read_uvs=textured,
                                read_tangents=normal_mapped)
    if arrays is None or len(arrays.triangles) == 0:
        # A vertex/face instancer's own mesh often has no faces on purpose; a mesh without
        # vertices is empty (e.g. geometry nodes turned it into points, reported as such).
        if ob.type == "MESH" and not getattr(ob, "is_instancer", False) and \
                arrays is not None and len(arrays.positions):
            summary.warn(f"Object '{ob.name}': mesh has no faces (skipped)")
        return (-1, 0)
    if arrays.missing_uv:
        summary.warn(f"Object '{ob.name}': UV map '{arrays.missing_uv}' not found; "
                     "using the active render UV map")
    mat_ids = triangle_material_ids(arrays.material_index, slot_ids)
    uvs = arrays.corner_uvs
    if uvs is None and textured:
        # Cycles reads a missing UV attribute as (0, 0): textures show their corner texel.
        summary.warn(f"Object '{ob.name}': no UV map for its image textures; using UV (0, 0)")
        uvs = np.zeros((len(arrays.triangles), 3, 2), dtype=np.float32)
    try:
        mesh_id = scene.add_mesh(arrays.positions, arrays.triangles, mat_ids,
                                 arrays.corner_normals, uvs, arrays.vertex_normals,
                                 arrays.corner_tangents)
    except native.StratumError as exc:
        raise ExportError(f"Object '{ob.name}': {exc}") from exc
    summary.meshes += 1
    summary.triangles += len(arrays.triangles)
    return (mesh_id, len(arrays.triangles))

