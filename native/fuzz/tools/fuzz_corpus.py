"""Writes the ABI fuzzer's seed corpus and the issue's known crashes as fuzzer programs.

The fuzzer (native/fuzz/) reads its input as a program over the C ABI; the encoding is in
native/fuzz/README.md. This script is an assembler for that encoding: each seed is a readable
list of operations, so the corpus is reviewable and can be regenerated after the encoding
changes (`.venv/bin/python native/fuzz/tools/fuzz_corpus.py`). Seeds go to native/fuzz/corpus/;
programs that reproduce the crashes of issue 12 go to native/fuzz/regressions/ (replayed by
ctest).

This module holds the programs (the seeds and the known crashes) and writes them; the
operations they are made of are encoded by fuzz_ops.py, the field values by fuzz_encoding.py
(beside it: a script's folder is the first entry of sys.path, so they import by their names).
"""

from __future__ import annotations

from pathlib import Path

from fuzz_encoding import OPS, axis_scale, matrix, rotate, scale, translate, unit
from fuzz_ops import (
    SHADER_INPUTS,
    background,
    bind,
    bind_program,
    camera,
    closure_material,
    environment,
    file_texture,
    huge_png_texture,
    instance,
    instance_ex,
    instances,
    light,
    material,
    material_desc,
    mesh,
    pixels_texture,
    raw_mesh,
    render,
    save_load,
    shader_program,
    special_path_texture,
    throughput,
    vertex_normals,
)

FUZZ = Path(__file__).resolve().parents[1]  # native/fuzz


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
    s["box-adaptive"] = box_scene() + render(
        [("use_adaptive_sampling", 1), ("adaptive_metric", "mse"), ("adaptive_threshold", 0.5),
         ("adaptive_min_samples", 1)], samples=2
    )
    s["box-tree-split"] = box_scene() + render(
        [("light_selection", "tree"), ("light_tree_splits", 16), ("passes", "Depth,Debug Sample Count")]
    )
    s["box-sample-range"] = box_scene() + render(
        [("sample_offset", 1), ("sample_count", 1), ("bvh", "dynamic"), ("mist_depth", 2.0)]
    )
    s["box-radiosity"] = box_scene() + render(
        [("integrator", "radiosity"), ("radiosity_solver", "gauss_seidel"), ("radiosity_patch_size", 0.5),
         ("radiosity_tolerance", 0.01)]
    )
    s["box-guiding"] = box_scene() + render(
        [("use_guiding", 1), ("guiding_training_samples", 1), ("guiding_bsdf_fraction", 0.3), ("guiding_split", "full")]
    )
    s["box-crop"] = box_scene() + render([("crop_x", 2), ("crop_y", 1), ("crop_width", 4), ("crop_height", 5)])
    s["box-cancel"] = box_scene() + render(mode=1) + render(mode=3, rerender=True) + render(mode=2, rerender=True)
    s["box-destroy"] = box_scene() + render(mode=4)
    s["camera-ortho"] = box_scene() + camera(1) + render()
    s["camera-equirect"] = box_scene() + camera(2) + render()
    s["camera-dof"] = box_scene() + camera(3) + render()
    for kind, name in enumerate(["point", "sun", "rectangle", "ellipse", "spot", "spot-v1"]):
        s[f"light-{name}"] = material(1) + mesh(2) + instance(0) + light(kind) + camera(0) + render()
    s["light-point-radiosity"] = material(1) + mesh(2) + instance(0) + light(0) + camera(0) + render(
        [("integrator", "radiosity"), ("radiosity_solver", "shooting")]
    )
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
    # A program driving the cube's base colour: sin(generated x * 6) in all three channels,
    # evaluated on drawn inputs, and the same program as the world. Its registers follow the
    # inputs: the constant 6 where the fuzzer draws a value (every 7th register), then the
    # three results.
    six, product, sine, colour = (SHADER_INPUTS + k for k in (5, 6, 7, 8))
    assert six % 7 == 0
    s["shader-program"] = (
        box_scene()
        + shader_program([(0, [2, 0], [15, six], [product]), (0, [4, 0], [product, product], [sine]),
                          (35, [2], [sine], [colour])], 12, registers={six: 6.0},
                         inputs={15: 0.25})
        + bind_program(0, 0, 0, colour, background=(0, colour, 8, 4))
        + render()
        + save_load(1)
        + render()
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
        out = FUZZ / folder
        out.mkdir(parents=True, exist_ok=True)
        for name, program in programs.items():
            (out / name).write_bytes(program)
        print(f"{out}: {len(programs)} programs")


if __name__ == "__main__":
    main()
