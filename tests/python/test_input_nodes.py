"""Translators of the nodes that read the shading point (stratum.shaders.nodes.input_nodes) on
stand-ins for Blender nodes: the native node each becomes, the renderer inputs it reads, what it
warns about, and values evaluated natively against values worked out by hand. Their agreement
with Cycles is tests/blender/test_node_agreement.py's."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from stratum import native
from stratum.shaders.nodes import NodeCompiler

from node_fakes import Node, Socket, link

V3 = (3, 4, 1)
V5 = (5, 0, 1)


def compile_into(node: Node, output: str, target: Socket, version: tuple[int, int, int] = V5,
                 **compiler: Any) -> tuple[NodeCompiler, int, list[str]]:
    """`node`'s `output` compiled into the consuming socket `target` (a float socket is read as
    a float, any other as a vector)."""
    warnings: list[str] = []
    c = NodeCompiler(version, lambda _node, message: warnings.append(message), **compiler)
    link(node, output, target)
    kind = "float" if target.type == "VALUE" else "vector"
    return c, c.value(target, kind), warnings


def evaluate(c: NodeCompiler, register: int, width: int, **inputs: Any) -> np.ndarray:
    regs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    for name, value in inputs.items():
        at, w = native.SHADER_INPUTS[name]
        regs[at:at + w] = value
    with native.Scene() as scene:
        program_id = scene.add_shader_program(c.builder.program)
        return scene.evaluate_program(program_id, regs, register, width)


def only_node(c: NodeCompiler, kind: str) -> Any:
    (found,) = [n for n in c.builder.program.nodes if n.type == native.node_type(kind)]
    return found


# ---- Camera Data ---------------------------------------------------------------------------------

def camera_data() -> Node:
    return Node("ShaderNodeCameraData", "Camera Data", (),
                [Socket("View Vector", (0.0, 0.0, 0.0)), Socket("View Z Depth"),
                 Socket("View Distance")])


@pytest.mark.parametrize(("output", "width", "want"), [
    ("View Vector", 3, [3 / 13, 4 / 13, 12 / 13]), ("View Z Depth", 1, [12.0]),
    ("View Distance", 1, [13.0])])
def test_camera_data_reads_the_point_in_camera_space(output: str, width: int,
                                                     want: list[float]) -> None:
    target = Socket("Target", 0.5) if width == 1 else Socket("Target", (0.0, 0.0, 0.0))
    c, register, warnings = compile_into(camera_data(), output, target)
    assert warnings == []
    assert only_node(c, "camera_data").inputs == (native.SHADER_INPUTS["camera"][0],)
    assert evaluate(c, register, width, camera=(3.0, 4.0, 12.0)) == pytest.approx(want, rel=1e-6)


def test_camera_data_in_a_world_warns_and_uses_the_socket_value() -> None:
    c, register, warnings = compile_into(camera_data(), "View Z Depth", Socket("Strength", 0.5),
                                         world=True)
    assert len(warnings) == 1
    assert "Camera Data 'Camera Data' in a world is not supported" in warnings[0]
    assert not c.builder.program.nodes
    assert evaluate(c, register, 1) == pytest.approx([0.5])


# ---- Wireframe -----------------------------------------------------------------------------------

def wireframe(size: float, pixel_size: bool) -> Node:
    return Node("ShaderNodeWireframe", "Wireframe", [Socket("Size", size)],
                [Socket("Fac", identifier="Fac")], use_pixel_size=pixel_size)


TRIANGLE = (0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0)
VIEW = {"true_normal": (0.0, 0.0, 1.0), "incoming": (0.0, 0.0, 1.0), "triangle": TRIANGLE}


@pytest.mark.parametrize(("pixel_size", "size", "footprint"), [(False, 0.1, 0.0), (True, 1.0, 0.1)])
def test_wireframe_is_one_within_half_the_size_of_an_edge(pixel_size: bool, size: float,
                                                          footprint: float) -> None:
    # Half the width is 0.05 either way (with Pixel Size: 1 pixel of footprint 0.1, halved).
    c, register, warnings = compile_into(wireframe(size, pixel_size), "Fac", Socket("Strength"))
    assert warnings == []
    n = only_node(c, "wireframe")
    assert n.modes[0] == int(pixel_size)
    assert n.inputs[0] == native.SHADER_INPUTS["position"][0]
    assert n.inputs[5:] == tuple(native.SHADER_INPUTS["triangle"][0] + k for k in (0, 3, 6))
    near_an_edge = evaluate(c, register, 1, position=(0.3, 0.04, 0.0), pixel_footprint=footprint,
                            **VIEW)
    # 0.3 from two edges, 0.4 / sqrt(2) = 0.28 from the third.
    inside = evaluate(c, register, 1, position=(0.3, 0.3, 0.0), pixel_footprint=footprint, **VIEW)
    assert (near_an_edge[0], inside[0]) == (1.0, 0.0)
    # The world has no triangle (every vertex 0): Cycles' 0 for no primitive.
    assert evaluate(c, register, 1, position=(0.3, 0.04, 0.0), pixel_footprint=footprint) == [0.0]


@pytest.mark.parametrize(("version", "warned"), [((4, 3, 0), True), ((4, 4, 0), False)])
def test_wireframe_inside_a_bump_warns_before_4_4(version: tuple[int, int, int],
                                                  warned: bool) -> None:
    warnings: list[str] = []
    c = NodeCompiler(version, lambda _node, message: warnings.append(message))
    target = Socket("Height")
    link(wireframe(0.1, False), "Fac", target)
    moved = c.builder.constant((0.3, 0.04, 0.0))
    register = c.at_offset({"position": moved}, "bump-x", lambda: c.value(target, "float"))
    assert only_node(c, "wireframe").inputs[0] == moved
    assert evaluate(c, register, 1, **VIEW) == [1.0]
    assert bool(warnings) == warned
    if warned:
        assert "difference quotient" in warnings[0]


# ---- Tangent -------------------------------------------------------------------------------------

def tangent(direction: str, axis: str = "Z", uv_map: str = "") -> Node:
    return Node("ShaderNodeTangent", "Tangent", (), [Socket("Tangent", (0.0, 0.0, 0.0))],
                direction_type=direction, axis=axis, uv_map=uv_map)


IDENTITY = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)


@pytest.mark.parametrize("axis", ["X", "Y", "Z"])
def test_tangent_radial_circles_the_axis_in_the_shading_plane(axis: str) -> None:
    c, register, warnings = compile_into(tangent("RADIAL", axis), "Tangent",
                                         Socket("Color", (0.0, 0.0, 0.0, 1.0)))
    assert warnings == [] and c.uv_tangent_maps == {}
    n = only_node(c, "tangent")
    assert n.modes[:2] == (0, "XYZ".index(axis))
    # g - 1/2 = (0.3, 0, 0.4): the radial tangents about X, Y and Z, then N x normalize(T x N)
    # with N = +Z keeps their part in the XY plane, unit.
    got = evaluate(c, register, 3, generated=(0.8, 0.5, 0.9), normal=(0.0, 0.0, 1.0),
                   normal_transform=IDENTITY)
    radial = {"X": (0.0, -0.4, 0.0), "Y": (-0.4, 0.0, 0.3), "Z": (0.0, 0.3, 0.0)}[axis]
    flat = np.array([radial[0], radial[1], 0.0])
    assert got == pytest.approx(flat / np.linalg.norm(flat), abs=1e-6)


def test_tangent_radial_is_taken_to_world_space_as_a_normal() -> None:
    c, register, _ = compile_into(tangent("RADIAL", "Z"), "Tangent",
                                  Socket("Color", (0.0, 0.0, 0.0, 1.0)))
    # Object X goes to world Y, object Y to world -X: the radial tangent (0, 0.3, 0) about Z
    # becomes world (-0.3, 0, 0).
    rotation = (0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0)
    got = evaluate(c, register, 3, generated=(0.8, 0.5, 0.5), normal=(0.0, 0.0, 1.0),
                   normal_transform=rotation)
    assert got == pytest.approx([-1.0, 0.0, 0.0], abs=1e-6)


@pytest.mark.parametrize("uv_map", ["", "UVMap"])
def test_tangent_uv_map_reads_the_mikktspace_tangent_and_records_the_map(uv_map: str) -> None:
    c, register, warnings = compile_into(tangent("UV_MAP", uv_map=uv_map), "Tangent",
                                         Socket("Color", (0.0, 0.0, 0.0, 1.0)))
    assert warnings == []
    assert c.uv_tangent_maps == {"Tangent": uv_map}
    assert only_node(c, "tangent").modes[0] == 1
    got = evaluate(c, register, 3, normal=(0.0, 0.0, 1.0), mikktspace_tangent=(2.0, 0.0, 1.0))
    assert got == pytest.approx([1.0, 0.0, 0.0], abs=1e-6)
    # A mesh without corner tangents: 0, as Cycles' missing attribute.
    assert evaluate(c, register, 3, normal=(0.0, 0.0, 1.0)) == pytest.approx([0.0] * 3)


def test_tangent_of_an_unknown_direction_warns() -> None:
    c, register, warnings = compile_into(tangent("SPIRAL"), "Tangent",
                                         Socket("Color", (0.25, 0.5, 0.75, 1.0)))
    assert len(warnings) == 1 and "direction SPIRAL" in warnings[0]
    assert evaluate(c, register, 3) == pytest.approx([0.25, 0.5, 0.75])


# ---- Script --------------------------------------------------------------------------------------

def test_a_script_node_warns_and_its_consumer_reads_its_own_value() -> None:
    """Cycles without OSL drops the node and its links: the consuming socket's own value, not
    the Script output's default."""
    script = Node("ShaderNodeScript", "Script", [Socket("In", 2.0)], [Socket("Fac", 0.3)])
    c, register, warnings = compile_into(script, "Fac", Socket("Strength", 0.6))
    assert len(warnings) == 1
    assert warnings[0].startswith("Script 'Script': OSL scripts are not supported")
    assert warnings[0].endswith("using the value of 'Strength'")
    assert evaluate(c, register, 1) == pytest.approx([0.6])


# ---- Light Path ----------------------------------------------------------------------------------

LIGHT_PATH_3_4 = ("Is Camera Ray", "Is Shadow Ray", "Is Diffuse Ray", "Is Glossy Ray",
                  "Is Singular Ray", "Is Reflection Ray", "Is Transmission Ray", "Ray Length",
                  "Ray Depth", "Diffuse Depth", "Glossy Depth", "Transparent Depth",
                  "Transmission Depth")
LIGHT_PATH_5_0 = (*LIGHT_PATH_3_4[:7], "Is Volume Scatter Ray", *LIGHT_PATH_3_4[7:],
                  "Portal Depth")


def light_path(outputs: tuple[str, ...]) -> Node:
    return Node("ShaderNodeLightPath", "Light Path", (), [Socket(name) for name in outputs])


@pytest.mark.parametrize(("version", "outputs"), [(V3, LIGHT_PATH_3_4), (V5, LIGHT_PATH_5_0)])
def test_light_path_outputs_are_the_renderers_path_inputs(version: tuple[int, int, int],
                                                          outputs: tuple[str, ...]) -> None:
    # Each output reads its own renderer input, unchanged: no node in between, in materials and
    # in the world alike.
    for world in (False, True):
        for k, output in enumerate(outputs):
            c, register, warnings = compile_into(light_path(outputs), output,
                                                 Socket("Strength", 0.5), version, world=world)
            assert warnings == []
            name = output.lower().replace(" ", "_").removeprefix("is_")
            name = "is_" + name if output.startswith("Is ") else name
            assert register == native.SHADER_INPUTS[name][0], output
            value = float(k + 1)
            assert evaluate(c, register, 1, **{name: value}) == pytest.approx([value])
