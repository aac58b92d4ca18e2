"""The frame a render fills and the native settings it renders with, read from a Blender
scene: output size, border region, film and every scene.stratum property."""

from __future__ import annotations

from typing import Any

from .. import blender_settings
from ..light_path_source import cycles_light_paths


def render_size(scene: Any) -> tuple[int, int]:
    r = scene.render
    scale = r.resolution_percentage / 100.0
    return max(int(r.resolution_x * scale), 1), max(int(r.resolution_y * scale), 1)


def border_region(scene: Any) -> tuple[int, int, int, int] | None:
    """The border (Render Region) in pixels of the frame, bottom-left origin: (x, y, width,
    height), or None without a border. Blender's render pipeline truncates border * size to
    integers (render_init_from_main: disprect = border * winx/winy) and renders, and hands the
    engine, only that region; use_crop_to_border only decides whether Blender pads it back to
    the full frame afterwards."""
    r = scene.render
    if not r.use_border:
        return None
    width, height = render_size(scene)
    x0, x1 = int(r.border_min_x * width), int(r.border_max_x * width)
    y0, y1 = int(r.border_min_y * height), int(r.border_max_y * height)
    if x1 - x0 < 1 or y1 - y0 < 1 or (x0, y0, x1, y1) == (0, 0, width, height):
        return None
    return x0, y0, x1 - x0, y1 - y0


def result_size(scene: Any) -> tuple[int, int]:
    """Size of the render result the engine fills: the border region, or the frame."""
    region = border_region(scene)
    return (region[2], region[3]) if region is not None else render_size(scene)


def renderer_settings(scene: Any) -> dict[str, int | float | str]:
    """Native settings from the output resolution, border and film, and every scene.stratum
    property (blender_settings.py says which setting comes from where), the Light Paths ones
    from Cycles' settings where the scene uses those (light_paths.py); name -> value, the
    Python type selecting set_int / set_float / set_string (a checkbox's bool as 0 or 1).
    The border and film settings are only sent when used, so a library without them still
    renders every other scene."""
    s = scene.stratum
    width, height = render_size(scene)
    extra: dict[str, int | float | str] = {}
    region = border_region(scene)
    if region is not None:
        extra.update(zip(("crop_x", "crop_y", "crop_width", "crop_height"), region, strict=True))
    if scene.render.film_transparent:
        extra["film_transparent"] = 1
    chosen = {name: library_value(getattr(s, name)) for name in blender_settings.PROPERTIES}
    return {"width": width, "height": height} | chosen | cycles_light_paths(scene) | extra


def layer_samples(scene: Any, view_layer: Any | None, samples: int) -> int:
    """The samples an F12 render of `view_layer` takes, Cycles' rule (blender/sync.cpp
    sync_view_layer, session.cpp): the layer's own (View Layer > Use > Samples, 0 = none) unless
    scene.cycles.use_layer_samples is 'IGNORE'; with 'BOUNDED' only when fewer than `samples`.
    Blender's own setting read as Cycles reads it, whatever scene.stratum.light_paths says; the
    viewport takes its own samples (viewport.py)."""
    own = int(getattr(view_layer, "samples", 0) or 0)
    mode = str(getattr(getattr(scene, "cycles", None), "use_layer_samples", "USE"))
    if own <= 0 or mode == "IGNORE" or (mode == "BOUNDED" and own >= samples):
        return samples
    return own


def library_value(value: Any) -> int | float | str:
    """A property's value as the library takes it: a checkbox (blender_settings.is_switch) as
    0 or 1, the integer setting it is; anything else as it is."""
    return int(value) if isinstance(value, bool) else value
