"""A light's node tree as Cycles reads it: the lamp's colour and power times its Emission node's
Color x Strength.

Cycles shades a lamp with its node tree (Light > Nodes): the output's Emission scales what the
lamp emits, evaluated with sd->ray_length the distance from the lit point to the point on the
lamp (FLT_MAX for a sun). Node trees whose emission does not depend on where the lamp is seen
(constants, Blackbody for a colour temperature, Math, Mix, ramps) are evaluated once here with
the native node program and fold into the lamp's colour. One whose program reads the ray length
and the Light Path node and nothing else of the shading point (a Light Falloff, Cycles' way to
change a lamp's falloff; Is Camera Ray, for a lamp that lights but is not seen) becomes a
LampProgram, which the renderer runs at each distance and path (native.Scene.set_light_program).
One that reads more (a Texture Coordinate, a Fresnel, a gobo texture) is not supported: one
warning, and the lamp renders without its nodes."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import bpy
import numpy as np

from .. import native
from ..shaders.nodes import NodeCompiler
from ..shaders.nodes.math_nodes import color_times
from .common import ExportSummary, active_output, linked_from

Rgb = tuple[float, float, float]


@dataclass(frozen=True)
class LampProgram:
    """A light's node tree that reads the distance to the lamp: the program, and the register of
    the RGB factor it puts on the lamp's emission."""

    program: native.ShaderProgram
    register: int

    def key(self) -> tuple[Any, ...]:
        return (self.program.key(), self.register)


def _renderer_inputs(program: native.ShaderProgram) -> set[int]:
    """The renderer-input registers the program's nodes read."""
    return {r for n in program.nodes for r in n.inputs if r < native.SHADER_INPUT_REGISTERS}


# What a lamp's program may read: the distance, and the Light Path node's outputs (the renderer
# fills them as Cycles' emission evaluation does: no ray kind, Ray Depth the path's depth + 1).
_LAMP_INPUTS = frozenset(native.SHADER_INPUTS[name][0] for name in (
    "ray_length", "is_camera_ray", "is_shadow_ray", "is_diffuse_ray", "is_glossy_ray",
    "is_singular_ray", "is_reflection_ray", "is_transmission_ray", "is_volume_scatter_ray",
    "ray_depth", "diffuse_depth", "glossy_depth", "transparent_depth", "transmission_depth",
    "portal_depth"))


def node_emission(ob: Any, summary: ExportSummary) -> Rgb | LampProgram | None:
    """The factor a light's node tree puts on its colour: an RGB when it is the same wherever the
    lamp is seen, a LampProgram when it depends on the distance only, or None when the light has
    no node tree in use (or one Stratum cannot render, after a warning)."""
    light = ob.data
    tree = getattr(light, "node_tree", None)
    if tree is None or not getattr(light, "use_nodes", True):
        return None
    output = active_output(tree, "ShaderNodeOutputLight")
    surface = output.inputs.get("Surface") if output is not None else None
    node = linked_from(surface) if surface is not None else None
    if node is None:
        summary.warn(f"Light '{ob.name}': its node tree's output has nothing connected; it "
                     "emits nothing, as in Cycles")
        return (0.0, 0.0, 0.0)
    if node.bl_idname != "ShaderNodeEmission":
        summary.warn(f"Light '{ob.name}': node '{node.name}' ({node.bl_idname}) on its output "
                     "is not supported; rendered without its nodes")
        return None
    warnings: list[str] = []
    c = NodeCompiler(tuple(bpy.app.version), lambda _node, message: warnings.append(message))
    color = c.value(node.inputs["Color"], "color")
    strength = c.value(node.inputs["Strength"], "float")
    register = color_times(c, color, strength)
    for message in warnings:
        summary.warn(f"Light '{ob.name}': {message}")
    program = c.builder.program
    reads = _renderer_inputs(program)
    if reads and reads <= _LAMP_INPUTS:
        return LampProgram(program, register)
    if reads:
        summary.warn(f"Light '{ob.name}': its nodes depend on where the light is seen (texture "
                     "coordinates, geometry), which is not supported; rendered without its nodes")
        return None
    with native.Scene() as scratch:
        program_id = scratch.add_shader_program(program)
        value = scratch.evaluate_program(
            program_id, np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32), register, 3)
    # A lamp adds light: a negative or NaN factor reads 0, as for the lamp's own colour.
    return tuple(float(v) if np.isfinite(v) and v > 0.0 else 0.0 for v in value)  # type: ignore
