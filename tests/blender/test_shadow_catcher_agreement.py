"""Stratum against Cycles on a shadow catcher (issue 34): a catcher floor (object.is_shadow_catcher)
under a red cube, lit by an HDRI (an equirectangular image written here: a dim sky and a bright
patch that casts the cube's shadow), in the running Blender (3.4 under run_in_blender.py, 5.0
under the bpy wheel).

Two cases, both with a transparent film (Cycles' usual catcher setup):
* "pass": View Layer > Passes > Shadow Catcher on (view_layer.cycles / view_layer.stratum
  use_pass_shadow_catcher). Compared: the Shadow Catcher pass (the catcher's light with the cube
  over its light without it, alpha-overed on white: < 1 in the shadow, 1 elsewhere), and
  Combined's alpha, which Cycles then shows as the plain matte's (the cube's coverage alone; the
  catcher transparent).
* "approximate": the pass off. Compared: Combined's alpha, Cycles' approximate matte with shadow
  (the cube's coverage, and the shadow's opacity 1 − mean(ratio) on the catcher).

The world is in the light group "sky", whose pass Combined_sky the "pass" case checks on the
catcher (the pixels whose matte alpha is 0 in every render): there it holds the world light met
after the split in Cycles before 3.5, compared with the tolerances above, and exactly 0 from 3.5
on, in Cycles' render as in Stratum's; so each Blender checks its own rule. (Elsewhere the pass
is the cube's sky light, the light groups' plain case of test_light_group_agreement.py.)

Tolerances and the noise gate are agreement.py's (test_cycles_agreement.py derives them): image
means within 2% and 16 x 16 block means within 5% per channel, blocks whose Cycles mean is
below 0.01 not compared, after 4 sigma of each difference is checked to be below half its
tolerance. RES x RES = 32 x 32 (four blocks) keeps the four renders per case cheap.
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
    image_world,
    new_scene,
    stratum_available,
)
from exr_file import read_pass
from multilayer_passes import set_multilayer_exr

RES = 32
BLOCK = 16
SPP_PER_SEED = 256
MAX_BOUNCES = 2
ENV_W, ENV_H = 32, 16
CATCHER_OUT = OUT / "shadow_catcher"
CASES = ("pass", "approximate")


def _environment_pixels() -> np.ndarray:
    """(ENV_H, ENV_W, 4) RGBA, rows bottom (nadir) to top: a blue-grey sky and ground, and a
    bright patch at about 45-56 degrees of elevation that casts a clear shadow."""
    px = np.zeros((ENV_H, ENV_W, 4), dtype=np.float32)
    px[..., :3] = (0.25, 0.3, 0.4)
    px[: ENV_H // 2, :, :3] = (0.15, 0.12, 0.1)
    px[12:13, 4:7, :3] = (40.0, 36.0, 30.0)
    px[..., 3] = 1.0
    return px


def _catcher_scene(case: str) -> bpy.types.Scene:
    scene = new_scene(RES)
    scene.render.film_transparent = True
    set_multilayer_exr(scene.render.image_settings)
    image_world(scene, "hdri", _environment_pixels()).lightgroup = "sky"

    add_diffuse_floor(scene, 4.0)
    bpy.data.objects["floor"].is_shadow_catcher = True
    red = bpy.data.materials.new("red")
    red.use_nodes = True
    red.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.15, 0.1, 1.0)
    mesh = bpy.data.meshes.new("cube")
    h = 0.6
    corners = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (0.0, 2 * h)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    mesh.from_pydata(corners, [], faces)
    mesh.materials.append(red)
    scene.collection.objects.link(bpy.data.objects.new("cube", mesh))
    # From (0, -4.5, 3.5) towards (0, 0, 0.4): tilted 55 degrees from straight down.
    add_camera(scene, 45.0, (0.0, -4.5, 3.5), (math.atan2(4.5, 3.1), 0.0, 0.0))

    use_pass = case == "pass"
    view_layer = scene.view_layers[0]
    view_layer.lightgroups.add(name="sky")
    view_layer.cycles.use_pass_shadow_catcher = use_pass
    view_layer.stratum.use_pass_shadow_catcher = use_pass
    return scene


def _configure(renderer: str, scene: bpy.types.Scene, seed: int) -> None:
    configure_cycles(scene, seed, samples=SPP_PER_SEED, max_bounces=MAX_BOUNCES)
    if renderer == "stratum":
        configure_stratum(scene, seed, samples=SPP_PER_SEED, max_bounces=MAX_BOUNCES)


def _render(case: str, renderer: str) -> dict[str, list[np.ndarray]]:
    """Per seed, the case's compared images (rows bottom to top, float64): "Combined" RGBA and,
    in the "pass" case, "Combined_sky" and "Shadow Catcher" RGB."""
    images: dict[str, list[np.ndarray]] = {}
    for seed in SEEDS:
        scene = _catcher_scene(case)
        _configure(renderer, scene, seed)
        path: Path = CATCHER_OUT / case / f"{renderer}_seed{seed}.exr"
        path.parent.mkdir(parents=True, exist_ok=True)
        if path.exists():
            path.unlink()
        scene.render.filepath = str(path)
        bpy.ops.render.render(write_still=True)
        layer = scene.view_layers[0].name
        names = ("Combined", "Combined_sky", "Shadow Catcher") if case == "pass" else ("Combined",)
        for name in names:
            pixels = read_pass(path, name, layer)[::-1].astype(np.float64)
            images.setdefault(name, []).append(pixels)
    return images


@pytest.mark.parametrize("case", CASES)
def test_shadow_catcher_agrees_with_cycles(library, case: str) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    cycles, stratum = _render(case, "cycles"), _render(case, "stratum")
    # Combined's alpha tells the two Combined modes apart (the matte's RGB, the cube's light, is
    # the same in both): the cube's coverage alone with the pass, plus the shadow without it.
    compared_images = {"Combined": lambda img: img[..., 3:4]}
    if case == "pass":
        from stratum import blender_versions

        compared_images["Shadow Catcher"] = lambda img: img[..., :3]
        catcher = np.logical_and.reduce([img[..., 3] == 0.0 for img in cycles["Combined"] + stratum["Combined"]])
        assert catcher.mean() > 0.5
        if blender_versions.lightgroups_take_split_emission(bpy.app.version):
            compared_images["Combined_sky"] = lambda img: img * catcher[..., None]
        else:
            for img in cycles["Combined_sky"] + stratum["Combined_sky"]:
                assert np.all(img[catcher] == 0.0)
    for name, part in compared_images.items():
        c = Renders("cycles", [part(img) for img in cycles[name]], [0.0, 0.0], BLOCK)
        s = Renders("stratum", [part(img) for img in stratum[name]], [0.0, 0.0], BLOCK)
        c.calibrate()
        s.calibrate()
        compared = c.block_mean() > 0.01
        assert compared.any()
        title = f"shadow catcher {case}: {name}" + (" alpha" if name == "Combined" else "")
        assert_agreement(c, s, compared, title, CATCHER_OUT / case / name.replace(" ", "_"))
