"""What the Cycles-vs-Stratum agreement tests share: the peer settings (configure_cycles,
configure_stratum), the parts of the scenes they build (new_scene, add_diffuse_floor,
add_camera), rendering a scene with two seeds (render_two_seeds) into `Renders` with their noise
estimates, the noise gate (noise_failures, block_noise), the comparisons at the image and block
tolerances (compare; assert_agreement for the small built scenes) and the human-readable output.

Used by test_cycles_agreement.py, whose docstring derives the tolerances and the statistics,
and by the camera, light, environment, estimator and feature agreement tests.
"""

from __future__ import annotations

import time
from pathlib import Path

import bpy
import numpy as np

from exr_file import read_image

REPO = Path(__file__).resolve().parents[2]
SCENE = REPO / "scenes" / "cornell_box.blend"
# One folder per Blender, so a 3.4 run and a 5.0 run do not overwrite each other's images.
OUT = REPO / "out" / "agreement" / f"blender-{bpy.app.version_string.split()[0]}"

RES = 64
SPP_PER_SEED = 1024  # two seeds -> N = 2048 samples per pixel in each compared image
SEEDS = (1, 2)
MAX_BOUNCES = 8
FILTER_WIDTH = 1.5
BLOCK = 16
IMAGE_TOL = 0.02  # relative, per channel
BLOCK_TOL = 0.05  # relative, per channel and block
DARK_BLOCK = 0.01  # blocks whose Cycles mean is below this are not compared
K_SIGMA = 4.0
DIFF_GAIN = 4.0
CHANNELS = "RGB"


# ---- rendering -----------------------------------------------------------------------------


def set_frame_and_exr(scene: bpy.types.Scene, res: int) -> None:
    """What every compared render shares: res x res at 100 %, the whole frame, all threads, a
    32-bit float RGBA EXR (half floats would hide differences at the tolerances)."""
    r = scene.render
    r.resolution_x = r.resolution_y = res
    r.resolution_percentage = 100
    r.use_border = False
    r.threads_mode = "AUTO"
    settings = r.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.color_mode = "RGBA"
    settings.exr_codec = "ZIP"


def new_scene(res: int) -> bpy.types.Scene:
    """An empty scene on the factory settings, res x res (set_frame_and_exr), with an opaque
    film and the Standard view transform."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    set_frame_and_exr(scene, res)
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    return scene


def add_diffuse_floor(scene: bpy.types.Scene, half_size: float) -> None:
    """A square plane at z = 0, 2 half_size on a side, whose material is one Diffuse BSDF
    (0.8 grey)."""
    mat = bpy.data.materials.new("floor")
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    for n in list(nodes):
        if n.bl_idname != "ShaderNodeOutputMaterial":
            nodes.remove(n)
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    mat.node_tree.links.new(diffuse.outputs[0], nodes["Material Output"].inputs["Surface"])
    mesh = bpy.data.meshes.new("floor")
    h = half_size
    mesh.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(mat)
    scene.collection.objects.link(bpy.data.objects.new("floor", mesh))


def add_camera(scene: bpy.types.Scene, lens_mm: float, location: tuple[float, float, float],
               rotation: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> None:
    """The scene's camera: a perspective one fitted to a 36 mm wide sensor (lens_mm sets the
    horizontal angle, 2 atan(18 / lens_mm)) at `location`, Euler `rotation` (XYZ)."""
    cam = bpy.data.cameras.new("cam")
    cam.sensor_fit = "HORIZONTAL"
    cam.sensor_width = 36.0
    cam.lens = lens_mm
    camera = bpy.data.objects.new("cam", cam)
    camera.location = location
    camera.rotation_euler = rotation
    scene.collection.objects.link(camera)
    scene.camera = camera


def image_world(scene: bpy.types.Scene, name: str, rgba: np.ndarray) -> bpy.types.World:
    """The scene's world: a float image of rgba ((h, w, 4), rows bottom (nadir) to top, as
    Blender stores them) through an Environment Texture with Closest lookup into the Background
    node's Color (texels compare exactly between the engines)."""
    h, w = rgba.shape[:2]
    image = bpy.data.images.new(name, w, h, alpha=True, float_buffer=True)
    image.pixels.foreach_set(rgba.reshape(-1))
    image.update()
    world = bpy.data.worlds.new(name)
    world.use_nodes = True
    nodes = world.node_tree.nodes
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = image
    env.interpolation = "Closest"
    world.node_tree.links.new(env.outputs["Color"], nodes["Background"].inputs["Color"])
    scene.world = world
    return world


def add_top_ortho_camera(scene: bpy.types.Scene, scale: float = 2.0,
                         height: float = 3.0) -> None:
    """The scene's camera: orthographic, `scale` wide, at (0, 0, height) looking down -Z (the
    node and bump tests' view of a quad in z = 0)."""
    cam = bpy.data.cameras.new("cam")
    cam.type = "ORTHO"
    cam.ortho_scale = scale
    camera = bpy.data.objects.new("cam", cam)
    camera.location = (0.0, 0.0, height)
    scene.collection.objects.link(camera)
    scene.camera = camera


def render_pixel_centres(scene: bpy.types.Scene, engine: str, path: Path, res: int,
                         max_bounces: int | None = None) -> np.ndarray:
    """One sample per pixel through a 0.01 px box filter, by Cycles (CPU, no denoising) or
    Stratum: each pixel's value at its centre, so that the two compare exactly."""
    scene.render.engine = engine
    if engine == "CYCLES":
        c = scene.cycles
        c.device, c.samples, c.use_denoising = "CPU", 1, False
        c.pixel_filter_type, c.filter_width = "BOX", 0.01
        if max_bounces is not None:
            c.max_bounces = max_bounces
    else:
        s = scene.stratum
        s.light_paths = "STRATUM"  # its own bounces (below), not those of a file tuned for Cycles
        s.samples, s.filter_type, s.filter_width = 1, "box", 0.01
        if max_bounces is not None:
            s.max_bounces = max_bounces
    path.parent.mkdir(parents=True, exist_ok=True)
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    return load_exr(path, res)


def open_scene() -> bpy.types.Scene:
    bpy.ops.wm.open_mainfile(filepath=str(SCENE), load_ui=False)
    scene = bpy.context.scene
    set_frame_and_exr(scene, RES)
    scene.render.film_transparent = False
    return scene


def configure_cycles(scene: bpy.types.Scene, seed: int, *, samples: int = SPP_PER_SEED,
                     max_bounces: int = MAX_BOUNCES) -> None:
    """Cycles as the peer: CPU, no denoising, adaptive sampling, clamping or glossy blur, every
    bounce limit equal to max_bounces, Stratum's pixel filter. Shared by the other agreement
    tests."""
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = samples
    c.seed = seed
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = max_bounces
    c.diffuse_bounces = max_bounces
    c.glossy_bounces = max_bounces
    c.transmission_bounces = max_bounces
    c.volume_bounces = 0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.light_sampling_threshold = 0.0
    c.pixel_filter_type = "BLACKMAN_HARRIS"
    c.filter_width = FILTER_WIDTH
    if hasattr(c, "use_layer_samples"):
        c.use_layer_samples = "IGNORE"


def configure_stratum(scene: bpy.types.Scene, seed: int, *, samples: int = SPP_PER_SEED,
                      max_bounces: int = MAX_BOUNCES) -> None:
    """Stratum with the same samples, bounces and pixel filter as configure_cycles: its own
    Light Paths settings, unlimited per kind and unclamped as configure_cycles sets Cycles'."""
    scene.render.engine = "STRATUM"
    s = scene.stratum
    s.light_paths = "STRATUM"
    s.samples = samples
    s.seed = seed
    s.max_bounces = max_bounces
    s.filter_type = "blackman_harris"
    s.filter_width = FILTER_WIDTH
    s.threads = 0


def render_exr(scene: bpy.types.Scene, path: Path, res: int = RES) -> tuple[np.ndarray, float]:
    """Renders the scene to a linear EXR and returns (res x res x 3 float64, seconds)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.exists():
        path.unlink()
    scene.render.filepath = str(path)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    seconds = time.perf_counter() - t0
    assert path.is_file(), f"render did not write {path}"
    return load_exr(path, res), seconds


def load_exr(path: Path, res: int = RES) -> np.ndarray:
    """The EXR's RGB as float64 (res, res, 3), rows bottom to top as Blender stores them."""
    rgba = read_image(path)
    h, w = rgba.shape[:2]
    assert (w, h) == (res, res), f"{path}: size {w}x{h}, expected {res}x{res}"
    return rgba[..., :3].astype(np.float64)


class Renders:
    """Two seeds of one renderer: their mean (the compared image) and noise estimates."""

    def __init__(self, name: str, images: list[np.ndarray], seconds: list[float],
                 block: int = BLOCK) -> None:
        a, b = images
        self.name = name
        self.block = block  # side of the compared blocks, in pixels
        self.res = a.shape[0]
        self.seconds = seconds
        self.mean = (a + b) / 2.0
        half = (a - b) / 2.0
        self.half_diff = half
        self.pixel_var = half**2  # unbiased estimate of Var[mean_p] per pixel and channel
        self.inflation = 1.0  # >1 when pixels are correlated (see module docstring)

    def block_mean(self) -> np.ndarray:
        return _blocks(self.mean, self.block).mean(axis=(1, 3))

    def block_var(self) -> np.ndarray:
        n = self.block * self.block
        return _blocks(self.pixel_var, self.block).sum(axis=(1, 3)) / n**2 * self.inflation**2

    def image_var(self) -> np.ndarray:
        return self.pixel_var.sum(axis=(0, 1)) / (self.res * self.res) ** 2 * self.inflation**2

    def calibrate(self) -> float:
        """sqrt(mean z^2) of the block means of the half-difference image (1 if pixels are
        independent); sigmas are inflated by it when it is above 1."""
        n = self.block * self.block
        hb = _blocks(self.half_diff, self.block).mean(axis=(1, 3))
        vb = _blocks(self.pixel_var, self.block).sum(axis=(1, 3)) / n**2
        ok = vb > 0
        ratio = float(np.sqrt(np.mean(hb[ok] ** 2 / vb[ok]))) if ok.any() else 1.0
        self.inflation = max(1.0, ratio)
        return ratio


def _blocks(img: np.ndarray, block: int = BLOCK) -> np.ndarray:
    nb = img.shape[0] // block
    return img.reshape(nb, block, nb, block, img.shape[-1])


def render_two_seeds(name: str, configure, out: Path = OUT, open_scene=open_scene, *,
                     res: int = RES, block: int = BLOCK) -> Renders:
    """The scene open_scene() opens or builds (the Cornell box by default; res x res) rendered
    with seeds SEEDS, configure(scene, seed) choosing the renderer and its settings, compared in
    blocks of block x block pixels; EXRs in out/<name>_seed<seed>.exr."""
    images, seconds = [], []
    for seed in SEEDS:
        scene = open_scene()
        configure(scene, seed)
        img, sec = render_exr(scene, out / f"{name}_seed{seed}.exr", res)
        images.append(img)
        seconds.append(sec)
    renders = Renders(name, images, seconds, block)
    renders.calibrate()
    return renders


def stratum_available() -> str:
    """'' when the STRATUM engine can render, else the reason it cannot."""
    try:
        import stratum  # noqa: F401
        from stratum import native
    except ImportError as exc:
        return f"stratum add-on not importable: {exc}"
    if not native.library_available():
        try:
            native.load_library()
        except native.StratumError as exc:
            return str(exc)
    if not any(getattr(cls, "bl_idname", "") == "STRATUM"
               for cls in bpy.types.RenderEngine.__subclasses__()):
        return "STRATUM render engine is not registered"
    return ""


# ---- output for humans -----------------------------------------------------------------------


def save_png(name: str, rgb: np.ndarray, *, linear_to_srgb: bool, out: Path = OUT) -> None:
    """Writes rgb (rows bottom to top, linear unless told) as an 8-bit PNG in out."""
    out.mkdir(parents=True, exist_ok=True)
    x = np.clip(rgb, 0.0, 1.0)
    if linear_to_srgb:  # the 'Standard' view transform: plain sRGB encoding
        x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)
    rgba = np.concatenate([x, np.ones(x.shape[:2] + (1,))], axis=-1).astype(np.float32)
    image = bpy.data.images.new(name, RES, RES, alpha=True)  # byte buffer: stored as is
    try:
        image.pixels.foreach_set(rgba.ravel())
        image.filepath_raw = str(out / f"{name}.png")
        image.file_format = "PNG"
        image.save()
    finally:
        bpy.data.images.remove(image)


def difference_image(s: np.ndarray, c: np.ndarray) -> np.ndarray:
    d = (s - c).mean(axis=-1) * DIFF_GAIN
    out = np.zeros(s.shape)
    out[..., 0] = np.maximum(d, 0.0)
    out[..., 2] = np.maximum(-d, 0.0)
    return out


def per_channel(v: np.ndarray, fmt: str = "{:.4f}") -> str:
    """One value per channel as "R=... G=... B=...", each formatted by fmt."""
    return " ".join(f"{ch}={fmt.format(x)}" for ch, x in zip(CHANNELS, v))


# ---- noise gate and comparison ----------------------------------------------------------------


def noise_failures(reference: Renders, candidate: Renders) -> list[str]:
    """Why the two renders' noise would make a comparison at IMAGE_TOL / BLOCK_TOL meaningless
    ([] when it does not): 4 sigma_D of the image-mean difference must be below half the image
    tolerance, and below the block tolerance for every compared block (those whose reference
    mean is >= DARK_BLOCK). Relative to the reference's means."""
    failures = []
    c_img = reference.mean.mean(axis=(0, 1))
    sd_img = np.sqrt(reference.image_var() + candidate.image_var())
    if not (K_SIGMA * sd_img < 0.5 * IMAGE_TOL * c_img).all():
        failures.append(
            f"image-mean noise too high for a {IMAGE_TOL:.0%} test: 4 sigma_D = "
            f"{per_channel(K_SIGMA * sd_img / c_img, '{:.3%}')}")
    cb = reference.block_mean()
    lit = cb >= DARK_BLOCK
    rel = K_SIGMA * np.sqrt(reference.block_var() + candidate.block_var()) / np.maximum(cb, 1e-12)
    bad = np.argwhere(lit & (rel >= BLOCK_TOL))
    if bad.size:
        failures.append(
            f"{len(bad)} blocks too noisy for a {BLOCK_TOL:.0%} test (4 sigma_D >= tolerance); "
            f"worst {float(rel[lit].max()):.2%}; correlation factors {candidate.name} "
            f"{candidate.inflation:.2f}, {reference.name} {reference.inflation:.2f}")
    return failures


def block_noise(reference: Renders, candidate: Renders) -> tuple[float, float]:
    """(median, worst) 4 sigma_D of the compared blocks, relative to the reference's means."""
    cb = reference.block_mean()
    lit = cb >= DARK_BLOCK
    rel = K_SIGMA * np.sqrt(reference.block_var() + candidate.block_var()) / np.maximum(cb, 1e-12)
    return float(np.median(rel[lit])), float(rel[lit].max())


def compare(reference: Renders, candidate: Renders, out: Path, header: str) -> tuple[str, bool]:
    """Compares candidate with reference (image means within IMAGE_TOL, every compared block
    within BLOCK_TOL, relative to the reference) and writes out/report.txt, the sRGB images
    and the difference image. Returns (report, agree)."""
    s, c = candidate.mean, reference.mean
    save_png(reference.name, c, linear_to_srgb=True, out=out)
    save_png(candidate.name, s, linear_to_srgb=True, out=out)
    save_png("difference", difference_image(s, c), linear_to_srgb=False, out=out)

    c_img, s_img = c.mean(axis=(0, 1)), s.mean(axis=(0, 1))
    img_rel = (s_img - c_img) / c_img
    img_sigma = np.sqrt(reference.image_var() + candidate.image_var()) / c_img
    cb, sb = reference.block_mean(), candidate.block_mean()
    sigma_b = np.sqrt(reference.block_var() + candidate.block_var())
    lit = cb >= DARK_BLOCK
    blk_rel = np.where(lit, (sb - cb) / np.maximum(cb, 1e-12), 0.0)
    bad = np.argwhere(lit & (np.abs(blk_rel) > BLOCK_TOL))

    nb = RES // BLOCK
    width = max(len(reference.name), len(candidate.name))
    lines = [
        header,
        (f"render seconds: {reference.name} {reference.seconds}, {candidate.name} "
         f"{candidate.seconds}"),
        f"image mean {reference.name:<{width}}: {per_channel(c_img)}",
        f"image mean {candidate.name:<{width}}: {per_channel(s_img)}",
        f"relative diff     : {per_channel(img_rel, '{:+.3%}')}   (tolerance {IMAGE_TOL:.0%})",
        f"1 sigma of diff   : {per_channel(img_sigma, '{:.3%}')}",
        (f"pixel-correlation factors: {reference.name} {reference.inflation:.2f}, "
         f"{candidate.name} {candidate.inflation:.2f}"),
        (f"blocks ({BLOCK}x{BLOCK}, row 0 = top), relative diff per channel"
         f" (tolerance {BLOCK_TOL:.0%}; '.' = dark, not compared):"),
    ]
    for by in reversed(range(nb)):  # print top row first
        row = []
        for bx in range(nb):
            if not lit[by, bx].all():
                row.append("        .        ")
            else:
                row.append("/".join(f"{100 * v:+5.1f}" for v in blk_rel[by, bx]))
        lines.append("  " + "  ".join(row))
    order = np.argsort(-np.abs(blk_rel).max(axis=-1).ravel())[:5]
    lines.append("worst blocks (row from top, col): rel diff, z = diff / sigma")
    for flat in order:
        by, bx = divmod(int(flat), nb)
        z = (sb[by, bx] - cb[by, bx]) / np.maximum(sigma_b[by, bx], 1e-12)
        lines.append(f"  ({nb - 1 - by},{bx}) {reference.name} {per_channel(cb[by, bx])}  "
                     f"rel {per_channel(blk_rel[by, bx], '{:+.2%}')}  "
                     f"z {per_channel(z, '{:+.1f}')}")
    report = "\n".join(lines)
    out.mkdir(parents=True, exist_ok=True)
    (out / "report.txt").write_text(report + "\n")
    agree = bool((np.abs(img_rel) <= IMAGE_TOL).all()) and bad.size == 0
    return report, agree



def assert_agreement(reference: Renders, candidate: Renders, compared: np.ndarray, title: str,
                     out: Path, *, image_tol: float = IMAGE_TOL,
                     block_tol: float = BLOCK_TOL) -> None:
    """Asserts per RGB channel that the candidate's image mean is within image_tol of the
    reference's and its block means within block_tol where `compared` (per block and channel)
    holds, relative to the reference. First asserts that 4 sigma of every such difference is
    below half its tolerance, so that a failure is a difference of models, not noise. The report
    (headed by title, a '.' per block not compared) is printed and written to out/report.txt."""
    c, s = reference, candidate
    c_img, s_img = c.mean.mean(axis=(0, 1)), s.mean.mean(axis=(0, 1))
    img_sigma = np.sqrt(c.image_var() + s.image_var())
    cb, sb = c.block_mean(), s.block_mean()
    sigma_b = np.sqrt(c.block_var() + s.block_var())
    rel_noise = K_SIGMA * sigma_b / np.maximum(cb, 1e-12)
    assert (K_SIGMA * img_sigma < 0.5 * image_tol * c_img).all()
    assert (K_SIGMA * sigma_b[compared] < 0.5 * block_tol * cb[compared]).all(), (
        f"block noise too high: worst 4 sigma {float(rel_noise[compared].max()):.2%}")

    img_rel = (s_img - c_img) / c_img
    blk_rel = np.where(compared, (sb - cb) / np.maximum(cb, 1e-12), 0.0)
    nb = c.res // c.block
    report = (f"{title}, Blender {bpy.app.version_string}: image mean {c.name} "
              f"{per_channel(c_img)}, {s.name} {per_channel(s_img)}, "
              f"rel {per_channel(img_rel, '{:+.3%}')}; blocks: worst rel "
              f"{float(np.abs(blk_rel).max()):+.2%}, worst 4 sigma "
              f"{float(rel_noise[compared].max()):.2%}\n"
              + "\n".join("  " + " ".join(
                  f"{100 * blk_rel[by, bx].mean():+7.2f}%" if compared[by, bx].all()
                  else "    .   " for bx in range(nb)) for by in reversed(range(nb))))
    out.mkdir(parents=True, exist_ok=True)
    (out / "report.txt").write_text(report + "\n")
    print("\n" + report)
    assert (np.abs(img_rel) <= image_tol).all(), report
    assert (np.abs(blk_rel) <= block_tol).all(), report
