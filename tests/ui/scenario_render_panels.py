"""The render-properties panels in Blender 3.4's real UI (tests/ui/test_panels_ui.py): the
largest area becomes a Properties editor on the Render tab, Stratum's Sampling and Light Paths
panels and their subpanels open, and screenshots are taken with adaptive sampling off and on
(the Noise Threshold blocks grey out and read Samples / Max Samples).

Each panel's draw is wrapped before registration so that the scenario records which panels
Blender itself drew, with its own UILayout, and any exception a draw raised (Blender only
prints those); findings go to results.json (driver.py).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import bpy
from driver import Scenario, ScenarioFailed, load_png, recording

# The panels a screenshot shows open; Film and Performance stay closed, as in Cycles.
OPENED_PREFIXES = ("STRATUM_RENDER_PT_sampling", "STRATUM_RENDER_PT_light_paths")


def properties_area(s: Scenario) -> Iterator[float]:
    """Turns the largest area into a Properties editor on the Render tab (s.area); its tabs
    exist once it has been drawn."""
    _, area, _ = s.view3d()
    area.type = "PROPERTIES"
    yield 1.0
    area.spaces.active.context = "RENDER"
    s.area = area


def screenshot(s: Scenario, area: Any, name: str) -> list[float]:
    """Saves <out>/<name>.png of `area`; returns its per-channel mean (a change of what is
    drawn changes it)."""
    path = s.out / f"{name}.png"
    window = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=window, area=area, screen=window.screen):
        bpy.ops.screen.screenshot_area(filepath=str(path))
    image = load_png(path)
    s.results.setdefault("shots", {})[name] = list(image.shape)
    return [float(v) for v in image[..., :3].reshape(-1, 3).mean(axis=0)]


def steps(s: Scenario) -> Iterator[float]:
    import stratum
    from stratum import ui

    for cls in ui.classes:
        if cls.__name__.startswith(OPENED_PREFIXES):
            cls.bl_options = set(getattr(cls, "bl_options", set())) - {"DEFAULT_CLOSED"}
        cls.draw = recording(cls.__name__, cls.draw, s)
        if "draw_header" in vars(cls):
            cls.draw_header = recording(f"{cls.__name__}.header", cls.draw_header, s)
    stratum.register()
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    yield from properties_area(s)
    area = s.area
    yield 1.5
    s.results["off"] = screenshot(s, area, "adaptive_off")
    s.log("panels drawn with adaptive sampling off")

    scene.stratum.use_adaptive_sampling = True
    scene.stratum.use_preview_adaptive_sampling = True
    area.tag_redraw()
    yield 1.5
    s.results["on"] = screenshot(s, area, "adaptive_on")
    s.log("panels drawn with adaptive sampling on")

    scene.stratum.integrator = "ao"
    area.tag_redraw()
    yield 1.5
    s.results["ao"] = screenshot(s, area, "ambient_occlusion")
    s.log("panels drawn for ambient occlusion")
    if not s.results.get("drawn"):
        raise ScenarioFailed("Blender drew none of Stratum's panels")


if __name__ == "__main__":
    Scenario.main(steps)
