"""Denoising with Intel Open Image Denoise (stratum.native.oidn): the F12 render's Combined
pass when scene.stratum.use_denoising is on, and any renderer's image for the viewport when
scene.stratum.use_preview_denoising is on: ask for `library_guides()` through `with_passes`
before the render starts, then `denoise_renderer(renderer, albedo, normal)` (or
`denoise_rgba` for an image at hand); report a native.DenoiserUnavailable once.

Guides: OIDN's RT filter takes a first-hit albedo and normal beside the noisy colour. The
render asks the library for the `Denoising Albedo` and `Denoising Normal` passes through its
`passes` setting when the library has them; with an albedo but no `Denoising Normal` the
`Normal` pass stands in. Without an albedo the colour is denoised alone: OIDN refuses a normal
without an albedo ("unsupported combination of input features", measured with 2.5.1).

As Cycles does, the undenoised image is kept in a `Noisy Image` pass (RGBA) and Combined
receives the denoised RGB with the render's own alpha. Negative colour values (possible with
control variates) are clamped to 0 for the filter only, which expects HDR values in
[0, +inf); the Noisy Image pass keeps them.

A missing or broken OIDN is one warning and the render stays undenoised; OIDN is looked for
once per render, before it starts, so the warning comes first and costs no render time.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from .. import native

NOISY_PASS = "Noisy Image"
ALBEDO_PASS = "Denoising Albedo"
NORMAL_PASS = "Denoising Normal"
# What stands in for NORMAL_PASS in a library without it.
FALLBACK_NORMAL_PASS = "Normal"


def guide_passes(available: Iterable[str]) -> tuple[str | None, str | None]:
    """(albedo pass, normal pass) to denoise with among the passes a library can render; a
    normal only with an albedo (see the module docstring)."""
    names = set(available)
    if ALBEDO_PASS not in names:
        return None, None
    for normal in (NORMAL_PASS, FALLBACK_NORMAL_PASS):
        if normal in names:
            return ALBEDO_PASS, normal
    return ALBEDO_PASS, None


def library_guides() -> tuple[str | None, str | None]:
    """guide_passes among the passes the loaded library can render."""
    return guide_passes(p.name for p in native.passes())


def with_passes(settings: dict[str, Any], names: Iterable[str]) -> dict[str, Any]:
    """`settings` with `names` added to its comma-separated `passes` list (kept in order,
    without repeats)."""
    current = [name for name in str(settings.get("passes", "")).split(",") if name]
    wanted = current + [name for name in names if name not in current]
    return settings | {"passes": ",".join(wanted)} if wanted else dict(settings)


def denoise_rgba(rgba: np.ndarray, albedo: np.ndarray | None = None,
                 normal: np.ndarray | None = None) -> np.ndarray:
    """A denoised copy of a linear H x W x 4 image: its RGB through OIDN's RT filter (HDR),
    its alpha unchanged. `albedo` and `normal` are H x W x 3 guides of the same pixels (a
    normal only with an albedo). Raises native.DenoiserUnavailable when OIDN is missing or
    fails, ValueError for images of the wrong shape."""
    image = np.asarray(rgba, dtype=np.float32)
    if image.ndim != 3 or image.shape[2] != 4:
        raise ValueError(f"denoise_rgba: expected an H x W x 4 image, got shape {image.shape}")
    color = np.maximum(image[..., :3], 0.0)
    guide_albedo = None if albedo is None else np.clip(albedo, 0.0, 1.0)
    out = image.copy()
    out[..., :3] = native.denoise(color, guide_albedo, normal, hdr=True)
    return out


def denoise_renderer(renderer: native.Renderer, albedo: str | None = None,
                     normal: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(noisy, denoised) H x W x 4 images of a renderer's current image (rows bottom first, as
    read_pixels gives them), guided by its passes `albedo` and `normal` (names from
    library_guides(), which the render's `passes` setting must have asked for). For F12 and
    the viewport; raises native.DenoiserUnavailable as denoise_rgba does."""
    width, height = renderer.image_size
    noisy = renderer.read_pixels().reshape(height, width, 4)
    guide_albedo = renderer.read_pass(albedo) if albedo else None
    guide_normal = renderer.read_pass(normal) if normal else None
    return noisy, denoise_rgba(noisy, guide_albedo, guide_normal)


def _find_pass(result: Any, name: str) -> Any:
    passes = result.layers[0].passes
    found = passes.get(name) if hasattr(passes, "get") else None
    return found if found is not None else passes.find_by_name(name, "")


def _write_pass(render_pass: Any, rgba: np.ndarray) -> None:
    """rgba into a render result pass: 3.x/4.0 take an (N, 4) array, 4.1+ a flat one."""
    flat = np.ascontiguousarray(rgba, dtype=np.float32).reshape(-1)
    try:
        render_pass.rect.foreach_set(flat)
    except (TypeError, ValueError, RuntimeError):
        render_pass.rect.foreach_set(flat.reshape(-1, 4))


class FinalDenoising:
    """Denoises one F12 render's result after its last samples (see `prepare_final`)."""

    def __init__(self, engine: Any, albedo: str | None, normal: str | None) -> None:
        self.engine = engine
        self.albedo = albedo
        self.normal = normal

    def apply(self, renderer: native.Renderer, result: Any) -> None:
        """Writes the render's image into the Noisy Image pass and its denoised version into
        Combined; on an OIDN failure, reports it and leaves Combined undenoised."""
        self.engine.update_stats("", "Denoising")
        try:
            noisy, denoised = denoise_renderer(renderer, self.albedo, self.normal)
        except native.DenoiserUnavailable as exc:
            self.engine._report("WARNING", f"Stratum: the render is not denoised: {exc}")
            width, height = renderer.image_size
            noisy, denoised = renderer.read_pixels().reshape(height, width, 4), None
        noisy_pass = _find_pass(result, NOISY_PASS)
        if noisy_pass is not None:
            _write_pass(noisy_pass, noisy)
        if denoised is not None:
            _write_pass(_find_pass(result, "Combined"), denoised)


def prepare_final(engine: Any, scene: Any, settings: dict[str, Any]) -> FinalDenoising | None:
    """Before an F12 render starts: None when scene.stratum.use_denoising is off or OIDN
    cannot be loaded (then one warning says why); else adds the guide passes to `settings`
    (in place), adds the Noisy Image pass to the render result Blender is about to make, and
    returns what denoises the result at the end."""
    if not getattr(scene.stratum, "use_denoising", False):
        return None
    try:
        native.load_denoiser()
    except native.DenoiserUnavailable as exc:
        engine._report("WARNING", f"Stratum: the render is not denoised: {exc}")
        return None
    albedo, normal = library_guides()
    settings.update(with_passes(settings, [name for name in (albedo, normal) if name]))
    engine.add_pass(NOISY_PASS, 4, "RGBA")
    return FinalDenoising(engine, albedo, normal)


def register_passes(engine: Any, scene: Any, view_layer: Any) -> None:
    """Declares the Noisy Image pass to the compositor while denoising is on (Cycles' way:
    update_render_passes registers what add_pass will add)."""
    if getattr(scene.stratum, "use_denoising", False):
        engine.register_pass(scene, view_layer, NOISY_PASS, 4, "RGBA", "COLOR")
