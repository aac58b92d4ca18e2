"""Plain stand-ins for Blender shader nodes, sockets and links (the compiler reads nodes by duck
typing): enough of bpy's node API for stratum.shaders.nodes and stratum.shaders.surface."""

from __future__ import annotations

from typing import Any


class Socket:
    def __init__(self, name: str, default_value: Any = 0.0, type: str | None = None,
                 identifier: str | None = None) -> None:
        self.name = name
        self.identifier = identifier or name
        self.default_value = default_value
        if type is None:
            size = len(default_value) if isinstance(default_value, (tuple, list)) else 1
            type = {1: "VALUE", 3: "VECTOR", 4: "RGBA"}.get(size, "VALUE")
        self.type = type
        self.enabled = True
        self.links: list[Any] = []

    @property
    def is_linked(self) -> bool:
        return bool(self.links)


class Link:
    def __init__(self, from_node: Any, from_socket: Socket, to_socket: Socket | None = None) -> None:
        self.from_node = from_node
        self.from_socket = from_socket
        self.to_socket = to_socket
        self.is_muted = False
        self.is_valid = True


class Sockets(list):
    def get(self, name: str) -> Socket | None:
        return next((s for s in self if s.name == name or s.identifier == name), None)

    def __getitem__(self, key: Any) -> Any:
        if isinstance(key, str):
            found = self.get(key)
            if found is None:
                raise KeyError(key)
            return found
        return super().__getitem__(key)


class Node:
    """A node: `inputs` as (name, default) pairs or Socket objects; `outputs` as names (float
    sockets) or Socket objects."""

    def __init__(self, bl_idname: str, name: str, inputs: Any = (), outputs: Any = (),
                 **props: Any) -> None:
        self.bl_idname = bl_idname
        self.name = name
        items = inputs.items() if isinstance(inputs, dict) else inputs
        self.inputs = Sockets(s if isinstance(s, Socket) else Socket(*s) for s in items)
        self.outputs = Sockets(s if isinstance(s, Socket) else Socket(s) for s in outputs)
        self.mute = False
        self.internal_links: list[Link] = []
        for key, value in props.items():
            setattr(self, key, value)


class Tree:
    def __init__(self, nodes: list[Node]) -> None:
        self.nodes = nodes


def link(src: Node, output: str | int, dst: Node | Socket, input_: str | int = 0) -> None:
    socket = dst if isinstance(dst, Socket) else dst.inputs[input_]
    socket.links = [Link(src, src.outputs[output], socket)]


def math(name: str, operation: str, a: float = 0.0, b: float = 0.0, c: float = 0.0,
         **props: Any) -> Node:
    return Node("ShaderNodeMath", name,
                [Socket("Value", a), Socket("Value", b, identifier="Value_001"),
                 Socket("Value", c, identifier="Value_002")], ["Value"],
                operation=operation, **props)


def texture_coordinate(name: str = "Texture Coordinate") -> Node:
    outputs = [Socket(n, (0.0, 0.0, 0.0)) for n in
               ("Generated", "Normal", "UV", "Object", "Camera", "Window", "Reflection")]
    return Node("ShaderNodeTexCoord", name, (), outputs, object=None, from_instancer=False)


def separate_xyz(name: str = "Separate XYZ") -> Node:
    return Node("ShaderNodeSeparateXYZ", name, [Socket("Vector", (0.0, 0.0, 0.0))],
                ["X", "Y", "Z"])
