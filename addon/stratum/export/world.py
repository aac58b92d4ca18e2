"""The scene world -> native constant background."""

from __future__ import annotations

from typing import Any

from .common import (
    ExportSummary,
    active_output,
    linked_from,
    rgb,
    socket_value,
    uses_nodes,
)


def convert_world(scene: Any, summary: ExportSummary) -> tuple[float, float, float]:
    world = scene.world
    if world is None:
        return (0.0, 0.0, 0.0)
    if not uses_nodes(world):
        return rgb(world.color)
    node_tree = world.node_tree
    output = active_output(node_tree, "ShaderNodeOutputWorld")
    surface = output.inputs.get("Surface") if output is not None else None
    node = linked_from(surface) if surface is not None else None
    if node is None:
        return (0.0, 0.0, 0.0)  # as Cycles: nothing connected renders black
    if node.bl_idname != "ShaderNodeBackground":
        summary.warn(f"World '{world.name}': shader node '{node.name}' ({node.bl_idname}) is "
                     "not supported; using the world colour (constant background only)")
        return rgb(world.color)
    linked = [s for s in ("Color", "Strength") if node.inputs[s].is_linked]
    if linked:
        summary.warn(f"World '{world.name}': linked Background {', '.join(linked)} (e.g. an "
                     "environment texture) is not supported; using the socket values as a "
                     "constant background")
    color = rgb(socket_value(node, "Color"))
    strength = float(socket_value(node, "Strength"))
    return (max(color[0] * strength, 0.0), max(color[1] * strength, 0.0),
            max(color[2] * strength, 0.0))
