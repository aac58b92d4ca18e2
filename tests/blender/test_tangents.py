"""The exporter's MikkTSpace tangents (stratum.export.mikktspace) against Blender's own MikkTSpace
(Mesh.calc_tangents) on the same triangles: the mesh is rebuilt from its loop triangles, so
both see one input, as Cycles' MikkTSpace sees the triangulated mesh. Blender's last bits vary
between calls (the reason the exporter computes its own); angles agree within 0.1 degree,
float32's arccos resolution near 1 being about 0.03 degree."""

from __future__ import annotations

import bpy
import numpy as np
from stratum.export.mikktspace import mikktspace_tangents, tangent_space_normals


def _read(collection, attr: str, count: int, width: int, dtype) -> np.ndarray:
    out = np.empty(count * width, dtype=dtype)
    collection.foreach_get(attr, out)
    return out.reshape(count, width) if width > 1 else out


def test_tangents_match_blenders_mikktspace_on_the_triangles() -> None:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.mesh.primitive_monkey_add()  # non-planar quads, UV seams and mirrored islands
    source = bpy.context.object.data
    source.calc_loop_triangles()
    n_tri, n_loops = len(source.loop_triangles), len(source.loops)
    loops = _read(source.loop_triangles, "loops", n_tri, 3, np.int64)
    triangles = _read(source.loop_triangles, "vertices", n_tri, 3, np.int64)
    positions = _read(source.vertices, "co", len(source.vertices), 3, np.float32)
    uvs = _read(source.uv_layers[0].data, "uv", n_loops, 2, np.float32)[loops]
    mesh = bpy.data.meshes.new("triangles")
    mesh.from_pydata(positions.tolist(), [], triangles.tolist())
    mesh.uv_layers.new(name="UVMap").data.foreach_set("uv", uvs.ravel())
    for polygon in mesh.polygons:
        polygon.use_smooth = True
    mesh.update()
    mesh.calc_tangents(uvmap="UVMap")
    blender = _read(mesh.loops, "tangent", n_tri * 3, 3, np.float32).reshape(n_tri, 3, 3)
    signs = _read(mesh.loops, "bitangent_sign", n_tri * 3, 1, np.float32).reshape(n_tri, 3)
    vertex_normals = _read(mesh.vertices, "normal", len(mesh.vertices), 3, np.float32)
    ours = mikktspace_tangents(positions, triangles,
                               tangent_space_normals(positions, triangles, None, vertex_normals),
                               uvs)
    cosines = np.clip(np.sum(ours[..., :3] * blender, axis=2), -1.0, 1.0)
    worst = float(np.degrees(np.arccos(cosines)).max())
    assert worst < 0.1, f"tangents differ by up to {worst:.3f} degrees"
    assert (ours[..., 3] == signs).all()
