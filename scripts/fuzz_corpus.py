"""Writes the ABI fuzzer's seed corpus and the issue's known crashes as fuzzer programs.

The fuzzer (native/fuzz/) reads its input as a program over the C ABI; the encoding is in
native/fuzz/README.md. This script is an assembler for that encoding: each seed is a readable
list of operations, so the corpus is reviewable and can be regenerated after the encoding
changes (`python scripts/fuzz_corpus.py`). Seeds go to native/fuzz/corpus/; programs that
reproduce the crashes of issue 12 go to native/fuzz/regressions/ (replayed by ctest).
"""

from __future__ import annotations

import struct
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# ByteReader::special_floats(), by index.
SPECIAL = {
    "0": 0,
    "-0": 1,
    "denorm": 2,
    "-denorm": 3,
    "flt_min": 4,
    "1e-38": 5,
    "1e-18": 6,
    "1e-9": 7,
    "1e-4": 8,
    "1e4": 9,
    "1e9": 10,
    "1e18": 11,
    "flt_large": 12,
    "1e19": 13,
    "1e30": 14,
    "3e38": 15,
    "flt_max": 16,
    "inf": 17,
    "nan": 18,
    "-1e19": 19,
    "-1e30": 20,
    "-3e38": 21,
    "-flt_max": 22,
    "-inf": 23,
    "-nan": 24,
    "1": 25,
    "-1": 26,
    "pi": 27,
    "2pi": 28,
    "0.5": 29,
    "65536": 30,
    "-1e-18": 31,
}

OPS = {
    name: code
    for code, name in enumerate(
        [
            "material",
            "closure_material",
            "texture",
            "bind_texture",
            "mesh",
            "instance",
            "instance_ex",
            "light",
            "camera",
            "background",
            "environment",
            "new_scene",
            "save_load",
            "render",
            "rerender",
            "throughput",
            "sampling",
            "models",
        ]
    )
}
OPS["instances"] = 254  # operations added later take the top byte values (native/fuzz/program.cpp)
OPS["vertex_normals"] = 253


def special(name: str) -> bytes:
    return bytes([SPECIAL[name]])


def raw(v: float) -> bytes:
    return bytes([0xE0]) + struct.pack("<f", v)


def _scaled(v: float | str, kind: str) -> bytes:
    """A float field value: a special by name, the one-byte scaled form when exact, else raw."""
    if isinstance(v, str):
        return special(v)
    if kind == "signed":
        s = v * 16 + 128
    elif kind == "positive":
        s = v * 16 + 32
    else:
        s = v * 191 + 32
    if s == int(s) and 32 <= s < 224:
        return bytes([int(s)])
    return raw(v)


def signed(v: float | str) -> bytes:
    return _scaled(v, "signed")


def positive(v: float | str) -> bytes:
    return _scaled(v, "positive")


def unit(v: float | str) -> bytes:
    return _scaled(v, "unit")


def mutations(fields: dict[str, tuple[int, str]], changes: dict[str, float | str]) -> bytes:
    """The mutation list of a descriptor: count, then (field index, value) pairs."""
    out = bytes([len(changes)])
    for name, value in changes.items():
        index, kind = fields[name]
        out += bytes([index])
        out += _scaled(value, kind) if kind != "int" else small_int(int(value))
    return out


def small_int(v: int) -> bytes:
    """draw_small_int: selectors from 16 on give s % 12 - 2, so 24 + (v + 2) gives v in -2..9."""
    assert -2 <= v <= 9
    return bytes([24 + v + 2])


def matrix(preset: int = 0, args: bytes = b"", changes: dict[int, float | str] | None = None) -> bytes:
    out = bytes([preset]) + args
    changes = changes or {}
    out += bytes([len(changes)])
    for element, value in changes.items():
        out += bytes([element]) + signed(value)
    return out


def translate(x: float | str, y: float | str, z: float | str, **kw) -> bytes:
    return matrix(1, signed(x) + signed(y) + signed(z), **kw)


def scale(s: float | str, **kw) -> bytes:
    return matrix(2, positive(s), **kw)


def axis_scale(x: float | str, y: float | str, z: float | str, **kw) -> bytes:
    return matrix(3, signed(x) + signed(y) + signed(z), **kw)


def rotate(axis: int, angle: float | str, **kw) -> bytes:
    return matrix(4, bytes([axis]) + signed(angle), **kw)


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


INT_SETTINGS = ["width", "height", "samples", "max_bounces", "seed", "threads", "crop_x", "crop_y"]
INT_SETTINGS += ["crop_width", "crop_height", "film_transparent", "rr_min_depth"]
FLOAT_SETTINGS = ["filter_width", "ao_distance", "control_variate"]
STRING_SETTINGS = ["sampler", "filter_type", "integrator", "hemisphere", "light_sampling"]
STRING_SETTINGS += ["mis_heuristic", "light_selection", "triangle_sampling", "rr_mode"]
SETTING_NAMES = INT_SETTINGS + FLOAT_SETTINGS + STRING_SETTINGS

# render_ops.cpp string_values(): fixed values, then the choices of the settings (samplers, filters,
# integrators, hemispheres) in menu order, read from the library at run time.
FIXED_VALUES = ["box", "blackman_harris", "gaussian", "mis", "nee", "bsdf", "power", "balance", "max"]
FIXED_VALUES += ["mixed", "uniform", "solid_angle", "area", "throughput", "albedo", "off", "on", "", "Random"]
FIXED_VALUES += ["path "]


def raw_string(s: str) -> bytes:
    return bytes([240, len(s)]) + s.encode()


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


def box_scene() -> bytes:
    """A white cube on a floor, a small emissive panel above to the side, a point light, a camera."""
    return (
        material(0)
        + material(3, emission_r=4.0, emission_g=4.0, emission_b=4.0)
        + mesh(2)
        + mesh(1, material_id=1)
        + mesh(1)
        + instance(0, scale(0.5))
        + instance(1, scale(0.5, changes={3: 1.5, 11: 2.5}))
        + instance(2, axis_scale(4, 4, 1, changes={11: -1.0}))
        + light(0, translate(1, 1, 0))
        + camera(0)
    )


def seeds() -> dict[str, bytes]:
    s = {}
    s["box-path"] = box_scene() + render()
    s["box-light-tracer"] = box_scene() + render([("integrator", "light")])
    s["box-ao-direct"] = box_scene() + render([("integrator", "ao")]) + render([("integrator", "direct")], rerender=True)
    for sampler in ["random", "sobol", "halton_owen", "stratified", "bluenoise", "zsobol", "fibonacci"]:
        s[f"box-{sampler}"] = box_scene() + render([("sampler", sampler), ("seed", 3)])
    s["box-estimators"] = box_scene() + render(
        [("light_sampling", "nee"), ("light_selection", "power"), ("triangle_sampling", "area"), ("rr_mode", "off")]
    )
    s["box-settings"] = box_scene() + render(
        [("filter_type", "box"), ("filter_width", 2.0), ("film_transparent", 1), ("control_variate", 0.5)]
    )
    s["box-crop"] = box_scene() + render([("crop_x", 2), ("crop_y", 1), ("crop_width", 4), ("crop_height", 5)])
    s["box-cancel"] = box_scene() + render(mode=1) + render(mode=3, rerender=True) + render(mode=2, rerender=True)
    s["box-destroy"] = box_scene() + render(mode=4)
    s["camera-ortho"] = box_scene() + camera(1) + render()
    s["camera-equirect"] = box_scene() + camera(2) + render()
    s["camera-dof"] = box_scene() + camera(3) + render()
    for kind, name in enumerate(["point", "sun", "rectangle", "ellipse", "spot", "spot-v1"]):
        s[f"light-{name}"] = material(1) + mesh(2) + instance(0) + light(kind) + camera(0) + render()
    s["instances-batch"] = box_scene() + instances([(0, translate(0.5, 0, 0)), (0, rotate(1, 0.5))]) + render()
    s["instances-refused"] = (
        box_scene()
        + instances([(0, b"\x00\x00"), (0, translate("nan", 0, 0))])
        + instances([(0, b"\x00\x00")], nulls=2)
        + instances([], nulls=3)
        + render()
    )
    # A unit square (two triangles over corners 0-5) and a vertex without a face; then a face
    # past the corners, a corner vertex out of range, a NaN position, NULL arrays.
    square = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 2, 2]
    s["vertex-normals"] = vertex_normals(square, [(0, 3, [0, 0, 1]), (3, 3, [0, 0, 1])],
                                         [0, 1, 2, 0, 2, 3], threads=2)
    s["vertex-normals-refused"] = (
        vertex_normals(square, [(4, 3, [0, 0, 1])], [0, 1, 2, 3, 4])
        + vertex_normals(square, [(0, 3, [0, 0, 1])], [0, 1, 7])
        + vertex_normals([0, 0, "nan"], [(0, 1, [0, 0, 1])], [0])
        + vertex_normals(square, [(0, 3, [0, 0, 1])], [0, 1, 2], nulls=8)
        + vertex_normals([], [], [], nulls=15)
    )
    s["materials"] = (
        material(1, roughness=0.2)
        + material(2, metallic=1.0)
        + material(4)
        + material(5, ior=1.5)
        + material(6)
        + material(7)
        + mesh(2, material_id=0)
        + mesh(0, material_id=1)
        + mesh(1, material_id=2)
        + mesh(1, material_id=3)
        + instance(0, translate(-2, 0, 0))
        + instance(1)
        + instance(2, translate(2, 0, 0))
        + instance(3, translate(0, 2, 0))
        + light(2)
        + camera(0)
        + render()
    )
    s["closures"] = (
        closure_material([((0.5, 0.5, 0.5), material_desc(0)), ((0.5, 0.5, 0.5), material_desc(4))])
        + closure_material([((1, 1, 1), material_desc(2, coat=0.5, transmission=0.5))])
        + mesh(2)
        + mesh(1, material_id=1)
        + instance(0)
        + instance(1, translate(0, 0, -1))
        + light(1)
        + camera(0)
        + render()
    )
    s["textures"] = (
        material(1)
        + pixels_texture(2, 2, 3, 0.5)
        + file_texture(0)
        + file_texture(2, color_space=2)
        + file_texture(3, source=3)
        + bind(0, 0, 0)
        + bind(0, 1, 1, channel=0)
        + bind(0, 3, 2)
        + mesh(2, flags=5)
        + instance(0)
        + light(0)
        + camera(0)
        + render()
    )
    s["texture-formats"] = b"".join(file_texture(t) for t in range(8)) + b"".join(
        file_texture(t, source=3) for t in range(8)
    )
    s["motion"] = (
        material(0)
        + mesh(2)
        + mesh(1)
        + instance_ex(0, translate(-1, 0, 0), translate(1, 0, 0))
        + instance_ex(0, rotate(2, 0.5), rotate(2, 1.5), visibility=1, holdout=1)
        + instance(1, translate(0, 0, -1))
        + light(0)
        + camera(0)
        + render()
    )
    s["environment"] = box_scene() + environment(4, 2, 1.0, 1.0, rotation=2) + render()
    s["background"] = box_scene() + background(0.2, 0.3, 0.5) + render([("integrator", "light")])
    s["save-load"] = box_scene() + save_load(1) + render() + save_load(0)
    s["throughput"] = box_scene() + throughput() + throughput(1, 1, 2, 4)
    s["raw-mesh"] = (
        material(0)
        + raw_mesh([-1, -1, 0, 1, -1, 0, 0, 1, 0, 0, 0, 1], [0, 1, 2, 0, 1, 3, 1, 2, 3])
        + instance(0)
        + light(0)
        + camera(0)
        + render()
    )
    # Cases of issue 12 that do not crash this harness today (motion with extreme transforms,
    # a 3e38 W light), kept as seeds: mutations near them are where such crashes live.
    s["motion-shear-1e19"] = box_scene() + instance_ex(0, matrix(0), matrix(0, changes={1: "1e19"})) + render()
    s["motion-element-3.4e38"] = (
        box_scene() + instance_ex(0, matrix(0), matrix(0, changes={3: -3.4e38})) + render(width=4, height=4, samples=1)
    )
    s["point-light-3e38"] = material(0) + mesh(1) + instance(0) + light(0, strength="3e38") + camera(0) + render()
    s["library"] = (
        bytes([OPS["sampling"], 0, 3, 16 + 16, 1, 2, 3, 4, 16 + 8, 16 + 8, 16 + 1, 16 + 2, 0, 6, 0, 0, 16])
        + bytes([OPS["sampling"], 1, 2, 4])
        + b"".join(unit(v) for v in [0.1, 0.2, 0.5, 0.5, "1", "0", 0.9, 0.3])
        + bytes([1])
        + bytes([OPS["sampling"], 2, 2])
        + bytes([OPS["sampling"], 3, 0, 10, 0])
        + bytes([OPS["models"], 0, 16 + 3])
        + bytes([OPS["models"], 2, 16 + 1])
    )
    return s


def known_crashes() -> dict[str, bytes]:
    """The crashes and hangs of issue 12 (Embree assertions, a memory bomb, hangs)."""
    k = {}
    k["issue12-aperture-1e30"] = box_scene() + camera(3, aperture_radius="1e30") + render()
    k["issue12-lens-1e-38"] = box_scene() + camera(0, lens_mm="1e-38") + render()
    k["issue12-camera-1e19"] = box_scene() + camera(0, translate(0, 0, "1e19")) + render()
    k["issue12-ortho-scale-1e20"] = box_scene() + camera(1, ortho_scale=1e20) + render()
    k["issue12-equirect-1e19"] = box_scene() + camera(2, translate("1e19", 0, 0)) + render()
    k["issue12-zero-scale-instance"] = box_scene() + instance(0, axis_scale(1, 0, 1)) + render()
    k["issue12-tiny-scale-instance"] = box_scene() + instance(0, axis_scale(1, "1e-18", 1)) + render()
    k["issue12-throughput-1e19"] = box_scene() + camera(0, translate(0, 0, "1e19")) + throughput()
    k["issue12-emission-3e38"] = (
        material(3, emission_r="3e38", emission_g="3e38", emission_b="3e38")
        + mesh(1)
        + instance(0)
        + camera(0)
        + render()
    )
    k["issue12-png-65535"] = huge_png_texture(7, 7)
    k["issue12-texture-dev-zero"] = special_path_texture(5)
    k["issue12-texture-fifo"] = special_path_texture(2)
    # Found by the fuzzer: finite texels that OpenColorIO's or the sRGB curve's conversion turns
    # into Inf (1e19 ** 2.4), which a scene file then writes as null and cannot load back.
    k["texture-srgb-1e19-save-load"] = pixels_texture(1, 1, 1, "1e19") + save_load(0)
    # Found by the fuzzer: an OCIO config path that is a FIFO blocks in OpenColorIO's read.
    k["texture-ocio-config-fifo"] = pixels_texture(2, 2, 3, 0.5)[:-4] + bytes([3, 3, 1, 0])
    return k


def main() -> None:
    for folder, programs in (("corpus", seeds()), ("regressions", known_crashes())):
        out = ROOT / "native" / "fuzz" / folder
        out.mkdir(parents=True, exist_ok=True)
        for name, program in programs.items():
            (out / name).write_bytes(program)
        print(f"{out}: {len(programs)} programs")


if __name__ == "__main__":
    main()
