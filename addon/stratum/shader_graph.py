"""Blender shader node graphs -> weighted closures, as Cycles flattens them (pure Python).

    flat = flatten_surface(surface_socket, blender_version, warn)
    flat.closures, flat.uv_map, flat.program

Cycles evaluates a material's shader tree into a list of closures, each with an RGB weight:
Mix Shader scales its first input by (1 - Fac) and its second by Fac, Add Shader passes its
weight to both inputs, and Principled BSDF with Alpha < 1 is Mix(Transparent, Principled, Alpha)
(intern/cycles/scene/shader_nodes.cpp, PrincipledBsdfNode::compile). This module walks the
same tree into the native contract's closures (stratum.h StratumClosureDesc) plus the image
textures that drive their parameters (StratumTextureBinding).

| Node (bl_idname)               | Closure       | Inputs read (* = texture-bindable)       |
|--------------------------------|---------------|------------------------------------------|
| ShaderNodeBsdfPrincipled, 3.x  | PRINCIPLED_V1 | Base Color*, Metallic*, Roughness*,      |
|                                |               | Specular*, IOR, Transmission, Clearcoat, |
|                                |               | Clearcoat Roughness, Emission x Emission |
|                                |               | Strength, Alpha*, Normal*                |
| ShaderNodeBsdfPrincipled, 4.x+ | PRINCIPLED_V2 | Base Color*, Metallic*, Roughness*, IOR, |
|                                |               | Specular IOR Level*, Transmission Weight,|
|                                |               | Coat Weight/Roughness/IOR/Tint, Emission |
|                                |               | Color x Strength, Alpha*, Normal*        |
| ShaderNodeBsdfDiffuse          | DIFFUSE       | Color*, Normal*                          |
| ShaderNodeBsdfGlossy (3.x) /   | GLOSSY        | Color*, Roughness*, Normal*              |
|   ShaderNodeBsdfAnisotropic    |               |                                          |
| ShaderNodeBsdfGlass            | GLASS         | Color*, Roughness*, IOR, Normal*         |
| ShaderNodeBsdfTransparent      | TRANSPARENT   | Color*                                   |
| ShaderNodeEmission             | EMISSION      | Color x Strength                         |
| ShaderNodeHoldout              | HOLDOUT       |                                          |
| ShaderNodeMixShader, AddShader | (weights)     | Fac (constant or image*)                 |

`*`: an Image Texture node linked directly (Color or Alpha output), or through a Normal Map node
(tangent space) for Normal. Anything else linked to an input: one warning naming the material
and the node, and the socket's own value. A socket value that is NaN or outside what the
renderer takes (stratum.fallbacks: Cycles' own clamps) is replaced, with one warning per node
and socket. This module never imports bpy: nodes are read by duck typing (bl_idname, name,
inputs, outputs, links), so the unit tests use plain objects.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from . import native
from .fallbacks import (
    NON_NEGATIVE,
    UNIT,
    Range,
    clamp,
    clamp_rgb,
    finite_product,
)
from .shader_closures import (
    DEFAULT_GREY,
    VOLUME_NODES,
    Binding,
    Closure,
    ClosureNodes,
    ImageRef,
    ProgramInput,
    Rgb,
)
from .shader_flow import propagate
from .shader_nodes import NodeCompiler
from .shader_nodes.math_nodes import color_times, math_node

IMAGE_NODE = "ShaderNodeTexImage"
NORMAL_MAP_NODE = "ShaderNodeNormalMap"
# Parameters the native contract does not take textures for (stratum.h: emissive triangles are
# light-sampled with a constant emission; transmission waits for a per-material weight).
NATIVE_UNBINDABLE = frozenset({native.PARAM_EMISSION, native.PARAM_TRANSMISSION})


@dataclass(frozen=True)
class _Key:
    """A shader node as the walk meets it: by name (unique in its tree), with the image weight
    of the image-driven Mix Shader above it, if any, and the program register holding the
    product of the node-driven Mix factors above it, if any. The node itself is carried, not
    compared."""

    name: str
    node: Any = field(compare=False)
    binding: Binding | None = None
    program_weight: int | None = None


class Flattener(ClosureNodes):
    """Walks one material's surface tree. `warn(node, message)` is called at most once per
    node and subject (a socket, or the node itself; the caller prefixes the material name)."""

    def __init__(self, version: tuple[int, int, int], warn: Callable[[Any, str], None],
                 attribute_slot: Callable[[str], int | None] | None = None) -> None:
        self.version = version
        self._warn = warn
        self._warned: set[tuple[str, str]] = set()
        self._program_weight: int | None = None  # of the closure node being emitted
        self._bound: set[tuple[str, str]] = set()  # (node, socket) driven by a texture
        self.closures: list[Closure] = []
        # The material's node program: every linked input that is not a plain image binding.
        self.nodes = NodeCompiler(version, lambda node, message: self.warn(node, message),
                                  attribute_slot=attribute_slot)

    # ---- warnings and socket reading ------------------------------------------------------

    def warn(self, node: Any, message: str, subject: str = "") -> None:
        key = (getattr(node, "name", str(id(node))), subject)
        if key in self._warned:
            return
        self._warned.add(key)
        self._warn(node, message)

    def _source(self, socket: Any) -> tuple[Any, Any] | None:
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

    def _image(self, image_node: Any) -> ImageRef:
        """The UV layer an Image Texture reads, from its Vector input."""
        found = self._source(image_node.inputs["Vector"])
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
        unless a texture drives the input (then the value is not used)."""
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

    def texture(self, node: Any, name: str, param: int, bindings: list[Any]) -> None:
        """Records what drives input `name`: an Image Texture linked directly (or, for Normal,
        through a tangent-space Normal Map) as an image binding, anything else as an input of
        the material's node program (a ProgramInput)."""
        socket = node.inputs.get(name)
        found = self._source(socket) if socket is not None else None
        if found is None:
            return
        src, out = found
        if param == native.PARAM_NORMAL:
            if src.bl_idname == NORMAL_MAP_NODE and getattr(src, "space", "TANGENT") == "TANGENT":
                image = self._source(src.inputs["Color"])
                # Read (and a bad value warned about) even without an image: the user's value.
                strength = self.scalar(src, "Strength", 1.0, NON_NEGATIVE)
                if image is not None and image[0].bl_idname == IMAGE_NODE:
                    if self.version >= (4, 0, 0) and not 0.0 <= strength <= 1.0:
                        # Cycles 4.x+ scales the tangent-space normal; the renderer follows
                        # 3.4's lerp, which agrees only for strengths in [0, 1].
                        self.warn(src, f"Normal Map '{src.name}': strength {strength:g} outside "
                                       "[0, 1] renders as Cycles 3.x does")
                    bindings.append(Binding(param, self._image(image[0]), -1, strength))
                    self._bound.add((node.name, name))
                    return
                if image is None:
                    return  # a Normal Map with a constant colour: the flat normal
        elif src.bl_idname == IMAGE_NODE and param not in NATIVE_UNBINDABLE:
            channel = 3 if out.name == "Alpha" else -1
            bindings.append(Binding(param, self._image(src), channel, 1.0, 0.0))
            self._bound.add((node.name, name))
            return
        self.program_input(node, name, PROGRAM_PARAM[param], bindings)

    def program_input(self, node: Any, name: str, param: str, bindings: list[Any]) -> None:
        """Drives `param` by what is linked to input `name` (nothing if it is unlinked)."""
        socket = node.inputs.get(name)
        if socket is None or not self.nodes.linked(socket):
            return
        register = self.nodes.value(socket, PROGRAM_KIND[param])
        bindings.append(ProgramInput(param, register))
        self._bound.add((node.name, name))

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

    def unsupported_link(self, node: Any, name: str, bindings: list[Any] | None = None) -> None:
        """An input the native closure takes as a constant: driven by the program when it has a
        program parameter (CONSTANT_PARAMS) and `bindings` is given, else a warning when it is
        linked."""
        param = CONSTANT_PARAMS.get(name)
        if param is not None and bindings is not None:
            self.program_input(node, name, param, bindings)
            return
        socket = node.inputs.get(name)
        found = self._source(socket) if socket is not None else None
        if found is not None:
            src = found[0]
            self.warn(src, f"node '{src.name}' ({src.bl_idname}) on '{name}' of '{node.name}' "
                           "is not supported; using the socket's value")

    # ---- the walk ---------------------------------------------------------------------------

    def walk(self, socket: Any, weight: Rgb) -> None:
        """Closures of the tree feeding `socket`, scaled by `weight`.

        The tree is walked as the graph it is, as Cycles compiles each node once: every
        (node, image weight) pair is visited once with the sum of the weights of the paths
        reaching it (stratum.shader_flow), so nesting depth and shared inputs cost nothing
        extra. A tree without sharing gives its closures left to right, each weight the product
        of the factors along its path."""
        root = self._visit(socket, None)
        if root is None:
            return
        order, weights = propagate(root, weight, self._inputs, self._cut_cycle)
        for key in order:
            if not _is_combiner(key.node):
                self._leaf(key, weights[key])

    def _cut_cycle(self, child: _Key, parent: _Key) -> None:
        self.warn(child.node, f"node '{child.name}' feeds itself through '{parent.name}' (a "
                              "cycle); that link is ignored", "cycle")

    def _visit(self, socket: Any, binding: Binding | None,
               program_weight: int | None = None) -> _Key | None:
        """The (node, image weight, program weight) feeding `socket`; None for nothing
        (unlinked: Cycles adds no closure; muted: rendered as nothing, with a warning)."""
        found = self._source(socket)
        if found is None:
            return None
        node = found[0]
        if getattr(node, "mute", False):
            self.warn(node, f"muted node '{node.name}' is rendered as nothing")
            return None
        return _Key(node.name, node, binding, program_weight)

    def _inputs(self, key: _Key) -> list[tuple[_Key, float]]:
        """The shader inputs of a Mix or Add Shader with the factor each scales its weight by
        (Mix: 1 - Fac and Fac; an image Fac moves into the inputs' image weights); [] for a
        closure node."""
        node, binding, weight = key.node, key.binding, key.program_weight
        kind = node.bl_idname
        pairs: list[tuple[Any, float, Binding | None, int | None]] = []
        if kind == "ShaderNodeAddShader":
            pairs = [(node.inputs[0], 1.0, binding, weight), (node.inputs[1], 1.0, binding, weight)]
        elif kind == "ShaderNodeMixShader":
            pairs = self._mix_inputs(node, binding, weight)
        found = ((self._visit(socket, b, w), f) for socket, f, b, w in pairs)
        return [(child, f) for child, f in found if child is not None]

    def _times(self, weight: int | None, factor: int) -> int:
        """Program register of weight x factor (factor alone without a weight)."""
        if weight is None:
            return factor
        return math_node(self.nodes, weight, factor, self.nodes.builder.constant(0.0), "MULTIPLY")

    def _mix_inputs(self, node: Any, binding: Binding | None,
                    weight: int | None) -> list[tuple[Any, float, Binding | None, int | None]]:
        fac_socket = node.inputs[0]
        found = self._source(fac_socket)
        if found is not None and found[0].bl_idname != IMAGE_NODE:
            # A node-driven factor: the program computes saturate(Fac) and 1 - saturate(Fac), as
            # Cycles' svm_node_mix_closure; nested mixes multiply.
            self._bound.add((node.name, fac_socket.name))
            fac = self.nodes.value(fac_socket, "float")
            zero, one = self.nodes.builder.constant(0.0), self.nodes.builder.constant(1.0)
            saturated = math_node(self.nodes, fac, one, zero, "MULTIPLY", clamp=True)
            rest = math_node(self.nodes, one, saturated, zero, "SUBTRACT")
            return [(node.inputs[1], 1.0, binding, self._times(weight, rest)),
                    (node.inputs[2], 1.0, binding, self._times(weight, saturated))]
        if found is not None and found[0].bl_idname == IMAGE_NODE:
            if binding is None:
                channel = 3 if found[1].name == "Alpha" else -1
                image = self._image(found[0])
                # first input x (1 - fac), second x fac (fac from the image, per shading point)
                return [(node.inputs[1], 1.0, Binding(native.PARAM_WEIGHT, image, channel, -1.0,
                                                      1.0), weight),
                        (node.inputs[2], 1.0, Binding(native.PARAM_WEIGHT, image, channel, 1.0,
                                                      0.0), weight)]
            self.warn(node, f"Mix Shader '{node.name}': an image factor inside another "
                            "image-driven mix is not supported; using its Fac value")
        fac = self.scalar(node, fac_socket.name, 0.5, UNIT)
        return [(node.inputs[1], 1.0 - fac, binding, weight),
                (node.inputs[2], fac, binding, weight)]

    def _leaf(self, key: _Key, weight: Rgb) -> None:
        """The closures of one shader node that is not a Mix or Add Shader."""
        node, binding = key.node, key.binding
        self._program_weight = key.program_weight
        kind = node.bl_idname
        if kind == "ShaderNodeBsdfPrincipled":
            self._principled(node, weight, binding)
        elif kind in VOLUME_NODES:
            # Cycles evaluates volume closures in volume shaders only (svm_node_closure_volume
            # returns for a surface), so on a surface input they add nothing.
            self.warn(node, f"volume shader '{node.name}' ({kind}) on a surface input adds "
                            "nothing, as in Cycles")
        else:
            made = self._simple(node)
            if made is None:
                self.warn(node, f"shader node '{node.name}' ({kind}) is not supported; using a "
                                "default Principled BSDF")
                made = (self._default_principled(), [])
            self._emit(weight, binding, *made)

    def _emit(self, weight: Rgb, weight_binding: Binding | None, material: native.Material,
              bindings: list[Any], program_weight: int | None = None) -> None:
        """Adds a closure; `program_weight` (a scalar register) multiplies its weight, after
        the Mix factors above it (self._program_weight)."""
        factor = self._program_weight
        if program_weight is not None:
            factor = self._times(factor, program_weight)
        if weight_binding is None and factor is None and max(weight) <= 0.0:
            return  # Cycles drops closures of zero weight
        images = [b for b in bindings if isinstance(b, Binding)]
        programs = [b for b in bindings if isinstance(b, ProgramInput)]
        if weight_binding is not None:
            images.append(weight_binding)
        if factor is not None:
            programs.append(ProgramInput("weight", self.nodes.builder.broadcast(factor)))
        self.closures.append(Closure(weight, material, images, programs))

    def _default_principled(self) -> native.Material:
        v2 = self.version >= (4, 0, 0)
        return native.Material(
            model=native.closure_model("principled_v2" if v2 else "principled_v1"),
            base_color=DEFAULT_GREY, roughness=0.5, specular=0.5, ior=1.5 if v2 else 1.45,
            distribution=native.MICROFACET_MULTISCATTER_GGX if v2 else native.MICROFACET_GGX)


# Texture-bindable parameters and the program parameter a non-image link drives instead.
PROGRAM_PARAM = {
    native.PARAM_BASE_COLOR: "base_color", native.PARAM_ROUGHNESS: "roughness",
    native.PARAM_METALLIC: "metallic", native.PARAM_NORMAL: "normal",
    native.PARAM_EMISSION: "emission", native.PARAM_WEIGHT: "weight",
    native.PARAM_TRANSMISSION: "transmission", native.PARAM_SPECULAR: "specular",
}
# What each program parameter reads from its socket.
PROGRAM_KIND = {
    "base_color": "color", "roughness": "float", "metallic": "float", "normal": "vector",
    "emission": "color", "weight": "float", "transmission": "float", "specular": "float",
    "ior": "float", "coat": "float", "coat_roughness": "float", "coat_tint": "color",
}
# Inputs the closures take as constants that a program may drive (both generations' names).
CONSTANT_PARAMS = {
    "IOR": "ior", "Clearcoat": "coat", "Clearcoat Roughness": "coat_roughness",
    "Coat Weight": "coat", "Coat Roughness": "coat_roughness",
    "Coat Tint": "coat_tint",
}

def _is_combiner(node: Any) -> bool:
    return node.bl_idname in ("ShaderNodeMixShader", "ShaderNodeAddShader")


@dataclass
class FlatSurface:
    """A surface tree flattened: its closures, the UV layer its image bindings read ("" = the
    active render layer), and the node program its ProgramInputs read (None if it has none)
    with the Image Texture nodes that program reads (its IMAGE nodes' mode 0 indexes them)."""

    closures: list[Closure]
    uv_map: str = ""
    program: native.ShaderProgram | None = None
    program_images: list[Any] = field(default_factory=list)


def flatten_surface(surface: Any, version: tuple[int, int, int],
                    warn: Callable[[Any, str], None],
                    attribute_slot: Callable[[str], int | None] | None = None) -> FlatSurface:
    """The closures of the tree linked to `surface` (a Material Output's Surface input).
    Textures reading different UV maps: one warning, the first map wins (the native mesh
    carries one UV set)."""
    flattener = Flattener(version, warn, attribute_slot)
    flattener.walk(surface, (1.0, 1.0, 1.0))
    uv_maps = [b.image.uv_map for c in flattener.closures for b in c.bindings]
    uv_map = uv_maps[0] if uv_maps else ""
    for b in (b for c in flattener.closures for b in c.bindings):
        if b.image.uv_map != uv_map:
            flattener.warn(b.image.node, f"Image Texture '{b.image.node.name}' reads UV map "
                                         f"'{b.image.uv_map or 'active'}' but the material "
                                         f"already uses '{uv_map or 'active'}'; using the latter")
    uses_program = any(c.programs for c in flattener.closures)
    program = flattener.nodes.builder.program if uses_program else None
    return FlatSurface(flattener.closures, uv_map, program,
                       list(flattener.nodes.images) if uses_program else [])
