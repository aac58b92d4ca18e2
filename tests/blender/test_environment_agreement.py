"""Stratum against Cycles on an Environment Texture world, in the running Blender.

Runs in Blender 3.4 (`blender -b --factory-startup --python tests/blender/run_in_blender.py --
tests/blender/test_environment_agreement.py`) and under the bpy wheel (`.venv/bin/python -m
pytest tests/blender/test_environment_agreement.py`). Rendering, EXR reading and the noise
estimates are those of agreement.py (imported; test_cycles_agreement.py's docstring has the
statistics).

Scene: a 40 m diffuse plane (Diffuse BSDF, 0.8) lit only by the world: Background (strength
STRENGTH) <- Environment Texture (equirectangular, interpolation Closest, as Stratum looks it up)
of a generated ENV_W x ENV_H float image (bpy.data.images.new(float_buffer=True), filled in the
test): a sky whose colour changes with azimuth and elevation, a bright patch, and a ground of
another colour. A 90-degree camera 1 m above the plane looks along +X rotated by 30 degrees, so
the upper half of the image is the sky itself (the equirectangular mapping: u, v, orientation)
and the lower half the plane (the image's integral, sampled by NEE and BSDF rays under MIS).
max_bounces 0, RES x RES = 32 x 32, Blackman-Harris 1.5 px, two seeds per renderer. Two
variants: the texture's Vector input unlinked, and Texture Coordinate Generated -> Mapping
(Point, rotation Z = MAPPING_Z) -> Vector, which Stratum takes as a world-to-environment
rotation.

Asserted per RGB channel: image means within 2%, and 8 x 8 block means within 5% (every
block is lit).

Statistical reasoning. The sky pixels vary only by where the pixel filter puts the samples
(texel edges inside a pixel's footprint); the plane's by the environment sampling. The module
measures both renderers' noise from the half difference of the two seeds and asserts first that
4 sigma of every compared difference is below half its tolerance (so the comparison tests the
model, not the noise), with 2 x SPP_PER_SEED samples per pixel. A wrong mapping (u mirrored or
shifted by half a turn, v flipped) moves the sky's features by many pixels and fails whole
blocks; a wrong pdf or MIS weight changes the plane's brightness.
"""

from __future__ import annotations

import functools
import math

import bpy
import numpy as np
import pytest

from agreement import (
    K_SIGMA,
    OUT,
    Renders,
    configure_cycles,
    configure_stratum,
    per_channel,
    render_exr,
    set_frame_and_exr,
    stratum_available,
)

RES = 32
BLOCK = 8
SPP_PER_SEED = 1024
SEEDS = (1, 2)
IMAGE_TOL = 0.02
BLOCK_TOL = 0.05
ENV_W, ENV_H = 32, 16
STRENGTH = 1.5
MAPPING_Z = math.radians(60.0)
VARIANTS = ("unmapped", "mapping")
ENV_OUT = OUT.parent / (OUT.name + "-environment")


def _environment_pixels() -> np.ndarray:
    """(ENV_H, ENV_W, 4) RGBA, rows bottom (-Z) to top as Blender stores them."""
    px = np.zeros((ENV_H, ENV_W, 4), dtype=np.float32)
    for row in range(ENV_H):
        v = (row + 0.5) / ENV_H  # 0 at the bottom (nadir), 1 at the top (zenith)
        for col in range(ENV_W):
            u = (col + 0.5) / ENV_W
            if v > 0.5:  # sky
                elevation = v - 0.5
                r = 0.4 + 0.3 * math.sin(2 * math.pi * u)
                g = 0.5 + 0.3 * math.cos(2 * math.pi * u) * (1.0 - elevation)
                b = 0.6 + 0.8 * elevation
            else:  # ground
                r, g, b = 0.3, 0.2 + 0.2 * u, 0.1
            px[row, col] = (r, g, b, 1.0)
    px[10:12, 20:24, :3] = (6.0, 5.0, 3.0)  # a bright patch in the sky
    return px


def _environment_scene(variant: str = "unmapped") -> bpy.types.Scene:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    set_frame_and_exr(scene, RES)
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"

    image = bpy.data.images.new("sky", ENV_W, ENV_H, alpha=True, float_buffer=True)
    image.pixels.foreach_set(_environment_pixels().reshape(-1))
    image.update()
    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    nodes = world.node_tree.nodes
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = image
    env.interpolation = "Closest"
    background = nodes["Background"]
    background.inputs["Strength"].default_value = STRENGTH
    world.node_tree.links.new(env.outputs["Color"], background.inputs["Color"])
    if variant == "mapping":
        coords = nodes.new("ShaderNodeTexCoord")
        mapping = nodes.new("ShaderNodeMapping")
        mapping.vector_type = "POINT"
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, MAPPING_Z)
        world.node_tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        world.node_tree.links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    scene.world = world

    mat = bpy.data.materials.new("floor")
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    for n in list(nodes):
        if n.bl_idname != "ShaderNodeOutputMaterial":
            nodes.remove(n)
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    mat.node_tree.links.new(diffuse.outputs[0], nodes["Material Output"].inputs["Surface"])
    mesh = bpy.data.meshes.new("floor")
    h = 20.0
    mesh.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(mat)
    scene.collection.objects.link(bpy.data.objects.new("floor", mesh))

    cam = bpy.data.cameras.new("cam")
    cam.sensor_fit = "HORIZONTAL"
    cam.sensor_width = 36.0
    cam.lens = 18.0  # 90 degrees
    camera = bpy.data.objects.new("cam", cam)
    camera.location = (0.0, 0.0, 1.0)
    # Looks down local -Z: Rx(90) turns it to +Y, Rz(-60) then to 30 degrees left of +X.
    camera.rotation_euler = (math.pi / 2, 0.0, math.radians(-60.0))
    scene.collection.objects.link(camera)
    scene.camera = camera
    return scene


# Direct light only (max_bounces 0), with the shared peer settings of the Cornell-box test.
_configure_cycles = functools.partial(configure_cycles, samples=SPP_PER_SEED, max_bounces=0)
_configure_stratum = functools.partial(configure_stratum, samples=SPP_PER_SEED, max_bounces=0)


def _render_two_seeds(name: str, configure, variant: str) -> Renders:
    images, seconds = [], []
    for seed in SEEDS:
        scene = _environment_scene(variant)
        configure(scene, seed)
        img, sec = render_exr(scene, ENV_OUT / f"{name}_{variant}_seed{seed}.exr", RES)
        images.append(img)
        seconds.append(sec)
    renders = Renders(name, images, seconds, BLOCK)
    renders.calibrate()
    return renders


@pytest.fixture(scope="module", params=VARIANTS)
def variant(request) -> str:
    return request.param


@pytest.fixture(scope="module")
def cycles_env(variant: str) -> Renders:
    return _render_two_seeds("cycles", _configure_cycles, variant)


@pytest.fixture(scope="module")
def stratum_env(library, variant: str) -> Renders:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    return _render_two_seeds("stratum", _configure_stratum, variant)


@pytest.mark.parametrize("kind", VARIANTS)
def test_environment_texture_is_exported_without_warnings(recording_scene, kind: str) -> None:
    from stratum.export import export_scene

    scene = _environment_scene(kind)
    summary = export_scene(bpy.context.evaluated_depsgraph_get(), recording_scene)
    assert summary.warnings == []
    env = recording_scene.environment
    assert env is not None and env["strength"] == pytest.approx(STRENGTH)
    c, s = (math.cos(MAPPING_Z), math.sin(MAPPING_Z)) if kind == "mapping" else (1.0, 0.0)
    np.testing.assert_allclose(np.asarray(env["rotation"]).reshape(3, 3),
                               [[c, -s, 0], [s, c, 0], [0, 0, 1]], atol=1e-6)
    # Rows top to bottom: the exported image is Blender's flipped vertically.
    expected = _environment_pixels()[::-1, :, :3]
    np.testing.assert_array_equal(env["rgb"], expected)
    assert scene.world.name == "sky"


def test_unsupported_environment_setups_warn_and_fall_back(recording_scene) -> None:
    from stratum.export import export_scene

    scene = _environment_scene("mapping")
    nodes = scene.world.node_tree.nodes
    mapping = next(n for n in nodes if n.bl_idname == "ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.3, 0.0, 0.0)  # not about Z
    summary = export_scene(bpy.context.evaluated_depsgraph_get(), recording_scene)
    assert len(summary.warnings) == 1 and "Vector input" in summary.warnings[0]
    np.testing.assert_array_equal(recording_scene.environment["rotation"], np.eye(3))

    env = next(n for n in nodes if n.bl_idname == "ShaderNodeTexEnvironment")
    env.image = None
    recording_scene.environment = None
    summary = export_scene(bpy.context.evaluated_depsgraph_get(), recording_scene)
    assert any("has no image" in w for w in summary.warnings)
    assert recording_scene.environment is None  # the constant background applies


def test_environment_agrees_with_cycles(cycles_env: Renders, stratum_env: Renders,
                                        variant: str) -> None:
    c, s = cycles_env, stratum_env
    c_img, s_img = c.mean.mean(axis=(0, 1)), s.mean.mean(axis=(0, 1))
    img_sigma = np.sqrt(c.image_var() + s.image_var())
    cb, sb = c.block_mean(), s.block_mean()
    sigma_b = np.sqrt(c.block_var() + s.block_var())
    assert (cb > 0).all()
    # The comparison is meaningful: 4 sigma of the differences well below the tolerances.
    assert (K_SIGMA * img_sigma < 0.5 * IMAGE_TOL * c_img).all()
    assert (K_SIGMA * sigma_b < 0.5 * BLOCK_TOL * cb).all(), (
        f"block noise too high: worst 4 sigma {float((K_SIGMA * sigma_b / cb).max()):.2%}")

    img_rel = (s_img - c_img) / c_img
    blk_rel = (sb - cb) / cb
    report = (f"environment texture ({variant}), Blender {bpy.app.version_string}: image mean "
              f"cycles "
              f"{per_channel(c_img)}, stratum {per_channel(s_img)}, "
              f"rel {per_channel(img_rel, '{:+.3%}')}; "
              f"blocks: worst rel {float(np.abs(blk_rel).max()):+.2%}, worst 4 sigma "
              f"{float((K_SIGMA * sigma_b / cb).max()):.2%}\n"
              + "\n".join("  " + " ".join(f"{100 * blk_rel[by, bx].mean():+7.2f}%"
                                          for bx in range(RES // BLOCK))
                          for by in reversed(range(RES // BLOCK))))
    ENV_OUT.mkdir(parents=True, exist_ok=True)
    (ENV_OUT / f"report_{variant}.txt").write_text(report + "\n")
    print("\n" + report)
    assert (np.abs(img_rel) <= IMAGE_TOL).all(), report
    assert (np.abs(blk_rel) <= BLOCK_TOL).all(), report
