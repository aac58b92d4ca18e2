"""A light's node tree as Cycles reads it: the lamp's colour and power times its Emission node's
Color x Strength.

Cycles shades a lamp with its node tree (Light > Nodes): the output's Emission scales what the
lamp emits. Node trees whose emission does not depend on where the lamp is seen (constants,
Blackbody for a colour temperature, Math, Mix, ramps) are evaluated once here with the native
node program and fold into the lamp's colour. One that does (a Texture Coordinate, a Fresnel, a
gobo texture) is not supported: one warning, and the lamp renders without its nodes."""

from __future__ import annotations

from typing import Any

import bpy
import numpy as np

from .. import native
from ..shaders.nodes import NodeCompiler
from ..shaders.nodes.math_nodes import color_times
from .common import ExportSummary, active_output, linked_from

Rgb = tuple[float, float, float]


def _reads_the_shading_point(program: native.ShaderProgram) -> bool:
    return any(r < native.SHADER_INPUT_REGISTERS for n in program.nodes for r in n.inputs)


def node_emission(ob: Any, summary: ExportSummary) -> Rgb | None:
    """The factor a light's node tree puts on its colour, or None when it has no node tree in
    use (or one Stratum cannot fold, after a warning)."""
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
    if _reads_the_shading_point(program):
        summary.warn(f"Light '{ob.name}': its nodes depend on where the light is seen (texture "
                     "coordinates, geometry), which is not supported; rendered without its nodes")
        return None
    with native.Scene() as scratch:
        program_id = scratch.add_shader_program(program)
        value = scratch.evaluate_program(
            program_id, np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32), register, 3)
    # A lamp adds light: a negative or NaN factor reads 0, as for the lamp's own colour.
    return tuple(float(v) if np.isfinite(v) and v > 0.0 else 0.0 for v in value)  # type: ignore
