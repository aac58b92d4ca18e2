"""The Stratum RenderEngine: what Blender calls. F12 is final_render.py; the frame and its
settings are frame.py; material, light and world thumbnails are preview.py.

render() never lets an exception escape: export errors, native errors and a missing library
are reported with self.report({'ERROR'}, ...) and the render ends cleanly.
"""

from __future__ import annotations

import traceback
from typing import Any

import bpy

from .. import native
from ..engine_id import ENGINE_ID
from ..export.common import ExportCancelled, ExportError, ExportSummary
from . import denoise, render_passes
from .final_render import render_frame
from .preview import render_preview
from .viewport import free_viewport, view_draw, view_update, viewport_call


class StratumRenderEngine(bpy.types.RenderEngine):
    bl_idname = ENGINE_ID
    bl_label = "Stratum"
    # Blender renders material, light and world thumbnails with Stratum (render() with
    # is_preview); Material Preview shading draws with EEVEE, as it does for Cycles.
    bl_use_preview = True
    bl_use_eevee_viewport = True
    bl_use_postprocess = True
    # Show Blender's standard shader nodes (Principled, Diffuse, Emission...) in the node
    # editor: Stratum reads those node trees.
    bl_use_shading_nodes_custom = False

    # Reports of the most recent render (level, message): for tests and the CLI, because
    # background renders do not always surface RenderEngine.report().
    last_reports: list[tuple[str, str]] = []
    last_summary: ExportSummary | None = None

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)  # required in Blender 4.4+

    def __del__(self) -> None:
        # Blender frees the engine when the view leaves Rendered shading, closes or quits.
        free_viewport(id(self))

    def _report(self, level: str, message: str) -> None:
        type(self).last_reports.append((level, message))
        try:
            self.report({level}, message)
        except Exception:  # noqa: BLE001 - reporting must never fail a render
            print(f"Stratum {level}: {message}")

    def render(self, depsgraph: Any) -> None:
        if self.is_preview:
            render_preview(self, depsgraph)  # reports nothing: preview.py says why
            return
        type(self).last_reports = []
        type(self).last_summary = None
        try:
            render_frame(self, depsgraph)
        except ExportCancelled:
            pass
        except (ExportError, native.StratumError) as exc:
            self._report("ERROR", f"Stratum: {exc}")
        except Exception as exc:  # noqa: BLE001 - nothing may crash Blender
            traceback.print_exc()
            self._report("ERROR", f"Stratum internal error: {type(exc).__name__}: {exc}")

    def update_render_passes(self, scene: Any = None, renderlayer: Any = None) -> None:
        """The passes the compositor's Render Layers node shows (Cycles registers Combined
        here too, as the node then takes its sockets from this list alone): Combined, those
        the view layer's toggles ask for, and the denoiser's Noisy Image."""
        try:
            self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", "COLOR")
            render_passes.register_passes(self, scene, renderlayer)
            denoise.register_passes(self, scene, renderlayer)
        except Exception:  # noqa: BLE001 - nothing may crash Blender
            traceback.print_exc()

    # ---- the Rendered viewport (engine/viewport.py) ----------------------------------------

    def view_update(self, context: Any, depsgraph: Any) -> None:
        viewport_call(self, lambda state: view_update(state, depsgraph))

    def view_draw(self, context: Any, depsgraph: Any) -> None:
        viewport_call(self, lambda state: view_draw(state, self, context, depsgraph))


def register() -> None:
    render_passes.register()
    bpy.utils.register_class(StratumRenderEngine)


def unregister() -> None:
    bpy.utils.unregister_class(StratumRenderEngine)
    render_passes.unregister()
