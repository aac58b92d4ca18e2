"""Sky Texture translation (stratum.shaders.nodes.sky_texture) on plain stand-ins for Blender
nodes: the native node and data per sky type, both Blender generations' property names, and the
warnings for what is not supported."""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from stratum import native
from stratum.shaders.nodes import NodeCompiler
from stratum.shaders.nodes.sky_texture import preetham_data, translate_sky

V3 = (3, 4, 1)
V4 = (4, 5, 15)
V5 = (5, 0, 1)


def sky(sky_type: str, **props: Any) -> Any:
    values: dict[str, Any] = {
        "sun_direction": (0.0, 0.0, 1.0), "turbidity": 2.2, "ground_albedo": 0.3,
        "sun_disc": True, "sun_size": 0.0095, "sun_intensity": 1.0, "sun_elevation": 0.26,
        "sun_rotation": 0.0, "altitude": 0.0, "air_density": 1.0, "dust_density": 1.0,
        "ozone_density": 1.0}
    values.update(props)
    socket = SimpleNamespace(name="Vector", identifier="Vector", links=[], is_linked=False,
                             default_value=(0.0, 0.0, 0.0))
    return SimpleNamespace(name="Sky", bl_idname="ShaderNodeTexSky", sky_type=sky_type,
                           inputs=[socket], outputs=[], mute=False, **values)


def compile_sky(node: Any, version: tuple[int, int, int] = V3) -> tuple[NodeCompiler, int]:
    c = NodeCompiler(version, lambda n, m: None)
    return c, translate_sky(c, node)["Color"]


def test_preetham_data_is_cycles_packing() -> None:
    data = preetham_data((0.0, 0.0, 2.0), 2.2)  # normalised: the sun at the zenith
    assert len(data) == 32
    assert data[1] == pytest.approx(0.0)  # sun theta
    # Padding of the 9-wide configurations past Perez's five coefficients.
    for channel in range(3):
        assert data[5 + 9 * channel + 5: 5 + 9 * channel + 9] == [0.0] * 4
    assert data[5] == pytest.approx(0.1787 * 2.2 - 1.4630)


def test_preetham_node_evaluates_at_the_zenith() -> None:
    c, color = compile_sky(sky("PREETHAM", sun_direction=(0.3, 0.4, 0.6), turbidity=3.0))
    node = c.builder.program.nodes[-1]
    assert node.type == native.node_type("sky") and tuple(node.modes)[:2] == (0, 0)
    assert node.inputs[0] == native.SHADER_INPUTS["generated"][0]
    scene = native.Scene()
    pid = scene.add_shader_program(c.builder.program)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    gen = native.SHADER_INPUTS["generated"][0]
    inputs[gen:gen + 3] = (-0.5135234, -0.85666883, 0.0491154194)
    # Cycles 3.4's pixel at that direction (scripts/cycles_reference/sky.py).
    got = scene.evaluate_program(pid, inputs, color, 3)
    assert got == pytest.approx([0.48978439, 0.469021291, 0.537845731], rel=1e-4)


@pytest.mark.parametrize(("version", "sky_type", "dust_name", "model"),
                         [(V3, "NISHITA", "dust_density", 2),
                          (V5, "SINGLE_SCATTERING", "aerosol_density", 3),
                          (V5, "MULTIPLE_SCATTERING", "aerosol_density", 4)])
def test_nishita_passes_blender_values(version: tuple[int, int, int], sky_type: str,
                                       dust_name: str, model: int) -> None:
    props = {"sun_elevation": 0.4, "sun_rotation": -1.0, "sun_size": 0.02,
             "sun_intensity": 0.5, "altitude": 300.0, "air_density": 1.5, "ozone_density": 2.0,
             dust_name: 3.0}
    node = sky(sky_type, sun_disc=False, **props)
    if dust_name != "dust_density":
        del node.dust_density
    c, _ = compile_sky(node, version)
    program = c.builder.program
    n = program.nodes[-1]
    assert tuple(n.modes)[:2] == (model, 0)
    data = list(program.data)[n.data_offset:n.data_offset + n.data_count]
    assert data == pytest.approx([0.4, -1.0, 0.02, 0.5, 300.0, 1.5, 3.0, 2.0])


@pytest.mark.parametrize("sky_type", ["SOMETHING_NEW"])
def test_unsupported_types_warn_through_the_compiler(sky_type: str) -> None:
    from stratum.shaders.nodes import Unsupported

    with pytest.raises(Unsupported, match=sky_type):
        compile_sky(sky(sky_type), V5)


def test_texture_mapping_other_than_identity_is_warned() -> None:
    warnings: list[str] = []
    c = NodeCompiler(V3, lambda n, m: warnings.append(m))
    node = sky("PREETHAM")
    node.texture_mapping = SimpleNamespace(translation=(0, 0, 0), rotation=(0, 0, math.pi),
                                           scale=(1, 1, 1), use_min=False, use_max=False)
    translate_sky(c, node)
    assert any("Texture Mapping" in w for w in warnings)


@pytest.mark.parametrize(("version", "sky_type", "matrix"), [
    (V3, "PREETHAM", 0), (V3, "NISHITA", 0), (V4, "PREETHAM", 1), (V4, "NISHITA", 1),
    (V5, "PREETHAM", 2), (V5, "MULTIPLE_SCATTERING", 2)])
def test_xyz_matrix_is_the_colour_configuration_s(version: tuple[int, int, int], sky_type: str,
                                                  matrix: int) -> None:
    node = sky(sky_type)
    if version >= (5, 0, 0):
        node.aerosol_density = node.dust_density
        del node.dust_density
    c, _ = compile_sky(node, version)
    assert tuple(c.builder.program.nodes[-1].modes)[2] == matrix


def _evaluate(c: NodeCompiler, color: int, direction: tuple[float, float, float]) -> np.ndarray:
    scene = native.Scene()
    pid = scene.add_shader_program(c.builder.program)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    gen = native.SHADER_INPUTS["generated"][0]
    inputs[gen:gen + 3] = direction
    return scene.evaluate_program(pid, inputs, color, 3)


@pytest.mark.parametrize(("version", "direction", "cycles"), [
    (V3, (-0.68892938, -0.41288352, 0.5957377), (0.06552908, 0.09531364, 0.14335762)),
    (V3, (0.91333187, -0.22882426, -0.33684468), (0.19828089, 0.22876978, 0.21615353)),
    (V4, (-0.68892938, -0.41288352, 0.5957377), (0.06552866, 0.09531379, 0.14335771)),
    (V4, (0.91333187, -0.22882426, -0.33684468), (0.19827975, 0.22877017, 0.21615361)),
    (V5, (-0.68892938, -0.41288352, 0.5957377), (0.06553943, 0.09531147, 0.14332327)),
])
def test_hosek_wilkie_matches_cycles(version: tuple[int, int, int],
                                     direction: tuple[float, float, float],
                                     cycles: tuple[float, float, float]) -> None:
    # Cycles 3.4's, 4.5's and 5.0's pixels (scripts/cycles_reference/sky.py): the dataset cooked
    # here, through each version's XYZ matrix (4.5's and 5.0's are 2.4e-4 apart).
    node = sky("HOSEK_WILKIE", sun_direction=(-0.5, 0.2, 0.4), turbidity=4.0, ground_albedo=0.5)
    c, color = compile_sky(node, version)
    assert c.builder.program.nodes[-1].modes[0] == 1
    assert _evaluate(c, color, direction) == pytest.approx(cycles, rel=1e-4)


def test_hosek_wilkie_turbidity_ends() -> None:
    from stratum.shaders.nodes.sky_texture import hosek_wilkie_data

    # Below 1 turbidity is clamped to 1 (Blender's range); at 10 the last block is taken alone,
    # continuous with the interpolation just below it.
    assert hosek_wilkie_data((0, 0.5, 0.5), 0.3, 0.2) == hosek_wilkie_data((0, 0.5, 0.5), 1.0, 0.2)
    low, high = hosek_wilkie_data((0, 0.5, 0.5), 9.999, 0.2), hosek_wilkie_data((0, 0.5, 0.5),
                                                                                 10.0, 0.2)
    assert low == pytest.approx(high, rel=1e-2, abs=1e-3)
