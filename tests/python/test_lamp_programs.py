"""A lamp's emission scaled by a node program through the binding (Scene.set_light_program):
a Light Falloff in the lamp's tree, run at the distance to the lamp, what the library refuses,
and removing it. The native tests (tests/native/lights/test_lamp_programs.cpp) hold the renderer to
the distances; this checks the binding's arguments and errors."""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import pytest

from conftest import lit_quad_scene


def _linear_falloff(native: Any, strength: float) -> Any:
    """Light Falloff on the renderer's ray length, its Linear output copied to RGB at the
    program's registers base + 5 .. + 7."""
    base = native.SHADER_INPUT_REGISTERS
    registers = [0.0] * (base + 8)
    registers[base] = strength
    ray_length = native.SHADER_INPUTS["ray_length"][0]
    falloff = native.ShaderNode(type=native.node_type("light_falloff"), modes=(1,),
                                inputs=(base, base + 1, ray_length),
                                outputs=(base + 2, base + 3, base + 4))
    broadcast = native.ShaderNode(type=native.node_type("copy"), modes=(2,), inputs=(base + 3,),
                                  outputs=(base + 5,))
    return native.ShaderProgram([falloff, broadcast], registers, [])


def _centre(native: Any, scene: Any) -> float:
    """Pixel (4, 4) of an 8 x 8 render with direct light only."""
    with native.Renderer(scene, width=8, height=8, samples=1, seed=1, max_bounces=0,
                         filter_type="box", filter_width=0.01) as renderer:
        renderer.start()
        deadline = time.monotonic() + 60
        while not renderer.wait(100):
            assert time.monotonic() < deadline, "render did not finish"
        pixels = renderer.read_pixels(np.empty(8 * 8 * 4, dtype=np.float32)).reshape(8, 8, 4)
    return float(pixels[4, 4, 0])


def test_a_light_falloff_runs_at_the_distance_to_the_lamp(native: Any) -> None:
    # A delta lamp 2 above the quad, the camera 4 above it (50 mm on a 36 mm sensor: 1.44 either
    # side of the axis, 0.36 per pixel): pixel (4, 4) sees the point 0.18 off the axis in x and
    # y, 2.016135 from the lamp, so the Linear output is 0.5 x that. The sample lies within
    # 0.005 px (1.8e-3) of the centre in x and y, where the distance changes by 0.09 per unit:
    # 1.1e-4 relative.
    distance = float(np.sqrt(4.0 + 2 * 0.18**2))
    with lit_quad_scene(native, light_radius=0.0, background=0.0) as scene:
        plain = _centre(native, scene)
        program = scene.add_shader_program(_linear_falloff(native, 0.5))
        scene.set_light_program(0, program, native.SHADER_INPUT_REGISTERS + 5)
        assert _centre(native, scene) == pytest.approx(plain * 0.5 * distance, rel=1.2e-4)
        scene.set_light_program(0, None)
        assert _centre(native, scene) == plain


def test_the_library_refuses_what_a_lamp_cannot_run(native: Any) -> None:
    with lit_quad_scene(native, light_radius=0.0, background=0.0) as scene:
        program = scene.add_shader_program(_linear_falloff(native, 0.5))
        with pytest.raises(native.StratumError, match="light_id 3 is not a light"):
            scene.set_light_program(3, program, native.SHADER_INPUT_REGISTERS + 5)
        position = native.SHADER_INPUTS["position"][0]
        reads_position = native.ShaderProgram(
            [native.ShaderNode(type=native.node_type("copy"), modes=(1,), inputs=(position,),
                               outputs=(native.SHADER_INPUT_REGISTERS,))],
            [0.0] * (native.SHADER_INPUT_REGISTERS + 3), [])
        other = scene.add_shader_program(reads_position)
        with pytest.raises(native.StratumError, match="may read only RAY_LENGTH"):
            scene.set_light_program(0, other, native.SHADER_INPUT_REGISTERS)
        with pytest.raises(ValueError, match="light_id"):
            scene.set_light_program(-1, program)
