"""Invalid values in Blender data -> the value the renderer takes, and what to tell the user.

Blender's RNA stores NaN in shader sockets, light, world and camera properties, and a socket
takes any float, whatever its UI range (measured in 3.4.1 and 5.0.1: `default_value = nan`,
`-1`, `3e38` are all kept; +Inf is stored as FLT_MAX; colour sockets clamp negatives to 0).
Old or foreign .blend files carry the same. Cycles reads every such value through its own
clamps, and the fallbacks here are those clamps (docs/invalid_values.md):

* Cycles clamps with `max(x, lo)` / `fmaxf(x, lo)` / `saturatef(x)` (kernel/svm/closure.h,
  util/math_base.h). Each of them turns NaN into the lower bound: `max(a, b)` is
  `a > b ? a : b`, SSE `_mm_max_ps(a, b)` returns b when either is NaN, and `fmaxf` returns
  the operand that is not NaN. So a NaN becomes the low end of the parameter's range here too.
* A value outside the range is clamped to it.

Every replacement is reported, once per value, by the caller (the message names the material
and socket, the light or the world and the field).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

Rgb = tuple[float, float, float]

FLT_MAX = 3.4028234663852886e38  # the largest float32: the ABI's floats cannot exceed it


@dataclass(frozen=True)
class Range:
    """The values a parameter may take; NaN becomes `low` (Cycles' clamps, above)."""

    low: float
    high: float = FLT_MAX


UNIT = Range(0.0, 1.0)  # saturatef: roughness, metallic, transmission, alpha, Mix Fac
NON_NEGATIVE = Range(0.0)  # max(x, 0): emission strength, Specular IOR Level, normal strength
# fmaxf(ior, 1e-5f) for the Principled, Glass and Refraction IOR (both Cycles generations).
IOR = Range(1e-5)
COAT_IOR = Range(1.0)  # fmaxf(coat_ior, 1.0f) (Cycles 4.x+)
# The native material's upper limits for the unbounded Specular (3.x) and coat weight.
SPECULAR = Range(0.0, 1e6)
COAT = Range(0.0, 1e6)


def _describe(value: float, valid: Range) -> str:
    if math.isnan(value):
        return "is not a number"
    if math.isinf(value):
        return "is infinite"
    if value < valid.low:
        return f"is below {valid.low:g}"
    return f"is above {valid.high:g}"


def clamp(value: float, valid: Range) -> tuple[float, str | None]:
    """(the value the renderer takes, None) for a valid value, else (the fallback, why)."""
    if valid.low <= value <= valid.high:
        return value, None
    fallback = valid.high if value > valid.high else valid.low  # NaN and -Inf: low
    return fallback, f"= {value:g} {_describe(value, valid)}; using {fallback:g}"


def clamp_rgb(color: Rgb, valid: Range) -> tuple[Rgb, str | None]:
    """clamp() on each component; one message for the colour."""
    fixed = tuple(clamp(c, valid)[0] for c in color)
    out: Rgb = (fixed[0], fixed[1], fixed[2])
    if out == tuple(color):
        return out, None
    bad = next(c for c in color if not valid.low <= c <= valid.high)
    return out, (f"= ({color[0]:g}, {color[1]:g}, {color[2]:g}) {_describe(bad, valid)}; "
                 f"using ({out[0]:g}, {out[1]:g}, {out[2]:g})")


def finite_product(color: Rgb, strength: float) -> tuple[Rgb, bool]:
    """color x strength, each component limited to FLT_MAX (a float32 cannot hold more), and
    whether one had to be. Both factors are valid (finite, >= 0) here."""
    out = tuple(min(c * strength, FLT_MAX) for c in color)
    return (out[0], out[1], out[2]), any(c * strength > FLT_MAX for c in color)
