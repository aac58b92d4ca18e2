"""The render's geometry in the viewport depsgraph.

Python can evaluate only the viewport depsgraph (`Context.evaluated_depsgraph_get`); a render
gets the render depsgraph, in which every modifier is as it renders (Properties > Modifiers:
"Realtime" vs "Render", subdivision's Levels Viewport vs Render) and objects as they render.
A script that exports a scene outside a render (`stratum render --scheduler`, the benchmarks)
first makes the viewport show what the render would, so that it exports the same triangles
(the Wolf scene: 215k at its render level of 4, 3k at its viewport level). It changes the
open file: call it in a Blender process that does not save it.
"""

from __future__ import annotations

from typing import Any


def use_render_geometry(scene: Any) -> None:
    """Modifiers shown and subdivided, and objects hidden or shown, as the render has them."""
    for ob in scene.objects:
        ob.hide_viewport = ob.hide_render
        for modifier in ob.modifiers:
            modifier.show_viewport = modifier.show_render
            if hasattr(modifier, "render_levels") and hasattr(modifier, "levels"):
                modifier.levels = modifier.render_levels
