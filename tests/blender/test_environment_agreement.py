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

Asserted per RGB channel (agreement.assert_agreement): image means within 2%, and 8 x 8 block
means within 5% (agreement.py's IMAGE_TOL, BLOCK_TOL; every block is lit).

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
    OUT,
    Renders,
    add_camera,
    add_diffuse_floor,
    assert_agreement,
    configure_cycles,
    configure_stratum,
    image_world,
    new_scene,
    render_two_seeds,
    stratum_available,
)

RES = 32
BLOCK = 8
SPP_PER_SEED = 1024
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
    scene = new_scene(RES)
    world = image_world(scene, "sky", _environment_pixels())
    nodes = world.node_tree.nodes
    env = nodes["Environment Texture"]
    nodes["Background"].inputs["Strength"].default_value = STRENGTH
    if variant == "mapping":
        coords = nodes.new("ShaderNodeTexCoord")
        mapping = nodes.new("ShaderNodeMapping")
        mapping.vector_type = "POINT"
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, MAPPING_Z)
        world.node_tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        world.node_tree.links.new(mapping.outputs["Vector"], env.inputs["Vector"])

    add_diffuse_floor(scene, 20.0)
    # Looks down local -Z: Rx(90) turns it to +Y, Rz(-60) then to 30 degrees left of +X.
    add_camera(scene, 18.0, (0.0, 0.0, 1.0), (math.pi / 2, 0.0, math.radians(-60.0)))  # 90 deg
    return scene


# Direct light only (max_bounces 0), with the shared peer settings of the Cornell-box test.
_configure_cycles = functools.partial(configure_cycles, samples=SPP_PER_SEED, max_bounces=0)
_configure_stratum = functools.partial(configure_stratum, samples=SPP_PER_SEED, max_bounces=0)


def _render_two_seeds(name: str, configure, variant: str) -> Renders:
    """EXRs in ENV_OUT/<variant>/<name>_seed<seed>.exr."""
    return render_two_seeds(name, configure, ENV_OUT / variant,
                            functools.partial(_environment_scene, variant), res=RES, block=BLOCK)


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
    from stratum.export.sync import export_scene

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
    from stratum.export.sync import export_scene

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
    compared = cycles_env.block_mean() > 0
    assert compared.all()
    assert_agreement(cycles_env, stratum_env, compared, f"environment texture ({variant})",
                     ENV_OUT / variant)
