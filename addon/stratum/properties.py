"""Scene render settings (`scene.stratum`), built at register time from the library's list of
settings (native.settings()): each property has its setting's name, label, description,
range, choices and default, so the UI and the library cannot disagree. Which settings are
properties, and the few defaults that differ from the library's, are in blender_settings.py;
what only the UI decides (soft limits, subtypes) is here.

A use_* setting of range 0..1 (blender_settings.is_switch) is a checkbox, as Cycles' use_*
switches are; the engine sends it to the library as 0 or 1.

Enum items carry explicit numbers equal to the choice's position in the library's list:
Blender stores an EnumProperty as that number, and the library only appends choices, so a
saved .blend keeps its choice when choices are added.

If the library cannot be loaded, registration still succeeds: scene.stratum then has no
settings (there is nothing to describe them with), the render panels say why, and the engine
reports the load error on render.
"""

from __future__ import annotations

from typing import Any

import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty

from . import native
from .blender_settings import (
    BLENDER_ONLY,
    LIGHT_PATHS_DEFAULT,
    LIGHT_PATHS_SOURCES,
    PROPERTIES,
    UI_DEFAULTS,
    VIEWPORT_DEFAULTS,
    VIEWPORT_PROPERTIES,
    VIEWPORT_SETTINGS,
    is_switch,
)

# Where a slider stops dragging; typing goes on to the library's maximum.
SOFT_MAXIMA: dict[str, int | float] = {
    "samples": 4096,
    "ao_distance": 100.0,
    "filter_width": 10.0,
    "control_variate": 10.0,
    # Cycles' maximum of its Min Samples (adaptive_min_samples)
    "adaptive_min_samples": 4096,
    "guiding_training_samples": 4096,
}
# Decimals a float shows (Blender's default is 3): a noise threshold of 0.0050 should not
# read 0.005 next to Cycles' 4 decimals.
PRECISIONS: dict[str, int] = {
    "adaptive_threshold": 4,
    "radiosity_tolerance": 6,
}
# Blender's ranges include their minimum. Where the library excludes its minimum
# (open_minimum), the UI stops at the smallest value worth offering instead.
OPEN_MINIMUM_FLOORS: dict[str, float] = {
    "ao_distance": 1e-4,
    # Below 1e-7 the solve's ΔE is at the rounding of its double sums (radiosity_system.h).
    "radiosity_tolerance": 1e-7,
}
# Units the UI can display.
UNIT_SUBTYPES: dict[str, str] = {
    "pixels": "PIXEL",
    "scene units": "DISTANCE",
}
# An IntProperty holds a C int and a FloatProperty a float: the library's wider ends (seed up
# to 2^32 - 1, ao_distance up to inf) are cut to what Blender can store.
INT_MAX = 2**31 - 1
FLOAT_MAX = float(np.finfo(np.float32).max)

# Why the library could not be loaded at register time ("" when it could).
load_error: str = ""
_property_group: type | None = None


def _minimum(setting: native.Setting) -> int | float:
    if not setting.open_minimum:
        return setting.minimum
    if setting.name not in OPEN_MINIMUM_FLOORS:
        raise RuntimeError(f"setting {setting.name!r} excludes its minimum {setting.minimum}: "
                           "properties.OPEN_MINIMUM_FLOORS needs the smallest value the UI "
                           "offers")
    return OPEN_MINIMUM_FLOORS[setting.name]


def _float32_range(lo: float, hi: float) -> tuple[float, float]:
    """The float32 values nearest to [lo, hi] inside it: a FloatProperty stores a float, and
    the float nearest to 0.01 (0.0099999998) lies below a library minimum of 0.01, which
    would refuse the property's own minimum."""
    low, high = np.float32(lo), np.float32(hi)
    if float(low) < lo:
        low = np.nextafter(low, np.float32(np.inf))
    if float(high) > hi:
        high = np.nextafter(high, np.float32(-np.inf))
    return float(low), float(high)


def _number_options(setting: native.Setting, largest: int | float) -> dict[str, Any]:
    """Range, soft maximum and subtype of an INT or FLOAT property."""
    lo, hi = _minimum(setting), min(setting.maximum, largest)
    if setting.kind == native.SettingKind.FLOAT:
        lo, hi = _float32_range(lo, hi)
    options: dict[str, Any] = {"min": lo, "max": hi}
    if setting.name in SOFT_MAXIMA:
        options["soft_max"] = SOFT_MAXIMA[setting.name]
    if setting.name in PRECISIONS:
        options["precision"] = PRECISIONS[setting.name]
    if setting.unit in UNIT_SUBTYPES:
        options["subtype"] = UNIT_SUBTYPES[setting.unit]
    return options


def switch_description(description: str) -> str:
    """A 0/1 setting's description says what 1 does ("1: a pixel stops ..."); a checkbox's
    tooltip says it without the "1: "."""
    if not description.startswith("1: "):
        return description
    text = description[len("1: "):]
    return text[:1].upper() + text[1:]


def make_property(setting: native.Setting, label: str | None = None,
                  description: str | None = None, default: Any = None) -> Any:
    """The bpy property of one INT, FLOAT or CHOICE setting (a checkbox for a switch); label,
    description and default replace the library's (and UI_DEFAULTS') when given."""
    if default is None:
        default = UI_DEFAULTS.get(setting.name, setting.default)
    common = {"name": setting.label if label is None else label,
              "description": setting.description if description is None else description,
              "default": default}
    if is_switch(setting):
        if description is None:
            common["description"] = switch_description(setting.description)
        return BoolProperty(**common | {"default": bool(default)})
    if setting.kind == native.SettingKind.INT:
        return IntProperty(**common, **_number_options(setting, INT_MAX))
    if setting.kind == native.SettingKind.FLOAT:
        return FloatProperty(**common, **_number_options(setting, FLOAT_MAX))
    if setting.kind == native.SettingKind.CHOICE:
        items = [(choice.name, choice.label, choice.description, number)
                 for number, choice in enumerate(setting.choices)]
        return EnumProperty(items=items, **common)
    raise ValueError(f"setting {setting.name!r}: a {setting.kind.name} setting has no "
                     "Blender property")


def _update_render_passes(_settings: Any, context: bpy.types.Context) -> None:
    """Denoising adds a pass (Noisy Image): the compositor asks the engine for its passes
    again (engine.update_render_passes), as Cycles' denoising switches do."""
    view_layer = getattr(context, "view_layer", None)
    if view_layer is not None:
        view_layer.update_render_passes()


def _make_property_group(settings: tuple[native.Setting, ...]) -> type:
    by_name = {setting.name: setting for setting in settings}

    class StratumRenderSettings(bpy.types.PropertyGroup):
        __annotations__ = {name: make_property(by_name[name])
                           for name in PROPERTIES if name in by_name}
        # The add-on's own switches need no library (registered without it too).
        __annotations__.update({
            name: BoolProperty(name=label, description=description, default=default,
                               update=_update_render_passes)
            for name, (label, description, default) in BLENDER_ONLY.items()})
        __annotations__.update(_viewport_properties(by_name))
        __annotations__["light_paths"] = EnumProperty(
            name="Settings", description="Where the Light Paths settings (bounces per kind, "
            "clamping) come from", default=LIGHT_PATHS_DEFAULT,
            items=[(*item, number) for number, item in enumerate(LIGHT_PATHS_SOURCES)])

    return StratumRenderSettings


def _viewport_properties(by_name: dict[str, native.Setting]) -> dict[str, Any]:
    """The Rendered viewport's own properties (blender_settings.VIEWPORT_PROPERTIES); none
    without the library, whose sampler list and sample range they use."""
    if "sampler" not in by_name or "samples" not in by_name:
        return {}

    def common(name: str) -> dict[str, Any]:
        label, description = VIEWPORT_PROPERTIES[name]
        return {"name": label, "description": description, "default": VIEWPORT_DEFAULTS[name]}

    samples = by_name["samples"]
    samplers = [(choice.name, choice.label, choice.description, number)
                for number, choice in enumerate(by_name["sampler"].choices)]
    # The viewport's stand-ins for library settings (a library without one has no stand-in).
    stand_ins = {name: make_property(by_name[setting], *VIEWPORT_PROPERTIES[name],
                                     default=VIEWPORT_DEFAULTS[name])
                 for name, setting in VIEWPORT_SETTINGS.items() if setting in by_name}
    return stand_ins | {
        "preview_samples": IntProperty(**common("preview_samples"), min=samples.minimum,
                                       max=min(samples.maximum, INT_MAX),
                                       soft_max=SOFT_MAXIMA["samples"]),
        "preview_start_resolution": IntProperty(**common("preview_start_resolution"), min=0,
                                                max=16384, subtype="PIXEL"),
        "use_split_view": BoolProperty(**common("use_split_view")),
        "compare_sampler": EnumProperty(items=samplers, **common("compare_sampler")),
        "split_position": FloatProperty(**common("split_position"), min=0.0, max=1.0,
                                        subtype="FACTOR"),
    }


def register() -> None:
    global _property_group, load_error
    try:
        settings = native.settings()
        load_error = ""
    except native.StratumError as exc:
        settings = ()
        load_error = str(exc)
    _property_group = _make_property_group(settings)
    bpy.utils.register_class(_property_group)
    bpy.types.Scene.stratum = PointerProperty(type=_property_group, name="Stratum")


def unregister() -> None:
    global _property_group
    if hasattr(bpy.types.Scene, "stratum"):
        del bpy.types.Scene.stratum
    if _property_group is not None:
        bpy.utils.unregister_class(_property_group)
        _property_group = None
