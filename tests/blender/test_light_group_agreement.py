"""Stratum against Cycles on light groups (issue 34): two view-layer light groups, "key" (an area
light and an emissive panel) and "fill" (a point light and the world), over a grey floor with
a red cube, three bounces, in the running Blender (3.4 under run_in_blender.py, 5.0 under the
bpy wheel).

Compared, each against Cycles' own pass with agreement.py's tolerances (image means within 2%
and 16 x 16 block means within 5% per channel after the noise gate; test_cycles_agreement.py
derives them): the passes Combined_key and Combined_fill. And, within Stratum's render, that
the two sum to Combined per pixel: every emitter is in one of them, so the sum is Combined's
contributions added in another order (float rounding: relative 1e-5, and 1e-6 absolute for
the float32 EXR of a dark pixel).
"""

from __future__ import annotations

import math
from pathlib import Path

import bpy
import numpy as np
import pytest

from agreement import (
    OUT,
    SEEDS,
    Renders,
    add_camera,
    add_diffuse_floor,
    assert_agreement,
    configure_cycles,
    configure_stratum,
    new_scene,
    stratum_available,
)
from exr_file import read_pass
from multilayer_passes import set_multilayer_exr

RES = 32
BLOCK = 16
SPP_PER_SEED = 512
MAX_BOUNCES = 3
GROUPS = ("key", "fill")
GROUPS_OUT = OUT / "light_groups"


def _emission_material(name: str, color: tuple[float, float, float], strength: float) -> bpy.types.Material:
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*color, 1.0)
    emission.inputs["Strength"].default_value = strength
    out = nodes.new("ShaderNodeOutputMaterial")
    mat.node_tree.links.new(emission.outputs[0], out.inputs["Surface"])
    return mat


def _quad(name: str, corners: list[tuple[float, float, float]], mat: bpy.types.Material) -> bpy.types.Object:
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(corners, [], [(0, 1, 2, 3)])
    mesh.materials.append(mat)
    ob = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(ob)
    return ob


def _group_scene() -> bpy.types.Scene:
    scene = new_scene(RES)
    set_multilayer_exr(scene.render.image_settings)
    view_layer = scene.view_layers[0]
    for group in GROUPS:
        view_layer.lightgroups.add(name=group)

    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.1, 0.15, 0.25, 1.0)
    world.lightgroup = "fill"
    scene.world = world

    add_diffuse_floor(scene, 4.0)
    red = bpy.data.materials.new("red")
    red.use_nodes = True
    red.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.15, 0.1, 1.0)
    h = 0.6
    cube = bpy.data.meshes.new("cube")
    corners = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (0.0, 2 * h)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    cube.from_pydata(corners, [], faces)
    cube.materials.append(red)
    scene.collection.objects.link(bpy.data.objects.new("cube", cube))

    panel = _quad("panel", [(1.5, -1.0, 0.01), (2.5, -1.0, 0.01), (2.5, 0.0, 0.01), (1.5, 0.0, 0.01)],
                  _emission_material("glow", (1.0, 0.6, 0.2), 4.0))
    panel.lightgroup = "key"

    area = bpy.data.lights.new("key_light", "AREA")
    area.energy = 150.0
    area.size = 1.0
    area.color = (1.0, 0.9, 0.7)
    key = bpy.data.objects.new("key_light", area)
    key.location = (-1.5, -1.0, 2.5)
    key.rotation_euler = (math.radians(-30.0), math.radians(-30.0), 0.0)
    key.lightgroup = "key"
    scene.collection.objects.link(key)

    point = bpy.data.lights.new("fill_light", "POINT")
    point.energy = 60.0
    point.shadow_soft_size = 0.2
    point.color = (0.6, 0.7, 1.0)
    fill = bpy.data.objects.new("fill_light", point)
    fill.location = (1.5, 1.5, 1.5)
    fill.lightgroup = "fill"
    scene.collection.objects.link(fill)

    add_camera(scene, 45.0, (0.0, -4.5, 3.5), (math.atan2(4.5, 3.1), 0.0, 0.0))
    return scene


def _render(renderer: str) -> dict[str, list[np.ndarray]]:
    """Per seed, Combined (RGBA) and each group's pass (RGB), rows bottom to top, float64."""
    images: dict[str, list[np.ndarray]] = {}
    for seed in SEEDS:
        scene = _group_scene()
        configure_cycles(scene, seed, samples=SPP_PER_SEED, max_bounces=MAX_BOUNCES)
        if renderer == "stratum":
            configure_stratum(scene, seed, samples=SPP_PER_SEED, max_bounces=MAX_BOUNCES)
        path: Path = GROUPS_OUT / f"{renderer}_seed{seed}.exr"
        path.parent.mkdir(parents=True, exist_ok=True)
        if path.exists():
            path.unlink()
        scene.render.filepath = str(path)
        bpy.ops.render.render(write_still=True)
        layer = scene.view_layers[0].name
        for name in ("Combined", *(f"Combined_{group}" for group in GROUPS)):
            images.setdefault(name, []).append(read_pass(path, name, layer)[::-1].astype(np.float64))
    return images


def test_light_groups_sum_to_combined_and_agree_with_cycles(library) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    cycles, stratum = _render("cycles"), _render("stratum")
    for k in range(len(SEEDS)):
        combined = stratum["Combined"][k][..., :3]
        total = sum(stratum[f"Combined_{group}"][k] for group in GROUPS)
        assert np.all(np.abs(total - combined) <= 1e-5 * np.abs(combined) + 1e-6), (
            f"seed {SEEDS[k]}: the groups do not sum to Combined; worst difference "
            f"{float(np.abs(total - combined).max()):.3g}")
    for group in GROUPS:
        name = f"Combined_{group}"
        c = Renders("cycles", cycles[name], [0.0, 0.0], BLOCK)
        s = Renders("stratum", stratum[name], [0.0, 0.0], BLOCK)
        c.calibrate()
        s.calibrate()
        compared = c.block_mean() > 0.01
        assert compared.any()
        assert_agreement(c, s, compared, f"light group {group}", GROUPS_OUT / group)
