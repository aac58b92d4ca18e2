"""Issue-5 export through real renders (native library needed): border regions handed to
Blender as it expects, transparent film, holdout, image textures, motion blur."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest
from stratum.engine import StratumRenderEngine

from conftest import engine_reports
from exr_file import read_image


def _render(scene: Any, path: Path) -> np.ndarray:
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    errors = engine_reports("ERROR")
    assert not errors, errors
    return read_image(path)


@pytest.mark.parametrize("crop", [True, False])
def test_border_render_fills_the_region(library: Any, scene_builder: Any, tmp_path: Path,
                                        crop: bool) -> None:
    b = scene_builder().basic()
    b.set_resolution(64, 32)
    r = b.scene.render
    r.use_border, r.use_crop_to_border = True, crop
    r.border_min_x, r.border_max_x, r.border_min_y, r.border_max_y = 0.25, 0.75, 0.5, 1.0
    pixels = _render(b.scene, tmp_path / f"border_{crop}.exr")
    if crop:
        assert pixels.shape[:2] == (16, 32)
        assert (pixels[..., 3] > 0).all()
    else:
        assert pixels.shape[:2] == (32, 64)  # Blender pads the region back into the frame
        inside = np.zeros((32, 64), dtype=bool)
        inside[16:32, 16:48] = True  # rows bottom to top: y 16..31 is the upper half
        assert (pixels[..., 3][inside] > 0).all() and (pixels[..., 3][~inside] == 0).all()


def test_border_region_matches_the_full_frame(library: Any, scene_builder: Any,
                                              tmp_path: Path) -> None:
    """The region's pixels are the full frame's pixels there (same seed, per-pixel streams)."""
    b = scene_builder().basic()
    b.set_resolution(64, 32)
    full = _render(b.scene, tmp_path / "full.exr")
    r = b.scene.render
    r.use_border, r.use_crop_to_border = True, True
    r.border_min_x, r.border_max_x, r.border_min_y, r.border_max_y = 0.25, 0.75, 0.25, 0.75
    region = _render(b.scene, tmp_path / "region.exr")
    assert region.shape[:2] == (16, 32)
    np.testing.assert_allclose(region, full[8:24, 16:48], rtol=1e-5, atol=1e-6)


def test_film_transparent_background_alpha(library: Any, scene_builder: Any,
                                           tmp_path: Path) -> None:
    b = scene_builder().basic()
    b.scene.render.film_transparent = True
    pixels = _render(b.scene, tmp_path / "transparent.exr")
    assert pixels[0, 0, 3] == pytest.approx(0.0)  # corner: background only
    assert pixels[16, 16, 3] == pytest.approx(1.0)  # centre: the cube


def test_holdout_object_cuts_alpha(library: Any, scene_builder: Any, tmp_path: Path) -> None:
    b = scene_builder().basic()
    b.scene.objects["Cube"].is_holdout = True
    b.scene.render.film_transparent = True  # without it Cycles' holdout is black, alpha 1
    pixels = _render(b.scene, tmp_path / "holdout.exr")
    assert pixels[16, 16, 3] == pytest.approx(0.0, abs=1e-6)
    assert np.allclose(pixels[16, 16, :3], 0.0, atol=1e-6)


def test_image_texture_reaches_the_render(library: Any, scene_builder: Any,
                                          tmp_path: Path) -> None:
    """A left-black / right-white image as the colour of a diffuse camera-facing quad under a
    white world (radiance = albedo x 1): the render's left half is black, its right half
    lit."""
    b = scene_builder()
    b.camera()
    b.world((1.0, 1.0, 1.0))
    image = bpy.data.images.new("Halves", 2, 1, float_buffer=True)
    image.pixels.foreach_set(np.array([0, 0, 0, 1, 1, 1, 1, 1], dtype=np.float32))
    mat = bpy.data.materials.new("Halves")
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    nt = mat.node_tree
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.image, tex.interpolation, tex.extension = image, "Closest", "EXTEND"
    nt.links.new(tex.outputs["Color"], diffuse.inputs["Color"])
    nt.links.new(diffuse.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    quad = bpy.data.meshes.new("Quad")
    quad.from_pydata([(-4, 0, -4), (4, 0, -4), (4, 0, 4), (-4, 0, 4)], [], [(0, 1, 2, 3)])
    layer = quad.uv_layers.new(name="UVMap")
    layer.data.foreach_set("uv", np.array([0, 0, 1, 0, 1, 1, 0, 1], dtype=np.float32))
    quad.materials.append(mat)
    b.link(bpy.data.objects.new("Quad", quad))
    pixels = _render(b.scene, tmp_path / "texture.exr")
    assert pixels[:, :12, :3].mean() < 0.05
    assert pixels[:, 20:, :3].mean() > 0.5


def test_motion_blur_render(library: Any, scene_builder: Any, tmp_path: Path) -> None:
    """A cube moving sideways over the shutter: its edges are blurred (partial coverage)."""
    b = scene_builder().basic()
    b.scene.stratum.samples = 64
    cube = b.scene.objects["Cube"]
    driver = cube.driver_add("location", 0).driver
    driver.expression = "frame"
    b.scene.frame_set(0)
    b.scene.render.use_motion_blur = True
    b.scene.render.motion_blur_shutter = 1.0  # x from -0.5 to 0.5 over the shutter
    b.scene.render.film_transparent = False
    pixels = _render(b.scene, tmp_path / "motion.exr")
    assert StratumRenderEngine.last_summary.moving_instances == 1
    row = pixels[16, :, :3].mean(axis=1)
    background = row[0]
    # The blurred edge ramps over several pixels instead of one step.
    ramp = np.abs(np.diff(row))
    assert (ramp > 0.02 * abs(row.max() - background)).sum() >= 3


def test_object_camera_visibility_reaches_the_render(library: Any, scene_builder: Any,
                                                      tmp_path: Path) -> None:
    """A cube hidden from camera rays: the image is the world colour everywhere."""
    b = scene_builder().basic()
    b.scene.objects["Cube"].visible_camera = False
    hidden = _render(b.scene, tmp_path / "hidden.exr")
    assert hidden[..., :3] == pytest.approx(np.full_like(hidden[..., :3], 0.05), abs=1e-4)


def test_light_diffuse_visibility_reaches_the_render(library: Any, scene_builder: Any,
                                                     tmp_path: Path) -> None:
    """A light invisible to diffuse rays leaves the (diffuse) cube lit by the world only."""
    b = scene_builder().basic()
    lit = _render(b.scene, tmp_path / "lit.exr")[12:20, 12:20, :3].mean()
    b.scene.objects["Light"].visible_diffuse = False
    unlit = _render(b.scene, tmp_path / "unlit.exr")[12:20, 12:20, :3].mean()
    assert unlit < 0.5 * lit


def test_equirectangular_camera_renders(library: Any, scene_builder: Any,
                                        tmp_path: Path) -> None:
    """A panorama from the camera: the cube occupies a patch around the view direction, the
    rest of the sphere of directions is the world colour."""
    b = scene_builder().basic()
    cam = b.scene.camera.data
    cam.type = "PANO"
    source = cam if bpy.app.version >= (4, 0, 0) else cam.cycles
    source.panorama_type = "EQUIRECTANGULAR"
    b.set_resolution(64, 32)
    pixels = _render(b.scene, tmp_path / "pano.exr")
    assert pixels.shape[:2] == (32, 64)
    world = np.isclose(pixels[..., :3], 0.05, atol=1e-4).all(axis=2)
    assert 0.5 < world.mean() < 1.0


def test_mixed_and_added_emission_closures_render_their_weights(
        library: Any, scene_builder: Any, tmp_path: Path) -> None:
    """Add(Mix(red, blue, 0.25), green x 0.5) emission on a quad filling the view, black world:
    every pixel is (0.75, 0.5, 0.25) -- the closure weights, end to end."""
    b = scene_builder()
    b.camera()
    b.world((0.0, 0.0, 0.0))
    mat = bpy.data.materials.new("Weights")
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    nt = mat.node_tree
    emissions = []
    for color, strength in (((1, 0, 0, 1), 1.0), ((0, 0, 1, 1), 1.0), ((0, 1, 0, 1), 0.5)):
        node = nt.nodes.new("ShaderNodeEmission")
        node.inputs["Color"].default_value = color
        node.inputs["Strength"].default_value = strength
        emissions.append(node)
    mix, add = nt.nodes.new("ShaderNodeMixShader"), nt.nodes.new("ShaderNodeAddShader")
    mix.inputs[0].default_value = 0.25
    nt.links.new(emissions[0].outputs[0], mix.inputs[1])
    nt.links.new(emissions[1].outputs[0], mix.inputs[2])
    nt.links.new(mix.outputs[0], add.inputs[0])
    nt.links.new(emissions[2].outputs[0], add.inputs[1])
    nt.links.new(add.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    quad = bpy.data.meshes.new("Quad")
    quad.from_pydata([(-4, 0, -4), (4, 0, -4), (4, 0, 4), (-4, 0, 4)], [], [(0, 1, 2, 3)])
    quad.materials.append(mat)
    b.link(bpy.data.objects.new("Quad", quad))
    pixels = _render(b.scene, tmp_path / "weights.exr")
    assert pixels[..., :3].reshape(-1, 3).mean(axis=0) == pytest.approx((0.75, 0.5, 0.25),
                                                                        abs=1e-3)
