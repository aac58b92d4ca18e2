"""What the render-pass tests (test_render_passes.py, test_pass_agreement.py) share: the
multilayer EXR they render every pass into (set_multilayer_exr; exr_file.read_channels reads
it back) and the render-result name of a native pass in this Blender (result_name)."""

from __future__ import annotations

from typing import Any


def result_name(native_name: str) -> str:
    """The render-result pass of a native pass in this Blender (5.0 renamed some; that the
    names are Cycles' is tested against Cycles itself in test_render_passes.py)."""
    from stratum.engine import render_passes

    return next(spec.result_name for _, _, specs in render_passes.TOGGLES for spec in specs
                if spec.name == native_name)


def set_multilayer_exr(settings: Any) -> None:
    """A 32-bit multilayer EXR of every pass, ZIP-compressed (lossless, and a codec
    exr_file reads). Blender 5.0 makes multilayer a media type, and writes the passes besides
    Combined only with "Interleave" on (use_exr_interleave; off in a new 5.0 scene, on in files
    from earlier versions), for Cycles as for Stratum."""
    if hasattr(settings, "media_type"):
        settings.media_type = "MULTI_LAYER_IMAGE"
    settings.file_format = "OPEN_EXR_MULTILAYER"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    if hasattr(settings, "use_exr_interleave"):
        settings.use_exr_interleave = True
