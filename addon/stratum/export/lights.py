"""Blender lights -> native lights.

Units follow what Cycles renders in the running Blender (docs/cycles_models.md, measured):
point power P has intensity P/(4π) (a spot's too, on its axis; its cone falloff gains a factor
cos θ in Cycles 3.x), sun strength is irradiance, and an area light of power P
and area A has radiance P/(πA) in Cycles 4.x/5.x but P/(4A) in Cycles 3.x. The native library
implements the physical P/(πA), so a 3.x area light's power is scaled by π/4.

Invalid values (docs/invalid_values.md): a NaN or infinite power, exposure,
radius, spot size, blend, angle, size or spread makes every sample of the light non-finite in
Cycles, whose film drops such samples (ensure_finite), so the light renders as nothing; here it
is skipped, with a warning naming the field. A negative power (Cycles subtracts light) cannot
be rendered: skipped too. A NaN colour component is 0 (Cycles' film zeroes it per channel);
a power beyond the largest float is limited to it. A NaN or infinite transform is an error
naming the light, as for objects.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import bpy
import numpy as np

from .. import blender_versions, native
from ..shaders.fallbacks import FLT_MAX, NON_NEGATIVE, clamp_rgb
from .common import ExportError, ExportSummary, comparable, matrix_to_array, rgb
from .light_nodes import LampProgram, Rgb, node_emission
from .placement import first_non_finite

# Object > Visibility > Ray Visibility (Object properties in Blender 3.0+, lights too).
_RAY_VISIBILITY = (
    ("visible_camera", native.VISIBLE_CAMERA),
    ("visible_diffuse", native.VISIBLE_DIFFUSE),
    ("visible_glossy", native.VISIBLE_GLOSSY),
    ("visible_transmission", native.VISIBLE_TRANSMISSION),
    ("visible_shadow", native.VISIBLE_SHADOW),
)
# Fields each light type reads, beyond energy and exposure (all: colour).
_SHAPE_FIELDS = {
    "POINT": ("shadow_soft_size",),
    "SPOT": ("shadow_soft_size", "spot_size", "spot_blend"),
    "SUN": ("angle",),
    "AREA": ("size", "spread"),
}
# Cycles' spread is (0, pi]; 5.x lets it reach 0 (3.x stops at 1 degree), the native side reads
# 0 as pi, so a 0 is sent as this smallest positive spread.
MIN_SPREAD = 1e-3


def object_visibility(ob: Any) -> int:
    """StratumVisibility bits of an object's ray visibility, and VISIBLE_SHADOW_CATCHER for
    Object > Visibility > Shadow Catcher (on a light: it lights shadow catchers, Blender's
    default)."""
    bits = 0
    for attr, bit in _RAY_VISIBILITY:
        if getattr(ob, attr, True):
            bits |= bit
    if getattr(ob, "is_shadow_catcher", False):
        bits |= native.VISIBLE_SHADOW_CATCHER
    return bits


def cast_shadow(light: Any) -> bool:
    """Light > Cast Shadow: Cycles 3.x reads light.cycles.cast_shadow, 4.x+ light.use_shadow."""
    if blender_versions.cast_shadow_in_cycles_settings(bpy.app.version):
        cycles = getattr(light, "cycles", None)
        if cycles is not None and hasattr(cycles, "cast_shadow"):
            return bool(cycles.cast_shadow)
    return bool(getattr(light, "use_shadow", True))


@dataclass(frozen=True)
class ConvertedLight:
    """A native light, and the program that scales its emission by the distance to it when its
    node tree reads that (a Light Falloff; light_nodes.py), else None."""

    light: native.Light
    program: LampProgram | None = None

    def key(self) -> tuple[Any, ...]:
        """Equal exactly when the two send the same values."""
        return (comparable(self.light),
                self.program.key() if self.program is not None else None)


def convert_light(ob: Any, matrix_world: Any, visibility: int,
                  summary: ExportSummary, lightgroup: int = 0) -> ConvertedLight | None:
    """A native light (in native light group `lightgroup`) and its program, or None (skipped:
    with a warning when it cannot be rendered)."""
    light = ob.data
    if not cast_shadow(light):
        visibility &= ~native.VISIBLE_SHADOW
    if visibility & native.VISIBLE_ALL & ~native.VISIBLE_SHADOW == 0:
        return None  # seen by no ray: contributes nothing (native 0 would mean "all")
    kind = light.type
    reason = _unrenderable(light, kind)
    if reason is not None:
        summary.warn(f"Light '{ob.name}': {reason}; the light is skipped")
        return None
    color, problem = clamp_rgb(rgb(light.color), NON_NEGATIVE)
    if problem is not None:
        summary.warn(f"Light '{ob.name}': 'color' {problem}")
    factor = node_emission(ob, summary)
    program = None
    if isinstance(factor, LampProgram):
        program = factor  # the renderer scales the emission; the colour stays the lamp's own
    elif factor is not None:
        color = (min(color[0] * factor[0], FLT_MAX), min(color[1] * factor[1], FLT_MAX),
                 min(color[2] * factor[2], FLT_MAX))
    native_light = _native_light(ob, matrix_world, visibility, color, summary)
    if native_light is None:
        return None
    native_light.lightgroup = lightgroup
    return ConvertedLight(native_light, program)


def _native_light(ob: Any, matrix_world: Any, visibility: int, color: Rgb,
                  summary: ExportSummary) -> native.Light | None:
    """The native light of `ob` with `color` (its nodes' factor folded in), or None."""
    light = ob.data
    kind = light.type
    transform = matrix_to_array(matrix_world)
    bad = first_non_finite(transform)
    if bad is not None:  # as for objects (an area light's would read as "no area" below)
        raise ExportError(f"Light '{ob.name}': transform element {bad[0]} = {bad[1]:g} is not "
                          "finite")
    power = float(light.energy) * _exposure_scale(light)
    if power > FLT_MAX:
        summary.warn(f"Light '{ob.name}': power {power:g} W (with the exposure) exceeds the "
                     "largest float; limited to it")
        power = FLT_MAX
    if kind in ("POINT", "SPOT") and light.shadow_soft_size > 0.0 and not getattr(
            light, "use_soft_falloff", True):
        # Cycles 4.1+ with Soft Falloff off draws a radius as a uniform sphere; Stratum has
        # only the facing disk of Soft Falloff on (and of Cycles 3.x).
        summary.warn(f"Light '{ob.name}': 'Soft Falloff' off is not supported "
                     "(rendered as with Soft Falloff on)")
    if kind == "POINT":
        return native.Light(type=native.light_type("point"), color=color, strength=power,
                            radius=max(float(light.shadow_soft_size), 0.0), transform=transform,
                            visibility=visibility)
    if kind == "SPOT":
        spot_type = native.light_type(blender_versions.spot_light_model(bpy.app.version))
        return native.Light(type=spot_type, color=color, strength=power,
                            radius=max(float(light.shadow_soft_size), 0.0), transform=transform,
                            spot_size=float(light.spot_size), spot_blend=float(light.spot_blend),
                            visibility=visibility)
    if kind == "SUN":
        return native.Light(type=native.light_type("sun"), color=color, strength=power,
                            angle=float(light.angle), transform=transform,
                            visibility=visibility)
    if kind == "AREA":
        if not getattr(light, "normalize", True):
            summary.warn(f"Light '{ob.name}': 'Normalize' off is not supported "
                         "(rendered normalized)")
        shape = light.shape
        size_x = float(light.size)
        size_y = float(light.size_y) if shape in {"RECTANGLE", "ELLIPSE"} else size_x
        rectangle = shape in {"SQUARE", "RECTANGLE"}
        light_type = native.light_type("area_rectangle" if rectangle else "area_ellipse")
        scale = np.linalg.norm(np.asarray(transform).reshape(4, 4)[:3, :2], axis=0)
        if not (size_x * scale[0] > 0.0 and size_y * scale[1] > 0.0):
            summary.warn(f"Light '{ob.name}': area light of size {size_x:g} x {size_y:g} "
                         "(with the object's scale) has no area and emits nothing (skipped)")
            return None
        power *= blender_versions.area_light_power_scale(bpy.app.version)
        return native.Light(type=light_type, color=color, strength=power,
                            size_x=size_x, size_y=size_y, transform=transform,
                            visibility=visibility,
                            spread=max(float(getattr(light, "spread", math.pi)), MIN_SPREAD))
    summary.warn(f"Light '{ob.name}': type {kind} is not supported (skipped)")
    return None


def _unrenderable(light: Any, kind: str) -> str | None:
    """Why a light cannot be rendered (a field NaN, infinite, or a negative power), or None."""
    fields = ["energy", "exposure", *_SHAPE_FIELDS.get(kind, ())]
    if kind == "AREA" and light.shape in {"RECTANGLE", "ELLIPSE"}:
        fields.append("size_y")
    for field in fields:
        if not hasattr(light, field):
            continue
        value = float(getattr(light, field))
        if math.isnan(value):
            return f"'{field}' is not a number (Cycles renders such a light as nothing)"
        if math.isinf(value):
            return f"'{field}' = {value:g} is infinite (Cycles renders such a light as nothing)"
    energy = float(light.energy)
    if energy < 0.0:
        return f"'energy' = {energy:g} W is negative (a light that subtracts is not supported)"
    return None


def _exposure_scale(light: Any) -> float:
    """Blender 4.x lights have an exposure: the power is multiplied by 2^exposure."""
    return 2.0 ** float(getattr(light, "exposure", 0.0))
