"""The meshes of evaluated objects in the native scene: each distinct evaluated geometry (with
its material assignment) sent once, with the arrays its materials need (UVs for textures,
tangents for normal maps and UV-map Tangent nodes)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import native
from .common import ExportError, ExportSummary
from .materials import MaterialTable
from .meshes import (
    GEOMETRY_TYPES,
    mesh_key,
    object_mesh_arrays,
    slot_material_ids,
    triangle_material_ids,
)

LIGHT_ID = -2  # object_geometry's mesh id for a light


def object_geometry(ob: Any, depsgraph: Any, scene: Any, materials: MaterialTable,
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
        found = add_mesh(ob, depsgraph, scene, materials, summary)
        mesh_ids[key] = found
    return found


def add_mesh(ob: Any, depsgraph: Any, scene: Any, materials: MaterialTable,
              summary: ExportSummary) -> tuple[int, int]:
    """(mesh id, triangles) of an object's evaluated geometry; (-1, 0) when it has none."""
    slot_ids = slot_material_ids(ob, materials.id_for)
    uv_map = next((materials.uv_maps.get(int(i), "") for i in slot_ids
                   if materials.uv_maps.get(int(i))), "")
    textured = bool(materials.textured.intersection(int(i) for i in slot_ids))
    programmed = bool(materials.programmed.intersection(int(i) for i in slot_ids))
    normal_mapped = bool(materials.normal_mapped.intersection(int(i) for i in slot_ids))
    uv_tangents = [t for i in dict.fromkeys(int(i) for i in slot_ids)
                   for t in materials.uv_tangents.get(i, ())]
    arrays = object_mesh_arrays(ob, depsgraph, uv_map, len(slot_ids),
                                read_uvs=textured or programmed,
                                read_tangents=normal_mapped or bool(uv_tangents),
                                attributes=dict(materials.attributes.names) if programmed else None)
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
    if arrays.uv_name:
        _check_tangent_maps(ob.name, uv_tangents, arrays.uv_name, arrays.render_uv_name, summary)
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
        for slot, (vector, rgba) in arrays.attributes.items():
            scene.set_mesh_attribute(mesh_id, slot, vector, rgba)
        texture_space = manual_texture_space(ob)
        if texture_space is not None:
            scene.set_mesh_texture_space(mesh_id, *texture_space)
    except native.StratumError as exc:
        raise ExportError(f"Object '{ob.name}': {exc}") from exc
    summary.meshes += 1
    summary.triangles += len(arrays.triangles)
    return (mesh_id, len(arrays.triangles))


def _check_tangent_maps(object_name: str, uv_tangents: list[tuple[str, str, str]],
                        carried: str, render: str, summary: ExportSummary) -> None:
    """A warning per UV-map Tangent node naming another map than the one UV map the mesh
    carries (`carried`; a node's "" is the active render map, `render`): Cycles gives that
    map's tangent (0 when the mesh has no such map), Stratum the carried one's."""
    for material, node, named in uv_tangents:
        if (named or render) != carried:
            summary.warn(f"Material '{material}': Tangent '{node}' reads UV map "
                         f"'{named or render}', but Object '{object_name}' carries one UV map, "
                         f"'{carried}', whose tangents are used")


def manual_texture_space(ob: Any) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
    """(location, size) of the object data's texture space when the user set it (Auto Texture
    Space off); None for the automatic one, the bounding box, which the renderer computes."""
    data = getattr(ob, "data", None)
    if data is None or getattr(data, "use_auto_texspace", True):
        return None
    location = getattr(data, "texspace_location", None)
    size = getattr(data, "texspace_size", None)
    if location is None or size is None:
        return None
    return tuple(float(v) for v in location), tuple(float(v) for v in size)
