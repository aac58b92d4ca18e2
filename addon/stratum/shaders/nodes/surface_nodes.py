"""Bump and Normal Map nodes: a program normal for the closures' Normal input.

| node (bl_idname)     | native     | notes                                                      |
|----------------------|------------|------------------------------------------------------------|
| ShaderNodeBump       | bump       | Height compiled three times: at the point and moved by the |
|                      |            | renderer's DPDX and DPDY steps (positions, generated,      |
|                      |            | object and UV coordinates all moved), as Cycles compiles   |
|                      |            | the height graph at the ray differential's offsets         |
| ShaderNodeNormalMap  | normal_map | TANGENT (the UV map's dpdu as tangent) and WORLD spaces;   |
|                      |            | OBJECT and the BLENDER_* spaces: not supported             |

An Image Texture linked straight to a Normal Map in tangent space never reaches here: the
material keeps its image binding with MikkTSpace tangents (stratum.shaders.inputs)."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler, Unsupported
from .math_nodes import math_node
from .registry import translator

# The renderer inputs a Bump moves, and the inputs holding their change along each step.
MOVED = {"position": ("dpdx", "dpdy"), "generated": ("dgenerated_dx", "dgenerated_dy"),
         "object": ("dobject_dx", "dobject_dy"), "uv": ("duv_dx", "duv_dy")}


def _moved(c: NodeCompiler, axis: int) -> dict[str, int]:
    """Registers of each moved input, shifted by its step along axis 0 (x) or 1 (y)."""
    zero = c.builder.constant(0.0)
    out = {}
    for name, steps in MOVED.items():
        base, step = c.geometry(name), c.geometry(steps[axis])
        parts = [math_node(c, base + k, step + k, zero, "ADD") for k in range(3)]
        out[name] = c.builder.combine(*parts)
    return out


def _normal_input(c: NodeCompiler, node: Any) -> int:
    socket = c.socket(node, "Normal")
    return c.value(socket, "vector") if c.linked(socket) else c.geometry("normal")


@translator("ShaderNodeBump")
def bump(c: NodeCompiler, node: Any) -> dict[str, int]:
    height = c.socket(node, "Height")
    center = c.value(height, "float")
    if c.linked(height):
        moved_x, moved_y = _moved(c, 0), _moved(c, 1)
        h_x = c.at_offset(moved_x, f"bump-x:{node.name}", lambda: c.value(height, "float"))
        h_y = c.at_offset(moved_y, f"bump-y:{node.name}", lambda: c.value(height, "float"))
    else:
        h_x = h_y = center
    strength = c.input(node, "Strength", "float")
    distance = c.input(node, "Distance", "float")
    normal = c.builder.node("bump", (int(bool(getattr(node, "invert", False))),), (
        center, h_x, h_y, strength, distance, _normal_input(c, node), c.geometry("dpdx"),
        c.geometry("dpdy")), (3,))[0]
    return {"Normal": normal}


@translator("ShaderNodeNormalMap")
def normal_map(c: NodeCompiler, node: Any) -> dict[str, int]:
    space = str(getattr(node, "space", "TANGENT"))
    if space not in ("TANGENT", "WORLD"):
        raise Unsupported(f"Normal Map '{node.name}': space {space} is not supported")
    color = c.input(node, "Color", "color")
    strength = c.input(node, "Strength", "float")
    modern = int(blender_versions.normal_map_scales_strength(c.version))
    normal = c.builder.node("normal_map", (0 if space == "TANGENT" else 1, modern), (
        color, strength, c.geometry("normal"), c.geometry("uv_tangent")), (3,))[0]
    return {"Normal": normal}
