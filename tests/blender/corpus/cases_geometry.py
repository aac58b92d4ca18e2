"""Geometry: bad vertices, UVs and normals, degenerate triangles, meshes without faces,
transforms (zero, tiny, huge, negative, NaN scale and placement) of single objects and of linked
duplicates (two objects sharing one mesh, which Stratum places as Embree instances of one mesh),
motion blur to absurd placements, material indices beyond the slots."""

from __future__ import annotations

import math
from typing import Any

import bpy

from .case import case, clean, culprit, lit_centre, survive, warning
from .stage import Stage

NAN = float("nan")


def _cube_with_vertex(s: Stage, name: str, co: tuple[float, float, float]) -> None:
    s.base()
    ob = s.mesh(name, location=(2.5, 0.0, 0.0))
    ob.data.vertices[2].co = co


@case("geo_nan_vertex", "geometry", "a cube with one vertex at (0, NaN, 0)",
      culprit("NanVertex", words=("vertex", "position", "nan")))
def geo_nan_vertex(s: Stage) -> None:
    _cube_with_vertex(s, "NanVertex", (0.0, NAN, 0.0))


@case("geo_inf_vertex", "geometry", "a vertex at +inf (RNA stores FLT_MAX)",
      culprit("InfVertex", words=("vertex", "position")))
def geo_inf_vertex(s: Stage) -> None:
    _cube_with_vertex(s, "InfVertex", (math.inf, 0.0, 0.0))


@case("geo_vertex_1e30", "geometry", "a triangle with a vertex at 1e30 (vanished silently)",
      culprit("FarVertex", words=("vertex", "position")))
def geo_vertex_1e30(s: Stage) -> None:
    _cube_with_vertex(s, "FarVertex", (1e30, 0.0, 0.0))


def _degenerate_mesh(s: Stage) -> None:
    s.base()
    me = bpy.data.meshes.new("Degenerate")
    verts = [(0, 0, 0), (0, 0, 0), (0, 0, 0), (0, 0, 1), (0, 0, 2), (0, 0, 3),
             (1, 0, 0), (1, 0, 1e-30), (1, 1e-30, 0)]
    me.from_pydata(verts, [], [(0, 1, 2), (3, 4, 5), (6, 7, 8)])
    s.mesh("Degenerate", data=me, location=(0.0, -2.0, 0.0))


@case("geo_degenerate_triangles", "geometry",
      "triangles with three equal vertices, three collinear vertices, and area ~1e-60",
      clean(pixels=lit_centre))
def geo_degenerate_triangles(s: Stage) -> None:
    _degenerate_mesh(s)


def _without_faces(s: Stage, name: str, edges: bool) -> None:
    s.base()
    me = bpy.data.meshes.new(name)
    me.from_pydata([(0, 0, 0), (1, 0, 0), (1, 1, 0)], [(0, 1), (1, 2)] if edges else [], [])
    s.mesh(name, data=me, location=(0.0, -2.0, 0.0))


@case("geo_vertices_only", "geometry", "a mesh of three loose vertices",
      warning("LooseVerts", words=("face",), same_as=lambda s: s.base()))
def geo_vertices_only(s: Stage) -> None:
    _without_faces(s, "LooseVerts", edges=False)


@case("geo_loose_edges", "geometry", "a mesh of loose edges only",
      warning("WireOnly", words=("face",), same_as=lambda s: s.base()))
def geo_loose_edges(s: Stage) -> None:
    _without_faces(s, "WireOnly", edges=True)


@case("geo_empty_mesh", "geometry", "a mesh object with no vertices at all",
      clean(same_as=lambda s: s.base()))
def geo_empty_mesh(s: Stage) -> None:
    s.base()
    s.mesh("Nothing", data=bpy.data.meshes.new("Nothing"))


def _twins(s: Stage, scale: tuple[float, float, float] | None) -> Any:
    """The base scene without its cube, plus two objects sharing one mesh: 'Twin' beside the
    cube's place, and 'FlatTwin' with `scale` (omitted when scale is None: the reference)."""
    s.base(cube=False)
    shared = s.cube_data("Shared", half=0.8)
    s.mesh("Twin", data=shared, location=(-1.2, 0.0, 0.0))
    if scale is not None:
        return s.mesh("FlatTwin", data=shared, location=(1.2, 0.0, 0.0), scale=scale)
    return None


@case("geo_linked_duplicate_flat", "geometry",
      "a linked duplicate scaled (1, 0, 1): Blender aborted in Embree",
      warning("FlatTwin", same_as=lambda s: _twins(s, None)))
def geo_linked_duplicate_flat(s: Stage) -> None:
    _twins(s, (1.0, 0.0, 1.0))


@case("geo_linked_duplicate_tiny", "geometry", "a linked duplicate scaled 1e-18",
      warning("FlatTwin", same_as=lambda s: _twins(s, None)))
def geo_linked_duplicate_tiny(s: Stage) -> None:
    _twins(s, (1e-18, 1e-18, 1e-18))


@case("geo_linked_duplicate_zero", "geometry", "a linked duplicate scaled (0, 0, 0)",
      warning("FlatTwin", same_as=lambda s: _twins(s, None)))
def geo_linked_duplicate_zero(s: Stage) -> None:
    _twins(s, (0.0, 0.0, 0.0))


@case("geo_linked_duplicate_huge", "geometry", "a linked duplicate scaled 1e19",
      culprit("FlatTwin", words=("scale", "transform", "large", "bound")))
def geo_linked_duplicate_huge(s: Stage) -> None:
    _twins(s, (1e19, 1e19, 1e19))


@case("geo_linked_duplicate_nan_location", "geometry",
      "a linked duplicate with location (NaN, 0, 0)",
      culprit("FlatTwin", words=("transform", "matrix", "location", "nan", "finite")))
def geo_linked_duplicate_nan(s: Stage) -> None:
    _twins(s, (1.0, 1.0, 1.0)).location = (NAN, 0.0, 0.0)


@case("geo_nan_location", "geometry", "an object at (NaN, 0, 0) (message lacked its name)",
      culprit("NanPlaced", words=("transform", "matrix", "location", "nan", "finite")))
def geo_nan_location(s: Stage) -> None:
    s.base()
    s.mesh("NanPlaced", location=(NAN, 0.0, 0.0))


@case("geo_nan_scale", "geometry", "an object with scale (1, NaN, 1)",
      culprit("NanScaled", words=("transform", "matrix", "scale", "nan", "finite")))
def geo_nan_scale(s: Stage) -> None:
    s.base()
    s.mesh("NanScaled", location=(2.5, 0.0, 0.0), scale=(1.0, NAN, 1.0))


@case("geo_single_flat", "geometry",
      "a single (not shared) cube scaled (1, 0, 1): a flat square, placed in world space",
      clean())
def geo_single_flat(s: Stage) -> None:
    s.base(cube=False)
    s.mesh("Flattened", scale=(1.0, 0.0, 1.0))


@case("geo_negative_scale", "geometry", "a cube scaled (-1, 1, 1) (mirrored, inverted winding)",
      clean(quiet=True, pixels=lit_centre))
def geo_negative_scale(s: Stage) -> None:
    s.base(cube=False)
    s.mesh("Mirrored", scale=(-1.0, 1.0, 1.0))


@case("geo_tiny_object", "geometry", "a cube of 2e-6 m before the camera", clean(quiet=True))
def geo_tiny_object(s: Stage) -> None:
    s.base()
    s.mesh("Speck", location=(0.0, -3.0, 0.0), scale=(1e-6, 1e-6, 1e-6))


@case("geo_huge_ground", "geometry", "a ground plane 2e7 m wide under the cube",
      clean(quiet=True, pixels=lit_centre))
def geo_huge_ground(s: Stage) -> None:
    s.base()
    me = bpy.data.meshes.new("Ground")
    me.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [], [(0, 1, 2, 3)])
    s.mesh("Ground", data=me, location=(0.0, 0.0, -1.0), scale=(1e7, 1e7, 1.0))


@case("geo_object_1e19_away", "geometry", "an object 1e19 m from the origin",
      culprit("FarAway", words=("transform", "position", "location", "large", "bound", "far")))
def geo_object_1e19_away(s: Stage) -> None:
    s.base()
    s.mesh("FarAway", location=(1e19, 0.0, 0.0))


@case("geo_camera_inside_object", "geometry", "the camera inside a closed cube",
      clean(quiet=True))
def geo_camera_inside_object(s: Stage) -> None:
    s.base()
    s.mesh("Shell", location=(0.0, -6.0, 0.0), scale=(0.5, 0.5, 0.5))


@case("geo_empty_scene", "geometry", "a camera and nothing else", clean(quiet=True))
def geo_empty_scene(s: Stage) -> None:
    s.camera()


@case("geo_nan_uv", "geometry", "a textured cube whose UVs are NaN",
      culprit("NanUV", words=("uv",)))
def geo_nan_uv(s: Stage) -> None:
    image = bpy.data.images.new("Checker", 8, 8)
    image.generated_type = "COLOR_GRID"
    ob = s.textured_cube(image, name="NanUV")
    uvs = ob.data.uv_layers[0].data
    uvs.foreach_set("uv", [NAN] * (2 * len(uvs)))


def _moving(s: Stage, name: str, attribute: str, end: tuple[float, float, float]) -> None:
    """Motion blur on; object `name` (sharing its mesh with 'Cube', so it is a real Embree
    instance) keyframed from the base placement at frame 1 to `end` at frame 2."""
    s.base()
    s.scene.render.use_motion_blur = True
    s.scene.render.motion_blur_shutter = 0.5
    ob = s.mesh(name, data=bpy.data.objects["Cube"].data, location=(0.0, -2.0, 0.0),
                scale=(0.3, 0.3, 0.3))
    ob.keyframe_insert(data_path=attribute, frame=1)
    setattr(ob, attribute, end)
    ob.keyframe_insert(data_path=attribute, frame=2)
    s.scene.frame_set(1)


@case("geo_motion_to_1e19", "geometry",
      "a motion-blurred linked duplicate moving to 1e19 m over the shutter (Embree abort)",
      culprit("Streak", words=("transform", "motion", "position", "location", "large")))
def geo_motion_to_1e19(s: Stage) -> None:
    _moving(s, "Streak", "location", (1e19, 0.0, 0.0))


@case("geo_motion_scale_flt_max", "geometry",
      "a motion-blurred linked duplicate scaling to -3.4e38 (the render never finished)",
      culprit("Swell", words=("transform", "motion", "scale", "large")))
def geo_motion_scale_flt_max(s: Stage) -> None:
    _moving(s, "Swell", "scale", (-3.4e38, 1.0, 1.0))


@case("geo_motion_to_minus_flt_max", "geometry",
      "a motion-blurred linked duplicate moving to x = -3.4e38 (a 1-sample render never ended)",
      culprit("Flung", words=("transform", "motion", "position", "location", "large")))
def geo_motion_to_minus_flt_max(s: Stage) -> None:
    _moving(s, "Flung", "location", (-3.4e38, 0.0, 0.0))


@case("geo_material_index_out_of_range", "geometry",
      "faces whose material index (7) is beyond the object's one slot", clean(quiet=True))
def geo_material_index_out_of_range(s: Stage) -> None:
    s.base(cube=False)
    mat, _ = s.material("OnlySlot")
    ob = s.mesh("Cube", material=mat)
    ob.data.polygons.foreach_set("material_index", [7] * len(ob.data.polygons))


@case("geo_nan_custom_normals", "geometry", "custom split normals that are all NaN",
      survive("NanNormals", words=("normal",)))
def geo_nan_custom_normals(s: Stage) -> None:
    s.base(cube=False)
    me = s.cube_data("NanNormals")
    if hasattr(me, "use_auto_smooth"):  # before 4.1 custom normals need auto smooth
        me.use_auto_smooth = True
    me.normals_split_custom_set([(NAN, NAN, NAN)] * len(me.loops))
    s.mesh("NanNormals", data=me)
