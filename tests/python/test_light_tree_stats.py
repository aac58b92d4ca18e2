"""The light tree's build report (issue 16, "build time and memory reported"): a render that
chooses lights by the tree (light_selection tree, or auto with more than 3 lights) reports the
tree's build seconds and bytes in its progress; a render without one reports 0, 0, and so does
one whose integrator never chooses a light for a shading point (ao). Also the add-on's stats
line, which shows them."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from conftest import look_at_origin_from

# A tree of N point lamps has 2N - 1 nodes of a few dozen bytes and one trail per lamp: well
# over 16 bytes per lamp and well under 1 kB.
BYTES_PER_LAMP = (16, 1024)


def lamp_scene(native: Any, lamps: int) -> Any:
    """A grey 2x2 quad seen from above, lit by `lamps` point lamps (radius 0.05) in a row 1 m
    above it."""
    scene = native.Scene()
    grey = scene.add_material({"model": native.closure_model("diffuse"), "base_color": (0.8, 0.8, 0.8)})
    positions = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float32)
    triangles = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
    scene.add_instance(scene.add_mesh(positions, triangles, np.full(2, grey, dtype=np.uint32)),
                       np.eye(4, dtype=np.float32))
    for k in range(lamps):
        m = np.eye(4, dtype=np.float32)
        m[0, 3], m[2, 3] = -1.0 + 2.0 * (k + 0.5) / lamps, 1.0
        scene.add_light(type=native.light_type("point"), strength=10.0, radius=0.05, transform=m)
    scene.set_camera(native.Camera(transform=look_at_origin_from(4.0)))
    return scene


def render_progress(native: Any, scene: Any, **settings: Any) -> Any:
    with native.Renderer(scene, width=8, height=8, samples=1, **settings) as renderer:
        renderer.start()
        while not renderer.wait(100):
            pass
        return renderer.progress()


@pytest.mark.parametrize(("lamps", "settings", "uses_tree"), [
    (16, {"light_selection": "tree"}, True),
    (16, {}, True),  # auto (the default) above 3 lights
    (4, {"light_selection": "auto"}, True),
    (3, {"light_selection": "auto"}, False),
    (16, {"light_selection": "mixed"}, False),
    (16, {"light_selection": "power"}, False),
    (16, {"light_selection": "tree", "integrator": "ao"}, False),
])
def test_progress_reports_the_tree_it_built(native: Any, lamps: int, settings: dict[str, Any],
                                            uses_tree: bool) -> None:
    scene = lamp_scene(native, lamps)
    try:
        p = render_progress(native, scene, **settings)
    finally:
        scene.close()
    if not uses_tree:
        assert (p.counters["light_tree.seconds"], p.counters["light_tree.bytes"]) == (0.0, 0.0)
        return
    assert BYTES_PER_LAMP[0] * lamps < p.counters["light_tree.bytes"] < BYTES_PER_LAMP[1] * lamps
    # Built within the render (the build is part of its path-tracing time).
    assert 0.0 <= p.counters["light_tree.seconds"] <= p.render_seconds


def test_auto_is_the_default_and_last_choice(native: Any) -> None:
    info = next(s for s in native.settings() if s.name == "light_selection")
    assert info.default == "auto"
    assert [c.name for c in info.choices][-1] == "auto"
    # Saved .blend files store the position: the older four keep theirs.
    assert [c.name for c in info.choices][:4] == ["mixed", "power", "uniform", "tree"]
