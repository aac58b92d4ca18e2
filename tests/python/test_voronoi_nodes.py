"""Voronoi and White Noise translation (stratum.shaders.nodes.voronoi_textures) on plain stand-ins
for Blender nodes: the native node's modes and registers in Blender 3.4's and 5.0's socket
layouts, the generation each version picks, the Generated default, 4.0-4.2's Lacunarity slot and
the warnings; then the compiled programs evaluated by the native library."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from stratum import native
from stratum.blender_versions import voronoi_generation
from stratum.shaders.nodes import NodeCompiler

V34 = (3, 4, 1)
V40 = (4, 0, 2)
V44 = (4, 4, 0)
V45 = (4, 5, 0)
V50 = (5, 0, 1)


class Socket:
    def __init__(self, name: str, default_value: Any = 0.0, type_: str = "VALUE",
                 node: Any = None) -> None:
        self.name = self.identifier = name
        self.default_value = default_value
        self.type = type_
        self.links: list[Any] = []
        self.node = node

    @property
    def is_linked(self) -> bool:
        return bool(self.links)


class Link:
    def __init__(self, from_node: Any, from_socket: Socket) -> None:
        self.from_node, self.from_socket = from_node, from_socket
        self.is_muted, self.is_valid = False, True


class Node:
    def __init__(self, bl_idname: str, name: str, inputs: list[tuple[str, Any, str]],
                 outputs: list[tuple[str, str]], **props: Any) -> None:
        self.bl_idname, self.name, self.mute = bl_idname, name, False
        self.inputs = [Socket(n, v, t, self) for n, v, t in inputs]
        self.outputs = [Socket(n, None, t, self) for n, t in outputs]
        for key, value in props.items():
            setattr(self, key, value)

    def input(self, name: str) -> Socket:
        return next(s for s in self.inputs if s.name == name)

    def output(self, name: str) -> Socket:
        return next(s for s in self.outputs if s.name == name)


OUTPUTS = [("Distance", "VALUE"), ("Color", "RGBA"), ("Position", "VECTOR"), ("W", "VALUE"),
           ("Radius", "VALUE")]


def voronoi_v3(**props: Any) -> Node:
    inputs = [("Vector", (0.0, 0.0, 0.0), "VECTOR"), ("W", 0.0, "VALUE"), ("Scale", 5.0, "VALUE"),
              ("Smoothness", 1.0, "VALUE"), ("Exponent", 0.5, "VALUE"),
              ("Randomness", 1.0, "VALUE")]
    return Node("ShaderNodeTexVoronoi", "Voronoi", inputs, OUTPUTS, **{
        "voronoi_dimensions": "3D", "feature": "F1", "distance": "EUCLIDEAN", **props})


def voronoi_v4(**props: Any) -> Node:
    inputs = [("Vector", (0.0, 0.0, 0.0), "VECTOR"), ("W", 0.0, "VALUE"), ("Scale", 5.0, "VALUE"),
              ("Detail", 0.0, "VALUE"), ("Roughness", 0.5, "VALUE"), ("Lacunarity", 2.0, "VALUE"),
              ("Smoothness", 1.0, "VALUE"), ("Exponent", 0.5, "VALUE"),
              ("Randomness", 1.0, "VALUE")]
    return Node("ShaderNodeTexVoronoi", "Voronoi", inputs, OUTPUTS, **{
        "voronoi_dimensions": "3D", "feature": "F1", "distance": "EUCLIDEAN", "normalize": False,
        **props})


def white_noise(dims: str = "3D") -> Node:
    return Node("ShaderNodeTexWhiteNoise", "White", [("Vector", (0.0, 0.0, 0.0), "VECTOR"),
                                                     ("W", 0.0, "VALUE")],
                [("Value", "VALUE"), ("Color", "RGBA")], noise_dimensions=dims)


def value_node(name: str, value: float) -> Node:
    node = Node("ShaderNodeValue", name, [], [("Value", "VALUE")])
    node.outputs[0].default_value = value
    return node


def link(src: Node, output: str, dst: Node, input_: str) -> None:
    dst.input(input_).links = [Link(src, src.output(output))]


def compile_node(node: Node, version: tuple[int, int, int]) -> tuple[NodeCompiler, dict[str, int],
                                                                     list[str]]:
    warnings: list[str] = []
    c = NodeCompiler(version, lambda n, m: warnings.append(m))
    regs = {s.name: c.output(node, s) for s in node.outputs}
    return c, regs, warnings


def the_node(c: NodeCompiler, kind: str) -> Any:
    nodes = [n for n in c.builder.program.nodes if n.type == native.node_type(kind)]
    assert len(nodes) == 1
    return nodes[0]


def register_value(c: NodeCompiler, register: int) -> float:
    return c.builder.program.registers[register]


@pytest.mark.parametrize(("version", "expected"), [
    ((3, 4, 1), 0), ((3, 6, 0), 0), ((4, 0, 2), 1), ((4, 2, 0), 1), ((4, 4, 0), 1),
    ((4, 5, 0), 2), ((5, 0, 1), 3), ((5, 1, 0), 3)])
def test_generation_per_blender_version(version: tuple[int, int, int], expected: int) -> None:
    assert voronoi_generation(version) == expected


def test_blender3_layout_modes_and_registers() -> None:
    node = voronoi_v3(voronoi_dimensions="4D", feature="SMOOTH_F1", distance="MINKOWSKI")
    node.input("Exponent").default_value = 1.5
    node.input("Smoothness").default_value = 0.25
    node.input("W").default_value = 0.75
    c, regs, warnings = compile_node(node, V34)
    n = the_node(c, "voronoi")
    assert tuple(n.modes[:5]) == (3, 2, 3, 0, 0)
    assert n.inputs[0] == native.SHADER_INPUTS["generated"][0]  # unlinked Vector
    values = [register_value(c, r) for r in n.inputs[1:9]]
    # w, scale, detail (absent: 0), roughness (0.5), lacunarity (2), smoothness, exponent, random
    assert values == [0.75, 5.0, 0.0, 0.5, 2.0, 0.25, 1.5, 1.0]
    assert set(regs) == {"Distance", "Color", "Position", "W", "Radius"}
    assert list(n.outputs[:5]) == [regs[k] for k in ("Distance", "Color", "Position", "W",
                                                     "Radius")]
    assert warnings == []


@pytest.mark.parametrize("version", [V44, V45, V50])
def test_blender4_layout_reads_the_fractal_sockets(version: tuple[int, int, int]) -> None:
    node = voronoi_v4(voronoi_dimensions="2D", feature="DISTANCE_TO_EDGE", distance="CHEBYCHEV",
                      normalize=True)
    node.input("Detail").default_value = 2.5
    node.input("Roughness").default_value = 0.25
    node.input("Lacunarity").default_value = 3.0
    c, _, warnings = compile_node(node, version)
    n = the_node(c, "voronoi")
    assert tuple(n.modes[:5]) == (1, 3, 2, voronoi_generation(version), 1)
    assert [register_value(c, r) for r in n.inputs[3:6]] == [2.5, 0.25, 3.0]
    assert warnings == []


def test_linked_inputs_and_vector() -> None:
    node = voronoi_v4()
    scale = value_node("s", 7.0)
    link(scale, "Value", node, "Scale")
    coord = Node("ShaderNodeTexCoord", "tc", [], [("Object", "VECTOR"), ("Generated", "VECTOR")])
    coord.object, coord.from_instancer = None, False
    link(coord, "Object", node, "Vector")
    c, _, _ = compile_node(node, V50)
    n = the_node(c, "voronoi")
    assert n.inputs[0] == native.SHADER_INPUTS["object"][0]
    assert register_value(c, n.inputs[2]) == 7.0


def test_blender40_reads_lacunarity_from_the_smoothness_link() -> None:
    # Cycles 4.0-4.2: a linked Smoothness feeds Lacunarity; a linked Lacunarity is ignored.
    node = voronoi_v4()
    link(value_node("smooth", 0.3), "Value", node, "Smoothness")
    c, _, warnings = compile_node(node, V40)
    n = the_node(c, "voronoi")
    assert n.inputs[5] == n.inputs[6]
    assert any("Lacunarity" in w for w in warnings)

    node = voronoi_v4()
    node.input("Lacunarity").default_value = 2.5
    link(value_node("lac", 4.0), "Value", node, "Lacunarity")
    c, _, warnings = compile_node(node, V40)
    assert register_value(c, the_node(c, "voronoi").inputs[5]) == 2.5
    assert warnings
    # 4.3+ reads the link.
    c, _, warnings = compile_node(node, V44)
    assert register_value(c, the_node(c, "voronoi").inputs[5]) == 4.0
    assert warnings == []


def test_normalize_is_ignored_before_4() -> None:
    node = voronoi_v3(normalize=True)
    c, _, _ = compile_node(node, V34)
    assert the_node(c, "voronoi").modes[4] == 0


@pytest.mark.parametrize(("attribute", "value"), [("feature", "F3"), ("distance", "HAMMING"),
                                                  ("voronoi_dimensions", "5D")])
def test_unknown_enum_values_warn_and_use_the_socket_value(attribute: str, value: str) -> None:
    node = voronoi_v4(**{attribute: value})
    emission = Node("ShaderNodeEmission", "Emission", [("Color", (0.5, 0.5, 0.5, 1.0), "RGBA")],
                    [])
    link(node, "Distance", emission, "Color")
    warnings: list[str] = []
    c = NodeCompiler(V50, lambda n, m: warnings.append(m))
    register = c.value(emission.input("Color"), "color")
    assert [c.builder.program.registers[register + i] for i in range(3)] == [0.5, 0.5, 0.5]
    assert len(warnings) == 1 and value in warnings[0] and "Voronoi" in warnings[0]


def test_white_noise_modes_and_registers() -> None:
    for i, dims in enumerate(("1D", "2D", "3D", "4D")):
        node = white_noise(dims)
        node.input("W").default_value = 0.5
        node.input("Vector").default_value = (0.25, 0.5, 2.0)
        c, regs, _ = compile_node(node, V34)
        n = the_node(c, "white_noise")
        assert n.modes[0] == i
        # Unlinked, the Vector is the socket's value (Cycles gives it no default link).
        assert [register_value(c, n.inputs[0] + k) for k in range(3)] == [0.25, 0.5, 2.0]
        assert register_value(c, n.inputs[1]) == 0.5
        assert list(n.outputs[:2]) == [regs["Value"], regs["Color"]]


def evaluate(c: NodeCompiler, register: int, width: int, generated: tuple[float, ...]) -> Any:
    scene = native.Scene()
    pid = scene.add_shader_program(c.builder.program)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    base = native.SHADER_INPUTS["generated"][0]
    inputs[base:base + 3] = generated
    return scene.evaluate_program(pid, inputs, register, width)


def test_programs_evaluate_natively() -> None:
    # Randomness 0: the regular lattice. At generated (0.3, 0.5, 0.9) * scale 5 = (1.5, 2.5, 4.5)
    # the nearest lattice point is at distance sqrt(3) / 2 (a tie of 8); (0.2, 0.4, 0.6) is one.
    node = voronoi_v4()
    node.input("Randomness").default_value = 0.0
    c, regs, _ = compile_node(node, V50)
    assert evaluate(c, regs["Distance"], 1, (0.3, 0.5, 0.9))[0] == pytest.approx(0.75 ** 0.5)
    assert evaluate(c, regs["Distance"], 1, (0.2, 0.4, 0.6))[0] == pytest.approx(0.0, abs=1e-6)
    node = white_noise("1D")
    c, regs, _ = compile_node(node, V50)
    value = evaluate(c, regs["Value"], 1, (0.0, 0.0, 0.0))[0]
    assert 0.0 <= value <= 1.0
    color = evaluate(c, regs["Color"], 3, (0.0, 0.0, 0.0))
    assert color[0] == value  # Color's first component is the Value hash
