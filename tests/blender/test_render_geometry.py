"""A scene exported outside a render (stratum render --scheduler, the benchmarks) has the
render's geometry: use_render_geometry makes the viewport depsgraph, the only one Python can
evaluate, hold subdivision at its render level, modifiers as they render, and objects as they
render (issue 15: Wolf's 215k triangles come from a render level of 4)."""

from __future__ import annotations

from typing import Any

from stratum.export.render_geometry import use_render_geometry
from stratum.export.sync import export_scene


def test_export_takes_render_levels_modifiers_and_visibility(scene_builder: Any,
                                                              recording_scene: Any) -> None:
    b = scene_builder().basic()
    cube = b.scene.objects["Cube"]
    subsurf = cube.modifiers.new("subdivision", "SUBSURF")
    subsurf.levels, subsurf.render_levels = 0, 2
    # Shown only in renders: a second subdivision, and an object hidden in the viewport.
    extra = cube.modifiers.new("render only", "SUBSURF")
    extra.levels = extra.render_levels = 1
    extra.show_viewport = False
    hidden = b.mesh_object("RenderOnly")
    hidden.location = (3.0, 0.0, 0.0)
    hidden.hide_viewport = True
    # A modifier shown in the viewport only does not render.
    viewport_only = hidden.modifiers.new("viewport only", "SUBSURF")
    viewport_only.levels = 1
    viewport_only.show_render = False

    before = export_scene(b.depsgraph(), recording_scene)
    assert before.object_triangles == {"Cube": 12}
    use_render_geometry(b.scene)
    after = export_scene(b.depsgraph(), type(recording_scene)())
    # 6 faces x 4^(2 + 1) quads x 2 triangles; the hidden cube as it renders: 12 triangles.
    assert after.object_triangles == {"Cube": 6 * 4**3 * 2, "RenderOnly": 12}
