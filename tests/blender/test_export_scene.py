"""Issue-5 export, checked at what reaches the native scene (a recording stand-in, so these run
without the native library): shader trees flattened into closures, images once each with their
source and colour space, UV maps, instances with visibility/holdout/motion, excluded
collections, light visibility and spread, equirectangular cameras, border and film settings."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest
from stratum import native
from stratum.engine import StratumRenderEngine, frame
from stratum.export.images import blender_ocio_config
from stratum.export.sync import SceneSync, export_scene

V4 = bpy.app.version >= (4, 0, 0)


def _material(name: str) -> tuple[Any, Any, Any]:
    """A material whose tree is only a Material Output: (material, node tree, Surface input)."""
    mat = bpy.data.materials.new(name)
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    nt = mat.node_tree
    for node in list(nt.nodes):
        if node.bl_idname != "ShaderNodeOutputMaterial":
            nt.nodes.remove(node)
    return mat, nt, nt.nodes["Material Output"].inputs["Surface"]


def _image(name: str, width: int = 4, height: int = 2, alpha: bool = True,
           float_buffer: bool = True) -> Any:
    image = bpy.data.images.new(name, width, height, alpha=alpha, float_buffer=float_buffer)
    px = np.zeros((height, width, 4), dtype=np.float32)
    px[..., 0] = np.arange(width)[None, :] / width  # red ramps left to right
    px[..., 1] = np.arange(height)[:, None] / height  # green ramps bottom (row 0) to top
    px[..., 3] = 1.0
    image.pixels.foreach_set(px.ravel())
    return image


def _textured_material(name: str, image: Any, uv_map: str = "") -> Any:
    mat, nt, surface = _material(name)
    bsdf = nt.nodes.new("ShaderNodeBsdfPrincipled")
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.image = image
    nt.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    if uv_map:
        uv = nt.nodes.new("ShaderNodeUVMap")
        uv.uv_map = uv_map
        nt.links.new(uv.outputs["UV"], tex.inputs["Vector"])
    nt.links.new(bsdf.outputs[0], surface)
    return mat


def _uv_cube(b: Any, name: str, material: Any, layers: tuple[str, ...] = ("UVMap",)) -> Any:
    ob = b.mesh_object(name, material=material)
    for i, layer_name in enumerate(layers):
        layer = ob.data.uv_layers.new(name=layer_name)
        uvs = np.full(len(ob.data.loops) * 2, 0.1 * (i + 1), dtype=np.float32)
        layer.data.foreach_set("uv", uvs)
    return ob


def test_mix_and_add_shaders_become_weighted_closures(scene_builder: Any,
                                                      recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    mat, nt, surface = _material("Layered")
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    glossy = nt.nodes.new("ShaderNodeBsdfGlossy")
    emission = nt.nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 2.0
    mix = nt.nodes.new("ShaderNodeMixShader")
    mix.inputs[0].default_value = 0.25
    add = nt.nodes.new("ShaderNodeAddShader")
    nt.links.new(diffuse.outputs[0], mix.inputs[1])
    nt.links.new(glossy.outputs[0], mix.inputs[2])
    nt.links.new(mix.outputs[0], add.inputs[0])
    nt.links.new(emission.outputs[0], add.inputs[1])
    nt.links.new(add.outputs[0], surface)
    b.mesh_object("Cube", material=mat)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    (closures,) = [m for m in recording_scene.materials if isinstance(m, list)]
    assert [(w[0], m.model) for w, m in closures] == [
        (pytest.approx(0.75), native.closure_model("diffuse")), (pytest.approx(0.25),
                                                         native.closure_model("glossy")),
        (pytest.approx(1.0), native.closure_model("emission"))]
    assert closures[2][1].emission == pytest.approx((2.0, 2.0, 2.0))


def test_glass_transparent_holdout_and_principled_alpha(scene_builder: Any,
                                                        recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    models = {}
    for kind in ("ShaderNodeBsdfGlass", "ShaderNodeBsdfTransparent", "ShaderNodeHoldout"):
        mat, nt, surface = _material(kind)
        node = nt.nodes.new(kind)
        if kind == "ShaderNodeBsdfGlass":
            node.distribution = "GGX"
            node.inputs["IOR"].default_value = 1.33
        nt.links.new(node.outputs[0], surface)
        b.mesh_object(kind, material=mat, location=(3.0 * len(models), 0.0, 0.0))
        models[kind] = mat
    mat, nt, surface = _material("HalfAlpha")
    bsdf = nt.nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.inputs["Alpha"].default_value = 0.25
    nt.links.new(bsdf.outputs[0], surface)
    b.mesh_object("Alpha", material=mat, location=(0.0, 3.0, 0.0))
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    singles = [m for m in recording_scene.materials if not isinstance(m, list)]
    assert {m.model for m in singles} == {native.closure_model("glass"), native.closure_model("transparent"),
                                          native.closure_model("holdout")}
    glass = next(m for m in singles if m.model == native.closure_model("glass"))
    assert glass.ior == pytest.approx(1.33)
    (alpha,) = [m for m in recording_scene.materials if isinstance(m, list)]
    assert [(w[0], m.model) for w, m in alpha] == [
        (pytest.approx(0.75), native.closure_model("transparent")),
        (pytest.approx(0.25), native.closure_model("principled_v2" if V4 else "principled_v1"))]


def test_generated_image_once_with_binding_and_named_uv_map(scene_builder: Any,
                                                            recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    image = _image("Ramp")
    a = _textured_material("A", image, uv_map="Second")
    c = _textured_material("C", image, uv_map="Second")
    _uv_cube(b, "CubeA", a, ("First", "Second"))
    _uv_cube(b, "CubeC", c, ("First", "Second")).location = (3.0, 0.0, 0.0)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    assert summary.textures == 1 and len(recording_scene.textures) == 1
    tex = recording_scene.textures[0]
    assert tex.path is None and tex.file_data is None
    assert tex.pixels.shape == (2, 4, 4)
    # rows bottom to top, as Image.pixels and the C ABI: row 0 has green 0
    assert tex.pixels[0, :, 1] == pytest.approx(0.0)
    assert tex.pixels[-1, :, 1] == pytest.approx(0.5)
    assert tex.color_space == "Non-Color"  # generated float buffer: already scene-linear
    assert [bd.param for bd in recording_scene.bindings] == [native.PARAM_BASE_COLOR] * 2
    assert {bd.texture_id for bd in recording_scene.bindings} == {0}
    for mesh in recording_scene.meshes:  # the "Second" layer (0.2), not "First" (0.1)
        assert mesh["corner_uvs"] == pytest.approx(np.full_like(mesh["corner_uvs"], 0.2))


def test_uvs_are_read_only_for_textured_materials(scene_builder: Any,
                                                   recording_scene: Any) -> None:
    """As Cycles exports a UV attribute only for shaders that ask for it, an untextured mesh
    sends no corner UVs (the largest per-corner array of a big mesh); a textured one does."""
    b = scene_builder()
    b.camera()
    plain, _, surface = _material("Plain")
    bsdf = plain.node_tree.nodes.new("ShaderNodeBsdfDiffuse")
    plain.node_tree.links.new(bsdf.outputs[0], surface)
    _uv_cube(b, "PlainCube", plain)
    _uv_cube(b, "TexturedCube", _textured_material("Tex", _image("Ramp"))).location = (3, 0, 0)
    export_scene(b.depsgraph(), recording_scene)
    uvs = sorted((m["corner_uvs"] is None) for m in recording_scene.meshes)
    assert uvs == [False, True]


def test_file_and_packed_images_and_colour_space(scene_builder: Any, recording_scene: Any,
                                                 tmp_path: Path) -> None:
    b = scene_builder()
    b.camera()
    on_disk = _image("OnDisk", alpha=False, float_buffer=False)
    on_disk.filepath_raw = str(tmp_path / "on_disk.png")
    on_disk.file_format = "PNG"
    on_disk.save()
    loaded = bpy.data.images.load(str(tmp_path / "on_disk.png"))
    loaded.colorspace_settings.name = "Non-Color"
    packed = bpy.data.images.load(str(tmp_path / "on_disk.png"), check_existing=False)
    packed.pack()
    for i, image in enumerate((loaded, packed)):
        mat = _textured_material(f"M{i}", image)
        _uv_cube(b, f"Cube{i}", mat).location = (3.0 * i, 0.0, 0.0)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    file_tex, packed_tex = recording_scene.textures
    assert file_tex.path == str(tmp_path / "on_disk.png")
    assert file_tex.color_space == "Non-Color"
    assert packed_tex.path is None and packed_tex.file_data[:4] == b"\x89PNG"
    assert packed_tex.file_name.endswith(".png")
    assert packed_tex.color_space == "sRGB"
    config = blender_ocio_config()
    assert config is not None and os.path.isfile(config)
    assert file_tex.ocio_config == config == packed_tex.ocio_config


def test_image_alpha_cutout_and_mix_factor(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    image = _image("Mask")
    mat, nt, surface = _material("Cutout")
    bsdf = nt.nodes.new("ShaderNodeBsdfPrincipled")
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.image = image
    tex.interpolation = "Closest"
    tex.extension = "EXTEND"
    nt.links.new(tex.outputs["Alpha"], bsdf.inputs["Alpha"])
    nt.links.new(bsdf.outputs[0], surface)
    _uv_cube(b, "Leaf", mat)
    export_scene(b.depsgraph(), recording_scene)
    (tex_desc,) = recording_scene.textures
    assert tex_desc.interpolation == native.TEXTURE_CLOSEST
    assert tex_desc.extension == native.TEXTURE_EXTEND
    by_closure = {(bd.closure_index, bd.param): bd for bd in recording_scene.bindings}
    transparent = by_closure[(0, native.PARAM_WEIGHT)]
    principled = by_closure[(1, native.PARAM_WEIGHT)]
    assert (transparent.channel, transparent.scale, transparent.offset) == (3, -1.0, 1.0)
    assert (principled.channel, principled.scale, principled.offset) == (3, 1.0, 0.0)


def test_unsupported_node_one_warning_naming_material_and_node(scene_builder: Any,
                                                               recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    # The Ambient Occlusion node (rays traced from the shading point) has no translator.
    mat, nt, surface = _material("Noisy")
    bsdf = nt.nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.inputs["Roughness"].default_value = 0.3
    noise = nt.nodes.new("ShaderNodeAmbientOcclusion")
    nt.links.new(noise.outputs["AO"], bsdf.inputs["Roughness"])
    nt.links.new(noise.outputs["Color"], bsdf.inputs["Base Color"])
    nt.links.new(bsdf.outputs[0], surface)
    b.mesh_object("A", material=mat)
    b.mesh_object("B", material=mat, location=(3.0, 0.0, 0.0))
    summary = export_scene(b.depsgraph(), recording_scene)
    assert len(summary.warnings) == 1
    assert "Material 'Noisy'" in summary.warnings[0] and noise.name in summary.warnings[0]
    assert recording_scene.materials[0].roughness == pytest.approx(0.3)


def _vertex_instancer(b: Any, count: int) -> Any:
    """A mesh of `count` vertices instancing a child cube on each (instance_type VERTS)."""
    grid = bpy.data.meshes.new("Points")
    side = math.ceil(math.sqrt(count))
    idx = np.arange(count)
    co = np.stack([idx % side * 3.0, idx // side * 3.0, np.zeros(count)], axis=1)
    grid.vertices.add(count)
    grid.vertices.foreach_set("co", co.astype(np.float32).ravel())
    grid.update()
    parent = b.link(bpy.data.objects.new("Instancer", grid))
    parent.instance_type = "VERTS"
    child = b.mesh_object("Piece")
    child.parent = parent
    return parent


def _count_calls(scene: Any, names: tuple[str, ...]) -> dict[str, int]:
    """Wraps the scene's methods `names` (instance attributes shadow the class's) and returns
    the live count of calls of each."""
    calls = dict.fromkeys(names, 0)
    for name in names:
        original = getattr(scene, name)

        def counted(*args: Any, _name: str = name, _original: Any = original, **kwargs: Any) -> Any:
            calls[_name] += 1
            return _original(*args, **kwargs)

        setattr(scene, name, counted)
    return calls


# How fast 10 000 instances export is measured by `make bench` (instances_10k, against Cycles'
# sync), not timed here: these tests check the shape that keeps it fast, every plain placement
# sent in one bulk call rather than one call each.
PLACEMENT_CALLS = ("add_instance", "add_instance_ex", "add_instances")


def test_ten_thousand_instances_export_in_one_bulk_call(scene_builder: Any,
                                                        recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    _vertex_instancer(b, 10_000)
    dg = b.depsgraph()
    calls = _count_calls(recording_scene, PLACEMENT_CALLS)
    summary = export_scene(dg, recording_scene)
    # + 1: the child object itself, which Blender renders as well
    assert summary.meshes == 1 and summary.instances == 10_001
    assert len(recording_scene.instances) == 10_001
    assert calls == {"add_instance": 0, "add_instance_ex": 0, "add_instances": 1}, calls


def test_ten_thousand_instances_into_the_native_scene(scene_builder: Any, library: Any) -> None:
    b = scene_builder()
    b.camera()
    _vertex_instancer(b, 10_000)
    dg = b.depsgraph()
    with library.Scene() as scene:
        calls = _count_calls(scene, PLACEMENT_CALLS)
        summary = export_scene(dg, scene)
    assert summary.meshes == 1 and summary.instances == 10_001
    assert calls == {"add_instance": 0, "add_instance_ex": 0, "add_instances": 1}, calls


def test_visibility_and_holdout_reach_the_instances(scene_builder: Any,
                                                    recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    plain = b.mesh_object("Plain")
    no_glossy = b.mesh_object("NoGlossy", location=(3.0, 0.0, 0.0))
    no_glossy.visible_glossy = False
    no_glossy.visible_shadow = False
    held = b.mesh_object("Held", location=(6.0, 0.0, 0.0))
    held.is_holdout = True
    coll = bpy.data.collections.new("HeldCollection")
    b.scene.collection.children.link(coll)
    in_coll = bpy.data.objects.new("InHeldCollection", b.mesh_data("InHeldCollection"))
    in_coll.location = (9.0, 0.0, 0.0)
    coll.objects.link(in_coll)
    bpy.context.view_layer.layer_collection.children["HeldCollection"].holdout = True
    export_scene(b.depsgraph(), recording_scene)
    names = {}
    for position, (mesh_id, matrix) in enumerate(recording_scene.instances):
        names[round(float(matrix[0, 3]))] = recording_scene.instance_descs.get(position)
    assert plain.name == "Plain" and names[0] is None  # a default instance (add_instance)
    desc = names[3]
    assert desc.visibility == native.VISIBLE_ALL & ~native.VISIBLE_GLOSSY & \
        ~native.VISIBLE_SHADOW
    assert not desc.holdout
    assert names[6].holdout and names[6].visibility == native.VISIBLE_ALL
    assert names[9].holdout  # through its collection's view-layer holdout


def test_shadow_catchers_and_light_groups_reach_instances_lights_and_world(
        scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    world = b.world()
    view_layer = bpy.context.view_layer
    for group in ("key", "fill"):
        view_layer.lightgroups.add(name=group)
    catcher = b.mesh_object("Catcher")
    catcher.is_shadow_catcher = True
    glowing = b.mesh_object("Glowing", location=(3.0, 0.0, 0.0))
    glowing.lightgroup = "fill"
    stray = b.mesh_object("Stray", location=(6.0, 0.0, 0.0))
    stray.lightgroup = "no such group"
    lamp = b.point_light()
    lamp.lightgroup = "key"
    lamp.is_shadow_catcher = False
    world.lightgroup = "fill"
    export_scene(b.depsgraph(), recording_scene)
    names = {}
    for position, (_, matrix) in enumerate(recording_scene.instances):
        names[round(float(matrix[0, 3]))] = recording_scene.instance_descs.get(position)
    assert names[0].visibility == native.VISIBLE_ALL | native.VISIBLE_SHADOW_CATCHER
    assert names[0].lightgroup == 0
    # Light groups are numbered in the view layer's order from 1; a name it lacks is none.
    assert names[3].lightgroup == 2 and names[3].visibility == native.VISIBLE_ALL
    assert names[6] is None  # in no group the view layer has: a plain instance
    (light,) = recording_scene.lights
    assert light.lightgroup == 1 and not light.visibility & native.VISIBLE_SHADOW_CATCHER
    assert recording_scene.world_lightgroup == 2


def test_excluded_and_render_disabled_collections_are_not_rendered(
        scene_builder: Any, library: Any) -> None:
    b = scene_builder().basic()
    for name in ("Excluded", "RenderOff"):
        coll = bpy.data.collections.new(name)
        b.scene.collection.children.link(coll)
        coll.objects.link(bpy.data.objects.new(f"In{name}", b.mesh_data(f"In{name}")))
    bpy.context.view_layer.layer_collection.children["Excluded"].exclude = True
    bpy.data.collections["RenderOff"].hide_render = True
    bpy.ops.render.render()  # the render depsgraph: hide_render applies there, not in viewports
    summary = StratumRenderEngine.last_summary
    assert summary is not None and set(summary.object_instances) == {"Cube"}


def test_motion_blur_moving_objects_only(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    moving = b.mesh_object("Moving")
    b.mesh_object("Still", location=(0.0, 0.0, 5.0))
    driver = moving.driver_add("location", 0).driver
    driver.type = "SCRIPTED"
    driver.expression = "frame"  # a simple expression: evaluated without Python
    b.scene.frame_set(1)
    b.scene.render.use_motion_blur = True
    b.scene.render.motion_blur_shutter = 0.5
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.moving_instances == 1
    (desc,) = recording_scene.instance_descs.values()
    start = np.asarray(desc.transform).reshape(4, 4)
    end = np.asarray(desc.transform_end).reshape(4, 4)
    # CENTER: shutter [frame - 0.25, frame + 0.25] around frame 1
    assert (start[0, 3], end[0, 3]) == pytest.approx((0.75, 1.25))
    assert b.scene.frame_current == 1 and moving.matrix_world.translation.x == pytest.approx(1.0)


def test_motion_blur_needs_the_layers_switch_and_a_final_render(scene_builder: Any,
                                                                recording_scene: Any) -> None:
    """Cycles: motion blur = the scene's and the view layer's use_motion_blur, F12 only (its
    viewport renders none)."""
    b = scene_builder()
    b.camera()
    moving = b.mesh_object("Moving")
    driver = moving.driver_add("location", 0).driver
    driver.type = "SCRIPTED"
    driver.expression = "frame"
    b.scene.frame_set(1)
    b.scene.render.use_motion_blur = True
    b.scene.render.motion_blur_shutter = 0.5
    assert SceneSync(lambda: recording_scene, viewport=True).full(b.depsgraph()).moving_instances == 0
    b.scene.view_layers[0].use_motion_blur = False
    assert export_scene(b.depsgraph(), recording_scene).moving_instances == 0


def test_light_visibility_shadow_and_spread(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder()
    b.camera()
    light = bpy.data.lights.new("Panel", "AREA")
    light.size = 1.0
    light.spread = math.radians(30.0)
    if V4:
        light.use_shadow = False
    else:
        light.cycles.cast_shadow = False
    ob = b.link(bpy.data.objects.new("Panel", light))
    ob.visible_diffuse = False
    hidden = b.point_light()
    for attr in ("visible_camera", "visible_diffuse", "visible_glossy", "visible_transmission"):
        setattr(hidden, attr, False)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.lights == 1  # the point light is seen by no ray
    (panel,) = recording_scene.lights
    camera = native.VISIBLE_CAMERA if ob.visible_camera else 0  # Blender's default differs
    # A light's Shadow Catcher flag (on by default): it lights shadow catchers.
    assert ob.is_shadow_catcher
    assert panel.visibility == camera | native.VISIBLE_GLOSSY | native.VISIBLE_TRANSMISSION | \
        native.VISIBLE_SHADOW_CATCHER
    assert panel.spread == pytest.approx(math.radians(30.0))


def test_equirectangular_camera(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()
    cam = b.scene.camera.data
    cam.type = "PANO"
    source = cam if V4 else cam.cycles
    source.panorama_type = "EQUIRECTANGULAR"
    source.latitude_min, source.latitude_max = -1.0, 0.5
    source.longitude_min, source.longitude_max = -2.0, 2.5
    export_scene(b.depsgraph(), recording_scene)
    c = recording_scene.camera
    assert c.type == native.CAMERA_EQUIRECTANGULAR
    assert (c.latitude_min, c.latitude_max, c.longitude_min, c.longitude_max) == \
        pytest.approx((-1.0, 0.5, -2.0, 2.5))


def test_border_and_film_transparent_settings(scene_builder: Any) -> None:
    b = scene_builder().basic()
    r = b.scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = 200, 100, 50
    assert frame.renderer_settings(b.scene).keys().isdisjoint({"crop_x", "film_transparent"})
    r.use_border = True
    r.border_min_x, r.border_max_x = 0.25, 0.755
    r.border_min_y, r.border_max_y = 0.1, 0.5
    r.film_transparent = True
    settings = frame.renderer_settings(b.scene)
    assert (settings["width"], settings["height"]) == (100, 50)
    # Blender truncates border * size: x 25..75, y 5..25
    assert (settings["crop_x"], settings["crop_y"], settings["crop_width"],
            settings["crop_height"]) == (25, 5, 50, 20)
    assert settings["film_transparent"] == 1
    assert frame.result_size(b.scene) == (50, 20)


def test_geometry_nodes_instances_of_mesh_data(scene_builder: Any,
                                               recording_scene: Any) -> None:
    """Instance on Points with a Cube node: the instances are mesh data without an object of
    their own (instance_object is the instancer); their geometry is instance.object's."""
    b = scene_builder()
    b.camera()
    points = bpy.data.meshes.new("Points")
    points.from_pydata([(0, 0, 0), (3, 0, 0), (0, 3, 0)], [], [])
    scatter = b.link(bpy.data.objects.new("Scatter", points))
    group = bpy.data.node_groups.new("Scatter", "GeometryNodeTree")
    if hasattr(group, "interface"):  # 4.0+
        group.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
        group.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    else:
        group.inputs.new("NodeSocketGeometry", "Geometry")
        group.outputs.new("NodeSocketGeometry", "Geometry")
    nodes, links = group.nodes, group.links
    group_in, group_out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    on_points, cube = nodes.new("GeometryNodeInstanceOnPoints"), nodes.new("GeometryNodeMeshCube")
    links.new(group_in.outputs[0], on_points.inputs["Points"])
    links.new(cube.outputs[0], on_points.inputs["Instance"])
    links.new(on_points.outputs[0], group_out.inputs[0])
    scatter.modifiers.new("Scatter", "NODES").node_group = group
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.meshes == 1 and summary.triangles == 12
    assert summary.instances == 3
    xs = sorted((round(float(m[0, 3])), round(float(m[1, 3]))) for _, m in
                recording_scene.instances)
    assert xs == [(0, 0), (0, 3), (3, 0)]


def test_every_closure_carries_this_blenders_bump_shadowing(scene_builder: Any,
                                                            recording_scene: Any) -> None:
    """Cycles 3.x-4.4 shade perturbed normals with Chiang et al.'s term, 4.5+ with Conty
    Estevez et al.'s, whose smoothing the material's Bump Map Correction turns off."""
    b = scene_builder()
    b.camera()
    mat, nt, surface = _material("Mixed")
    mix = nt.nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.5
    nt.links.new(nt.nodes.new("ShaderNodeBsdfDiffuse").outputs[0], mix.inputs[1])
    nt.links.new(nt.nodes.new("ShaderNodeBsdfPrincipled").outputs[0], mix.inputs[2])
    nt.links.new(mix.outputs[0], surface)
    b.mesh_object("Cube", material=mat)
    b.mesh_object("Default")
    if bpy.app.version >= (4, 5, 0):
        uncorrected, _, plain = _material("Uncorrected")
        uncorrected.cycles.use_bump_map_correction = False
        nt_u = uncorrected.node_tree
        nt_u.links.new(nt_u.nodes.new("ShaderNodeBsdfDiffuse").outputs[0], plain)
        b.mesh_object("Plain", material=uncorrected)
    export_scene(b.depsgraph(), recording_scene)
    expected = (native.BUMP_SHADOWING_CHIANG if bpy.app.version < (4, 5, 0)
                else native.BUMP_SHADOWING_CONTY)
    models = []
    for entry in recording_scene.materials:
        closures = [m for _, m in entry] if isinstance(entry, list) else [entry]
        models.append([m.bump_shadowing for m in closures])
    # The mix (both closures) and the default grey of the object without a material; in 4.5+
    # also the material without correction. Ids follow the depsgraph's order: compare sorted.
    wanted = [[expected, expected], [expected]]
    if bpy.app.version >= (4, 5, 0):
        wanted.append([native.BUMP_SHADOWING_CONTY_UNSMOOTHED])
    assert sorted(models) == sorted(wanted)
