"""Evaluated Blender geometry -> native meshes, with numpy foreach_get (no per-element loops)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .. import blender_versions
from ..shaders.nodes.input_nodes import RENDER_COLOR
from .common import ExportError
from .mikktspace import mikktspace_tangents, tangent_space_normals
from .vertex_normals import angle_weighted_vertex_normals

# Object types that to_mesh() can turn into triangles.
GEOMETRY_TYPES = {"MESH", "CURVE", "SURFACE", "FONT", "META"}


@dataclass
class MeshArrays:
    positions: np.ndarray  # (N, 3) float32
    triangles: np.ndarray  # (T, 3) uint32
    material_index: np.ndarray  # (T,) int32, the object's material slot per triangle
    corner_normals: np.ndarray | None  # (T, 3, 3) float32
    corner_uvs: np.ndarray | None  # (T, 3, 2) float32
    missing_uv: str = ""  # the UV map asked for, when the mesh has no layer of that name
    vertex_normals: np.ndarray | None = None  # (N, 3) float32, instead of corner_normals
    corner_tangents: np.ndarray | None = None  # (T, 3, 4) float32: MikkTSpace tangent, sign
    # Per attribute slot the node programs read: (whether its Fac is the mean of RGB, (T, 3, 4)
    # float32 RGBA per corner); a slot whose attribute the mesh lacks is absent.
    attributes: dict[int, tuple[bool, np.ndarray]] = field(default_factory=dict)
    uv_name: str = ""  # the UV layer corner_uvs hold ("" without UVs)
    render_uv_name: str = ""  # the mesh's active render UV layer, when UVs were read


def _get(collection: Any, attr: str, count: int, width: int, dtype: Any) -> np.ndarray:
    out = np.empty(count * width, dtype=dtype)
    if count:
        collection.foreach_get(attr, out)
    return out.reshape(count, width) if width > 1 else out


def _corner_normals(mesh: Any, n_loops: int) -> np.ndarray:
    """Per-loop (corner) normals, (L, 3)."""
    if blender_versions.has_corner_normals(mesh):
        return _get(mesh.corner_normals, "vector", n_loops, 3, np.float32)
    # Before 4.1: split normals honour use_auto_smooth (sharp edges) and smooth/flat faces.
    mesh.calc_normals_split()
    return _get(mesh.loops, "normal", n_loops, 3, np.float32)


def _vertex_normals(mesh: Any, positions: np.ndarray) -> np.ndarray | None:
    """Vertex normals (N, 3), the same floats on every export: Blender 4.1+'s own; before 4.1
    recomputed in a fixed order, because Blender's own vary in their last bits from one
    evaluation to the next (export/vertex_normals.py; None for non-finite face normals)."""
    if blender_versions.has_corner_normals(mesh):
        return _get(mesh.vertex_normals, "vector", len(positions), 3, np.float32)
    n_poly = len(mesh.polygons)
    # uint32 for all three: RNA declares them unsigned, and foreach_get copies in bulk only
    # into a buffer of that signedness (3.4.1, 1M-triangle monkey: loop_start and loop_total
    # 53 ms as int32, 5 ms as uint32).
    return angle_weighted_vertex_normals(
        positions, _get(mesh.loops, "vertex_index", len(mesh.loops), 1, np.uint32),
        _get(mesh.polygons, "loop_start", n_poly, 1, np.uint32),
        _get(mesh.polygons, "loop_total", n_poly, 1, np.uint32),
        _get(mesh.polygon_normals, "vector", n_poly, 3, np.float32))


def _all_faces_flat(mesh: Any, smooth: np.ndarray) -> bool:
    """True when every face is flat-shaded (`smooth`: use_smooth per polygon) and no custom
    normals apply: then each triangle is shaded with its own geometric normal, as Cycles does
    for triangles that are not smooth, and no corner normals need to be sent (a 1M-triangle
    flat mesh would send 36 MB of them)."""
    if blender_versions.has_corner_normals(mesh):  # custom normals apply whenever present
        if getattr(mesh, "has_custom_normals", False):
            return False
    elif mesh.use_auto_smooth:  # before 4.1 custom normals and sharp edges need auto smooth
        return False
    return len(smooth) > 0 and not smooth.any()


def _smooth_vertex_normals(mesh: Any, smooth: np.ndarray,
                           positions: np.ndarray) -> np.ndarray | None:
    """Per-vertex normals (N, 3) when they are the whole story: every face smooth and no split
    normals (4.1+: normals_domain 'POINT'; before: no auto smooth). Cycles takes such a mesh's
    normals per vertex too; a third of the floats of per-corner normals is the win."""
    if blender_versions.has_normals_domain(mesh):
        if mesh.normals_domain != "POINT":
            return None
    elif mesh.use_auto_smooth or not smooth.all():
        return None
    return _vertex_normals(mesh, positions)


def _unsplit_normals(mesh: Any, triangles: np.ndarray, polygons: Any,
                     smooth: np.ndarray, positions: np.ndarray) -> np.ndarray | None:
    """Corner normals (T, 3, 3) of a Blender < 4.1 mesh without auto smooth whose faces are
    partly smooth, partly flat (all-flat and all-smooth meshes are handled before), None for
    other meshes.

    Without auto smooth, calc_normals_split copies each corner's vertex normal (smooth face) or
    its face normal (flat face) and nothing else (3.4 mesh_normals.cc, normals_loop_split with
    use_split_normals false; custom normals are ignored then): the same normals are made here
    from the vertex normals (_vertex_normals) and polygon_normals, which skips computing and
    reading 3 normals per loop (a third of a 1M-triangle export). `polygons()` gives the
    triangles' polygon indices, fetched only when some face is flat."""
    if blender_versions.has_corner_normals(mesh) or mesh.use_auto_smooth:
        return None
    tri_poly = polygons()
    face_normals = _get(mesh.polygon_normals, "vector", len(smooth), 3, np.float32)
    flat = ~smooth[tri_poly]
    vertex_normals = _vertex_normals(mesh, positions)
    if vertex_normals is None:  # non-finite face normals: Blender's split normals are read
        return None
    normals = vertex_normals[triangles]
    normals[flat] = face_normals[tri_poly[flat]][:, None, :]
    return normals


def _uv_layer(mesh: Any, name: str) -> tuple[Any | None, bool]:
    """The UV layer `name` ("" = the active render layer, as Cycles' default UV), and whether
    a named layer was missing (then the active render layer is used)."""
    layers = mesh.uv_layers
    if name:
        layer = layers.get(name)
        if layer is not None:
            return layer, False
    render = next((layer for layer in layers if layer.active_render), None)
    return (render if render is not None else layers.active), bool(name)


def _corner_uvs(layer: Any, n_loops: int) -> np.ndarray:
    if blender_versions.uv_layer_has_uv_vectors(layer):
        return _get(layer.uv, "vector", n_loops, 2, np.float32)
    return _get(layer.data, "uv", n_loops, 2, np.float32)


def mesh_arrays(mesh: Any, object_name: str, uv_map: str = "",
                material_slots: int = 2, read_uvs: bool = True,
                read_tangents: bool = False,
                attributes: dict[str, int] | None = None) -> MeshArrays:
    """Triangulated arrays of an evaluated mesh (UVs from layer `uv_map`, "" = the active
    render layer); ExportError naming the object on bad data. With `material_slots` <= 1 every
    triangle maps to the one slot (slot indices are clamped), so material indices are not read
    and come back as zeros. With `read_uvs` false no UVs are read (corner_uvs None): as Cycles
    exports a UV attribute only for shaders that ask for it, a mesh without textures skips the
    largest per-corner array. With `read_tangents` (a normal-mapped material, or one with a
    UV-map Tangent node) and a UV layer, the layer's MikkTSpace tangents are computed too
    (mikktspace.py: on the triangles, as Cycles does, and the same bits on every export)."""
    mesh.calc_loop_triangles()
    n_vert = len(mesh.vertices)
    n_loops = len(mesh.loops)
    n_tri = len(mesh.loop_triangles)

    positions = _get(mesh.vertices, "co", n_vert, 3, np.float32)
    finite = np.isfinite(positions)
    if not finite.all():
        bad = int(np.flatnonzero(~finite.all(axis=1))[0])
        value = tuple(float(v) for v in positions[bad])
        raise ExportError(
            f"Object '{object_name}' has a non-finite vertex position (NaN or Inf): "
            f"vertex {bad} = {value}"
        )

    # uint32: the dtype of Blender's MLoopTri fields, which foreach_get then copies in bulk
    # (int32 makes it convert element by element, 5x slower).
    triangles = _get(mesh.loop_triangles, "vertices", n_tri, 3, np.uint32)
    tri_loops: np.ndarray | None = None
    tri_polygons: np.ndarray | None = None

    def loops() -> np.ndarray:
        nonlocal tri_loops
        if tri_loops is None:
            tri_loops = _get(mesh.loop_triangles, "loops", n_tri, 3, np.uint32)
        return tri_loops

    def polygons() -> np.ndarray:
        nonlocal tri_polygons
        if tri_polygons is None:
            tri_polygons = _get(mesh.loop_triangles, "polygon_index", n_tri, 1, np.uint32)
        return tri_polygons

    if material_slots > 1:
        material_index = _get(mesh.loop_triangles, "material_index", n_tri, 1, np.int32)
    else:
        material_index = np.zeros(n_tri, dtype=np.int32)

    # use_smooth is read once: it decides between no normals (all flat), vertex normals (all
    # smooth) and corner normals (mixed, or split normals).
    normals = vertex_normals = None
    smooth = _get(mesh.polygons, "use_smooth", len(mesh.polygons), 1, bool)
    if n_tri and not _all_faces_flat(mesh, smooth):
        vertex_normals = _smooth_vertex_normals(mesh, smooth, positions)
        if vertex_normals is None:
            normals = _unsplit_normals(mesh, triangles, polygons, smooth, positions)
            if normals is None:
                normals = _corner_normals(mesh, n_loops)[loops()]  # (T, 3, 3)
            if not np.isfinite(normals).all():
                normals = None  # degenerate faces; let the renderer use geometric normals
        elif not np.isfinite(vertex_normals).all():
            vertex_normals = None  # the same for a smooth mesh's vertex normals
    uvs = tangents = None
    layer, missing = _uv_layer(mesh, uv_map) if read_uvs else (None, False)
    render_layer = _uv_layer(mesh, "")[0] if layer is not None else None
    if n_tri and layer is not None:
        uvs = _corner_uvs(layer, n_loops)[loops()]  # (T, 3, 2)
        if not np.isfinite(uvs).all():
            raise ExportError(f"Object '{object_name}' has non-finite UV coordinates")
        if read_tangents:
            tangents = mikktspace_tangents(
                positions, triangles,
                tangent_space_normals(positions, triangles, normals, vertex_normals), uvs)
    read = {}
    for key, slot in (attributes or {}).items():
        found = corner_attribute(mesh, key, triangles, loops, polygons) if n_tri else None
        if found is not None:
            read[slot] = found
    return MeshArrays(positions, triangles, material_index, normals, uvs,
                      uv_map if missing else "", vertex_normals, tangents, read,
                      layer.name if uvs is not None else "",
                      render_layer.name if render_layer is not None else "")


# Attribute data types: (RNA field, components, whether Fac is the mean of RGB).
ATTRIBUTE_FIELDS = {
    "FLOAT": ("value", 1, False), "INT": ("value", 1, False), "BOOLEAN": ("value", 1, False),
    "INT8": ("value", 1, False), "FLOAT2": ("vector", 2, False),
    "FLOAT_VECTOR": ("vector", 3, True),
    "FLOAT_COLOR": ("color", 4, True), "BYTE_COLOR": ("color", 4, True),
}


def corner_attribute(mesh: Any, key: str, triangles: np.ndarray, loops: Any,
                     polygons: Any) -> tuple[bool, np.ndarray] | None:
    """Attribute `key` of the mesh per triangle corner as RGBA ((T, 3, 4) float32), as Cycles
    reads it for the Attribute and Color Attribute nodes: a scalar repeated in RGB, a 2-vector
    (x, y, 0), alpha 1 unless it is a colour (scene linear, Blender's `color`); point, corner and
    face domains; None when the mesh has no such attribute (the node then reads Cycles' missing
    attribute). A UV map's name reads its UVs (Blender 3.4 keeps UV maps apart from attributes)."""
    if key == RENDER_COLOR:
        colors = getattr(mesh, "color_attributes", None)
        index = getattr(colors, "render_color_index", -1) if colors is not None else -1
        attribute = colors[index] if colors is not None and 0 <= index < len(colors) else None
    else:
        attribute = mesh.attributes.get(key) if key else None
    n_tri = len(triangles)
    if attribute is None:
        layer = mesh.uv_layers.get(key) if key else None
        if layer is None:
            return None
        uv = _get(layer.data, "uv", len(mesh.loops), 2, np.float32)[loops()]
        rgba = np.concatenate([uv, np.zeros((n_tri, 3, 1), np.float32),
                               np.ones((n_tri, 3, 1), np.float32)], axis=2)
        return False, np.ascontiguousarray(rgba)
    spec = ATTRIBUTE_FIELDS.get(attribute.data_type)
    if spec is None or attribute.domain not in ("POINT", "CORNER", "FACE"):
        return None
    name, width, vector = spec
    values = _get(attribute.data, name, len(attribute.data), width, np.float32).reshape(-1, width)
    if attribute.domain == "POINT":
        corners = values[triangles]
    elif attribute.domain == "CORNER":
        corners = values[loops()]
    else:
        corners = np.repeat(values[polygons()][:, None, :], 3, axis=1)
    rgba = np.ones((n_tri, 3, 4), np.float32)
    if width == 1:
        rgba[:, :, :3] = corners
    elif width == 2:
        rgba[:, :, :2] = corners
        rgba[:, :, 2] = 0.0
    else:
        rgba[:, :, :width] = corners
    return vector, np.nan_to_num(rgba, nan=0.0, posinf=0.0, neginf=0.0)


def _readable_mesh_data(ob_eval: Any) -> Any | None:
    """The evaluated mesh of a mesh object when it can be read in place, else None (then
    to_mesh makes a copy, 10% of a 1M-triangle export). As Cycles 3.4 (blender/util.h
    object_to_mesh) does: in place unless in edit mode (its evaluated layers can be empty) or,
    before 4.1, with auto smooth, where calc_normals_split would write into the shared mesh.
    Reading adds only Blender's own runtime caches (loop triangles, normals)."""
    if ob_eval.type != "MESH":
        return None
    data = ob_eval.data
    if data is None or data.is_editmode:
        return None
    if not blender_versions.has_corner_normals(data) and data.use_auto_smooth:
        return None
    return data


def object_mesh_arrays(ob: Any, depsgraph: Any, uv_map: str = "",
                       material_slots: int = 2, read_uvs: bool = True,
                       read_tangents: bool = False,
                       attributes: dict[str, int] | None = None) -> MeshArrays | None:
    """Evaluated, triangulated geometry of an object (None if it has no surface);
    `material_slots` as in mesh_arrays."""
    # Depsgraph instances are evaluated already (and temporary: evaluated_get would find the
    # instancer of a geometry-nodes instance, not the instance's own data).
    evaluated = getattr(ob, "is_evaluated", False) or depsgraph is None
    ob_eval = ob if evaluated else ob.evaluated_get(depsgraph)
    shared = _readable_mesh_data(ob_eval)
    if shared is not None:
        return mesh_arrays(shared, ob.name, uv_map, material_slots, read_uvs, read_tangents,
                           attributes)
    try:
        mesh = ob_eval.to_mesh()
    except RuntimeError as exc:
        raise ExportError(f"Object '{ob.name}': cannot convert to a mesh: {exc}") from exc
    if mesh is None:
        return None
    try:
        return mesh_arrays(mesh, ob.name, uv_map, material_slots, read_uvs, read_tangents,
                           attributes)
    finally:
        ob_eval.to_mesh_clear()


def mesh_key(ob: Any, slot_ids: tuple[int, ...]) -> tuple[Any, ...]:
    """Deduplication key: the evaluated geometry (plus materials). A mesh object's evaluated
    data is shared by every object (and instance) showing the same geometry, and is its own
    for an object whose modifiers changed it; other types are keyed by the original object."""
    data = getattr(ob, "data", None)
    if ob.type == "MESH" and data is not None:
        return ("data", data.as_pointer(), slot_ids)
    original = getattr(ob, "original", None) or ob
    return ("object", original.as_pointer(), slot_ids)


def slot_material_ids(ob: Any, id_for: Any) -> np.ndarray:
    """Scene material id per material slot of `ob` (at least one entry: the default)."""
    slots = [slot.material for slot in ob.material_slots]
    if not slots:
        return np.array([id_for(None)], dtype=np.uint32)
    return np.array([id_for(m) for m in slots], dtype=np.uint32)


def triangle_material_ids(material_index: np.ndarray, slot_ids: np.ndarray) -> np.ndarray:
    if len(slot_ids) == 1:  # every index clamps to the one slot
        return np.full(len(material_index), slot_ids[0], dtype=np.uint32)
    idx = np.clip(material_index, 0, len(slot_ids) - 1)
    return np.ascontiguousarray(slot_ids.take(idx), dtype=np.uint32)


__all__ = [
    "GEOMETRY_TYPES",
    "MeshArrays",
    "mesh_arrays",
    "mesh_key",
    "object_mesh_arrays",
    "slot_material_ids",
    "triangle_material_ids",
]
