"""Material, light and world thumbnails rendered by Stratum (bl_use_preview).

Blender renders its own preview scene through render() with engine.is_preview set, in a job
thread, at the size it shows (ICON_SIZE_PREVIEW icons are 128 x 128 pixels, the material
panel's preview as wide as the panel). The preview scene is preview.blend's, in a Main of its
own: the preview shape wearing the material, the preview lights, a checker floor (not in
icons), and a world of colour 0.05 (a copy of the scene's world with the panel's World
lighting; the world itself for world previews). Its scene.stratum is that scene's, left at
the defaults, so a preview renders with the library's settings and those here.

A preview must be quick: it is redrawn with every edit of what it shows. Its sample count
spends a fixed budget of pixel samples over the frame (preview_samples). What the preview
scene cannot show exactly (its shapes' and lights' unsupported features) is not reported:
the user looks at their own scene's warnings, not at those of a scene they never made. Each
distinct problem is printed once to the console, and kept in last_reports for tests.
"""

from __future__ import annotations

import traceback
from typing import Any

from .. import native, properties
from ..export.common import ExportCancelled, ExportError
from ..export.sync import export_scene
from .final_render import render_progressively, stop_requested
from .frame import renderer_settings, result_size

# Pixel samples a preview spends, whatever its size: 128 x 128 pixels x 16 samples. On the
# preview sphere (the heaviest shape is the shader ball's mesh, a handful of bounces) a pixel
# sample costs about 4 us of CPU on this machine's cores (tests/blender/test_preview.py
# measures a thumbnail), so a thumbnail takes about a second of CPU with export and BVH.
PIXEL_SAMPLE_BUDGET = 128 * 128 * 16
MIN_SAMPLES = 1
MAX_SAMPLES = 64
# Light paths in a preview: enough for glass (into and out of the shape, then the floor) and
# a diffuse bounce; the library's default is for final renders.
MAX_BOUNCES = 4

# (level, message) of the most recent preview render, for tests.
last_reports: list[tuple[str, str]] = []
_printed: set[str] = set()


def preview_samples(width: int, height: int) -> int:
    """Samples per pixel of a width x height preview: the budget spread over its pixels,
    between MIN_SAMPLES and MAX_SAMPLES (an icon of 32 x 32 still stops at 64)."""
    samples = PIXEL_SAMPLE_BUDGET // max(width * height, 1)
    return max(MIN_SAMPLES, min(MAX_SAMPLES, samples))


def preview_settings(scene: Any) -> dict[str, int | float | str]:
    """Native settings of a preview render of `scene` (the preview scene): the frame's, with the
    sample count from preview_samples and at most MAX_BOUNCES bounces."""
    settings = renderer_settings(scene)
    width, height = result_size(scene)
    settings["samples"] = preview_samples(width, height)
    bounces = settings.get("max_bounces")
    if isinstance(bounces, int):
        settings["max_bounces"] = min(bounces, MAX_BOUNCES)
    return settings


class _QuietEngine:
    """The engine as render_progressively sees it, with its warnings kept instead of reported
    (the module docstring says why). Everything else is the engine's."""

    def __init__(self, engine: Any) -> None:
        self._engine = engine

    def __getattr__(self, name: str) -> Any:
        return getattr(self._engine, name)

    def _report(self, level: str, message: str) -> None:
        _note(level, message)


def _note(level: str, message: str) -> None:
    last_reports.append((level, message))
    if message not in _printed:
        _printed.add(message)
        print(f"Stratum preview {level}: {message}")


def render_preview(engine: Any, depsgraph: Any) -> None:
    """Renders the preview scene of `depsgraph` into the engine's result. Never raises: a
    preview that cannot be rendered stays empty and the reason is printed once."""
    last_reports.clear()
    try:
        _render(engine, depsgraph)
    except ExportCancelled:
        pass
    except (ExportError, native.StratumError) as exc:
        _note("ERROR", f"Stratum: {exc}")
    except Exception as exc:  # noqa: BLE001 - nothing may crash Blender
        traceback.print_exc()
        _note("ERROR", f"Stratum internal error: {type(exc).__name__}: {exc}")


def _render(engine: Any, depsgraph: Any) -> None:
    if properties.load_error:
        raise native.StratumError(
            native.ERROR_INVALID_STATE,
            f"the native library could not be loaded ({properties.load_error})")
    scene = depsgraph.scene
    settings = preview_settings(scene)
    width, height = result_size(scene)
    with native.Scene() as native_scene:
        summary = export_scene(depsgraph, native_scene, should_stop=lambda: stop_requested(engine))
        for warning in summary.warnings:
            _note("WARNING", warning)
        if stop_requested(engine):
            return
        renderer = native.Renderer(native_scene)
    with renderer:
        for name, value in settings.items():
            renderer.set(name, value)
        render_progressively(_QuietEngine(engine), renderer, width, height)

