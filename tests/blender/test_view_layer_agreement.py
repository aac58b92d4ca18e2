"""Stratum against Cycles on the View Layer switches and on Light Paths > Caustics (issue 34,
acceptance 1): Environment off, material override, the layer's samples, Filter Glossy 1, and
caustics off behind glass and via a mirror, in the running Blender.

Runs in Blender 3.4 (run_in_blender.py) and under the bpy wheels.

Deterministic cases (render_pixel_centres: one sample at each pixel's centre, box filter of
0.01 px, so each pixel is one camera ray, compared per pixel within PIXEL_TOL):

* Environment off (view_layer.use_sky): a bright world over a diffuse floor, transparent film.
  Cycles renders the floor exactly black (the world neither shows nor lights) with alpha 1, and
  the background with alpha 0: RGBA per pixel.
* Surfaces off (view_layer.use_solid) and, in 5.0, the world override: every pixel is the
  override's world colour, the floor gone.
* Material override: a floor with a diffuse material and a cube without material slots, both
  rendered with the layer's Emission override (camera rays see its emission only), the world
  kept.
* Samples (view_layer.samples with scene.cycles.use_layer_samples): the Debug Sample Count pass
  Stratum writes holds the samples the layer renders with, Cycles' rule for USE, BOUNDED and
  IGNORE (session.cpp). Stratum only: the count a renderer reports is its own.

Statistical cases, with the machinery and the tolerances of agreement.py (image means within 2%
and 16 x 16 block means within 5% per channel after the noise gate, 4 sigma of each difference
below half its tolerance; test_cycles_agreement.py derives them), at RES x RES,
two seeds (samples per seed in CASES), Stratum reading Cycles' values as a file tuned for Cycles does (light_paths CYCLES):

* filter_glossy: a diffuse floor lit by a spot lamp only through a mirror tile above it (a
  Glossy BSDF of roughness 0); sharp, no path finds that light; blur_glossy 1 widens the
  mirror after the floor's diffuse bounce, and the tile's light sample brings it.
* caustics_off: the same floor under a smooth glass slab and beside the mirror, lit from above;
  with caustics_reflective and caustics_refractive off the floor gets no light through either.
  Unfiltered, most of the light under the slab and off the mirror would be there.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import bpy
import numpy as np
import pytest

from agreement import (
    OUT,
    Renders,
    add_camera,
    add_diffuse_floor,
    assert_agreement,
    configure_cycles,
    configure_stratum,
    new_scene,
    render_two_seeds,
    stratum_available,
)
from exr_file import read_image, read_pass
from multilayer_passes import result_name, set_multilayer_exr

RES = 32
BLOCK = 16
PIXEL_RES = 16
PIXEL_TOL = 1e-3
LAYER_OUT = OUT / "view_layer"


@pytest.fixture(autouse=True)
def _stratum(library: Any) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)


# ---- scenes ------------------------------------------------------------------------------------


def _node_material(name: str, node_type: str, inputs: dict[str, Any],
                   **attributes: Any) -> bpy.types.Material:
    """A material of one shader node wired to the output."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    for n in list(nodes):
        if n.bl_idname != "ShaderNodeOutputMaterial":
            nodes.remove(n)
    node = nodes.new(node_type)
    for key, value in attributes.items():
        setattr(node, key, value)
    for key, value in inputs.items():
        node.inputs[key].default_value = value
    mat.node_tree.links.new(node.outputs[0], nodes["Material Output"].inputs["Surface"])
    return mat


def _world(scene: bpy.types.Scene, strength: float, color: float = 1.0) -> None:
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (color, color, color, 1.0)
    background.inputs["Strength"].default_value = strength
    scene.world = world


def _quad(scene: bpy.types.Scene, name: str, corners: list[tuple[float, float, float]],
          material: bpy.types.Material | None) -> bpy.types.Object:
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(corners, [], [(0, 1, 2, 3)])
    if material is not None:
        mesh.materials.append(material)
    ob = bpy.data.objects.new(name, mesh)
    scene.collection.objects.link(ob)
    return ob


def _box(scene: bpy.types.Scene, name: str, centre: tuple[float, float, float],
         half: tuple[float, float, float], material: bpy.types.Material | None) -> None:
    """An axis-aligned box of outward faces."""
    cx, cy, cz = centre
    hx, hy, hz = half
    verts = [(cx + sx * hx, cy + sy * hy, cz + sz * hz)
             for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    if material is not None:
        mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new(name, mesh))


def _area_lamp(scene: bpy.types.Scene, location: tuple[float, float, float],
               rotation: tuple[float, float, float], size: float, power: float) -> None:
    lamp = bpy.data.lights.new("lamp", "AREA")
    lamp.size = size
    lamp.energy = power
    ob = bpy.data.objects.new("lamp", lamp)
    ob.location = location
    ob.rotation_euler = rotation
    scene.collection.objects.link(ob)


def _floor_view(res: int) -> bpy.types.Scene:
    """A 0.8 grey diffuse floor 6 x 6 at z = 0 seen from above at 45 degrees: the floor fills
    the lower two thirds of the view, the background the rest."""
    scene = new_scene(res)
    add_diffuse_floor(scene, 3.0)
    add_camera(scene, 30.0, (0.0, -3.5, 3.0), (math.radians(45.0), 0.0, 0.0))
    return scene


def _mirror(scene: bpy.types.Scene) -> None:
    """A perfect mirror wall at x = 1, facing -x (Glossy BSDF, roughness 0)."""
    mirror = _node_material("mirror", "ShaderNodeBsdfGlossy",
                            {"Color": (0.9, 0.9, 0.9, 1.0), "Roughness": 0.0})
    _quad(scene, "mirror", [(1.0, -3.0, 0.0), (1.0, 3.0, 0.0), (1.0, 3.0, 1.5),
                            (1.0, -3.0, 1.5)], mirror)


def _filter_glossy_scene() -> bpy.types.Scene:
    """The floor lit only through a mirror tile: a spot lamp of radius 0 facing up into a 3 x 3
    mirror (Glossy BSDF, roughness 0) 0.6 above it, which faces down; the world black. Sharp,
    the mirror passes none of the lamp's light to the floor (a delta lamp seen in a delta mirror:
    no path finds it); blurred after the floor's diffuse bounce (alpha about 0.45), the tile's
    light sample does."""
    scene = new_scene(RES)
    add_diffuse_floor(scene, 3.0)
    # Under the tile, looking down at the floor it lights.
    add_camera(scene, 20.0, (-0.5, -1.9, 0.9), (math.radians(55.0), 0.0, 0.0))
    _world(scene, 0.0)
    mirror = _node_material("mirror", "ShaderNodeBsdfGlossy",
                            {"Color": (0.9, 0.9, 0.9, 1.0), "Roughness": 0.0})
    x, y, h = -0.5, -0.5, 1.5
    _quad(scene, "tile", [(x - h, y - h, 1.0), (x - h, y + h, 1.0), (x + h, y + h, 1.0),
                          (x + h, y - h, 1.0)], mirror)
    lamp = bpy.data.lights.new("spot", "SPOT")
    lamp.energy = 100.0
    lamp.shadow_soft_size = 0.0
    lamp.spot_size = math.radians(120.0)
    lamp.spot_blend = 0.0
    ob = bpy.data.objects.new("spot", lamp)
    ob.location = (x, y, 0.4)
    ob.rotation_euler = (math.pi, 0.0, 0.0)  # facing +z
    scene.collection.objects.link(ob)
    return scene


def _caustics_scene() -> bpy.types.Scene:
    """The floor under a smooth glass slab (x in [-1.5, 0]) and beside the mirror, lit by an area
    lamp above; the world black."""
    scene = _floor_view(RES)
    _world(scene, 0.0)
    _mirror(scene)
    glass = _node_material("glass", "ShaderNodeBsdfGlass",
                           {"Color": (1.0, 1.0, 1.0, 1.0), "Roughness": 0.0, "IOR": 1.45},
                           distribution="GGX")
    _box(scene, "slab", (-0.75, 0.0, 0.6), (0.75, 1.5, 0.05), glass)
    _area_lamp(scene, (-0.3, -1.0, 2.5), (0.0, 0.0, 0.0), 0.5, 400.0)
    return scene


# ---- deterministic cases ------------------------------------------------------------------------


def _render_rgba(scene: bpy.types.Scene, engine: str, path: Path) -> np.ndarray:
    """RGBA of one camera ray per pixel centre (agreement.render_pixel_centres' settings)."""
    scene.render.engine = engine
    if engine == "CYCLES":
        c = scene.cycles
        c.device, c.samples, c.use_denoising = "CPU", 1, False
        c.use_adaptive_sampling = False
        c.pixel_filter_type, c.filter_width = "BOX", 0.01
    else:
        s = scene.stratum
        s.light_paths = "STRATUM"
        s.samples, s.filter_type, s.filter_width = 1, "box", 0.01
    path.parent.mkdir(parents=True, exist_ok=True)
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return read_image(path)[..., :4].astype(np.float64)


def _both(build: Any, name: str) -> tuple[np.ndarray, np.ndarray]:
    images = []
    for engine in ("CYCLES", "STRATUM"):
        images.append(_render_rgba(build(), engine, LAYER_OUT / f"{name}_{engine.lower()}.exr"))
    return images[0], images[1]


def _environment_off() -> bpy.types.Scene:
    scene = _floor_view(PIXEL_RES)
    _world(scene, 5.0)
    scene.render.film_transparent = True
    scene.view_layers[0].use_sky = False
    return scene


def test_environment_off_neither_shows_nor_lights_the_world() -> None:
    cycles, stratum = _both(_environment_off, "environment_off")
    # What Cycles does: the floor is black and opaque, the background transparent.
    assert np.all(cycles[..., :3] == 0.0)
    assert (cycles[..., 3] == 1.0).any() and (cycles[..., 3] == 0.0).any()
    np.testing.assert_allclose(stratum, cycles, atol=PIXEL_TOL)


def _material_override() -> bpy.types.Scene:
    scene = _floor_view(PIXEL_RES)
    _world(scene, 1.0, color=0.1)
    _box(scene, "cube", (0.0, 0.0, 0.3), (0.3, 0.3, 0.3), None)  # no material slots
    override = _node_material("override", "ShaderNodeEmission",
                              {"Color": (0.2, 0.5, 0.8, 1.0), "Strength": 1.0})
    scene.view_layers[0].material_override = override
    return scene


def test_material_override_replaces_every_slot_and_the_default() -> None:
    cycles, stratum = _both(_material_override, "material_override")
    emission = np.array([0.2, 0.5, 0.8])
    seen = np.all(np.abs(cycles[..., :3] - emission) < PIXEL_TOL, axis=-1)
    assert seen.sum() > PIXEL_RES * PIXEL_RES // 2  # the floor and the cube, not the world
    np.testing.assert_allclose(stratum, cycles, atol=PIXEL_TOL)


def _surfaces_off() -> bpy.types.Scene:
    scene = _floor_view(PIXEL_RES)
    _world(scene, 1.0, color=0.1)
    layer = scene.view_layers[0]
    layer.use_solid = False
    if hasattr(layer, "world_override"):  # Blender 5.0
        override = bpy.data.worlds.new("override")
        override.use_nodes = True
        override.node_tree.nodes["Background"].inputs["Color"].default_value = (0.6, 0.3, 0.2, 1)
        layer.world_override = override
    return scene


def test_surfaces_off_and_the_world_override() -> None:
    """Surfaces off: the floor is gone, every pixel is the world; 5.0's world override is that
    world."""
    cycles, stratum = _both(_surfaces_off, "surfaces_off")
    has_override = "world_override" in bpy.types.ViewLayer.bl_rna.properties
    world = (0.6, 0.3, 0.2) if has_override else (0.1, 0.1, 0.1)
    np.testing.assert_allclose(cycles[..., :3], np.broadcast_to(world, cycles[..., :3].shape),
                               atol=PIXEL_TOL)
    np.testing.assert_allclose(stratum, cycles, atol=PIXEL_TOL)


@pytest.mark.parametrize(("mode", "own", "samples"), [
    ("USE", 3, 3), ("USE", 0, 5), ("BOUNDED", 3, 3), ("BOUNDED", 9, 5), ("IGNORE", 3, 5)])
def test_the_layer_samples_rule_is_cycles(mode: str, own: int, samples: int) -> None:
    from stratum.engine.frame import layer_samples

    scene = SimpleNamespace(cycles=SimpleNamespace(use_layer_samples=mode))
    assert layer_samples(scene, SimpleNamespace(samples=own), 5) == samples


def test_a_render_takes_the_view_layers_samples(tmp_path: Path) -> None:
    scene = _floor_view(8)
    scene.render.engine = "STRATUM"
    scene.stratum.samples = 16
    scene.cycles.use_layer_samples = "BOUNDED"
    layer = scene.view_layers[0]
    layer.samples = 3
    layer.stratum.use_pass_sample_count = True
    set_multilayer_exr(scene.render.image_settings)
    path = tmp_path / "samples.exr"
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    count = read_pass(path, result_name("Debug Sample Count"), layer.name)
    assert np.all(count == 3.0), np.unique(count)


# ---- statistical cases --------------------------------------------------------------------------

# name -> (scene, the scene.cycles values the case sets, samples per seed: what the noise gate
# needs).
CASES = {
    "filter_glossy": (_filter_glossy_scene, {"blur_glossy": 1.0}, 1024),
    "caustics_off": (_caustics_scene, {"caustics_reflective": False,
                                       "caustics_refractive": False}, 256),
}


def _configure(case: str, engine: str, scene: bpy.types.Scene, seed: int) -> None:
    _, values, samples = CASES[case]
    configure_cycles(scene, seed, samples=samples)
    for name, value in values.items():
        setattr(scene.cycles, name, value)
    if engine == "stratum":
        configure_stratum(scene, seed, samples=samples)
        scene.stratum.light_paths = "CYCLES"
        # Stratified as Cycles' own samples are (test_light_path_agreement.py says why): with
        # the independent sampler Stratum's noise alone needs about 3x the samples.
        scene.stratum.sampler = "sobol"


def _render(case: str, engine: str) -> Renders:
    return render_two_seeds(engine, functools.partial(_configure, case, engine),
                            LAYER_OUT / case, CASES[case][0], res=RES, block=BLOCK)


@pytest.mark.parametrize("case", list(CASES))
def test_caustics_switches_agree_with_cycles(case: str) -> None:
    cycles = _render(case, "cycles")
    stratum = _render(case, "stratum")
    compared = cycles.block_mean() > 0.01
    assert compared.any()
    assert_agreement(cycles, stratum, compared, f"view layer / caustics {case}", LAYER_OUT / case)
