"""Shared pieces of the exporter: errors, summary, matrix conversion, node-tree helpers."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, fields
from typing import Any

import bpy
import numpy as np

from .. import blender_versions, native


class ExportError(RuntimeError):
    """The scene cannot be exported; the message names the object and the problem."""


class ExportCancelled(RuntimeError):
    """The user pressed Esc during export."""


class FullExportNeeded(Exception):
    """A change that live edits cannot express (SceneSync.update); the message says which."""


@dataclass
class ExportSummary:
    """What export_scene sent to the native scene (used by the engine and the tests)."""

    materials: int = 0
    meshes: int = 0  # unique meshes sent (deduplicated evaluated data)
    instances: int = 0  # mesh instances placed
    triangles: int = 0  # triangles of the unique meshes
    instanced_triangles: int = 0  # triangles over all instances
    lights: int = 0
    textures: int = 0  # images sent (each once)
    moving_instances: int = 0  # instances with motion blur (transform differs over the shutter)
    object_triangles: dict[str, int] = field(default_factory=dict)  # evaluated, per object
    object_instances: dict[str, int] = field(default_factory=dict)  # instances per object
    warnings: list[str] = field(default_factory=list)
    export_seconds: float = 0.0

    def warn(self, message: str) -> None:
        if message not in self.warnings:
            self.warnings.append(message)


def named_edit(what: str, send: Callable[[], None]) -> Callable[[], None]:
    """`send` (a live edit of the native scene), its rejection an ExportError naming `what`."""

    def edit() -> None:
        try:
            send()
        except native.StratumError as exc:
            raise ExportError(f"{what}: {exc}") from exc

    return edit


def comparable(description: Any) -> tuple[Any, ...]:
    """The field values of a native description (a dataclass), arrays as their bytes: equal
    exactly when the description sends the same values."""
    return tuple(value.tobytes() if isinstance(value, np.ndarray) else value
                 for value in (getattr(description, f.name) for f in fields(description)))


def uses_nodes(idblock: Any) -> bool:
    """True when a material/world is shaded by its node tree. Blender 5.0 deprecates
    use_nodes (node trees are always used), so it is only read before 5.0."""
    if getattr(idblock, "node_tree", None) is None:
        return False
    if blender_versions.node_trees_always_used(bpy.app.version):
        return True
    return bool(getattr(idblock, "use_nodes", True))


def matrix_to_array(matrix: Any) -> np.ndarray:
    """A Blender 4x4 Matrix as 16 float32, row-major (m[row*4 + col]), as the C ABI wants."""
    return np.ascontiguousarray(np.array(matrix, dtype=np.float32).reshape(16))


def instance_matrices(depsgraph: Any, count: int) -> np.ndarray:
    """matrix_world of every depsgraph object instance, in iteration order, as (count, 4, 4)
    row-major float32: one foreach_get instead of a Matrix conversion per instance (which
    costs ~0.2 ms each in Blender 3.4). RNA stores matrices column-major, hence the transpose."""
    flat = np.empty(count * 16, dtype=np.float32)
    if count:
        depsgraph.object_instances.foreach_get("matrix_world", flat)
    return np.ascontiguousarray(flat.reshape(count, 4, 4).transpose(0, 2, 1))


def linked_from(socket: Any) -> Any | None:
    """The node feeding `socket`, following reroute nodes; None if unlinked."""
    seen = 0
    while socket is not None and socket.is_linked and seen < 64:
        link = socket.links[0]
        if getattr(link, "is_muted", False) or not getattr(link, "is_valid", True):
            return None
        node = link.from_node
        if node.bl_idname == "NodeReroute":
            socket = node.inputs[0]
            seen += 1
            continue
        return node
    return None


def active_output(node_tree: Any, idname: str) -> Any | None:
    """The active output node (target ALL or CYCLES) of a shader node tree."""
    getter = getattr(node_tree, "get_output_node", None)
    if getter is not None:
        try:
            node = getter("CYCLES")
        except (TypeError, RuntimeError):
            node = None
        if node is not None and node.bl_idname == idname:
            return node
    candidates = [n for n in node_tree.nodes if n.bl_idname == idname]
    for node in candidates:
        if getattr(node, "is_active_output", False) and getattr(node, "target", "ALL") in {
            "ALL",
            "CYCLES",
        }:
            return node
    return candidates[0] if candidates else None


def socket_value(node: Any, name: str) -> Any | None:
    """default_value of input `name`, or None if the node has no such input."""
    socket = node.inputs.get(name)
    if socket is None:
        return None
    return socket.default_value


def rgb(value: Any) -> tuple[float, float, float]:
    v = tuple(float(x) for x in value)
    return (v[0], v[1], v[2])
