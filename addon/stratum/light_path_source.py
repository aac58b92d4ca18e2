"""The Light Paths settings a scene renders with: Stratum's own (scene.stratum) or Cycles'
(scene.cycles), as scene.stratum.light_paths decides (blender_settings.LIGHT_PATHS_SOURCES)."""

from __future__ import annotations

from typing import Any

from . import blender_settings


def uses_cycles_light_paths(scene: Any) -> bool:
    """Whether the scene renders with Cycles' Light Paths settings."""
    cycles = getattr(scene, "cycles", None)
    names = blender_settings.CYCLES_LIGHT_PATHS.values()
    available = cycles is not None and all(hasattr(cycles, name) for name in names)
    tuned = available and any(cycles.is_property_set(name) for name in names)
    return blender_settings.light_paths_from_cycles(scene.stratum.light_paths, available, tuned)


def cycles_light_paths(scene: Any) -> dict[str, int | float]:
    """Cycles' Light Paths values under the library's setting names (empty when the scene
    renders with Stratum's own)."""
    if not uses_cycles_light_paths(scene):
        return {}
    values = {setting: getattr(scene.cycles, name)
              for setting, name in blender_settings.CYCLES_LIGHT_PATHS.items()}
    # Cycles' caustics checkboxes: the library's 0..1 integer settings.
    return {setting: int(value) if isinstance(value, bool) else value
            for setting, value in values.items()}


def light_path_holder(scene: Any, name: str) -> tuple[Any, str]:
    """Where the value of setting `name` that the scene renders with lives: (scene.cycles, its
    Cycles name) for a Light Paths setting taken from Cycles, else (scene.stratum, name). What
    the panels draw and what `stratum render`'s options set, so that a change shows."""
    if name in blender_settings.CYCLES_LIGHT_PATHS and uses_cycles_light_paths(scene):
        return scene.cycles, blender_settings.CYCLES_LIGHT_PATHS[name]
    return scene.stratum, name
