"""Render-properties panels (laid out like Cycles') and reuse of Blender's own panels."""

from __future__ import annotations

from typing import Any

import bpy

from . import properties

ENGINE_ID = "STRATUM"

# Contexts whose built-in panels Stratum reuses.
REUSED_CONTEXTS = {"material", "world", "data", "object"}
# Built-in panels written for EEVEE that a Stratum user needs: material slots and the
# node-based Surface view of material and world (Cycles' own surface panels live in the
# Cycles add-on, which may be absent, and show Cycles-only settings).
EXTRA_PANELS = (
    "EEVEE_MATERIAL_PT_context_material",
    "EEVEE_MATERIAL_PT_surface",
    "EEVEE_WORLD_PT_surface",
)
# Panels that draw Cycles-only properties (scene.cycles, light.cycles, ...).
SKIP_PREFIXES = ("CYCLES_", "NODE_CYCLES_")

_patched: list[type] = []


def _settings_layout(panel: bpy.types.Panel,
                     context: bpy.types.Context) -> tuple[bpy.types.UILayout, Any]:
    """The panel's layout set up as Cycles' panels set theirs (labels left of their values,
    no animation decorators), and the scene.stratum settings it draws."""
    layout = panel.layout
    layout.use_property_split = True
    layout.use_property_decorate = False
    return layout, context.scene.stratum


class StratumButtonsPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE_ID}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        # Without the library scene.stratum has no settings to draw; the library panel says why.
        return context.engine in cls.COMPAT_ENGINES and not properties.load_error


class STRATUM_RENDER_PT_library(StratumButtonsPanel, bpy.types.Panel):
    bl_label = "Native Library"

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        return context.engine in cls.COMPAT_ENGINES and bool(properties.load_error)

    def draw(self, context: bpy.types.Context) -> None:
        col = self.layout.column()
        col.label(text="The Stratum library could not be loaded:", icon="ERROR")
        col.label(text=properties.load_error)


class STRATUM_RENDER_PT_sampling(StratumButtonsPanel, bpy.types.Panel):
    bl_label = "Sampling"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column(align=True)
        col.prop(settings, "samples", text="Samples")
        col = layout.column()
        col.prop(settings, "sampler", text="Sampler")
        col.prop(settings, "hemisphere", text="Hemisphere")
        col.prop(settings, "seed", text="Seed")
        col = layout.column()
        col.prop(settings, "integrator", text="Integrator")
        if settings.integrator == "ao":
            col.prop(settings, "ao_distance", text="AO Distance")


class STRATUM_RENDER_PT_sampling_denoising(StratumButtonsPanel, bpy.types.Panel):
    bl_label = "Denoising"
    bl_parent_id = "STRATUM_RENDER_PT_sampling"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column(heading="Denoise", align=True)
        col.prop(settings, "use_denoising", text="Render")
        col.prop(settings, "use_preview_denoising", text="Viewport")


class STRATUM_RENDER_PT_viewport(StratumButtonsPanel, bpy.types.Panel):
    """The Rendered viewport: its samples, start resolution and the sampler split view."""

    bl_label = "Viewport"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.prop(settings, "preview_samples", text="Samples")
        col.prop(settings, "preview_start_resolution", text="Start Resolution")
        col = layout.column(heading="Split View")
        col.prop(settings, "use_split_view", text="Compare Samplers")
        sub = col.column()
        sub.active = settings.use_split_view
        sub.prop(settings, "compare_sampler", text="Right Sampler")
        sub.prop(settings, "split_position", text="Position", slider=True)


class STRATUM_RENDER_PT_light_paths(StratumButtonsPanel, bpy.types.Panel):
    bl_label = "Light Paths"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        integrator = settings.integrator
        if integrator == "ao":
            # Ambient occlusion traces no light paths: no bounce limit or estimator applies.
            layout.label(text="Ambient occlusion has no light-path settings")
            return
        # Each option only where it changes the estimator: `direct` is the path tracer with
        # max_bounces 0; the light tracer starts at the lights, so light sampling, its MIS
        # heuristic and the control variate are path-tracer choices; the heuristic only weighs
        # the two strategies of MIS; the minimum depth only matters while roulette is on.
        path_tracer = integrator != "light"
        if integrator != "direct":
            layout.column().prop(settings, "max_bounces", text="Max Bounces")
        col = layout.column()
        if path_tracer:
            col.prop(settings, "light_sampling", text="Light Sampling")
            if settings.light_sampling == "mis":
                col.prop(settings, "mis_heuristic", text="MIS Heuristic")
            if settings.light_sampling != "bsdf":
                col.prop(settings, "triangle_sampling", text="Triangle Sampling")
        col.prop(settings, "light_selection", text="Light Selection")
        col = layout.column()
        col.prop(settings, "rr_mode", text="Russian Roulette")
        if settings.rr_mode != "off":
            col.prop(settings, "rr_min_depth", text="Min Depth")
        if path_tracer:
            layout.column().prop(settings, "control_variate", text="Control Variate")


class STRATUM_RENDER_PT_film(StratumButtonsPanel, bpy.types.Panel):
    bl_label = "Film"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.prop(settings, "filter_type", text="Pixel Filter")
        col.prop(settings, "filter_width", text="Width")


class STRATUM_RENDER_PT_performance(StratumButtonsPanel, bpy.types.Panel):
    bl_label = "Performance"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.prop(settings, "threads", text="Threads")


classes: tuple[type, ...] = (
    STRATUM_RENDER_PT_library,
    STRATUM_RENDER_PT_sampling,
    STRATUM_RENDER_PT_sampling_denoising,
    STRATUM_RENDER_PT_viewport,
    STRATUM_RENDER_PT_light_paths,
    STRATUM_RENDER_PT_film,
    STRATUM_RENDER_PT_performance,
)


def compatible_builtin_panels() -> list[type]:
    """Blender's panels (material, light, world, camera, object data, object) to show for
    Stratum: the generic ones written for any engine (they list BLENDER_RENDER or CYCLES),
    minus Cycles' own, plus the node-based surface panels."""
    panels: list[type] = []
    for name in dir(bpy.types):
        if name.startswith(SKIP_PREFIXES):
            continue
        panel = getattr(bpy.types, name, None)
        if not isinstance(panel, type) or not issubclass(panel, bpy.types.Panel):
            continue
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if not isinstance(engines, set):
            continue
        if getattr(panel, "bl_context", "") not in REUSED_CONTEXTS:
            continue
        if name in EXTRA_PANELS or "BLENDER_RENDER" in engines or "CYCLES" in engines:
            panels.append(panel)
    return panels


def register() -> None:
    for cls in classes:
        bpy.utils.register_class(cls)
    for panel in compatible_builtin_panels():
        if ENGINE_ID not in panel.COMPAT_ENGINES:
            panel.COMPAT_ENGINES.add(ENGINE_ID)
            _patched.append(panel)


def unregister() -> None:
    while _patched:
        panel = _patched.pop()
        if hasattr(panel, "COMPAT_ENGINES"):
            panel.COMPAT_ENGINES.discard(ENGINE_ID)
    for cls in reversed(classes):
        if getattr(cls, "is_registered", True):
            bpy.utils.unregister_class(cls)
