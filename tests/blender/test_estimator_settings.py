"""The estimator settings of issue 6 in Blender: scene.stratum.light_sampling, mis_heuristic,
light_selection, triangle_sampling, rr_mode, rr_min_depth, control_variate; the renderer's notices as WARNING
reports. Runs in Blender 3.4 (run_in_blender.py) and under the bpy 5.0.1 wheel.

The enum items are the library's choices (properties.py builds them from native.settings()):
every item of every enum property is sent through the engine's settings to a native renderer,
which rejects unknown values (with a message naming them, checked below), so an item the engine
could not render with fails here.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest
from stratum import native
from stratum.engine import StratumRenderEngine, final_render, frame

from conftest import engine_reports, render_still

ENUMS = ("light_sampling", "mis_heuristic", "light_selection", "triangle_sampling", "rr_mode")
DEFAULTS = {"light_sampling": "mis", "mis_heuristic": "power", "light_selection": "auto",
            "triangle_sampling": "solid_angle", "rr_mode": "throughput", "rr_min_depth": 3,
            "control_variate": 0.0}
# Values per enum, as the library lists them (native/src/integrators/estimator_options.cpp).
ENUM_SIZES = {"triangle_sampling": 2, "light_selection": 5}
# Defaults appended after the menu's other items (a .blend stores an item's position, so the
# older items keep theirs): light_selection's auto (issue 16).
APPENDED_DEFAULTS = ("light_selection",)


def _enum_identifiers(name: str) -> list[str]:
    prop = bpy.types.Scene.bl_rna.properties["stratum"].fixed_type.properties[name]
    return [item.identifier for item in prop.enum_items]


def test_properties_exist_with_the_contract_defaults(library: Any, scene_builder: Any) -> None:
    s = scene_builder().scene.stratum
    for name, value in DEFAULTS.items():
        assert getattr(s, name) == value, name
    rna = type(s).bl_rna.properties
    assert (rna["rr_min_depth"].hard_min, rna["rr_min_depth"].hard_max) == (0, 1024)
    assert rna["control_variate"].hard_min == 0.0
    # The first item of each menu is the native default (the contract's "first value"), but
    # for a default appended later, the last.
    for name in ENUMS:
        position = -1 if name in APPENDED_DEFAULTS else 0
        assert _enum_identifiers(name)[position] == DEFAULTS[name], name


@pytest.mark.parametrize("name", ENUMS)
def test_every_enum_item_is_accepted_by_the_native_renderer(library: Any, scene_builder: Any,
                                                            name: str) -> None:
    """Each item goes the engine's way (scene.stratum -> renderer_settings -> Renderer.set)."""
    b = scene_builder()
    items = _enum_identifiers(name)
    assert len(items) == ENUM_SIZES.get(name, 3), items
    with native.Scene() as scene:
        for item in items:
            setattr(b.scene.stratum, name, item)
            settings = frame.renderer_settings(b.scene)
            assert settings[name] == item
            with native.Renderer(scene, **settings):
                pass  # every setting accepted (StratumError otherwise)


def test_numeric_settings_reach_the_renderer(library: Any, scene_builder: Any) -> None:
    b = scene_builder()
    b.scene.stratum.rr_min_depth = 1024
    b.scene.stratum.control_variate = 0.25
    settings = frame.renderer_settings(b.scene)
    assert settings["rr_min_depth"] == 1024 and isinstance(settings["rr_min_depth"], int)
    assert settings["control_variate"] == 0.25 and isinstance(settings["control_variate"], float)
    with native.Scene() as scene, native.Renderer(scene, **settings):
        pass


@pytest.mark.parametrize(("name", "bad"), [
    ("light_sampling", "bsdf_only"), ("mis_heuristic", "cube"), ("light_selection", "random"),
    ("triangle_sampling", "spherical"), ("rr_mode", "russian"), ("rr_min_depth", -1),
    ("rr_min_depth", 1025), ("control_variate", -0.5), ("control_variate", math.inf),
])
def test_bad_native_values_are_rejected_naming_them(library: Any, name: str, bad: Any) -> None:
    with (native.Scene() as scene, native.Renderer(scene) as renderer,
          pytest.raises(native.StratumError) as excinfo):
        renderer.set(name, bad)
    message = str(excinfo.value)
    assert name in message and str(bad) in message, message


def test_a_rejected_value_is_an_error_report_not_an_exception(
        library: Any, scene_builder: Any, monkeypatch: Any, tmp_path: Path) -> None:
    """RNA keeps the properties valid; should a value still be rejected natively (a library
    older than the add-on), the engine reports it and the render ends cleanly."""
    b = scene_builder().basic()
    original = frame.renderer_settings
    monkeypatch.setattr(final_render, "renderer_settings",
                        lambda scene: original(scene) | {"rr_mode": "no_such_mode"})
    render_still(b.scene, tmp_path / "rejected.exr")
    errors = engine_reports("ERROR")
    assert len(errors) == 1 and "no_such_mode" in errors[0], StratumRenderEngine.last_reports


def _point_lit_scene(b: Any) -> Any:
    """A cube lit only by a point light of radius 0 (nothing a ray can hit), black world."""
    b.camera()
    b.mesh_object("Cube")
    light = b.point_light()
    light.data.shadow_soft_size = 0.0
    b.world((0.0, 0.0, 0.0))
    b.set_resolution(16, 16)
    b.scene.stratum.samples = 4
    b.scene.stratum.max_bounces = 2
    return b.scene


def test_bsdf_sampling_of_a_point_light_warns_and_renders_black(
        library: Any, scene_builder: Any, tmp_path: Path) -> None:
    """BSDF sampling alone never finds a point light: the renderer's notice becomes a WARNING
    report saying why, and the render finishes (black: that light is all there is)."""
    scene = _point_lit_scene(scene_builder())
    scene.stratum.light_sampling = "bsdf"
    pixels = render_still(scene, tmp_path / "bsdf.exr")
    assert not engine_reports("ERROR"), StratumRenderEngine.last_reports
    warnings = [m for m in engine_reports("WARNING") if m.startswith("Stratum: ")]
    assert warnings, f"no notice reported: {StratumRenderEngine.last_reports}"
    assert any("point" in m.lower() for m in warnings), warnings
    assert pixels is not None and pixels.shape[:2] == (16, 16)
    assert np.isfinite(pixels).all() and pixels[..., :3].max() == 0.0


@pytest.mark.parametrize("light_sampling", ["mis", "nee"])
def test_strategies_that_sample_the_point_light_have_no_notice(
        library: Any, scene_builder: Any, tmp_path: Path, light_sampling: str) -> None:
    scene = _point_lit_scene(scene_builder())
    scene.stratum.light_sampling = light_sampling
    pixels = render_still(scene, tmp_path / f"{light_sampling}.exr")
    assert StratumRenderEngine.last_reports == []
    assert pixels is not None and pixels[..., :3].max() > 0.0
