"""Color Ramp (ShaderNodeValToRGB) and the curve nodes (ShaderNodeRGBCurve, ShaderNodeVectorCurve,
ShaderNodeFloatCurve), baked into tables as Cycles bakes them (blender/shader.cpp and
blender/util.h: colorramp_to_array, curvemapping_color_to_array, curvemapping_float_to_array)
and looked up by the native color_ramp and curves nodes (ramp_node.cpp).

* Table size: Blender 3.x and 4.0 bake RAMP_TABLE_SIZE = 256 entries at i / 255, later
  versions 257 at i / 256 (measured: a CONSTANT ramp black below 0.5 and white from 0.5 is
  black at 0.501 in Blender 3.4's Cycles and white in 5.0's; the change is read from Cycles'
  blender/util.h, which has the 257 entries with 4.1's mesh code).
* Color Ramp: entry i is the ramp's evaluate(i / (n - 1)) (RGBA), interpolated between entries
  unless the ramp's interpolation is CONSTANT. Every interpolation
  and colour mode (RGB, HSV, HSL and their hue interpolations) is Blender's own evaluate().
* Curves: n entries over [min_x, max_x], the first and last points' x over the curves used
  (RGB: C, R, G, B; vector: X, Y, Z; float: the one curve); entry i at x = min_x + i / (n - 1)
  (max_x - min_x) is, for RGB Curves, R(C(x)), G(C(x)), B(C(x)), else each curve at x. The
  mapping's extend (EXTRAPOLATED or HORIZONTAL) chooses extrapolation outside the range. The
  mapping's black/white levels are not applied (Cycles does not apply them)."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler, Unsupported
from .registry import translator

TABLE_SIZE = 256  # Cycles' RAMP_TABLE_SIZE


def table_size(version: tuple[int, ...]) -> int:
    """Entries Cycles bakes: RAMP_TABLE_SIZE before Blender 4.1, one more from 4.1."""
    return TABLE_SIZE + 1 if blender_versions.ramp_table_has_end_entry(version) else TABLE_SIZE
CURVE_RGB, CURVE_VECTOR, CURVE_FLOAT = range(3)


def ramp_table(ramp: Any, size: int = TABLE_SIZE) -> list[float]:
    """`size` RGBA entries of a ColorRamp, flattened."""
    table: list[float] = []
    for i in range(size):
        rgba = [float(v) for v in ramp.evaluate(i / (size - 1))]
        table.extend((rgba + [1.0] * 4)[:4])
    return table


@translator("ShaderNodeValToRGB")
def color_ramp(c: NodeCompiler, node: Any) -> dict[str, int]:
    ramp = node.color_ramp
    interpolate = str(getattr(ramp, "interpolation", "LINEAR")) != "CONSTANT"
    fac = c.input(node, "Fac", "float")
    color, alpha = c.builder.node("color_ramp", (int(interpolate),), (fac,), (3, 1),
                                  ramp_table(ramp, table_size(c.version)))
    return {"Color": color, "Alpha": alpha}


def _prepare(mapping: Any) -> None:
    # Cycles calls update(); evaluate() needs the tables initialize() builds.
    for name in ("initialize", "update"):
        method = getattr(mapping, name, None)
        if callable(method):
            method()


def curve_range(mapping: Any, count: int) -> tuple[float, float]:
    """(min_x, max_x): the first point's x and the last point's x over the first `count`
    curves (Cycles' curvemapping_minmax)."""
    curves = list(mapping.curves)[:count]
    if len(curves) < count or any(len(cm.points) == 0 for cm in curves):
        raise Unsupported(f"a curve mapping has fewer than {count} curves with points")
    lo = min(float(cm.points[0].location[0]) for cm in curves)
    hi = max(float(cm.points[len(cm.points) - 1].location[0]) for cm in curves)
    return lo, hi


def curve_table(mapping: Any, kind: int, size: int = TABLE_SIZE) -> list[float]:
    """(min_x, max_x) and the `size` entries of the baked curves, flattened."""
    count = {CURVE_RGB: 4, CURVE_VECTOR: 3, CURVE_FLOAT: 1}[kind]
    _prepare(mapping)
    lo, hi = curve_range(mapping, count)
    curves = list(mapping.curves)
    evaluate = mapping.evaluate
    table = [lo, hi]
    for i in range(size):
        x = lo + i / (size - 1) * (hi - lo)
        if kind == CURVE_RGB:
            xc = evaluate(curves[3], x)
            table.extend(float(evaluate(curves[k], xc)) for k in range(3))
        elif kind == CURVE_VECTOR:
            table.extend(float(evaluate(curves[k], x)) for k in range(3))
        else:
            table.append(float(evaluate(curves[0], x)))
    return table


def _curves(c: NodeCompiler, node: Any, kind: int, fac_key: str, value_key: str,
            out_key: str) -> dict[str, int]:
    mapping = node.mapping
    try:
        data = curve_table(mapping, kind, table_size(c.version))
    except Unsupported as exc:
        raise Unsupported(f"{node.bl_idname} '{node.name}': {exc}") from None
    extrapolate = str(getattr(mapping, "extend", "EXTRAPOLATED")) == "EXTRAPOLATED"
    fac = c.input(node, fac_key, "float")
    value = c.input(node, value_key, "float" if kind == CURVE_FLOAT else
                    ("color" if kind == CURVE_RGB else "vector"))
    width = 1 if kind == CURVE_FLOAT else 3
    out = c.builder.node("curves", (kind, int(extrapolate)), (fac, value), (width,), data)
    return {out_key: out[0]}


@translator("ShaderNodeRGBCurve")
def rgb_curves(c: NodeCompiler, node: Any) -> dict[str, int]:
    return _curves(c, node, CURVE_RGB, "Fac", "Color", "Color")


@translator("ShaderNodeVectorCurve")
def vector_curves(c: NodeCompiler, node: Any) -> dict[str, int]:
    return _curves(c, node, CURVE_VECTOR, "Fac", "Vector", "Vector")


@translator("ShaderNodeFloatCurve")
def float_curve(c: NodeCompiler, node: Any) -> dict[str, int]:
    return _curves(c, node, CURVE_FLOAT, "Factor", "Value", "Value")
