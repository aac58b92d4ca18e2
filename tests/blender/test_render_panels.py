"""The render-properties panels laid out like Cycles' (issue 16, acceptance 5): Sampling with
its Viewport, Render, Denoising, Advanced, Lights and Path Guiding subpanels, Light Paths with Max Bounces,
Russian Roulette, Direct Light and Control Variate; the Noise Threshold blocks; what greys out
when. Runs in Blender 3.4 (run_in_blender.py) and under the bpy 5.0 wheel; the real UI's
drawing of the same panels is tests/ui/test_panels_ui.py.
"""

from __future__ import annotations

from typing import Any

import bpy
import pytest
from stratum import blender_settings, ui
from stratum.engine.frame import renderer_settings
from stratum.engine.viewport import settings_from_scene

from panel_layout import PanelRecord, draw_panel

CHILDREN = {
    "STRATUM_RENDER_PT_sampling": ["STRATUM_RENDER_PT_sampling_viewport",
                                   "STRATUM_RENDER_PT_sampling_render",
                                   "STRATUM_RENDER_PT_sampling_denoising",
                                   "STRATUM_RENDER_PT_sampling_advanced",
                                   "STRATUM_RENDER_PT_sampling_lights",
                                   "STRATUM_RENDER_PT_sampling_path_guiding"],
    "STRATUM_RENDER_PT_sampling_viewport": ["STRATUM_RENDER_PT_sampling_viewport_split"],
    "STRATUM_RENDER_PT_light_paths": ["STRATUM_RENDER_PT_light_paths_max_bounces",
                                      "STRATUM_RENDER_PT_light_paths_clamping",
                                      "STRATUM_RENDER_PT_light_paths_caustics",
                                      "STRATUM_RENDER_PT_light_paths_roulette",
                                      "STRATUM_RENDER_PT_light_paths_direct_light",
                                      "STRATUM_RENDER_PT_light_paths_control_variate"],
}
# (panel, switch, threshold, samples, min samples) of the two Noise Threshold blocks.
NOISE_THRESHOLDS = [
    ("STRATUM_RENDER_PT_sampling_render", "use_adaptive_sampling", "adaptive_threshold",
     "samples", "adaptive_min_samples"),
    ("STRATUM_RENDER_PT_sampling_viewport", "use_preview_adaptive_sampling",
     "preview_adaptive_threshold", "preview_samples", "preview_adaptive_min_samples"),
]


def _items(name: str) -> list[str]:
    prop = bpy.types.Scene.bl_rna.properties["stratum"].fixed_type.properties[name]
    return [item.identifier for item in prop.enum_items]


def _panel(name: str) -> type:
    return next(cls for cls in ui.classes if cls.__name__ == name)


def _draw_all(scene: Any) -> dict[str, PanelRecord]:
    """Every settings panel's drawing (headers as '<panel>.header')."""
    drawn = {}
    for cls in ui.classes:
        if cls is ui.STRATUM_RENDER_PT_library:
            continue
        if "draw" in vars(cls):
            drawn[cls.__name__] = draw_panel(cls, scene)
        if "draw_header" in vars(cls):
            drawn[f"{cls.__name__}.header"] = draw_panel(cls, scene, header=True)
    return drawn


def test_panels_nest_like_cycles(library: Any) -> None:
    """Subpanels hang where Cycles' do, are registered in the order they are shown (a
    subpanel after its parent), and show for Stratum only."""
    parents = {child: parent for parent, children in CHILDREN.items() for child in children}
    names = [cls.__name__ for cls in ui.classes]
    for cls in ui.classes:
        assert getattr(cls, "bl_parent_id", None) == parents.get(cls.__name__), cls.__name__
        assert hasattr(bpy.types, cls.__name__), cls.__name__
    for parent, children in CHILDREN.items():
        positions = [names.index(child) for child in children]
        assert positions == sorted(positions) and names.index(parent) < positions[0], parent
    context = type("Context", (), {"engine": "STRATUM"})()
    assert all(cls.poll(context) for cls in ui.classes if cls is not ui.STRATUM_RENDER_PT_library)
    context.engine = "CYCLES"
    assert not any(cls.poll(context) for cls in ui.classes)


def test_every_property_is_drawn_once(library: Any, scene_builder: Any) -> None:
    """Every scene.stratum property is in exactly one panel: a setting the library adds to
    blender_settings.PROPERTIES and no panel draws fails here."""
    scene = scene_builder().scene
    drawn = [name for record in _draw_all(scene).values() for name in record.names()]
    expected = (set(blender_settings.PROPERTIES) | set(blender_settings.BLENDER_ONLY)
                | set(blender_settings.VIEWPORT_PROPERTIES) | {"light_paths"})
    assert sorted(drawn) == sorted(expected)


@pytest.mark.parametrize("panel, use, threshold, samples, min_samples", NOISE_THRESHOLDS)
def test_noise_threshold_greys_out_without_adaptive_sampling(
        library: Any, scene_builder: Any, panel: str, use: str, threshold: str, samples: str,
        min_samples: str) -> None:
    """Cycles' block: the checkbox and the threshold under the heading Noise Threshold, the
    sample count read Max Samples while adaptive sampling is on, Min Samples; the threshold
    and Min Samples greyed out while it is off."""
    s = scene_builder().scene.stratum
    assert getattr(s, use) is False  # adaptive sampling is off by default, as in the library
    off = draw_panel(_panel(panel), s.id_data)
    assert "Noise Threshold" in off.headings
    assert off.names()[:4] == [use, threshold, samples, min_samples]
    assert off.prop(use).active and off.prop(use).text == ""
    assert not off.prop(threshold).active and off.prop(threshold).text == ""
    assert off.prop(samples).active and off.prop(samples).text == "Samples"
    assert not off.prop(min_samples).active and off.prop(min_samples).text == "Min Samples"
    setattr(s, use, True)
    on = draw_panel(_panel(panel), s.id_data)
    assert all(on.prop(name).active for name in (use, threshold, samples, min_samples))
    assert on.prop(samples).text == "Max Samples"


def test_adaptive_settings_reach_the_library_as_integers(library: Any,
                                                         scene_builder: Any) -> None:
    """use_adaptive_sampling is a checkbox; the engine sends it as the 0/1 the library's
    integer setting takes, and the viewport sends its own adaptive settings instead of F12's."""
    s = scene_builder().basic().scene.stratum
    rna = s.bl_rna.properties
    assert rna["use_adaptive_sampling"].type == "BOOLEAN"
    assert rna["use_preview_adaptive_sampling"].type == "BOOLEAN"
    assert rna["adaptive_threshold"].precision == 4
    s.use_adaptive_sampling, s.adaptive_threshold, s.adaptive_min_samples = True, 0.05, 8
    s.preview_adaptive_threshold, s.preview_adaptive_min_samples = 0.25, 4
    sent = renderer_settings(s.id_data)
    assert type(sent["use_adaptive_sampling"]) is int and sent["use_adaptive_sampling"] == 1
    assert (sent["adaptive_threshold"], sent["adaptive_min_samples"]) == (
        pytest.approx(0.05), 8)
    viewport = settings_from_scene(s.id_data).native
    assert type(viewport["use_adaptive_sampling"]) is int
    assert viewport["use_adaptive_sampling"] == 0  # the viewport's own switch, still off
    assert (viewport["adaptive_threshold"], viewport["adaptive_min_samples"]) == (
        pytest.approx(0.25), 4)
    with library.Renderer(library.Scene()) as renderer:
        for settings in (sent, viewport):
            for name in ("use_adaptive_sampling", "adaptive_threshold", "adaptive_min_samples"):
                renderer.set(name, settings[name])


def test_viewport_adaptive_properties_take_the_library_ranges(library: Any,
                                                              scene_builder: Any) -> None:
    s = scene_builder().scene.stratum
    rna = s.bl_rna.properties
    for name, setting_name in blender_settings.VIEWPORT_SETTINGS.items():
        setting, prop = library.setting(setting_name), rna[name]
        assert getattr(s, name) == pytest.approx(blender_settings.VIEWPORT_DEFAULTS[name]), name
        if prop.type != "BOOLEAN":
            assert (prop.hard_min, prop.hard_max) == pytest.approx(
                (setting.minimum, setting.maximum)), name


def test_split_view_greys_out_when_off(library: Any, scene_builder: Any) -> None:
    s = scene_builder().scene.stratum
    panel = ui.STRATUM_RENDER_PT_sampling_viewport_split
    assert draw_panel(panel, s.id_data, header=True).names() == ["use_split_view"]
    assert not any(p.active for p in draw_panel(panel, s.id_data).props)
    s.use_split_view = True
    assert all(p.active for p in draw_panel(panel, s.id_data).props)


def test_light_selection_is_drawn_for_each_of_its_choices(library: Any,
                                                          scene_builder: Any) -> None:
    """Sampling > Lights draws whatever choices the library lists (a new one needs no UI
    change), greyed out only for ambient occlusion, which samples no lights; the tree's splits
    also where the choice is no tree."""
    s = scene_builder().scene.stratum
    for choice in _items("light_selection"):
        s.light_selection = choice
        for integrator in _items("integrator"):
            s.integrator = integrator
            drawn = draw_panel(ui.STRATUM_RENDER_PT_sampling_lights, s.id_data)
            assert drawn.prop("light_selection").active == (integrator != "ao")
            # Tree Splits sits under it, greyed out where no tree chooses the lights.
            assert drawn.prop("light_tree_splits").active == (
                integrator != "ao" and choice in ("tree", "auto"))


def _active(records: dict[str, PanelRecord]) -> dict[str, bool]:
    return {p.name: p.active for record in records.values() for p in record.props}


def test_light_paths_grey_out_what_an_integrator_does_not_use(library: Any,
                                                              scene_builder: Any) -> None:
    """Every option stays in its place and is active only where it changes the estimator:
    ambient occlusion traces no light paths; `direct` is the path tracer with max_bounces 0;
    radiosity's settings are its own, and its final gather takes a light sample (triangle
    sampling) but traces no paths (no bounces, roulette, strategy or control variate);
    light sampling, its heuristic and the control variate are path-tracer choices; the
    heuristic only weighs MIS's two strategies; the minimum depth matters while roulette is
    on. The native registry decides which integrators exist."""
    s = scene_builder().scene.stratum
    panels = ["STRATUM_RENDER_PT_light_paths", *CHILDREN["STRATUM_RENDER_PT_light_paths"]]
    for integrator in _items("integrator"):
        for light_sampling in _items("light_sampling"):
            for rr_mode in _items("rr_mode"):
                s.integrator, s.light_sampling, s.rr_mode = integrator, light_sampling, rr_mode
                active = _active({p: draw_panel(_panel(p), s.id_data) for p in panels})
                paths = integrator not in ("ao", "radiosity")
                path_tracer = integrator not in ("ao", "light", "radiosity")
                radiosity = integrator == "radiosity"
                assert active == {
                    "integrator": True,
                    "ao_distance": integrator == "ao",
                    "radiosity_patch_size": radiosity,
                    "radiosity_solver": radiosity,
                    "radiosity_tolerance": radiosity,
                    "radiosity_rays": radiosity,
                    "light_paths": True,
                    "max_bounces": integrator not in ("ao", "direct", "radiosity"),
                    "diffuse_bounces": integrator not in ("ao", "direct", "radiosity"),
                    "glossy_bounces": integrator not in ("ao", "direct", "radiosity"),
                    "transmission_bounces": integrator not in ("ao", "direct", "radiosity"),
                    "transparent_max_bounces": paths,
                    "clamp_direct": paths,
                    "clamp_indirect": paths,
                    # Filter Glossy and caustics change a camera path by what it did before:
                    # the path tracer's (a particle cannot know; `direct` has no second hit).
                    "filter_glossy": integrator not in ("ao", "direct", "radiosity", "light"),
                    "caustics_reflective": integrator not in ("ao", "direct", "radiosity", "light"),
                    "caustics_refractive": integrator not in ("ao", "direct", "radiosity", "light"),
                    "rr_mode": paths,
                    "rr_min_depth": paths and rr_mode != "off",
                    "light_sampling": path_tracer,
                    "mis_heuristic": path_tracer and light_sampling == "mis",
                    "triangle_sampling": (path_tracer and light_sampling != "bsdf") or radiosity,
                    "control_variate": path_tracer,
                }, (integrator, light_sampling, rr_mode)


def test_advanced_holds_the_pattern_seed_and_hemisphere(library: Any,
                                                        scene_builder: Any) -> None:
    drawn = draw_panel(ui.STRATUM_RENDER_PT_sampling_advanced, scene_builder().scene)
    assert [(p.name, p.text) for p in drawn.props] == [
        ("sampler", "Pattern"), ("seed", "Seed"), ("hemisphere", "Hemisphere")]


def test_path_guiding_is_the_path_tracers_and_greys_out_when_off(library: Any,
                                                                 scene_builder: Any) -> None:
    """Sampling > Path Guiding (Cycles' place for it): the switch in its header, active for the
    path tracer only; training samples and BSDF fraction active while it is on (issue 17,
    acceptance 6). The settings reach the library under their registry names."""
    s = scene_builder().scene.stratum
    panel = ui.STRATUM_RENDER_PT_sampling_path_guiding
    assert draw_panel(panel, s.id_data, header=True).names() == ["use_guiding"]
    assert draw_panel(panel, s.id_data).names() == ["guiding_training_samples",
                                                   "guiding_bsdf_fraction", "guiding_split"]
    for integrator in _items("integrator"):
        for use in (False, True):
            s.integrator, s.use_guiding = integrator, use
            header = draw_panel(panel, s.id_data, header=True)
            assert header.prop("use_guiding").active == (integrator == "path"), integrator
            drawn = draw_panel(panel, s.id_data)
            assert all(p.active == (integrator == "path" and use) for p in drawn.props), integrator
    s.integrator, s.use_guiding = "path", True
    s.guiding_training_samples, s.guiding_bsdf_fraction = 16, 0.25
    settings = dict(renderer_settings(s.id_data))
    assert settings["use_guiding"] == 1
    assert settings["guiding_training_samples"] == 16
    assert settings["guiding_bsdf_fraction"] == pytest.approx(0.25)
