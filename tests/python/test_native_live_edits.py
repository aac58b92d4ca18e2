"""The live-edit bindings (Scene.set_instance, set_material, set_closure_material, set_light):
an edit reaches a renderer made before it at its next start, with the image of a scene built
with the edit from the start (tests/native/scene/test_live_scene.cpp holds the native side to that,
bit for bit); bad edits are refused by name."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from conftest import lit_quad_scene

SETTINGS = {"width": 16, "height": 12, "samples": 4, "seed": 3, "max_bounces": 2, "threads": 2}


def _translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = (x, y, z)
    return m


def _move_quad(native: Any, scene: Any) -> None:
    scene.set_instance(0, native.Instance(0, _translation(0.3, 0.0, 0.0)))


def _recolour_quad(native: Any, scene: Any) -> None:
    scene.set_material(0, native.Material(model=native.closure_model("diffuse"),
                                          base_color=(0.2, 0.6, 0.9)))


def _mix_quad(native: Any, scene: Any) -> None:
    scene.set_closure_material(0, [
        ((0.5, 0.5, 0.5), native.Material(model=native.closure_model("diffuse"),
                                          base_color=(0.9, 0.1, 0.1))),
        ((0.5, 0.5, 0.5), native.Material(model=native.closure_model("glossy"), roughness=0.3))])


def _dim_light(native: Any, scene: Any) -> None:
    # lit_quad_scene's light, at 40 W instead of 100 W
    scene.set_light(0, native.Light(type=native.light_type("point"), strength=40.0, radius=0.1,
                                    transform=_translation(0.0, 0.0, 2.0)))


EDITS: dict[str, Callable[[Any, Any], None]] = {
    "instance": _move_quad, "material": _recolour_quad, "closure material": _mix_quad,
    "light": _dim_light,
}


def _render(renderer: Any) -> np.ndarray:
    renderer.start()
    deadline = time.monotonic() + 60
    while not renderer.wait(100):
        assert time.monotonic() < deadline, "render did not finish"
    return renderer.read_pixels().copy()


@pytest.mark.parametrize("kind", sorted(EDITS))
def test_an_edit_reaches_the_renderer_as_a_fresh_build_would(native: Any, kind: str) -> None:
    edit = EDITS[kind]
    with lit_quad_scene(native, light_radius=0.1, background=0.1) as scene, \
            native.Renderer(scene, **SETTINGS) as renderer:
        before = _render(renderer)
        edit(native, scene)
        after = _render(renderer)
    with lit_quad_scene(native, light_radius=0.1, background=0.1) as scene:
        edit(native, scene)
        with native.Renderer(scene, **SETTINGS) as renderer:
            fresh = _render(renderer)
    assert np.array_equal(after, fresh)
    assert not np.array_equal(after, before)


def test_edits_of_parts_that_do_not_exist_are_refused_naming_them(native: Any) -> None:
    with lit_quad_scene(native, light_radius=0.1, background=0.1) as scene:
        with pytest.raises(native.StratumError, match="instance 3"):
            scene.set_instance(3, native.Instance(0, np.eye(4)))
        with pytest.raises(native.StratumError, match="material 5"):
            scene.set_material(5, native.Material())
        with pytest.raises(native.StratumError, match="material 5"):
            scene.set_closure_material(5, [((1.0, 1.0, 1.0), native.Material())])
        with pytest.raises(native.StratumError, match="light 1"):
            scene.set_light(1, native.Light())
        with pytest.raises(native.StratumError):
            scene.set_instance(0, native.Instance(7, np.eye(4)))  # no mesh 7


def test_bad_values_are_refused_before_the_call(native: Any) -> None:
    with lit_quad_scene(native, light_radius=0.1, background=0.1) as scene:
        with pytest.raises(ValueError, match="instance index"):
            scene.set_instance(-1, native.Instance(0, np.eye(4)))
        with pytest.raises(ValueError, match="at least one closure"):
            scene.set_closure_material(0, [])
        with pytest.raises(ValueError, match="unknown field"):
            scene.set_material(0, {"colour": (1.0, 0.0, 0.0)})
        with pytest.raises(ValueError, match="light transform"):
            scene.set_light(0, native.Light(transform=np.eye(3)))
