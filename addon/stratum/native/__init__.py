"""ctypes binding of the Stratum C ABI (native/include/stratum/stratum.h).

This package is the ONLY code that knows the C ABI (and the only one that imports ctypes).
Everything above it (export, engine, cli) talks to `Scene`, `Renderer`, `settings()`,
`registry()`, `light_type()`, `closure_model()` and `node_type()`. Every native call goes through
library._check, so a non-OK status becomes a `StratumError` carrying stratum_last_error()'s
text; nothing here can abort the host process on bad input, because the library validates every
value.

Its modules, by job: abi (status codes, enums, C structs and function signatures mirroring
the header), library (loading libstratum.so, errors, version), settings (the render settings
with their choices, the registries among them, and the passes, as the library lists them),
models (light types, closure models and shader node types by name, as the library lists them),
marshalling (Python values as C arguments), descriptions (the dataclasses a Scene is made
of), scene (`Scene`), renderer (`Renderer`, `Progress`), inspection (sampler points, hemisphere
warps, the blue-noise texture and the dimension layout, without a scene), geometry (vertex
normals, without a scene), oidn (Intel Open
Image Denoise, a library of its own: `denoise`, `load_denoiser`, `DenoiserUnavailable`). The
public API is re-exported here, so `from stratum import native; native.Scene` is all a caller
needs. Names with a leading underscore (_check, _Handle, the ctypes structs, ...) are shared
between these modules only.
"""

from __future__ import annotations

from .abi import (
    ATTRIBUTE_SLOTS,
    BUMP_SHADOWING_CHIANG,
    BUMP_SHADOWING_CHIANG_UNSMOOTHED,
    BUMP_SHADOWING_CONTY,
    BUMP_SHADOWING_CONTY_UNSMOOTHED,
    BUMP_SHADOWING_NONE,
    CAMERA_EQUIRECTANGULAR,
    CAMERA_ORTHOGRAPHIC,
    CAMERA_PERSPECTIVE,
    CAMERA_TYPES,
    ERROR_INTERNAL,
    ERROR_INVALID_ARGUMENT,
    ERROR_INVALID_STATE,
    ERROR_IO,
    ERROR_OUT_OF_MEMORY,
    MAX_LIGHT_GROUPS,
    MICROFACET_GGX,
    MICROFACET_MULTISCATTER_GGX,
    OK,
    PARAM_BASE_COLOR,
    PARAM_EMISSION,
    PARAM_METALLIC,
    PARAM_NORMAL,
    PARAM_ROUGHNESS,
    PARAM_SPECULAR,
    PARAM_TRANSMISSION,
    PARAM_WEIGHT,
    PROGRAM_PARAMS,
    SENSOR_FIT_AUTO,
    SENSOR_FIT_HORIZONTAL,
    SENSOR_FIT_VERTICAL,
    SENSOR_FITS,
    SHADER_INPUT_REGISTERS,
    SHADER_INPUTS,
    STATUS_NAMES,
    TEXTURE_CLIP,
    TEXTURE_CLOSEST,
    TEXTURE_EXTEND,
    TEXTURE_LINEAR,
    TEXTURE_MIRROR,
    TEXTURE_REPEAT,
    VISIBLE_ALL,
    VISIBLE_CAMERA,
    VISIBLE_DIFFUSE,
    VISIBLE_GLOSSY,
    VISIBLE_SHADOW,
    VISIBLE_SHADOW_CATCHER,
    VISIBLE_TRANSMISSION,
    SettingKind,
)
from .descriptions import (
    Camera,
    Instance,
    Light,
    Material,
    Texture,
    TextureBinding,
    TextureInfo,
)
from .geometry import vertex_normals
from .inspection import (
    BLUENOISE_TEXTURE_SIZE,
    bluenoise_texture,
    bounce_dimension_stride,
    camera_dimensions,
    dimension_name,
    sampler_points,
    warp_hemisphere,
)
from .library import (
    LibraryLoadError,
    LibraryStatus,
    StratumError,
    default_library_path,
    library_available,
    library_status,
    load_library,
    version,
)
from .models import closure_model, closure_models, light_type, light_types, node_type, node_types
from .oidn import DenoiserUnavailable, denoise
from .oidn import load_library as load_denoiser
from .programs import ProgramBinding, ShaderNode, ShaderProgram
from .renderer import Progress, Renderer
from .scene import Scene
from .settings import (
    REGISTRY_SETTINGS,
    Pass,
    RegistryEntry,
    Setting,
    passes,
    registry,
    setting,
    settings,
)

__all__ = [
    "ATTRIBUTE_SLOTS",
    "BLUENOISE_TEXTURE_SIZE", "BUMP_SHADOWING_CHIANG", "BUMP_SHADOWING_CHIANG_UNSMOOTHED",
    "BUMP_SHADOWING_CONTY", "BUMP_SHADOWING_CONTY_UNSMOOTHED", "BUMP_SHADOWING_NONE",
    "CAMERA_EQUIRECTANGULAR", "CAMERA_ORTHOGRAPHIC", "CAMERA_PERSPECTIVE", "CAMERA_TYPES",
    "Camera", "ERROR_INTERNAL", "ERROR_INVALID_ARGUMENT", "ERROR_INVALID_STATE", "ERROR_IO",
    "DenoiserUnavailable", "ERROR_OUT_OF_MEMORY", "Instance", "LibraryLoadError", "LibraryStatus",
    "Light",
    "MICROFACET_GGX", "MICROFACET_MULTISCATTER_GGX", "Material", "OK",
    "PARAM_BASE_COLOR", "PARAM_EMISSION", "PARAM_METALLIC", "PARAM_NORMAL", "PARAM_ROUGHNESS",
    "PARAM_SPECULAR", "PARAM_TRANSMISSION", "PARAM_WEIGHT", "PROGRAM_PARAMS", "Pass",
    "ProgramBinding", "Progress", "SHADER_INPUTS", "SHADER_INPUT_REGISTERS", "ShaderNode",
    "ShaderProgram",
    "REGISTRY_SETTINGS", "RegistryEntry", "Renderer", "SENSOR_FITS", "SENSOR_FIT_AUTO",
    "SENSOR_FIT_HORIZONTAL", "SENSOR_FIT_VERTICAL", "STATUS_NAMES", "Scene", "Setting",
    "SettingKind", "StratumError", "TEXTURE_CLIP", "TEXTURE_CLOSEST", "TEXTURE_EXTEND",
    "TEXTURE_LINEAR", "TEXTURE_MIRROR", "TEXTURE_REPEAT",
    "Texture", "TextureBinding", "TextureInfo", "MAX_LIGHT_GROUPS", "VISIBLE_ALL", "VISIBLE_CAMERA",
    "VISIBLE_DIFFUSE", "VISIBLE_GLOSSY", "VISIBLE_SHADOW", "VISIBLE_SHADOW_CATCHER",
    "VISIBLE_TRANSMISSION",
    "bluenoise_texture", "bounce_dimension_stride", "camera_dimensions", "closure_model",
    "closure_models", "denoise", "light_type", "light_types", "load_denoiser", "node_type",
    "node_types",
    "default_library_path", "dimension_name", "library_available", "library_status",
    "load_library", "passes",
    "registry", "sampler_points", "setting", "settings", "version", "vertex_normals",
    "warp_hemisphere",
]
