"""Blender lights -> native lights.

Units follow what Cycles renders in the running Blender (docs/cycles_models.md, measured):
point power P has intensity P/(4π) (a spot's too, on its axis; its cone falloff gains a factor
cos θ in Cycles 3.x), sun strength is irradiance, and an area light of power P
and area A has radiance P/(πA) in Cycles 4.x/5.x but P/(4A) in Cycles 3.x. The native library
implements the physical P/(πA), so a 3.x area light's power is scaled by π/4.
"""

from __future__ import annotations

import math
from typing import Any

import bpy
import numpy as np

from .. import native
from .common import ExportSummary, matrix_to_array, rgb

# Object > Visibility > Ray Visibility (Object properties in Blender 3.0+, lights too).
_RAY_VISIBILITY = (
    ("visible_camera", native.VISIBLE_CAMERA),
    ("visible_diffuse", native.VISIBLE_DIFFUSE),
    ("visible_glossy", native.VISIBLE_GLOSSY),
    ("visible_transmission", native.VISIBLE_TRANSMISSION),
    ("visible_shadow", native.VISIBLE_SHADOW),
)
# Cycles' spread is (0, pi]; 5.x lets it reach 0 (3.x stops at 1 degree), the native side reads
# 0 as pi, so a 0 is sent as this smallest positive spread.
MIN_SPREAD = 1e-3


def object_visibility(ob: Any) -> int:
    """StratumVisibility bits of an object's ray visibility."""
    bits = 0
    for attr, bit in _RAY_VISIBILITY:
        if getattr(ob, attr, True):
            bits |= bit
    return bits


def cast_shadow(light: Any) -> bool:
    """Light > Cast Shadow: Cycles 3.x reads light.cycles.cast_shadow, 4.x+ light.use_shadow."""
    if bpy.app.version < (4, 0, 0):
        cycles = getattr(light, "cycles", None)
        if cycles is not None and hasattr(cycles, "cast_shadow"):
            return bool(cycles.cast_shadow)
    return bool(getattr(light, "use_shadow", True))


def convert_light(ob: Any, matrix_world: Any, visibility: int,
                  summary: ExportSummary) -> native.Light | None:
    """A native light, or None (skipped: with a warning when it cannot be rendered)."""
    light = ob.data
    if not cast_shadow(light):
        visibility &= ~native.VISIBLE_SHADOW
    if visibility & ~native.VISIBLE_SHADOW == 0:
        return None  # seen by no ray: contributes nothing (native 0 would mean "all")
    color = rgb(light.color)
    transform = matrix_to_array(matrix_world)
    kind = light.type
    power = float(light.energy) * _exposure_scale(light)
    if kind in ("POINT", "SPOT") and light.shadow_soft_size > 0.0 and not getattr(
            light, "use_soft_falloff", True):
        # Cycles 4.1+ with Soft Falloff off draws a radius as a uniform sphere; Stratum has
        # only the facing disk of Soft Falloff on (and of Cycles 3.x).
        summary.warn(f"Light '{ob.name}': 'Soft Falloff' off is not supported "
                     "(rendered as with Soft Falloff on)")
    if kind == "POINT":
        return native.Light(type=native.LIGHT_POINT, color=color, strength=power,
                            radius=max(float(light.shadow_soft_size), 0.0), transform=transform,
                            visibility=visibility)
    if kind == "SPOT":
        # Cycles 3.x multiplies the spot falloff by cos(angle to the axis), 4.x+ does not.
        spot_type = native.LIGHT_SPOT_V1 if bpy.app.version < (4, 0, 0) else native.LIGHT_SPOT
        return native.Light(type=spot_type, color=color, strength=power,
                            radius=max(float(light.shadow_soft_size), 0.0), transform=transform,
                            spot_size=float(light.spot_size), spot_blend=float(light.spot_blend),
                            visibility=visibility)
    if kind == "SUN":
        return native.Light(type=native.LIGHT_SUN, color=color, strength=power,
                            angle=float(light.angle), transform=transform,
                            visibility=visibility)
    if kind == "AREA":
        if not getattr(light, "normalize", True):
            summary.warn(f"Light '{ob.name}': 'Normalize' off is not supported "
                         "(rendered normalized)")
        shape = light.shape
        size_x = float(light.size)
        size_y = float(light.size_y) if shape in {"RECTANGLE", "ELLIPSE"} else size_x
        light_type = (native.LIGHT_AREA_RECTANGLE if shape in {"SQUARE", "RECTANGLE"}
                      else native.LIGHT_AREA_ELLIPSE)
        scale = np.linalg.norm(np.asarray(transform).reshape(4, 4)[:3, :2], axis=0)
        if not (size_x * scale[0] > 0.0 and size_y * scale[1] > 0.0):
            summary.warn(f"Light '{ob.name}': area light of size {size_x:g} x {size_y:g} "
                         "(with the object's scale) has no area and emits nothing (skipped)")
            return None
        if bpy.app.version < (4, 0, 0):
            power *= math.pi / 4.0
        return native.Light(type=light_type, color=color, strength=power,
                            size_x=size_x, size_y=size_y, transform=transform,
                            visibility=visibility,
                            spread=max(float(getattr(light, "spread", math.pi)), MIN_SPREAD))
    summary.warn(f"Light '{ob.name}': type {kind} is not supported (skipped)")
    return None


def _exposure_scale(light: Any) -> float:
    """Blender 4.x lights have an exposure: the power is multiplied by 2^exposure."""
    return 2.0 ** float(getattr(light, "exposure", 0.0))
