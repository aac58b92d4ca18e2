"""`NodeCompiler`: Blender node graphs -> one shader program (pure Python, no bpy).

    c = NodeCompiler(version, warn)
    register = c.value(socket, "color")     # what feeds `socket`, as 3 registers

Nodes are read by duck typing (bl_idname, name, inputs, outputs, mute, internal_links; sockets:
identifier, name, type, default_value, is_linked, links, enabled), so tests use plain objects.
Each node is compiled once per group scope (its outputs memoised), as Cycles compiles a shader
graph once; links are followed through reroutes, muted nodes (their internal links, as Blender
bypasses them) and node groups, which are flattened: a Group node's output is its tree's Group
Output input, and a Group Input output is the Group node's input, one scope out.

A node without a translator (stratum.shaders.nodes.registry), a cycle, or a link that cannot be
followed gives one warning naming the node, and the consuming socket's own value: the documented
fallback (docs/shader_nodes.md)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ... import blender_versions
from .builder import FLOAT, VECTOR, ProgramBuilder

FLOAT_TYPES = frozenset({"VALUE", "INT", "BOOLEAN"})
# Cycles' colour-to-float conversion (svm/convert.h rgb_to_gray): the luminance weights of each
# colour configuration (blender_versions.color_config: 3.x, 4.0-4.5, 5.0+), as the native
# luminance() has them (measured in Cycles 3.4, 4.2, 4.5 and 5.0: docs/blender_versions.md).
LUMINANCE_WEIGHTS = ((0.212672979, 0.715152621, 0.0721754432),
                     (0.212674037, 0.715151608, 0.0721754208),
                     (0.212639123, 0.715169132, 0.0721927583))


class Unsupported(Exception):
    """A node or link the compiler cannot translate; the message is the warning."""


def identifier(socket: Any) -> str:
    return str(getattr(socket, "identifier", None) or socket.name)


def socket_kind(socket: Any) -> str:
    """"float", "vector", "color" or "shader" (Blender's socket type)."""
    t = getattr(socket, "type", "VALUE")
    if t in FLOAT_TYPES:
        return "float"
    if t == "VECTOR":
        return "vector"
    if t == "RGBA":
        return "color"
    return "shader" if t == "SHADER" else "float"


def width(kind: str) -> int:
    return FLOAT if kind == "float" else VECTOR


class NodeCompiler:
    """Compiles the nodes feeding sockets into one program (self.builder). `warn(node, message)`
    is called once per node and subject."""

    def __init__(self, version: tuple[int, int, int], warn: Callable[[Any, str], None],
                 builder: ProgramBuilder | None = None,
                 attribute_slot: Callable[[str], int | None] | None = None,
                 world: bool = False) -> None:
        self.version = tuple(version)
        self.builder = builder or ProgramBuilder()
        # Compiling a world's program: the renderer bakes it per direction, so its inputs are a
        # direction's (no camera, no triangle: native shader_nodes.h), which some nodes need to
        # know (Camera Data).
        self.world = world
        # The mesh-attribute slot of an attribute name (the exporter's table; None: no meshes,
        # as for the world, or a fifth name).
        self._attribute_slot = attribute_slot
        self._warn = warn
        self._warned: set[tuple[str, ...]] = set()
        self._memo: dict[tuple[Any, ...], dict[str, int]] = {}
        self._active: set[tuple[Any, ...]] = set()
        # The group nodes enclosing the node being compiled, outermost first.
        self._scope: tuple[Any, ...] = ()
        # Renderer inputs replaced while a Bump node's height is compiled at an offset.
        self.overrides: dict[str, int] = {}
        self._override_key: tuple[Any, ...] = ()
        # Image Texture nodes the program reads, in IMAGE node mode-0 order (the exporter maps
        # them to texture ids: export/materials.py resolve_images).
        self.images: list[Any] = []
        # Per Tangent node in UV-map mode, the UV map it names ("" for the active render map):
        # the exporter sends those materials' meshes with MikkTSpace tangents, of the one UV
        # map a mesh carries (export/geometry.py warns when that is not the one named).
        self.uv_tangent_maps: dict[str, str] = {}

    @property
    def color_config(self) -> int:
        """This Blender's colour configuration: which luminance weights and XYZ matrix."""
        return blender_versions.color_config(self.version)

    # ---- warnings ---------------------------------------------------------------------------

    def warn(self, node: Any, message: str, subject: str = "") -> None:
        key = (*self._scope_names(), getattr(node, "name", str(id(node))), subject)
        if key in self._warned:
            return
        self._warned.add(key)
        self._warn(node, message)

    def _scope_names(self) -> tuple[str, ...]:
        return tuple(getattr(g, "name", "") for g in self._scope)

    # ---- inputs of the node being translated -------------------------------------------------

    def socket(self, node: Any, key: str | int) -> Any:
        """The input of `node` with identifier (or name, or index) `key`; enabled ones first."""
        if isinstance(key, int):
            return node.inputs[key]
        found = None
        for s in node.inputs:
            if identifier(s) == key or s.name == key:
                if getattr(s, "enabled", True):
                    return s
                found = found or s
        if found is None:
            raise Unsupported(f"node '{node.name}' ({node.bl_idname}) has no input '{key}' in "
                              f"Blender {'.'.join(map(str, self.version))}")
        return found

    def has_input(self, node: Any, key: str) -> bool:
        return any(identifier(s) == key or s.name == key for s in node.inputs)

    def input(self, node: Any, key: str | int, kind: str) -> int:
        """Register of input `key` of `node` as `kind` ("float", "vector", "color")."""
        return self.value(self.socket(node, key), kind)

    def vector_or(self, node: Any, key: str, default_input: str) -> int:
        """A texture's Vector input: what is linked, or the renderer input Cycles uses for an
        unlinked one (e.g. "generated" for procedural textures, "uv" for images)."""
        socket = self.socket(node, key)
        if self._source(socket) is None:
            return self.geometry(default_input)
        return self.value(socket, "vector")

    def geometry(self, name: str) -> int:
        """Register of a renderer input (native.SHADER_INPUTS), or its Bump-offset stand-in."""
        return self.overrides.get(name, self.builder.input(name))

    def attribute(self, key: str) -> int:
        """The first register of the mesh-attribute slot holding `key` (colour, alpha at + 3,
        Fac at + 4); Unsupported when this graph has no meshes or the slots are full."""
        if self._attribute_slot is None:
            raise Unsupported("attributes are read from meshes only")
        slot = self._attribute_slot(key)
        if slot is None:
            raise Unsupported("more than 4 distinct attributes in the scene's materials")
        return self.geometry(f"attribute{slot}")

    def linked(self, socket: Any) -> bool:
        return self._source(socket) is not None

    # ---- values -----------------------------------------------------------------------------

    def value(self, socket: Any, kind: str) -> int:
        """Register(s) holding what feeds `socket`, converted to `kind`."""
        found = self._source(socket)
        if found is None:
            return self.constant_of(socket, kind)
        node, out, scope = found
        if node is None:
            # The chain ended at an unlinked socket (a group's output or a muted node's input).
            return self.constant_of(out, kind)
        saved = self._scope
        self._scope = scope
        try:
            register = self.output(node, out)
            return self.convert(register, socket_kind(out), kind)
        except Unsupported as exc:
            self.warn(node, f"{exc}; using the value of '{socket.name}'", "unsupported")
            self._scope = saved
            return self.constant_of(socket, kind)
        finally:
            self._scope = saved

    def output(self, node: Any, out: Any) -> int:
        """Register of output `out` of `node` (compiled once per scope and Bump offset)."""
        from .registry import TRANSLATORS

        key = (self._scope_names(), node.name, self._override_key)
        outputs = self._memo.get(key)
        if outputs is None:
            if key in self._active:
                raise Unsupported(f"node '{node.name}' feeds itself (a cycle)")
            translate = TRANSLATORS.get(node.bl_idname)
            if translate is None:
                raise Unsupported(f"node '{node.name}' ({node.bl_idname}) is not supported")
            self._active.add(key)
            try:
                outputs = translate(self, node)
            finally:
                self._active.discard(key)
            self._memo[key] = outputs
        name = identifier(out)
        if name not in outputs:
            raise Unsupported(f"output '{out.name}' of node '{node.name}' ({node.bl_idname}) is "
                              "not supported")
        return outputs[name]

    def convert(self, register: int, have: str, want: str) -> int:
        if have == want or {have, want} == {"vector", "color"}:
            return register
        if want == "float":
            if have == "color":
                return self.builder.to_float_from_color(register, self.color_config)
            return self.builder.to_float_from_vector(register)
        if have == "float":
            return self.builder.broadcast(register)
        raise Unsupported(f"a {have} socket cannot feed a {want} input")

    def constant_of(self, socket: Any, kind: str) -> int:
        """The socket's own value as `kind` (a shader or valueless socket: 0)."""
        raw = getattr(socket, "default_value", 0.0)
        try:
            values = [float(v) for v in raw]
        except TypeError:
            values = [float(raw)]
        have = "float" if len(values) == 1 else ("color" if len(values) == 4 else "vector")
        values = values[:3]
        if kind == "float":
            if have == "float":
                return self.builder.constant(values[0])
            if have == "color":
                weights = LUMINANCE_WEIGHTS[self.color_config]
                luminance = sum(w * v for w, v in zip(weights, values, strict=True))
                return self.builder.constant(luminance)
            return self.builder.constant(sum(values) / 3.0)
        if have == "float":
            return self.builder.constant((values[0],) * 3)
        return self.builder.constant(values)

    def _source(self, socket: Any) -> tuple[Any, Any, tuple[Any, ...]] | None:
        """(node, output socket, scope) feeding `socket`, through reroutes, muted nodes and
        group boundaries; (None, socket, scope) when the chain ends at an unlinked socket inside
        a group or a muted node; None if `socket` itself is unlinked."""
        scope = self._scope
        first = True
        for _ in range(10_000):
            # Blender ignores a muted or invalid link and one from an unavailable output (a
            # 1D Voronoi's Position): the input then has its own value.
            links = [link for link in (getattr(socket, "links", None) or ())
                     if not getattr(link, "is_muted", False) and getattr(link, "is_valid", True)
                     and getattr(link.from_socket, "enabled", True)]
            if not getattr(socket, "is_linked", False) or not links:
                return None if first else (None, socket, scope)
            first = False
            link = links[0]
            node, out = link.from_node, link.from_socket
            kind = node.bl_idname
            if kind == "NodeReroute":
                socket = node.inputs[0]
                continue
            if getattr(node, "mute", False):
                through = [lk.from_socket for lk in getattr(node, "internal_links", ())
                           if identifier(lk.to_socket) == identifier(out)]
                if not through:
                    return (None, out, scope)
                socket = through[0]
                continue
            if kind == "NodeGroupInput":
                if not scope:
                    return (None, out, scope)
                group = scope[-1]
                scope = scope[:-1]
                socket = self._by_identifier(group.inputs, identifier(out))
                if socket is None:
                    return (None, out, scope)
                continue
            if kind == "ShaderNodeGroup":
                tree = getattr(node, "node_tree", None)
                output = _group_output(tree) if tree is not None else None
                inner = self._by_identifier(output.inputs, identifier(out)) if output else None
                if inner is None:
                    return (None, out, scope)
                scope = (*scope, node)
                socket = inner
                continue
            return (node, out, scope)
        return None

    @staticmethod
    def _by_identifier(sockets: Any, key: str) -> Any | None:
        for s in sockets:
            if identifier(s) == key:
                return s
        return None

    # ---- Bump offsets -----------------------------------------------------------------------

    def at_offset(self, overrides: dict[str, int], tag: str, compile_: Callable[[], int]) -> int:
        """Runs `compile_` with renderer inputs replaced by `overrides` (a Bump node's height at
        an offset point); nodes compiled inside are memoised apart, under `tag`."""
        saved, saved_key = self.overrides, self._override_key
        self.overrides = {**saved, **overrides}
        self._override_key = (*saved_key, tag)
        try:
            return compile_()
        finally:
            self.overrides, self._override_key = saved, saved_key


def _group_output(tree: Any) -> Any | None:
    outputs = [n for n in tree.nodes if n.bl_idname == "NodeGroupOutput"]
    for n in outputs:
        if getattr(n, "is_active_output", False):
            return n
    return outputs[0] if outputs else None
