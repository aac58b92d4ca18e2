"""Materials: NaN, infinite (RNA stores FLT_MAX) and out-of-range socket values, IOR 0,
emission up to FLT_MAX, missing or empty node trees, unsupported and volume shaders, deep and
cyclic node graphs. A bad value is a WARNING naming the material and the socket, and the render
finishes with a documented fallback (issue 12, point 3)."""

from __future__ import annotations

import math
from typing import Any

import bpy

from .case import case, clean, lit_centre, survive, warning
from .stage import Stage, emission_color_socket

NAN = float("nan")


def _principled_cube(s: Stage, name: str, socket: str, value: Any) -> None:
    """The base scene whose cube has a Principled material `name` with `socket` = value."""
    s.base(cube=False)
    mat, principled = s.material(name)
    principled.inputs[socket].default_value = value
    s.mesh("Cube", material=mat)


def _socket_case(name: str, what: str, material: str, socket: str, value: Any,
                 words: tuple[str, ...]) -> None:
    case(name, "materials", what, warning(material, words=words))(
        lambda s: _principled_cube(s, material, socket, value))


_socket_case("mat_nan_base_color", "Principled Base Color NaN (became grey silently)",
             "NanColour", "Base Color", (NAN, NAN, NAN, 1.0), ("Base Color",))
_socket_case("mat_inf_base_color", "Principled Base Color inf (FLT_MAX): an albedo of 3e38",
             "HotColour", "Base Color", (math.inf, 0.5, 0.5, 1.0), ("Base Color",))
_socket_case("mat_nan_roughness", "Principled Roughness NaN (became 0.5 silently)",
             "NanRough", "Roughness", NAN, ("Roughness",))
_socket_case("mat_negative_roughness", "Principled Roughness -1", "NegRough", "Roughness", -1.0,
             ("Roughness",))
_socket_case("mat_nan_metallic", "Principled Metallic NaN", "NanMetal", "Metallic", NAN,
             ("Metallic",))
_socket_case("mat_nan_ior", "Principled IOR NaN", "NanIor", "IOR", NAN, ("IOR",))
_socket_case("mat_zero_ior", "Principled IOR 0 (became 0.001 silently)", "ZeroIor", "IOR", 0.0,
             ("IOR",))
_socket_case("mat_nan_alpha", "Principled Alpha NaN", "NanAlpha", "Alpha", NAN, ("Alpha",))
_socket_case("mat_nan_emission_strength", "Principled Emission Strength NaN (became 1)",
             "NanGlow", "Emission Strength", NAN, ("Emission Strength", "Strength"))
_socket_case("mat_negative_emission_strength", "Principled Emission Strength -1 (became 0)",
             "NegGlow", "Emission Strength", -1.0, ("Emission Strength", "Strength"))


@case("mat_nan_emission_color", "materials", "Principled emission colour NaN (became white)",
      warning("NanEmitColour", words=("Emission",)))
def mat_nan_emission_color(s: Stage) -> None:
    _principled_cube(s, "NanEmitColour", emission_color_socket(), (NAN, NAN, NAN, 1.0))
    bpy.data.materials["NanEmitColour"].node_tree.nodes["Principled BSDF"].inputs[
        "Emission Strength"].default_value = 1.0


def _emitter(s: Stage, name: str, strength: float) -> None:
    """The base scene without lamp or world: only the cube, emitting white at `strength`."""
    s.camera()
    mat, node = s.shader_material(name, "ShaderNodeEmission")
    node.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    node.inputs["Strength"].default_value = strength
    s.mesh("Cube", material=mat)
    s.mesh("Floor", location=(0.0, 0.0, -1.5), scale=(4.0, 4.0, 0.1))


@case("mat_emission_3e38", "materials",
      "an Emission shader of strength 3e38 (accepted as <= FLT_MAX, gave Inf pixels)",
      clean(pixels=lit_centre))
def mat_emission_3e38(s: Stage) -> None:
    _emitter(s, "Blinding", 3e38)


@case("mat_emission_flt_max_principled", "materials",
      "Principled emission colour and strength both FLT_MAX (their product overflows)",
      survive("Overflow", words=("emission",), pixels=lit_centre))
def mat_emission_flt_max_principled(s: Stage) -> None:
    s.camera()
    mat, principled = s.material("Overflow")
    principled.inputs[emission_color_socket()].default_value = (math.inf, math.inf, math.inf, 1)
    principled.inputs["Emission Strength"].default_value = math.inf
    s.mesh("Cube", material=mat)


@case("mat_emission_node_nan_strength", "materials", "an Emission shader of strength NaN",
      warning("NanEmitter", words=("Strength",)))
def mat_emission_node_nan_strength(s: Stage) -> None:
    _emitter(s, "NanEmitter", NAN)


@case("mat_glass_zero_ior", "materials", "a Glass BSDF with IOR 0",
      warning("ZeroGlass", words=("IOR",)))
def mat_glass_zero_ior(s: Stage) -> None:
    s.base(cube=False)
    mat, node = s.shader_material("ZeroGlass", "ShaderNodeBsdfGlass")
    node.inputs["IOR"].default_value = 0.0
    s.mesh("Cube", material=mat)


@case("mat_nan_mix_factor", "materials", "a Mix Shader whose Fac is NaN",
      warning("NanMix", words=("Fac",)))
def mat_nan_mix_factor(s: Stage) -> None:
    s.base(cube=False)
    mat, mix = s.shader_material("NanMix", "ShaderNodeMixShader")
    nt = mat.node_tree
    mix.inputs["Fac"].default_value = NAN
    nt.links.new(nt.nodes.new("ShaderNodeBsdfDiffuse").outputs[0], mix.inputs[1])
    nt.links.new(nt.nodes.new("ShaderNodeEmission").outputs[0], mix.inputs[2])
    s.mesh("Cube", material=mat)


@case("mat_nan_normal_map_strength", "materials", "a Normal Map node of strength NaN",
      warning("NanBump", words=("Strength", "Normal Map")))
def mat_nan_normal_map_strength(s: Stage) -> None:
    s.base(cube=False)
    mat, principled = s.material("NanBump")
    nt = mat.node_tree
    normal_map = nt.nodes.new("ShaderNodeNormalMap")
    normal_map.inputs["Strength"].default_value = NAN
    nt.links.new(normal_map.outputs["Normal"], principled.inputs["Normal"])
    s.mesh("Cube", material=mat).data.uv_layers.new(name="UVMap")


# 3.4 renders the material's viewport colour; 5.0 has no such thing, so its tree is emptied
# instead, which Cycles renders black (measured in 5.0.1), as Stratum does since issue 18.
@case("mat_without_nodes", "materials",
      "a material not using nodes (3.4; 5.0 has no such thing: its tree is emptied instead)",
      clean(pixels=lit_centre if bpy.app.version < (5, 0, 0) else None))
def mat_without_nodes(s: Stage) -> None:
    s.base(cube=False)
    mat, _ = s.material("Plain")
    mat.diffuse_color = (0.8, 0.2, 0.2, 1.0)
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = False
    else:
        mat.node_tree.nodes.clear()
    s.mesh("Cube", material=mat)


@case("mat_empty_node_tree", "materials", "a node material whose nodes were all deleted",
      clean())
def mat_empty_node_tree(s: Stage) -> None:
    s.base(cube=False)
    mat, _ = s.material("Emptied")
    mat.node_tree.nodes.clear()
    s.mesh("Cube", material=mat)


@case("mat_empty_slot", "materials", "an object with an empty material slot",
      clean(quiet=True, pixels=lit_centre))
def mat_empty_slot(s: Stage) -> None:
    s.base(cube=False)
    s.mesh("Cube").data.materials.append(None)


@case("mat_image_node_without_image", "materials", "an Image Texture node with no image",
      clean())
def mat_image_node_without_image(s: Stage) -> None:
    s.base(cube=False)
    mat = s.image_material("NoImage", None)
    s.mesh("Cube", material=mat).data.uv_layers.new(name="UVMap")


@case("mat_unsupported_node", "materials", "a Toon BSDF on the surface",
      warning("Cartoon", words=("Toon",)))
def mat_unsupported_node(s: Stage) -> None:
    s.base(cube=False)
    mat, _ = s.shader_material("Cartoon", "ShaderNodeBsdfToon")
    s.mesh("Cube", material=mat)


@case("mat_volume_scatter", "materials",
      "Volume Scatter on the Volume output, no surface (was 'no shader connected')",
      warning("Smoky", words=("volume",)))
def mat_volume_scatter(s: Stage) -> None:
    s.base(cube=False)
    mat, _ = s.shader_material("Smoky", "ShaderNodeVolumeScatter", output="Volume")
    s.mesh("Cube", material=mat)


@case("mat_principled_volume", "materials", "Principled Volume on the Volume output",
      warning("Cloudy", words=("volume",)))
def mat_principled_volume(s: Stage) -> None:
    s.base(cube=False)
    mat, _ = s.shader_material("Cloudy", "ShaderNodeVolumePrincipled", output="Volume")
    s.mesh("Cube", material=mat)


# Deeper than a recursive graph walk survives under Python's default recursion limit of 1000
# (the exporter's failed at about 450 levels: "internal error: RecursionError"); building it
# costs about a second (node creation is quadratic in Blender).
DEEP_CHAIN = 600


@case("mat_deep_mix_chain", "materials",
      f"{DEEP_CHAIN} Mix Shaders nested in a chain, a Diffuse BSDF at the bottom",
      clean(pixels=lit_centre))
def mat_deep_mix_chain(s: Stage) -> None:
    s.base(cube=False)
    mat, principled = s.material("Nested")
    nt = mat.node_tree
    below = principled.outputs[0]
    for _ in range(DEEP_CHAIN):
        mix = nt.nodes.new("ShaderNodeMixShader")
        mix.inputs["Fac"].default_value = 0.0
        nt.links.new(below, mix.inputs[1])
        below = mix.outputs[0]
    nt.links.new(below, nt.nodes["Material Output"].inputs["Surface"])
    s.mesh("Cube", material=mat)


# A Mix Shader taking the one below on both inputs: the weight stays 1 at every level, but there
# are 2^SHARED_CHAIN paths to the bottom BSDF; a walk per path would never finish.
SHARED_CHAIN = 40


@case("mat_shared_mix_chain", "materials",
      f"{SHARED_CHAIN} Mix Shaders, each taking the one below on both inputs (2^{SHARED_CHAIN} "
      "paths)", clean(pixels=lit_centre))
def mat_shared_mix_chain(s: Stage) -> None:
    s.base(cube=False)
    mat, principled = s.material("Shared")
    nt = mat.node_tree
    below = principled.outputs[0]
    for _ in range(SHARED_CHAIN):
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(below, mix.inputs[1])
        nt.links.new(below, mix.inputs[2])
        below = mix.outputs[0]
    nt.links.new(below, nt.nodes["Material Output"].inputs["Surface"])
    s.mesh("Cube", material=mat)


@case("mat_node_cycle", "materials", "two Mix Shaders feeding each other (a cycle)", clean())
def mat_node_cycle(s: Stage) -> None:
    s.base(cube=False)
    mat, first = s.shader_material("Loop", "ShaderNodeMixShader")
    nt = mat.node_tree
    second = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(second.outputs[0], first.inputs[1])
    nt.links.new(first.outputs[0], second.inputs[1])
    s.mesh("Cube", material=mat)
