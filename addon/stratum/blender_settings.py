"""Where each native render setting (native.settings()) comes from in Blender. Without bpy, so
that the README's settings table (scripts/settings_table.py) and the tests read it too.

Every setting the library lists is in exactly one of these, and tests/python/test_settings.py
fails naming a setting that is in none, so a new library setting cannot be forgotten:

* PROPERTIES: a property of scene.stratum with the setting's name, whose label, description,
  range, choices and default are the library's (properties.py builds them);
* FROM_BLENDER: taken from Blender's own render settings by the engine (engine/frame.py), so that
  Stratum does not duplicate what Blender already has;
* NOT_IN_BLENDER: nothing in Blender sets it yet, for the reason given.

BLENDER_ONLY lists the scene.stratum properties that are no library setting: what the add-on
does around a render (denoising).
"""

from __future__ import annotations

from .native import Setting, SettingKind

PROPERTIES: tuple[str, ...] = (
    "samples", "use_adaptive_sampling", "adaptive_threshold", "adaptive_min_samples",
    "adaptive_metric", "sampler",
    "hemisphere", "seed", "integrator", "ao_distance", "max_bounces",
    "diffuse_bounces", "glossy_bounces", "transmission_bounces", "transparent_max_bounces",
    "clamp_direct", "clamp_indirect", "filter_glossy", "caustics_reflective", "caustics_refractive",
    "light_sampling", "mis_heuristic", "triangle_sampling", "light_selection",
    "light_tree_splits", "rr_mode",
    "rr_min_depth", "control_variate", "filter_type", "filter_width", "threads",
    "radiosity_patch_size", "radiosity_solver", "radiosity_tolerance", "radiosity_rays",
    "use_guiding", "guiding_training_samples", "guiding_bsdf_fraction", "guiding_split",
)

# Setting -> the Blender value it is taken from.
FROM_BLENDER: dict[str, str] = {
    "width": "scene.render.resolution_x × resolution_percentage / 100",
    "height": "scene.render.resolution_y × resolution_percentage / 100",
    "crop_x": "scene.render.border_min_x × width, with use_border",
    "crop_y": "scene.render.border_min_y × height, with use_border",
    "crop_width": "(scene.render.border_max_x − border_min_x) × width, with use_border",
    "crop_height": "(scene.render.border_max_y − border_min_y) × height, with use_border",
    "film_transparent": "scene.render.film_transparent",
    "passes": "the view layer's pass toggles (View Layer > Passes; engine/render_passes.py)",
    "lightgroups": "the view layer's light groups (View Layer > Light Groups; "
                   "engine/render_passes.py): one Combined_<name> pass each",
    "lightgroup_split_emission": "the running Blender: 1 before 3.5 (Cycles then still wrote "
                                 "emission after a shadow catcher split to light groups)",
    "mist_start": "scene.world.mist_settings.start, with the Mist pass",
    "mist_depth": "scene.world.mist_settings.depth, with the Mist pass",
    "mist_falloff": "scene.world.mist_settings.falloff (quadratic 2, linear 1, inverse quadratic "
                    "0.5), with the Mist pass",
}

# Setting -> why nothing in Blender sets it.
NOT_IN_BLENDER: dict[str, str] = {
    "bvh": "F12 renders use the library's default (static); the Rendered viewport uses dynamic",
    "sample_offset": "a render in Blender takes all the samples; `stratum render --scheduler` "
                     "gives each Dask worker its range (distributed.py)",
    "sample_count": "a render in Blender takes all the samples; `stratum render --scheduler` "
                    "gives each Dask worker its range (distributed.py)",
}

# scene.stratum properties of the add-on alone: name -> (label, description, default). Off by
# default: denoising changes the image a scene renders, and OIDN is a library of its own that
# may be missing (engine/denoise.py).
BLENDER_ONLY: dict[str, tuple[str, str, bool]] = {
    "use_denoising": (
        "Denoise Render",
        "Denoise the final render with Intel Open Image Denoise, guided by the albedo and "
        "normal of the first surface hit; the undenoised image is kept in the Noisy Image pass",
        False),
    "use_preview_denoising": (
        "Denoise Viewport",
        "Denoise the rendered viewport with Intel Open Image Denoise",
        False),
}

# Cycles' Light Paths settings, which a scene renders with instead of Stratum's own when its
# `light_paths` property says so (light_paths_from_cycles): setting -> scene.cycles property.
CYCLES_LIGHT_PATHS: dict[str, str] = {
    "max_bounces": "max_bounces",
    "diffuse_bounces": "diffuse_bounces",
    "glossy_bounces": "glossy_bounces",
    "transmission_bounces": "transmission_bounces",
    "transparent_max_bounces": "transparent_max_bounces",
    "clamp_direct": "sample_clamp_direct",
    "clamp_indirect": "sample_clamp_indirect",
    "filter_glossy": "blur_glossy",
    "caustics_reflective": "caustics_reflective",
    "caustics_refractive": "caustics_refractive",
}

# scene.stratum.light_paths: where the Light Paths settings come from. Stratum's own default to
# unbiased rendering (no per-kind limit below the total, no clamping, no Filter Glossy, caustics
# on); Cycles' defaults clamp indirect light at 10, blur glossy lobes after blurry bounces
# (blur_glossy 1) and stop diffuse and glossy paths after 4 bounces. A file whose Cycles
# Light Paths were set (saved with a value, scene.cycles.is_property_set) was tuned for Cycles,
# and Auto renders it with them; a new scene, or one never tuned, renders unbiased.
LIGHT_PATHS_SOURCES: tuple[tuple[str, str, str], ...] = (
    ("AUTO", "Auto", "Cycles' Light Paths settings when the file has set any of them (a scene "
     "tuned for Cycles renders as in Cycles), else Stratum's own"),
    ("STRATUM", "Stratum", "Stratum's own Light Paths settings (unbiased by default: no per-kind "
     "limit, no clamping)"),
    ("CYCLES", "Cycles", "Cycles' Light Paths settings of this scene (scene.cycles), with their "
     "clamping and per-kind limits"),
)
LIGHT_PATHS_DEFAULT = "AUTO"


def light_paths_from_cycles(source: str, cycles_available: bool, cycles_set: bool) -> bool:
    """Whether a scene renders with Cycles' Light Paths settings: `source` is its light_paths
    property, `cycles_available` whether it has Cycles' settings at all (the Cycles add-on is
    enabled), `cycles_set` whether any of them was set in the file (LIGHT_PATHS_SOURCES)."""
    if not cycles_available or source == "STRATUM":
        return False
    return source == "CYCLES" or cycles_set


# The Blender defaults that differ from the library's on purpose. Blender stores a property
# only once it is changed, so a saved .blend that never touched one of these renders with the
# default here: changing it changes how the bundled scenes render.
UI_DEFAULTS: dict[str, int | float | str] = {
    # Cycles' default sample count, so that switching a scene between the engines keeps it;
    # the library's own default (16) suits quick native renders and tests.
    "samples": 64,
}



# Integer settings of range 0..1 named as Cycles names its checkboxes without use_.
SWITCHES = frozenset({"caustics_reflective", "caustics_refractive"})


def is_switch(setting: Setting) -> bool:
    """A use_* (or SWITCHES) integer setting of range 0..1, whose property is a checkbox
    (BoolProperty) as Cycles' switches are; the engine sends its value as 0 or 1
    (engine/frame.py)."""
    return (setting.kind == SettingKind.INT
            and (setting.name.startswith("use_") or setting.name in SWITCHES)
            and (setting.minimum, setting.maximum) == (0, 1))


# Blender-only properties of scene.stratum, not library settings: the Rendered viewport's
# (engine/viewport.py). name -> (label, description).
VIEWPORT_PROPERTIES: dict[str, tuple[str, str]] = {
    "preview_samples": ("Viewport Samples",
                        "Samples per pixel the Rendered viewport refines to before it stops"),
    "preview_start_resolution": ("Start Resolution",
                                 "Each change is first rendered with one sample at a resolution "
                                 "whose longer side is at most this many pixels, then at twice "
                                 "it, up to the viewport's own, so that a first image comes "
                                 "fast (0 = off)"),
    "use_split_view": ("Split View",
                       "Render the left part of the viewport with Sampler and the right part "
                       "with Compare Sampler, at the same samples and seed"),
    "compare_sampler": ("Compare Sampler", "Sampler of the right part of a split viewport"),
    "split_position": ("Split Position", "Where the viewport is split, from its left (0) to "
                       "its right (1) edge"),
    "use_preview_adaptive_sampling": ("Viewport Adaptive Sampling",
                                      "Adaptive sampling in the Rendered viewport (its Noise "
                                      "Threshold checkbox); F12 renders use Render's"),
    "preview_adaptive_threshold": ("Viewport Noise Threshold",
                                   "Noise threshold of the Rendered viewport's adaptive "
                                   "sampling (0 = automatic: max(0.001, 1/samples))"),
    "preview_adaptive_min_samples": ("Viewport Min Samples",
                                     "Samples every pixel of the Rendered viewport takes before "
                                     "adaptive sampling may stop it (0 = automatic)"),
}
# Viewport properties that stand for a library setting in the Rendered viewport, as Cycles'
# preview_* settings do: the viewport renders with their value instead of the F12 render's
# (engine/viewport.py), and they take that setting's range and kind.
VIEWPORT_SETTINGS: dict[str, str] = {
    "use_preview_adaptive_sampling": "use_adaptive_sampling",
    "preview_adaptive_threshold": "adaptive_threshold",
    "preview_adaptive_min_samples": "adaptive_min_samples",
}
# Defaults of the viewport properties: Cycles' start resolution (64), not its viewport sample
# count (1024 in 3.x is meant for a GPU; 32 refines a CPU viewport in seconds), and the sampler
# compared with the library's default sampler, `random`. Adaptive sampling is off, as the
# library's default for F12 is; when on, Cycles' viewport threshold (0.1, ten times its F12
# one) is the starting point.
VIEWPORT_DEFAULTS: dict[str, int | float | bool | str] = {
    "preview_samples": 32,
    "preview_start_resolution": 64,
    "use_split_view": False,
    "compare_sampler": "sobol",
    "split_position": 0.5,
    "use_preview_adaptive_sampling": False,
    "preview_adaptive_threshold": 0.1,
    "preview_adaptive_min_samples": 0,
}
