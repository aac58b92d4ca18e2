"""The Light Path node against Cycles (issue 34): its outputs driving emissions, transparencies,
a lamp and the world, in the running Blender (3.4 through run_in_blender.py, 5.0 under the wheel).

Exact cases (per pixel, |S - C| <= 1e-3): one sample at each pixel centre through a 0.01 px box
filter, in scenes where that sample is deterministic (no light sample chooses among lights, only
delta lights and delta scattering), max_bounces 0 (Cycles still adds the emission met after the
last bounce, as Stratum does):

* camera: four 8-px strips seen from above. An emitter (R, G, B) = (Is Camera Ray, Transparent
  Depth, Ray Depth) under two Transparent sheets: (1, 2, 0). Two emitters the camera does not
  see, above perfect mirrors: (Is Glossy, Is Singular, Glossy Depth) and (Ray Depth, Is
  Reflection, Is Camera Ray) of the mirrored ray: (1, 1, 1) and (1, 1, 0). An empty strip: 0.
* shadow: a diffuse floor under a sun of angle 0 shining down through two sheets the camera does
  not see, their Transparent colour (Is Shadow, Ray Depth / 2, 1 - Transparent Depth): the floor
  is 0.8 x (1, 1/4, 0).
* lamp: the floor lit by that sun with (Ray Depth, 1 - Is Camera Ray, Is Shadow) in its nodes:
  0.8 x (1, 1, 0).
* world: (Is Camera Ray, Ray Depth, Is Diffuse Ray) seen by the camera: (1, 1, 0).

The user case (agreement.py's tolerances: 2% per channel image mean, 5% per 16-px block, after the
noise gate): a world that lights the scene but is black to the camera (Mix Shader by Is Camera
Ray between a white and a black Background) and an emissive panel in view that lights but is not
seen (its strength times 1 - Is Camera Ray), over a diffuse floor with a box on it, and a lamp
with 1 - Is Camera Ray in its nodes, which Cycles evaluates without the camera flag.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest

from agreement import (
    OUT,
    Renders,
    add_top_ortho_camera,
    assert_agreement,
    configure_cycles,
    configure_stratum,
    new_scene,
    render_pixel_centres,
    render_two_seeds,
    stratum_available,
)

RES = 32
NODE_OUT = OUT.parent / (OUT.name + "-light-path-node")
USER_RES = 32
USER_BLOCK = 16
USER_SPP = 512


def _black_world(scene: bpy.types.Scene) -> None:
    # Black through its nodes too: Blender 5.0's new worlds are grey Background nodes.
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    world.color = (0.0, 0.0, 0.0)
    scene.world = world


def _quad(scene: bpy.types.Scene, name: str, x0: float, x1: float, z: float, material: Any,
          camera: bool = True) -> None:
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(x0, -2, z), (x1, -2, z), (x1, 2, z), (x0, 2, z)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    ob = bpy.data.objects.new(name, mesh)
    ob.visible_camera = camera
    scene.collection.objects.link(ob)


def _light_path_rgb(tree: Any, outputs: tuple[str, str, str],
                    transforms: tuple[str, str, str] = ("", "", "")) -> Any:
    """A Combine XYZ of three Light Path outputs, each as it is ('') or through a Math node
    ('half': x / 2, 'one_minus': 1 - x)."""
    nodes, links = tree.nodes, tree.links
    path = nodes.new("ShaderNodeLightPath")
    combine = nodes.new("ShaderNodeCombineXYZ")
    for k, (name, how) in enumerate(zip(outputs, transforms)):
        socket = path.outputs[name]
        if how:
            math_node = nodes.new("ShaderNodeMath")
            if how == "half":
                math_node.operation = "MULTIPLY"
                links.new(socket, math_node.inputs[0])
                math_node.inputs[1].default_value = 0.5
            else:
                math_node.operation = "SUBTRACT"
                math_node.inputs[0].default_value = 1.0
                links.new(socket, math_node.inputs[1])
            socket = math_node.outputs[0]
        links.new(socket, combine.inputs[k])
    return combine.outputs[0]


def _material(name: str, shader: str) -> tuple[Any, Any]:
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    node = tree.nodes.new(shader)
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(node.outputs[0], out.inputs["Surface"])
    return mat, node


def _emitter(name: str, outputs: tuple[str, str, str]) -> Any:
    mat, node = _material(name, "ShaderNodeEmission")
    node.inputs["Strength"].default_value = 1.0
    mat.node_tree.links.new(_light_path_rgb(mat.node_tree, outputs), node.inputs["Color"])
    return mat


def _mirror() -> Any:
    mat, node = _material("mirror", "ShaderNodeBsdfGlossy")
    node.distribution = "GGX"
    node.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    node.inputs["Roughness"].default_value = 0.0
    return mat


def _sun(scene: bpy.types.Scene, outputs: tuple[str, str, str] | None = None,
         transforms: tuple[str, str, str] = ("", "", "")) -> None:
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = math.pi
    sun.angle = 0.0
    if outputs is not None:
        sun.use_nodes = True
        tree = sun.node_tree
        emission = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeEmission")
        tree.links.new(_light_path_rgb(tree, outputs, transforms), emission.inputs["Color"])
    scene.collection.objects.link(bpy.data.objects.new("sun", sun))


def _floor(scene: bpy.types.Scene) -> None:
    mat, node = _material("floor", "ShaderNodeBsdfDiffuse")
    node.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    _quad(scene, "floor", -2.0, 2.0, 0.0, mat)


def _camera_scene() -> bpy.types.Scene:
    scene = new_scene(RES)
    _black_world(scene)
    add_top_ortho_camera(scene, 4.0)
    _quad(scene, "behind_sheets", -2.0, -1.0, 0.0,
          _emitter("camera", ("Is Camera Ray", "Transparent Depth", "Ray Depth")))
    sheet, node = _material("sheet", "ShaderNodeBsdfTransparent")
    node.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    _quad(scene, "sheet1", -2.0, -1.0, 0.5, sheet)
    _quad(scene, "sheet2", -2.0, -1.0, 1.0, sheet)
    mirror = _mirror()
    for k, outputs in enumerate((("Is Glossy Ray", "Is Singular Ray", "Glossy Depth"),
                                 ("Ray Depth", "Is Reflection Ray", "Is Camera Ray"))):
        _quad(scene, f"mirror{k}", -1.0 + k, k, 0.0, mirror)
        _quad(scene, f"mirrored{k}", -1.0 + k, k, 0.5, _emitter(f"mirrored{k}", outputs),
              camera=False)
    return scene


def _shadow_scene() -> bpy.types.Scene:
    scene = new_scene(RES)
    _black_world(scene)
    add_top_ortho_camera(scene, 4.0)
    _floor(scene)
    sheet, node = _material("shadow_sheet", "ShaderNodeBsdfTransparent")
    sheet.node_tree.links.new(
        _light_path_rgb(sheet.node_tree, ("Is Shadow Ray", "Ray Depth", "Transparent Depth"),
                        ("", "half", "one_minus")), node.inputs["Color"])
    # Wider than the view on one side: their diagonal edges then meet no pixel centre's shadow
    # ray (Cycles counts a surface twice where a ray meets the edge both triangles share).
    _quad(scene, "sheet1", -2.3, 2.2, 0.5, sheet, camera=False)
    _quad(scene, "sheet2", -2.3, 2.2, 1.0, sheet, camera=False)
    _sun(scene)
    return scene


def _lamp_scene() -> bpy.types.Scene:
    scene = new_scene(RES)
    _black_world(scene)
    add_top_ortho_camera(scene, 4.0)
    _floor(scene)
    _sun(scene, ("Ray Depth", "Is Camera Ray", "Is Shadow Ray"), ("", "one_minus", ""))
    return scene


def _world_scene() -> bpy.types.Scene:
    scene = new_scene(RES)
    add_top_ortho_camera(scene, 4.0)
    world = bpy.data.worlds.new("light_path")
    world.use_nodes = True
    tree = world.node_tree
    background = tree.nodes["Background"]
    background.inputs["Strength"].default_value = 1.0
    tree.links.new(_light_path_rgb(tree, ("Is Camera Ray", "Ray Depth", "Is Diffuse Ray")),
                   background.inputs["Color"])
    scene.world = world
    return scene


# name: the scene's builder (its expected pixels: _expected)
EXACT = {
    "camera": _camera_scene,
    "shadow": _shadow_scene,
    "lamp": _lamp_scene,
    "world": _world_scene,
}


def _expected(case: str) -> np.ndarray:
    want = np.zeros((RES, RES, 3))
    if case == "camera":
        strip = RES // 4
        want[:, 0:strip] = (1.0, 2.0, 0.0)
        want[:, strip:2 * strip] = (1.0, 1.0, 1.0)
        want[:, 2 * strip:3 * strip] = (1.0, 1.0, 0.0)
    elif case == "shadow":
        want[:] = (0.8, 0.8 * 0.25, 0.0)
    elif case == "lamp":
        want[:] = (0.8, 0.8, 0.0)
    else:
        want[:] = (1.0, 1.0, 0.0)
    return want


@pytest.mark.parametrize("case", list(EXACT))
def test_light_path_outputs_agree_with_cycles_per_pixel(library, case: str) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    images = {}
    for engine in ("CYCLES", "STRATUM"):
        scene = EXACT[case]()
        images[engine] = render_pixel_centres(
            scene, engine, NODE_OUT / f"{case}_{engine.lower()}.exr", RES, max_bounces=0)
    cycles, stratum = images["CYCLES"], images["STRATUM"]
    # The expected values first: a Cycles that disagreed with them would make the comparison
    # meaningless.
    np.testing.assert_allclose(cycles, _expected(case), atol=1e-3, err_msg=f"Cycles, {case}")
    worst = float(np.max(np.abs(stratum - cycles)))
    assert worst <= 1e-3, f"{case}: Stratum differs from Cycles by up to {worst:.2e}"


# ---- the user case ---------------------------------------------------------------------------


def _user_scene() -> bpy.types.Scene:
    scene = new_scene(USER_RES)
    world = bpy.data.worlds.new("lights_unseen")
    world.use_nodes = True
    tree = world.node_tree
    tree.nodes.clear()
    lighting = tree.nodes.new("ShaderNodeBackground")
    lighting.inputs["Color"].default_value = (0.9, 0.95, 1.0, 1.0)
    lighting.inputs["Strength"].default_value = 1.0
    seen = tree.nodes.new("ShaderNodeBackground")
    seen.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    mix = tree.nodes.new("ShaderNodeMixShader")
    path = tree.nodes.new("ShaderNodeLightPath")
    out = tree.nodes.new("ShaderNodeOutputWorld")
    tree.links.new(path.outputs["Is Camera Ray"], mix.inputs[0])
    tree.links.new(lighting.outputs[0], mix.inputs[1])
    tree.links.new(seen.outputs[0], mix.inputs[2])
    tree.links.new(mix.outputs[0], out.inputs["Surface"])
    scene.world = world
    _floor(scene)
    box, node = _material("box", "ShaderNodeBsdfDiffuse")
    node.inputs["Color"].default_value = (0.8, 0.3, 0.2, 1.0)
    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(0.3, 0.2, 0.4))
    bpy.context.object.data.materials.append(box)
    # A panel that lights but is not seen: an Emission of strength 4 (1 - Is Camera Ray), in view,
    # turned toward the floor and the camera.
    panel, emission = _material("panel", "ShaderNodeEmission")
    minus = panel.node_tree.nodes.new("ShaderNodeMath")
    minus.operation = "SUBTRACT"
    minus.inputs[0].default_value = 1.0
    panel.node_tree.links.new(
        panel.node_tree.nodes.new("ShaderNodeLightPath").outputs["Is Camera Ray"], minus.inputs[1])
    times = panel.node_tree.nodes.new("ShaderNodeMath")
    times.operation = "MULTIPLY"
    times.inputs[1].default_value = 4.0
    panel.node_tree.links.new(minus.outputs[0], times.inputs[0])
    panel.node_tree.links.new(times.outputs[0], emission.inputs["Strength"])
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(-0.7, -0.4, 1.3), rotation=(-2.6, 0.0, 0.0))
    bpy.context.object.data.materials.append(panel)
    # A lamp out of view whose nodes read Light Path (Cycles evaluates a lamp with its emission
    # flag alone, so Is Camera Ray is 0 there even for a camera ray: the node cannot hide a lamp,
    # only its ray visibility can): it lights at full strength.
    lamp = bpy.data.lights.new("lamp", "AREA")
    lamp.energy = 30.0
    lamp.size = 1.0
    lamp.use_nodes = True
    lamp_emission = next(n for n in lamp.node_tree.nodes if n.bl_idname == "ShaderNodeEmission")
    lamp.node_tree.links.new(_light_path_rgb(lamp.node_tree, ("Is Camera Ray",) * 3, ("one_minus",) * 3),
                             lamp_emission.inputs["Color"])
    lamp_ob = bpy.data.objects.new("lamp", lamp)
    lamp_ob.location = (1.2, 0.8, 2.5)
    scene.collection.objects.link(lamp_ob)
    cam = bpy.data.cameras.new("cam")
    cam.sensor_fit, cam.sensor_width, cam.lens = "HORIZONTAL", 36.0, 30.0
    camera = bpy.data.objects.new("cam", cam)
    camera.location = (0.0, -3.2, 2.2)
    camera.rotation_euler = (math.radians(58.0), 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    return scene


def _user_configure(engine: str, scene: bpy.types.Scene, seed: int) -> None:
    configure_cycles(scene, seed, samples=USER_SPP)
    if engine == "stratum":
        configure_stratum(scene, seed, samples=USER_SPP)


def test_a_world_and_a_lamp_that_light_but_are_not_seen_agree_with_cycles(library) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    out: Path = NODE_OUT / "user_case"
    renders: dict[str, Renders] = {
        engine: render_two_seeds(engine, functools.partial(_user_configure, engine), out,
                                 _user_scene, res=USER_RES, block=USER_BLOCK)
        for engine in ("cycles", "stratum")}
    cycles, stratum = renders["cycles"], renders["stratum"]
    compared = cycles.block_mean() > 0.01
    assert compared.any()
    assert_agreement(cycles, stratum, compared, "Light Path: world and lamp unseen", out)
