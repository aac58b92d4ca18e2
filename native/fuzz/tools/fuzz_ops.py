"""One encoder per operation of the ABI fuzzer's programs (native/fuzz/program.cpp; encoding in
native/fuzz/README.md), for the assembler fuzz_corpus.py: materials and closures, lights,
cameras, meshes, instances, vertex normals, background and environment, textures and their
bindings, renders with their settings, throughput, save/load. Each returns the bytes of one
operation; the field values are encoded by fuzz_encoding.py.
"""

from __future__ import annotations

from fuzz_encoding import OPS, mutations, positive, raw_string, signed, unit
from stratum.native.abi import SHADER_INPUT_REGISTERS

MATERIAL_FIELDS = {
    "base_r": (0, "unit"),
    "base_g": (1, "unit"),
    "base_b": (2, "unit"),
    "roughness": (3, "unit"),
    "metallic": (4, "unit"),
    "specular": (5, "unit"),
    "ior": (6, "positive"),
    "emission_r": (7, "positive"),
    "emission_g": (8, "positive"),
    "emission_b": (9, "positive"),
    "transmission": (10, "unit"),
    "coat": (11, "unit"),
    "coat_roughness": (12, "unit"),
    "coat_ior": (13, "positive"),
}


def material_desc(model: int, **changes: float | str) -> bytes:
    return bytes([model]) + mutations(MATERIAL_FIELDS, changes)


def material(model: int, **changes: float | str) -> bytes:
    return bytes([OPS["material"]]) + material_desc(model, **changes)


def closure_material(closures: list[tuple[tuple[float, float, float], bytes]]) -> bytes:
    out = bytes([OPS["closure_material"], len(closures)])
    for weight, desc in closures:
        out += b"".join(unit(w) for w in weight) + desc
    return out


LIGHT_FIELDS = {
    "strength": (3, "positive"),
    "radius": (4, "positive"),
    "angle": (5, "unit"),
    "size_x": (6, "positive"),
    "size_y": (7, "positive"),
    "spot_size": (8, "unit"),
    "spot_blend": (9, "unit"),
    "spread": (10, "unit"),
}


def light(kind: int, transform: bytes = b"\x00\x00", **changes: float | str) -> bytes:
    return bytes([OPS["light"], kind]) + transform + mutations(LIGHT_FIELDS, changes)


CAMERA_FIELDS = {
    "lens_mm": (0, "positive"),
    "sensor_width_mm": (1, "positive"),
    "shift_x": (3, "signed"),
    "clip_start": (5, "positive"),
    "clip_end": (6, "positive"),
    "ortho_scale": (7, "positive"),
    "aperture_radius": (8, "positive"),
    "focus_distance": (9, "positive"),
}


def camera(preset: int = 0, transform: bytes = b"\x00\x00", **changes: float | str) -> bytes:
    """preset 0 perspective, 1 orthographic, 2 equirectangular, 3 perspective with an aperture."""
    return bytes([OPS["camera"], preset]) + transform + mutations(CAMERA_FIELDS, changes)


def mesh(preset: int, material_id: int = 0, flags: int = 0) -> bytes:
    """preset 0 triangle, 1 square, 2 cube; flags: 1 corner normals, 2 vertex normals, 4 uvs."""
    return bytes([OPS["mesh"], preset, 0, flags, 0, 0, 0, material_id])


def raw_mesh(positions: list[float | str], triangles: list[int], material_id: int = 0) -> bytes:
    out = bytes([OPS["mesh"], 3, len(positions) // 3, len(triangles) // 3])
    out += b"".join(signed(p) for p in positions) + bytes(triangles)
    return out + bytes([0, 0, 0, 0, 0, material_id])


def instance(mesh_id: int, transform: bytes = b"\x00\x00") -> bytes:
    return bytes([OPS["instance"], mesh_id]) + transform


def instance_ex(
    mesh_id: int,
    start: bytes = b"\x00\x00",
    end: bytes = b"\x00\x00",
    motion: bool = True,
    visibility: int = 31,
    holdout: int = 0,
) -> bytes:
    return (
        bytes([OPS["instance_ex"], mesh_id])
        + start
        + bytes([1 if motion else 0])
        + end
        + bytes([visibility, holdout])
    )


def instances(rows: list[tuple[int, bytes]], nulls: int = 0) -> bytes:
    """One stratum_scene_add_instances call: (mesh id, transform) rows; nulls bit 1 passes NULL
    mesh ids, bit 2 NULL transforms."""
    return bytes([OPS["instances"], len(rows)]) + b"".join(bytes([m]) + t for m, t in rows) + bytes([nulls])


def vertex_normals(positions: list[float | str], faces: list[tuple[int, int, list[float | str]]],
                   corners: list[int], threads: int = 0, nulls: int = 0) -> bytes:
    """One stratum_vertex_normals call: positions (3 per vertex), faces as (start, size, normal),
    corner vertices, a thread count below 4; nulls bit 1 passes NULL positions, 2 the face
    arrays, 4 corner_vertices, 8 out_normals."""
    out = bytes([OPS["vertex_normals"], len(positions) // 3]) + b"".join(signed(p) for p in positions)
    out += bytes([len(faces)])
    for start, size, normal in faces:
        out += bytes([start, size]) + b"".join(signed(n) for n in normal)
    return out + bytes([len(corners)]) + bytes(corners) + bytes([threads, nulls])


def background(r: float, g: float, b: float) -> bytes:
    return bytes([OPS["background"]]) + unit(r) + unit(g) + unit(b)


def environment(width: int, height: int, value: float, strength: float, rotation: int = 0) -> bytes:
    """rotation 0: none, 1: identity, 2: about z by 0.5 rad."""
    out = bytes([OPS["environment"], width, height, rotation << 3]) + positive(value) + bytes([0])
    out += positive(strength)
    if rotation == 2:
        out += signed(0.5)
    if rotation:
        out += bytes([0])
    return out


def pixels_texture(width: int, height: int, channels: int, value: float) -> bytes:
    """A pixels texture, sRGB, no OCIO config, linear interpolation, repeat."""
    return (
        bytes([OPS["texture"], 0, width, height, channels])
        + unit(value)
        + bytes([0, 0])  # no pixel changes; file name selector
        + bytes([0, 0])  # colour space "sRGB"; OCIO config NULL
        + bytes([1, 0])
    )


def file_texture(template: int, color_space: int = 0, source: int = 1) -> bytes:
    """In-memory file (source 1) or a file in the temp dir (source 3) from template
    `template` (0 png rgba8, 1 png rgb16, 2 exr, 3 hdr, 4 tga, 5 bmp, 6 jpg, 7 tif)."""
    return bytes([OPS["texture"], source, template, 0, 0, 0, color_space, 0, 1, 0])


def huge_png_texture(width_selector: int, height_selector: int) -> bytes:
    """The PNG template with an IHDR that claims another size (i64 selectors: 7 = 65535)."""
    return bytes([OPS["texture"], 1, 0, 6, width_selector, height_selector, 0, 0, 0, 0, 1, 0])


def special_path_texture(which: int) -> bytes:
    """which: 0 missing, 1 the directory's '', 2 FIFO, 3 not an image, 4 a directory,
    5 /dev/zero, 6 /dev/null, 7 ''."""
    return bytes([OPS["texture"], 4, which, 0, 0, 0, 1, 0])


def bind(material_id: int, param: int, texture_id: int, channel: int = -1, scale_: float = 1.0) -> bytes:
    return (
        bytes([OPS["bind_texture"], material_id, 0, param, texture_id, channel + 1])
        + signed(scale_)
        + signed(0.0)
        + bytes([0])
    )


# STRATUM_SHADER_INPUT_REGISTERS, as the binding reads it from the header's value.
SHADER_INPUTS = SHADER_INPUT_REGISTERS


def shader_program(nodes: list[tuple[int, list[int], list[int], list[int]]], extra: int,
                   registers: dict[int, float] | None = None,
                   inputs: dict[int, float] | None = None) -> bytes:
    """op_add_shader_program (native/fuzz/program_ops.cpp): SHADER_INPUTS + extra registers
    (every 7th from SHADER_INPUTS drawn: `registers` gives them, else 0), no data, nodes as
    (type, modes, input registers, output registers), then the evaluation's inputs (`inputs`,
    else 0)."""
    count = SHADER_INPUTS + extra
    out = bytes([OPS["shader_program"], len(nodes), extra])
    for i in range(SHADER_INPUTS, count):
        if i % 7 == 0:
            out += signed((registers or {}).get(i, 0.0))
    out += bytes([0])  # no data
    for type_, modes, ins, outs in nodes:
        out += bytes([type_]) + bytes(m + 1 for m in (modes + [0] * 6)[:6])
        out += bytes(r % (count + 1) for r in (ins + [0] * 12)[:12])
        out += bytes((r - SHADER_INPUTS) % (extra + 1) for r in (outs + [SHADER_INPUTS] * 6)[:6])
        out += bytes([0, 0])  # data offset 0, count 0
    for i in range(SHADER_INPUTS):
        out += signed((inputs or {}).get(i, 0.0))
    return out


def bind_program(material_id: int, param: int, program_id: int, register: int,
                 background: tuple[int, int, int, int] | None = None) -> bytes:
    """op_bind_program: a binding, then optionally the world's program (program, register,
    width, height)."""
    out = bytes([OPS["bind_program"], material_id, 0, param, program_id, register % 129])
    if background is None:
        return out + bytes([0])
    program, reg, width, height = background
    return out + bytes([1, program, reg % 129, width, height])


INT_SETTINGS = ["width", "height", "samples", "max_bounces", "seed", "threads", "crop_x", "crop_y"]
INT_SETTINGS += ["crop_width", "crop_height", "film_transparent", "rr_min_depth"]
FLOAT_SETTINGS = ["filter_width", "ao_distance", "control_variate"]
STRING_SETTINGS = ["sampler", "filter_type", "integrator", "hemisphere", "light_sampling"]
STRING_SETTINGS += ["mis_heuristic", "light_selection", "triangle_sampling", "rr_mode"]
# The C++ table (native/fuzz/render_ops.cpp) in its order: the first names, two near misses, then
# the names appended later (so that older programs keep their meaning).
APPENDED_SETTINGS = ["use_adaptive_sampling", "adaptive_threshold", "adaptive_min_samples",
                     "adaptive_metric", "light_tree_splits", "sample_offset", "sample_count", "bvh",
                     "mist_start", "mist_depth", "mist_falloff", "passes",
                     "radiosity_patch_size", "radiosity_solver", "radiosity_tolerance",
                     "use_guiding", "guiding_training_samples", "guiding_bsdf_fraction", "guiding_split"]
SETTING_NAMES = (INT_SETTINGS + FLOAT_SETTINGS + STRING_SETTINGS + ["WIDTH", ""]
                 + APPENDED_SETTINGS)


def render(
    settings: list[tuple[str, int | float | str]] = (),
    width: int = 8,
    height: int = 8,
    samples: int = 2,
    bounces: int = 4,
    threads: int = 2,
    mode: int = 0,
    rerender: bool = False,
) -> bytes:
    """mode 0: wait; 1: cancel at once; 2: change a setting while rendering; 3: read progress and
    pixels while rendering; 4: destroy while rendering. Strings are passed raw (exact names)."""
    out = bytes([OPS["rerender" if rerender else "render"], len(settings)])
    for name, value in settings:
        if isinstance(value, str):
            out += bytes([2, SETTING_NAMES.index(name)]) + raw_string(value)
        elif isinstance(value, float):
            out += bytes([1, SETTING_NAMES.index(name), 8]) + positive(value)
        else:
            assert 0 <= value <= 239
            out += bytes([0, SETTING_NAMES.index(name), value + 16])
    out += bytes([width - 1, height - 1, samples - 1, bounces, threads - 1, mode])
    return out + (bytes([1]) if mode != 4 else b"")  # no image written


def throughput(width: int = 4, height: int = 4, samples: int = 1, bounces: int = 2) -> bytes:
    return bytes([OPS["throughput"], width, height, samples, bounces, 0])


def save_load(mode: int = 1) -> bytes:
    """mode 0: round trip; 1: round trip, continue with the loaded scene."""
    return bytes([OPS["save_load"], mode])
