"""Render-properties panels (laid out like Cycles') and reuse of Blender's own panels."""

from __future__ import annotations

from typing import Any

import bpy

from . import native, properties
from .engine_id import ENGINE_ID
from .light_path_source import light_path_holder
from .version import __version__

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


class StratumPreferences(bpy.types.AddonPreferences):
    """Edit > Preferences > Add-ons (Extensions in 4.2+) > Stratum: the version, and which native
    library the add-on loads or why it cannot, the first thing to read after an install."""

    # The add-on's module: "stratum" as a legacy add-on, "bl_ext.<repository>.stratum" as an
    # extension (Blender 4.2+); ui.py sits at the package's top, so its package is that module.
    bl_idname = __package__

    def draw(self, context: bpy.types.Context) -> None:
        col = self.layout.column()
        col.label(text=f"Stratum {__version__}")
        status = native.library_status()
        if status.version is None:
            col.label(text="The native library could not be loaded:", icon="ERROR")
            col.label(text=status.error or "")
        else:
            col.label(text=f"Native library {status.version}: {status.path}")


# What a setting applies to, by integrator (names from the library's integrator registry).
# A setting that does not apply is drawn greyed out (layout.active = False), as Cycles greys
# its own, so the panels keep their shape when the integrator changes: ambient occlusion traces
# no light paths; `direct` is the path tracer with max_bounces 0; the light tracer starts at
# the lights, so light sampling, its heuristic and the control variate are path-tracer
# choices.
NO_LIGHT_PATHS = frozenset({"ao"})
# The light_selection choices that may choose lights by the tree, the only ones light_tree_splits
# changes (auto picks the tree in a scene of more than a few lights).
TREE_SELECTIONS = frozenset({"tree", "auto"})
NO_BOUNCE_LIMIT = frozenset({"ao", "direct", "radiosity"})
NO_LIGHT_SAMPLING = frozenset({"ao", "light"})
# Radiosity solves the scene once and shows it through a final gather: one light sample (by
# the light selection and triangle sampling) and one gather ray per camera hit, no paths, so
# no roulette, light-sampling strategy or control variate.
FINAL_GATHER = frozenset({"radiosity"})
# Path guiding guides the path tracer's scattered directions (`direct` scatters none it could use).
GUIDED = frozenset({"path"})
RADIOSITY_SETTINGS = (("radiosity_patch_size", "Patch Size"), ("radiosity_solver", "Solver"),
                      ("radiosity_tolerance", "Tolerance"), ("radiosity_rays", "Form Factor Rays"))


def draw_noise_threshold(layout: bpy.types.UILayout, settings: Any, use: str, threshold: str,
                         samples: str, min_samples: str, metric: str | None = None) -> None:
    """Cycles' Noise Threshold block (its Sampling > Render and > Viewport panels): a checkbox
    and the threshold on one row under the heading, then the sample count, read Max Samples
    while adaptive sampling is on, and Min Samples. What adaptive sampling alone uses is greyed
    out while it is off (Cycles hides Min Samples; greyed, it stays where it will be). Stratum's
    `metric` (what the threshold measures; one for F12 and the viewport) comes last, in the
    Render panel only."""
    adaptive = bool(getattr(settings, use))
    heading = layout.column(align=True, heading="Noise Threshold")
    row = heading.row(align=True)
    row.prop(settings, use, text="")
    sub = row.row()
    sub.active = adaptive
    sub.prop(settings, threshold, text="")
    col = layout.column(align=True)
    col.prop(settings, samples, text="Max Samples" if adaptive else "Samples")
    sub = col.column(align=True)
    sub.active = adaptive
    sub.prop(settings, min_samples, text="Min Samples")
    if metric is not None:
        sub.prop(settings, metric, text="Metric")


class STRATUM_RENDER_PT_sampling(StratumButtonsPanel, bpy.types.Panel):
    """Holds the Viewport, Render, Denoising, Advanced and Lights subpanels and nothing of its
    own, as Cycles' Sampling panel."""

    bl_label = "Sampling"

    def draw(self, context: bpy.types.Context) -> None:
        """Draws nothing: every setting is in a subpanel (bpy refuses a Panel without draw)."""


class STRATUM_RENDER_PT_sampling_viewport(StratumButtonsPanel, bpy.types.Panel):
    """The Rendered viewport's sampling: its own noise threshold and samples, as Cycles'."""

    bl_label = "Viewport"
    bl_parent_id = "STRATUM_RENDER_PT_sampling"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        draw_noise_threshold(layout, settings, "use_preview_adaptive_sampling",
                             "preview_adaptive_threshold", "preview_samples",
                             "preview_adaptive_min_samples")
        layout.column().prop(settings, "preview_start_resolution", text="Start Resolution")


class STRATUM_RENDER_PT_sampling_viewport_split(StratumButtonsPanel, bpy.types.Panel):
    """Stratum's sampler split view: the viewport's right part with another sampler."""

    bl_label = "Split View"
    bl_parent_id = "STRATUM_RENDER_PT_sampling_viewport"
    bl_options = {"DEFAULT_CLOSED"}

    def draw_header(self, context: bpy.types.Context) -> None:
        self.layout.prop(context.scene.stratum, "use_split_view", text="")

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.active = settings.use_split_view
        col.prop(settings, "compare_sampler", text="Right Sampler")
        col.prop(settings, "split_position", text="Position", slider=True)


class STRATUM_RENDER_PT_sampling_render(StratumButtonsPanel, bpy.types.Panel):
    """F12 renders' sampling: noise threshold and samples, as Cycles'."""

    bl_label = "Render"
    bl_parent_id = "STRATUM_RENDER_PT_sampling"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        draw_noise_threshold(layout, settings, "use_adaptive_sampling", "adaptive_threshold",
                             "samples", "adaptive_min_samples", "adaptive_metric")


class STRATUM_RENDER_PT_sampling_denoising(StratumButtonsPanel, bpy.types.Panel):
    bl_label = "Denoising"
    bl_parent_id = "STRATUM_RENDER_PT_sampling"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column(heading="Denoise", align=True)
        col.prop(settings, "use_denoising", text="Render")
        col.prop(settings, "use_preview_denoising", text="Viewport")


class STRATUM_RENDER_PT_sampling_advanced(StratumButtonsPanel, bpy.types.Panel):
    """Cycles' Sampling > Advanced: the pattern (Stratum's sampler) and its seed, and the
    distribution of diffuse directions."""

    bl_label = "Advanced"
    bl_parent_id = "STRATUM_RENDER_PT_sampling"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.prop(settings, "sampler", text="Pattern")
        col.prop(settings, "seed", text="Seed")
        col.prop(settings, "hemisphere", text="Hemisphere")


class STRATUM_RENDER_PT_sampling_lights(StratumButtonsPanel, bpy.types.Panel):
    """Cycles' Sampling > Lights (its Light Tree switch): how a light sample picks a light."""

    bl_label = "Lights"
    bl_parent_id = "STRATUM_RENDER_PT_sampling"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.active = settings.integrator not in NO_LIGHT_PATHS
        col.prop(settings, "light_selection", text="Light Selection")
        sub = col.column()
        sub.active = settings.light_selection in TREE_SELECTIONS
        sub.prop(settings, "light_tree_splits", text="Tree Splits")


class STRATUM_RENDER_PT_sampling_path_guiding(StratumButtonsPanel, bpy.types.Panel):
    """Cycles' Sampling > Path Guiding: a switch in the header, the training, the mixture's
    share and the tree's split rule below; the path tracer's alone (GUIDED), greyed out for
    the other integrators."""

    bl_label = "Path Guiding"
    bl_parent_id = "STRATUM_RENDER_PT_sampling"
    bl_options = {"DEFAULT_CLOSED"}

    def draw_header(self, context: bpy.types.Context) -> None:
        settings = context.scene.stratum
        self.layout.active = settings.integrator in GUIDED
        self.layout.prop(settings, "use_guiding", text="")

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.active = settings.integrator in GUIDED and settings.use_guiding
        col.prop(settings, "guiding_training_samples", text="Training Samples")
        col.prop(settings, "guiding_bsdf_fraction", text="BSDF Fraction")
        col.prop(settings, "guiding_split", text="Split")


class STRATUM_RENDER_PT_light_paths(StratumButtonsPanel, bpy.types.Panel):
    """The light-transport algorithm; its subpanels hold what shapes its paths."""

    bl_label = "Light Paths"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.prop(settings, "integrator", text="Integrator")
        col.prop(settings, "light_paths", text="Settings")
        sub = col.column()
        sub.active = settings.integrator == "ao"
        sub.prop(settings, "ao_distance", text="AO Distance")
        sub = col.column()
        sub.active = settings.integrator == "radiosity"
        for name, text in RADIOSITY_SETTINGS:
            sub.prop(settings, name, text=text)


# Cycles' Max Bounces and Clamping subpanels: (setting, label).
MAX_BOUNCES = (("max_bounces", "Total"), ("diffuse_bounces", "Diffuse"),
               ("glossy_bounces", "Glossy"), ("transmission_bounces", "Transmission"))
CLAMPING = (("clamp_direct", "Direct Light"), ("clamp_indirect", "Indirect Light"))
# Cycles' Caustics subpanel: (setting, label).
CAUSTICS = (("filter_glossy", "Filter Glossy"), ("caustics_reflective", "Reflective"),
            ("caustics_refractive", "Refractive"))


class STRATUM_RENDER_PT_light_paths_max_bounces(StratumButtonsPanel, bpy.types.Panel):
    """Cycles' Max Bounces: the total, per kind, and transparent pass-throughs (Stratum's own
    or Cycles', as Light Paths > Settings says: light_path_source.py)."""

    bl_label = "Max Bounces"
    bl_parent_id = "STRATUM_RENDER_PT_light_paths"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column(align=True)
        col.active = settings.integrator not in NO_BOUNCE_LIMIT
        for name, text in MAX_BOUNCES:
            col.prop(*light_path_holder(context.scene, name), text=text)
        col = layout.column()
        col.active = settings.integrator not in NO_LIGHT_PATHS | FINAL_GATHER
        col.prop(*light_path_holder(context.scene, "transparent_max_bounces"), text="Transparent")


class STRATUM_RENDER_PT_light_paths_clamping(StratumButtonsPanel, bpy.types.Panel):
    """Cycles' Clamping of direct and indirect light: biased by design (its tooltips say so)."""

    bl_label = "Clamping"
    bl_parent_id = "STRATUM_RENDER_PT_light_paths"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column(align=True)
        col.active = settings.integrator not in NO_LIGHT_PATHS | FINAL_GATHER
        for name, text in CLAMPING:
            col.prop(*light_path_holder(context.scene, name), text=text)


class STRATUM_RENDER_PT_light_paths_caustics(StratumButtonsPanel, bpy.types.Panel):
    """Cycles' Caustics: Filter Glossy and the reflective and refractive caustics switches,
    biased by design (their tooltips say so); what the path tracer applies (the light tracer
    and radiosity say in a notice that they do not)."""

    bl_label = "Caustics"
    bl_parent_id = "STRATUM_RENDER_PT_light_paths"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.active = settings.integrator not in NO_BOUNCE_LIMIT | {"light"}
        for name, text in CAUSTICS:
            col.prop(*light_path_holder(context.scene, name), text=text)


class STRATUM_RENDER_PT_light_paths_roulette(StratumButtonsPanel, bpy.types.Panel):
    """Russian roulette: how paths end before the bounce limit, and from which bounce (Cycles'
    Min Light Bounces)."""

    bl_label = "Russian Roulette"
    bl_parent_id = "STRATUM_RENDER_PT_light_paths"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.active = settings.integrator not in NO_LIGHT_PATHS | FINAL_GATHER
        col.prop(settings, "rr_mode", text="Mode")
        sub = col.column()
        sub.active = settings.rr_mode != "off"
        sub.prop(settings, "rr_min_depth", text="Min Depth")


class STRATUM_RENDER_PT_light_paths_direct_light(StratumButtonsPanel, bpy.types.Panel):
    """How the path tracer finds emission: light samples, BSDF samples or both by MIS."""

    bl_label = "Direct Light"
    bl_parent_id = "STRATUM_RENDER_PT_light_paths"

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.active = settings.integrator not in NO_LIGHT_SAMPLING
        strategy = col.column()
        strategy.active = settings.integrator not in FINAL_GATHER
        strategy.prop(settings, "light_sampling", text="Light Sampling")
        sub = strategy.column()
        sub.active = settings.light_sampling == "mis"
        sub.prop(settings, "mis_heuristic", text="MIS Heuristic")
        sub = col.column()
        sub.active = settings.light_sampling != "bsdf" or settings.integrator in FINAL_GATHER
        sub.prop(settings, "triangle_sampling", text="Triangle Sampling")


class STRATUM_RENDER_PT_light_paths_control_variate(StratumButtonsPanel, bpy.types.Panel):
    """The path tracer's control variate: an ambient radiance whose known integral is added
    back at each scattering vertex."""

    bl_label = "Control Variate"
    bl_parent_id = "STRATUM_RENDER_PT_light_paths"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context: bpy.types.Context) -> None:
        layout, settings = _settings_layout(self, context)
        col = layout.column()
        col.active = settings.integrator not in NO_LIGHT_SAMPLING | FINAL_GATHER
        col.prop(settings, "control_variate", text="Ambient Radiance")


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


# In Cycles' order: a subpanel after its parent, siblings top to bottom.
def _draw_lightgroup(layout: bpy.types.UILayout, owner: Any, view_layer: Any) -> None:
    """Cycles' Light Group field: the owner's group, searched among the view layer's, with a
    button that adds a typed name the view layer lacks."""
    row = layout.row(align=True)
    row.use_property_decorate = False
    sub = row.column(align=True)
    sub.prop_search(owner, "lightgroup", view_layer, "lightgroups", text="Light Group",
                    results_are_suggestions=True)
    sub = row.column(align=True)
    sub.enabled = bool(owner.lightgroup) and not any(
        group.name == owner.lightgroup for group in view_layer.lightgroups)
    sub.operator("scene.view_layer_add_lightgroup", icon="ADD", text="").name = owner.lightgroup


class STRATUM_OBJECT_PT_catcher_and_lightgroup(bpy.types.Panel):
    """Object > Shadow Catcher and Light Group (Cycles' Visibility > Mask and Shading > Light
    Group): what integrators/shadow_catcher.h and the light group passes read."""

    bl_label = "Shadow Catcher and Light Group"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"
    bl_options = {"DEFAULT_CLOSED"}
    COMPAT_ENGINES = {ENGINE_ID}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        return context.engine in cls.COMPAT_ENGINES and getattr(context, "object", None) is not None

    def draw(self, context: bpy.types.Context) -> None:
        layout = self.layout
        layout.use_property_split = True
        ob = context.object
        layout.prop(ob, "is_shadow_catcher")
        _draw_lightgroup(layout, ob, context.view_layer)


class STRATUM_WORLD_PT_lightgroup(bpy.types.Panel):
    """World > Light Group (Cycles' World > Settings > Light Group)."""

    bl_label = "Light Group"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "world"
    bl_options = {"DEFAULT_CLOSED"}
    COMPAT_ENGINES = {ENGINE_ID}

    @classmethod
    def poll(cls, context: bpy.types.Context) -> bool:
        return context.engine in cls.COMPAT_ENGINES and getattr(context, "world", None) is not None

    def draw(self, context: bpy.types.Context) -> None:
        layout = self.layout
        layout.use_property_split = True
        _draw_lightgroup(layout, context.world, context.view_layer)


classes: tuple[type, ...] = (
    STRATUM_RENDER_PT_library,
    STRATUM_RENDER_PT_sampling,
    STRATUM_RENDER_PT_sampling_viewport,
    STRATUM_RENDER_PT_sampling_viewport_split,
    STRATUM_RENDER_PT_sampling_render,
    STRATUM_RENDER_PT_sampling_denoising,
    STRATUM_RENDER_PT_sampling_advanced,
    STRATUM_RENDER_PT_sampling_lights,
    STRATUM_RENDER_PT_sampling_path_guiding,
    STRATUM_RENDER_PT_light_paths,
    STRATUM_RENDER_PT_light_paths_max_bounces,
    STRATUM_RENDER_PT_light_paths_clamping,
    STRATUM_RENDER_PT_light_paths_caustics,
    STRATUM_RENDER_PT_light_paths_roulette,
    STRATUM_RENDER_PT_light_paths_direct_light,
    STRATUM_RENDER_PT_light_paths_control_variate,
    STRATUM_RENDER_PT_film,
    STRATUM_RENDER_PT_performance,
)
# Stratum's panels in other contexts than render.
other_panels: tuple[type, ...] = (
    STRATUM_OBJECT_PT_catcher_and_lightgroup,
    STRATUM_WORLD_PT_lightgroup,
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
    bpy.utils.register_class(StratumPreferences)
    for cls in (*classes, *other_panels):
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
    for cls in (*reversed(other_panels), *reversed(classes), StratumPreferences):
        if getattr(cls, "is_registered", True):
            bpy.utils.unregister_class(cls)
