"""Blender lights -> native lights."""

from __future__ import annotations

from typing import Any

from .. import native
from .common import ExportSummary, matrix_to_array, rgb


def convert_light(ob: Any, matrix_world: Any, summary: ExportSummary) -> native.Light | None:
    light = ob.data
    color = rgb(light.color)
    transform = matrix_to_array(matrix_world)
    kind = light.type
    if kind in {"POINT", "SPOT"}:
        if kind == "SPOT":
            summary.warn(f"Light '{ob.name}': spot cone ignored (rendered as a point light)")
        return native.Light(type=native.LIGHT_POINT, color=color, strength=float(light.energy),
                            radius=max(float(light.shadow_soft_size), 0.0), transform=transform)
    if kind == "SUN":
        return native.Light(type=native.LIGHT_SUN, color=color, strength=float(light.energy),
                            angle=float(light.angle), transform=transform)
    if kind == "AREA":
        shape = light.shape
        size_x = float(light.size)
        size_y = float(light.size_y) if shape in {"RECTANGLE", "ELLIPSE"} else size_x
        light_type = (native.LIGHT_AREA_RECTANGLE if shape in {"SQUARE", "RECTANGLE"}
                      else native.LIGHT_AREA_ELLIPSE)
        return native.Light(type=light_type, color=color, strength=float(light.energy),
                            size_x=size_x, size_y=size_y, transform=transform)
    summary.warn(f"Light '{ob.name}': type {kind} is not supported (skipped)")
    return None
