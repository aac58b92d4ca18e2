"""Render passes in Blender's render result: which the view layer asks for, their registration
for the compositor (update_render_passes), add_pass before the result is made, and the copy of
each from the native film into the result when the render ends.

Names, channel ids and kinds are Cycles' (intern/cycles/blender/addon/engine.py
list_render_passes), so the compositor's Render Layers node and multilayer EXR see what they see
with Cycles. Blender's own view-layer toggles drive the passes it has one for (Depth, Mist,
Normal, Position, UV, Vector, Object and Material Index, Diffuse/Glossy/Transmission Color,
Emit, Env, AO; the mist's start, depth and falloff are the world's); `view_layer.stratum`
holds the others (Cycles keeps its equivalents in view_layer.cycles).
docs/passes.md says what each pass holds.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import bpy
import numpy as np
from bpy.props import BoolProperty, PointerProperty

from .. import blender_versions
from ..engine_id import ENGINE_ID
from ..export.instances import lightgroup_numbers


@dataclass(frozen=True)
class PassSpec:
    name: str  # the native pass (Cycles 3.x's name)
    channels: int
    chan_id: str  # Blender's channel letters
    kind: str  # register_pass type: VALUE, VECTOR or COLOR
    # False: not rendered, the result holds zeros. Only Vector: Stratum exports no motion at
    # the frames before and after, so it has no motion vectors, and 0 is what Cycles writes
    # when motion blur is on (scene/film.cpp skips the motion pass unless need_motion() is
    # MOTION_PASS). Written, not left to Blender, which fills a new Vector pass with its
    # "unknown speed" 10000 (PASS_VECTOR_MAX) that the Vector Blur node would smear.
    native: bool = True
    # k > 0: Cycles' light group pass "Combined_<name>" of the view layer's k-th light group,
    # the native light group k (renderer.read_lightgroup), not a pass of the `passes` setting.
    lightgroup: int = 0

    @property
    def result_name(self) -> str:
        """The render-result pass: Cycles' name in the running Blender."""
        return blender_versions.render_pass_name(self.name, bpy.app.version)


# Toggle (owner "view_layer" = Blender's, "stratum" = view_layer.stratum) -> passes it adds.
TOGGLES: tuple[tuple[str, str, tuple[PassSpec, ...]], ...] = (
    ("view_layer", "use_pass_z", (PassSpec("Depth", 1, "Z", "VALUE"),)),
    ("view_layer", "use_pass_mist", (PassSpec("Mist", 1, "Z", "VALUE"),)),
    ("view_layer", "use_pass_normal", (PassSpec("Normal", 3, "XYZ", "VECTOR"),)),
    ("view_layer", "use_pass_position", (PassSpec("Position", 3, "XYZ", "VECTOR"),)),
    ("view_layer", "use_pass_uv", (PassSpec("UV", 3, "UVA", "VECTOR"),)),
    ("view_layer", "use_pass_vector", (PassSpec("Vector", 4, "XYZW", "VECTOR", native=False),)),
    ("view_layer", "use_pass_object_index", (PassSpec("IndexOB", 1, "X", "VALUE"),)),
    ("view_layer", "use_pass_material_index", (PassSpec("IndexMA", 1, "X", "VALUE"),)),
    ("view_layer", "use_pass_diffuse_color", (PassSpec("DiffCol", 3, "RGB", "COLOR"),)),
    ("view_layer", "use_pass_glossy_color", (PassSpec("GlossCol", 3, "RGB", "COLOR"),)),
    ("view_layer", "use_pass_transmission_color", (PassSpec("TransCol", 3, "RGB", "COLOR"),)),
    ("view_layer", "use_pass_emit", (PassSpec("Emit", 3, "RGB", "COLOR"),)),
    ("view_layer", "use_pass_environment", (PassSpec("Env", 3, "RGB", "COLOR"),)),
    ("view_layer", "use_pass_ambient_occlusion", (PassSpec("AO", 3, "RGB", "COLOR"),)),
    ("stratum", "use_pass_denoising_data", (PassSpec("Denoising Normal", 3, "XYZ", "VECTOR"),
                                            PassSpec("Denoising Albedo", 3, "RGB", "COLOR"))),
    ("stratum", "use_pass_sample_count", (PassSpec("Debug Sample Count", 1, "X", "VALUE"),)),
    ("stratum", "use_pass_error", (PassSpec("Stratum Error", 3, "RGB", "COLOR"),)),
    ("stratum", "use_pass_shadow_catcher", (PassSpec("Shadow Catcher", 3, "RGB", "COLOR"),)),
)


class StratumViewLayerSettings(bpy.types.PropertyGroup):
    """The passes Blender has no generic view-layer toggle for (Cycles keeps these in
    view_layer.cycles)."""

    use_pass_denoising_data: BoolProperty(  # type: ignore[valid-type]
        name="Denoising Data",
        description="Denoising Albedo and Denoising Normal: the features a denoiser reads "
                    "beside the image, as Cycles writes them",
        default=False)
    use_pass_sample_count: BoolProperty(  # type: ignore[valid-type]
        name="Sample Count",
        description="Debug Sample Count: the camera samples taken in each pixel",
        default=False)
    use_pass_error: BoolProperty(  # type: ignore[valid-type]
        name="Error",
        description="Stratum Error: each pixel's estimated standard error of the mean (RGB), "
                    "from the spread of its samples; valid for independent samples (random)",
        default=False)
    use_pass_shadow_catcher: BoolProperty(  # type: ignore[valid-type]
        name="Shadow Catcher",
        description="Shadow Catcher: the light on shadow catchers over their light without the "
                    "other objects, to multiply a background plate by (Cycles' pass); with it, "
                    "Combined holds the objects without the catchers' shadows",
        default=False)


def enabled_passes(view_layer: Any) -> list[PassSpec]:
    """The passes besides Combined that the view layer's toggles ask for, in TOGGLES order,
    then one per light group of the view layer (Cycles' "Combined_<name>", RGB, in their
    order, numbered as the export numbers the emitters' groups: lightgroup_numbers)."""
    owners = {"view_layer": view_layer, "stratum": getattr(view_layer, "stratum", None)}
    chosen: list[PassSpec] = []
    for owner, prop, specs in TOGGLES:
        if owners[owner] is not None and getattr(owners[owner], prop, False):
            chosen.extend(specs)
    chosen.extend(PassSpec(f"Combined_{name}", 3, "RGB", "COLOR", lightgroup=k)
                  for name, k in lightgroup_numbers(view_layer).items())
    return chosen


def native_setting(specs: list[PassSpec]) -> str:
    """The native `passes` setting for these passes."""
    return ",".join(spec.name for spec in specs if spec.native and not spec.lightgroup)


# Blender's mist falloff -> the exponent Cycles raises the mist to (blender/sync.cpp).
MIST_FALLOFF = {"QUADRATIC": 2.0, "LINEAR": 1.0, "INVERSE_QUADRATIC": 0.5}


def mist_settings(mist: Any) -> dict[str, float]:
    """The native mist settings of a world's mist_settings (World > Mist Pass)."""
    return {"mist_start": float(mist.start), "mist_depth": float(mist.depth),
            "mist_falloff": MIST_FALLOFF.get(mist.falloff, 2.0)}


def register_passes(engine: Any, scene: Any, view_layer: Any) -> None:
    """For RenderEngine.update_render_passes: tells the compositor which passes besides
    Combined the view layer's toggles add."""
    for spec in enabled_passes(view_layer):
        engine.register_pass(scene, view_layer, spec.result_name, spec.channels, spec.chan_id,
                             spec.kind)


class ResultPasses:
    """The passes of one F12 render: made before begin_result (it adds them to the result),
    it names them in the native settings and copies them into the result when the render
    ends."""

    def __init__(self, engine: Any, view_layer: Any, world: Any = None) -> None:
        self.specs = enabled_passes(view_layer)
        self.world = world
        for spec in self.specs:
            engine.add_pass(spec.result_name, spec.channels, spec.chan_id, layer=view_layer.name)

    def configure(self, settings: dict[str, Any]) -> None:
        """Adds these passes to the native settings' `passes` (after any already there, such
        as the denoiser's guides, without repeats), and the world's mist settings with Mist."""
        current = [name for name in str(settings.get("passes", "")).split(",") if name]
        wanted = current + [spec.name for spec in self.specs
                            if spec.native and not spec.lightgroup and spec.name not in current]
        if wanted:
            settings["passes"] = ",".join(wanted)
        lightgroups = sum(1 for spec in self.specs if spec.lightgroup)
        if lightgroups:
            settings["lightgroups"] = lightgroups
            settings["lightgroup_split_emission"] = int(
                blender_versions.lightgroups_take_split_emission(bpy.app.version))
        if self.world is not None and any(spec.name == "Mist" for spec in self.specs):
            settings.update(mist_settings(self.world.mist_settings))

    def write(self, renderer: Any, result: Any) -> None:
        """Copies every pass from the renderer into the result's first layer."""
        layer = result.layers[0]
        for spec in self.specs:
            render_pass = layer.passes.find_by_name(spec.result_name, "")
            if render_pass is None:
                continue
            if spec.lightgroup:
                write_rect(render_pass, renderer.read_lightgroup(spec.lightgroup))
            elif spec.native:
                write_rect(render_pass, renderer.read_pass(spec.name))
            else:
                width, height = renderer.image_size
                write_rect(render_pass, np.zeros((height, width, spec.channels), np.float32))


def write_rect(render_pass: Any, pixels: np.ndarray) -> None:
    """Sets a render pass's pixels from a (height, width, channels) float32 array (rows bottom
    to top, as Blender's): 3.x/4.0 take an (N, channels) array, 4.1+ a flat one."""
    flat = np.ascontiguousarray(pixels, dtype=np.float32).reshape(-1)
    shaped = flat.reshape(-1, pixels.shape[-1])
    first, second = (flat, shaped) if blender_versions.flat_pass_pixels(bpy.app.version) \
        else (shaped, flat)
    try:
        render_pass.rect.foreach_set(first)
    except (TypeError, ValueError, RuntimeError):
        render_pass.rect.foreach_set(second)


class STRATUM_VIEWLAYER_PT_passes_data(bpy.types.Panel):
    """The passes Stratum fills, under Blender's View Layer > Passes."""

    bl_label = "Data"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "view_layer"
    bl_parent_id = "VIEWLAYER_PT_layer_passes"
    COMPAT_ENGINES = {ENGINE_ID}

    @classmethod
    def poll(cls, context: Any) -> bool:
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context: Any) -> None:
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        view_layer = context.view_layer
        col = layout.column(heading="Include", align=True)
        col.prop(view_layer, "use_pass_combined")
        col.prop(view_layer, "use_pass_z")
        col.prop(view_layer, "use_pass_mist")
        col.prop(view_layer, "use_pass_normal")
        col.prop(view_layer, "use_pass_position")
        col.prop(view_layer, "use_pass_uv")
        col.prop(view_layer, "use_pass_vector")
        col.prop(view_layer, "use_pass_object_index")
        col.prop(view_layer, "use_pass_material_index")
        col = layout.column(heading="Light", align=True)
        col.prop(view_layer, "use_pass_diffuse_color", text="Diffuse Color")
        col.prop(view_layer, "use_pass_glossy_color", text="Glossy Color")
        col.prop(view_layer, "use_pass_transmission_color", text="Transmission Color")
        col.prop(view_layer, "use_pass_emit", text="Emission")
        col.prop(view_layer, "use_pass_environment")
        col.prop(view_layer, "use_pass_ambient_occlusion", text="Ambient Occlusion")
        col.prop(view_layer.stratum, "use_pass_shadow_catcher")
        col = layout.column(heading="Stratum", align=True)
        col.prop(view_layer.stratum, "use_pass_denoising_data")
        col.prop(view_layer.stratum, "use_pass_sample_count")
        col.prop(view_layer.stratum, "use_pass_error")


class STRATUM_VIEWLAYER_PT_passes_lightgroups(bpy.types.Panel):
    """The view layer's light groups (Cycles' Light Groups panel): one Combined_<name> pass
    each, of the lights, emissive objects and world whose Light Group names it."""

    bl_label = "Light Groups"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "view_layer"
    bl_parent_id = "VIEWLAYER_PT_layer_passes"
    bl_options = {"DEFAULT_CLOSED"}
    COMPAT_ENGINES = {ENGINE_ID}

    @classmethod
    def poll(cls, context: Any) -> bool:
        return context.engine in cls.COMPAT_ENGINES and hasattr(context.view_layer, "lightgroups")

    def draw(self, context: Any) -> None:
        view_layer = context.view_layer
        row = self.layout.row()
        row.template_list("UI_UL_list", "lightgroups", view_layer, "lightgroups", view_layer,
                          "active_lightgroup_index", rows=2)
        col = row.column(align=True)
        col.operator("scene.view_layer_add_lightgroup", icon="ADD", text="")
        col.operator("scene.view_layer_remove_lightgroup", icon="REMOVE", text="")


# Blender's view-layer panels Stratum shows: the layer itself and the Passes panel its own
# Data panel sits in (their other children draw EEVEE's settings).
BLENDER_PANELS = ("VIEWLAYER_PT_layer", "VIEWLAYER_PT_layer_passes")
_patched: list[type] = []


def register() -> None:
    bpy.utils.register_class(StratumViewLayerSettings)
    bpy.types.ViewLayer.stratum = PointerProperty(type=StratumViewLayerSettings, name="Stratum")
    for name in BLENDER_PANELS:
        panel = getattr(bpy.types, name, None)
        engines = getattr(panel, "COMPAT_ENGINES", None)
        if isinstance(engines, set) and ENGINE_ID not in engines:
            engines.add(ENGINE_ID)
            _patched.append(panel)
    bpy.utils.register_class(STRATUM_VIEWLAYER_PT_passes_data)
    bpy.utils.register_class(STRATUM_VIEWLAYER_PT_passes_lightgroups)


def unregister() -> None:
    if getattr(STRATUM_VIEWLAYER_PT_passes_lightgroups, "is_registered", True):
        bpy.utils.unregister_class(STRATUM_VIEWLAYER_PT_passes_lightgroups)
    if getattr(STRATUM_VIEWLAYER_PT_passes_data, "is_registered", True):
        bpy.utils.unregister_class(STRATUM_VIEWLAYER_PT_passes_data)
    while _patched:
        panel = _patched.pop()
        if hasattr(panel, "COMPAT_ENGINES"):
            panel.COMPAT_ENGINES.discard(ENGINE_ID)
    if hasattr(bpy.types.ViewLayer, "stratum"):
        del bpy.types.ViewLayer.stratum
    bpy.utils.unregister_class(StratumViewLayerSettings)
