"""F12 progress (issue 14): the image and the "Sample N/M" counter move throughout a render,
also during its last pass (half of a render's samples), through the engine's own loop
(engine/final_render.py) in a real Blender render.

The renderer is scripted (ScriptedRenderer) and the loop's clock stands in for real time, so
what the loop does at each step does not depend on this machine's speed: each wait() is one
tile of a pass ending and 0.4 s passing. tests/native/render/test_render_progress.cpp shows that the
native renderer does report tiles within a pass.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from conftest import render_still

bpy = pytest.importorskip("bpy")

SAMPLES = 16
TILES_PER_PASS = 8
SECONDS_PER_STEP = 0.4


def _schedule() -> list[dict[str, Any]]:
    """Progress after each tile of passes [0,1) [1,2) [2,4) [4,8) [8,16), as the renderer
    reports it (render/renderer.h)."""
    states, serial, begin = [], 0, 0
    while begin < SAMPLES:
        end = min(SAMPLES, max(1, 2 * begin))
        for tile in range(1, TILES_PER_PASS + 1):
            serial += 1
            states.append({"samples_done": end if tile == TILES_PER_PASS else begin,
                           "samples_in_progress": end, "update_serial": serial,
                           "samples_average": begin + (end - begin) * tile / TILES_PER_PASS})
        begin = end
    states[-1]["done"] = True
    return states


class ScriptedRenderer:
    """Stands in for native.Renderer in render_progressively: each wait() ends one tile."""

    def __init__(self, width: int, height: int, clock: list[float]) -> None:
        self.states = _schedule()
        self.step = -1
        self.clock = clock
        self.pixels = width * height

    def start(self) -> None:
        self.step = 0

    def wait(self, timeout_ms: int) -> bool:
        self.step = min(self.step + 1, len(self.states) - 1)
        self.clock[0] += SECONDS_PER_STEP
        return bool(self.states[self.step].get("done"))

    def progress(self) -> Any:
        from stratum import native

        s = self.states[max(self.step, 0)]
        return native.Progress(
            done=bool(s.get("done")), cancelled=False, samples_done=s["samples_done"],
            samples_total=SAMPLES, update_serial=s["update_serial"], rays=1e6,
            build_seconds=0.0, render_seconds=1.0,
            fraction_done=s["samples_average"] / SAMPLES,
            samples_in_progress=s["samples_in_progress"],
            samples_average=s["samples_average"])

    def read_pixels(self, out: np.ndarray) -> np.ndarray:
        # The image as the renderer would publish it: its grey level is the samples average.
        out[:] = self.states[max(self.step, 0)]["samples_average"] / SAMPLES
        return out

    def cancel(self) -> None:
        pass

    def notices(self) -> list[str]:
        return []


class RecordingEngine:
    """The engine as render_progressively sees it, recording what it shows and when."""

    def __init__(self, engine: Any, renderer: ScriptedRenderer) -> None:
        self._engine = engine
        self._renderer = renderer
        self.results: list[tuple[float, dict[str, Any]]] = []  # (clock, progress state)
        self.stats: list[tuple[dict[str, Any], str]] = []

    def __getattr__(self, name: str) -> Any:
        return getattr(self._engine, name)

    def _state(self) -> dict[str, Any]:
        return self._renderer.states[max(self._renderer.step, 0)]

    def update_result(self, result: Any) -> None:
        self.results.append((self._renderer.clock[0], self._state()))
        self._engine.update_result(result)

    def update_stats(self, stats: str, info: str) -> None:
        self.stats.append((self._state(), info))
        self._engine.update_stats(stats, info)


def test_image_and_counter_move_during_the_last_pass(
        library: Any, scene_builder: Any, monkeypatch: pytest.MonkeyPatch,
        tmp_path: Path) -> None:
    from stratum.engine import final_render

    b = scene_builder().basic()
    b.set_resolution(16, 8)
    b.scene.stratum.samples = SAMPLES
    clock = [100.0]
    recorded: list[RecordingEngine] = []
    original = final_render.render_progressively

    def scripted(engine: Any, renderer: Any, width: int, height: int, *rest: Any) -> None:
        fake = ScriptedRenderer(width, height, clock)
        recording = RecordingEngine(engine, fake)
        recorded.append(recording)
        original(recording, fake, width, height, *rest)

    monkeypatch.setattr(final_render, "render_progressively", scripted)
    monkeypatch.setattr(final_render, "clock", lambda: clock[0])
    pixels = render_still(b.scene, tmp_path / "progress.exr")
    assert len(recorded) == 1
    rec = recorded[0]
    last_pass = [s for _, s in rec.results
                 if s["samples_done"] == SAMPLES // 2 and s["samples_in_progress"] == SAMPLES]
    # The last pass is 8 polls of 0.4 s (7 before its last tile), 12.8 s into the render:
    # copies, every result_interval (0.75 s) at the latest, show 3 of them.
    assert len(last_pass) >= 3, rec.results
    # Every copy of new pixels comes within a second of the previous one.
    times = [t for t, _ in rec.results]
    assert max(np.diff(times)) <= 1.0, times
    # The counter shows the samples rendered per pixel as tiles end, also within the pass.
    shown = [float(re.match(r"Sample ([\d.]+)/16", info).group(1))
             for s, info in rec.stats
             if info.startswith("Sample") and s["samples_done"] == SAMPLES // 2]
    assert len(set(shown)) >= 3 and shown == sorted(shown), shown
    assert all(SAMPLES // 2 <= n <= SAMPLES for n in shown), shown
    # The final image is the renderer's last one.
    assert pixels is not None
    np.testing.assert_allclose(pixels[..., :3], 1.0)


@pytest.mark.parametrize(("average", "shown"), [
    (0.0, "0"), (0.25, "0.2"), (32.0, "32"), (47.36, "47.3"), (63.99, "63.9"), (64.0, "64")])
def test_counter_shows_samples_per_pixel_to_a_tenth_rounded_down(
        stratum_addon: Any, average: float, shown: str) -> None:
    """A tenth, so that the counter moves while one sample per pixel takes seconds; rounded down,
    so that 64/64 means every pixel has its 64."""
    from stratum import native
    from stratum.engine.final_render import format_stats

    progress = native.Progress(
        done=False, cancelled=False, samples_done=32, samples_total=64, update_serial=1,
        rays=0.0, build_seconds=0.0, render_seconds=0.0, fraction_done=average / 64,
        samples_in_progress=64, samples_average=average)
    assert format_stats(progress, 1.0).startswith(f"Sample {shown}/64 | "), \
        format_stats(progress, 1.0)


def test_stats_line_shows_the_guiding_tree(stratum_addon: Any) -> None:
    """Path guiding's tree, from its progress counters, as the light tree's
    (test_many_lights_hall.py) and the radiosity solve's (test_radiosity.py)."""
    from stratum import native
    from stratum.engine.final_render import format_stats

    fields: dict[str, Any] = {
        "done": False, "cancelled": False, "samples_done": 4, "samples_total": 16,
        "update_serial": 1, "rays": 1e6, "build_seconds": 0.1, "render_seconds": 1.0,
        "fraction_done": 0.25, "samples_in_progress": 8, "samples_average": 4.0}
    without = format_stats(native.Progress(**fields), 2.0)
    assert "Guiding" not in without
    guided = format_stats(native.Progress(**fields, counters={"guiding.nodes": 5377.0,
                                                              "guiding.bytes": 1.25e6}), 2.0)
    assert guided == without + " | Guiding 5377 nodes, 1.25 MB"
