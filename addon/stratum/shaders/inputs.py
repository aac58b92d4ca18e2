"""The inputs of a material's shader nodes, read for its closures (pure Python).

An input is either its own value, clamped to what the renderer takes (stratum.shaders.fallbacks:
Cycles' own clamps; a replacement is warned about once per node and socket), or driven by what
is linked to it: an Image Texture linked directly (or, for Normal, through a tangent-space
Normal Map) becomes an image binding of the closure parameter, anything else a register of the
material's node program (compiled by stratum.shaders.nodes) that the parameter reads.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .. import blender_versions, native
from .fallbacks import NON_NEGATIVE, Range, clamp, clamp_rgb, finite_product
from .nodes import NodeCompiler
from .nodes.math_nodes import color_times
from .records import Binding, ImageRef, ProgramInput, Rgb

IMAGE_NODE = "ShaderNodeTexImage"
NORMAL_MAP_NODE = "ShaderNodeNormalMap"
# The closure parameters a texture or the program may drive (native.PROGRAM_PARAMS names) and
# each one's native texture parameter.
IMAGE_PARAMS = {
    "base_color": native.PARAM_BASE_COLOR, "roughness": native.PARAM_ROUGHNESS,
    "metallic": native.PARAM_METALLIC, "normal": native.PARAM_NORMAL,
    "emission": native.PARAM_EMISSION, "weight": native.PARAM_WEIGHT,
    "transmission": native.PARAM_TRANSMISSION, "specular": native.PARAM_SPECULAR,
}
# Parameters the native contract does not take textures for (stratum.h: emissive triangles are
# light-sampled with a constant emission; transmission waits for a per-material weight): a
# linked image drives them through the program.
NATIVE_UNBINDABLE = frozenset({"emission", "transmission"})
# What each program parameter reads from its socket.
PROGRAM_KIND = {
    "base_color": "color", "roughness": "float", "metallic": "float", "normal": "vector",
    "emission": "color", "weight": "float", "transmission": "float", "specular": "float",
    "ior": "float", "coat": "float", "coat_roughness": "float", "coat_tint": "color",
}


class InputReader:
    """Reads the inputs of one material's shader nodes. `warn(node, message)` is called at
    most once per node and subject (a socket, or the node itself; the caller prefixes the
    material name), for the warnings of the node compiler (self.nodes) too."""

    def __init__(self, version: tuple[int, int, int], warn: Callable[[Any, str], None],
                 attribute_slot: Callable[[str], int | None] | None = None) -> None:
        self.version = version
        self._warn = warn
        self._warned: set[tuple[str, str]] = set()
        self._bound: set[tuple[str, str]] = set()  # (node, socket) driven by a link
        # The material's node program: every linked input that is not a plain image binding.
        self.nodes = NodeCompiler(version, lambda node, message: self.warn(node, message),
                                  attribute_slot=attribute_slot)

    def warn(self, node: Any, message: str, subject: str = "") -> None:
        key = (getattr(node, "name", str(id(node))), subject)
        if key in self._warned:
            return
        self._warned.add(key)
        self._warn(node, message)

    def bind(self, node: Any, name: str) -> None:
        """Marks input `name` of `node` as driven by a link: its own value is not used, so a bad
        one is not warned about."""
        self._bound.add((node.name, name))

    def source(self, socket: Any) -> tuple[Any, Any] | None:
        """(node, output socket) feeding `socket`, following reroutes; None if unlinked."""
        for _ in range(64):
            if socket is None or not socket.is_linked:
                return None
            link = socket.links[0]
            if getattr(link, "is_muted", False) or not getattr(link, "is_valid", True):
                return None
            node = link.from_node
            if node.bl_idname == "NodeReroute":
                socket = node.inputs[0]
                continue
            return node, link.from_socket
        return None

    def image(self, image_node: Any) -> ImageRef:
        """The UV layer an Image Texture reads, from its Vector input."""
        found = self.source(image_node.inputs["Vector"])
        if found is None:
            return ImageRef(image_node)
        node, out = found
        if node.bl_idname == "ShaderNodeUVMap":
            return ImageRef(image_node, str(node.uv_map))
        if node.bl_idname == "ShaderNodeTexCoord" and out.name == "UV":
            return ImageRef(image_node)
        self.warn(node, f"node '{node.name}' ({node.bl_idname}) on the Vector input of "
                        f"'{image_node.name}' is not supported; using the UV map")
        return ImageRef(image_node)

    # ---- an input's own value ---------------------------------------------------------------

    def value(self, node: Any, name: str, fallback: Any) -> Any:
        """An input's own value (fallback if the node has no such input)."""
        socket = node.inputs.get(name)
        if socket is None:
            return fallback
        return socket.default_value

    def raw(self, node: Any, name: str, fallback: float) -> float:
        """An input's value as stored (NaN included): for tests of "is this feature used"."""
        return float(self.value(node, name, fallback))

    def scalar(self, node: Any, name: str, fallback: float, valid: Range) -> float:
        """An input's value within `valid` (fallbacks.clamp); a replacement is warned about
        unless a link drives the input (then the value is not used)."""
        fixed, problem = clamp(self.raw(node, name, fallback), valid)
        if problem is not None and (node.name, name) not in self._bound:
            self.warn(node, f"'{name}' of '{node.name}' {problem}", name)
        return fixed

    def color(self, node: Any, name: str, fallback: Rgb, valid: Range) -> Rgb:
        """scalar() for a colour input (its first three components)."""
        c = tuple(float(x) for x in tuple(self.value(node, name, fallback))[:3])
        fixed, problem = clamp_rgb((c[0], c[1], c[2]), valid)
        if problem is not None and (node.name, name) not in self._bound:
            self.warn(node, f"'{name}' of '{node.name}' {problem}", name)
        return fixed

    def emission(self, node: Any, color_name: str, strength_name: str, color_fallback: Rgb,
                 strength_fallback: float) -> Rgb:
        """Emitted radiance: colour x strength, each >= 0, the product at most FLT_MAX."""
        color = self.color(node, color_name, color_fallback, NON_NEGATIVE)
        strength = self.scalar(node, strength_name, strength_fallback, NON_NEGATIVE)
        radiance, limited = finite_product(color, strength)
        if limited:
            self.warn(node, f"'{color_name}' x '{strength_name}' of '{node.name}' exceeds the "
                            "largest float (3.4e38); limited to it", strength_name)
        return radiance

    # ---- what drives a linked input ---------------------------------------------------------

    def texture(self, node: Any, name: str, param: str, bindings: list[Any]) -> None:
        """Records what drives input `name` (closure parameter `param`, an IMAGE_PARAMS key):
        an Image Texture linked directly (or, for Normal, through a tangent-space Normal Map)
        as an image binding, anything else as an input of the material's node program."""
        socket = node.inputs.get(name)
        found = self.source(socket) if socket is not None else None
        if found is None:
            return
        src, out = found
        if param == "normal":
            if src.bl_idname == NORMAL_MAP_NODE and getattr(src, "space", "TANGENT") == "TANGENT":
                image = self.source(src.inputs["Color"])
                # Read (and a bad value warned about) even without an image: the user's value.
                strength = self.scalar(src, "Strength", 1.0, NON_NEGATIVE)
                if image is not None and image[0].bl_idname == IMAGE_NODE:
                    if (blender_versions.normal_map_scales_strength(self.version)
                            and not 0.0 <= strength <= 1.0):
                        # The renderer follows 3.4's interpolation, which agrees with the
                        # scaling of 4.0 and later only for strengths in [0, 1].
                        self.warn(src, f"Normal Map '{src.name}': strength {strength:g} outside "
                                       "[0, 1] renders as Cycles 3.x does")
                    bindings.append(Binding(IMAGE_PARAMS[param], self.image(image[0]), -1,
                                            strength))
                    self.bind(node, name)
                    return
                if image is None:
                    return  # a Normal Map with a constant colour: the flat normal
        elif src.bl_idname == IMAGE_NODE and param not in NATIVE_UNBINDABLE:
            channel = 3 if out.name == "Alpha" else -1
            bindings.append(Binding(IMAGE_PARAMS[param], self.image(src), channel, 1.0, 0.0))
            self.bind(node, name)
            return
        self.program_input(node, name, param, bindings)

    def program_input(self, node: Any, name: str, param: str, bindings: list[Any]) -> None:
        """Drives `param` by what is linked to input `name` (nothing if it is unlinked)."""
        socket = node.inputs.get(name)
        if socket is None or not self.nodes.linked(socket):
            return
        register = self.nodes.value(socket, PROGRAM_KIND[param])
        bindings.append(ProgramInput(param, register))
        self.bind(node, name)

    def emission_program(self, node: Any, color_name: str, strength_name: str,
                         bindings: list[Any]) -> bool:
        """Emission colour x strength computed by the program when either input is linked
        (True then: the constant emission must be 0, see stratum_scene_bind_program)."""
        color = node.inputs.get(color_name)
        strength = node.inputs.get(strength_name)
        if not any(s is not None and self.nodes.linked(s) for s in (color, strength)):
            return False
        c = self.nodes.value(color, "color") if color is not None else \
            self.nodes.builder.constant((1.0, 1.0, 1.0))
        k = self.nodes.value(strength, "float") if strength is not None else \
            self.nodes.builder.constant(1.0)
        bindings.append(ProgramInput("emission", color_times(self.nodes, c, k)))
        return True

    def constant_link(self, node: Any, name: str, param: str | None = None,
                      bindings: list[Any] | None = None) -> None:
        """An input the native closure takes as a constant: driven by the program through
        `param` when one is given with `bindings`, else a warning when it is linked."""
        if param is not None and bindings is not None:
            self.program_input(node, name, param, bindings)
            return
        socket = node.inputs.get(name)
        found = self.source(socket) if socket is not None else None
        if found is not None:
            src = found[0]
            self.warn(src, f"node '{src.name}' ({src.bl_idname}) on '{name}' of '{node.name}' "
                           "is not supported; using the socket's value")
