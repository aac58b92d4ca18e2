"""Translation of the colour nodes (stratum.shaders.nodes.color_nodes, ramp_nodes) on plain
stand-ins for Blender nodes, in Blender 3.4's and 5.0's socket layouts, run through the native
library: each node's program evaluated and compared with values computed here."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from stratum.shaders.nodes import NodeCompiler
from stratum.shaders.nodes.ramp_nodes import table_size

V34 = (3, 4, 1)
V42 = (4, 2, 23)
V45 = (4, 5, 15)
V50 = (5, 0, 1)


class Socket:
    def __init__(self, identifier: str, type_: str = "VALUE", default: Any = 0.0,
                 name: str | None = None, enabled: bool = True) -> None:
        self.identifier = identifier
        self.name = name or identifier
        self.type = type_
        self.default_value = default
        self.enabled = enabled
        self.links: list[Any] = []

    @property
    def is_linked(self) -> bool:
        return bool(self.links)


class Link:
    def __init__(self, from_node: Any, from_socket: Socket) -> None:
        self.from_node, self.from_socket = from_node, from_socket
        self.is_muted, self.is_valid = False, True


class Node:
    def __init__(self, bl_idname: str, inputs: list[Socket], outputs: list[Socket],
                 **props: Any) -> None:
        self.bl_idname = bl_idname
        self.name = bl_idname
        self.inputs, self.outputs = inputs, outputs
        self.mute = False
        for k, v in props.items():
            setattr(self, k, v)

    def out(self, identifier: str) -> Socket:
        return next(s for s in self.outputs if s.identifier == identifier)


def compile_output(node: Node, output: str, kind: str, version: tuple[int, int, int]
                   ) -> tuple[NodeCompiler, int, list[str]]:
    warnings: list[str] = []
    c = NodeCompiler(version, lambda _n, msg: warnings.append(msg))
    sink = Socket("Sink", {"float": "VALUE", "vector": "VECTOR", "color": "RGBA"}[kind],
                  0.0 if kind == "float" else (0.25, 0.5, 0.75, 1.0))
    sink.links = [Link(node, node.out(output))]
    return c, c.value(sink, kind), warnings


def evaluate(native: Any, node: Node, output: str, kind: str = "color",
             version: tuple[int, int, int] = V50) -> tuple[np.ndarray, list[str], Any]:
    c, register, warnings = compile_output(node, output, kind, version)
    with native.Scene() as scene:
        pid = scene.add_shader_program(c.builder.program)
        got = scene.evaluate_program(pid, np.zeros(native.SHADER_INPUT_REGISTERS), register,
                                     1 if kind == "float" else 3)
    return got, warnings, c.builder.program


def rgba(*v: float) -> tuple[float, ...]:
    return (*v, 1.0)


# ---- Mix -------------------------------------------------------------------------------------

def mix_rgb(blend: str, fac: float, a: tuple[float, ...], b: tuple[float, ...],
            version: tuple[int, int, int], use_clamp: bool = False) -> Node:
    fac_name = "Fac" if version < (4, 0, 0) else "Factor"
    return Node("ShaderNodeMixRGB",
                [Socket("Fac", "VALUE", fac, fac_name), Socket("Color1", "RGBA", rgba(*a)),
                 Socket("Color2", "RGBA", rgba(*b))],
                [Socket("Color", "RGBA")], blend_type=blend, use_clamp=use_clamp)


def mix_node(data_type: str, version: tuple[int, int, int], **values: Any) -> Node:
    """A ShaderNodeMix with the sockets of `version` (5.0 adds the rotation ones)."""
    inputs = [Socket("Factor_Float", "VALUE", 0.5, "Factor", data_type != "VECTOR" or
                     values.get("factor_mode") != "NON_UNIFORM"),
              Socket("Factor_Vector", "VECTOR", (0.5, 0.5, 0.5), "Factor",
                     values.get("factor_mode") == "NON_UNIFORM"),
              Socket("A_Float", "VALUE", 0.0, "A", data_type == "FLOAT"),
              Socket("B_Float", "VALUE", 0.0, "B", data_type == "FLOAT"),
              Socket("A_Vector", "VECTOR", (0, 0, 0), "A", data_type == "VECTOR"),
              Socket("B_Vector", "VECTOR", (0, 0, 0), "B", data_type == "VECTOR"),
              Socket("A_Color", "RGBA", rgba(0, 0, 0), "A", data_type == "RGBA"),
              Socket("B_Color", "RGBA", rgba(0, 0, 0), "B", data_type == "RGBA")]
    outputs = [Socket("Result_Float", "VALUE", name="Result"),
               Socket("Result_Vector", "VECTOR", name="Result"),
               Socket("Result_Color", "RGBA", name="Result")]
    if version >= (4, 0, 0):
        inputs += [Socket("A_Rotation", "ROTATION", (0, 0, 0), "A", data_type == "ROTATION"),
                   Socket("B_Rotation", "ROTATION", (0, 0, 0), "B", data_type == "ROTATION")]
        outputs.append(Socket("Result_Rotation", "ROTATION", name="Result"))
    for s in inputs:
        if s.identifier in values:
            s.default_value = values[s.identifier]
    props = {k: values.get(k, d) for k, d in (("blend_type", "MIX"), ("factor_mode", "UNIFORM"),
                                             ("clamp_factor", True), ("clamp_result", False))}
    return Node("ShaderNodeMix", inputs, outputs, data_type=data_type, **props)


@pytest.mark.parametrize("version", [V34, V50])
def test_mix_rgb_clamps_the_factor_and_optionally_the_result(native: Any,
                                                            version: tuple[int, int, int]) -> None:
    a, b = (0.2, 0.6, 0.9), (0.5, 1.0, 0.8)
    got, warnings, _ = evaluate(native, mix_rgb("ADD", 1.5, a, b, version), "Color",
                                version=version)
    assert warnings == []
    assert got == pytest.approx([0.7, 1.6, 1.7], abs=1e-6)
    got, _, _ = evaluate(native, mix_rgb("ADD", 1.5, a, b, version, True), "Color",
                         version=version)
    assert got == pytest.approx([0.7, 1.0, 1.0], abs=1e-6)


# Every blend by Blender's identifier, as Cycles computes it per channel at t = 0.4.
BLENDS: dict[str, Callable[[float, float, float], float]] = {
    "MIX": lambda t, a, b: a + t * (b - a),
    "DARKEN": lambda t, a, b: a + t * (min(a, b) - a),
    "MULTIPLY": lambda t, a, b: a * (1 - t + t * b),
    "BURN": lambda t, a, b: min(max(1 - (1 - a) / (1 - t + t * b), 0.0), 1.0),
    "LIGHTEN": lambda t, a, b: a + t * (max(a, b) - a),
    "SCREEN": lambda t, a, b: 1 - (1 - t * b) * (1 - a),
    "DODGE": lambda t, a, b: min(1.0, a / (1 - t * b)),
    "ADD": lambda t, a, b: a + t * b,
    "OVERLAY": lambda t, a, b: (a * (1 - t + 2 * t * b) if a < 0.5
                                else 1 - (1 - t + 2 * t * (1 - b)) * (1 - a)),
    "SOFT_LIGHT": lambda t, a, b: (1 - t) * a + t * ((1 - a) * b * a + a * (1 - (1 - b) * (1 - a))),
    "LINEAR_LIGHT": lambda t, a, b: a + t * (2 * b - 1),
    "DIFFERENCE": lambda t, a, b: a + t * (abs(a - b) - a),
    "EXCLUSION": lambda t, a, b: max(0.0, a + t * (b - 2 * a * b)),
    "SUBTRACT": lambda t, a, b: a - t * b,
    "DIVIDE": lambda t, a, b: a if b == 0 else (1 - t) * a + t * a / b,
}


@pytest.mark.parametrize("blend", sorted(BLENDS))
def test_mix_color_blends_by_identifier(native: Any, blend: str) -> None:
    a, b = (0.2, 0.6, 0.9), (0.5, 0.25, 0.8)
    node = mix_node("RGBA", V50, blend_type=blend, Factor_Float=0.4, A_Color=rgba(*a),
                    B_Color=rgba(*b))
    got, warnings, _ = evaluate(native, node, "Result_Color")
    assert warnings == []
    assert got == pytest.approx([BLENDS[blend](0.4, x, y) for x, y in zip(a, b, strict=True)],
                                abs=1e-6)


def test_mix_hsv_blends(native: Any) -> None:
    # (0.8, 0.4, 0.2): hue 1/18, saturation 0.75, value 0.8. (0.2, 0.2, 0.8): hue 2/3, s 0.75.
    a, blue = (0.8, 0.4, 0.2), (0.2, 0.2, 0.8)
    for blend in ("HUE", "COLOR"):
        node = mix_node("RGBA", V34, blend_type=blend, Factor_Float=1.0, A_Color=rgba(*a),
                        B_Color=rgba(*blue))
        assert evaluate(native, node, "Result_Color", version=V34)[0] == pytest.approx(
            [0.2, 0.2, 0.8], abs=1e-5)
    node = mix_node("RGBA", V34, blend_type="VALUE", Factor_Float=0.4, A_Color=rgba(*a),
                    B_Color=rgba(0.5, 0.5, 1.0))
    assert evaluate(native, node, "Result_Color", version=V34)[0] == pytest.approx(
        [0.88, 0.44, 0.22], abs=1e-5)
    node = mix_node("RGBA", V34, blend_type="SATURATION", Factor_Float=0.4, A_Color=rgba(*a),
                    B_Color=rgba(0.5, 0.5, 1.0))
    assert evaluate(native, node, "Result_Color", version=V34)[0] == pytest.approx(
        [0.8, 0.8 * (1 - 0.65 * 2 / 3), 0.8 * 0.35], abs=1e-5)


@pytest.mark.parametrize("version", [V34, V50])
def test_mix_float_and_vector_kinds(native: Any, version: tuple[int, int, int]) -> None:
    node = mix_node("FLOAT", version, Factor_Float=1.25, A_Float=2.0, B_Float=6.0,
                    clamp_factor=False)
    assert evaluate(native, node, "Result_Float", "float", version)[0] == pytest.approx(7.0)
    node = mix_node("FLOAT", version, Factor_Float=1.25, A_Float=2.0, B_Float=6.0)
    assert evaluate(native, node, "Result_Float", "float", version)[0] == pytest.approx(6.0)
    node = mix_node("VECTOR", version, Factor_Float=-0.5, A_Vector=(1, 2, 3),
                    B_Vector=(3, 2, -1), clamp_factor=False)
    assert evaluate(native, node, "Result_Vector", "vector", version)[0] == pytest.approx(
        [0.0, 2.0, 5.0])
    node = mix_node("VECTOR", version, factor_mode="NON_UNIFORM",
                    Factor_Vector=(0.25, -1.0, 2.0), A_Vector=(1, 2, 3), B_Vector=(3, 2, -1))
    got, warnings, _ = evaluate(native, node, "Result_Vector", "vector", version)
    assert warnings == []
    assert got == pytest.approx([1.5, 2.0, -1.0])


def test_mix_rotation_is_unsupported_with_one_warning(native: Any) -> None:
    node = mix_node("ROTATION", V50)
    got, warnings, _ = evaluate(native, node, "Result_Rotation", "vector")
    assert len(warnings) == 1 and "data type ROTATION" in warnings[0]
    assert got == pytest.approx([0.25, 0.5, 0.75])  # the consuming socket's own value


# ---- Adjustments -----------------------------------------------------------------------------

def hue_sat(version: tuple[int, int, int], hue: float) -> Node:
    fac = "Fac" if version < (4, 0, 0) else "Factor"
    return Node("ShaderNodeHueSaturation",
                [Socket("Hue", "VALUE", hue), Socket("Saturation", "VALUE", 1.0),
                 Socket("Value", "VALUE", 1.0), Socket("Fac", "VALUE", 1.0, fac),
                 Socket("Color", "RGBA", rgba(0.8, 0.4, 0.2))], [Socket("Color", "RGBA")])


def test_hue_saturation_wraps_hue_as_each_version(native: Any) -> None:
    # Hue -1: 1/18 - 0.5 = -4/9. Blender 4.3+ wraps to 5/9 (200 degrees); 3.4's fmod keeps -4/9,
    # whose HSV sector is none of 0..4: (v, p, q).
    got, _, program = evaluate(native, hue_sat(V50, -1.0), "Color")
    assert program.nodes[-1].modes[0] == 0
    assert got == pytest.approx([0.2, 0.6, 0.8], abs=1e-5)
    got, _, program = evaluate(native, hue_sat(V34, -1.0), "Color", version=V34)
    assert program.nodes[-1].modes[0] == 1
    assert got == pytest.approx([0.8, 0.2, 0.6], abs=1e-5)
    assert evaluate(native, hue_sat((4, 2, 0), 0.5), "Color", version=(4, 2, 0))[2].nodes[
        -1].modes[0] == 1


@pytest.mark.parametrize("version", [V34, V50])
def test_invert_gamma_bright_contrast_rgb_to_bw(native: Any,
                                                version: tuple[int, int, int]) -> None:
    fac = "Fac" if version < (4, 0, 0) else "Factor"
    node = Node("ShaderNodeInvert", [Socket("Fac", "VALUE", 0.25, fac),
                                     Socket("Color", "RGBA", rgba(0.2, 1.0, 2.0))],
                [Socket("Color", "RGBA")])
    assert evaluate(native, node, "Color", version=version)[0] == pytest.approx(
        [0.35, 0.75, 1.25])
    node = Node("ShaderNodeGamma", [Socket("Color", "RGBA", rgba(0.5, -0.5, 0.0)),
                                    Socket("Gamma", "VALUE", 2.2)], [Socket("Color", "RGBA")])
    assert evaluate(native, node, "Color", version=version)[0] == pytest.approx(
        [0.5 ** 2.2, -0.5, 0.0], abs=1e-6)
    bright = "Bright" if version < (4, 0, 0) else "Brightness"
    node = Node("ShaderNodeBrightContrast",
                [Socket("Color", "RGBA", rgba(0.5, 0.1, 0.9)), Socket("Bright", "VALUE", 0.1,
                                                                       bright),
                 Socket("Contrast", "VALUE", 1.0)], [Socket("Color", "RGBA")])
    assert evaluate(native, node, "Color", version=version)[0] == pytest.approx(
        [0.6, 0.0, 1.4], abs=1e-6)
    node = Node("ShaderNodeRGBToBW", [Socket("Color", "RGBA", rgba(1.0, 0.5, 0.25))],
                [Socket("Val")])
    weights = LUMINANCE[version]
    assert evaluate(native, node, "Val", "float", version)[0] == pytest.approx(
        weights[0] + 0.5 * weights[1] + 0.25 * weights[2], abs=1e-6)


# Cycles' luminance weights (rgb_to_y): RGB to BW of unit red, green and blue rendered by Cycles
# 3.4, 4.2, 4.5 and 5.0 (docs/blender_versions.md). 3.x's and 5.0's differ from 4.x's by 1e-6 and
# 3.4e-5 (red): a colour whose weighted channels nearly cancel shows it.
LUMINANCE = {V34: (0.212672979, 0.715152621, 0.0721754432),
             V42: (0.212674037, 0.715151608, 0.0721754208),
             V45: (0.212674037, 0.715151608, 0.0721754208),
             V50: (0.212639123, 0.715169132, 0.0721927583)}


@pytest.mark.parametrize("version", list(LUMINANCE))
def test_luminance_weights_of_each_blender(native: Any, version: tuple[int, int, int]) -> None:
    for k, weight in enumerate(LUMINANCE[version]):
        unit = rgba(*(1.0 if i == k else 0.0 for i in range(3)))
        bw = Node("ShaderNodeRGBToBW", [Socket("Color", "RGBA", unit)], [Socket("Val")])
        rgb = Node("ShaderNodeRGB", [], [Socket("Color", "RGBA", unit)])
        # RGB to BW, a colour output read as a float (the compiler's conversion node) and an
        # unlinked colour socket read as a float (folded into a constant), as in Cycles.
        c = NodeCompiler(version, lambda _n, _m: None)
        constant = c.constant_of(Socket("Color", "RGBA", unit), "float")
        with native.Scene() as scene:
            pid = scene.add_shader_program(c.builder.program)
            folded = scene.evaluate_program(pid, np.zeros(native.SHADER_INPUT_REGISTERS),
                                            constant, 1)[0]
        for got in (evaluate(native, bw, "Val", "float", version)[0][0],
                    evaluate(native, rgb, "Color", "float", version)[0][0], folded):
            assert got == pytest.approx(weight, rel=1e-7), (k, got)
    # Where the weighted channels nearly cancel, each Blender's own weights are needed: the
    # other configurations' are 2e-6 (3.x against 4.x) to 7e-5 (5.0) off here, the float
    # rounding of this sum a few 1e-8.
    colour = rgba(1.0, -1.0, 6.96)
    node = Node("ShaderNodeRGBToBW", [Socket("Color", "RGBA", colour)], [Socket("Val")])
    got = evaluate(native, node, "Val", "float", version)[0][0]
    for other, weights in LUMINANCE.items():
        want = sum(w * v for w, v in zip(weights, colour[:3], strict=True))
        if weights == LUMINANCE[version]:
            assert got == pytest.approx(want, abs=1e-7)
        else:
            assert abs(got - want) > 1e-6, other


# ---- Separate / Combine ----------------------------------------------------------------------

@pytest.mark.parametrize(("mode", "expected"), [("RGB", (0.8, 0.4, 0.2)),
                                                ("HSV", (1 / 18, 0.75, 0.8)),
                                                ("HSL", (1 / 18, 0.6, 0.5))])
def test_separate_and_combine_color(native: Any, mode: str,
                                    expected: tuple[float, float, float]) -> None:
    sep = Node("ShaderNodeSeparateColor", [Socket("Color", "RGBA", rgba(0.8, 0.4, 0.2))],
               [Socket("Red"), Socket("Green"), Socket("Blue")], mode=mode)
    for k, out in enumerate(("Red", "Green", "Blue")):
        assert evaluate(native, sep, out, "float")[0][0] == pytest.approx(expected[k], abs=1e-6)
    comb = Node("ShaderNodeCombineColor", [Socket("Red", "VALUE", expected[0]),
                                           Socket("Green", "VALUE", expected[1]),
                                           Socket("Blue", "VALUE", expected[2])],
                [Socket("Color", "RGBA")], mode=mode)
    got, warnings, program = evaluate(native, comb, "Color")
    assert warnings == []
    assert got == pytest.approx([0.8, 0.4, 0.2], abs=1e-5)
    # RGB needs no conversion node.
    assert any(n.type == native.node_type("combine_color") for n in program.nodes) == (
        mode != "RGB")


def test_blender_3_separate_combine_rgb_and_hsv(native: Any) -> None:
    sep = Node("ShaderNodeSeparateHSV", [Socket("Color", "RGBA", rgba(0.5, 0.5, 1.0))],
               [Socket("H"), Socket("S"), Socket("V")])
    assert [evaluate(native, sep, k, "float", V34)[0][0] for k in "HSV"] == pytest.approx(
        [2 / 3, 0.5, 1.0], abs=1e-6)
    comb = Node("ShaderNodeCombineHSV", [Socket("H", "VALUE", 1.0), Socket("S", "VALUE", 1.0),
                                         Socket("V", "VALUE", 0.5)], [Socket("Color", "RGBA")])
    assert evaluate(native, comb, "Color", version=V34)[0] == pytest.approx([0.5, 0.0, 0.0])
    sep = Node("ShaderNodeSeparateRGB", [Socket("Image", "RGBA", rgba(0.1, 0.2, 0.3))],
               [Socket("R"), Socket("G"), Socket("B")])
    assert [evaluate(native, sep, k, "float", V34)[0][0] for k in "RGB"] == pytest.approx(
        [0.1, 0.2, 0.3], abs=1e-7)
    comb = Node("ShaderNodeCombineRGB", [Socket("R", "VALUE", 0.1), Socket("G", "VALUE", 0.2),
                                         Socket("B", "VALUE", 0.3)], [Socket("Image", "RGBA")])
    assert evaluate(native, comb, "Image", version=V34)[0] == pytest.approx([0.1, 0.2, 0.3])


# ---- Color Ramp and curves -------------------------------------------------------------------

class Ramp:
    """A ColorRamp stand-in: black (alpha 1) below 0.5, white (alpha 0) from 0.5 when CONSTANT,
    else linear from black at 0 to (1, 0.5, 0) with alpha 0 at 1."""

    def __init__(self, interpolation: str) -> None:
        self.interpolation = interpolation
        self.calls: list[float] = []

    def evaluate(self, x: float) -> tuple[float, float, float, float]:
        self.calls.append(x)
        if self.interpolation == "CONSTANT":
            return (1.0, 1.0, 1.0, 0.0) if x >= 0.5 else (0.0, 0.0, 0.0, 1.0)
        return (x, 0.5 * x, 0.0, 1.0 - x)


def ramp_node(interpolation: str, fac: float) -> Node:
    return Node("ShaderNodeValToRGB", [Socket("Fac", "VALUE", fac)],
                [Socket("Color", "RGBA"), Socket("Alpha")], color_ramp=Ramp(interpolation))


def test_color_ramp_table_size_as_each_version(native: Any) -> None:
    # Cycles measured: this ramp at 0.501 is black in 3.4 (256 entries at i / 255, entry 127 at
    # 0.498) and white in 5.0 (257 at i / 256, entry 128 at 0.5).
    assert (table_size(V34), table_size(V50)) == (256, 257)
    for version, white in ((V34, False), (V50, True)):
        node = ramp_node("CONSTANT", 0.501)
        got, warnings, program = evaluate(native, node, "Color", version=version)
        assert warnings == []
        assert got == pytest.approx([1.0 if white else 0.0] * 3)
        assert program.nodes[-1].modes[0] == 0  # not interpolated
        n = table_size(version)
        assert node.color_ramp.calls == pytest.approx([i / (n - 1) for i in range(n)])


def test_color_ramp_linear_and_alpha(native: Any) -> None:
    node = ramp_node("EASE", 0.3)
    got, _, program = evaluate(native, node, "Color")
    assert program.nodes[-1].modes[0] == 1
    assert got == pytest.approx([0.3, 0.15, 0.0], abs=1e-6)
    alpha, _, _ = evaluate(native, ramp_node("LINEAR", 0.3), "Alpha", "float")
    assert alpha[0] == pytest.approx(0.7, abs=1e-6)


class Point:
    def __init__(self, x: float, y: float) -> None:
        self.location = (x, y)


class Curve:
    def __init__(self, fn: Callable[[float], float], x0: float = 0.0, x1: float = 1.0) -> None:
        self.fn = fn
        self.points = [Point(x0, fn(x0)), Point(x1, fn(x1))]


class Mapping:
    def __init__(self, curves: list[Curve], extend: str = "EXTRAPOLATED") -> None:
        self.curves = curves
        self.extend = extend
        self.prepared: list[str] = []

    def initialize(self) -> None:
        self.prepared.append("initialize")

    def update(self) -> None:
        self.prepared.append("update")

    def evaluate(self, curve: Curve, x: float) -> float:
        assert self.prepared, "evaluate() before initialize()"
        return curve.fn(x)


def test_rgb_curves_compose_the_combined_curve_and_extrapolate(native: Any) -> None:
    # R = x^2 on [-1, 1], G = 2x, B = 0.5, combined C = identity on [0, 1]: range [-1, 1].
    mapping = Mapping([Curve(lambda x: x * x, -1.0), Curve(lambda x: 2 * x), Curve(lambda x: 0.5),
                       Curve(lambda x: x)])
    fac = "Fac"
    node = Node("ShaderNodeRGBCurve", [Socket("Fac", "VALUE", 1.0, fac),
                                       Socket("Color", "RGBA", rgba(0.5, 2.0, -2.0))],
                [Socket("Color", "RGBA")], mapping=mapping)
    got, warnings, program = evaluate(native, node, "Color", version=V34)
    assert warnings == [] and mapping.prepared == ["initialize", "update"]
    data = program.data[program.nodes[-1].data_offset:]
    assert data[:2] == [-1.0, 1.0] and len(data) == 2 + 3 * 256
    # R at 0.5 interpolates x^2 between entries (error < 1e-4 at this spacing); G at 2 is
    # extrapolated linearly from the last two entries (4); B at -2 holds 0.5.
    assert got == pytest.approx([0.25, 4.0, 0.5], abs=1e-4)
    mapping.extend = "HORIZONTAL"
    got, _, _ = evaluate(native, node, "Color", version=V34)
    assert got == pytest.approx([0.25, 2.0, 0.5], abs=1e-4)


@pytest.mark.parametrize("version", [V34, V50])
def test_vector_and_float_curves(native: Any, version: tuple[int, int, int]) -> None:
    fac = "Fac" if version < (4, 0, 0) else "Factor"
    mapping = Mapping([Curve(lambda x: 1 - x, -1.0), Curve(lambda x: 2 * x), Curve(lambda x: x)])
    node = Node("ShaderNodeVectorCurve", [Socket("Fac", "VALUE", 0.5, fac),
                                          Socket("Vector", "VECTOR", (0.5, 0.5, 3.0))],
                [Socket("Vector", "VECTOR")], mapping=mapping)
    got, warnings, _ = evaluate(native, node, "Vector", "vector", version)
    assert warnings == []
    # Halfway between input and curve: (0.5 + 0.5) / 2, (0.5 + 1) / 2, (3 + 3) / 2.
    assert got == pytest.approx([0.5, 0.75, 3.0], abs=1e-5)
    mapping = Mapping([Curve(lambda x: 3 * x + 1, 0.0, 2.0)])
    node = Node("ShaderNodeFloatCurve", [Socket("Factor", "VALUE", 1.0),
                                         Socket("Value", "VALUE", 1.5)],
                [Socket("Value")], mapping=mapping)
    got, _, program = evaluate(native, node, "Value", "float", version)
    assert got[0] == pytest.approx(5.5, abs=1e-5)
    assert len(program.data) == 2 + table_size(version)
