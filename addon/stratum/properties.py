"""Scene render settings (`scene.stratum`), named exactly as the native settings.

The sampler and filter menus are built from the native registries at register time, so the
menu and the library cannot disagree. If the library cannot be loaded, registration still
succeeds (with a single 'random' sampler) and the engine reports the load error on render.
"""

from __future__ import annotations

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty, PointerProperty

from . import native

EnumItems = list[tuple[str, str, str]]

FALLBACK_SAMPLERS: EnumItems = [("random", "Random", "Independent uniform random numbers")]
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


def _make_property_group(samplers: EnumItems, filters: EnumItems) -> type:
    sampler_default = "random" if any(i[0] == "random" for i in samplers) else samplers[0][0]
    filter_default = (
        "blackman_harris" if any(i[0] == "blackman_harris" for i in filters) else filters[0][0]
    )

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
    _property_group = _make_property_group(samplers, filters)
    bpy.utils.register_class(_property_group)
    bpy.types.Scene.stratum = PointerProperty(type=_property_group, name="Stratum")


def unregister() -> None:
    global _property_group
    if hasattr(bpy.types.Scene, "stratum"):
        del bpy.types.Scene.stratum
    if _property_group is not None:
        bpy.utils.unregister_class(_property_group)
        _property_group = None
