"""Noise and Musgrave translators (stratum.shaders.nodes.noise_textures) on stand-ins for both
Blender generations' nodes: the native modes, which sockets feed which registers, warnings for
what cannot be translated, and one evaluation through the native library."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from stratum import native
from stratum.blender_versions import noise_generation
from stratum.shaders.nodes import NodeCompiler

GENERATED = native.SHADER_INPUTS["generated"][0]


class Socket:
    def __init__(self, name: str, default_value: Any = 0.0, type_: str = "VALUE",
                 enabled: bool = True) -> None:
        self.name = self.identifier = name
        self.default_value = default_value
        self.type = type_
        self.enabled = enabled
        self.links: list[Any] = []

    @property
    def is_linked(self) -> bool:
        return bool(self.links)


class Link:
    def __init__(self, from_node: Any, from_socket: Socket) -> None:
        self.from_node, self.from_socket = from_node, from_socket


class Node:
    def __init__(self, bl_idname: str, name: str, inputs: list[Socket], outputs: list[Socket],
                 **props: Any) -> None:
        self.bl_idname, self.name = bl_idname, name
        self.inputs, self.outputs = inputs, outputs
        self.mute = False
        for k, v in props.items():
            setattr(self, k, v)


def noise_node(version: tuple[int, int, int], **props: Any) -> Node:
    """A Noise Texture with the sockets `version` has (listed from Blender 3.4 and 5.0)."""
    inputs = [Socket("Vector", (0.0, 0.0, 0.0), "VECTOR"), Socket("W", 0.0), Socket("Scale", 5.0),
              Socket("Detail", 2.0), Socket("Roughness", 0.5)]
    if version >= (4, 0):
        inputs.append(Socket("Lacunarity", 2.0))
    if version >= (4, 1):
        inputs += [Socket("Offset", 0.0), Socket("Gain", 1.0)]
    inputs.append(Socket("Distortion", 0.0))
    outputs = [Socket("Fac"), Socket("Color", type_="RGBA")]
    return Node("ShaderNodeTexNoise", "Noise", inputs, outputs, **props)


def musgrave_node(**props: Any) -> Node:
    inputs = [Socket("Vector", (0.0, 0.0, 0.0), "VECTOR"), Socket("W", 0.0), Socket("Scale", 5.0),
              Socket("Detail", 2.0), Socket("Dimension", 2.0), Socket("Lacunarity", 2.0),
              Socket("Offset", 0.0), Socket("Gain", 1.0)]
    return Node("ShaderNodeTexMusgrave", "Musgrave", inputs, [Socket("Fac")], **props)


def read(node: Node, output: str, version: tuple[int, int, int]
         ) -> tuple[NodeCompiler, int, list[str]]:
    """Compiles what an Emission colour linked to `output` of `node` reads."""
    warnings: list[str] = []
    c = NodeCompiler(version, lambda n, msg: warnings.append(msg))
    out = next(s for s in node.outputs if s.name == output)
    target = Socket("Color", (0.0, 0.0, 0.0, 1.0), "RGBA")
    target.links = [Link(node, out)]
    out.links = [Link(node, out)]  # the output is read (is_linked)
    return c, c.value(target, "color"), warnings


def only_node(c: NodeCompiler, kind: int) -> native.ShaderNode:
    nodes = [n for n in c.builder.program.nodes if n.type == kind]
    assert len(nodes) == 1
    return nodes[0]


@pytest.mark.parametrize(("version", "generation"), [
    ((3, 4, 1), 0), ((3, 6, 0), 0), ((4, 0, 2), 1), ((4, 1, 0), 2), ((4, 2, 0), 3), ((5, 0, 0), 3)])
def test_generation_follows_the_blender_version(version: tuple[int, int, int],
                                                generation: int) -> None:
    assert noise_generation(version) == generation


def test_blender_3_noise_reads_its_sockets_and_defaults_the_new_ones() -> None:
    node = noise_node((3, 4, 1), noise_dimensions="4D")
    node.inputs[3].default_value = 4.5  # Detail
    c, _, warnings = read(node, "Fac", (3, 4, 1))
    assert not warnings
    n = only_node(c, native.node_type("noise"))
    assert n.modes == (3, 1, 1, 0, 0)  # 4D, fBM, normalised, Blender 3, no colour
    regs = c.builder.program.registers
    assert n.inputs[0] == GENERATED  # an unlinked Vector is the Generated coordinate
    assert [regs[i] for i in n.inputs[2:9]] == [5.0, 4.5, 0.5, 2.0, 0.0, 1.0, 0.0]


def test_blender_5_noise_types_and_normalize() -> None:
    node = noise_node((5, 0, 0), noise_dimensions="2D", noise_type="HETERO_TERRAIN",
                      normalize=False)
    node.inputs[6].default_value = 0.75  # Offset
    c, _, warnings = read(node, "Color", (5, 0, 0))
    assert not warnings
    n = only_node(c, native.node_type("noise"))
    assert n.modes == (1, 4, 0, 3, 1)  # 2D, hetero terrain, not normalised, 4.2+, colour read
    assert c.builder.program.registers[n.inputs[6]] == 0.75
    # W is not read in 2D (a constant 0 stands in).
    assert c.builder.program.registers[n.inputs[1]] == 0.0


@pytest.mark.parametrize("kind", ["MULTIFRACTAL", "FBM", "HYBRID_MULTIFRACTAL",
                                  "RIDGED_MULTIFRACTAL", "HETERO_TERRAIN"])
def test_musgrave_types_map_to_cycles_order(kind: str) -> None:
    order = ["MULTIFRACTAL", "FBM", "HYBRID_MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HETERO_TERRAIN"]
    c, _, warnings = read(musgrave_node(musgrave_dimensions="1D", musgrave_type=kind), "Fac",
                          (3, 4, 1))
    assert not warnings
    assert only_node(c, native.node_type("musgrave")).modes == (0, order.index(kind))


def test_unknown_modes_warn_and_use_the_socket_value() -> None:
    c, _, warnings = read(noise_node((5, 0, 0), noise_dimensions="5D"), "Fac", (5, 0, 0))
    assert len(warnings) == 1 and "dimensions 5D" in warnings[0]
    assert not [n for n in c.builder.program.nodes if n.type == native.node_type("noise")]
    c, _, warnings = read(musgrave_node(musgrave_type="SPIKY"), "Fac", (3, 4, 1))
    assert len(warnings) == 1 and "SPIKY" in warnings[0]


def test_linked_w_feeds_1d_noise() -> None:
    value = Node("ShaderNodeValue", "Value", [], [Socket("Value", 0.25)])
    node = noise_node((4, 0, 0), noise_dimensions="1D")
    node.inputs[1].links = [Link(value, value.outputs[0])]
    c, _, warnings = read(node, "Fac", (4, 0, 0))
    assert not warnings
    n = only_node(c, native.node_type("noise"))
    assert c.builder.program.registers[n.inputs[1]] == 0.25
    assert n.modes[3] == 1


def test_evaluates_through_the_native_library() -> None:
    # Detail 0: one octave, 0.5 snoise + 0.5, at a lattice point 0.5 exactly (Perlin is 0 there).
    node = noise_node((5, 0, 0))
    node.inputs[2].default_value = 1.0  # Scale
    node.inputs[3].default_value = 0.0  # Detail
    c, reg, _ = read(node, "Color", (5, 0, 0))
    scene = native.Scene()
    pid = scene.add_shader_program(c.builder.program)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    inputs[GENERATED:GENERATED + 3] = (2.0, -3.0, 7.0)
    fac = scene.evaluate_program(pid, inputs, reg, 3)
    assert fac[0] == pytest.approx(0.5, abs=1e-7)
    inputs[GENERATED:GENERATED + 3] = (2.3, -3.6, 7.1)
    assert abs(scene.evaluate_program(pid, inputs, reg, 3)[0] - 0.5) > 1e-3


class Mapping:
    translation = (0.0, 0.0, 0.0)
    rotation = (0.0, 0.0, 0.0)
    scale = (1.0, 1.0, 1.0)
    use_min = use_max = False
    mapping_x, mapping_y, mapping_z = "X", "Y", "Z"


def test_a_hidden_texture_mapping_is_warned_about() -> None:
    _, _, warnings = read(noise_node((5, 0, 0), texture_mapping=Mapping()), "Fac", (5, 0, 0))
    assert not warnings
    moved = Mapping()
    moved.scale = (2.0, 1.0, 1.0)
    _, _, warnings = read(musgrave_node(texture_mapping=moved), "Fac", (3, 4, 1))
    assert len(warnings) == 1 and "texture mapping" in warnings[0]
