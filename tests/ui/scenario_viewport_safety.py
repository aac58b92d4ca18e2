"""What a user may do while the Rendered viewport renders must not crash Blender (issue 14,
acceptance 7), in Blender 3.4's UI: delete the object being rendered, undo, switch the engine
to Cycles and back, close the viewport (the area becomes another editor) and open it again,
and finally quit Blender with the viewport rendering. Each action happens while a render is
under way (many samples, so that it is); the scenario checks that Blender is still drawing
after each and that the viewport starts again where it should. The exit code of the quit is
checked by the test (tests/ui/conftest.py)."""

from __future__ import annotations

from collections.abc import Iterator

import bpy
from driver import Scenario


def rendering(s: Scenario) -> Iterator[float]:
    """A Rendered view with a long render in progress."""
    s.space().shading.type = "RENDERED"
    yield 1.5


def steps(s: Scenario) -> Iterator[float]:
    import stratum

    stratum.register()
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    scene.stratum.preview_samples = 4096
    s.plain_view()
    yield from rendering(s)
    s.screenshot("rendering")

    victim = bpy.data.objects["TallBox"]
    bpy.data.objects.remove(victim, do_unlink=True)
    bpy.ops.ed.undo_push(message="delete TallBox")
    yield 1.5
    s.screenshot("deleted")
    s.log("deleted the object being rendered")

    with s.override():
        bpy.ops.ed.undo()
    yield 1.5
    s.results["undo_restored"] = "TallBox" in bpy.data.objects
    s.screenshot("undone")
    s.log("undo")

    scene = bpy.context.scene  # undo reloads the scene: the old reference is stale
    scene.render.engine = "CYCLES"
    yield 1.5
    scene.render.engine = "STRATUM"
    yield 1.5
    s.screenshot("engine_back")
    s.log("engine switched to Cycles and back")

    _, area, _ = s.view3d()
    area.type = "IMAGE_EDITOR"
    yield 1.0
    area.type = "VIEW_3D"
    yield from rendering(s)
    s.screenshot("reopened")
    s.log("viewport closed and opened again")


if __name__ == "__main__":
    Scenario.main(steps)
