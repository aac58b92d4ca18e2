"""Fixtures for the native-binding and CLI tests (plain Python, no bpy)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", "long: an end-to-end run of a minute or more; make check leaves it out")


@pytest.fixture(scope="session")
def native() -> Any:
    """stratum.native with the library loaded; skips until libstratum.so is built."""
    from stratum import native as mod

    try:
        mod.load_library()
    except mod.StratumError as exc:
        pytest.skip(f"native library not available: {exc}")
    return mod


def look_at_origin_from(z: float) -> np.ndarray:
    """Camera-to-world transform: camera at (0, 0, z) looking down -Z (row-major 4x4)."""
    m = np.eye(4, dtype=np.float32)
    m[2, 3] = z
    return m


def lit_quad_scene(native: Any, light_radius: float, background: float) -> Any:
    """A grey 2x2 quad in front of the camera, lit by a 100 W point light 2 above it of the
    given radius (0: a delta light no ray hits), with a uniform grey background."""
    scene = native.Scene()
    grey = scene.add_material({"model": native.closure_model("diffuse"), "base_color": (0.8, 0.8, 0.8)})
    positions = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float32)
    triangles = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
    mesh = scene.add_mesh(positions, triangles, np.full(2, grey, dtype=np.uint32))
    scene.add_instance(mesh, np.eye(4, dtype=np.float32))
    light = np.eye(4, dtype=np.float32)
    light[2, 3] = 2.0
    scene.add_light(type=native.light_type("point"), strength=100.0, radius=light_radius, transform=light)
    scene.set_camera(native.Camera(transform=look_at_origin_from(4.0)))
    scene.set_background((background, background, background))
    return scene


@pytest.fixture
def tiny_scene(native: Any) -> Any:
    """A lit quad in front of the camera, with a grey background."""
    scene = lit_quad_scene(native, light_radius=0.1, background=0.1)
    yield scene
    scene.close()
