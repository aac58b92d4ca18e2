"""Python-side descriptions of what a Scene is made of (materials, textures, instances, lights,
camera): dataclasses whose fields and defaults are those of the C structs they fill."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from .abi import (
    BUMP_SHADOWING_NONE,
    CAMERA_PERSPECTIVE,
    MICROFACET_GGX,
    SENSOR_FIT_AUTO,
    TEXTURE_LINEAR,
    TEXTURE_REPEAT,
    VISIBLE_ALL,
    VISIBLE_SHADOW_CATCHER,
)
from .models import closure_model, light_type

# The default transform of lights and cameras: the 4x4 identity, row-major (a tuple: one
# default shared by every instance must be immutable).
IDENTITY_TRANSFORM: tuple[float, ...] = tuple(np.eye(4, dtype=np.float32).ravel())


@dataclass
class Material:
    model: int = field(default_factory=lambda: closure_model("diffuse"))
    base_color: tuple[float, float, float] = (0.8, 0.8, 0.8)
    roughness: float = 0.5
    metallic: float = 0.0
    specular: float = 0.5
    ior: float = 1.5
    emission: tuple[float, float, float] = (0.0, 0.0, 0.0)
    distribution: int = MICROFACET_GGX
    transmission: float = 0.0
    coat: float = 0.0
    coat_roughness: float = 0.03
    coat_ior: float = 1.5
    coat_tint: tuple[float, float, float] = (1.0, 1.0, 1.0)
    bump_shadowing: int = BUMP_SHADOWING_NONE


@dataclass
class Texture:
    """One image for stratum_scene_add_texture: exactly one of path, file_data (with
    file_name naming its format), pixels ((height, width, channels) float32, rows bottom to
    top as Blender's Image.pixels)."""

    path: str | None = None
    file_data: bytes | None = None
    file_name: str | None = None
    pixels: np.ndarray | None = None
    color_space: str = "sRGB"
    ocio_config: str | None = None
    interpolation: int = TEXTURE_LINEAR
    extension: int = TEXTURE_REPEAT


@dataclass(frozen=True)
class TextureInfo:
    """What loading a texture found: its size and its texels that were NaN or infinite after
    conversion to scene linear, which the renderer holds as (0, 0, 0, 0) as Cycles does."""

    width: int
    height: int
    replaced_texels: int


@dataclass
class TextureBinding:
    """Drives one parameter of one closure of a material by a texture (see stratum.h)."""

    material_id: int
    closure_index: int
    param: int
    texture_id: int
    channel: int = -1  # -1 RGB, 0..3 one channel
    scale: float = 1.0
    offset: float = 0.0
    emission_strength: float = 0.0  # must be 0 (PARAM_EMISSION bindings are refused)


@dataclass
class Instance:
    mesh_id: int
    transform: Sequence[float] | np.ndarray
    transform_end: Sequence[float] | np.ndarray | None = None  # set when the object moves
    visibility: int = VISIBLE_ALL
    holdout: bool = False
    pass_index: int = 0  # Object > Relations > Pass Index (the IndexOB pass)
    lightgroup: int = 0  # its emission's light group: 0 none, k in 1..MAX_LIGHT_GROUPS


@dataclass
class Light:
    type: int = field(default_factory=lambda: light_type("point"))
    color: tuple[float, float, float] = (1.0, 1.0, 1.0)
    strength: float = 10.0
    radius: float = 0.0
    angle: float = 0.0
    size_x: float = 1.0
    size_y: float = 1.0
    transform: Sequence[float] | np.ndarray = IDENTITY_TRANSFORM
    spot_size: float = math.pi  # full cone angle (spot lights)
    spot_blend: float = 0.0
    # Blender's lights light shadow catchers (object.is_shadow_catcher is on for them).
    visibility: int = VISIBLE_ALL | VISIBLE_SHADOW_CATCHER
    spread: float = math.pi  # area lights
    lightgroup: int = 0  # 0 none, k in 1..MAX_LIGHT_GROUPS


@dataclass
class Camera:
    lens_mm: float = 50.0
    sensor_width_mm: float = 36.0
    sensor_height_mm: float = 24.0
    sensor_fit: int | str = SENSOR_FIT_AUTO
    shift_x: float = 0.0
    shift_y: float = 0.0
    clip_start: float = 0.1
    clip_end: float = 1000.0
    transform: Sequence[float] | np.ndarray = IDENTITY_TRANSFORM
    type: int | str = CAMERA_PERSPECTIVE  # or "PERSP" / "ORTHO"
    ortho_scale: float = 6.0  # orthographic: extent of the fitted image side (scene units)
    aperture_radius: float = 0.0  # thin lens radius (scene units); 0 = pinhole
    focus_distance: float = 0.0  # depth of the sharp plane; > 0 when aperture_radius > 0
    aperture_blades: int = 0  # 0 = round, >= 3 = polygon
    aperture_rotation: float = 0.0  # radians
    latitude_min: float = -math.pi / 2  # equirectangular ranges (radians)
    latitude_max: float = math.pi / 2
    longitude_min: float = -math.pi
    longitude_max: float = math.pi
