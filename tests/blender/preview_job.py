"""Thumbnails of a red material, a point light and a blue world rendered by Stratum through
Blender's own preview job (bpy.ops.ed.lib_id_generate_preview, the operator behind "Generate
Preview"): Blender renders its preview scene with the engine's render() (is_preview), in a
job thread, and copies the result into the ID's preview image. Used by test_preview.py:

* imported (the bpy 5.0 wheel, background): run_waiting() starts each job and waits for it;
* run as a script in Blender 3.4 with its UI (under Xvfb):
      blender --factory-startup -noaudio --python tests/blender/preview_job.py -- OUT.json
  Blender 3.4 in background mode cannot finish a preview job (it crashes in the job thread
  after render() returns, whatever the engine; reproduced with a render() that does nothing),
  so there the jobs run under its event loop (bpy.app.timers) and the results go to OUT.json.

Each result: the preview's size, its mean RGBA and the mean RGB of its central quarter (where
the shape is), the process CPU seconds of the render() call (time.process_time: every thread
of the process, so the native render threads too) and what the preview reported.
"""

from __future__ import annotations

import json
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import bpy
import numpy as np

ADDON_DIR = Path(__file__).resolve().parents[2] / "addon"
KINDS = ("material", "light", "world")
RED = (0.8, 0.05, 0.05)
BLUE = (0.05, 0.1, 0.8)


def make_id(kind: str) -> Any:
    """The data-block whose preview is rendered: a red diffuse material, a point light, a blue
    world."""
    if kind == "material":
        mat = bpy.data.materials.new("PreviewRed")
        if bpy.app.version < (5, 0, 0):  # always true from 5.0, and deprecated
            mat.use_nodes = True
        bsdf = mat.node_tree.nodes["Principled BSDF"]
        bsdf.inputs["Base Color"].default_value = (*RED, 1.0)
        bsdf.inputs["Roughness"].default_value = 1.0
        return mat
    if kind == "light":
        light = bpy.data.lights.new("PreviewLight", "POINT")
        light.energy = 100.0
        return light
    world = bpy.data.worlds.new("PreviewBlue")
    world.color = BLUE
    if bpy.app.version < (5, 0, 0):
        world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (*BLUE, 1.0)
    return world


class RenderRecorder:
    """Wraps the engine's preview entry point: records each preview render's CPU time and
    reports (stratum.engine looks render_preview up at each call)."""

    def __init__(self) -> None:
        import stratum.engine as engine_module
        from stratum.engine import preview

        self._module = engine_module
        self._preview = preview
        self._original = engine_module.render_preview
        self.renders: list[dict[str, Any]] = []
        engine_module.render_preview = self._render

    def _render(self, engine: Any, depsgraph: Any) -> None:
        r = depsgraph.scene.render
        start = time.process_time()
        self._original(engine, depsgraph)
        self.renders.append({
            "cpu_seconds": time.process_time() - start,
            "size": [r.resolution_x, r.resolution_y],
            "reports": [list(report) for report in self._preview.last_reports],
            # What the engine's F12 reports hold afterwards: previews add nothing there.
            "engine_reports": [list(report) for report in type(engine).last_reports],
        })

    def restore(self) -> None:
        self._module.render_preview = self._original


def start_job(idblock: Any) -> None:
    with bpy.context.temp_override(id=idblock):
        bpy.ops.ed.lib_id_generate_preview()


def preview_pixels(idblock: Any) -> np.ndarray:
    p = idblock.preview
    width, height = p.image_size
    pixels = np.empty(width * height * 4, dtype=np.float32)
    p.image_pixels_float.foreach_get(pixels)
    return pixels.reshape(height, width, 4)


def summary(idblock: Any, render: dict[str, Any] | None) -> dict[str, Any]:
    pixels = preview_pixels(idblock)
    h, w = pixels.shape[:2]
    centre = pixels[h // 4: 3 * h // 4, w // 4: 3 * w // 4, :3]
    return {"render": render, "image_size": [w, h],
            "mean_rgba": pixels.reshape(-1, 4).mean(axis=0).tolist(),
            "centre_rgb": centre.reshape(-1, 3).mean(axis=0).tolist()}


def run_waiting(timeout: float = 120.0) -> dict[str, Any]:
    """In this process, without an event loop (the bpy wheel): each job runs in its thread;
    the preview is complete when render() has returned and its pixels have arrived."""
    recorder = RenderRecorder()
    results: dict[str, Any] = {}
    try:
        for kind in KINDS:
            idblock = make_id(kind)
            before = len(recorder.renders)
            start_job(idblock)
            deadline = time.monotonic() + timeout
            while time.monotonic() < deadline:
                if len(recorder.renders) > before and preview_pixels(idblock).any():
                    break
                time.sleep(0.05)
            render = recorder.renders[before] if len(recorder.renders) > before else None
            results[kind] = summary(idblock, render)
    finally:
        recorder.restore()
    return results


def run_with_event_loop(out: Path, timeout: float = 120.0) -> None:
    """In Blender with its UI: one job after the other from timers, then the results to
    `out` and quit."""
    recorder = RenderRecorder()
    results: dict[str, Any] = {}
    queue = list(KINDS)
    current: dict[str, Any] = {}

    def finish() -> None:
        out.write_text(json.dumps(results))
        sys.stdout.flush()
        # Not wm.quit_blender: that saves the session to quit.blend in the temporary folder.
        os._exit(0)

    def poll() -> float | None:
        idblock, started = current["id"], current["started"]
        if bpy.app.is_job_running("RENDER_PREVIEW") and time.monotonic() - started < timeout:
            return 0.1
        render = recorder.renders[current["before"]] \
            if len(recorder.renders) > current["before"] else None
        results[current["kind"]] = summary(idblock, render)
        return next_job()

    def next_job() -> float | None:
        if not queue:
            finish()
            return None
        kind = queue.pop(0)
        current.update(kind=kind, id=make_id(kind), before=len(recorder.renders),
                       started=time.monotonic())
        start_job(current["id"])
        bpy.app.timers.register(poll, first_interval=0.1)
        return None

    start: Callable[[], float | None] = next_job
    bpy.app.timers.register(start, first_interval=0.5)


def main() -> None:
    if str(ADDON_DIR) not in sys.path:
        sys.path.insert(0, str(ADDON_DIR))
    import stratum

    stratum.register()
    bpy.context.scene.render.engine = "STRATUM"
    out = Path(sys.argv[sys.argv.index("--") + 1])
    run_with_event_loop(out)


if __name__ == "__main__":
    main()
