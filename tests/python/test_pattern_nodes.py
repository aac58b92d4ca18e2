"""Pattern textures (Checker, Gradient, Brick, Magic) and the Image node in programs: their
translation (stratum.shaders.nodes.pattern_textures, image_node) in both Blender generations'
sockets, warnings for what is not supported, and the native result of a translated node against
the formula worked out here."""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from stratum import native
from stratum.shaders.nodes import NodeCompiler

V3 = (3, 4, 1)
V5 = (5, 0, 1)


class Socket:
    def __init__(self, identifier: str, type_: str = "VALUE", default_value: Any = 0.0,
                 name: str | None = None) -> None:
        self.identifier = identifier
        self.name = name or identifier
        self.type = type_
        self.default_value = default_value
        self.links: list[Any] = []
        self.enabled = True

    @property
    def is_linked(self) -> bool:
        return bool(self.links)


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


def link(src: Node, output: str, dst: Socket) -> None:
    out = next(s for s in src.outputs if s.identifier == output)
    dst.links = [SimpleNamespace(from_node=src, from_socket=out, is_muted=False, is_valid=True)]
    out.links.append(SimpleNamespace(to_socket=dst))


def outputs(version: tuple[int, int, int]) -> list[Socket]:
    # 4.x/5.x names the Fac output "Factor"; the identifier is "Fac" in both.
    fac_name = "Factor" if version >= (4, 0, 0) else "Fac"
    return [Socket("Color", "RGBA"), Socket("Fac", "VALUE", name=fac_name)]


def color(value: tuple[float, float, float]) -> tuple[float, ...]:
    return (*value, 1.0)


def checker_node(version: tuple[int, int, int], scale: float = 5.0) -> Node:
    return Node("ShaderNodeTexChecker", "Checker",
                [Socket("Vector", "VECTOR", (0.0, 0.0, 0.0)),
                 Socket("Color1", "RGBA", color((0.8, 0.7, 0.6))),
                 Socket("Color2", "RGBA", color((0.1, 0.2, 0.3))),
                 Socket("Scale", "VALUE", scale)], outputs(version))


def gradient_node(version: tuple[int, int, int], kind: str) -> Node:
    return Node("ShaderNodeTexGradient", "Gradient", [Socket("Vector", "VECTOR", (0.0, 0.0, 0.0))],
                outputs(version), gradient_type=kind)


def brick_node(version: tuple[int, int, int], **props: Any) -> Node:
    values = {"offset_frequency": 2, "squash_frequency": 2, "offset": 0.5, "squash": 1.0}
    values.update(props)
    return Node("ShaderNodeTexBrick", "Brick",
                [Socket("Vector", "VECTOR", (0.0, 0.0, 0.0)),
                 Socket("Color1", "RGBA", color((0.8, 0.8, 0.8))),
                 Socket("Color2", "RGBA", color((0.2, 0.2, 0.2))),
                 Socket("Mortar", "RGBA", color((0.0, 0.0, 0.0))),
                 Socket("Scale", "VALUE", 5.0), Socket("Mortar Size", "VALUE", 0.02),
                 Socket("Mortar Smooth", "VALUE", 0.1), Socket("Bias", "VALUE", 0.0),
                 Socket("Brick Width", "VALUE", 0.5), Socket("Row Height", "VALUE", 0.25)],
                outputs(version), **values)


def magic_node(version: tuple[int, int, int], depth: int = 2) -> Node:
    return Node("ShaderNodeTexMagic", "Magic",
                [Socket("Vector", "VECTOR", (0.0, 0.0, 0.0)), Socket("Scale", "VALUE", 5.0),
                 Socket("Distortion", "VALUE", 1.0)], outputs(version), turbulence_depth=depth)


def image_node(name: str = "Image", projection: str = "FLAT", space: str = "sRGB",
               alpha_mode: str = "STRAIGHT") -> Node:
    image = SimpleNamespace(colorspace_settings=SimpleNamespace(name=space,
                                                                is_data=space == "Non-Color"),
                            alpha_mode=alpha_mode, name=name)
    return Node("ShaderNodeTexImage", name, [Socket("Vector", "VECTOR", (0.0, 0.0, 0.0))],
                [Socket("Color", "RGBA"), Socket("Alpha", "VALUE")], image=image,
                projection=projection, interpolation="Linear", extension="REPEAT")


def compile_output(node: Node, output: str, kind: str,
                   version: tuple[int, int, int] = V5) -> tuple[NodeCompiler, int, list[str]]:
    warnings: list[str] = []
    c = NodeCompiler(version, lambda n, msg: warnings.append(msg))
    consumer = Socket("Target", "RGBA" if kind == "color" else "VALUE")
    link(node, output, consumer)
    return c, c.value(consumer, kind), warnings


def last_node(c: NodeCompiler) -> Any:
    return c.builder.program.nodes[-1]


def evaluate(c: NodeCompiler, register: int, width: int,
             generated: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> np.ndarray:
    scene = native.Scene()
    program_id = scene.add_shader_program(c.builder.program)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    inputs[15:18] = generated
    return scene.evaluate_program(program_id, inputs, register, width)


# ---- translation --------------------------------------------------------------------------------

@pytest.mark.parametrize("version", [V3, V5])
def test_checker_reads_generated_and_its_sockets(version: tuple[int, int, int]) -> None:
    c, fac, warnings = compile_output(checker_node(version), "Fac", "float", version)
    node = last_node(c)
    assert warnings == []
    assert node.type == native.node_type("checker")
    assert node.inputs[0] == native.SHADER_INPUTS["generated"][0]
    assert fac == node.outputs[1]
    # Generated (0.3, 0.1, 0.1) x 5 = (1.5, 0.5, 0.5): x odd, y even, z even: fac 1.
    assert evaluate(c, fac, 1, (0.3, 0.1, 0.1))[0] == 1.0
    assert evaluate(c, fac, 1, (0.1, 0.1, 0.1))[0] == 0.0


@pytest.mark.parametrize("version", [V3, V5])
def test_checker_colour(version: tuple[int, int, int]) -> None:
    c, col, _ = compile_output(checker_node(version), "Color", "color", version)
    assert evaluate(c, col, 3, (0.3, 0.1, 0.1)) == pytest.approx([0.8, 0.7, 0.6])
    assert evaluate(c, col, 3, (0.1, 0.1, 0.1)) == pytest.approx([0.1, 0.2, 0.3])


@pytest.mark.parametrize("version", [V3, V5])
@pytest.mark.parametrize(("kind", "number"), [
    ("LINEAR", 0), ("QUADRATIC", 1), ("EASING", 2), ("DIAGONAL", 3), ("RADIAL", 4),
    ("QUADRATIC_SPHERE", 5), ("SPHERICAL", 6)])
def test_gradient_types_in_cycles_order(version: tuple[int, int, int], kind: str,
                                        number: int) -> None:
    c, fac, _ = compile_output(gradient_node(version, kind), "Fac", "float", version)
    assert last_node(c).modes[0] == number
    x, y, z = 0.25, 0.5, 0.1
    r = max(0.999999 - math.sqrt(x * x + y * y + z * z), 0.0)
    want = {"LINEAR": x, "QUADRATIC": x * x, "EASING": 3 * x * x - 2 * x ** 3,
            "DIAGONAL": (x + y) / 2, "RADIAL": math.atan2(y, x) / (2 * math.pi) + 0.5,
            "QUADRATIC_SPHERE": r * r, "SPHERICAL": r}[kind]
    assert evaluate(c, fac, 1, (x, y, z))[0] == pytest.approx(want, abs=1e-6)


def test_gradient_unknown_type_warns_and_uses_the_socket() -> None:
    c, fac, warnings = compile_output(gradient_node(V5, "SPIRAL"), "Fac", "float")
    assert len(warnings) == 1 and "SPIRAL" in warnings[0]
    assert c.builder.program.registers[fac] == 0.0


@pytest.mark.parametrize(("version", "generation"), [((3, 4, 1), 0), ((3, 5, 0), 1), (V5, 1)])
def test_brick_modes_data_and_generation(version: tuple[int, int, int], generation: int) -> None:
    c, _, warnings = compile_output(brick_node(version, offset_frequency=3, squash_frequency=4,
                                               offset=0.25, squash=1.5), "Color", "color",
                                    version)
    node = last_node(c)
    assert warnings == []
    assert node.type == native.node_type("brick")
    assert tuple(node.modes[:3]) == (3, 4, generation)
    data = c.builder.program.data[node.data_offset:node.data_offset + node.data_count]
    assert data == pytest.approx([0.25, 1.5])
    regs = c.builder.program.registers
    # Inputs in the native order: vector, colour 1, colour 2, mortar, then the six floats.
    assert regs[node.inputs[4]] == 5.0
    assert regs[node.inputs[5]] == pytest.approx(0.02)
    assert regs[node.inputs[9]] == 0.25


def test_brick_mortar_by_hand() -> None:
    # Generated (0.13, 0.0502) x 5: 0.001 above row 1's lower edge, inside the mortar: with
    # smoothing 0.1, 1 - 0.001 / 0.02 = 0.95 is past it: fac 1, the mortar colour (black).
    c, fac, _ = compile_output(brick_node(V5), "Fac", "float")
    assert evaluate(c, fac, 1, (0.13, 0.0502, 0.0))[0] == 1.0
    assert evaluate(c, fac, 1, (0.13, 0.07, 0.0))[0] == 0.0


def test_brick_frequency_out_of_range_warns() -> None:
    _, _, warnings = compile_output(brick_node(V5, offset_frequency=300), "Fac", "float")
    assert len(warnings) == 1 and "offset_frequency" in warnings[0]


@pytest.mark.parametrize("version", [V3, V5])
def test_magic_depth_and_value(version: tuple[int, int, int]) -> None:
    c, col, _ = compile_output(magic_node(version, depth=0), "Color", "color", version)
    assert last_node(c).modes[0] == 0
    # Generated (0.1, 0.2, 0.3), scale 5: x = sin(15) ... at depth 0, distortion 1.
    p = (0.1, 0.2, 0.3)
    want = (0.5 - math.sin(sum(p) * 25) / 2, 0.5 - math.cos((-p[0] + p[1] - p[2]) * 25) / 2,
            0.5 + math.cos((-p[0] - p[1] + p[2]) * 25) / 2)
    assert evaluate(c, col, 3, p) == pytest.approx(want, abs=1e-5)


def test_magic_depth_out_of_range_warns() -> None:
    _, _, warnings = compile_output(magic_node(V5, depth=11), "Fac", "float")
    assert len(warnings) == 1 and "depth" in warnings[0]


def test_texture_mapping_not_identity_warns_once() -> None:
    node = checker_node(V5)
    node.texture_mapping = SimpleNamespace(translation=(0.5, 0, 0), rotation=(0, 0, 0),
                                           scale=(1, 1, 1), use_min=False, use_max=False,
                                           mapping_x="X", mapping_y="Y", mapping_z="Z")
    _, _, warnings = compile_output(node, "Fac", "float")
    assert len(warnings) == 1 and "texture mapping" in warnings[0]
    node = checker_node(V5)
    node.texture_mapping = SimpleNamespace(translation=(0, 0, 0), rotation=(0, 0, 0),
                                           scale=(1, 1, 1), use_min=False, use_max=False,
                                           mapping_x="X", mapping_y="Y", mapping_z="Z")
    assert compile_output(node, "Fac", "float")[2] == []


def test_linked_vector_is_used() -> None:
    coord = Node("ShaderNodeTexCoord", "Texture Coordinate", [],
                 [Socket("UV", "VECTOR"), Socket("Generated", "VECTOR")], object=None)
    node = checker_node(V5)
    link(coord, "UV", node.inputs[0])
    c, _, _ = compile_output(node, "Fac", "float")
    assert last_node(c).inputs[0] == native.SHADER_INPUTS["uv"][0]


# ---- Image --------------------------------------------------------------------------------------

@pytest.mark.parametrize("version", [V3, V5])
def test_image_node_indexes_images_and_reads_uv(version: tuple[int, int, int]) -> None:
    a, b = image_node("A"), image_node("B")
    warnings: list[str] = []
    c = NodeCompiler(version, lambda n, msg: warnings.append(msg))
    ta, tb = Socket("T1", "RGBA"), Socket("T2", "RGBA")
    link(a, "Color", ta)
    link(b, "Color", tb)
    c.value(ta, "color")
    c.value(tb, "color")
    c.value(ta, "color")  # memoised: no second node, no second entry
    assert c.images == [a, b]
    nodes = [n for n in c.builder.program.nodes if n.type == native.node_type("image")]
    assert [n.modes[0] for n in nodes] == [0, 1]
    assert all(n.inputs[0] == native.SHADER_INPUTS["uv"][0] for n in nodes)
    assert warnings == []


@pytest.mark.parametrize(("space", "alpha", "linked", "mode"), [
    ("sRGB", "STRAIGHT", False, 1), ("sRGB", "STRAIGHT", True, 2), ("sRGB", "PREMUL", True, 2),
    ("Non-Color", "STRAIGHT", True, 0), ("sRGB", "CHANNEL_PACKED", True, 0),
    ("sRGB", "NONE", False, 0)])
def test_image_alpha_mode_as_cycles(space: str, alpha: str, linked: bool, mode: int) -> None:
    node = image_node(space=space, alpha_mode=alpha)
    if linked:
        link(node, "Alpha", Socket("Elsewhere", "VALUE"))
    c, _, _ = compile_output(node, "Color", "color")
    assert last_node(c).modes[1] == mode


@pytest.mark.parametrize("projection", ["BOX", "SPHERE", "TUBE"])
def test_image_projection_unsupported(projection: str) -> None:
    c, col, warnings = compile_output(image_node(projection=projection), "Color", "color")
    assert len(warnings) == 1 and projection in warnings[0]
    assert c.images == []
    assert c.builder.program.registers[col:col + 3] == [0.0, 0.0, 0.0]


# ---- Wave ---------------------------------------------------------------------------------------

def wave_node(version: tuple[int, int, int], **props: Any) -> Node:
    values = {"wave_type": "BANDS", "bands_direction": "X", "rings_direction": "X",
              "wave_profile": "SIN"}
    values.update(props)
    return Node("ShaderNodeTexWave", "Wave",
                [Socket("Vector", "VECTOR", (0.0, 0.0, 0.0)), Socket("Scale", "VALUE", 5.0),
                 Socket("Distortion", "VALUE", 0.0), Socket("Detail", "VALUE", 2.0),
                 Socket("Detail Scale", "VALUE", 1.0), Socket("Detail Roughness", "VALUE", 0.5),
                 Socket("Phase Offset", "VALUE", 0.0)], outputs(version), **values)


@pytest.mark.parametrize(("version", "generation"), [
    ((3, 4, 1), 0), ((3, 6, 0), 0), ((4, 0, 2), 1), ((4, 1, 1), 2), ((4, 2, 0), 3), (V5, 3)])
def test_wave_noise_generation_by_version(version: tuple[int, int, int], generation: int) -> None:
    c, _, warnings = compile_output(wave_node(version), "Fac", "float", version)
    assert warnings == []
    assert last_node(c).modes[4] == generation


@pytest.mark.parametrize(("props", "modes"), [
    ({"wave_type": "RINGS", "rings_direction": "SPHERICAL", "wave_profile": "TRI"}, (1, 0, 3, 2)),
    ({"bands_direction": "DIAGONAL", "wave_profile": "SAW"}, (0, 3, 0, 1)),
    ({"bands_direction": "Z"}, (0, 2, 0, 0))])
def test_wave_modes(props: dict[str, str], modes: tuple[int, ...]) -> None:
    c, _, _ = compile_output(wave_node(V5, **props), "Fac", "float")
    assert tuple(last_node(c).modes[:4]) == modes


def test_wave_bands_x_value() -> None:
    # Generated x = 0.1, scale 5: n = 20 x (0.5 + 1e-6) x 0.999999; sine profile 1/2 - cos(n)/2.
    c, fac, _ = compile_output(wave_node(V5), "Fac", "float")
    n = 20 * (0.5 + 1e-6) * 0.999999
    assert evaluate(c, fac, 1, (0.1, 0.3, 0.2))[0] == pytest.approx(0.5 - math.cos(n) / 2,
                                                                     abs=2e-6)


def test_wave_unknown_profile_warns() -> None:
    _, _, warnings = compile_output(wave_node(V5, wave_profile="SQUARE"), "Fac", "float")
    assert len(warnings) == 1 and "SQUARE" in warnings[0]
