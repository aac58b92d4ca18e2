"""ctypes binding of the Stratum C ABI (native/include/stratum/stratum.h).

This is the ONLY module that knows the C ABI. Everything above it (export, engine, cli) talks
to `Scene`, `Renderer` and `registry()`. Every native call goes through `_check`, so a non-OK
status becomes a `StratumError` carrying stratum_last_error()'s text; nothing here can abort
the host process on bad input, because the library validates every value.

The library is loaded lazily (first use), from $STRATUM_LIBRARY or stratum/lib/libstratum.so,
with RTLD_LOCAL | RTLD_DEEPBIND on Linux: Blender (and the bpy wheel) carry their own Embree,
OIIO and TBB, and deep binding keeps our library bound to the copies it was linked with.
"""

from __future__ import annotations

import ctypes
import math
import os
import sys
import threading
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, is_dataclass
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

# ---- status codes and enums (mirror stratum.h) --------------------------------------------

OK = 0
ERROR_INVALID_ARGUMENT = 1
ERROR_INVALID_STATE = 2
ERROR_OUT_OF_MEMORY = 3
ERROR_INTERNAL = 4
ERROR_IO = 5

STATUS_NAMES: dict[int, str] = {
    OK: "OK",
    ERROR_INVALID_ARGUMENT: "invalid argument",
    ERROR_INVALID_STATE: "invalid state",
    ERROR_OUT_OF_MEMORY: "out of memory",
    ERROR_INTERNAL: "internal error",
    ERROR_IO: "I/O error",
}

REGISTRY_SAMPLER = 0
REGISTRY_FILTER = 1
REGISTRY_INTEGRATOR = 2
REGISTRY_HEMISPHERE = 3
REGISTRIES: dict[str, int] = {
    "sampler": REGISTRY_SAMPLER,
    "filter": REGISTRY_FILTER,
    "integrator": REGISTRY_INTEGRATOR,
    "hemisphere": REGISTRY_HEMISPHERE,
}

MATERIAL_DIFFUSE = 0
MATERIAL_PRINCIPLED_V1 = 1
MATERIAL_PRINCIPLED_V2 = 2
MATERIAL_EMISSION = 3
MATERIAL_GLOSSY = 4
MATERIAL_GLASS = 5
MATERIAL_TRANSPARENT = 6
MATERIAL_HOLDOUT = 7

TEXTURE_CLOSEST = 0
TEXTURE_LINEAR = 1
TEXTURE_REPEAT = 0
TEXTURE_EXTEND = 1
TEXTURE_CLIP = 2
TEXTURE_MIRROR = 3

PARAM_BASE_COLOR = 0
PARAM_ROUGHNESS = 1
PARAM_METALLIC = 2
PARAM_NORMAL = 3
PARAM_EMISSION = 4
PARAM_WEIGHT = 5
PARAM_TRANSMISSION = 6
PARAM_SPECULAR = 7

VISIBLE_CAMERA = 1
VISIBLE_DIFFUSE = 2
VISIBLE_GLOSSY = 4
VISIBLE_TRANSMISSION = 8
VISIBLE_SHADOW = 16
VISIBLE_ALL = 31

MICROFACET_GGX = 0
MICROFACET_MULTISCATTER_GGX = 1

# StratumBumpShadowing: Cycles' term for closures whose normal is perturbed.
BUMP_SHADOWING_NONE = 0
BUMP_SHADOWING_CHIANG = 1  # Cycles 2.90-4.4
BUMP_SHADOWING_CHIANG_UNSMOOTHED = 2  # Cycles 4.2-4.4, Bump Map Correction off
BUMP_SHADOWING_CONTY = 3  # Cycles 4.5+
BUMP_SHADOWING_CONTY_UNSMOOTHED = 4  # Cycles 4.5+, Bump Map Correction off

LIGHT_POINT = 0
LIGHT_SUN = 1
LIGHT_AREA_RECTANGLE = 2
LIGHT_AREA_ELLIPSE = 3
LIGHT_SPOT = 4  # Cycles 4.x/5.x spot
LIGHT_SPOT_V1 = 5  # Cycles 3.x spot: the 4.x falloff times cos(angle to the axis)

CAMERA_PERSPECTIVE = 0
CAMERA_ORTHOGRAPHIC = 1
CAMERA_EQUIRECTANGULAR = 2
CAMERA_TYPES: dict[str, int] = {"PERSP": CAMERA_PERSPECTIVE, "ORTHO": CAMERA_ORTHOGRAPHIC,
                                "EQUIRECTANGULAR": CAMERA_EQUIRECTANGULAR}

SENSOR_FIT_AUTO = 0
SENSOR_FIT_HORIZONTAL = 1
SENSOR_FIT_VERTICAL = 2
SENSOR_FITS: dict[str, int] = {
    "AUTO": SENSOR_FIT_AUTO,
    "HORIZONTAL": SENSOR_FIT_HORIZONTAL,
    "VERTICAL": SENSOR_FIT_VERTICAL,
}


class StratumError(RuntimeError):
    """A native call failed (status != OK) or the library could not be loaded.

    stratum_last_error() reads "stratum_function: detail"; the function is kept apart
    (`function`) so that what a user sees, str(error), is the detail alone: Blender's messages
    name the object and field, not the ABI entry point. `message` is the whole text. `index`
    is the failing element of a batched call (add_instances), else None."""

    def __init__(self, status: int, message: str, index: int | None = None) -> None:
        self.status = status
        self.message = message
        self.index = index
        head, sep, rest = message.partition(": ")
        is_function = sep and head.startswith("stratum_") and head.isidentifier()
        self.function = head if is_function else ""
        self.detail = rest if is_function else message
        super().__init__(self.detail or STATUS_NAMES.get(status, f"status {status}"))


class LibraryLoadError(StratumError):
    """libstratum.so is missing or cannot be loaded."""

    def __init__(self, message: str) -> None:
        super().__init__(ERROR_INTERNAL, message)


# ---- C structs -------------------------------------------------------------------------------

_c_float3 = ctypes.c_float * 3
_c_float16 = ctypes.c_float * 16


class _MaterialDesc(ctypes.Structure):
    _fields_ = [
        ("model", ctypes.c_int32),
        ("base_color", _c_float3),
        ("roughness", ctypes.c_float),
        ("metallic", ctypes.c_float),
        ("specular", ctypes.c_float),
        ("ior", ctypes.c_float),
        ("emission", _c_float3),
        ("distribution", ctypes.c_int32),
        ("transmission", ctypes.c_float),
        ("coat", ctypes.c_float),
        ("coat_roughness", ctypes.c_float),
        ("coat_ior", ctypes.c_float),
        ("coat_tint", _c_float3),
        ("bump_shadowing", ctypes.c_int32),
    ]


class _ClosureDesc(ctypes.Structure):
    _fields_ = [
        ("weight", _c_float3),
        ("closure", _MaterialDesc),
    ]


class _TextureDesc(ctypes.Structure):
    _fields_ = [
        ("path", ctypes.c_char_p),
        ("file_data", ctypes.c_void_p),
        ("file_size", ctypes.c_size_t),
        ("file_name", ctypes.c_char_p),
        ("pixels", ctypes.POINTER(ctypes.c_float)),
        ("width", ctypes.c_uint32),
        ("height", ctypes.c_uint32),
        ("channels", ctypes.c_uint32),
        ("color_space", ctypes.c_char_p),
        ("ocio_config", ctypes.c_char_p),
        ("interpolation", ctypes.c_int32),
        ("extension", ctypes.c_int32),
    ]


class _TextureInfo(ctypes.Structure):
    _fields_ = [
        ("width", ctypes.c_uint32),
        ("height", ctypes.c_uint32),
        ("replaced_texels", ctypes.c_uint64),
    ]


class _TextureBinding(ctypes.Structure):
    _fields_ = [
        ("material_id", ctypes.c_uint32),
        ("closure_index", ctypes.c_uint32),
        ("param", ctypes.c_int32),
        ("texture_id", ctypes.c_uint32),
        ("channel", ctypes.c_int32),
        ("scale", ctypes.c_float),
        ("offset", ctypes.c_float),
        ("emission_strength", ctypes.c_float),
    ]


class _InstanceDesc(ctypes.Structure):
    _fields_ = [
        ("mesh_id", ctypes.c_uint32),
        ("transform", _c_float16),
        ("transform_end", _c_float16),
        ("motion", ctypes.c_int32),
        ("visibility", ctypes.c_uint32),
        ("holdout", ctypes.c_int32),
    ]


class _MeshDesc(ctypes.Structure):
    _fields_ = [
        ("positions", ctypes.POINTER(ctypes.c_float)),
        ("vertex_count", ctypes.c_uint32),
        ("triangles", ctypes.POINTER(ctypes.c_uint32)),
        ("triangle_count", ctypes.c_uint32),
        ("corner_normals", ctypes.POINTER(ctypes.c_float)),
        ("corner_uvs", ctypes.POINTER(ctypes.c_float)),
        ("material_ids", ctypes.POINTER(ctypes.c_uint32)),
        ("vertex_normals", ctypes.POINTER(ctypes.c_float)),
        ("corner_tangents", ctypes.POINTER(ctypes.c_float)),
    ]


class _LightDesc(ctypes.Structure):
    _fields_ = [
        ("type", ctypes.c_int32),
        ("color", _c_float3),
        ("strength", ctypes.c_float),
        ("radius", ctypes.c_float),
        ("angle", ctypes.c_float),
        ("size_x", ctypes.c_float),
        ("size_y", ctypes.c_float),
        ("transform", _c_float16),
        ("spot_size", ctypes.c_float),
        ("spot_blend", ctypes.c_float),
        ("visibility", ctypes.c_uint32),
        ("spread", ctypes.c_float),
    ]


class _CameraDesc(ctypes.Structure):
    _fields_ = [
        ("lens_mm", ctypes.c_float),
        ("sensor_width_mm", ctypes.c_float),
        ("sensor_height_mm", ctypes.c_float),
        ("sensor_fit", ctypes.c_int32),
        ("shift_x", ctypes.c_float),
        ("shift_y", ctypes.c_float),
        ("clip_start", ctypes.c_float),
        ("clip_end", ctypes.c_float),
        ("transform", _c_float16),
        ("type", ctypes.c_int32),
        ("ortho_scale", ctypes.c_float),
        ("aperture_radius", ctypes.c_float),
        ("focus_distance", ctypes.c_float),
        ("aperture_blades", ctypes.c_int32),
        ("aperture_rotation", ctypes.c_float),
        ("latitude_min", ctypes.c_float),
        ("latitude_max", ctypes.c_float),
        ("longitude_min", ctypes.c_float),
        ("longitude_max", ctypes.c_float),
    ]


class _Progress(ctypes.Structure):
    _fields_ = [
        ("done", ctypes.c_int32),
        ("cancelled", ctypes.c_int32),
        ("samples_done", ctypes.c_int32),
        ("samples_total", ctypes.c_int32),
        ("update_serial", ctypes.c_uint32),
        ("rays", ctypes.c_double),
        ("build_seconds", ctypes.c_double),
        ("render_seconds", ctypes.c_double),
        ("fraction_done", ctypes.c_double),
    ]


# ---- Python-side descriptions ---------------------------------------------------------------


@dataclass
class Material:
    model: int = MATERIAL_DIFFUSE
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


@dataclass
class Light:
    type: int = LIGHT_POINT
    color: tuple[float, float, float] = (1.0, 1.0, 1.0)
    strength: float = 10.0
    radius: float = 0.0
    angle: float = 0.0
    size_x: float = 1.0
    size_y: float = 1.0
    transform: Sequence[float] | np.ndarray = tuple(np.eye(4, dtype=np.float32).ravel())
    spot_size: float = math.pi  # full cone angle (spot lights)
    spot_blend: float = 0.0
    visibility: int = VISIBLE_ALL
    spread: float = math.pi  # area lights


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
    transform: Sequence[float] | np.ndarray = tuple(np.eye(4, dtype=np.float32).ravel())
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


@dataclass(frozen=True)
class Progress:
    done: bool
    cancelled: bool
    samples_done: int
    samples_total: int
    update_serial: int
    rays: float
    build_seconds: float
    render_seconds: float
    fraction_done: float


class RegistryEntry(NamedTuple):
    """(name, label, description) of a registry entry."""

    name: str
    label: str
    description: str


# ---- library loading ------------------------------------------------------------------------

_lib: ctypes.CDLL | None = None
_lib_lock = threading.Lock()


def default_library_path() -> Path:
    """$STRATUM_LIBRARY, else stratum/lib/libstratum.so next to this module."""
    env = os.environ.get("STRATUM_LIBRARY")
    if env:
        return Path(env)
    return Path(__file__).resolve().parent / "lib" / "libstratum.so"


def _declare(lib: ctypes.CDLL) -> None:
    c_int32, c_uint32, c_int64 = ctypes.c_int32, ctypes.c_uint32, ctypes.c_int64
    p_char = ctypes.c_char_p
    p_void = ctypes.c_void_p
    pp_void = ctypes.POINTER(ctypes.c_void_p)
    pp_char = ctypes.POINTER(ctypes.c_char_p)
    p_u32 = ctypes.POINTER(ctypes.c_uint32)
    p_i32 = ctypes.POINTER(ctypes.c_int32)
    p_float = ctypes.POINTER(ctypes.c_float)
    signatures: dict[str, tuple[Any, list[Any]]] = {
        "stratum_last_error": (p_char, []),
        "stratum_version": (p_char, []),
        "stratum_registry_count": (c_int32, [c_int32]),
        "stratum_registry_entry": (c_int32, [c_int32, c_int32, pp_char, pp_char, pp_char]),
        "stratum_dimension_name": (c_int32, [c_uint32, pp_char]),
        "stratum_camera_dimensions": (c_uint32, []),
        "stratum_bounce_dimension_stride": (c_uint32, []),
        "stratum_sampler_points": (c_int32, [p_char, c_uint32, c_uint32, c_uint32, c_uint32,
                                             c_uint32, c_uint32, c_uint32, c_uint32, c_uint32,
                                             p_float]),
        "stratum_warp_hemisphere": (c_int32, [p_char, p_float, c_uint32, p_float, p_float]),
        "stratum_bluenoise_texture": (c_int32, [p_float, c_uint32]),
        "stratum_scene_create": (c_int32, [pp_void]),
        "stratum_scene_destroy": (None, [p_void]),
        "stratum_scene_add_material": (c_int32, [p_void, ctypes.POINTER(_MaterialDesc), p_u32]),
        "stratum_scene_add_mesh": (c_int32, [p_void, ctypes.POINTER(_MeshDesc), p_u32]),
        "stratum_scene_add_instance": (c_int32, [p_void, c_uint32, p_float]),
        "stratum_scene_add_light": (c_int32, [p_void, ctypes.POINTER(_LightDesc)]),
        "stratum_scene_set_camera": (c_int32, [p_void, ctypes.POINTER(_CameraDesc)]),
        "stratum_scene_set_background": (c_int32, [p_void, p_float]),
        "stratum_scene_set_environment": (c_int32, [p_void, p_float, c_uint32, c_uint32,
                                                    ctypes.c_float, p_float]),
        "stratum_scene_save": (c_int32, [p_void, p_char]),
        "stratum_scene_load": (c_int32, [p_char, pp_void]),
        "stratum_scene_measure_ray_throughput": (c_int32, [p_void, c_uint32, c_uint32, c_uint32,
                                                           c_uint32, c_uint32,
                                                           ctypes.POINTER(ctypes.c_double),
                                                           ctypes.POINTER(ctypes.c_double)]),
        "stratum_renderer_create": (c_int32, [p_void, pp_void]),
        "stratum_renderer_destroy": (None, [p_void]),
        "stratum_renderer_set_int": (c_int32, [p_void, p_char, c_int64]),
        "stratum_renderer_set_float": (c_int32, [p_void, p_char, ctypes.c_double]),
        "stratum_renderer_set_string": (c_int32, [p_void, p_char, p_char]),
        "stratum_renderer_start": (c_int32, [p_void]),
        "stratum_renderer_notices": (c_int32, [p_void, pp_char]),
        "stratum_renderer_cancel": (c_int32, [p_void]),
        "stratum_renderer_wait": (c_int32, [p_void, c_int32, p_i32]),
        "stratum_renderer_progress": (c_int32, [p_void, ctypes.POINTER(_Progress)]),
        "stratum_renderer_read_pixels": (c_int32, [p_void, p_float, ctypes.c_size_t]),
        "stratum_renderer_write_image": (c_int32, [p_void, p_char]),
        "stratum_scene_add_closure_material": (c_int32, [p_void, ctypes.POINTER(_ClosureDesc),
                                                         c_uint32, p_u32]),
        "stratum_scene_add_texture": (c_int32, [p_void, ctypes.POINTER(_TextureDesc), p_u32]),
        "stratum_scene_texture_info": (c_int32, [p_void, ctypes.c_uint32,
                                                 ctypes.POINTER(_TextureInfo)]),
        "stratum_scene_bind_texture": (c_int32, [p_void, ctypes.POINTER(_TextureBinding)]),
        "stratum_scene_add_instance_ex": (c_int32, [p_void, ctypes.POINTER(_InstanceDesc)]),
    }
    for name, (restype, argtypes) in signatures.items():
        try:
            fn = getattr(lib, name)
        except AttributeError as exc:
            raise LibraryLoadError(f"{lib._name}: missing symbol {name}") from exc
        fn.restype = restype
        fn.argtypes = argtypes


def load_library(path: str | os.PathLike[str] | None = None) -> ctypes.CDLL:
    """Loads (once) and returns the library; raises LibraryLoadError with the reason."""
    global _lib
    with _lib_lock:
        if _lib is not None:
            return _lib
        lib_path = Path(path) if path is not None else default_library_path()
        if not lib_path.is_file():
            raise LibraryLoadError(
                f"Stratum native library not found at {lib_path} "
                "(build it with `make build`, or set STRATUM_LIBRARY)"
            )
        mode = ctypes.RTLD_LOCAL
        if sys.platform.startswith("linux"):
            mode = os.RTLD_LOCAL | os.RTLD_DEEPBIND
        try:
            lib = ctypes.CDLL(str(lib_path), mode=mode)
        except OSError as exc:
            raise LibraryLoadError(f"cannot load Stratum native library {lib_path}: {exc}") from exc
        _declare(lib)
        _lib = lib
        return lib


def library_available() -> bool:
    try:
        load_library()
    except StratumError:
        return False
    return True


def _last_error(lib: ctypes.CDLL) -> str:
    raw = lib.stratum_last_error()
    return raw.decode("utf-8", "replace") if raw else ""


def _check(lib: ctypes.CDLL, status: int, what: str) -> None:
    if status != OK:
        message = _last_error(lib) or f"{what} failed: {STATUS_NAMES.get(status, status)}"
        raise StratumError(int(status), message)


def version() -> str:
    lib = load_library()
    raw = lib.stratum_version()
    return raw.decode("utf-8", "replace") if raw else ""


def registry(kind: str) -> list[RegistryEntry]:
    """Entries of the 'sampler', 'filter', 'integrator' or 'hemisphere' registry, as
    (name, label, description)."""
    if kind not in REGISTRIES:
        raise ValueError(f"unknown registry {kind!r}; expected one of {sorted(REGISTRIES)}")
    lib = load_library()
    reg = REGISTRIES[kind]
    count = lib.stratum_registry_count(reg)
    if count < 0:
        raise StratumError(ERROR_INVALID_ARGUMENT, _last_error(lib) or f"unknown registry {kind}")
    entries: list[RegistryEntry] = []
    for i in range(count):
        name, label, desc = ctypes.c_char_p(), ctypes.c_char_p(), ctypes.c_char_p()
        status = lib.stratum_registry_entry(
            reg, i, ctypes.byref(name), ctypes.byref(label), ctypes.byref(desc)
        )
        _check(lib, status, "stratum_registry_entry")
        entries.append(
            RegistryEntry(
                (name.value or b"").decode(),
                (label.value or b"").decode(),
                (desc.value or b"").decode(),
            )
        )
    return entries


# ---- sampling without a scene ------------------------------------------------------------------

_UINT32_MAX = 0xFFFFFFFF


def _uint32(value: Any, what: str) -> int:
    """value as a C uint32_t, or ValueError naming it (ctypes would wrap negatives silently)."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise ValueError(f"{what} = {value!r} is not an integer")
    if not 0 <= int(value) <= _UINT32_MAX:
        raise ValueError(f"{what} = {value} is out of range [0, {_UINT32_MAX}]")
    return int(value)


def dimension_name(dimension: int) -> str:
    """Name of a sample dimension in the layout ("filter.x", "bounce1.bsdf.u", ...)."""
    lib = load_library()
    name = ctypes.c_char_p()
    _check(lib, lib.stratum_dimension_name(_uint32(dimension, "dimension"), ctypes.byref(name)),
           "stratum_dimension_name")
    return (name.value or b"").decode()


def camera_dimensions() -> int:
    """Dimensions before the first bounce block (filter, lens, time, ...)."""
    return int(load_library().stratum_camera_dimensions())


def bounce_dimension_stride() -> int:
    """Dimensions per bounce block; bounce k's block starts at camera_dimensions() + k * stride."""
    return int(load_library().stratum_bounce_dimension_stride())


def sampler_points(sampler: str, samples: int, seed: int, width: int, height: int,
                   pixel: tuple[int, int], dims: tuple[int, int], count: int) -> np.ndarray:
    """The first `count` samples of one pixel in two dimensions, as a (count, 2) float32 array:
    exactly what a render of width x height at `samples` spp with `seed` would read. When
    dims = (2k, 2k + 1) the sampler's 2D pair is used, as the integrators do. Indices beyond
    `samples` are allowed (every sampler is defined for any sample index)."""
    lib = load_library()
    px, py = pixel
    da, db = dims
    n = _uint32(count, "count")
    out = np.empty((n, 2), dtype=np.float32)
    status = lib.stratum_sampler_points(
        sampler.encode(), _uint32(samples, "samples"), _uint32(seed, "seed"),
        _uint32(width, "width"), _uint32(height, "height"), _uint32(px, "pixel x"),
        _uint32(py, "pixel y"), _uint32(da, "dimension"), _uint32(db, "dimension"), n,
        _float_ptr(out))
    _check(lib, status, "stratum_sampler_points")
    return out


def warp_hemisphere(distribution: str, uv: Any) -> tuple[np.ndarray, np.ndarray]:
    """Maps points of [0,1)^2 ((n, 2) array-like) through a hemisphere distribution (registry
    'hemisphere'): returns unit vectors (n, 3) with z along the normal, and their solid-angle
    densities (n,)."""
    lib = load_library()
    points = np.ascontiguousarray(np.asarray(uv, dtype=np.float32))
    if points.ndim != 2 or points.shape[1] != 2:
        raise ValueError(f"uv: expected an (n, 2) array, got shape {points.shape}")
    n = _uint32(points.shape[0], "count")
    xyz = np.empty((n, 3), dtype=np.float32)
    pdf = np.empty(n, dtype=np.float32)
    status = lib.stratum_warp_hemisphere(distribution.encode(), _float_ptr(points), n,
                                         _float_ptr(xyz), _float_ptr(pdf))
    _check(lib, status, "stratum_warp_hemisphere")
    return xyz, pdf


BLUENOISE_TEXTURE_SIZE = 128


def bluenoise_texture() -> np.ndarray:
    """The `bluenoise` sampler's void-and-cluster texture as a (128, 128) float32 array indexed
    [y, x]: (rank + 0.5)/16384 per texel, the values the sampler reads."""
    lib = load_library()
    n = BLUENOISE_TEXTURE_SIZE
    out = np.empty((n, n), dtype=np.float32)
    _check(lib, lib.stratum_bluenoise_texture(_float_ptr(out), n * n), "stratum_bluenoise_texture")
    return out


# ---- helpers ---------------------------------------------------------------------------------


def _float_ptr(arr: np.ndarray) -> Any:
    return arr.ctypes.data_as(ctypes.POINTER(ctypes.c_float))


def _uint_ptr(arr: np.ndarray) -> Any:
    return arr.ctypes.data_as(ctypes.POINTER(ctypes.c_uint32))


def _fields(value: Any) -> dict[str, Any]:
    if is_dataclass(value) and not isinstance(value, type):
        return asdict(value)
    if isinstance(value, Mapping):
        return dict(value)
    raise TypeError(f"expected a dict or dataclass, got {type(value).__name__}")


def _set_struct(struct: ctypes.Structure, values: Mapping[str, Any], what: str) -> None:
    known = {name for name, _ in struct._fields_}
    for key, value in values.items():
        if key not in known:
            raise ValueError(f"{what}: unknown field {key!r} (known: {sorted(known)})")
        current = getattr(struct, key)
        if isinstance(current, ctypes.Array):
            seq = np.asarray(value, dtype=np.float64).ravel()
            if seq.size != len(current):
                raise ValueError(f"{what}.{key}: expected {len(current)} values, got {seq.size}")
            for i, v in enumerate(seq):
                current[i] = float(v)
        else:
            setattr(struct, key, value)


def _matrix16(matrix: Any, what: str) -> np.ndarray:
    m = np.ascontiguousarray(np.asarray(matrix, dtype=np.float32).reshape(-1))
    if m.size != 16:
        raise ValueError(f"{what}: expected a 4x4 matrix (16 floats), got {m.size} values")
    return m


class _Handle:
    """Owns one native handle and frees it exactly once (close / context manager / __del__)."""

    _destroy_name = ""

    def __init__(self) -> None:
        self._lib = load_library()
        self._ptr = ctypes.c_void_p()

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._ptr:
            raise StratumError(ERROR_INVALID_STATE, f"{type(self).__name__} is closed")
        return self._ptr

    def close(self) -> None:
        ptr = getattr(self, "_ptr", None)
        if ptr:
            getattr(self._lib, self._destroy_name)(ptr)
            self._ptr = ctypes.c_void_p()

    @property
    def closed(self) -> bool:
        return not self._ptr

    def __enter__(self):  # noqa: ANN204 - returns the concrete subclass
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # noqa: BLE001 - never raise from a finalizer
            pass


# ---- Scene -----------------------------------------------------------------------------------


class Scene(_Handle):
    """A native scene under construction: materials, meshes, instances, lights, camera."""

    _destroy_name = "stratum_scene_destroy"

    def __init__(self, _adopt: ctypes.c_void_p | None = None) -> None:
        super().__init__()
        if _adopt is not None:
            self._ptr = _adopt
        else:
            _check(self._lib, self._lib.stratum_scene_create(ctypes.byref(self._ptr)),
                   "stratum_scene_create")

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Scene:
        lib = load_library()
        ptr = ctypes.c_void_p()
        _check(lib, lib.stratum_scene_load(os.fsencode(path), ctypes.byref(ptr)),
               "stratum_scene_load")
        return cls(_adopt=ptr)

    def save(self, path: str | os.PathLike[str]) -> None:
        _check(self._lib, self._lib.stratum_scene_save(self.handle, os.fsencode(path)),
               "stratum_scene_save")

    def measure_ray_throughput(self, width: int, height: int, samples: int, max_bounces: int,
                               threads: int = 0) -> tuple[float, float]:
        """Embree alone on the path tracer's ray mix: (rays traced, seconds), the ceiling
        `make bench` compares Stratum's rays/s with."""
        rays, seconds = ctypes.c_double(), ctypes.c_double()
        _check(self._lib, self._lib.stratum_scene_measure_ray_throughput(
            self.handle, _uint32(width, "width"), _uint32(height, "height"),
            _uint32(samples, "samples"), _uint32(max_bounces, "max_bounces"),
            _uint32(threads, "threads"), ctypes.byref(rays), ctypes.byref(seconds)),
            "stratum_scene_measure_ray_throughput")
        return rays.value, seconds.value

    def add_material(self, material: Mapping[str, Any] | Material) -> int:
        desc = _MaterialDesc()
        defaults = asdict(Material())
        defaults.update(_fields(material))
        _set_struct(desc, defaults, "material")
        out = ctypes.c_uint32()
        _check(self._lib,
               self._lib.stratum_scene_add_material(self.handle, ctypes.byref(desc),
                                                    ctypes.byref(out)),
               "stratum_scene_add_material")
        return int(out.value)

    def add_closure_material(
            self, closures: Sequence[tuple[Sequence[float], Mapping[str, Any] | Material]]) -> int:
        """A material made of weighted closures [(weight RGB, material), ...]."""
        n = len(closures)
        if n == 0:
            raise ValueError("closure material: at least one closure is needed")
        descs = (_ClosureDesc * n)()
        for i, (weight, material) in enumerate(closures):
            values = asdict(Material())
            values.update(_fields(material))
            _set_struct(descs[i].closure, values, f"closure {i}")
            _set_struct(descs[i], {"weight": weight}, f"closure {i}")
        out = ctypes.c_uint32()
        fn = self._lib.stratum_scene_add_closure_material
        _check(self._lib, fn(self.handle, descs, n, ctypes.byref(out)),
               "stratum_scene_add_closure_material")
        return int(out.value)

    def add_texture(self, texture: Texture) -> int:
        desc = _TextureDesc()
        keep: list[Any] = []  # buffers referenced by desc, alive until the (copying) call returns
        if texture.path is not None:
            desc.path = os.fsencode(texture.path)
        if texture.file_data is not None:
            data = ctypes.create_string_buffer(bytes(texture.file_data), len(texture.file_data))
            keep.append(data)
            desc.file_data = ctypes.cast(data, ctypes.c_void_p)
            desc.file_size = len(texture.file_data)
        if texture.file_name is not None:
            desc.file_name = texture.file_name.encode()
        if texture.pixels is not None:
            px = np.ascontiguousarray(texture.pixels, dtype=np.float32)
            if px.ndim == 2:
                px = px[:, :, None]
            if px.ndim != 3:
                raise ValueError(f"texture pixels: expected (height, width, channels), got "
                                 f"{px.shape}")
            keep.append(px)
            desc.pixels = _float_ptr(px)
            desc.height, desc.width, desc.channels = (int(v) for v in px.shape)
        desc.color_space = texture.color_space.encode()
        if texture.ocio_config is not None:
            desc.ocio_config = os.fsencode(texture.ocio_config)
        desc.interpolation = int(texture.interpolation)
        desc.extension = int(texture.extension)
        out = ctypes.c_uint32()
        fn = self._lib.stratum_scene_add_texture
        status = fn(self.handle, ctypes.byref(desc), ctypes.byref(out))
        del keep
        _check(self._lib, status, "stratum_scene_add_texture")
        return int(out.value)

    def texture_info(self, texture_id: int) -> TextureInfo:
        out = _TextureInfo()
        fn = self._lib.stratum_scene_texture_info
        _check(self._lib, fn(self.handle, int(texture_id), ctypes.byref(out)),
               "stratum_scene_texture_info")
        return TextureInfo(int(out.width), int(out.height), int(out.replaced_texels))

    def bind_texture(self, binding: TextureBinding) -> None:
        desc = _TextureBinding()
        _set_struct(desc, _fields(binding), "texture binding")
        fn = self._lib.stratum_scene_bind_texture
        _check(self._lib, fn(self.handle, ctypes.byref(desc)), "stratum_scene_bind_texture")

    def add_mesh(
        self,
        positions: np.ndarray,
        triangles: np.ndarray,
        material_ids: np.ndarray,
        corner_normals: np.ndarray | None = None,
        corner_uvs: np.ndarray | None = None,
        vertex_normals: np.ndarray | None = None,
        corner_tangents: np.ndarray | None = None,
    ) -> int:
        """positions (N,3) float32, triangles (T,3) uint32, material_ids (T,) uint32,
        corner_normals (T,3,3) float32, corner_uvs (T,3,2) float32, vertex_normals (N,3)
        float32 (at most one kind of normals), corner_tangents (T,3,4) float32 (MikkTSpace
        tangent and bitangent sign per corner). Arrays already of the right dtype and contiguous
        are passed without a copy."""
        pos = np.ascontiguousarray(positions, dtype=np.float32)
        tri = np.ascontiguousarray(triangles, dtype=np.uint32)
        mat = np.ascontiguousarray(material_ids, dtype=np.uint32)
        if pos.size % 3:
            raise ValueError(f"positions: size {pos.size} is not a multiple of 3")
        if tri.size % 3:
            raise ValueError(f"triangles: size {tri.size} is not a multiple of 3")
        n_vert, n_tri = pos.size // 3, tri.size // 3
        if mat.size != n_tri:
            raise ValueError(f"material_ids: {mat.size} values for {n_tri} triangles")
        desc = _MeshDesc()
        desc.positions = _float_ptr(pos)
        desc.vertex_count = n_vert
        desc.triangles = _uint_ptr(tri)
        desc.triangle_count = n_tri
        desc.material_ids = _uint_ptr(mat)
        nrm = uvs = vnrm = tangents = None
        if corner_tangents is not None:
            tangents = np.ascontiguousarray(corner_tangents, dtype=np.float32)
            if tangents.size != n_tri * 12:
                raise ValueError(f"corner_tangents: {tangents.size} floats for {n_tri} triangles "
                                 f"(expected {n_tri * 12})")
            desc.corner_tangents = _float_ptr(tangents)
        if vertex_normals is not None:
            vnrm = np.ascontiguousarray(vertex_normals, dtype=np.float32)
            if vnrm.size != n_vert * 3:
                raise ValueError(f"vertex_normals: {vnrm.size} floats for {n_vert} vertices "
                                 f"(expected {n_vert * 3})")
            desc.vertex_normals = _float_ptr(vnrm)
        if corner_normals is not None:
            nrm = np.ascontiguousarray(corner_normals, dtype=np.float32)
            if nrm.size != n_tri * 9:
                raise ValueError(f"corner_normals: {nrm.size} floats for {n_tri} triangles "
                                 f"(expected {n_tri * 9})")
            desc.corner_normals = _float_ptr(nrm)
        if corner_uvs is not None:
            uvs = np.ascontiguousarray(corner_uvs, dtype=np.float32)
            if uvs.size != n_tri * 6:
                raise ValueError(f"corner_uvs: {uvs.size} floats for {n_tri} triangles "
                                 f"(expected {n_tri * 6})")
            desc.corner_uvs = _float_ptr(uvs)
        out = ctypes.c_uint32()
        status = self._lib.stratum_scene_add_mesh(self.handle, ctypes.byref(desc),
                                                  ctypes.byref(out))
        # keep the arrays alive until the (copying) call has returned
        del pos, tri, mat, nrm, uvs, vnrm, tangents
        _check(self._lib, status, "stratum_scene_add_mesh")
        return int(out.value)

    def add_instance(self, mesh_id: int, matrix: Any) -> None:
        m = _matrix16(matrix, "instance transform")
        _check(self._lib,
               self._lib.stratum_scene_add_instance(self.handle, int(mesh_id), _float_ptr(m)),
               "stratum_scene_add_instance")

    def add_instances(self, mesh_ids: np.ndarray, transforms: np.ndarray) -> None:
        """Static instances in bulk: mesh_ids (N,) and transforms (N, 4, 4) row-major. One C
        call per instance without per-instance array conversion (scenes place 10 000s). A
        rejected instance raises StratumError whose `index` is its row."""
        ids = np.ascontiguousarray(mesh_ids, dtype=np.uint32).reshape(-1)
        mats = np.ascontiguousarray(transforms, dtype=np.float32).reshape(-1, 16)
        if len(ids) != len(mats):
            raise ValueError(f"add_instances: {len(ids)} mesh ids for {len(mats)} transforms")
        fn = self._lib.stratum_scene_add_instance
        handle = self.handle
        base = mats.ctypes.data
        pointer = ctypes.POINTER(ctypes.c_float)
        for i, mesh_id in enumerate(ids.tolist()):
            try:
                _check(self._lib, fn(handle, mesh_id, ctypes.cast(base + 64 * i, pointer)),
                       "stratum_scene_add_instance")
            except StratumError as exc:
                raise StratumError(exc.status, exc.message, index=i) from None

    def add_instance_ex(self, instance: Instance) -> None:
        """An instance with motion (transform_end not None), ray visibility and holdout."""
        desc = _InstanceDesc()
        desc.mesh_id = _uint32(instance.mesh_id, "instance mesh_id")
        # memmove, not per-element assignment: scenes place tens of thousands of instances.
        start = _matrix16(instance.transform, "instance transform")
        ctypes.memmove(desc.transform, start.ctypes.data, 64)
        if instance.transform_end is not None:
            end = _matrix16(instance.transform_end, "instance transform_end")
            ctypes.memmove(desc.transform_end, end.ctypes.data, 64)
            desc.motion = 1
        desc.visibility = _uint32(instance.visibility, "instance visibility")
        desc.holdout = 1 if instance.holdout else 0
        fn = self._lib.stratum_scene_add_instance_ex
        _check(self._lib, fn(self.handle, ctypes.byref(desc)), "stratum_scene_add_instance_ex")

    def add_light(self, light: Mapping[str, Any] | Light | None = None, **fields: Any) -> None:
        values = asdict(Light())
        if light is not None:
            values.update(_fields(light))
        values.update(fields)
        values["transform"] = _matrix16(values["transform"], "light transform")
        desc = _LightDesc()
        _set_struct(desc, values, "light")
        _check(self._lib, self._lib.stratum_scene_add_light(self.handle, ctypes.byref(desc)),
               "stratum_scene_add_light")

    def set_camera(self, camera: Mapping[str, Any] | Camera | None = None,
                   **fields: Any) -> None:
        values = asdict(Camera())
        if camera is not None:
            values.update(_fields(camera))
        values.update(fields)
        fit = values["sensor_fit"]
        if isinstance(fit, str):
            if fit not in SENSOR_FITS:
                raise ValueError(f"camera: unknown sensor_fit {fit!r}")
            values["sensor_fit"] = SENSOR_FITS[fit]
        kind = values["type"]
        if isinstance(kind, str):
            if kind not in CAMERA_TYPES:
                raise ValueError(f"camera: unknown type {kind!r} (known: {sorted(CAMERA_TYPES)})")
            values["type"] = CAMERA_TYPES[kind]
        values["transform"] = _matrix16(values["transform"], "camera transform")
        desc = _CameraDesc()
        _set_struct(desc, values, "camera")
        _check(self._lib, self._lib.stratum_scene_set_camera(self.handle, ctypes.byref(desc)),
               "stratum_scene_set_camera")

    def set_background(self, rgb: Sequence[float] | np.ndarray) -> None:
        c = np.ascontiguousarray(np.asarray(rgb, dtype=np.float32).reshape(-1)[:3])
        if c.size != 3:
            raise ValueError("background: expected 3 floats (linear RGB)")
        _check(self._lib, self._lib.stratum_scene_set_background(self.handle, _float_ptr(c)),
               "stratum_scene_set_background")

    def set_environment(self, rgb: np.ndarray, strength: float = 1.0,
                        rotation: Sequence[float] | np.ndarray | None = None) -> None:
        """Equirectangular environment image: rgb is (height, width, 3) linear RGB, rows top
        (+Z) to bottom, as stratum_scene_set_environment documents; rotation is the 3x3
        world-to-environment rotation (None = identity)."""
        img = np.ascontiguousarray(np.asarray(rgb, dtype=np.float32))
        if img.ndim != 3 or img.shape[2] != 3:
            raise ValueError(f"environment: expected a (height, width, 3) array, got {img.shape}")
        rot = None
        if rotation is not None:
            rot = np.ascontiguousarray(np.asarray(rotation, dtype=np.float32).reshape(-1))
            if rot.size != 9:
                raise ValueError("environment rotation: expected 9 floats (3x3 row-major)")
        _check(self._lib, self._lib.stratum_scene_set_environment(
            self.handle, _float_ptr(img), img.shape[1], img.shape[0], float(strength),
            None if rot is None else _float_ptr(rot)), "stratum_scene_set_environment")


# ---- Renderer --------------------------------------------------------------------------------


class Renderer(_Handle):
    """Renders a copy of a Scene on native worker threads."""

    _destroy_name = "stratum_renderer_destroy"

    def __init__(self, scene: Scene, **settings: int | float | str) -> None:
        super().__init__()
        _check(self._lib,
               self._lib.stratum_renderer_create(scene.handle, ctypes.byref(self._ptr)),
               "stratum_renderer_create")
        self._width = 0
        self._height = 0
        self._crop_width = 0  # a border render reads and writes only its region
        self._crop_height = 0
        self._started = False
        for name, value in settings.items():
            self.set(name, value)

    def close(self) -> None:
        # A render still running must stop before its handle is freed.
        ptr = getattr(self, "_ptr", None)
        if ptr and getattr(self, "_started", False):
            done = ctypes.c_int32(0)
            self._lib.stratum_renderer_cancel(ptr)
            self._lib.stratum_renderer_wait(ptr, 60000, ctypes.byref(done))
        super().close()

    def set(self, name: str, value: int | float | str) -> None:
        """Sets a named setting; the C function is chosen by the Python type of value."""
        key = name.encode()
        if isinstance(value, bool | int | np.integer):
            status = self._lib.stratum_renderer_set_int(self.handle, key, int(value))
            if name in ("width", "height", "crop_width", "crop_height"):
                setattr(self, f"_{name}", int(value))
        elif isinstance(value, float | np.floating):
            status = self._lib.stratum_renderer_set_float(self.handle, key, float(value))
        elif isinstance(value, str):
            status = self._lib.stratum_renderer_set_string(self.handle, key, value.encode())
        else:
            raise TypeError(f"setting {name!r}: unsupported type {type(value).__name__}")
        _check(self._lib, status, f"setting {name}")

    @property
    def width(self) -> int:
        return self._width

    @property
    def height(self) -> int:
        return self._height

    @property
    def image_size(self) -> tuple[int, int]:
        """(width, height) of the image read_pixels returns: the border region if one is set."""
        if self._crop_width > 0 and self._crop_height > 0:
            return self._crop_width, self._crop_height
        return self._width, self._height

    def start(self) -> None:
        _check(self._lib, self._lib.stratum_renderer_start(self.handle), "stratum_renderer_start")
        self._started = True

    def notices(self) -> list[str]:
        """What the render cannot show and why, one sentence each; [] when nothing: what the
        chosen estimator cannot render in this scene (e.g. BSDF sampling alone never finds a
        point light; set by start()), placements skipped by the scene build (added when the
        build ends) and samples or rays dropped as not finite (added when the render ends)."""
        out = ctypes.c_char_p()
        _check(self._lib, self._lib.stratum_renderer_notices(self.handle, ctypes.byref(out)),
               "stratum_renderer_notices")
        text = out.value.decode("utf-8", "replace") if out.value else ""
        return [line for line in text.split("\n") if line]

    def cancel(self) -> None:
        _check(self._lib, self._lib.stratum_renderer_cancel(self.handle),
               "stratum_renderer_cancel")

    def wait(self, timeout_ms: int) -> bool:
        """Waits up to timeout_ms; True when the render has ended."""
        done = ctypes.c_int32(0)
        _check(self._lib,
               self._lib.stratum_renderer_wait(self.handle, int(timeout_ms), ctypes.byref(done)),
               "stratum_renderer_wait")
        return bool(done.value)

    def progress(self) -> Progress:
        p = _Progress()
        _check(self._lib, self._lib.stratum_renderer_progress(self.handle, ctypes.byref(p)),
               "stratum_renderer_progress")
        return Progress(
            done=bool(p.done),
            cancelled=bool(p.cancelled),
            samples_done=int(p.samples_done),
            samples_total=int(p.samples_total),
            update_serial=int(p.update_serial),
            rays=float(p.rays),
            build_seconds=float(p.build_seconds),
            render_seconds=float(p.render_seconds),
            fraction_done=float(p.fraction_done),
        )

    def read_pixels(self, out: np.ndarray | None = None) -> np.ndarray:
        """Copies the current image (linear RGBA, rows bottom to top) into `out` (a contiguous
        float32 array of width*height*4 values, any shape) with one native copy."""
        if out is None:
            width, height = self.image_size
            out = np.empty(width * height * 4, dtype=np.float32)
        if out.dtype != np.float32 or not out.flags.c_contiguous or not out.flags.writeable:
            raise ValueError("read_pixels: out must be a writeable C-contiguous float32 array")
        _check(self._lib,
               self._lib.stratum_renderer_read_pixels(self.handle, _float_ptr(out), out.size),
               "stratum_renderer_read_pixels")
        return out

    def write_image(self, path: str | os.PathLike[str]) -> None:
        _check(self._lib,
               self._lib.stratum_renderer_write_image(self.handle, os.fsencode(path)),
               "stratum_renderer_write_image")
