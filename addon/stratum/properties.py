"""Scene render settings (`scene.stratum`), named exactly as the native settings.

The sampler, hemisphere, integrator and filter menus are built from the native registries at
register time (item tooltips are the registry descriptions), so a menu and the library cannot
disagree. If the library cannot be loaded, registration still succeeds (with one-item fallback
menus) and the engine reports the load error on render.
"""

from __future__ import annotations

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty, PointerProperty

from . import native

EnumItems = list[tuple[str, str, str]]

# The estimator options (textbook §4–§6). The identifiers are the native setting values
# (integrators/estimator_options.h), default first; tests/blender/test_estimator_settings.py
# renders with every item, so an identifier the library does not know fails there.
LIGHT_SAMPLING_ITEMS: EnumItems = [
    ("mis", "Multiple Importance",
     "Light sampling (next-event estimation) and BSDF sampling combined by multiple "
     "importance sampling (textbook §5.5)"),
    ("nee", "Light Sampling",
     "Next-event estimation only: emission is found by shadow rays to sampled lights; a "
     "scattered ray counts emission only after the camera or a delta vertex (eq. 5.16)"),
    ("bsdf", "BSDF Sampling",
     "BSDF sampling only: emission is found by scattered rays hitting lights (eq. 5.2); point "
     "and sun lights cannot be hit and stay black"),
]
MIS_HEURISTIC_ITEMS: EnumItems = [
    ("power", "Power", "Power heuristic with beta = 2: w = p_a^2 / (p_a^2 + p_b^2) (§4.4)"),
    ("balance", "Balance", "Balance heuristic: w = p_a / (p_a + p_b) (§4.4)"),
    ("max", "Maximum", "Maximum heuristic: weight 1 for the strategy with the larger pdf (§4.4)"),
]
LIGHT_SELECTION_ITEMS: EnumItems = [
    ("mixed", "Mixed",
     "Half proportional to power, half uniform over the lights (a defensive mixture)"),
    ("power", "Power", "Proportional to each light's power: p_j = Phi_j / sum Phi (eq. 5.14)"),
    ("uniform", "Uniform", "Every light with the same probability 1/N"),
]
TRIANGLE_SAMPLING_ITEMS: EnumItems = [
    ("solid_angle", "Solid Angle",
     "A direction uniform in the solid angle the triangle subtends (Arvo 1995): no fireflies "
     "next to emissive meshes"),
    ("area", "Area",
     "A point uniform in the triangle's area (textbook eq. 5.9): its weight grows as 1/r^2 "
     "near the emitter"),
]
RR_MODE_ITEMS: EnumItems = [
    ("throughput", "Throughput",
     "Survival probability min(1, max channel of the path throughput) (eq. 5.5-5.6)"),
    ("albedo", "Albedo",
     "Survival probability min(1, max channel of the surface reflectance) (eq. 5.5-5.6)"),
    ("off", "Off", "No Russian roulette: paths end only at the bounce limit or on escaping"),
]

FALLBACK_SAMPLERS: EnumItems = [("random", "Random", "Independent uniform random numbers")]
FALLBACK_HEMISPHERES: EnumItems = [
    ("cosine", "Cosine-Weighted", "Cosine-weighted directions (pdf cos(theta)/pi)"),
]
FALLBACK_INTEGRATORS: EnumItems = [("path", "Path Tracing", "Path tracing")]
FALLBACK_FILTERS: EnumItems = [
    ("box", "Box", "Box filter"),
    ("blackman_harris", "Blackman-Harris", "Blackman-Harris filter"),
]

# Why the library could not be loaded at register time ("" when it could).
load_error: str = ""
_property_group: type | None = None


def _registry_items(kind: str, fallback: EnumItems) -> EnumItems:
    global load_error
    try:
        entries = native.registry(kind)
    except native.StratumError as exc:
        load_error = str(exc)
        return list(fallback)
    items = [(e.name, e.label or e.name, e.description) for e in entries]
    return items or list(fallback)


def _default(items: EnumItems, preferred: str) -> str:
    return preferred if any(i[0] == preferred for i in items) else items[0][0]


def _make_property_group(samplers: EnumItems, filters: EnumItems, hemispheres: EnumItems,
                         integrators: EnumItems) -> type:
    sampler_default = _default(samplers, "random")
    filter_default = _default(filters, "blackman_harris")
    hemisphere_default = _default(hemispheres, "cosine")
    integrator_default = _default(integrators, "path")

    class StratumRenderSettings(bpy.types.PropertyGroup):
        __annotations__ = {
            "samples": IntProperty(
                name="Samples",
                description="Number of samples per pixel",
                default=64, min=1, soft_max=4096,
            ),
            "max_bounces": IntProperty(
                name="Max Bounces",
                description="Total maximum number of bounces (0 = direct lighting only), "
                "as Cycles' max_bounces",
                default=12, min=0, soft_max=1024,
            ),
            "seed": IntProperty(
                name="Seed",
                description="Seed of the sampler's scrambling and randomization",
                default=0, min=0,
            ),
            "sampler": EnumProperty(
                name="Sampler",
                description="Sampling strategy (from the native sampler registry)",
                items=samplers, default=sampler_default,
            ),
            "hemisphere": EnumProperty(
                name="Hemisphere",
                description="Distribution of diffuse and ambient-occlusion directions "
                "(from the native hemisphere registry)",
                items=hemispheres, default=hemisphere_default,
            ),
            "integrator": EnumProperty(
                name="Integrator",
                description="Light transport algorithm (from the native integrator registry)",
                items=integrators, default=integrator_default,
            ),
            "ao_distance": FloatProperty(
                name="AO Distance",
                description="Ambient occlusion: a direction is occluded when an obstacle lies "
                "within this distance",
                default=1.0, min=1e-4, soft_max=100.0, subtype="DISTANCE",
            ),
            "filter_type": EnumProperty(
                name="Filter Type",
                description="Pixel reconstruction filter",
                items=filters, default=filter_default,
            ),
            "filter_width": FloatProperty(
                name="Filter Width",
                description="Pixel filter width in pixels, as Cycles' filter_width",
                default=1.5, min=0.01, max=10.0, subtype="PIXEL",
            ),
            "light_sampling": EnumProperty(
                name="Light Sampling",
                description="How the path tracer finds emission",
                items=LIGHT_SAMPLING_ITEMS, default=LIGHT_SAMPLING_ITEMS[0][0],
            ),
            "mis_heuristic": EnumProperty(
                name="MIS Heuristic",
                description="Weights of light and BSDF samples under multiple importance "
                "sampling",
                items=MIS_HEURISTIC_ITEMS, default=MIS_HEURISTIC_ITEMS[0][0],
            ),
            "light_selection": EnumProperty(
                name="Light Selection",
                description="Probability of choosing each light for a light sample",
                items=LIGHT_SELECTION_ITEMS, default=LIGHT_SELECTION_ITEMS[0][0],
            ),
            "triangle_sampling": EnumProperty(
                name="Triangle Sampling",
                description="How a light sample takes a point on an emissive triangle",
                items=TRIANGLE_SAMPLING_ITEMS, default=TRIANGLE_SAMPLING_ITEMS[0][0],
            ),
            "rr_mode": EnumProperty(
                name="Russian Roulette",
                description="How a path's survival probability is chosen",
                items=RR_MODE_ITEMS, default=RR_MODE_ITEMS[0][0],
            ),
            "rr_min_depth": IntProperty(
                name="Roulette Min Depth",
                description="First bounce at which Russian roulette may end a path",
                default=3, min=0, max=1024,
            ),
            "control_variate": FloatProperty(
                name="Control Variate",
                description="Ambient radiance L_a of the control variate (textbook 5.17); "
                "0 = off",
                default=0.0, min=0.0, soft_max=10.0,
            ),
            "threads": IntProperty(
                name="Threads",
                description="Number of render threads (0 = all cores)",
                default=0, min=0, soft_max=1024,
            ),
        }

    return StratumRenderSettings


def register() -> None:
    global _property_group, load_error
    load_error = ""
    samplers = _registry_items("sampler", FALLBACK_SAMPLERS)
    filters = _registry_items("filter", FALLBACK_FILTERS)
    hemispheres = _registry_items("hemisphere", FALLBACK_HEMISPHERES)
    integrators = _registry_items("integrator", FALLBACK_INTEGRATORS)
    _property_group = _make_property_group(samplers, filters, hemispheres, integrators)
    bpy.utils.register_class(_property_group)
    bpy.types.Scene.stratum = PointerProperty(type=_property_group, name="Stratum")


def unregister() -> None:
    global _property_group
    if hasattr(bpy.types.Scene, "stratum"):
        del bpy.types.Scene.stratum
    if _property_group is not None:
        bpy.utils.unregister_class(_property_group)
        _property_group = None
