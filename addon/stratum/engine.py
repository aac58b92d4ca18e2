"""The Stratum RenderEngine: export, native render on worker threads, progressive results.

render() never lets an exception escape: export errors, native errors and a missing library
are reported with self.report({'ERROR'}, ...) and the render ends cleanly.
"""

from __future__ import annotations

import time
import traceback
from typing import Any

import bpy
import numpy as np

from . import blender_settings, native, properties
from .export import ExportCancelled, ExportError, ExportSummary, export_scene

ENGINE_ID = "STRATUM"
POLL_MS = 100


def render_size(scene: Any) -> tuple[int, int]:
    r = scene.render
    scale = r.resolution_percentage / 100.0
    return max(int(r.resolution_x * scale), 1), max(int(r.resolution_y * scale), 1)


def border_region(scene: Any) -> tuple[int, int, int, int] | None:
    """The border (Render Region) in pixels of the frame, bottom-left origin: (x, y, width,
    height), or None without a border. Blender's render pipeline truncates border * size to
    integers (render_init_from_main: disprect = border * winx/winy) and renders, and hands the
    engine, only that region; use_crop_to_border only decides whether Blender pads it back to
    the full frame afterwards."""
    r = scene.render
    if not r.use_border:
        return None
    width, height = render_size(scene)
    x0, x1 = int(r.border_min_x * width), int(r.border_max_x * width)
    y0, y1 = int(r.border_min_y * height), int(r.border_max_y * height)
    if x1 - x0 < 1 or y1 - y0 < 1 or (x0, y0, x1, y1) == (0, 0, width, height):
        return None
    return x0, y0, x1 - x0, y1 - y0


def result_size(scene: Any) -> tuple[int, int]:
    """Size of the render result the engine fills: the border region, or the frame."""
    region = border_region(scene)
    return (region[2], region[3]) if region is not None else render_size(scene)


def renderer_settings(scene: Any) -> dict[str, int | float | str]:
    """Native settings from the output resolution, border and film, and every scene.stratum
    property (blender_settings.py says which setting comes from where); name -> value, the
    Python type selecting set_int / set_float / set_string, as the properties return them.
    The border and film settings are only sent when used, so a library without them still
    renders every other scene."""
    s = scene.stratum
    width, height = render_size(scene)
    extra: dict[str, int | float | str] = {}
    region = border_region(scene)
    if region is not None:
        extra.update(zip(("crop_x", "crop_y", "crop_width", "crop_height"), region, strict=True))
    if scene.render.film_transparent:
        extra["film_transparent"] = 1
    chosen = {name: getattr(s, name) for name in blender_settings.PROPERTIES}
    return {"width": width, "height": height} | chosen | extra


def stop_requested(engine: Any) -> bool:
    """Blender's Esc: engine.test_break(). A module function so that tests can stand in for it
    (test_break is an RNA function, which a Python subclass or monkeypatch cannot override)."""
    return bool(engine.test_break())


def format_stats(progress: native.Progress, elapsed: float) -> str:
    rate = progress.rays / progress.render_seconds if progress.render_seconds > 0 else 0.0
    if rate >= 1e6:
        rays = f"{rate / 1e6:.2f}M"
    elif rate >= 1e3:
        rays = f"{rate / 1e3:.1f}k"
    else:
        rays = f"{rate:.0f}"
    return (f"Sample {progress.samples_done}/{progress.samples_total} | {elapsed:.1f}s | "
            f"{rays} rays/s")


class PixelWriter:
    """Copies renderer pixels into a render result pass: one read_pixels into a preallocated
    float32 buffer, one foreach_set. 3.x/4.0 want an (N, 4) array, 4.1+ a flat one."""

    def __init__(self, width: int, height: int) -> None:
        self.buffer = np.zeros(width * height * 4, dtype=np.float32)
        self._flat: bool = bpy.app.version >= (4, 1, 0)

    def write(self, renderer: native.Renderer, render_pass: Any) -> None:
        renderer.read_pixels(self.buffer)
        data = self.buffer if self._flat else self.buffer.reshape(-1, 4)
        try:
            render_pass.rect.foreach_set(data)
        except (TypeError, ValueError, RuntimeError):
            self._flat = not self._flat
            data = self.buffer if self._flat else self.buffer.reshape(-1, 4)
            render_pass.rect.foreach_set(data)


def report_notices(engine: Any, renderer: native.Renderer, reported: set[str]) -> None:
    """Reports the renderer's notices not reported yet, once each, through engine._report."""
    for notice in renderer.notices():
        if notice not in reported:
            reported.add(notice)
            engine._report("WARNING", f"Stratum: {notice}")


def combined_pass(result: Any) -> Any:
    layer = result.layers[0]
    passes = layer.passes
    found = passes.get("Combined") if hasattr(passes, "get") else None
    if found is None:
        found = passes.find_by_name("Combined", "")
    return found


class StratumRenderEngine(bpy.types.RenderEngine):
    bl_idname = ENGINE_ID
    bl_label = "Stratum"
    bl_use_preview = False
    bl_use_postprocess = True
    # Show Blender's standard shader nodes (Principled, Diffuse, Emission...) in the node
    # editor: Stratum reads those node trees.
    bl_use_shading_nodes_custom = False

    # Reports of the most recent render (level, message): for tests and the CLI, because
    # background renders do not always surface RenderEngine.report().
    last_reports: list[tuple[str, str]] = []
    last_summary: ExportSummary | None = None

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)  # required in Blender 4.4+

    def _report(self, level: str, message: str) -> None:
        type(self).last_reports.append((level, message))
        try:
            self.report({level}, message)
        except Exception:  # noqa: BLE001 - reporting must never fail a render
            print(f"Stratum {level}: {message}")

    def render(self, depsgraph: Any) -> None:
        type(self).last_reports = []
        type(self).last_summary = None
        try:
            self._render(depsgraph)
        except ExportCancelled:
            pass
        except (ExportError, native.StratumError) as exc:
            self._report("ERROR", f"Stratum: {exc}")
        except Exception as exc:  # noqa: BLE001 - nothing may crash Blender
            traceback.print_exc()
            self._report("ERROR", f"Stratum internal error: {type(exc).__name__}: {exc}")

    def _render(self, depsgraph: Any) -> None:
        scene = depsgraph.scene
        if properties.load_error:
            # scene.stratum was registered without settings: the library could not be loaded
            # then. Name why it still cannot, else ask for the registration to be redone.
            native.load_library()
            raise native.StratumError(
                native.ERROR_INVALID_STATE,
                f"the native library could not be loaded when the add-on was enabled "
                f"({properties.load_error}); enable the add-on again")
        settings = renderer_settings(scene)
        width, height = result_size(scene)

        self.update_stats("", "Exporting scene")
        with native.Scene() as native_scene:
            summary = export_scene(depsgraph, native_scene,
                                   should_stop=lambda: stop_requested(self),
                                   frame_set=self.frame_set)
            type(self).last_summary = summary
            for warning in summary.warnings:
                self._report("WARNING", warning)
            if stop_requested(self):  # Esc during export: no renderer, no BVH build
                return
            renderer = native.Renderer(native_scene)
        with renderer:
            for name, value in settings.items():
                renderer.set(name, value)
            self._progressive(renderer, width, height)

    def _progressive(self, renderer: native.Renderer, width: int, height: int) -> None:
        started = time.perf_counter()
        self.update_stats("", "Building BVH / starting")
        # Started before Blender's result and the pixel buffer are allocated: a render the
        # renderer refuses (a film beyond memory, 65536 x 20000) must not get them first, each
        # as large as the image, which the OOM killer would have ended Blender for.
        renderer.start()
        writer = PixelWriter(width, height)
        result = self.begin_result(0, 0, width, height)
        try:
            render_pass = combined_pass(result)
            # What this render cannot show (the estimator's limits at start; skipped objects and
            # dropped samples as the render learns them): warnings, the render goes on.
            reported: set[str] = set()
            report_notices(self, renderer, reported)
            last_serial: int | None = None
            cancelled_at: float | None = None
            while True:
                done = renderer.wait(POLL_MS)
                if cancelled_at is None and stop_requested(self):
                    renderer.cancel()
                    cancelled_at = time.perf_counter()
                progress = renderer.progress()
                if progress.update_serial != last_serial:
                    last_serial = progress.update_serial
                    writer.write(renderer, render_pass)
                    self.update_result(result)
                self.update_progress(min(progress.fraction_done, 1.0))
                self.update_stats("", format_stats(progress, time.perf_counter() - started))
                if done or progress.done:
                    break
                if cancelled_at is not None and time.perf_counter() - cancelled_at > 30.0:
                    self._report("ERROR", "Stratum: the renderer did not stop after cancel")
                    break
            # Final pixels (also the partial image after Esc).
            writer.write(renderer, render_pass)
            report_notices(self, renderer, reported)
        finally:
            self.end_result(result)


def register() -> None:
    bpy.utils.register_class(StratumRenderEngine)


def unregister() -> None:
    bpy.utils.unregister_class(StratumRenderEngine)
