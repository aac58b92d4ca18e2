"""Cancel latency (issue 12, point 8): Esc during export, during the BVH build of a 1M-triangle
scene and during rendering each give control back within 0.5 s.

Scenes: a grid of 1M triangles filling the view (export, rendering). For the BVH build, 2M
triangles: here Embree builds 1M triangles in 0.25-0.5 s, so a build that ignored the cancel
would still return within the bound and the test would show nothing; 2M on one thread take
about a second.

The latency is measured as the user sees it: from the moment RenderEngine.test_break() starts
returning True (Blender's Esc) to the moment the engine's render() returns. test_break, which
the engine reads through final_render.stop_requested (an RNA function cannot be overridden from
Python), is replaced by a clock that turns True at a chosen point of the render:
  * export: when the exporter starts reading the 1M-triangle mesh (object_mesh_arrays);
  * BVH build: right after Renderer.start(), which hands the scene to the worker thread whose
    first job is the Embree build (the poll loop sees the break at its next 100 ms wait);
  * rendering: when the progress first reports a finished sample pass of a 4096-sample render.
The bound is the issue's; it is a wall-clock bound on a shared machine, so it is measured
generously: up to ATTEMPTS times, the best attempt must meet it, and every attempt is printed.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import bpy
import numpy as np
import pytest

from conftest import SceneBuilder, engine_reports

BOUND_SECONDS = 0.5
ATTEMPTS = 3
GRID_1M = 708  # vertices per side: 707^2 quads = 999,698 triangles
GRID_2M = 1001  # 1000^2 quads = 2,000,000 triangles
# Enough samples that a render which ignored the cancel would run for seconds (64x64 pixels,
# ~0.5M samples/s on one thread here), in every phase.
SAMPLES = 4096


def grid_mesh(name: str, n: int) -> Any:
    """A flat n x n vertex grid over [-1, 1]^2 in z = 0, built with foreach_set (from_pydata
    takes seconds for a million faces in 3.4). Loop totals are derived from loop starts in
    4.0+ and must be set before."""
    me = bpy.data.meshes.new(name)
    axis = np.linspace(-1.0, 1.0, n, dtype=np.float32)
    co = np.zeros((n * n, 3), dtype=np.float32)
    co[:, 0], co[:, 1] = np.tile(axis, n), np.repeat(axis, n)
    first = (np.arange(n - 1)[:, None] * n + np.arange(n - 1)[None, :]).ravel()
    quads = np.stack([first, first + 1, first + n + 1, first + n], axis=1).astype(np.int32)
    count = len(quads)
    me.vertices.add(n * n)
    me.vertices.foreach_set("co", co.ravel())
    me.loops.add(4 * count)
    me.loops.foreach_set("vertex_index", quads.ravel())
    me.polygons.add(count)
    me.polygons.foreach_set("loop_start", np.arange(0, 4 * count, 4, dtype=np.int32))
    if bpy.app.version < (4, 0, 0):
        me.polygons.foreach_set("loop_total", np.full(count, 4, dtype=np.int32))
    me.update()
    return me


def grid_scene(grid: int, samples: int) -> Any:
    """The base scene (camera, cube, light, world) behind a grid of grid x grid vertices filling
    the view: 64x64 pixels, `samples` samples, one thread (which builds the BVH too: the
    slowest build, the worst case for a cancel)."""
    b = SceneBuilder().basic()
    grid = b.link(bpy.data.objects.new("Grid", grid_mesh("Grid", grid)))
    grid.location = (0.0, -2.0, 0.0)
    grid.rotation_euler = (1.5708, 0.0, 0.0)
    grid.scale = (2.0, 2.0, 2.0)
    b.set_resolution(64, 64)
    b.scene.stratum.samples = samples
    b.scene.stratum.threads = 1
    return b.scene


class BreakClock:
    """Stands in for Esc: test_break() is False until arm(), True from then on."""

    def __init__(self) -> None:
        self.armed_at: float | None = None
        self.returned_at: float | None = None

    def arm(self) -> None:
        if self.armed_at is None:
            self.armed_at = time.perf_counter()

    def latency(self) -> float | None:
        if self.armed_at is None or self.returned_at is None:
            return None
        return self.returned_at - self.armed_at


def _cancelled_render(monkeypatch: pytest.MonkeyPatch,
                      arm_at: Callable[[pytest.MonkeyPatch, BreakClock], None]) -> BreakClock:
    """One render of the current scene with test_break driven by a BreakClock that `arm_at`
    hooks into the render; returns the clock with both times set."""
    import stratum.engine.final_render
    from stratum.engine import StratumRenderEngine

    clock = BreakClock()
    render = StratumRenderEngine.render

    def timed_render(self: Any, depsgraph: Any) -> None:
        try:
            render(self, depsgraph)
        finally:
            clock.returned_at = time.perf_counter()

    with monkeypatch.context() as patch:
        patch.setattr(stratum.engine.final_render, "stop_requested", lambda engine: clock.armed_at is not None)
        patch.setattr(StratumRenderEngine, "render", timed_render)
        arm_at(patch, clock)
        bpy.ops.render.render()
    return clock


def _arm_in_export(patch: pytest.MonkeyPatch, clock: BreakClock) -> None:
    import stratum.export.geometry

    read = stratum.export.geometry.object_mesh_arrays

    def reading(ob: Any, *args: Any, **kwargs: Any) -> Any:
        if ob.name == "Grid":
            clock.arm()
        return read(ob, *args, **kwargs)

    patch.setattr(stratum.export.geometry, "object_mesh_arrays", reading)


def _arm_after_start(patch: pytest.MonkeyPatch, clock: BreakClock) -> None:
    from stratum import native

    start = native.Renderer.start

    def started(self: Any) -> None:
        start(self)
        clock.arm()

    patch.setattr(native.Renderer, "start", started)


def _arm_after_first_pass(patch: pytest.MonkeyPatch, clock: BreakClock) -> None:
    from stratum import native

    progress = native.Renderer.progress

    def reported(self: Any) -> Any:
        p = progress(self)
        if p.samples_done >= 1:
            clock.arm()
        return p

    patch.setattr(native.Renderer, "progress", reported)


PHASES = {
    "export": (_arm_in_export, GRID_1M),
    "bvh_build": (_arm_after_start, GRID_2M),
    "rendering": (_arm_after_first_pass, GRID_1M),
}


@pytest.mark.parametrize("phase", list(PHASES))
def test_cancel_returns_within_half_a_second(library: Any, monkeypatch: pytest.MonkeyPatch,
                                             phase: str) -> None:
    arm_at, grid = PHASES[phase]
    grid_scene(grid, SAMPLES)
    latencies: list[float] = []
    for _ in range(ATTEMPTS):
        clock = _cancelled_render(monkeypatch, arm_at)
        assert not engine_reports("ERROR"), engine_reports("ERROR")
        latency = clock.latency()
        assert latency is not None, f"the render never reached the {phase} phase"
        latencies.append(latency)
        if latency < BOUND_SECONDS:
            break
    print(f"\ncancel during {phase} ({bpy.app.version_string}): "
          + ", ".join(f"{t:.3f} s" for t in latencies))
    assert min(latencies) < BOUND_SECONDS, (
        f"cancel during {phase} returned after {min(latencies):.3f} s at best "
        f"(attempts: {latencies})")
