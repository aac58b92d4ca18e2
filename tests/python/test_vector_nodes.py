"""Vector and converter node translators (stratum.shaders.nodes.vector_nodes and
surface_inputs) on plain stand-ins for Blender nodes, in both Blender generations' layouts: the
native node, its modes and registers, warnings for what is unsupported, and a few results
evaluated natively against values worked out by hand."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from stratum import native
from stratum.blender_versions import vector_math_revision
from stratum.shaders.nodes import NodeCompiler
from stratum.shaders.nodes.surface_inputs import rec709_to_rgb, xyz_to_rgb
from stratum.shaders.nodes.vector_nodes import VECTOR_OPERATIONS

V3 = (3, 4, 1)
V43 = (4, 3, 0)
V5 = (5, 0, 1)


class Socket:
    def __init__(self, identifier: str, kind: str, default_value: Any = None, name: str = "",
                 enabled: bool = True) -> None:
        self.identifier = identifier
        self.name = name or identifier
        self.type = kind
        self.default_value = default_value
        self.enabled = enabled
        self.links: list[Any] = []

    @property
    def is_linked(self) -> bool:
        return bool(self.links)


class Link:
    def __init__(self, from_node: Any, from_socket: Socket) -> None:
        self.from_node = from_node
        self.from_socket = from_socket
        self.is_muted = False
        self.is_valid = True


class Node:
    def __init__(self, bl_idname: str, name: str, inputs: list[Socket], outputs: list[Socket],
                 **props: Any) -> None:
        self.bl_idname = bl_idname
        self.name = name
        self.inputs = inputs
        self.outputs = outputs
        self.mute = False
        for key, value in props.items():
            setattr(self, key, value)


def vec(identifier: str, value: tuple[float, ...] = (0.0, 0.0, 0.0), **kw: Any) -> Socket:
    return Socket(identifier, "VECTOR", value, **kw)


def val(identifier: str, value: float = 0.0, **kw: Any) -> Socket:
    return Socket(identifier, "VALUE", value, **kw)


def vector_math_node(operation: str, a: tuple[float, ...], b: tuple[float, ...] = (0, 0, 0),
                     c: tuple[float, ...] = (0, 0, 0), scale: float = 1.0) -> Node:
    return Node("ShaderNodeVectorMath", "Vector Math",
                [vec("Vector", a, name="Vector"), vec("Vector_001", b, name="Vector"),
                 vec("Vector_002", c, name="Vector"), val("Scale", scale)],
                [vec("Vector"), val("Value")], operation=operation)


def map_range_node(data_type: str = "FLOAT", **props: Any) -> Node:
    vector = data_type == "FLOAT_VECTOR"
    return Node("ShaderNodeMapRange", "Map Range",
                [val("Value", 0.25, enabled=not vector), val("From Min", 0.0, enabled=not vector),
                 val("From Max", 1.0, enabled=not vector), val("To Min", 10.0, enabled=not vector),
                 val("To Max", 20.0, enabled=not vector), val("Steps", 4.0, enabled=False),
                 vec("Vector", (0.25, 0.5, 2.0), enabled=vector),
                 vec("From_Min_FLOAT3", (0, 0, 0), name="From Min", enabled=vector),
                 vec("From_Max_FLOAT3", (1, 1, 1), name="From Max", enabled=vector),
                 vec("To_Min_FLOAT3", (0, 0, 0), name="To Min", enabled=vector),
                 vec("To_Max_FLOAT3", (2, 4, 8), name="To Max", enabled=vector),
                 vec("Steps_FLOAT3", (4, 4, 4), name="Steps", enabled=False)],
                [val("Result"), vec("Vector")], data_type=data_type, **props)


def compile_output(node: Node, output: str, kind: str,
                   version: tuple[int, int, int] = V5) -> tuple[NodeCompiler, int, list[str]]:
    warnings: list[str] = []
    c = NodeCompiler(version, lambda n, msg: warnings.append(msg))
    # The consuming socket's own value: what an unsupported node falls back to.
    fallback = 0.5 if kind == "float" else (0.25, 0.5, 0.75)
    target = Socket("Target", "RGBA" if kind == "color" else kind.upper(), fallback)
    out = next(s for s in node.outputs if s.identifier == output)
    target.links = [Link(node, out)]
    register = c.value(target, kind)
    return c, register, warnings


def evaluate(c: NodeCompiler, register: int, width: int, inputs: dict[str, Any] | None = None
             ) -> np.ndarray:
    regs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    for name, value in (inputs or {}).items():
        at, w = native.SHADER_INPUTS[name]
        regs[at:at + w] = value
    with native.Scene() as scene:
        pid = scene.add_shader_program(c.builder.program)
        return scene.evaluate_program(pid, regs, register, width)


def last_node(c: NodeCompiler) -> Any:
    return c.builder.program.nodes[-1]


# ---- Vector Math ---------------------------------------------------------------------------------

def test_vector_math_operations_follow_cycles_numbering() -> None:
    assert VECTOR_OPERATIONS.index("ADD") == 0
    assert VECTOR_OPERATIONS.index("REFLECT") == 6
    assert VECTOR_OPERATIONS.index("SCALE") == 10
    assert VECTOR_OPERATIONS.index("MULTIPLY_ADD") == 26
    assert VECTOR_OPERATIONS.index("SIGN") == 28
    assert len(VECTOR_OPERATIONS) == 29


@pytest.mark.parametrize(("version", "revision"), [(V3, 0), ((4, 2, 0), 0), (V43, 1), ((4, 5, 0), 1),
                                                   (V5, 2)])
def test_vector_math_revision_by_version(version: tuple[int, int, int], revision: int) -> None:
    assert vector_math_revision(version) == revision
    c, _, _ = compile_output(vector_math_node("ADD", (1, 2, 3)), "Vector", "vector", version)
    assert last_node(c).modes[:2] == (0, revision)


def test_vector_math_values() -> None:
    c, r, w = compile_output(vector_math_node("CROSS_PRODUCT", (1, -2, 3), (0.5, 4, -2)),
                             "Vector", "vector")
    assert w == []
    assert evaluate(c, r, 3) == pytest.approx([-8, 3.5, 5])
    c, r, _ = compile_output(vector_math_node("DOT_PRODUCT", (1, -2, 3), (0.5, 4, -2)), "Value",
                             "float")
    assert evaluate(c, r, 1) == pytest.approx([-13.5])
    c, r, _ = compile_output(vector_math_node("SCALE", (1, -2, 3), scale=1.5), "Vector", "vector")
    assert evaluate(c, r, 3) == pytest.approx([1.5, -3, 4.5])
    c, r, _ = compile_output(vector_math_node("WRAP", (5, -1, 0.5), (2, 2, 2), (0, 0, 2)),
                             "Vector", "vector", V3)
    assert evaluate(c, r, 3) == pytest.approx([1, 1, 2])


def test_vector_math_unknown_operation_warns_and_uses_socket_value() -> None:
    c, r, w = compile_output(vector_math_node("TELEPORT", (1, 2, 3)), "Vector", "vector")
    assert len(w) == 1 and "TELEPORT" in w[0]
    assert not c.builder.program.nodes
    assert c.builder.program.registers[r:r + 3] == [0.25, 0.5, 0.75]


# ---- Map Range, Clamp ----------------------------------------------------------------------------

@pytest.mark.parametrize("version", [V3, V5])
def test_map_range_float_and_vector(version: tuple[int, int, int]) -> None:
    c, r, w = compile_output(map_range_node(interpolation_type="SMOOTHSTEP", clamp=True),
                             "Result", "float", version)
    assert w == []
    assert tuple(last_node(c).modes[:3]) == (0, 2, 1)
    assert evaluate(c, r, 1) == pytest.approx([11.5625])
    c, r, w = compile_output(map_range_node("FLOAT_VECTOR", interpolation_type="LINEAR",
                                            clamp=True), "Vector", "vector", version)
    assert w == []
    assert tuple(last_node(c).modes[:3]) == (1, 0, 1)
    # (0.25, 0.5, 2) from [0,1] to [0,(2,4,8)], clamped: (0.5, 2, 8).
    assert evaluate(c, r, 3) == pytest.approx([0.5, 2, 8])


def test_map_range_unknown_interpolation_warns() -> None:
    c, r, w = compile_output(map_range_node(interpolation_type="BOUNCY"), "Result", "float")
    assert len(w) == 1 and "BOUNCY" in w[0]
    assert c.builder.program.registers[r] == 0.5


def test_clamp() -> None:
    node = Node("ShaderNodeClamp", "Clamp", [val("Value", 5.0), val("Min", 3.0), val("Max", 1.0)],
                [val("Result")], clamp_type="RANGE")
    c, r, _ = compile_output(node, "Result", "float")
    assert evaluate(c, r, 1) == pytest.approx([3.0])
    node.clamp_type = "MINMAX"
    c, r, _ = compile_output(node, "Result", "float")
    assert evaluate(c, r, 1) == pytest.approx([1.0])


# ---- Mapping, Vector Rotate, Normal, Vector Transform --------------------------------------------

def mapping_node(vector_type: str, linked_from: Node | None = None) -> Node:
    node = Node("ShaderNodeMapping", "Mapping",
                [vec("Vector", (1, 2, 3)), vec("Location", (10, 0, 0)),
                 vec("Rotation", (0, 0, math.pi / 2)), vec("Scale", (2, 1, 1))],
                [vec("Vector")], vector_type=vector_type)
    if linked_from is not None:
        node.inputs[0].links = [Link(linked_from, linked_from.outputs[0])]
    return node


def test_mapping_types_and_texture_coordinate_input() -> None:
    expected = {"POINT": [8, 2, 3], "VECTOR": [-2, 2, 3]}
    for kind, want in expected.items():
        c, r, _ = compile_output(mapping_node(kind), "Vector", "vector")
        assert last_node(c).modes[0] == ("POINT", "TEXTURE", "VECTOR", "NORMAL").index(kind)
        assert evaluate(c, r, 3) == pytest.approx(want, abs=1e-6)
    coords = Node("ShaderNodeTexCoord", "Texture Coordinate", [], [vec("Generated")])
    c, r, _ = compile_output(mapping_node("TEXTURE", coords), "Vector", "vector")
    assert last_node(c).inputs[0] == native.SHADER_INPUTS["generated"][0]
    assert evaluate(c, r, 3, {"generated": (8, 2, 3)}) == pytest.approx([1, 2, 3], abs=1e-6)


def test_vector_rotate() -> None:
    node = Node("ShaderNodeVectorRotate", "Vector Rotate",
                [vec("Vector", (2, 0, 0)), vec("Center", (1, 0, 0)), vec("Axis", (0, 0, 2)),
                 val("Angle", math.pi / 2), vec("Rotation", (0, 0, 0), enabled=False)],
                [vec("Vector")], rotation_type="AXIS_ANGLE", invert=True)
    c, r, _ = compile_output(node, "Vector", "vector", V3)
    assert tuple(last_node(c).modes[:2]) == (0, 1)
    assert evaluate(c, r, 3) == pytest.approx([1, -1, 0], abs=1e-6)


def test_normal_node_direction_is_its_output_value() -> None:
    node = Node("ShaderNodeNormal", "Normal", [vec("Normal", (0, 3, 3))],
                [vec("Normal", (0, 0, 2)), val("Dot")])
    c, r, _ = compile_output(node, "Dot", "float")
    assert evaluate(c, r, 1) == pytest.approx([1 / math.sqrt(2)])
    c, r, _ = compile_output(node, "Normal", "vector")
    assert evaluate(c, r, 3) == pytest.approx([0, 0, 1])


@pytest.mark.parametrize(("version", "want"), [(V3, [0, 0, 1]), (V5, [0, 0, 2])])
def test_vector_transform_equal_spaces(version: tuple[int, int, int], want: list[float]) -> None:
    node = Node("ShaderNodeVectorTransform", "Vector Transform", [vec("Vector", (0, 0, 2))],
                [vec("Vector")], vector_type="NORMAL", convert_from="OBJECT",
                convert_to="OBJECT")
    c, r, w = compile_output(node, "Vector", "vector", version)
    assert w == []
    assert evaluate(c, r, 3) == pytest.approx(want)


def test_vector_transform_between_spaces_warns() -> None:
    node = Node("ShaderNodeVectorTransform", "Vector Transform", [vec("Vector", (0, 0, 2))],
                [vec("Vector")], vector_type="POINT", convert_from="WORLD", convert_to="OBJECT")
    c, r, w = compile_output(node, "Vector", "vector")
    assert len(w) == 1 and "WORLD to OBJECT" in w[0] and "'Vector Transform'" in w[0]
    assert not c.builder.program.nodes
    assert c.builder.program.registers[r:r + 3] == [0.25, 0.5, 0.75]


# ---- Fresnel, Layer Weight -----------------------------------------------------------------------

def view_inputs(backfacing: float = 0.0) -> dict[str, Any]:
    return {"normal": (0, 0, 1), "incoming": (math.sqrt(0.75), 0, 0.5), "backfacing": backfacing}


def fresnel_closed_form(cos_i: float, eta: float) -> float:
    sin_t = math.sqrt(1 - cos_i * cos_i) / eta
    cos_t = math.sqrt(1 - sin_t * sin_t)
    rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return 0.5 * (rs * rs + rp * rp)


@pytest.mark.parametrize("version", [V3, V5])
def test_fresnel_reads_the_view_and_shading_normal(version: tuple[int, int, int]) -> None:
    node = Node("ShaderNodeFresnel", "Fresnel", [val("IOR", 1.5), vec("Normal")],
                [Socket("Fac", "VALUE", name="Factor" if version >= (4, 0, 0) else "Fac")])
    c, r, w = compile_output(node, "Fac", "float", version)
    assert w == []
    n = last_node(c)
    assert n.inputs[1:4] == (native.SHADER_INPUTS["normal"][0], native.SHADER_INPUTS["incoming"][0],
                             native.SHADER_INPUTS["backfacing"][0])
    assert evaluate(c, r, 1, view_inputs()) == pytest.approx([fresnel_closed_form(0.5, 1.5)],
                                                             rel=1e-5)
    assert evaluate(c, r, 1, view_inputs(1.0)) == pytest.approx([1.0])  # total reflection


def test_fresnel_linked_normal_is_used() -> None:
    normal = Node("ShaderNodeNormal", "N", [vec("Normal", (0, 0, 1))], [vec("Normal", (1, 0, 0)),
                                                                          val("Dot")])
    node = Node("ShaderNodeFresnel", "Fresnel", [val("IOR", 1.5), vec("Normal")], [val("Fac")])
    node.inputs[1].links = [Link(normal, normal.outputs[0])]
    c, r, _ = compile_output(node, "Fac", "float")
    assert last_node(c).inputs[1] != native.SHADER_INPUTS["normal"][0]
    # cos against (1, 0, 0) is sqrt(0.75).
    assert evaluate(c, r, 1, view_inputs()) == pytest.approx(
        [fresnel_closed_form(math.sqrt(0.75), 1.5)], rel=1e-5)


def test_layer_weight_outputs() -> None:
    node = Node("ShaderNodeLayerWeight", "Layer Weight", [val("Blend", 0.5), vec("Normal")],
                [val("Fresnel"), val("Facing")])
    c, r, _ = compile_output(node, "Facing", "float")
    assert evaluate(c, r, 1, view_inputs()) == pytest.approx([0.5])
    c, r, _ = compile_output(node, "Fresnel", "float")
    assert evaluate(c, r, 1, view_inputs()) == pytest.approx([fresnel_closed_form(0.5, 2.0)],
                                                             rel=1e-5)


# ---- Blackbody, Wavelength -----------------------------------------------------------------------

def test_colour_matrices_per_generation() -> None:
    # Every config's XYZ -> RGB is within 0.001 of Cycles' built-in XYZ -> Rec.709, so Cycles
    # takes its scene linear as Rec.709 and passes Blackbody's Rec.709 through unchanged.
    for version in (V3, V43, V5):
        assert rec709_to_rgb(version) == ((1, 0, 0), (0, 1, 0), (0, 0, 1))
    m3, m4, m5 = (np.array(xyz_to_rgb(v)) for v in (V3, V43, V5))
    assert not np.allclose(m3, m5, atol=1e-6, rtol=0)
    assert np.allclose(m3, m5, atol=1e-3)
    # 4.0-4.5's config matrix: 2e-5 from 3.x's, 5e-4 from 5.0's.
    assert np.abs(m4 - m3).max() < 2e-5
    assert np.abs(m4 - m5).max() > 5e-4
    # Its inverse's middle row is the luminance Cycles 4.2 and 4.5 render (RGB to BW of unit
    # colours: 0.212674037, 0.715151608, 0.0721754208) within Cycles' ACES round trip, < 6e-7.
    assert np.linalg.inv(m4)[1] == pytest.approx([0.212674037, 0.715151608, 0.0721754208],
                                                 abs=6e-7)
    # XYZ of D65 white (0.95047, 1, 1.08883) maps to RGB (1, 1, 1).
    white = np.array(xyz_to_rgb(V5)) @ np.array([0.95047, 1.0, 1.08883])
    assert white == pytest.approx([1, 1, 1], abs=2e-3)


@pytest.mark.parametrize("version", [V3, V43, V5])
def test_blackbody_and_wavelength(version: tuple[int, int, int]) -> None:
    node = Node("ShaderNodeBlackbody", "Blackbody", [val("Temperature", 12000.0)],
                [Socket("Color", "RGBA")])
    c, r, _ = compile_output(node, "Color", "color", version)
    assert last_node(c).data_count == 9
    assert evaluate(c, r, 3) == pytest.approx([0.8262955, 0.9945081, 1.5663077], rel=5e-4)
    node = Node("ShaderNodeWavelength", "Wavelength", [val("Wavelength", 555.0)],
                [Socket("Color", "RGBA")])
    c, r, _ = compile_output(node, "Color", "color", version)
    xyz = np.array([0.5121, 1.0, 0.0057])
    want = np.maximum(np.array(xyz_to_rgb(version)) @ xyz, 0) / 2.52
    assert evaluate(c, r, 3) == pytest.approx(want, rel=1e-5, abs=1e-7)


@pytest.mark.parametrize(("version", "cycles"), [
    (V3, ((0.0, 0.37348932, 0.0258514564), (0.980824411, 0.0612067766, 0.0))),
    ((4, 5, 15), ((0.0, 0.373489887, 0.0258514546), (0.980818927, 0.0612070113, 0.0))),
    (V5, ((0.0, 0.373480737, 0.0258452371), (0.980980158, 0.0612054989, 0.0))),
])
def test_wavelength_matches_each_blenders_cycles(
        version: tuple[int, int, int],
        cycles: tuple[tuple[float, float, float], ...]) -> None:
    # Cycles 3.4's, 4.5's (4.2's are the same) and 5.0's Wavelength at 510 and 600 nm (a world
    # background rendered to a float EXR). Each goes through its own config's XYZ matrix: 4.5's
    # pixels are 2.4e-4 from what 5.0's matrix gives, ours within 1.6e-5 of each (the
    # colour-matching table's interpolation).
    for nm, want in zip((510.0, 600.0), cycles, strict=True):
        node = Node("ShaderNodeWavelength", "Wavelength", [val("Wavelength", nm)],
                    [Socket("Color", "RGBA")])
        c, r, _ = compile_output(node, "Color", "color", version)
        assert evaluate(c, r, 3) == pytest.approx(want, rel=5e-5, abs=1e-7)


# ---- Light Falloff -------------------------------------------------------------------------------

def light_falloff_node(strength: float, smooth: float) -> Node:
    return Node("ShaderNodeLightFalloff", "Light Falloff",
                [val("Strength", strength), val("Smooth", smooth)],
                [val("Quadratic"), val("Linear"), val("Constant")])


@pytest.mark.parametrize("smooth", [0.0, 1.5])
def test_light_falloff_outputs_at_the_ray_length(smooth: float) -> None:
    # Strength s times l^0, l^1, l^2, then times l^2 / (smooth + l^2) when smooth > 0.
    s, length = 2.0, 3.0
    damp = length**2 / (smooth + length**2) if smooth > 0 else 1.0
    for output, power in (("Quadratic", 0), ("Linear", 1), ("Constant", 2)):
        c, r, w = compile_output(light_falloff_node(s, smooth), output, "float")
        assert w == []
        n = last_node(c)
        assert n.type == native.node_type("light_falloff")
        assert n.inputs[2] == native.SHADER_INPUTS["ray_length"][0]
        assert evaluate(c, r, 1, {"ray_length": length}) == pytest.approx(
            [s * length**power * damp], rel=1e-6)


@pytest.mark.parametrize(("version", "revision"), [(V3, 0), ((4, 3, 0), 0), ((4, 4, 0), 1), (V5, 1)])
def test_light_falloff_at_flt_max_follows_the_release(version: tuple[int, int, int],
                                                      revision: int) -> None:
    # A sun's or the world's ray length: Cycles before 4.4 multiplies by it (Linear 0.5 FLT_MAX),
    # 4.4 and later give the strength.
    flt_max = float(np.finfo(np.float32).max)
    c, r, _ = compile_output(light_falloff_node(0.5, 0.0), "Linear", "float", version)
    assert last_node(c).modes[0] == revision
    want = 0.5 if revision else 0.5 * flt_max
    assert evaluate(c, r, 1, {"ray_length": flt_max}) == pytest.approx([want], rel=1e-6)
