"""Denoising an F12 render with Open Image Denoise (engine/denoise.py), in Blender 3.4 and in
the bpy wheel: on the bundled Cornell box at 64 x 64 and 16 spp, the denoised image is at least
5 x closer (MSE) to a 4096-spp reference than the noisy one, the undenoised image is kept in
the Noisy Image pass, and a missing or broken OIDN is one warning and an undenoised render.

Where the MSE is measured. The box's light is seen by the camera at radiance 15, and the ~100
pixels of its anti-aliased rim hold coverage noise (k of 16 samples on the light: a standard
deviation of 15 * sqrt(p (1 - p) / 16), up to 1.9) that no guide can remove, because the
rim is a true edge. In linear values those pixels carry about half of both MSEs and the ratio
over all pixels is 2.1 to 2.8 (measured with colour alone and with the albedo and normal
guides); it is printed, not asserted. Cycles' own OIDN denoising of the same scene (bpy 5.0,
16 spp against its own 4096 spp, albedo and normal guides, adaptive sampling off) measures the
same: 2.1 over all linear pixels, 11.8 displayed, 16.3 below 1, 20.3 in relative MSE; Stratum
2.1, 11.1, 17.2, 19.3 (random; sobol 2.1, 10.9, 18.4, 21.3). Asserted at 5 x: the MSE of the
image as the scene displays it (its view transform is Standard: sRGB of the value clipped to
[0, 1]), the linear MSE of the pixels whose reference is below 1 (all but the light and its
rim), and the relative MSE mean((x - r)^2 / (r^2 + 0.01)) that rendering papers use for HDR
images (it weighs an error by the brightness it sits on, as the eye does).

Margin: the reference's own noise adds sigma^2 / 4096 per pixel to both MSEs, 1/256 of the
noisy image's (sigma^2 / 16), which lowers the ratio; each MSE averages about 12000 squared
errors, a relative standard error near sqrt(2 / 12000) ~ 1.3 % for Gaussian-like noise (more
with heavy tails): small against the factor 2 between the ratios measured and 5.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest

from conftest import engine_reports
from exr_file import read_pass

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "scenes" / "cornell_box.blend"
RES = 64
SPP = 16
REF_SPP = 4096


def _linear(rgb: np.ndarray) -> np.ndarray:
    return rgb.astype(np.float64)


def _displayed(rgb: np.ndarray) -> np.ndarray:
    """Blender's Standard view transform on an sRGB display: the sRGB encoding of the value
    clipped to [0, 1] (IEC 61966-2-1)."""
    x = np.clip(rgb.astype(np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1.0 / 2.4) - 0.055)


def _mse(image: np.ndarray, reference: np.ndarray, mask: np.ndarray | None) -> float:
    squared = (image - reference) ** 2
    return float(np.mean(squared if mask is None else squared[mask]))


def _relative_mse(image: np.ndarray, reference: np.ndarray) -> float:
    """mean((x - r)^2 / (r^2 + 0.01)) over pixels and channels (e.g. Rousselle et al. 2011,
    Bitterli et al. 2016: 0.01 keeps black pixels finite)."""
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + 0.01)))


def _cornell(samples: int, use_denoising: bool) -> Any:
    bpy.ops.wm.open_mainfile(filepath=str(CORNELL), load_ui=False)
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    scene.render.resolution_x = scene.render.resolution_y = RES
    scene.render.resolution_percentage = 100
    scene.render.use_border = False
    scene.stratum.samples = samples
    scene.stratum.use_denoising = use_denoising
    settings = scene.render.image_settings
    if hasattr(settings, "media_type"):  # Blender 5.0: multilayer EXR is a media type
        settings.media_type = "MULTI_LAYER_IMAGE"
    settings.file_format = "OPEN_EXR_MULTILAYER"
    settings.exr_codec = "NONE"
    settings.color_depth = "32"
    return scene


def _render(scene: Any, path: Path) -> Path:
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    assert path.is_file(), engine_reports("ERROR")
    return path


@pytest.fixture(scope="module")
def denoiser(library: Any) -> str:
    from stratum import native

    try:
        return native.load_denoiser()[1]
    except native.DenoiserUnavailable as exc:
        pytest.fail(f"Open Image Denoise is not available (make build copies it): {exc}")


@pytest.fixture(scope="session")
def reference(library: Any, tmp_path_factory: pytest.TempPathFactory) -> np.ndarray:
    """The Cornell box at REF_SPP through the same F12 path, undenoised (a few seconds)."""
    scene = _cornell(REF_SPP, use_denoising=False)
    assert scene.view_settings.view_transform == "Standard"  # what _displayed reproduces
    path = _render(scene, tmp_path_factory.mktemp("reference") / "reference.exr")
    return read_pass(path, "Combined")[..., :3].astype(np.float64)


def test_denoised_render_is_5x_closer_to_the_reference(denoiser: str, reference: np.ndarray,
                                                       tmp_path: Path) -> None:
    path = _render(_cornell(SPP, use_denoising=True), tmp_path / "denoised.exr")
    assert not engine_reports("WARNING") and not engine_reports("ERROR")
    combined, noisy = read_pass(path, "Combined"), read_pass(path, "Noisy Image")
    assert combined.shape == noisy.shape == (RES, RES, 4)
    # The Noisy Image pass is the render undenoised: the same bits as a render without
    # denoising (renders are deterministic; requesting guide passes changes no sample).
    plain = read_pass(_render(_cornell(SPP, use_denoising=False), tmp_path / "plain.exr"),
                      "Combined")
    np.testing.assert_array_equal(noisy, plain)
    np.testing.assert_array_equal(combined[..., 3], noisy[..., 3])  # alpha is kept
    ratios = {}
    for name, space, mask in (("linear, all pixels", _linear, None),
                              ("displayed (Standard, sRGB)", _displayed, None),
                              ("linear, reference < 1", _linear, reference.max(axis=-1) < 1.0)):
        noisy_mse, denoised_mse = (_mse(space(image[..., :3]), space(reference), mask)
                                   for image in (noisy, combined))
        ratios[name] = noisy_mse / denoised_mse
        print(f"Cornell box {RES}x{RES}, {SPP} spp against {REF_SPP} spp ({denoiser}), {name}: "
              f"MSE noisy {noisy_mse:.3e}, denoised {denoised_mse:.3e}, ratio {ratios[name]:.1f}")
    ratios["relative"] = (_relative_mse(noisy[..., :3].astype(np.float64), reference)
                          / _relative_mse(combined[..., :3].astype(np.float64), reference))
    print(f"relative MSE ratio {ratios['relative']:.1f}")
    assert ratios["displayed (Standard, sRGB)"] >= 5.0, ratios
    assert ratios["linear, reference < 1"] >= 5.0, ratios
    assert ratios["relative"] >= 5.0, ratios


def test_broken_denoiser_is_one_warning_and_an_undenoised_render(
        library: Any, monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    from stratum.native import oidn

    broken = tmp_path / "libOpenImageDenoise.so.2"
    broken.write_text("not a shared library\n" * 64)
    monkeypatch.setattr(oidn, "_lib", None)  # search again; the loaded library is restored
    monkeypatch.setenv(oidn.ENV_VAR, str(broken))
    path = _render(_cornell(SPP, use_denoising=True), tmp_path / "broken.exr")
    warnings = engine_reports("WARNING")
    assert len(warnings) == 1, warnings
    assert "not denoised" in warnings[0] and str(broken) in warnings[0], warnings[0]
    assert not engine_reports("ERROR")
    combined = read_pass(path, "Combined")
    plain = read_pass(_render(_cornell(SPP, use_denoising=False), tmp_path / "plain.exr"),
                      "Combined")
    np.testing.assert_array_equal(combined, plain)


def test_guides_are_albedo_and_normal_and_never_a_normal_alone(stratum_addon: Any) -> None:
    from stratum.engine import denoise

    everything = ["Combined", "Normal", "Denoising Albedo", "Denoising Normal"]
    assert denoise.guide_passes(everything) == ("Denoising Albedo", "Denoising Normal")
    assert denoise.guide_passes(["Combined", "Normal", "Denoising Albedo"]) == (
        "Denoising Albedo", "Normal")
    assert denoise.guide_passes(["Combined", "Denoising Albedo"]) == ("Denoising Albedo", None)
    assert denoise.guide_passes(["Combined", "Normal", "Denoising Normal"]) == (None, None)
    assert denoise.with_passes({"samples": 4}, []) == {"samples": 4}
    assert denoise.with_passes({"passes": "Depth,Normal"}, ["Normal", "Denoising Albedo"]) == {
        "passes": "Depth,Normal,Denoising Albedo"}


def test_denoise_rgba_keeps_alpha_and_checks_its_input(denoiser: str) -> None:
    from stratum.engine import denoise

    rng = np.random.default_rng(3)
    rgba = rng.exponential(0.5, (16, 24, 4)).astype(np.float32)
    rgba[..., 3] = rng.uniform(0.0, 1.0, (16, 24))
    rgba[0, 0, 0] = -0.5  # a control variate's negative estimate: clamped for the filter only
    before = rgba.copy()
    out = denoise.denoise_rgba(rgba)
    assert out.shape == rgba.shape and np.isfinite(out).all()
    np.testing.assert_array_equal(out[..., 3], rgba[..., 3])
    np.testing.assert_array_equal(rgba, before)
    assert not np.array_equal(out[..., :3], rgba[..., :3])
    with pytest.raises(ValueError, match="H x W x 4"):
        denoise.denoise_rgba(rgba[..., :3])


def test_denoising_adds_the_noisy_image_socket_to_the_compositor(stratum_addon: Any) -> None:
    scene = _cornell(SPP, use_denoising=False)
    if not hasattr(scene, "node_tree"):  # Blender 5.0 keeps the compositor in a node group
        pytest.skip("scene.node_tree is Blender 3.x/4.x's compositor")
    scene.use_nodes = True
    node = next(n for n in scene.node_tree.nodes if n.bl_idname == "CompositorNodeRLayers")

    def sockets() -> set[str]:
        return {socket.name for socket in node.outputs if socket.enabled}

    assert "Image" in sockets() and "Noisy Image" not in sockets()
    scene.stratum.use_denoising = True
    assert "Noisy Image" in sockets() and "Image" in sockets()
    scene.stratum.use_denoising = False
    assert "Noisy Image" not in sockets()


def test_denoiser_failing_during_the_render_is_one_warning(
        denoiser: str, monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """OIDN loads but its filter fails (an error string from oidnGetDeviceError): one warning,
    Combined undenoised, Noisy Image still written."""
    from stratum import native

    def failing(*_args: Any, **_kwargs: Any) -> np.ndarray:
        raise native.DenoiserUnavailable("Open Image Denoise (test) failed at denoising: "
                                         "out of memory")

    monkeypatch.setattr(native, "denoise", failing)
    path = _render(_cornell(SPP, use_denoising=True), tmp_path / "failing.exr")
    warnings = engine_reports("WARNING")
    assert len(warnings) == 1 and "out of memory" in warnings[0], warnings
    plain = read_pass(_render(_cornell(SPP, use_denoising=False), tmp_path / "plain.exr"),
                      "Combined")
    np.testing.assert_array_equal(read_pass(path, "Combined"), plain)
    np.testing.assert_array_equal(read_pass(path, "Noisy Image"), plain)


def test_denoising_switches_are_off_by_default_and_shown(stratum_addon: Any) -> None:
    from types import SimpleNamespace

    from stratum import ui

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    assert scene.stratum.use_denoising is False
    assert scene.stratum.use_preview_denoising is False
    panel = ui.STRATUM_RENDER_PT_sampling_denoising
    assert panel.bl_parent_id == "STRATUM_RENDER_PT_sampling"
    assert panel.poll(SimpleNamespace(engine="STRATUM", scene=scene))  # type: ignore[arg-type]
