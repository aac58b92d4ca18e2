"""The library's list of render settings and what is built from it: where each setting comes
from in Blender (stratum/blender_settings.py)."""

from __future__ import annotations

from typing import Any

from stratum import blender_settings


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
