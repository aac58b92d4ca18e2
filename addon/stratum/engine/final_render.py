"""F12: a frame exported, rendered by the native library on its own threads, and copied into
Blender's render result as it refines. Esc cancels; what the render cannot show is reported as
warnings."""

from __future__ import annotations

import math
import time
from typing import Any

import bpy
import numpy as np

from .. import blender_versions, native, properties
from ..export.sync import export_scene
from . import denoise
from .frame import layer_samples, renderer_settings, result_size
from .render_passes import ResultPasses

POLL_MS = 100


def clock() -> float:
    """The render loop's clock, in seconds. A module function so that tests can stand in for
    it (a scripted render then runs without waiting)."""
    return time.perf_counter()


def result_interval(elapsed: float) -> float:
    """Seconds between copies of new pixels into Blender's render result, `elapsed` seconds
    into the render. Cycles' display ladder (render_scheduler.cpp,
    guess_display_update_interval_in_seconds): 0.1 s in the first second, 0.25 s until 2 s,
    0.5 s until 4 s, then 1 s (2 s in Cycles' F12 after 32 samples). Stratum's last rung is
    0.75 s: the loop sees the interval pass only at its next poll (POLL_MS) and then copies the
    frame, so the image moves at least once a second throughout a render. Later copies are
    rarer because each reads and hands Blender the whole frame (a 4K frame is 130 MB)."""
    if elapsed < 1.0:
        return 0.1
    if elapsed < 2.0:
        return 0.25
    if elapsed < 4.0:
        return 0.5
    return 0.75


def stop_requested(engine: Any) -> bool:
    """Blender's Esc: engine.test_break(). A module function so that tests can stand in for it
    (test_break is an RNA function, which a Python subclass or monkeypatch cannot override)."""
    return bool(engine.test_break())


def format_stats(progress: native.Progress, elapsed: float) -> str:
    """Blender's status line. "Sample N/M" counts, as Cycles' does, the samples rendered per
    pixel: samples_average, which moves as tiles finish (within a pass of the renderer some
    pixels hold its end count and the others its start, where Cycles' pixels all hold N; the
    work is the same). N is shown to a tenth, rounded down, so that it moves at least once a
    second also when one sample per pixel takes seconds (a 512 x 512 Cornell box on 2 busy
    cores: 3.4 s); "64/64" only when every pixel has its 64."""
    rate = progress.rays / progress.render_seconds if progress.render_seconds > 0 else 0.0
    if rate >= 1e6:
        rays = f"{rate / 1e6:.2f}M"
    elif rate >= 1e3:
        rays = f"{rate / 1e3:.1f}k"
    else:
        rays = f"{rate:.0f}"
    tenths = math.floor(progress.samples_average * 10)
    samples = f"{tenths // 10}" if tenths % 10 == 0 else f"{tenths / 10:.1f}"
    stats = f"Sample {samples}/{progress.samples_total} | {elapsed:.1f}s | {rays} rays/s"
    # The light tree's cost, once built (issue 16: "build time and memory reported").
    if progress.counter("light_tree.bytes") > 0:
        stats += (f" | Light tree {progress.counter('light_tree.seconds') * 1e3:.0f} ms, "
                  f"{progress.counter('light_tree.bytes') / 1e6:.2f} MB")
    # The radiosity solve's size and cost (issue 17: K and the memory used).
    if progress.counter("radiosity.patches") > 0:
        stats += (f" | Radiosity {progress.counter('radiosity.patches'):.0f} patches, "
                  f"{progress.counter('radiosity.bytes') / 1e6:.1f} MB, "
                  f"{progress.counter('radiosity.seconds'):.2f} s, "
                  f"{progress.counter('radiosity.iterations'):.0f} iterations")
    # Path guiding's tree (issue 17: "report memory use and its growth").
    if progress.counter("guiding.nodes") > 0:
        stats += (f" | Guiding {progress.counter('guiding.nodes'):.0f} nodes, "
                  f"{progress.counter('guiding.bytes') / 1e6:.2f} MB")
    return stats


class PixelWriter:
    """Copies renderer pixels into a render result pass: one read_pixels into a preallocated
    float32 buffer, one foreach_set. 3.x/4.0 want an (N, 4) array, 4.1+ a flat one."""

    def __init__(self, width: int, height: int) -> None:
        self.buffer = np.zeros(width * height * 4, dtype=np.float32)
        self._flat: bool = blender_versions.flat_pass_pixels(bpy.app.version)

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


def render_frame(engine: Any, depsgraph: Any) -> None:
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
    settings["samples"] = layer_samples(scene, depsgraph.view_layer, int(settings["samples"]))
    denoising = denoise.prepare_final(engine, scene, settings)
    passes = ResultPasses(engine, depsgraph.view_layer, scene.world)
    passes.configure(settings)
    width, height = result_size(scene)

    engine.update_stats("", "Exporting scene")
    with native.Scene() as native_scene:
        summary = export_scene(depsgraph, native_scene,
                               should_stop=lambda: stop_requested(engine),
                               frame_set=engine.frame_set)
        type(engine).last_summary = summary
        for warning in summary.warnings:
            engine._report("WARNING", warning)
        if stop_requested(engine):  # Esc during export: no renderer, no BVH build
            return
        renderer = native.Renderer(native_scene)
    with renderer:
        for name, value in settings.items():
            renderer.set(name, value)
        render_progressively(engine, renderer, width, height, denoising, passes)


def render_progressively(engine: Any, renderer: native.Renderer, width: int, height: int,
                         denoising: denoise.FinalDenoising | None = None,
                         passes: ResultPasses | None = None) -> None:
    started = clock()
    engine.update_stats("", "Building BVH / starting")
    # Started before Blender's result and the pixel buffer are allocated: a render the
    # renderer refuses (a film beyond memory, 65536 x 20000) must not get them first, each
    # as large as the image, which the OOM killer would have ended Blender for.
    renderer.start()
    writer = PixelWriter(width, height)
    result = engine.begin_result(0, 0, width, height)
    try:
        render_pass = combined_pass(result)
        # What this render cannot show (the estimator's limits at start; skipped objects and
        # dropped samples as the render learns them): warnings, the render goes on.
        reported: set[str] = set()
        report_notices(engine, renderer, reported)
        last_serial: int | None = None
        written_at: float | None = None
        cancelled_at: float | None = None
        while True:
            done = renderer.wait(POLL_MS)
            now = clock()
            if cancelled_at is None and stop_requested(engine):
                renderer.cancel()
                cancelled_at = now
            progress = renderer.progress()
            # Tiles publish pixels many times a second: copied at result_interval's pace.
            if progress.update_serial != last_serial and (
                    written_at is None or now - written_at >= result_interval(now - started)):
                last_serial = progress.update_serial
                written_at = now
                writer.write(renderer, render_pass)
                engine.update_result(result)
            engine.update_progress(min(progress.fraction_done, 1.0))
            engine.update_stats("", format_stats(progress, now - started))
            if done or progress.done:
                break
            if cancelled_at is not None and now - cancelled_at > 30.0:
                engine._report("ERROR", "Stratum: the renderer did not stop after cancel")
                break
        # Final pixels (also the partial image after Esc).
        writer.write(renderer, render_pass)
        if passes is not None:
            passes.write(renderer, result)
        if denoising is not None:
            denoising.apply(renderer, result)
        report_notices(engine, renderer, reported)
    finally:
        engine.end_result(result)
