"""Scene export from the evaluated depsgraph (uses a recording stand-in for native.Scene, so
these tests run even before the native library is built)."""

from __future__ import annotations

import math
from typing import Any

import bpy
import numpy as np
import pytest
from stratum import native
from stratum.export.common import ExportError
from stratum.export.materials import convert_material
from stratum.export.sync import export_scene


def test_basic_scene(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.meshes == 1 and summary.instances == 1
    assert summary.triangles == 12
    assert summary.lights == 1
    mesh = recording_scene.meshes[0]
    assert mesh["positions"].shape == (8, 3) and mesh["positions"].dtype == np.float32
    assert mesh["triangles"].shape == (12, 3) and mesh["triangles"].dtype == np.uint32
    # A flat-shaded cube: every triangle is shaded with its geometric normal, as in Cycles.
    assert mesh["corner_normals"] is None
    # no material -> one default grey diffuse
    assert len(recording_scene.materials) == 1
    assert recording_scene.materials[0].model == native.closure_model("diffuse")
    assert recording_scene.materials[0].base_color == pytest.approx((0.8, 0.8, 0.8))
    cam = recording_scene.camera
    assert cam.lens_mm == pytest.approx(50.0)
    m = np.asarray(cam.transform).reshape(4, 4)
    assert m[:3, 3] == pytest.approx([0.0, -6.0, 0.0], abs=1e-5)  # row-major translation
    assert recording_scene.background == pytest.approx((0.05, 0.05, 0.05))


def test_smooth_faces_send_corner_normals(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()
    cube = b.scene.objects["Cube"].data
    for polygon in cube.polygons:
        polygon.use_smooth = True
    export_scene(b.depsgraph(), recording_scene)
    mesh = recording_scene.meshes[0]
    # all faces smooth, no split normals: one normal per vertex, as Cycles takes them
    assert mesh["corner_normals"] is None
    normals = mesh["vertex_normals"]
    assert normals.shape == (8, 3)
    assert np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-4)
    # a cube corner's smooth normal points along the diagonal
    assert np.allclose(np.abs(normals), 1.0 / np.sqrt(3.0), atol=1e-4)


def test_mixed_flat_and_smooth_faces_send_corner_normals(scene_builder: Any,
                                                         recording_scene: Any) -> None:
    b = scene_builder().basic()
    cube = b.scene.objects["Cube"].data
    for polygon in list(cube.polygons)[:3]:
        polygon.use_smooth = True
    export_scene(b.depsgraph(), recording_scene)
    mesh = recording_scene.meshes[0]
    assert mesh["vertex_normals"] is None
    normals = mesh["corner_normals"]
    assert normals.shape == (12, 3, 3)
    assert np.allclose(np.linalg.norm(normals, axis=2), 1.0, atol=1e-4)


def test_modifier_exports_evaluated_triangles(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    cube = b.mesh_object("Subdivided")
    mod = cube.modifiers.new("Subdivision", "SUBSURF")
    mod.levels = mod.render_levels = 1
    arr = b.mesh_object("Arrayed", location=(4.0, 0.0, 0.0))
    arr_mod = arr.modifiers.new("Array", "ARRAY")
    arr_mod.count = 3
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.object_triangles["Subdivided"] == 6 * 4 * 2  # 24 quads
    assert summary.object_triangles["Arrayed"] == 3 * 12
    assert summary.meshes == 2 and summary.instances == 2


def test_shared_mesh_is_exported_once(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    data = b.mesh_data("Shared")
    b.mesh_object("A", data=data, location=(-2.0, 0.0, 0.0))
    b.mesh_object("B", data=data, location=(2.0, 0.0, 0.0))
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.meshes == 1
    assert summary.instances == 2
    xs = sorted(float(m[0, 3]) for _, m in recording_scene.instances)
    assert xs == pytest.approx([-2.0, 2.0])


def test_collection_instance(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    source = bpy.data.collections.new("Source")  # not linked to the scene: instanced only
    source.objects.link(bpy.data.objects.new("Piece", b.mesh_data("Piece")))
    for i, x in enumerate((-3.0, 0.0, 3.0)):
        empty = bpy.data.objects.new(f"Instancer{i}", None)
        empty.instance_type = "COLLECTION"
        empty.instance_collection = source
        empty.location = (x, 0.0, 1.0)
        b.link(empty)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.meshes == 1
    assert summary.instances == 3
    assert summary.object_instances["Piece"] == 3
    xs = sorted(float(m[0, 3]) for _, m in recording_scene.instances)
    assert xs == pytest.approx([-3.0, 0.0, 3.0])


def test_material_slots_map_to_scene_materials(scene_builder: Any,
                                               recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    red = bpy.data.materials.new("Red")
    red.diffuse_color = (1.0, 0.0, 0.0, 1.0)
    if red.node_tree is not None:
        red.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (
            1.0, 0.0, 0.0, 1.0)
    blue = bpy.data.materials.new("Blue")
    blue.diffuse_color = (0.0, 0.0, 1.0, 1.0)
    if blue.node_tree is not None:
        blue.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (
            0.0, 0.0, 1.0, 1.0)
    ob = b.mesh_object("TwoMaterials", material=red)
    ob.data.materials.append(blue)
    ob.data.polygons[0].material_index = 1
    ob.data.update()
    export_scene(b.depsgraph(), recording_scene)
    ids = recording_scene.meshes[0]["material_ids"]
    colors = [recording_scene.materials[i].base_color for i in ids]
    assert sum(c == pytest.approx((0.0, 0.0, 1.0)) for c in colors) == 2  # one quad = 2 tris
    assert sum(c == pytest.approx((1.0, 0.0, 0.0)) for c in colors) == 10


def test_nan_vertex_is_an_error_naming_the_object(scene_builder: Any,
                                                   recording_scene: Any) -> None:
    b = scene_builder().basic()
    broken = b.mesh_object("BrokenMesh", location=(3.0, 0.0, 0.0))
    broken.data.vertices[0].co = (math.nan, 0.0, 0.0)
    with pytest.raises(ExportError, match="BrokenMesh") as info:
        export_scene(b.depsgraph(), recording_scene)
    assert "nan" in str(info.value).lower()


def test_missing_camera_is_a_clear_error(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.mesh_object("Cube")
    with pytest.raises(ExportError, match="no active camera"):
        export_scene(b.depsgraph(), recording_scene)


def test_non_equirectangular_panorama_is_rejected(scene_builder: Any,
                                                  recording_scene: Any) -> None:
    b = scene_builder()
    b.camera().data.type = "PANO"  # default panorama type: fisheye equisolid
    with pytest.raises(ExportError, match="FISHEYE_EQUISOLID"):
        export_scene(b.depsgraph(), recording_scene)


def _material_with(node_type: str) -> Any:
    mat = bpy.data.materials.new(node_type)
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    nt = mat.node_tree
    for node in list(nt.nodes):
        if node.bl_idname != "ShaderNodeOutputMaterial":
            nt.nodes.remove(node)
    out = nt.nodes["Material Output"]
    node = nt.nodes.new(node_type)
    nt.links.new(node.outputs[0], out.inputs["Surface"])
    return mat, node


def test_principled_version(stratum_addon: Any) -> None:
    mat, node = _material_with("ShaderNodeBsdfPrincipled")
    node.inputs["Base Color"].default_value = (0.2, 0.4, 0.6, 1.0)
    node.inputs["Roughness"].default_value = 0.3
    node.inputs["Metallic"].default_value = 0.7
    converted = convert_material(mat)
    (closure,) = converted.closures
    desc = closure.material
    expected = native.closure_model("principled_v1" if bpy.app.version < (4, 0, 0) else "principled_v2")
    assert desc.model == expected
    assert desc.base_color == pytest.approx((0.2, 0.4, 0.6))
    assert desc.roughness == pytest.approx(0.3)
    assert desc.metallic == pytest.approx(0.7)
    assert converted.warnings == []


def test_principled_unsupported_inputs_warn(stratum_addon: Any) -> None:
    mat, node = _material_with("ShaderNodeBsdfPrincipled")
    name = "Subsurface" if bpy.app.version < (4, 0, 0) else "Subsurface Weight"
    node.inputs[name].default_value = 1.0
    node.inputs["Sheen" if bpy.app.version < (4, 0, 0) else "Sheen Weight"].default_value = 1.0
    warnings = convert_material(mat).warnings
    # one warning per (material, node), naming both, whatever the number of unsupported inputs
    assert len(warnings) == 1
    assert f"Material '{mat.name}'" in warnings[0] and name in warnings[0]
    assert "Sheen" in warnings[0]


def test_emission_and_diffuse_and_unknown(stratum_addon: Any) -> None:
    mat, node = _material_with("ShaderNodeEmission")
    node.inputs["Color"].default_value = (1.0, 0.5, 0.25, 1.0)
    node.inputs["Strength"].default_value = 4.0
    converted = convert_material(mat)
    desc = converted.closures[0].material
    assert desc.model == native.closure_model("emission")
    assert desc.emission == pytest.approx((4.0, 2.0, 1.0))
    assert not converted.warnings

    mat, node = _material_with("ShaderNodeBsdfDiffuse")
    node.inputs["Color"].default_value = (0.1, 0.2, 0.3, 1.0)
    desc = convert_material(mat).closures[0].material
    assert desc.model == native.closure_model("diffuse")
    assert desc.base_color == pytest.approx((0.1, 0.2, 0.3))

    mat, node = _material_with("ShaderNodeBsdfToon")
    converted = convert_material(mat)
    assert converted.closures[0].material.base_color == pytest.approx((0.8, 0.8, 0.8))
    assert len(converted.warnings) == 1
    assert node.name in converted.warnings[0] and "ShaderNodeBsdfToon" in converted.warnings[0]


def test_one_warning_per_material(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    toon, _ = _material_with("ShaderNodeBsdfToon")
    b.mesh_object("G1", material=toon)
    b.mesh_object("G2", material=toon, location=(3.0, 0.0, 0.0))
    summary = export_scene(b.depsgraph(), recording_scene)
    assert len([w for w in summary.warnings if "Material 'ShaderNodeBsdfToon'" in w]) == 1


AREA_TYPES = {native.light_type("area_rectangle"), native.light_type("area_ellipse")}


def test_lights(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    specs = [("POINT", {}), ("SUN", {"angle": 0.1}), ("AREA", {"shape": "RECTANGLE",
             "size": 2.0, "size_y": 0.5}), ("AREA", {"shape": "DISK", "size": 1.5}),
             ("SPOT", {"spot_size": 0.8, "spot_blend": 0.3, "shadow_soft_size": 0.05})]
    for i, (kind, attrs) in enumerate(specs):
        light = bpy.data.lights.new(f"L{i}", kind)
        light.energy = 100.0 + i
        for key, value in attrs.items():
            setattr(light, key, value)
        b.link(bpy.data.objects.new(f"L{i}", light))
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.lights == 5
    # Cycles 3.x gives an area light of power P the radiance P/(4A), 4.x+ the physical
    # P/(πA); the native library is physical, so a 3.x area light's power arrives scaled by π/4.
    area_scale = math.pi / 4.0 if bpy.app.version < (4, 0, 0) else 1.0
    by_strength = {
        round(light.strength / (area_scale if light.type in AREA_TYPES else 1.0)): light
        for light in recording_scene.lights
    }
    assert by_strength[100].type == native.light_type("point")
    assert by_strength[101].type == native.light_type("sun")
    assert by_strength[101].angle == pytest.approx(0.1)
    assert by_strength[102].type == native.light_type("area_rectangle")
    assert (by_strength[102].size_x, by_strength[102].size_y) == pytest.approx((2.0, 0.5))
    assert by_strength[103].type == native.light_type("area_ellipse")
    assert (by_strength[103].size_x, by_strength[103].size_y) == pytest.approx((1.5, 1.5))
    # Cycles 3.x's spot falloff has an extra cos θ: the native SPOT_V1 model.
    spot_type = native.light_type("spot_v1" if bpy.app.version < (4, 0, 0) else "spot")
    assert by_strength[104].type == spot_type
    assert (by_strength[104].spot_size, by_strength[104].spot_blend) == pytest.approx((0.8, 0.3))
    assert by_strength[104].radius == pytest.approx(0.05)
    assert not any("L4" in w for w in summary.warnings)


def _lamp_with_strength(b: Any, name: str, node: str, output: str, **props: Any) -> Any:
    """A point lamp whose Emission Strength is the `output` of a `node` (its first input 0.5,
    its properties `props`)."""
    light = bpy.data.lights.new(name, "POINT")
    light.color = (1.0, 0.5, 0.25)
    light.use_nodes = True
    nt = light.node_tree
    emission = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeEmission")
    strength = nt.nodes.new(node)
    for key, value in props.items():
        setattr(strength, key, value)
    strength.inputs[0].default_value = 0.5
    nt.links.new(strength.outputs[output], emission.inputs["Strength"])
    return b.link(bpy.data.objects.new(name, light))


def test_a_light_falloff_makes_the_lamp_tree_a_program(scene_builder: Any,
                                                       recording_scene: Any) -> None:
    """A lamp tree that reads the ray length is sent as the lamp's program, run at each
    distance, and its colour is the lamp's own; a tree that reads nothing is folded."""
    b = scene_builder()
    b.camera()
    _lamp_with_strength(b, "Linear", "ShaderNodeLightFalloff", "Linear")
    _lamp_with_strength(b, "Constant", "ShaderNodeMath", "Value", operation="SQRT")  # 0.5 ** 0.5
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    linear, constant = recording_scene.lights
    assert tuple(linear.color) == pytest.approx((1.0, 0.5, 0.25))
    assert tuple(constant.color) == pytest.approx(tuple(0.5**0.5 * c for c in (1.0, 0.5, 0.25)))
    ((light_id, (program_id, register)),) = recording_scene.light_programs.items()
    assert light_id == 0
    with native.Scene() as scratch:
        pid = scratch.add_shader_program(recording_scene.programs[program_id])
        inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
        inputs[native.SHADER_INPUTS["ray_length"][0]] = 4.0
        assert scratch.evaluate_program(pid, inputs, register, 3) == pytest.approx([2.0] * 3)
