"""Registration: engine, properties, panels (Blender 3.4 and the bpy 5.0 wheel)."""

from __future__ import annotations

from typing import Any

import bpy
import pytest

from conftest import engine_reports

EXPECTED_PROPERTIES = {
    "samples": 64,
    "max_bounces": 12,
    "seed": 0,
    "filter_type": "blackman_harris",
    "filter_width": 1.5,
    "threads": 0,
    "hemisphere": "cosine",
    "integrator": "path",
    "ao_distance": 1.0,
}
# Menus built from native registries: property name -> registry kind.
REGISTRY_MENUS = {
    "sampler": "sampler",
    "hemisphere": "hemisphere",
    "integrator": "integrator",
    "filter_type": "filter",
}


def test_engine_in_render_engine_enum(stratum_addon: Any) -> None:
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"  # TypeError if 'STRATUM' were not an enum item
    assert scene.render.engine == "STRATUM"
    engines = {getattr(c, "bl_idname", "") for c in bpy.types.RenderEngine.__subclasses__()}
    assert "STRATUM" in engines
    from stratum.engine import StratumRenderEngine

    assert StratumRenderEngine.bl_label == "Stratum"
    assert StratumRenderEngine.bl_use_postprocess is True
    # Stratum renders material, light and world thumbnails; Material Preview shading is EEVEE's.
    assert StratumRenderEngine.bl_use_preview is True
    assert StratumRenderEngine.bl_use_eevee_viewport is True


def test_properties_defaults_and_limits(stratum_addon: Any) -> None:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    s = bpy.context.scene.stratum
    for name, default in EXPECTED_PROPERTIES.items():
        value = getattr(s, name)
        assert value == pytest.approx(default), name
    props = s.bl_rna.properties
    assert props["samples"].hard_min == 1
    assert props["max_bounces"].hard_min == 0
    assert props["seed"].hard_min == 0
    assert props["threads"].hard_min == 0
    assert props["filter_width"].hard_min == pytest.approx(0.01)
    assert props["filter_width"].hard_max == pytest.approx(100.0)  # the library's range
    assert props["filter_width"].soft_max == pytest.approx(10.0)
    assert props["ao_distance"].hard_min == pytest.approx(1e-4)
    assert props["ao_distance"].subtype == "DISTANCE"
    s.samples = 0  # clamped by the property's min
    assert s.samples == 1


def test_sampler_menu_equals_native_registry(library: Any) -> None:
    items = bpy.types.Scene.bl_rna.properties["stratum"].fixed_type.properties["sampler"]
    entries = library.registry("sampler")
    assert [item.identifier for item in items.enum_items] == [e.name for e in entries]
    descriptions = [item.description for item in items.enum_items]
    assert descriptions == [e.description for e in entries]
    filters = bpy.types.Scene.bl_rna.properties["stratum"].fixed_type.properties["filter_type"]
    assert {i.identifier for i in filters.enum_items} == {e.name for e in library.registry("filter")}


def test_properties_are_the_library_settings(library: Any) -> None:
    """Label, description, default, range and choices of every scene.stratum property are its
    setting's; enum numbers are the choices' positions (what a .blend stores). Only the UI's
    own defaults and Blender's storable range differ."""
    from stratum import blender_settings, properties

    rna = bpy.types.Scene.bl_rna.properties["stratum"].fixed_type.properties
    for name in blender_settings.PROPERTIES:
        setting, prop = library.setting(name), rna[name]
        default = blender_settings.UI_DEFAULTS.get(name, setting.default)
        if blender_settings.is_switch(setting):
            # A checkbox, whose tooltip says what 1 does without the "1: "
            assert prop.type == "BOOLEAN", name
            assert prop.name == setting.label, name
            assert prop.description == properties.switch_description(setting.description)
            assert prop.description[0].isupper() and "1: " not in prop.description, name
            assert prop.default == bool(default), name
            continue
        assert (prop.name, prop.description) == (setting.label, setting.description), name
        if setting.kind == library.SettingKind.CHOICE:
            assert prop.default == default, name
            assert [(i.identifier, i.name, i.description, i.value) for i in prop.enum_items] == [
                (c.name, c.label, c.description, n) for n, c in enumerate(setting.choices)], name
            continue
        largest = properties.INT_MAX if prop.type == "INT" else properties.FLOAT_MAX
        minimum = (properties.OPEN_MINIMUM_FLOORS[name] if setting.open_minimum
                   else setting.minimum)
        assert prop.default == pytest.approx(default), name
        assert prop.hard_min == pytest.approx(minimum), name
        assert prop.hard_max == pytest.approx(min(setting.maximum, largest)), name


def test_the_library_accepts_every_float_property_at_both_ends(library: Any,
                                                               scene_builder: Any) -> None:
    """A FloatProperty stores a float32: its ends, as the property holds them, are values the
    library takes (the float nearest 0.01 lies below it, so filter_width's minimum must be the
    next float up)."""
    s = scene_builder().scene.stratum
    props = s.bl_rna.properties
    names = {setting.name for setting in library.settings()}
    floats = [p.identifier for p in props
              if p.type == "FLOAT" and not p.is_array and p.identifier in names]
    assert "filter_width" in floats
    with library.Renderer(library.Scene()) as renderer:
        for name in floats:
            for end in (props[name].hard_min, props[name].hard_max):
                setattr(s, name, end)
                renderer.set(name, getattr(s, name))


def test_registration_without_the_library(stratum_addon: Any, scene_builder: Any,
                                          monkeypatch: pytest.MonkeyPatch,
                                          tmp_path: Any) -> None:
    """A missing library: registration succeeds with a scene.stratum of no settings, the
    settings panels step aside for one that names the load error, and a render reports it."""
    from types import SimpleNamespace

    from stratum import blender_settings, native, properties, ui

    stratum_addon.unregister()
    try:
        monkeypatch.setattr(native.library, "_lib", None)  # the loaded library is held there
        monkeypatch.setenv("STRATUM_LIBRARY", str(tmp_path / "missing" / "libstratum.so"))
        native.settings.cache_clear()
        stratum_addon.register()
        assert "libstratum.so" in properties.load_error
        scene = scene_builder().basic().scene
        assert not any(hasattr(scene.stratum, name) for name in blender_settings.PROPERTIES)
        context = SimpleNamespace(engine="STRATUM", scene=scene)
        assert ui.STRATUM_RENDER_PT_library.poll(context)  # type: ignore[arg-type]
        assert not ui.STRATUM_RENDER_PT_sampling.poll(context)  # type: ignore[arg-type]
        drawn: list[str] = []
        panel = SimpleNamespace(layout=_RecordingLayout(drawn))
        ui.STRATUM_RENDER_PT_library.draw(panel, context)  # type: ignore[arg-type]
        assert properties.load_error in drawn
        try:
            bpy.ops.render.render()
        except RuntimeError:
            pass
        errors = engine_reports("ERROR")
        assert errors and "libstratum.so" in errors[0]
    finally:
        stratum_addon.unregister()
        monkeypatch.undo()
        native.settings.cache_clear()
        stratum_addon.register()
    assert properties.load_error == ""
    assert hasattr(bpy.context.scene.stratum, "samples")


def test_render_panels_and_reused_panels(stratum_addon: Any) -> None:
    from stratum import ui

    for cls in ui.classes:
        assert cls.COMPAT_ENGINES == {"STRATUM"}
        assert cls.bl_context == "render"
        assert hasattr(bpy.types, cls.__name__)
    for name in ("EEVEE_MATERIAL_PT_context_material", "EEVEE_MATERIAL_PT_surface",
                 "EEVEE_WORLD_PT_surface", "DATA_PT_lens", "DATA_PT_context_light"):
        panel = getattr(bpy.types, name, None)
        if panel is not None:
            assert "STRATUM" in panel.COMPAT_ENGINES, name
    # Cycles-only panels are not borrowed
    for name in dir(bpy.types):
        if name.startswith("CYCLES_"):
            panel = getattr(bpy.types, name)
            assert "STRATUM" not in getattr(panel, "COMPAT_ENGINES", set()), name


def test_unregister_restores_builtin_panels(stratum_addon: Any) -> None:
    from stratum import ui

    surface = bpy.types.EEVEE_MATERIAL_PT_surface
    stratum_addon.unregister()
    try:
        assert "STRATUM" not in surface.COMPAT_ENGINES
        assert not hasattr(bpy.types.Scene, "stratum")
        assert not ui._patched
    finally:
        stratum_addon.register()
    assert "STRATUM" in surface.COMPAT_ENGINES
    assert hasattr(bpy.types.Scene, "stratum")


def _menu(prop: str) -> Any:
    return bpy.types.Scene.bl_rna.properties["stratum"].fixed_type.properties[prop]


@pytest.mark.parametrize("prop", sorted(REGISTRY_MENUS))
def test_menus_equal_native_registries(stratum_addon: Any, prop: str) -> None:
    """Every registry-backed menu lists exactly the registry's names, in order, with the
    registry's labels and descriptions (the tooltips)."""
    from stratum import native

    try:
        entries = native.registry(REGISTRY_MENUS[prop])
    except native.StratumError:
        pytest.skip("native library not available: menus use their fallbacks")
    items = _menu(prop).enum_items
    assert [i.identifier for i in items] == [e.name for e in entries]
    assert [i.name for i in items] == [e.label for e in entries]
    assert [i.description for i in items] == [e.description for e in entries]


@pytest.mark.parametrize("prop", ["sampler", "hemisphere", "integrator"])
def test_every_registry_entry_can_be_chosen(stratum_addon: Any, prop: str) -> None:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    s = bpy.context.scene.stratum
    for item in _menu(prop).enum_items:
        setattr(s, prop, item.identifier)
        assert getattr(s, prop) == item.identifier
    with pytest.raises(TypeError):
        setattr(s, prop, "no_such_entry")


class _RecordingLayout:
    """Stands in for a UILayout: records which properties a panel draws."""

    def __init__(self, drawn: list[str]) -> None:
        self.drawn = drawn
        self.use_property_split = False
        self.use_property_decorate = True
        self.active = True
        self.enabled = True

    def column(self, **_: Any) -> _RecordingLayout:
        return self

    def row(self, **_: Any) -> _RecordingLayout:
        return self

    def prop(self, data: Any, name: str, **_: Any) -> None:
        assert hasattr(data, name), name
        self.drawn.append(name)

    def label(self, text: str = "", **_: Any) -> None:
        self.drawn.append(text)
