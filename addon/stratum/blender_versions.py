"""What differs between the Blender versions Stratum supports (3.4 to 5.0), in one place.

Every module that reads Blender's data or reproduces Cycles asks here, by the name of the
difference, instead of comparing versions itself (tests/python/test_blender_versions.py fails on
a version comparison anywhere else). Pure Python without bpy: callers pass the version
(bpy.app.version in Blender; tests pass any), or, for a data API that Blender changed, the
object whose attributes tell.

Three kinds of difference:

* **Blender's data API** (RNA): where a value lives or in which form it is read and written.
* **Socket and pass names**: the Principled BSDF's sockets (renamed in 4.0) and the render
  passes (renamed in 5.0). Other nodes' sockets are found by every name they have had
  (NodeCompiler.socket takes an identifier or a name; a socket a version lacks is a default).
* **Cycles' evaluation per release**, which the renderer reproduces: each answer is the
  generation (a native mode, or a model's name) that matches the Blender a file is rendered in.
  The native node or model documents what each generation computes.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

Version = Sequence[int]


def _since(version: Version, *release: int) -> bool:
    """Whether `version` is `release` (major, minor) or later."""
    return tuple(version[:len(release)]) >= release


# ---- Blender's data API -------------------------------------------------------------------------


def has_corner_normals(mesh: Any) -> bool:
    """4.1 replaced split normals (calc_normals_split into loop.normal, only with
    use_auto_smooth) by Mesh.corner_normals, vertex_normals that are computed in a fixed order,
    normals_domain and custom normals that apply whenever present."""
    return hasattr(mesh, "corner_normals")


def has_normals_domain(mesh: Any) -> bool:
    """4.1: Mesh.normals_domain says whether the normals are per point, face or corner."""
    return hasattr(mesh, "normals_domain")


def uv_layer_has_uv_vectors(layer: Any) -> bool:
    """3.5: a UV layer's coordinates are the `uv` attribute's vectors (before: layer.data.uv)."""
    return hasattr(layer, "uv")


def panorama_in_cycles_settings(version: Version) -> bool:
    """Before 4.0 a camera's panorama type and ranges are Cycles' (camera.cycles); from 4.0
    they are the camera's own."""
    return not _since(version, 4, 0)


def cast_shadow_in_cycles_settings(version: Version) -> bool:
    """Before 4.0 a light's Cast Shadow is light.cycles.cast_shadow; from 4.0 light.use_shadow."""
    return not _since(version, 4, 0)


def node_trees_always_used(version: Version) -> bool:
    """5.0 deprecates use_nodes of materials and worlds: their node trees are always used."""
    return _since(version, 5, 0)


def flat_pass_pixels(version: Version) -> bool:
    """4.1: a render pass's rect.foreach_set takes a flat array (before: one row per pixel)."""
    return _since(version, 4, 1)


# ---- socket and pass names ----------------------------------------------------------------------


@dataclass(frozen=True)
class PrincipledSockets:
    """The Principled BSDF's inputs in one generation of its sockets, by what the native
    closure takes (the rest, Base Color, Metallic, Roughness, IOR, Normal, Alpha, Emission
    Strength and Coat IOR and Tint, kept their names)."""

    specular: str
    transmission: str
    emission: str
    coat: str
    coat_roughness: str
    # Inputs the closure takes as constants, each with the program parameter
    # (native.PROGRAM_PARAMS) that a link drives instead, or None: a link is warned about.
    constant: tuple[tuple[str, str | None], ...]
    # Inputs rendered without, each with its value that means "off" (else a warning).
    unsupported: tuple[tuple[str, float], ...]

    @property
    def bindable(self) -> tuple[tuple[str, str], ...]:
        """(input, parameter) of the inputs an image or the node program may drive, in the
        order their bindings are made."""
        return (("Base Color", "base_color"), ("Roughness", "roughness"),
                ("Metallic", "metallic"), ("Normal", "normal"), (self.specular, "specular"),
                (self.transmission, "transmission"), (self.emission, "emission"))


PRINCIPLED_V1 = PrincipledSockets(  # Blender 3.x
    specular="Specular", transmission="Transmission", emission="Emission", coat="Clearcoat",
    coat_roughness="Clearcoat Roughness",
    constant=(("IOR", "ior"), ("Clearcoat", "coat"), ("Clearcoat Roughness", "coat_roughness")),
    unsupported=(("Subsurface", 0.0), ("Sheen", 0.0), ("Anisotropic", 0.0),
                 ("Specular Tint", 0.0), ("Transmission Roughness", 0.0)))
PRINCIPLED_V2 = PrincipledSockets(  # Blender 4.0 and later
    specular="Specular IOR Level", transmission="Transmission Weight", emission="Emission Color",
    coat="Coat Weight", coat_roughness="Coat Roughness",
    constant=(("IOR", "ior"), ("Coat Weight", "coat"), ("Coat Roughness", "coat_roughness"),
              ("Coat IOR", None), ("Coat Tint", "coat_tint")),
    unsupported=(("Subsurface Weight", 0.0), ("Sheen Weight", 0.0), ("Anisotropic", 0.0),
                 ("Thin Film Thickness", 0.0), ("Diffuse Roughness", 0.0)))


def principled_v2(version: Version, node: Any = None) -> bool:
    """4.0's Principled BSDF (Cycles' principled v2 model, PRINCIPLED_V2's sockets): from 4.0,
    and for a Principled `node` that has 4.0's sockets in any version."""
    if node is not None and node.inputs.get(PRINCIPLED_V2.specular) is not None:
        return True
    return _since(version, 4, 0)


# Blender 5.0 renamed the passes it has toggles for: Cycles' list_render_passes yields "Emission"
# in 5.0 where 3.4's yields "Emit" (intern/cycles/blender/addon/engine.py of each), and the
# compositor's Render Layers sockets carry the new names. The library keeps the 3.x names.
PASSES_RENAMED_IN_5_0 = {"Emit": "Emission", "Env": "Environment", "AO": "Ambient Occlusion",
                         "IndexOB": "Object Index", "IndexMA": "Material Index",
                         "DiffCol": "Diffuse Color", "GlossCol": "Glossy Color",
                         "TransCol": "Transmission Color"}


def render_pass_name(name: str, version: Version) -> str:
    """The render-result pass of native pass `name` (Cycles 3.x's name) in Blender `version`."""
    if _since(version, 5, 0):
        return PASSES_RENAMED_IN_5_0.get(name, name)
    return name


# ---- Cycles' evaluation per release: lights and closures ----------------------------------------


def lightgroups_take_split_emission(version: Version) -> bool:
    """Cycles before 3.5 still writes emission met after a shadow catcher split to the light
    groups (film_write_emission_or_background_pass); 3.5's fix of T103403 (cycles commit
    8a2966181) skips it, as it always skipped NEE there."""
    return not _since(version, 3, 5)


def spot_light_model(version: Version) -> str:
    """The native spot light: Cycles 3.x multiplies the spot's falloff by the cosine to its
    axis ("spot_v1"), 4.0 and later do not ("spot")."""
    return "spot" if _since(version, 4, 0) else "spot_v1"


def area_light_power_scale(version: Version) -> float:
    """Cycles 3.x emits pi/4 of an area light's power (4.0 normalised it to the power)."""
    return 1.0 if _since(version, 4, 0) else math.pi / 4.0


def has_bump_map_correction(version: Version) -> bool:
    """4.2: a material's Bump Map Correction (cycles.use_bump_map_correction, default on) keeps
    or drops the smoothing of the shadowing term of bumped closures (before: always kept)."""
    return _since(version, 4, 2)


def conty_bump_shadowing(version: Version) -> bool:
    """The shadowing term of closures whose normal differs from the smooth one
    (kernel/closure/bsdf.h bump_shadowing_term): Chiang et al. 2019 up to 4.4, Conty Estevez
    et al. 2019 from 4.5."""
    return _since(version, 4, 5)


def normal_map_scales_strength(version: Version) -> bool:
    """Normal Map: 4.0 and later scale the tangent-space normal by Strength; 3.x interpolates
    from the smooth normal (they agree for strengths in [0, 1])."""
    return _since(version, 4, 0)


def color_config(version: Version) -> int:
    """Blender's colour configuration (datafiles/colormanagement/config.ocio), from which Cycles
    derives, when it starts, its luminance weights (colour to float, RGB to BW) and its XYZ to
    scene-linear matrix (Blackbody, Wavelength, Sky Texture), by one rule in every version
    (ShaderManager::init_xyz_transforms: the aces_interchange space through OpenColorIO's
    built-in ACES AP0 -> XYZ D65). 0: Blender 3.x (Linear through srgb_to_xyz.spimtx); 1: 4.0 to
    4.5 (OCIO profile 2: Linear Rec.709 from Linear CIE-XYZ D65 by a 16-digit BT.709 matrix);
    2: 5.0 and later (profile 2.4: the 7-digit BT.709 matrix). The native luminance weights and
    sky matrix take this number (shading/node_registry.h, sky_models.h)."""
    if not _since(version, 4, 0):
        return 0
    return 2 if _since(version, 5, 0) else 1


# ---- Cycles' evaluation per release: shader nodes (native program node modes) -------------------


def noise_generation(version: Version) -> int:
    """Noise and Musgrave Textures, and the Wave Texture's distortion (its fBM): 0 Blender
    3.x, 1 4.0, 2 4.1, 3 4.2 and later (native shading/nodes/noise_texture.cpp,
    wave_texture.cpp)."""
    if not _since(version, 4, 0):
        return 0
    if not _since(version, 4, 1):
        return 1
    return 3 if _since(version, 4, 2) else 2


def voronoi_generation(version: Version) -> int:
    """Voronoi Texture: 0 Blender 3.x, 1 4.0-4.4, 2 4.5, 3 5.0 and later (native
    shading/nodes/voronoi_texture.cpp)."""
    if not _since(version, 4, 0):
        return 0
    if not _since(version, 4, 5):
        return 1
    return 3 if _since(version, 5, 0) else 2


def voronoi_lacunarity_from_smoothness(version: Version) -> bool:
    """Cycles 4.0-4.2 loads the Voronoi's Lacunarity from Smoothness's stack slot."""
    return _since(version, 4, 0) and not _since(version, 4, 3)


def brick_generation(version: Version) -> int:
    """Brick: 3.5 clamped the mortar's smoothstep (0 before, 1 from 3.5)."""
    return 1 if _since(version, 3, 5) else 0


def hue_wraps_with_fmod(version: Version) -> bool:
    """Hue/Saturation/Value wraps the shifted hue with fmodf up to 4.2 and fractf from 4.3."""
    return not _since(version, 4, 3)


def ramp_table_has_end_entry(version: Version) -> bool:
    """4.1: Cycles bakes colour ramps and curves into RAMP_TABLE_SIZE + 1 entries (one more)."""
    return _since(version, 4, 1)


def vector_math_revision(version: Version) -> int:
    """Vector Math: 0 Blender 3.x-4.2, 1 4.3-4.5 (safe-normalised Reflect and Refract), 2 5.0
    and later (SSE modulo and floored wrap)."""
    if not _since(version, 4, 3):
        return 0
    return 2 if _since(version, 5, 0) else 1


def vector_transform_revision(version: Version) -> int:
    """Vector Transform: 0 Blender 3.x (normalises a NORMAL), 1 4.0 and later (leave it;
    native shading/nodes/mapping_node.cpp)."""
    return 1 if _since(version, 4, 0) else 0


def light_falloff_revision(version: Version) -> int:
    """Light Falloff at Cycles' ray length FLT_MAX (the world, suns): 0 before 4.4 (the outputs
    multiplied by it, Constant infinite), 1 from 4.4 (every output is the strength; native
    shading/nodes/light_falloff_node.cpp)."""
    return 1 if _since(version, 4, 4) else 0


def wireframe_at_bump_offsets(version: Version) -> bool:
    """Wireframe inside a Bump's Height: 4.4 and later evaluate it at the offset points (as
    every other node); before, Cycles adds a difference quotient to its value at the point."""
    return _since(version, 4, 4)
