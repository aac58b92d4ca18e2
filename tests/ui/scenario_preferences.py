"""The add-on's preferences in Blender 3.4's real UI, from the installed package
(tests/ui/test_preferences_ui.py): the zip named by $STRATUM_PACKAGE is installed through
Preferences > Add-ons > Install into the (temporary) user configuration, enabled, and the
largest area becomes the Preferences editor on Add-ons, filtered to Stratum and expanded, so
that Blender draws StratumPreferences (version, native library) with its own layout. The draw
is wrapped to record that it ran, without an error, and what it showed; a screenshot is kept.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from typing import Any

import bpy
from driver import Scenario, ScenarioFailed, recording


def steps(s: Scenario) -> Iterator[float]:
    package = os.environ["STRATUM_PACKAGE"]
    assert bpy.ops.preferences.addon_install(filepath=package) == {"FINISHED"}
    assert bpy.ops.preferences.addon_enable(module="stratum") == {"FINISHED"}
    ui = sys.modules["stratum.ui"]
    s.results["module_file"] = sys.modules["stratum"].__file__
    draw = ui.StratumPreferences.draw

    def draw_and_note(self: Any, context: Any) -> None:
        draw(self, context)
        status = ui.native.library_status()
        s.results["shown"] = {"version": ui.__version__, "library": str(status.path),
                              "library_version": status.version, "error": status.error}

    ui.StratumPreferences.draw = recording("StratumPreferences", draw_and_note, s)
    _, area, _ = s.view3d()
    area.type = "PREFERENCES"
    bpy.context.preferences.active_section = "ADDONS"
    bpy.context.window_manager.addon_search = "Stratum"
    # The list's disclosure triangle (it flips show_expanded of the listed module's bl_info).
    assert bpy.ops.preferences.addon_expand(module="stratum") == {"FINISHED"}
    area.tag_redraw()
    yield 2.0
    window = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=window, area=area, screen=window.screen):
        bpy.ops.screen.screenshot_area(filepath=str(s.out / "preferences.png"))
    if not (s.out / "preferences.png").is_file():
        raise ScenarioFailed("no screenshot")
    yield from s.wait_until(lambda: "shown" in s.results, timeout=10.0,
                            what="the preferences drawn")


Scenario.main(steps)
