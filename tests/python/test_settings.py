"""The library's list of render settings and what is built from it: where each setting comes
from in Blender (stratum/blender_settings.py) and the README's settings tables
(scripts/settings_table.py)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from stratum import blender_settings

REPO = Path(__file__).resolve().parents[2]


def _settings_table() -> Any:
    from scripts import settings_table

    return settings_table


def test_every_setting_has_a_place_in_blender(native: Any) -> None:
    """Each setting the library lists is a scene.stratum property, taken from Blender's own
    render settings, or explicitly not set from Blender: a new library setting fails here
    until it is placed in stratum/blender_settings.py."""
    places = {"PROPERTIES": set(blender_settings.PROPERTIES),
              "FROM_BLENDER": set(blender_settings.FROM_BLENDER),
              "NOT_IN_BLENDER": set(blender_settings.NOT_IN_BLENDER)}
    names = [s.name for s in native.settings()]
    unplaced = [name for name in names if not any(name in place for place in places.values())]
    assert not unplaced, (f"settings with no place in Blender: {unplaced}; add each to one of "
                          "PROPERTIES, FROM_BLENDER or NOT_IN_BLENDER in stratum/blender_settings.py")
    for place, members in places.items():
        assert members <= set(names), f"{place} names settings the library does not list: " \
            f"{sorted(members - set(names))}"
        for other, others in places.items():
            assert place == other or not members & others, f"in {place} and {other}: " \
                f"{sorted(members & others)}"
    assert len(set(blender_settings.PROPERTIES)) == len(blender_settings.PROPERTIES)


def test_properties_are_settings_blender_can_hold(native: Any) -> None:
    """A property is an int, float or enum (a LIST setting has no Blender property), and a UI
    default is a property's and a value its setting accepts."""
    for name in blender_settings.PROPERTIES:
        assert native.setting(name).kind != native.SettingKind.LIST, name
    for name, default in blender_settings.UI_DEFAULTS.items():
        setting = native.setting(name)
        assert name in blender_settings.PROPERTIES, name
        assert setting.default != default, f"{name}: the UI default is the library's; drop it"
        if setting.choices:
            assert default in setting.choice_names(), name
        else:
            assert type(default) is type(setting.default), name
            assert setting.minimum <= default <= setting.maximum, name


def test_readme_tables_are_what_the_script_writes(native: Any) -> None:
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    assert readme == _settings_table().with_tables(readme), (
        "README.md's settings tables differ from the library's settings: run "
        "`.venv/bin/python -m scripts.settings_table`")


def test_the_tables_name_every_setting_choice_and_pass(native: Any) -> None:
    """Guards the check above against a script that writes too little."""
    text = _settings_table().settings_markdown()
    for setting in native.settings():
        assert f"| `{setting.name}` | {setting.description}" in text, setting.name
        for choice in setting.choices:
            assert f"`{choice.name}`" in text, (setting.name, choice.name)
    for render_pass in native.passes():
        assert f"| `{render_pass.name}` | {render_pass.channels} |" in text


def test_the_script_refuses_a_readme_without_markers(native: Any) -> None:
    with pytest.raises(ValueError, match="settings:begin"):
        _settings_table().with_tables("# A README without the markers\n")


def _int_setting(native: Any, name: str, minimum: int, maximum: int) -> Any:
    return native.Setting(name=name, label="", description="", kind=native.SettingKind.INT,
                          minimum=minimum, maximum=maximum, open_minimum=False, unit="",
                          default=0, choices=())


def test_switches_are_use_settings_of_range_0_to_1(native: Any) -> None:
    """The rule that makes a setting a checkbox in Blender: an integer named use_* that takes
    0 or 1; film_transparent (0/1, not use_*) comes from Blender's own checkbox and stays an
    integer setting, and a use_* setting of a wider range is a number."""
    assert blender_settings.is_switch(native.setting("use_adaptive_sampling"))
    # Cycles' caustics checkboxes, named without use_.
    assert blender_settings.is_switch(native.setting("caustics_reflective"))
    assert not blender_settings.is_switch(native.setting("film_transparent"))
    assert not blender_settings.is_switch(native.setting("adaptive_min_samples"))
    assert blender_settings.is_switch(_int_setting(native, "use_x", 0, 1))
    assert not blender_settings.is_switch(_int_setting(native, "use_x", 0, 2))
    assert not blender_settings.is_switch(_int_setting(native, "x", 0, 1))
    switches = [s.name for s in native.settings() if blender_settings.is_switch(s)]
    assert switches and all(name in blender_settings.PROPERTIES for name in switches)


def test_viewport_stand_ins_name_property_settings(native: Any) -> None:
    """Each viewport stand-in (preview_*) replaces a scene.stratum setting in the viewport, has
    a label and a default, and its default is a value its setting takes."""
    for prop, name in blender_settings.VIEWPORT_SETTINGS.items():
        assert name in blender_settings.PROPERTIES, prop
        assert prop in blender_settings.VIEWPORT_PROPERTIES, prop
        setting, default = native.setting(name), blender_settings.VIEWPORT_DEFAULTS[prop]
        if blender_settings.is_switch(setting):
            assert isinstance(default, bool), prop
        else:
            assert type(default) is type(setting.default), prop
            assert setting.minimum <= default <= setting.maximum, prop


def test_the_table_says_which_settings_are_checkboxes(native: Any) -> None:
    text = _settings_table().settings_markdown()
    assert "`scene.stratum.use_adaptive_sampling` (a checkbox)" in text
    assert "`scene.stratum.preview_adaptive_threshold` (default `0.1`)" in text
