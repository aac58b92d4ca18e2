"""Stratum's data passes against Cycles' on the bundled Cornell box: Depth, Position, Normal,
Denoising Normal and Denoising Albedo, per pixel, away from edges.

Both render with a pixel filter of width 0.02 (every sample within 0.01 px of the pixel
centre), so the passes of one pixel are of (nearly) one point in both renderers and need no
noise allowance: Depth and Position are sample 0's in both, Normal and the denoising features
are the same for every sample of a flat or smooth face. Pixels whose 3 × 3 neighbourhood in
Cycles' passes spans a depth step (> 5%) or a crease (neighbour normals more than 3.6° apart)
are edges, where 0.01 px can change the surface seen, and are left out.

Tolerances: Depth and Position 1e-3 relative (a 0.01 px offset moves the point by < 1e-4 of
the depth at this 40 mm lens and 64 px); normals 2e-3 (the same offset on the sphere's smooth
shading). Denoising Albedo differs by definition (docs/passes.md): Cycles writes the base colour
plus the Principled specular layer's Fresnel-weighted albedo at the view angle (roughness 0.5 is
"diffuse-like" for it), Stratum the base colour + 0.04 (the layer's albedo at normal
incidence). The Fresnel reflectance of IOR 1.5 stays within 0.04-0.05 up to 45° from the normal
(0.042 at 30°, 0.05 at 45°), so where the camera sees a face within 45° they agree within 0.03
absolute (the rough layer's albedo spreads the Fresnel term a little); the comparison is limited
to those pixels. On the emitting quad both write its emission (15).

In Blender 5.0 (Principled v2, Cycles 4.x's rules) both write the Denoising Albedo as the sum
of the closures' bsdf_albedo estimates; they agree within 8e-4 there (measured).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import bpy
import numpy as np

from agreement import configure_cycles, configure_stratum, open_scene
from exr_file import read_channels
from multilayer_passes import result_name, set_multilayer_exr

RES = 48
SAMPLES = 4
PASSES = {"Depth": "Z", "Position": "XYZ", "Normal": "XYZ", "Denoising Normal": "XYZ",
          "Denoising Albedo": "RGB"}
COLOUR_PASSES = {"DiffCol": "RGB", "GlossCol": "RGB", "TransCol": "RGB"}

def render_passes(renderer: str, path: Path, colours: bool = False) -> dict[str, np.ndarray]:
    scene = open_scene()
    scene.render.resolution_x = scene.render.resolution_y = RES
    layer = scene.view_layers[0]
    layer.use_pass_z = layer.use_pass_normal = layer.use_pass_position = True
    if colours:
        layer.use_pass_diffuse_color = layer.use_pass_glossy_color = True
        layer.use_pass_transmission_color = True
    if renderer == "cycles":
        configure_cycles(scene, 1, samples=SAMPLES)
        scene.cycles.filter_width = 0.02
        layer.cycles.denoising_store_passes = True
    else:
        configure_stratum(scene, 1, samples=SAMPLES)
        scene.stratum.filter_width = 0.02
        layer.stratum.use_pass_denoising_data = True
    set_multilayer_exr(scene.render.image_settings)
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    channels = read_channels(path)
    name = layer.name
    out = {}
    for pass_name, letters in {**PASSES, **(COLOUR_PASSES if colours else {})}.items():
        keys = [f"{name}.{result_name(pass_name)}.{c}" for c in letters]
        missing = [k for k in keys if k not in channels]
        assert not missing, f"{renderer}: {missing} not in {sorted(channels)}"
        out[pass_name] = np.stack([channels[k] for k in keys], axis=-1).astype(np.float64)
    return out


def interior(depth: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Pixels away from depth steps (a second difference of the depth along a row or column
    above 1% of it: a plane's depth is nearly linear across pixels) and creases (a neighbour's
    normal more than 3.6° off); the outer ring is out."""
    keep = np.zeros(depth.shape, dtype=bool)
    keep[1:-1, 1:-1] = True
    for axis in (0, 1):
        second = np.roll(depth, 1, axis=axis) - 2 * depth + np.roll(depth, -1, axis=axis)
        keep &= np.abs(second) <= 0.01 * depth
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            n = np.roll(normal, (dy, dx), axis=(0, 1))
            keep &= np.sum(n * normal, axis=-1) >= np.cos(np.radians(3.6))
    return keep


def test_data_passes_agree_with_cycles_on_the_cornell_box(library: Any, tmp_path: Path) -> None:
    cycles = render_passes("cycles", tmp_path / "cycles.exr")
    stratum = render_passes("stratum", tmp_path / "stratum.exr")
    depth = cycles["Depth"][..., 0]
    keep = interior(depth, cycles["Normal"])
    # A large part of the image is interior (47% at 48 px: the frame's margin is background,
    # the boxes and the sphere are edges and creases at this size): the test is not vacuous.
    assert keep.sum() > 0.4 * RES * RES, keep.sum()
    scale = depth[keep][:, None]
    np.testing.assert_allclose(stratum["Depth"][..., 0][keep], depth[keep], rtol=1e-3)
    assert np.all(np.abs(stratum["Position"][keep] - cycles["Position"][keep]) <= 1e-3 * scale)
    np.testing.assert_allclose(stratum["Normal"][keep], cycles["Normal"][keep], atol=2e-3)
    np.testing.assert_allclose(stratum["Denoising Normal"][keep], cycles["Denoising Normal"][keep],
                               atol=2e-3)
    # Denoising Albedo where the camera sees a face within 45° of its normal (see the top; at
    # grazing views Cycles' Fresnel-weighted specular albedo grows: 0.16 above Stratum's on the
    # red wall's far end).
    camera = np.array(bpy.context.scene.camera.matrix_world.translation)
    to_camera = camera - cycles["Position"]
    to_camera /= np.linalg.norm(to_camera, axis=-1, keepdims=True)
    facing = keep & (np.sum(to_camera * cycles["Normal"], axis=-1) >= np.cos(np.radians(45.0)))
    assert facing.sum() > 0.1 * RES * RES, facing.sum()  # the back wall and the boxes' fronts
    np.testing.assert_allclose(stratum["Denoising Albedo"][facing],
                               cycles["Denoising Albedo"][facing], atol=0.03)


def test_colour_passes_agree_with_cycles_on_the_cornell_box(library: Any, tmp_path: Path) -> None:
    """DiffCol, GlossCol and TransCol are Cycles 3.4's closure weights: on the box's default
    Principled BSDFs (metallic 0, specular 0.5, no transmission, clearcoat or sheen) the diffuse
    closure's base colour, the specular closure's white 1 and no transmission; the emitter's
    Emission closure adds none. Both renderers write exactly these (no noise: the colours of a
    face do not depend on the sample), so away from edges they agree to float precision.
    Cycles 4.x/5.0 writes its bsdf_albedo estimates instead, which it reads from GGX albedo
    tables at the view angle; Stratum's Principled v2 computes them from its own fits of the same
    albedos (microfacet_ggx.h) and the smooth Fresnel: in Blender 5.0 they agree within 1e-3
    (measured: 6.7e-4 diffuse, 8.4e-4 glossy at most, 2e-4 on average)."""
    cycles = render_passes("cycles", tmp_path / "cycles.exr", colours=True)
    stratum = render_passes("stratum", tmp_path / "stratum.exr", colours=True)
    keep = interior(cycles["Depth"][..., 0], cycles["Normal"])
    assert keep.sum() > 0.4 * RES * RES, keep.sum()
    tolerance = 1e-4 if bpy.app.version < (4, 0, 0) else 1e-3
    for pass_name in COLOUR_PASSES:
        np.testing.assert_allclose(stratum[pass_name][keep], cycles[pass_name][keep],
                                   atol=tolerance, err_msg=pass_name)
    # Not vacuous: the walls' colours differ, and the specular closure is there.
    assert np.ptp(cycles["DiffCol"][keep][:, 0]) > 0.5
    assert np.any(cycles["GlossCol"][keep] > 0.1)  # 1 in 3.4, the specular albedo 0.14 in 5.0
