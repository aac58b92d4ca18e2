"""Colour nodes: Mix (3.4+ ShaderNodeMix and 3.x ShaderNodeMixRGB), Invert, Gamma,
Bright/Contrast, Hue/Saturation/Value, RGB to BW, Separate/Combine Color and 3.x's
Separate/Combine RGB and HSV.

| node (bl_idname)          | native node      | notes                                            |
|---------------------------|------------------|--------------------------------------------------|
| ShaderNodeMix             | mix              | FLOAT / VECTOR (UNIFORM, NON_UNIFORM) / RGBA;    |
|                           |                  | ROTATION (4.x+) is not supported                 |
| ShaderNodeMixRGB          | mix (RGBA)       | factor always clamped, Clamp clamps the result   |
| ShaderNodeInvert          | invert           |                                                  |
| ShaderNodeGamma           | gamma            |                                                  |
| ShaderNodeBrightContrast  | bright_contrast  |                                                  |
| ShaderNodeHueSaturation   | hsv              | hue wrapped by fmod before Blender 4.3, fract    |
| ShaderNodeRGBToBW         | rgb_to_bw        |                                                  |
| ShaderNodeSeparateColor   | separate_color   | RGB needs no node                                |
| ShaderNodeCombineColor    | combine_color    | RGB: the three registers gathered                |
| ShaderNodeSeparateRGB/HSV | as Separate Color| 3.x                                              |
| ShaderNodeCombineRGB/HSV  | as Combine Color | 3.x                                              |

Blend modes by Blender's identifier, numbered as Cycles' NodeMix (svm/types.h)."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler, Unsupported
from .registry import translator

BLEND_TYPES = {
    "MIX": 0, "ADD": 1, "MULTIPLY": 2, "SUBTRACT": 3, "SCREEN": 4, "DIVIDE": 5, "DIFFERENCE": 6,
    "DARKEN": 7, "LIGHTEN": 8, "OVERLAY": 9, "DODGE": 10, "BURN": 11, "HUE": 12, "SATURATION": 13,
    "VALUE": 14, "COLOR": 15, "SOFT_LIGHT": 16, "LINEAR_LIGHT": 17, "EXCLUSION": 18}

# The native mix node's kinds (mix_node.cpp MixKind).
MIX_FLOAT, MIX_VECTOR, MIX_VECTOR_NON_UNIFORM, MIX_COLOR = range(4)
# The colour models of separate_color / combine_color (color_convert_nodes.cpp).
COLOR_MODELS = {"RGB": 0, "HSV": 1, "HSL": 2}


def blend_type(node: Any) -> int:
    blend = str(getattr(node, "blend_type", "MIX"))
    if blend not in BLEND_TYPES:
        raise Unsupported(f"{node.bl_idname} '{node.name}': blend type {blend} is not supported")
    return BLEND_TYPES[blend]


def mix_color(c: NodeCompiler, factor: int, a: int, b: int, blend: int, clamp_factor: bool,
              clamp_result: bool) -> int:
    return c.builder.node("mix", (MIX_COLOR, blend, int(clamp_factor), int(clamp_result)),
                          (factor, a, b), (3,))[0]


@translator("ShaderNodeMixRGB")
def mix_rgb(c: NodeCompiler, node: Any) -> dict[str, int]:
    # Cycles' MixNode: svm_mix_clamped_factor, and a NODE_MIX_CLAMP of the result when Clamp.
    blend = blend_type(node)
    factor = c.input(node, "Fac", "float")
    a, b = c.input(node, "Color1", "color"), c.input(node, "Color2", "color")
    return {"Color": mix_color(c, factor, a, b, blend, True, bool(getattr(node, "use_clamp",
                                                                            False)))}


@translator("ShaderNodeMix")
def mix(c: NodeCompiler, node: Any) -> dict[str, int]:
    data_type = str(getattr(node, "data_type", "FLOAT"))
    clamp_factor = bool(getattr(node, "clamp_factor", True))
    if data_type == "FLOAT":
        factor = c.input(node, "Factor_Float", "float")
        a, b = c.input(node, "A_Float", "float"), c.input(node, "B_Float", "float")
        out = c.builder.node("mix", (MIX_FLOAT, 0, int(clamp_factor), 0), (factor, a, b), (1,))
        return {"Result_Float": out[0]}
    if data_type == "VECTOR":
        non_uniform = str(getattr(node, "factor_mode", "UNIFORM")) == "NON_UNIFORM"
        factor = (c.input(node, "Factor_Vector", "vector") if non_uniform
                  else c.input(node, "Factor_Float", "float"))
        a, b = c.input(node, "A_Vector", "vector"), c.input(node, "B_Vector", "vector")
        kind = MIX_VECTOR_NON_UNIFORM if non_uniform else MIX_VECTOR
        out = c.builder.node("mix", (kind, 0, int(clamp_factor), 0), (factor, a, b), (3,))
        return {"Result_Vector": out[0]}
    if data_type == "RGBA":
        blend = blend_type(node)
        factor = c.input(node, "Factor_Float", "float")
        a, b = c.input(node, "A_Color", "color"), c.input(node, "B_Color", "color")
        clamp_result = bool(getattr(node, "clamp_result", False))
        return {"Result_Color": mix_color(c, factor, a, b, blend, clamp_factor, clamp_result)}
    raise Unsupported(f"Mix node '{node.name}': data type {data_type} is not supported")


@translator("ShaderNodeInvert")
def invert(c: NodeCompiler, node: Any) -> dict[str, int]:
    fac, color = c.input(node, "Fac", "float"), c.input(node, "Color", "color")
    return {"Color": c.builder.node("invert", (), (fac, color), (3,))[0]}


@translator("ShaderNodeGamma")
def gamma(c: NodeCompiler, node: Any) -> dict[str, int]:
    color, g = c.input(node, "Color", "color"), c.input(node, "Gamma", "float")
    return {"Color": c.builder.node("gamma", (), (color, g), (3,))[0]}


@translator("ShaderNodeBrightContrast")
def bright_contrast(c: NodeCompiler, node: Any) -> dict[str, int]:
    color = c.input(node, "Color", "color")
    bright, contrast = c.input(node, "Bright", "float"), c.input(node, "Contrast", "float")
    return {"Color": c.builder.node("bright_contrast", (), (color, bright, contrast), (3,))[0]}


@translator("ShaderNodeHueSaturation")
def hue_saturation(c: NodeCompiler, node: Any) -> dict[str, int]:
    inputs = [c.input(node, k, "float") for k in ("Hue", "Saturation", "Value", "Fac")]
    inputs.append(c.input(node, "Color", "color"))
    wrap = int(blender_versions.hue_wraps_with_fmod(c.version))
    return {"Color": c.builder.node("hsv", (wrap,), inputs, (3,))[0]}


@translator("ShaderNodeRGBToBW")
def rgb_to_bw(c: NodeCompiler, node: Any) -> dict[str, int]:
    color = c.input(node, "Color", "color")
    return {"Val": c.builder.node("rgb_to_bw", (c.color_config,), (color,), (1,))[0]}


def separate(c: NodeCompiler, color: int, model: str) -> int:
    """Three registers in a row holding the components of `color` in `model`."""
    if model == "RGB":
        return color
    return c.builder.node("separate_color", (COLOR_MODELS[model],), (color,), (3,))[0]


def combine(c: NodeCompiler, x: int, y: int, z: int, model: str) -> int:
    if model == "RGB":
        return c.builder.combine(x, y, z)
    return c.builder.node("combine_color", (COLOR_MODELS[model],), (x, y, z), (3,))[0]


def color_model(node: Any) -> str:
    model = str(getattr(node, "mode", "RGB"))
    if model not in COLOR_MODELS:
        raise Unsupported(f"{node.bl_idname} '{node.name}': mode {model} is not supported")
    return model


@translator("ShaderNodeSeparateColor")
def separate_color(c: NodeCompiler, node: Any) -> dict[str, int]:
    model = color_model(node)
    v = separate(c, c.input(node, "Color", "color"), model)
    return {"Red": v, "Green": v + 1, "Blue": v + 2}


@translator("ShaderNodeCombineColor")
def combine_color(c: NodeCompiler, node: Any) -> dict[str, int]:
    model = color_model(node)
    x, y, z = (c.input(node, k, "float") for k in ("Red", "Green", "Blue"))
    return {"Color": combine(c, x, y, z, model)}


@translator("ShaderNodeSeparateRGB")
def separate_rgb(c: NodeCompiler, node: Any) -> dict[str, int]:
    v = c.input(node, "Image", "color")
    return {"R": v, "G": v + 1, "B": v + 2}


@translator("ShaderNodeCombineRGB")
def combine_rgb(c: NodeCompiler, node: Any) -> dict[str, int]:
    x, y, z = (c.input(node, k, "float") for k in ("R", "G", "B"))
    return {"Image": combine(c, x, y, z, "RGB")}


@translator("ShaderNodeSeparateHSV")
def separate_hsv(c: NodeCompiler, node: Any) -> dict[str, int]:
    v = separate(c, c.input(node, "Color", "color"), "HSV")
    return {"H": v, "S": v + 1, "V": v + 2}


@translator("ShaderNodeCombineHSV")
def combine_hsv(c: NodeCompiler, node: Any) -> dict[str, int]:
    x, y, z = (c.input(node, k, "float") for k in ("H", "S", "V"))
    return {"Color": combine(c, x, y, z, "HSV")}
