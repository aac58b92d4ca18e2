"""Camera effects against Cycles: the Cornell box through an orthographic camera and through a
thin lens with strong depth of field, rendered by Cycles and by Stratum, must agree.

Runs in Blender 3.4 (`blender -b --factory-startup -noaudio --python
tests/blender/run_in_blender.py -- tests/blender/test_camera_agreement.py`) and under the bpy
5.0 wheel (`.venv/bin/python -m pytest tests/blender/test_camera_agreement.py`).

Scene set-up, renderer settings (same filter, bounces, no denoising / adaptive sampling /
clamping) and the Stratum-availability check are imported from agreement.py; see
test_cycles_agreement.py's docstring for the statistics, restated briefly here.

Cameras (scenes/cornell_box.blend, camera at (0, -3.4, 1) looking along +Y)
* ortho: type ORTHO, ortho_scale 1.8 (AUTO fit), shift (0.05, -0.03): the back wall, the box
  fronts and the sphere, seen along parallel rays;
* dof: perspective lens 40 mm, dof f/0.1 -> Cycles aperture radius 40e-3/(2 x 0.1) = 0.2 m, a
  6-blade aperture rotated 0.3 rad, focused on the Sphere object (distance along the view
  axis 3.1 m): the back wall (depth 4.4 m) is blurred over ~0.2 x 1.3/3.1 = 0.08 m, the edges
  of the room over several pixels.

Statistics: each renderer renders each camera with seeds 1 and 2 at SPP_PER_SEED samples; the
compared image is their mean (N = 2 SPP_PER_SEED samples per pixel) and the half difference
(A1 - A2)/2 estimates its noise per pixel, Var[X_p] ~ ((A1_p - A2_p)/2)^2. Pixels are
independent (both renderers importance-sample the pixel filter), so a block mean of n pixels
has Var = sum_p Var[X_p] / n^2, and the difference D of the two renderers' block means has
Var[D] = Var_S + Var_C. With the Cornell box's per-sample relative deviation r_b <= 3.7 in
the worst 16x16 block (measured in test_cycles_agreement.py) and N = 2048:
4 sigma_rel(D) = 4 sqrt(2) 3.7 / sqrt(256 x 2048) = 2.9% < 5% (block tolerance), and for the
32x32 image mean (r ~ 1.3) 4 sqrt(2) 1.3 / sqrt(1024 x 2048) = 0.5% < 2%. Measured (bpy 5.0):
1 sigma of the image-mean difference 0.33..0.40% with DOF (4 sigma 1.6% < 2%: the blur
mixes dark border and lit wall, raising r), 4 sigma of the block differences 1.4..3.1%; the
agreement was within 0.4% (image) and 1% (blocks) for both cameras. The tests assert
exactly this with the measured sigmas (4 sigma_D below the tolerance for the image means and
for every compared block) before comparing, so a failure beyond tolerance has a probability
below ~1e-4 per value of being noise: it is a difference in the camera models.

Cost: 32 x 32 x 1024 = 1 M paths per render, 8 renders (2 cameras x 2 renderers x 2 seeds).
Images for humans: out/agreement/blender-<version>-camera/<camera>_<renderer>_seed<k>.exr and
report_<camera>.txt.
"""

from __future__ import annotations

import math
from pathlib import Path

import bpy
import numpy as np
import pytest

from agreement import (
    CHANNELS,
    DARK_BLOCK,
    K_SIGMA,
    OUT,
    configure_cycles,
    configure_stratum,
    load_exr,
    open_scene,
    per_channel,
    stratum_available,
)

RES = 32
BLOCK = 16
SPP_PER_SEED = 1024  # two seeds -> N = 2048 samples per pixel
SEEDS = (1, 2)
IMAGE_TOL = 0.02
BLOCK_TOL = 0.05
CAMERA_OUT = OUT.parent / (OUT.name + "-camera")
CAMERAS = ("ortho", "dof")


def _set_camera(scene: bpy.types.Scene, camera: str) -> None:
    cam = scene.camera.data
    if camera == "ortho":
        cam.type = "ORTHO"
        cam.ortho_scale = 1.8
        cam.shift_x, cam.shift_y = 0.05, -0.03
    else:
        cam.type = "PERSP"
        cam.dof.use_dof = True
        cam.dof.aperture_fstop = 0.1
        cam.dof.focus_object = bpy.data.objects["Sphere"]
        cam.dof.aperture_blades = 6
        cam.dof.aperture_rotation = 0.3


def _render(renderer: str, camera: str, seed: int) -> np.ndarray:
    scene = open_scene()
    scene.render.resolution_x = scene.render.resolution_y = RES
    (configure_cycles if renderer == "cycles" else configure_stratum)(scene, seed)
    if renderer == "cycles":
        scene.cycles.samples = SPP_PER_SEED
    else:
        scene.stratum.samples = SPP_PER_SEED
    _set_camera(scene, camera)
    path = CAMERA_OUT / f"{camera}_{renderer}_seed{seed}.exr"
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.exists():
        path.unlink()
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    assert path.is_file(), f"render did not write {path}"
    return load_exr(path, RES)


class TwoSeeds:
    """Mean of two seeds and the variance estimates of its image and block means."""

    def __init__(self, a: np.ndarray, b: np.ndarray) -> None:
        self.mean = (a + b) / 2.0
        self.pixel_var = ((a - b) / 2.0) ** 2

    @staticmethod
    def _blocks(img: np.ndarray) -> np.ndarray:
        nb = RES // BLOCK
        return img.reshape(nb, BLOCK, nb, BLOCK, img.shape[-1])

    def block_mean(self) -> np.ndarray:
        return self._blocks(self.mean).mean(axis=(1, 3))

    def block_var(self) -> np.ndarray:
        return self._blocks(self.pixel_var).sum(axis=(1, 3)) / (BLOCK * BLOCK) ** 2

    def image_var(self) -> np.ndarray:
        return self.pixel_var.sum(axis=(0, 1)) / (RES * RES) ** 2


@pytest.fixture(scope="module")
def renders(library) -> dict[tuple[str, str], TwoSeeds]:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    return {(r, c): TwoSeeds(*(_render(r, c, s) for s in SEEDS))
            for c in CAMERAS for r in ("cycles", "stratum")}


@pytest.mark.parametrize("camera", CAMERAS)
def test_camera_agrees_with_cycles(renders: dict[tuple[str, str], TwoSeeds], camera: str) -> None:
    c, s = renders[("cycles", camera)], renders[("stratum", camera)]
    c_img, s_img = c.mean.mean(axis=(0, 1)), s.mean.mean(axis=(0, 1))
    assert (c_img > 0.02).all(), f"{camera}: Cycles image too dark to compare: {per_channel(c_img)}"
    img_sigma = np.sqrt(c.image_var() + s.image_var()) / c_img
    img_rel = (s_img - c_img) / c_img
    cb, sb = c.block_mean(), s.block_mean()
    lit = cb >= DARK_BLOCK
    blk_sigma = np.sqrt(c.block_var() + s.block_var()) / np.maximum(cb, 1e-12)
    blk_rel = np.where(lit, (sb - cb) / np.maximum(cb, 1e-12), 0.0)
    report = "\n".join([
        (f"{camera}: Cornell box {RES}x{RES}, {len(SEEDS)} x {SPP_PER_SEED} spp, "
        f"Blender {bpy.app.version_string}"),
        f"image mean cycles : {per_channel(c_img)}",
        f"image mean stratum: {per_channel(s_img)}",
        (f"relative diff     : {per_channel(img_rel, '{:+.3%}')} (tolerance {IMAGE_TOL:.0%}), "
        f"1 sigma {per_channel(img_sigma, '{:.3%}')}"),
        "blocks (row 0 = bottom) rel diff / 4 sigma per channel:",
        *(f"  ({by},{bx}) " + " ".join(
            f"{ch}={blk_rel[by, bx, k]:+.2%}/{K_SIGMA * blk_sigma[by, bx, k]:.2%}"
            for k, ch in enumerate(CHANNELS))
          for by in range(RES // BLOCK) for bx in range(RES // BLOCK)),
    ])
    CAMERA_OUT.mkdir(parents=True, exist_ok=True)
    (CAMERA_OUT / f"report_{camera}.txt").write_text(report + "\n")
    print("\n" + report)
    # The noise must allow the comparison (see the module docstring).
    assert (K_SIGMA * img_sigma < IMAGE_TOL).all(), f"image noise too high:\n{report}"
    assert (K_SIGMA * blk_sigma[lit] < BLOCK_TOL).all(), f"block noise too high:\n{report}"
    assert (np.abs(img_rel) <= IMAGE_TOL).all(), f"image means differ:\n{report}"
    assert (np.abs(blk_rel) <= BLOCK_TOL).all(), f"block means differ:\n{report}"


def test_scene_unit_assumptions() -> None:
    """The docstring's geometry: the Sphere is 3.1 m from the camera along the view axis."""
    scene = open_scene()
    cam = scene.camera
    axis = np.array(cam.matrix_world.to_3x3().col[2])
    d = abs(float(np.dot(axis / np.linalg.norm(axis),
                         np.array(cam.location) - np.array(bpy.data.objects["Sphere"].location))))
    assert d == pytest.approx(3.1, abs=1e-3)
    assert math.isclose(scene.camera.data.lens, 40.0)
    assert isinstance(CAMERA_OUT, Path)
