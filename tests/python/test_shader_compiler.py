"""The node compiler (stratum.shaders.nodes) on stand-ins for Blender nodes: links through
reroutes, muted nodes and groups, each node compiled once, the fallbacks with their warnings, and
programs that run natively (the library evaluates what was compiled)."""

from __future__ import annotations

import math as pymath
from typing import Any

import numpy as np
import pytest
from stratum import native
from stratum.shaders.nodes import NodeCompiler

from node_fakes import Link, Node, Socket, Tree, link, math, separate_xyz, texture_coordinate

V3 = (3, 4, 1)
V5 = (5, 0, 1)


def compiled(socket: Socket, kind: str = "float",
             version: tuple[int, int, int] = V3) -> tuple[NodeCompiler, int, list[str]]:
    warnings: list[str] = []
    c = NodeCompiler(version, lambda node, message: warnings.append(message))
    return c, c.value(socket, kind), warnings


def run(c: NodeCompiler, register: int, width: int = 1, **inputs: Any) -> np.ndarray:
    """The program's register(s) evaluated natively with the given renderer inputs."""
    scene = native.Scene()
    program_id = scene.add_shader_program(c.builder.program)
    regs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    for name, value in inputs.items():
        start, size = native.SHADER_INPUTS[name]
        regs[start:start + size] = value
    return scene.evaluate_program(program_id, regs, register, width)


def consumer(default: float = 0.25) -> Socket:
    return Socket("Strength", default)


def sine_of_generated_x() -> tuple[Node, list[Node]]:
    coords, sep = texture_coordinate(), separate_xyz()
    scale = math("Scale", "MULTIPLY", b=6.0)
    sine = math("Sine", "SINE")
    link(coords, "Generated", sep, "Vector")
    link(sep, "X", scale, 0)
    link(scale, "Value", sine, 0)
    return sine, [coords, sep, scale]


def test_unlinked_socket_is_its_value() -> None:
    c, register, warnings = compiled(consumer(0.75))
    assert run(c, register)[0] == pytest.approx(0.75)
    assert not warnings and not c.builder.program.nodes


def test_math_chain_runs_natively() -> None:
    sine, _ = sine_of_generated_x()
    target = consumer()
    link(sine, "Value", target)
    c, register, warnings = compiled(target)
    assert not warnings
    for x in (0.0, 0.2, 0.9):
        assert run(c, register, generated=(x, 0.5, 0.5))[0] == pytest.approx(pymath.sin(6 * x),
                                                                              abs=1e-6)


def test_each_node_is_compiled_once() -> None:
    sine, _ = sine_of_generated_x()
    total = math("Sum", "ADD")
    link(sine, "Value", total, 0)
    link(sine, "Value", total, 1)
    target = consumer()
    link(total, "Value", target)
    c, register, _ = compiled(target)
    # multiply, sine, add: the shared sine is one node
    assert len(c.builder.program.nodes) == 3
    assert run(c, register, generated=(0.1, 0, 0))[0] == pytest.approx(2 * pymath.sin(0.6), 1e-6)


def test_reroutes_and_muted_nodes_pass_values_through() -> None:
    source = math("Source", "ADD", 0.5, 0.25)
    reroute = Node("NodeReroute", "Reroute", [Socket("Input", 0.0)], [Socket("Output", 0.0)])
    link(source, "Value", reroute, 0)
    muted = math("Muted", "MULTIPLY", b=100.0)
    muted.mute = True
    link(reroute, "Output", muted, 0)
    muted.internal_links = [Link(muted, muted.inputs[0], muted.outputs[0])]
    target = consumer()
    link(muted, "Value", target)
    c, register, warnings = compiled(target)
    assert not warnings
    assert run(c, register)[0] == pytest.approx(0.75)


def group_node(name: str, inner_tree: Tree, inputs: list[Socket], outputs: list[Socket]) -> Node:
    return Node("ShaderNodeGroup", name, inputs, outputs, node_tree=inner_tree)


def test_groups_are_flattened_with_their_inputs_one_scope_out() -> None:
    # A group computing In * 3, used twice with different inputs: two scopes, two results.
    group_in = Node("NodeGroupInput", "Group Input", (), [Socket("In", 0.0)])
    times = math("Times", "MULTIPLY", b=3.0)
    link(group_in, "In", times, 0)
    group_out = Node("NodeGroupOutput", "Group Output", [Socket("Out", 0.0)], (),
                     is_active_output=True)
    link(times, "Value", group_out, 0)
    tree = Tree([group_in, times, group_out])
    first = group_node("First", tree, [Socket("In", 1.0)], [Socket("Out", 0.0)])
    second = group_node("Second", tree, [Socket("In", 2.0)], [Socket("Out", 0.0)])
    total = math("Total", "ADD")
    link(first, "Out", total, 0)
    link(second, "Out", total, 1)
    target = consumer()
    link(total, "Value", target)
    c, register, warnings = compiled(target)
    assert not warnings
    assert run(c, register)[0] == pytest.approx(9.0)


def test_unknown_node_warns_once_and_uses_the_socket_value() -> None:
    strange = Node("ShaderNodeSomethingNew", "Strange", (), ["Value"])
    total = math("Total", "ADD")
    link(strange, "Value", total, 0)
    link(strange, "Value", total, 1)
    target = consumer()
    link(total, "Value", target)
    c, register, warnings = compiled(target)
    assert len(warnings) == 1 and "Strange" in warnings[0] and "not supported" in warnings[0]
    assert run(c, register)[0] == pytest.approx(0.0)  # both Value inputs' own 0


def test_a_cycle_warns_and_never_recurses_forever() -> None:
    a, b = math("A", "ADD", 0.0, 1.0), math("B", "ADD", 0.0, 1.0)
    link(a, "Value", b, 0)
    link(b, "Value", a, 0)
    target = consumer(0.5)
    link(a, "Value", target)
    c, register, warnings = compiled(target)
    assert any("cycle" in w for w in warnings)
    assert np.isfinite(run(c, register)[0])


def test_conversions_follow_cycles() -> None:
    rgb = Node("ShaderNodeRGB", "RGB", (), [Socket("Color", (0.2, 0.4, 0.6, 1.0))])
    target = consumer()
    link(rgb, "Color", target)
    c, register, _ = compiled(target)
    # Cycles 3.4's luminance weights (tests/python/test_color_nodes.py LUMINANCE).
    expected = 0.212672979 * 0.2 + 0.715152621 * 0.4 + 0.0721754432 * 0.6
    assert run(c, register)[0] == pytest.approx(expected, 1e-6)
    coords = texture_coordinate()
    vector_target = consumer()
    link(coords, "Object", vector_target)
    c, register, _ = compiled(vector_target)
    assert run(c, register, object=(0.3, 0.6, 1.2))[0] == pytest.approx(0.7, 1e-6)


def test_object_info_reads_the_instance_inputs() -> None:
    info = Node("ShaderNodeObjectInfo", "Object Info", (),
                ["Random", "Location", Socket("Color", (0.0, 0.0, 0.0, 1.0)), "Alpha"])
    target = consumer(0.5)
    link(info, "Random", target)
    c, register, warnings = compiled(target)
    assert not warnings
    assert run(c, register, object_random=0.375)[0] == pytest.approx(0.375)


@pytest.mark.parametrize("version", [V3, V5])
def test_bump_of_a_linear_height_tilts_the_normal_by_its_gradient(version: tuple[int, ...]) -> None:
    # Height = 0.5 x (object x): on a plane with normal +Z, N' = normalize((-0.5 d, 0, 1)) for
    # Distance d, whatever the step the renderer takes.
    coords, sep = texture_coordinate(), separate_xyz()
    height = math("Height", "MULTIPLY", b=0.5)
    link(coords, "Object", sep, "Vector")
    link(sep, "X", height, 0)
    bump = Node("ShaderNodeBump", "Bump",
                [("Strength", 1.0), ("Distance", 2.0), ("Height", 0.0),
                 Socket("Normal", (0.0, 0.0, 0.0))], [Socket("Normal", (0.0, 0.0, 0.0))],
                invert=False)
    link(height, "Value", bump, "Height")
    target = Socket("Normal", (0.0, 0.0, 0.0))
    link(bump, "Normal", target)
    c, register, warnings = compiled(target, "vector", version)
    assert not warnings
    step = 1e-3
    out = run(c, register, 3, object=(0.3, 0.1, 0.0), normal=(0, 0, 1), dpdx=(step, 0, 0),
              dpdy=(0, step, 0), dobject_dx=(step, 0, 0), dobject_dy=(0, step, 0))
    expected = np.array([-1.0, 0.0, 1.0]) / np.sqrt(2.0)
    assert out == pytest.approx(expected, abs=1e-4)


def test_a_link_from_an_unavailable_output_is_ignored_as_blender_does() -> None:
    source = math("Source", "ADD", 0.5, 0.25)
    source.outputs[0].enabled = False
    target = consumer(0.125)
    link(source, "Value", target)
    c, register, warnings = compiled(target)
    assert not warnings
    assert run(c, register)[0] == pytest.approx(0.125)
