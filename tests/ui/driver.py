"""Drives Blender's real UI from inside it: a scenario is a generator of steps run from
bpy.app.timers (the UI keeps drawing between steps, as it does for a user), whose findings go
to results.json in the output folder when it ends. Runs in Blender 3.4 under Xvfb
(tests/ui/conftest.py starts it); never imported by pytest itself.

A scenario script does

    from driver import Scenario
    def steps(s: Scenario) -> Iterator[float]:
        ...            # act on the UI
        yield 0.5      # let Blender draw for half a second
        yield from s.wait_until(lambda: ..., timeout=60.0, what="...")
    Scenario.main(steps)

Every exception (a failed check included) is recorded with its traceback and ends the run;
Blender is then quit, so a hung UI never outlives the test's timeout by much.
"""

from __future__ import annotations

import json
import sys
import time
import traceback
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import bpy
import numpy as np


class ScenarioFailed(AssertionError):
    pass


class Scenario:
    def __init__(self, out_dir: Path) -> None:
        self.out = out_dir
        self.out.mkdir(parents=True, exist_ok=True)
        self.results: dict[str, Any] = {"steps": []}
        self.started = time.perf_counter()

    # ---- the 3D view -----------------------------------------------------------------------

    def view3d(self) -> tuple[Any, Any, Any]:
        """(window, area, WINDOW region) of the largest 3D view of the screen."""
        best = None
        for window in bpy.context.window_manager.windows:
            for area in window.screen.areas:
                if area.type == "VIEW_3D" and (best is None or
                                               area.width * area.height > best[1].width * best[1].height):
                    region = next(r for r in area.regions if r.type == "WINDOW")
                    best = (window, area, region)
        if best is None:
            raise ScenarioFailed("the screen has no 3D view")
        return best

    def space(self) -> Any:
        return self.view3d()[1].spaces.active

    def override(self) -> Any:
        window, area, region = self.view3d()
        return bpy.context.temp_override(window=window, area=area, region=region,
                                         screen=window.screen)

    def plain_view(self) -> None:
        """Only the rendered pixels: no overlays, gizmos, header, toolbar or sidebar."""
        space = self.space()
        space.overlay.show_overlays = False
        space.show_gizmo = False
        for attribute in ("show_region_toolbar", "show_region_ui", "show_region_header",
                          "show_region_tool_header"):
            if hasattr(space, attribute):
                setattr(space, attribute, False)

    def screenshot(self, name: str) -> np.ndarray:
        """The 3D view as drawn (display transform applied): float RGBA (height, width, 4),
        rows bottom to top; also saved as <out>/<name>.png."""
        path = self.out / f"{name}.png"
        with self.override():
            bpy.ops.screen.screenshot_area(filepath=str(path))
        return load_png(path)

    # ---- running ---------------------------------------------------------------------------

    def log(self, message: str) -> None:
        elapsed = time.perf_counter() - self.started
        self.results["steps"].append(f"{elapsed:7.2f}s {message}")
        print(f"ui-scenario {elapsed:7.2f}s {message}", flush=True)

    def wait_until(self, condition: Callable[[], bool], timeout: float, what: str,
                   poll: float = 0.25) -> Iterator[float]:
        """Yields until condition() holds; ScenarioFailed naming `what` after `timeout` s."""
        deadline = time.perf_counter() + timeout
        while not condition():
            if time.perf_counter() > deadline:
                raise ScenarioFailed(f"timed out after {timeout:g} s waiting for {what}")
            yield poll
        self.log(f"{what}: done")

    def finish(self, error: str | None) -> None:
        self.results["error"] = error
        self.results["seconds"] = time.perf_counter() - self.started
        (self.out / "results.json").write_text(json.dumps(self.results, indent=1))
        bpy.ops.wm.quit_blender()

    @classmethod
    def main(cls, steps: Callable[[Scenario], Iterator[float]], persistent: bool = False) -> None:
        """Runs `steps` from a timer once the UI is up; the output folder is the first argument
        after `--`. `persistent`: the timer survives loading a file (Blender drops other
        timers then), for scenarios that load one."""
        out = Path(sys.argv[sys.argv.index("--") + 1])
        scenario = cls(out)
        iterator = steps(scenario)

        def tick() -> float | None:
            try:
                return next(iterator)
            except StopIteration:
                scenario.finish(None)
            except Exception:  # noqa: BLE001 - recorded for the test, then Blender quits
                scenario.finish(traceback.format_exc())
            return None

        bpy.app.timers.register(tick, first_interval=1.0, persistent=persistent)


def load_png(path: Path) -> np.ndarray:
    image = bpy.data.images.load(str(path), check_existing=False)
    try:
        width, height = image.size
        pixels = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        return pixels.reshape(height, width, 4)
    finally:
        bpy.data.images.remove(image)


def recording(name: str, draw: Callable[..., None], s: Scenario) -> Callable[..., None]:
    """`draw` (a panel's or preferences' draw) that also records, in s.results, that Blender
    drew `name` ("drawn") and any exception it raised ("draw_errors"; Blender only prints
    those)."""
    def draw_and_record(panel: Any, context: Any) -> None:
        try:
            draw(panel, context)
        except Exception:
            s.results.setdefault("draw_errors", []).append(traceback.format_exc())
            raise
        drawn = s.results.setdefault("drawn", [])
        if name not in drawn:
            drawn.append(name)

    return draw_and_record
