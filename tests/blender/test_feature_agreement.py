"""Stratum against Cycles on the feature scenes (scenes/features/*.blend), feature group by group.

Runs in Blender 3.4 (`blender -b --factory-startup -noaudio --python
tests/blender/run_in_blender.py -- tests/blender/test_feature_agreement.py`) and under the bpy
5.0 wheel (`.venv/bin/python -m pytest tests/blender/test_feature_agreement.py`).

Cases (scenes/features/make_features.py describes the scenes): materials, lights, world, the
three scenes of camera.blend (dof, ortho, motion), instancing, procedural (issue 18's
procedural materials), sky, and the two scenes of light_paths.blend (issue 34; described by
scenes/features/make_light_paths.py: light_paths renders with the file's own Cycles Light Paths
values, TUNED_LIGHT_PATHS). Each is rendered at RES x RES
by Cycles and by Stratum with the shared peer settings of agreement.py (CPU, same
samples, MAX_BOUNCES for every bounce kind, Blackman-Harris 1.5 px, no denoising, adaptive
sampling, clamping or glossy blur), seeds 1 and 2, SPP[case] samples per seed. Asserted:

* the export produces no warning (an unsupported feature is reported by name: the failure
  says which piece is missing);
* the noise allows the comparison: 4 sigma of every compared difference below half of its
  tolerance (the measurement of test_cycles_agreement.py: sigma from the half difference of
  the two seeds, pixel correlation checked on the block means);
* per RGB channel, |mean(S) - mean(C)| <= IMAGE_TOL mean(C);
* per RGB channel and 16 x 16 block, |block(S) - block(C)| <= BLOCK_TOL block(C) for every
  block that is not dark (below);
* mean LDR-FLIP(Stratum, Cycles) < FLIP_TOL, both images shown through Blender's Standard view
  transform at exposure 0 (linear clamped to [0, 1], then the sRGB OETF:
  stratum.compare.metrics.srgb_display), evaluated by flip_evaluator (in a subprocess with
  the project venv's Python when the running Blender's Python lacks it).

Dark blocks. A (block, channel) whose Cycles mean is below DARK = 0.016 (linear) is not compared
relatively. Why 0.016: on the display, an error e at linear value x moves the sRGB value by
e * OETF'(x) = e * (1.055 / 2.4) x^(1/2.4 - 1); a 5% error (e = 0.05 x) is one 8-bit level
(1/255) exactly at x = (1/255 / (0.05 * 0.4396))^2.4 = 0.016. Below it the tolerance is finer
than what an 8-bit display shows, and the relative noise of such blocks grows as 1/x. They are
still covered by the image means and by FLIP.

Statistics (see test_cycles_agreement.py's docstring for the derivation): with N = 2 SPP samples
per pixel, 4 sigma_rel of a block difference is 4 sqrt(2) r_b / sqrt(256 N), r_b the relative
standard deviation of one path sample over the block; SPP is chosen per case so that the
measured 4 sigma of every compared block is below half of BLOCK_TOL. The measured numbers are
in docs/features.md.

Images for humans: out/agreement/blender-<version>-features/<case>_{cycles,stratum}.png,
<case>_difference.png, <case>_report.txt.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import bpy
import numpy as np
import pytest
from stratum.blender_settings import CYCLES_LIGHT_PATHS

from agreement import (
    K_SIGMA,
    OUT,
    Renders,
    configure_cycles,
    configure_stratum,
    difference_image,
    load_exr,
    per_channel,
    render_two_seeds,
    set_frame_and_exr,
    stratum_available,
)

REPO = Path(__file__).resolve().parents[2]
FEATURES = REPO / "scenes" / "features"
FEATURE_OUT = OUT.parent / (OUT.name + "-features")

RES = 64
BLOCK = 16
SEEDS = (1, 2)
MAX_BOUNCES = 6
IMAGE_TOL = 0.02
BLOCK_TOL = 0.05
FLIP_TOL = 0.05
DARK = 0.016  # linear; see the module docstring

# case -> (file, scene name or None for the file's only scene, samples per seed)
CASES = {
    "materials": ("materials.blend", None, 3072),
    "lights": ("lights.blend", None, 768),
    "world": ("world.blend", None, 384),
    "camera_dof": ("camera.blend", "dof", 256),
    "camera_ortho": ("camera.blend", "ortho", 256),
    "camera_motion": ("camera.blend", "motion", 256),
    "instancing": ("instancing.blend", None, 256),
    "procedural": ("procedural.blend", None, 512),
    "sky": ("sky.blend", None, 512),
    "light_paths": ("light_paths.blend", "light_paths", 512),
    "environment_off": ("light_paths.blend", "environment_off", 128),
}
# Cases whose file carries Cycles' Light Paths values as a file tuned for Cycles does (per-kind
# bounces, clamping, Filter Glossy, caustics): both engines render with the file's values, Cycles
# from scene.cycles and Stratum through light_paths 'CYCLES', instead of the peer settings'
# unlimited, unclamped ones.
TUNED_LIGHT_PATHS = {"light_paths"}


# ---- rendering -----------------------------------------------------------------------------


def _open_case(case: str) -> bpy.types.Scene:
    """Opens the case's .blend, keeps only its scene (the context scene then), sets RES."""
    file, scene_name, _ = CASES[case]
    bpy.ops.wm.open_mainfile(filepath=str(FEATURES / file), load_ui=False)
    if scene_name is not None:
        for other in list(bpy.data.scenes):
            if other.name != scene_name:
                bpy.data.scenes.remove(other)
    scene = bpy.context.scene
    assert scene_name is None or scene.name == scene_name
    set_frame_and_exr(scene, RES)
    return scene


def _render_two_seeds(case: str, engine: str) -> Renders:
    """The case rendered by `engine` with seeds SEEDS; EXRs in
    FEATURE_OUT/<case>_<engine>_seed<seed>.exr."""
    spp = CASES[case][2]
    peer = configure_cycles if engine == "cycles" else configure_stratum

    def configure(scene: bpy.types.Scene, seed: int) -> None:
        tuned = {name: getattr(scene.cycles, name) for name in CYCLES_LIGHT_PATHS.values()}
        peer(scene, seed, samples=spp, max_bounces=MAX_BOUNCES)
        if case in TUNED_LIGHT_PATHS:
            for name, value in tuned.items():
                setattr(scene.cycles, name, value)
            if engine == "stratum":
                scene.stratum.light_paths = "CYCLES"

    return render_two_seeds(f"{case}_{engine}", configure, FEATURE_OUT, lambda: _open_case(case))


# ---- FLIP --------------------------------------------------------------------------------------


_FLIP_SCRIPT = """
import json, sys
import numpy as np
import flip_evaluator
ref, test = np.load(sys.argv[1]), np.load(sys.argv[2])
_, mean, _ = flip_evaluator.evaluate(ref, test, "LDR", applyMagma=False)
print(json.dumps(float(mean)))
"""


def _flip_python() -> str:
    """A Python with flip_evaluator: STRATUM_FLIP_PYTHON, else the project venv's."""
    candidates = [os.environ.get("STRATUM_FLIP_PYTHON"), str(REPO / ".venv" / "bin" / "python")]
    for candidate in candidates:
        if candidate and Path(candidate).is_file():
            return candidate
    raise AssertionError("flip_evaluator is not importable here and no Python that has it was "
                         "found: run `make setup` (creates .venv) or set STRATUM_FLIP_PYTHON")


def flip_ldr(image: np.ndarray, reference: np.ndarray, tag: str) -> float:
    """Mean LDR-FLIP of the linear image against the linear reference, both shown through the
    Standard view transform (stratum.compare.metrics.srgb_display)."""
    from stratum.compare.metrics import srgb_display

    # Blender stores rows bottom to top; FLIP's spatial filters do not care, but keep the
    # images upright for anyone inspecting the saved arrays.
    ref = np.ascontiguousarray(srgb_display(reference[::-1]))
    test = np.ascontiguousarray(srgb_display(image[::-1]))
    try:
        import flip_evaluator
    except ImportError:
        FEATURE_OUT.mkdir(parents=True, exist_ok=True)
        ref_path, test_path = FEATURE_OUT / f"{tag}_ref.npy", FEATURE_OUT / f"{tag}_test.npy"
        np.save(ref_path, ref)
        np.save(test_path, test)
        done = subprocess.run([_flip_python(), "-c", _FLIP_SCRIPT, str(ref_path), str(test_path)],
                              capture_output=True, text=True, timeout=120, check=False)
        assert done.returncode == 0, f"FLIP subprocess failed:\n{done.stderr}"
        return float(json.loads(done.stdout.strip().splitlines()[-1]))
    _, mean, _ = flip_evaluator.evaluate(ref, test, "LDR", applyMagma=False)
    return float(mean)


# ---- fixtures ------------------------------------------------------------------------------


@pytest.fixture(scope="module", params=list(CASES))
def case(request) -> str:
    return request.param


@pytest.fixture(scope="module")
def cycles_case(case: str) -> Renders:
    return _render_two_seeds(case, "cycles")


@pytest.fixture(scope="module")
def stratum_case(library, case: str) -> Renders:
    reason = stratum_available()
    assert not reason, f"Stratum cannot render: {reason}"
    return _render_two_seeds(case, "stratum")


# ---- output for humans ---------------------------------------------------------------------


def _save_png(name: str, rgb: np.ndarray, *, linear_to_srgb: bool) -> None:
    from stratum.compare.metrics import srgb_display

    FEATURE_OUT.mkdir(parents=True, exist_ok=True)
    x = srgb_display(rgb) if linear_to_srgb else np.clip(rgb, 0.0, 1.0)
    rgba = np.concatenate([x, np.ones(x.shape[:2] + (1,))], axis=-1).astype(np.float32)
    image = bpy.data.images.new(name, RES, RES, alpha=True)
    try:
        image.pixels.foreach_set(rgba.ravel())
        image.filepath_raw = str(FEATURE_OUT / f"{name}.png")
        image.file_format = "PNG"
        image.save()
    finally:
        bpy.data.images.remove(image)


# ---- tests ---------------------------------------------------------------------------------


def test_feature_scene_exports_without_warnings(library, case: str) -> None:
    """Every feature in the scene is one Stratum translates: a warning names what is not."""
    from stratum import native
    from stratum.export.sync import export_scene

    _open_case(case)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    with native.Scene() as scene:
        summary = export_scene(depsgraph, scene)
    assert summary.warnings == [], f"{case}: export warnings:\n" + "\n".join(summary.warnings)


def test_feature_noise_allows_comparison(cycles_case: Renders, stratum_case: Renders,
                                         case: str) -> None:
    """4 sigma of the differences below half of each tolerance: a failure of the agreement
    test is then a difference of models, not noise."""
    c, s = cycles_case, stratum_case
    c_img = c.mean.mean(axis=(0, 1))
    sd_img = np.sqrt(c.image_var() + s.image_var())
    assert (K_SIGMA * sd_img < 0.5 * IMAGE_TOL * c_img).all(), (
        f"{case}: image-mean noise too high: 4 sigma_D = "
        f"{per_channel(K_SIGMA * sd_img / c_img, '{:.3%}')} (each renderer alone: cycles "
        f"{per_channel(K_SIGMA * np.sqrt(c.image_var()) / c_img, '{:.3%}')}, stratum "
        f"{per_channel(K_SIGMA * np.sqrt(s.image_var()) / c_img, '{:.3%}')})")
    cb = c.block_mean()
    lit = cb >= DARK
    rel = K_SIGMA * np.sqrt(c.block_var() + s.block_var()) / np.maximum(cb, 1e-12)
    bad = lit & (rel >= 0.5 * BLOCK_TOL)
    # Each renderer's own share, so a failure says whose noise it is (more samples, or a
    # sampling problem in one renderer).
    own_c, own_s = (float((K_SIGMA * np.sqrt(r.block_var()) / np.maximum(cb, 1e-12))[lit].max())
                    for r in (c, s))
    assert not bad.any(), (
        f"{case}: {int(bad.sum())} (block, channel) values too noisy: worst 4 sigma_D "
        f"{float(rel[lit].max()):.2%} >= {0.5 * BLOCK_TOL:.1%} (worst 4 sigma of each renderer "
        f"alone: cycles {own_c:.2%}, stratum {own_s:.2%}); correlation factors "
        f"cycles {c.inflation:.2f}, stratum {s.inflation:.2f}")
    for name in ASSERTED_SPHERES.get(case, ()):
        _, _, sigma = _sphere_stats(case, name, c, s)
        assert (K_SIGMA * sigma < 0.5 * SPHERE_TOL).all(), (
            f"{case}: sphere '{name}' too noisy: 4 sigma_D = "
            f"{per_channel(K_SIGMA * sigma, '{:.2%}')}")


def _report(case: str, c: Renders, s: Renders, flip: float, flip_noise: float) -> tuple[
        str, np.ndarray, np.ndarray, np.ndarray]:
    c_img, s_img = c.mean.mean(axis=(0, 1)), s.mean.mean(axis=(0, 1))
    img_rel = (s_img - c_img) / c_img
    cb, sb = c.block_mean(), s.block_mean()
    lit = cb >= DARK
    blk_rel = np.where(lit, (sb - cb) / np.maximum(cb, 1e-12), 0.0)
    rel_sigma = np.sqrt(c.block_var() + s.block_var()) / np.maximum(cb, 1e-12)
    nb = RES // BLOCK
    worst = np.unravel_index(int(np.argmax(np.abs(blk_rel))), blk_rel.shape)
    summary = {
        "case": case, "blender": bpy.app.version_string.split()[0], "spp": 2 * CASES[case][2],
        "image_rel": [float(x) for x in img_rel],
        "worst_block_rel": float(blk_rel[worst]),
        "worst_block": [int(nb - 1 - worst[0]), int(worst[1]), "RGB"[worst[2]]],
        "worst_4sigma": float(K_SIGMA * rel_sigma[lit].max()) if lit.any() else 0.0,
        "flip": flip, "flip_noise_single_seed": flip_noise,
        "seconds_cycles": c.seconds, "seconds_stratum": s.seconds,
        "dark_values": int((~lit).sum()),
    }
    lines = [
        (f"{case}: {RES}x{RES}, {2 * CASES[case][2]} spp ({len(SEEDS)} seeds), max_bounces "
        f"{MAX_BOUNCES}, Blender {bpy.app.version_string}"),
        (f"render seconds: cycles {[round(t, 2) for t in c.seconds]}, "
        f"stratum {[round(t, 2) for t in s.seconds]}"),
        f"image mean cycles : {per_channel(c_img)}",
        f"image mean stratum: {per_channel(s_img)}",
        f"relative diff     : {per_channel(img_rel, '{:+.3%}')}   (tolerance {IMAGE_TOL:.0%})",
        (f"mean LDR-FLIP {flip:.4f} (tolerance {FLIP_TOL}); Cycles seed 1 vs seed 2: "
        f"{flip_noise:.4f}"),
        (f"blocks ({BLOCK}x{BLOCK}, top row first), relative diff R/G/B in % (tolerance "
        f"{BLOCK_TOL:.0%}; '.' = dark channel, below {DARK}):"),
    ]
    for by in reversed(range(nb)):
        row = []
        for bx in range(nb):
            row.append("/".join(f"{100 * v:+5.1f}" if ok else "  .  "
                                for v, ok in zip(blk_rel[by, bx], lit[by, bx])))
        lines.append("  " + "  ".join(row))
    lines.append("summary " + json.dumps(summary))
    return "\n".join(lines), img_rel, blk_rel, lit


# Objects whose screen discs are reported one by one: the spheres of materials.blend, named
# after their material (scenes/features/make_features.py MATERIALS).
SPHERES = {
    "materials": ("metal_smooth", "metal_medium", "metal_rough", "coat", "glass",
                  "rough_glass", "diffuse", "textured", "mix", "add", "cutout", "plastic"),
}
# Discs asserted per RGB channel within SPHERE_TOL of Cycles: the normal-mapped, textured
# sphere (MikkTSpace tangents and Cycles' bump shadowing term; it was +10% with per-triangle
# tangents and no term). Its mean covers only ~50 pixels, so the noise test asks 4 sigma of the
# disc's difference below half of SPHERE_TOL, sigma^2 = sum over the disc of each renderer's
# per-pixel variance (the seeds' half difference squared) / n^2, inflated as the blocks are.
ASSERTED_SPHERES = {"materials": ("textured",)}
SPHERE_TOL = 0.02


def _sphere_regions(case: str) -> dict[str, np.ndarray]:
    """Per listed sphere object, a boolean RES x RES mask (rows bottom to top) of the pixels
    inside 70% of its projected radius: pixels that see the sphere only."""
    from bpy_extras.object_utils import world_to_camera_view

    scene = _open_case(case)
    cam = scene.camera
    right = cam.matrix_world.to_3x3().col[0].normalized()
    ys, xs = np.mgrid[0:RES, 0:RES] + 0.5
    regions = {}
    for name in SPHERES.get(case, ()):
        ob = bpy.data.objects[name]
        center = ob.matrix_world.translation
        radius = max(ob.dimensions) / 2.0
        c = world_to_camera_view(scene, cam, center)
        e = world_to_camera_view(scene, cam, center + right * radius)
        r_px = 0.7 * RES * float(np.hypot(e.x - c.x, e.y - c.y))
        regions[name] = (xs - c.x * RES) ** 2 + (ys - c.y * RES) ** 2 <= r_px**2
    return regions


def _sphere_stats(case: str, name: str, c: Renders,
                  s: Renders) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(Cycles' disc mean, Stratum's relative difference, 1 sigma of that difference relative
    to Cycles' mean), per RGB channel, over the sphere's disc."""
    mask = _sphere_regions(case)[name]
    n = int(mask.sum())
    cm, sm = c.mean[mask].mean(axis=0), s.mean[mask].mean(axis=0)
    var = (c.pixel_var[mask].sum(axis=0) * c.inflation**2 +
           s.pixel_var[mask].sum(axis=0) * s.inflation**2) / n**2
    scale = np.maximum(cm, 1e-12)
    return cm, (sm - cm) / scale, np.sqrt(var) / scale


def _sphere_lines(case: str, c: Renders, s: Renders) -> list[str]:
    lines = []
    for name, mask in _sphere_regions(case).items():
        cm, rel, sigma = _sphere_stats(case, name, c, s)
        lines.append(f"  {name:13s} {int(mask.sum()):3d} px  cycles {per_channel(cm)}  rel "
                     f"{per_channel(rel, '{:+.1%}')}  "
                     f"4 sigma {per_channel(K_SIGMA * sigma, '{:.1%}')}")
    asserted = ", ".join(ASSERTED_SPHERES.get(case, ())) or "none"
    header = (f"per sphere (pixels inside 70% of its radius; asserted within {SPHERE_TOL:.0%}: "
              f"{asserted}):")
    return [header, *lines] if lines else []


def test_feature_agrees_with_cycles(cycles_case: Renders, stratum_case: Renders,
                                    case: str) -> None:
    c, s = cycles_case, stratum_case
    _save_png(f"{case}_cycles", c.mean, linear_to_srgb=True)
    _save_png(f"{case}_stratum", s.mean, linear_to_srgb=True)
    _save_png(f"{case}_difference", difference_image(s.mean, c.mean), linear_to_srgb=False)
    flip = flip_ldr(s.mean, c.mean, f"{case}_flip")
    # For scale: FLIP between Cycles' two seeds, i.e. images with half the samples each.
    flip_noise = flip_ldr(c.mean + c.half_diff, c.mean - c.half_diff, f"{case}_flipnoise")
    report, img_rel, blk_rel, lit = _report(case, c, s, flip, flip_noise)
    report = "\n".join([report, *_sphere_lines(case, c, s)])
    (FEATURE_OUT / f"{case}_report.txt").write_text(report + "\n")
    print("\n" + report)
    assert (np.abs(img_rel) <= IMAGE_TOL).all(), f"image means differ:\n{report}"
    bad = lit & (np.abs(blk_rel) > BLOCK_TOL)
    assert not bad.any(), f"{int(bad.sum())} (block, channel) values differ:\n{report}"
    assert flip < FLIP_TOL, f"mean FLIP {flip:.4f} >= {FLIP_TOL}:\n{report}"
    for name in ASSERTED_SPHERES.get(case, ()):
        _, rel, _ = _sphere_stats(case, name, c, s)
        assert (np.abs(rel) <= SPHERE_TOL).all(), (
            f"sphere '{name}' differs by {per_channel(rel, '{:+.2%}')} "
            f"(tolerance {SPHERE_TOL:.0%}):"
            f"\n{report}")


# ---- instancing at scale (functional; its speed is measured by scripts/bench/speed.py) ---------

TEN_THOUSAND = 10_000


def build_instance_grid(count: int = TEN_THOUSAND) -> bpy.types.Scene:
    """count instances of one 8-vertex cube: a vertex-instancing parent with `count` vertices
    on a square grid (shared with scripts/bench/speed.py), a camera above it and a sun."""
    import math

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    side = math.ceil(math.sqrt(count))
    idx = np.arange(count)
    verts = np.zeros((count, 3))
    verts[:, 0] = (idx % side - (side - 1) / 2) * 0.1
    verts[:, 1] = (idx // side - (side - 1) / 2) * 0.1
    grid = bpy.data.meshes.new("grid")
    grid.vertices.add(count)
    grid.vertices.foreach_set("co", verts.astype(np.float32).ravel())
    grid.update()
    parent = bpy.data.objects.new("grid", grid)
    parent.instance_type = "VERTS"
    scene.collection.objects.link(parent)
    cube = bpy.data.meshes.new("cube")
    h = 0.03
    cube.from_pydata([(x, y, z) for z in (-h, h) for y in (-h, h) for x in (-h, h)], [],
                     [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2),
                      (1, 3, 7, 5)])
    cube.update()
    child = bpy.data.objects.new("cube", cube)
    child.parent = parent
    scene.collection.objects.link(child)
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.location = (0.0, 0.0, 12.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 3.0
    scene.collection.objects.link(sun)
    return scene


def test_ten_thousand_instances_export_as_one_mesh_and_render(library) -> None:
    from stratum import native
    from stratum.export.sync import export_scene

    scene = build_instance_grid()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    with native.Scene() as native_scene:
        summary = export_scene(depsgraph, native_scene)
    # Blender renders the vertex-instanced child object itself too (at its own transform), in
    # 3.4 and 5.0 alike: one instance more than the grid's vertices.
    assert summary.instances == TEN_THOUSAND + 1
    assert summary.meshes == 1, "10 000 instances of one mesh must send the mesh once"
    assert summary.triangles == 12

    r = scene.render
    r.engine = "STRATUM"
    r.resolution_x = r.resolution_y = 32
    r.resolution_percentage = 100
    scene.stratum.samples = 4
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    path = FEATURE_OUT / "ten_thousand_instances.exr"
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.exists():
        path.unlink()
    r.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    image = load_exr(path, 32)
    # The cubes cover 10000 * 0.06^2 = 36 m^2 of the 10 m x 10 m grid seen from 12 m by a
    # 50 mm camera (39.6 degrees: a 8.6 m square): lit cube tops and the black background
    # between them, so the image is neither empty nor uniform.
    assert image.mean() > 0.01 and image.std() > 0.01, (image.mean(), image.std())

