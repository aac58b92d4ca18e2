"""Scene export: evaluated depsgraph -> native.Scene, numpy arrays only.

    summary = export_scene(depsgraph, native_scene)

Meshes are exported once per distinct evaluated geometry and placed by one instance per
object instance (object, collection instance, particle/geometry-nodes instance).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from .. import native
from .camera import convert_camera
from .common import ExportCancelled, ExportError, ExportSummary, matrix_to_array
from .lights import convert_light
from .materials import MaterialTable, convert_material
from .meshes import (
    GEOMETRY_TYPES,
    mesh_arrays,
    mesh_key,
    object_mesh_arrays,
    slot_material_ids,
    triangle_material_ids,
)
from .world import convert_environment, convert_world

__all__ = [
    "ExportCancelled",
    "ExportError",
    "ExportSummary",
    "convert_material",
    "export_scene",
    "mesh_arrays",
]


def export_scene(
    depsgraph: Any,
    scene: native.Scene,
    should_stop: Callable[[], bool] | None = None,
) -> ExportSummary:
    """Exports the evaluated scene of `depsgraph` into `scene`.

    Raises ExportError (message names the object) for data that cannot be rendered and
    ExportCancelled if should_stop() becomes true. Unsupported features that have a fallback
    are collected in summary.warnings (one per material / light / world)."""
    start = time.perf_counter()
    summary = ExportSummary()
    bl_scene = depsgraph.scene_eval if hasattr(depsgraph, "scene_eval") else depsgraph.scene
    materials = MaterialTable(scene, summary)
    mesh_ids: dict[tuple[Any, ...], tuple[int, int]] = {}  # key -> (mesh id, triangles)

    scene.set_camera(convert_camera(bl_scene, depsgraph))
    scene.set_background(convert_world(bl_scene, summary))
    environment = convert_environment(bl_scene, summary)
    if environment is not None:
        scene.set_environment(environment.rgb, environment.strength, environment.rotation)

    for count, instance in enumerate(depsgraph.object_instances):
        if should_stop is not None and count % 64 == 0 and should_stop():
            raise ExportCancelled("export cancelled")
        ob = instance.instance_object if instance.is_instance else instance.object
        if ob is None:
            continue
        kind = ob.type
        if kind == "LIGHT":
            light = convert_light(ob, instance.matrix_world, summary)
            if light is not None:
                try:
                    scene.add_light(light)
                except native.StratumError as exc:
                    raise ExportError(f"Light '{ob.name}': {exc}") from exc
                summary.lights += 1
            continue
        if kind not in GEOMETRY_TYPES:
            continue

        matrix = matrix_to_array(instance.matrix_world)
        slot_ids = slot_material_ids(ob, materials.id_for)
        key = mesh_key(ob, tuple(int(i) for i in slot_ids))
        found = mesh_ids.get(key)
        if found is None:
            arrays = object_mesh_arrays(ob, depsgraph)
            if arrays is None or len(arrays.triangles) == 0:
                mesh_ids[key] = (-1, 0)
                continue
            mat_ids = triangle_material_ids(arrays.material_index, slot_ids)
            try:
                mesh_id = scene.add_mesh(arrays.positions, arrays.triangles, mat_ids,
                                         arrays.corner_normals, arrays.corner_uvs)
            except native.StratumError as exc:
                raise ExportError(f"Object '{ob.name}': {exc}") from exc
            found = (mesh_id, len(arrays.triangles))
            mesh_ids[key] = found
            summary.meshes += 1
            summary.triangles += found[1]
        mesh_id, n_tri = found
        if mesh_id < 0:
            continue
        try:
            scene.add_instance(mesh_id, matrix)
        except native.StratumError as exc:
            raise ExportError(f"Object '{ob.name}': {exc}") from exc
        summary.instances += 1
        summary.instanced_triangles += n_tri
        summary.object_triangles[ob.name] = n_tri
        summary.object_instances[ob.name] = summary.object_instances.get(ob.name, 0) + 1

    summary.export_seconds = time.perf_counter() - start
    return summary
