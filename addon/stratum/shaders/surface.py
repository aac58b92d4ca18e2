"""Blender shader node graphs -> weighted closures, as Cycles flattens them (pure Python).

    flat = flatten_surface(surface_socket, blender_version, warn)
    flat.closures, flat.uv_map, flat.program

Cycles evaluates a material's shader tree into a list of closures, each with an RGB weight:
Mix Shader scales its first input by (1 - Fac) and its second by Fac, Add Shader passes its
weight to both inputs, and Principled BSDF with Alpha < 1 is Mix(Transparent, Principled, Alpha)
(intern/cycles/scene/shader_nodes.cpp, PrincipledBsdfNode::compile). This module walks the
same tree into the native contract's closures (stratum.h StratumClosureDesc) plus the image
textures that drive their parameters (StratumTextureBinding).

Three parts: this module walks the Mix and Add Shaders (Flattener), stratum.shaders.closures
makes the closures of the nodes it reaches (ClosureBuilder), and stratum.shaders.inputs reads
their inputs (InputReader), which stratum.shaders.nodes compiles into the node program when
something other than an image drives them.

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
renderer takes (stratum.shaders.fallbacks: Cycles' own clamps) is replaced, with one warning per
node and socket. This module never imports bpy: nodes are read by duck typing (bl_idname, name,
inputs, outputs, links), so the unit tests use plain objects.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from .. import native
from .closures import ClosureBuilder, program_product
from .fallbacks import UNIT
from .flow import propagate
from .inputs import IMAGE_NODE, InputReader
from .nodes.math_nodes import math_node
from .records import Binding, Closure, ClosureWeight, Rgb


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


class Flattener:
    """Walks one material's surface tree. `warn(node, message)` is called at most once per
    node and subject (a socket, or the node itself; the caller prefixes the material name)."""

    def __init__(self, version: tuple[int, int, int], warn: Callable[[Any, str], None],
                 attribute_slot: Callable[[str], int | None] | None = None) -> None:
        self.inputs = InputReader(version, warn, attribute_slot)
        self.nodes = self.inputs.nodes
        self.builder = ClosureBuilder(self.inputs)

    def walk(self, socket: Any, weight: Rgb) -> None:
        """Closures of the tree feeding `socket`, scaled by `weight`.

        The tree is walked as the graph it is, as Cycles compiles each node once: every
        (node, image weight) pair is visited once with the sum of the weights of the paths
        reaching it (stratum.shaders.flow), so nesting depth and shared inputs cost nothing
        extra. A tree without sharing gives its closures left to right, each weight the product
        of the factors along its path."""
        root = self._visit(socket, None)
        if root is None:
            return
        order, weights = propagate(root, weight, self._inputs, self._cut_cycle)
        for key in order:
            if not _is_combiner(key.node):
                self.builder.add(key.node, ClosureWeight(weights[key], key.binding,
                                                         key.program_weight))

    def _cut_cycle(self, child: _Key, parent: _Key) -> None:
        self.inputs.warn(child.node, f"node '{child.name}' feeds itself through '{parent.name}' "
                                     "(a cycle); that link is ignored", "cycle")

    def _visit(self, socket: Any, binding: Binding | None,
               program_weight: int | None = None) -> _Key | None:
        """The (node, image weight, program weight) feeding `socket`; None for nothing
        (unlinked: Cycles adds no closure; muted: rendered as nothing, with a warning)."""
        found = self.inputs.source(socket)
        if found is None:
            return None
        node = found[0]
        if getattr(node, "mute", False):
            self.inputs.warn(node, f"muted node '{node.name}' is rendered as nothing")
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

    def _mix_inputs(self, node: Any, binding: Binding | None,
                    weight: int | None) -> list[tuple[Any, float, Binding | None, int | None]]:
        fac_socket = node.inputs[0]
        found = self.inputs.source(fac_socket)
        if found is not None and found[0].bl_idname != IMAGE_NODE:
            # A node-driven factor: the program computes saturate(Fac) and 1 - saturate(Fac), as
            # Cycles' svm_node_mix_closure; nested mixes multiply.
            self.inputs.bind(node, fac_socket.name)
            fac = self.nodes.value(fac_socket, "float")
            zero, one = self.nodes.builder.constant(0.0), self.nodes.builder.constant(1.0)
            saturated = math_node(self.nodes, fac, one, zero, "MULTIPLY", clamp=True)
            rest = math_node(self.nodes, one, saturated, zero, "SUBTRACT")
            return [(node.inputs[1], 1.0, binding, program_product(self.nodes, weight, rest)),
                    (node.inputs[2], 1.0, binding, program_product(self.nodes, weight, saturated))]
        if found is not None and found[0].bl_idname == IMAGE_NODE:
            if binding is None:
                channel = 3 if found[1].name == "Alpha" else -1
                image = self.inputs.image(found[0])
                # first input x (1 - fac), second x fac (fac from the image, per shading point)
                return [(node.inputs[1], 1.0, Binding(native.PARAM_WEIGHT, image, channel, -1.0,
                                                      1.0), weight),
                        (node.inputs[2], 1.0, Binding(native.PARAM_WEIGHT, image, channel, 1.0,
                                                      0.0), weight)]
            self.inputs.warn(node, f"Mix Shader '{node.name}': an image factor inside another "
                                   "image-driven mix is not supported; using its Fac value")
        fac = self.inputs.scalar(node, fac_socket.name, 0.5, UNIT)
        return [(node.inputs[1], 1.0 - fac, binding, weight),
                (node.inputs[2], fac, binding, weight)]


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
    # The program's Tangent nodes in UV-map mode: node name -> UV map named (NodeCompiler).
    uv_tangent_maps: dict[str, str] = field(default_factory=dict)


def flatten_surface(surface: Any, version: tuple[int, int, int],
                    warn: Callable[[Any, str], None],
                    attribute_slot: Callable[[str], int | None] | None = None) -> FlatSurface:
    """The closures of the tree linked to `surface` (a Material Output's Surface input).
    Textures reading different UV maps: one warning, the first map wins (the native mesh
    carries one UV set)."""
    flattener = Flattener(version, warn, attribute_slot)
    flattener.walk(surface, (1.0, 1.0, 1.0))
    closures = flattener.builder.closures
    uv_maps = [b.image.uv_map for c in closures for b in c.bindings]
    uv_map = uv_maps[0] if uv_maps else ""
    for b in (b for c in closures for b in c.bindings):
        if b.image.uv_map != uv_map:
            flattener.inputs.warn(b.image.node, f"Image Texture '{b.image.node.name}' reads UV "
                                                f"map '{b.image.uv_map or 'active'}' but the "
                                                f"material already uses '{uv_map or 'active'}'; "
                                                "using the latter")
    uses_program = any(c.programs for c in closures)
    program = flattener.nodes.builder.program if uses_program else None
    return FlatSurface(closures, uv_map, program,
                       list(flattener.nodes.images) if uses_program else [],
                       dict(flattener.nodes.uv_tangent_maps) if uses_program else {})
