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

from .. import native
from .common import ExportSummary, matrix_to_array, rgb


def convert_light(ob: Any, matrix_world: Any, summary: ExportSummary) -> native.Light | None:
    light = ob.data
    color = rgb(light.color)
    transform = matrix_to_array(matrix_world)
    kind = light.type
    power = float(light.energy) * _exposure_scale(light)
    if kind == "POINT":
        return native.Light(type=native.LIGHT_POINT, color=color, strength=power,
                            radius=max(float(light.shadow_soft_size), 0.0), transform=transform)
    if kind == "SPOT":
        # Cycles 3.x multiplies the spot falloff by cos(angle to the axis), 4.x+ does not.
        spot_type = native.LIGHT_SPOT_V1 if bpy.app.version < (4, 0, 0) else native.LIGHT_SPOT
        return native.Light(type=spot_type, color=color, strength=power,
                            radius=max(float(light.shadow_soft_size), 0.0), transform=transform,
                            spot_size=float(light.spot_size), spot_blend=float(light.spot_blend))
    if kind == "SUN":
        return native.Light(type=native.LIGHT_SUN, color=color, strength=power,
                            angle=float(light.angle), transform=transform)
    if kind == "AREA":
        if not getattr(light, "normalize", True):
            summary.warn(f"Light '{ob.name}': 'Normalize' off is not supported "
                         "(rendered normalized)")
        shape = light.shape
        size_x = float(light.size)
        size_y = float(light.size_y) if shape in {"RECTANGLE", "ELLIPSE"} else size_x
        light_type = (native.LIGHT_AREA_RECTANGLE if shape in {"SQUARE", "RECTANGLE"}
                      else native.LIGHT_AREA_ELLIPSE)
        if bpy.app.version < (4, 0, 0):
            power *= math.pi / 4.0
        return native.Light(type=light_type, color=color, strength=power,
                            size_x=size_x, size_y=size_y, transform=transform)
    summary.warn(f"Light '{ob.name}': type {kind} is not supported (skipped)")
    return None


def _exposure_scale(light: Any) -> float:
    """Blender 4.x lights have an exposure: the power is multiplied by 2^exposure."""
    return 2.0 ** float(getattr(light, "exposure", 0.0))
