"""Light Paths settings in Blender (issue 34): which ones a scene renders with
(scene.stratum.light_paths, blender_settings.LIGHT_PATHS_SOURCES), Cycles' values reaching the
library under Stratum's names, and the Max Bounces and Clamping panels drawing the settings in
use. Runs in Blender 3.4 (run_in_blender.py) and in the bpy wheels. The rule without Blender:
tests/python/test_light_paths_source.py; what each setting does to an image against Cycles:
test_light_path_agreement.py.
"""

from __future__ import annotations

from typing import Any

import pytest
from stratum import blender_settings, ui
from stratum.engine.frame import renderer_settings

from panel_layout import draw_panel

CYCLES_DEFAULTS = {"max_bounces": 12, "diffuse_bounces": 4, "glossy_bounces": 4,
                   "transmission_bounces": 12, "transparent_max_bounces": 8,
                   "clamp_direct": 0.0, "clamp_indirect": 10.0, "filter_glossy": 1.0,
                   "caustics_reflective": 1, "caustics_refractive": 1}


def _light_paths(settings: dict[str, Any]) -> dict[str, Any]:
    return {name: settings[name] for name in blender_settings.CYCLES_LIGHT_PATHS}


def test_a_new_scene_renders_unbiased_with_stratums_own(library: Any, scene_builder: Any) -> None:
    scene = scene_builder().basic().scene
    assert scene.stratum.light_paths == "AUTO"
    sent = _light_paths(renderer_settings(scene))
    for name, value in sent.items():
        assert value == pytest.approx(library.setting(name).default), name
    assert sent["clamp_indirect"] == 0.0 and sent["diffuse_bounces"] == 1024


def test_a_file_tuned_for_cycles_renders_with_cycles_values(library: Any,
                                                            scene_builder: Any) -> None:
    """Auto: one Cycles Light Paths value set in the file brings all of them, Cycles' defaults
    (clamping at 10, 4 diffuse and glossy bounces) included; Stratum keeps its own when asked."""
    scene = scene_builder().basic().scene
    scene.cycles.diffuse_bounces = 2
    sent = _light_paths(renderer_settings(scene))
    assert sent == pytest.approx(CYCLES_DEFAULTS | {"diffuse_bounces": 2})
    scene.stratum.light_paths = "STRATUM"
    scene.stratum.glossy_bounces = 3
    own = _light_paths(renderer_settings(scene))
    assert own["diffuse_bounces"] == 1024 and own["glossy_bounces"] == 3
    assert own["clamp_indirect"] == 0.0


def test_cycles_source_takes_cycles_defaults_of_an_untouched_scene(library: Any,
                                                                   scene_builder: Any) -> None:
    scene = scene_builder().basic().scene
    scene.stratum.light_paths = "CYCLES"
    assert _light_paths(renderer_settings(scene)) == pytest.approx(CYCLES_DEFAULTS)
    scene.cycles.sample_clamp_indirect = 0.5
    scene.cycles.transparent_max_bounces = 3
    scene.cycles.blur_glossy = 0.25
    scene.cycles.caustics_refractive = False
    sent = renderer_settings(scene)
    assert sent["clamp_indirect"] == pytest.approx(0.5) and sent["transparent_max_bounces"] == 3
    assert sent["filter_glossy"] == pytest.approx(0.25) and sent["caustics_refractive"] == 0
    with library.Renderer(library.Scene()) as renderer:
        for name in blender_settings.CYCLES_LIGHT_PATHS:
            renderer.set(name, sent[name])


def test_the_panels_draw_the_settings_in_use(library: Any, scene_builder: Any) -> None:
    """Max Bounces and Clamping show Stratum's properties, or Cycles' where those render (what
    the user edits is what renders)."""
    scene = scene_builder().basic().scene
    panels = (ui.STRATUM_RENDER_PT_light_paths_max_bounces, ui.STRATUM_RENDER_PT_light_paths_clamping,
              ui.STRATUM_RENDER_PT_light_paths_caustics)
    own = [name for panel in panels for name in draw_panel(panel, scene).names()]
    assert own == ["max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
                   "transparent_max_bounces", "clamp_direct", "clamp_indirect", "filter_glossy",
                   "caustics_reflective", "caustics_refractive"]
    scene.stratum.light_paths = "CYCLES"
    cycles = [name for panel in panels for name in draw_panel(panel, scene).names()]
    assert cycles == [blender_settings.CYCLES_LIGHT_PATHS[name] for name in own]
