"""What the C ABI (native/include/stratum/stratum.h) declares, mirrored for ctypes: status
codes, enums, the C structs, and the restype/argtypes of every function. Keep in step with the
header; tests/python/test_native.py checks struct layouts.
"""

from __future__ import annotations

import ctypes
import enum
from typing import Any

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

# StratumModelKind: the listings of stratum_model_entry (light types, closure models, shader node
# types), which name every StratumLightType, StratumMaterialModel and node type value (models.py).
MODEL_LIGHT = 0
MODEL_CLOSURE = 1
MODEL_SHADER_NODE = 2


# StratumLinkTarget: what stratum_scene_set_light_linking sets.
LINK_INSTANCES = 0
LINK_LIGHTS = 1
MAX_LINK_SET = 63

# StratumSettingKind: how a render setting is set (stratum_renderer_set_int / _float / _string).
class SettingKind(enum.IntEnum):
    INT = 0
    FLOAT = 1
    CHOICE = 2  # one name of its choices
    LIST = 3  # comma-separated names of its choices, "" = none


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

# StratumProgramParam: closure parameters a shader program drives.
PROGRAM_PARAMS = {
    "base_color": 0, "roughness": 1, "metallic": 2, "normal": 3, "emission": 4, "weight": 5,
    "transmission": 6, "specular": 7, "ior": 8, "coat": 9, "coat_roughness": 10, "coat_tint": 11,
}
# StratumShaderInput: the registers the renderer writes at each shading point, and their widths.
SHADER_INPUTS = {
    "position": (0, 3), "normal": (3, 3), "true_normal": (6, 3), "incoming": (9, 3), "uv": (12, 3),
    "generated": (15, 3), "object": (18, 3), "camera": (21, 3), "window": (24, 3),
    "object_location": (27, 3), "backfacing": (30, 1), "object_random": (31, 1),
    "ray_length": (32, 1), "object_index": (33, 1), "material_index": (34, 1),
    "object_color": (35, 3), "object_alpha": (38, 1), "tangent": (39, 3), "parametric": (42, 3),
    "object_normal": (45, 3), "dpdx": (48, 3), "dpdy": (51, 3), "dgenerated_dx": (54, 3),
    "dgenerated_dy": (57, 3), "dobject_dx": (60, 3), "dobject_dy": (63, 3), "duv_dx": (66, 3),
    "duv_dy": (69, 3), "reflection": (72, 3), "uv_tangent": (75, 3), "pixel_footprint": (78, 1),
    # mesh attribute slot k: colour (3) at 80 + 5k, alpha at + 3, Fac at + 4
    "attribute0": (80, 5), "attribute1": (85, 5), "attribute2": (90, 5), "attribute3": (95, 5),
    "triangle": (100, 9), "mikktspace_tangent": (109, 3), "normal_transform": (112, 9),
    # Cycles' Light Path node: the ray kinds (0 or 1) and the depths
    "is_camera_ray": (121, 1), "is_shadow_ray": (122, 1), "is_diffuse_ray": (123, 1),
    "is_glossy_ray": (124, 1), "is_singular_ray": (125, 1), "is_reflection_ray": (126, 1),
    "is_transmission_ray": (127, 1), "is_volume_scatter_ray": (128, 1), "ray_depth": (129, 1),
    "diffuse_depth": (130, 1), "glossy_depth": (131, 1), "transparent_depth": (132, 1),
    "transmission_depth": (133, 1), "portal_depth": (134, 1),
}
SHADER_INPUT_REGISTERS = 144
# stratum_scene_set_light_program's program id that removes a lamp's program.
NO_PROGRAM = 0xFFFFFFFF
ATTRIBUTE_SLOTS = 4

VISIBLE_CAMERA = 1
VISIBLE_DIFFUSE = 2
VISIBLE_GLOSSY = 4
VISIBLE_TRANSMISSION = 8
VISIBLE_SHADOW = 16
VISIBLE_ALL = 31
# Not a ray kind: object.is_shadow_catcher (an instance is a catcher; a light lights catchers).
VISIBLE_SHADOW_CATCHER = 32
# STRATUM_MAX_LIGHT_GROUPS: light groups are numbered 1..this (0 = none).
MAX_LIGHT_GROUPS = 64

MICROFACET_GGX = 0
MICROFACET_MULTISCATTER_GGX = 1

# StratumBumpShadowing: Cycles' term for closures whose normal is perturbed.
BUMP_SHADOWING_NONE = 0
BUMP_SHADOWING_CHIANG = 1  # Cycles 2.90-4.4
BUMP_SHADOWING_CHIANG_UNSMOOTHED = 2  # Cycles 4.2-4.4, Bump Map Correction off
BUMP_SHADOWING_CONTY = 3  # Cycles 4.5+
BUMP_SHADOWING_CONTY_UNSMOOTHED = 4  # Cycles 4.5+, Bump Map Correction off

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
        ("pass_index", ctypes.c_uint32),
        ("lightgroup", ctypes.c_uint32),
    ]


class _ShaderNode(ctypes.Structure):
    _fields_ = [
        ("type", ctypes.c_int32),
        ("modes", ctypes.c_int32 * 6),
        ("inputs", ctypes.c_uint32 * 12),
        ("outputs", ctypes.c_uint32 * 6),
        ("data_offset", ctypes.c_uint32),
        ("data_count", ctypes.c_uint32),
    ]


class _ShaderProgramDesc(ctypes.Structure):
    _fields_ = [
        ("nodes", ctypes.POINTER(_ShaderNode)),
        ("node_count", ctypes.c_uint32),
        ("registers", ctypes.POINTER(ctypes.c_float)),
        ("register_count", ctypes.c_uint32),
        ("data", ctypes.POINTER(ctypes.c_float)),
        ("data_count", ctypes.c_uint32),
    ]


class _ProgramBinding(ctypes.Structure):
    _fields_ = [
        ("material_id", ctypes.c_uint32),
        ("closure_index", ctypes.c_uint32),
        ("param", ctypes.c_int32),
        ("program_id", ctypes.c_uint32),
        ("register_index", ctypes.c_uint32),
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
        ("lightgroup", ctypes.c_uint32),
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


class _SettingInfo(ctypes.Structure):
    _fields_ = [
        ("name", ctypes.c_char_p),
        ("label", ctypes.c_char_p),
        ("description", ctypes.c_char_p),
        ("kind", ctypes.c_int32),
        ("minimum", ctypes.c_double),
        ("maximum", ctypes.c_double),
        ("open_minimum", ctypes.c_int32),
        ("unit", ctypes.c_char_p),
        ("default_value", ctypes.c_char_p),
        ("choice_count", ctypes.c_int32),
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
        ("samples_in_progress", ctypes.c_int32),
        ("samples_average", ctypes.c_double),
    ]


# ---- functions -------------------------------------------------------------------------------


def function_signatures() -> dict[str, tuple[Any, list[Any]]]:
    """restype and argtypes of every stratum_* function, by name."""
    c_int32, c_uint32, c_int64 = ctypes.c_int32, ctypes.c_uint32, ctypes.c_int64
    p_char = ctypes.c_char_p
    p_void = ctypes.c_void_p
    pp_void = ctypes.POINTER(ctypes.c_void_p)
    pp_char = ctypes.POINTER(ctypes.c_char_p)
    p_u32 = ctypes.POINTER(ctypes.c_uint32)
    p_i32 = ctypes.POINTER(ctypes.c_int32)
    p_float = ctypes.POINTER(ctypes.c_float)
    p_u8 = ctypes.POINTER(ctypes.c_uint8)
    p_u64 = ctypes.POINTER(ctypes.c_uint64)
    return {
        "stratum_last_error": (p_char, []),
        "stratum_version": (p_char, []),
        "stratum_model_count": (c_int32, [c_int32]),
        "stratum_model_entry": (c_int32, [c_int32, c_int32, pp_char, ctypes.POINTER(c_int32)]),
        "stratum_dimension_name": (c_int32, [c_uint32, pp_char]),
        "stratum_camera_dimensions": (c_uint32, []),
        "stratum_bounce_dimension_stride": (c_uint32, []),
        "stratum_sampler_points": (c_int32, [p_char, c_uint32, c_uint32, c_uint32, c_uint32,
                                             c_uint32, c_uint32, c_uint32, c_uint32, c_uint32,
                                             p_float]),
        "stratum_warp_hemisphere": (c_int32, [p_char, p_float, c_uint32, p_float, p_float]),
        "stratum_bluenoise_texture": (c_int32, [p_float, c_uint32]),
        "stratum_vertex_normals": (c_int32, [c_uint32, p_float, c_uint32, p_u32, p_u32, p_float,
                                             c_uint32, p_u32, c_uint32, p_float]),
        "stratum_scene_create": (c_int32, [pp_void]),
        "stratum_scene_destroy": (None, [p_void]),
        "stratum_scene_add_material": (c_int32, [p_void, ctypes.POINTER(_MaterialDesc), p_u32]),
        "stratum_scene_add_mesh": (c_int32, [p_void, ctypes.POINTER(_MeshDesc), p_u32]),
        "stratum_scene_add_instance": (c_int32, [p_void, c_uint32, p_float]),
        "stratum_scene_add_instances": (c_int32, [p_void, c_uint32, p_u32, p_float, p_u32]),
        "stratum_scene_add_light": (c_int32, [p_void, ctypes.POINTER(_LightDesc)]),
        "stratum_scene_set_camera": (c_int32, [p_void, ctypes.POINTER(_CameraDesc)]),
        "stratum_scene_set_background": (c_int32, [p_void, p_float]),
        "stratum_scene_set_world_lightgroup": (c_int32, [p_void, c_uint32]),
        "stratum_scene_set_environment": (c_int32, [p_void, p_float, c_uint32, c_uint32,
                                                    ctypes.c_float, p_float]),
        # live edits
        "stratum_scene_set_instance": (c_int32, [p_void, c_uint32,
                                                 ctypes.POINTER(_InstanceDesc)]),
        "stratum_scene_set_material": (c_int32, [p_void, c_uint32,
                                                 ctypes.POINTER(_MaterialDesc)]),
        "stratum_scene_set_closure_material": (c_int32, [p_void, c_uint32,
                                                         ctypes.POINTER(_ClosureDesc), c_uint32]),
        "stratum_scene_set_material_pass_index": (c_int32, [p_void, c_uint32, c_uint32]),
        "stratum_scene_set_light": (c_int32, [p_void, c_uint32, ctypes.POINTER(_LightDesc)]),
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
        "stratum_progress_counter_count": (c_int32, []),
        "stratum_renderer_progress_counter": (c_int32, [p_void, c_int32, pp_char,
                                                        ctypes.POINTER(ctypes.c_double)]),
        "stratum_renderer_read_radiosity_iterations": (c_int32, [p_void,
                                                                 ctypes.POINTER(ctypes.c_double),
                                                                 ctypes.c_size_t]),
        "stratum_renderer_read_pixels": (c_int32, [p_void, p_float, ctypes.c_size_t]),
        "stratum_renderer_write_image": (c_int32, [p_void, p_char]),
        "stratum_renderer_sums_size": (c_int32, [p_void, ctypes.POINTER(ctypes.c_size_t)]),
        "stratum_renderer_read_sums": (c_int32, [p_void, p_void, ctypes.c_size_t]),
        "stratum_renderer_add_sums": (c_int32, [p_void, p_void, ctypes.c_size_t]),
        "stratum_scene_add_closure_material": (c_int32, [p_void, ctypes.POINTER(_ClosureDesc),
                                                         c_uint32, p_u32]),
        "stratum_scene_add_texture": (c_int32, [p_void, ctypes.POINTER(_TextureDesc), p_u32]),
        "stratum_scene_texture_info": (c_int32, [p_void, ctypes.c_uint32,
                                                 ctypes.POINTER(_TextureInfo)]),
        "stratum_scene_bind_texture": (c_int32, [p_void, ctypes.POINTER(_TextureBinding)]),
        "stratum_scene_add_instance_ex": (c_int32, [p_void, ctypes.POINTER(_InstanceDesc)]),
        # shader node programs (stratum/shader_nodes.h)
        "stratum_scene_add_shader_program": (c_int32, [p_void, ctypes.POINTER(_ShaderProgramDesc),
                                                       p_u32]),
        "stratum_scene_set_shader_program": (c_int32, [p_void, c_uint32,
                                                       ctypes.POINTER(_ShaderProgramDesc)]),
        "stratum_scene_bind_program": (c_int32, [p_void, ctypes.POINTER(_ProgramBinding)]),
        "stratum_scene_set_background_program": (c_int32, [p_void, c_uint32, c_uint32, c_uint32,
                                                           c_uint32]),
        "stratum_scene_set_light_program": (c_int32, [p_void, c_uint32, c_uint32, c_uint32]),
        "stratum_scene_evaluate_program": (c_int32, [p_void, c_uint32, p_float, c_uint32,
                                                     c_uint32, p_float]),
        "stratum_scene_set_mesh_texture_space": (c_int32, [p_void, c_uint32, p_float, p_float]),
        "stratum_scene_set_instance_object_info": (c_int32, [p_void, c_uint32, c_uint32, p_float,
                                                             p_float]),
        "stratum_scene_set_mesh_attribute": (c_int32, [p_void, c_uint32, c_uint32, c_int32,
                                                       p_float, c_uint32]),
        "stratum_scene_set_light_linking": (c_int32, [p_void, c_int32, c_uint32, c_uint32, p_u8,
                                                      p_u8, p_u64, p_u64]),
        # settings and passes
        "stratum_setting_count": (c_int32, []),
        "stratum_setting_info": (c_int32, [c_int32, ctypes.POINTER(_SettingInfo)]),
        "stratum_setting_choice": (c_int32, [c_int32, c_int32, pp_char, pp_char, pp_char]),
        "stratum_pass_count": (c_int32, []),
        "stratum_pass_info": (c_int32, [c_int32, pp_char, p_i32, pp_char]),
        "stratum_renderer_read_pass": (c_int32, [p_void, p_char, p_float, ctypes.c_size_t]),
        "stratum_renderer_read_lightgroup": (c_int32, [p_void, c_uint32, p_float, ctypes.c_size_t]),
    }
