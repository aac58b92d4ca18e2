"""What the Blender-side benchmarks (scripts/bench/) share: the render settings both renderers
get, Cycles' status-line parsing, a Stratum render through the native Renderer, and the scenes
the export and memory sections build. Needs bpy (the pure parts, JSON results and the summary
table, are in results.py)."""

from __future__ import annotations

import contextlib
import fcntl
import math
import os
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, Self

import bpy
import numpy as np

from scripts import REPO

OUT = REPO / "out"
CACHE = OUT / "bench_cache"
CORNELL = REPO / "scenes" / "cornell_box.blend"
WOLF = REPO / "scenes" / "wolf.blend"
MATERIALS = REPO / "scenes" / "features" / "materials.blend"

MAX_BOUNCES = 8
FILTER_WIDTH = 1.5

# Inside the Blender executable sys.argv is Blender's; under the bpy wheel it is the script's.
IN_BLENDER = Path(sys.argv[0]).name.startswith("blender")


def script_argv() -> list[str]:
    """The script's own arguments: after '--' inside Blender, sys.argv[1:] under the wheel."""
    if IN_BLENDER:
        return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return sys.argv[1:]


def open_scene(path: Path, res: int, samples: int, threads: int = 0) -> bpy.types.Scene:
    """`path` opened with the settings both renderers share: res x res, `samples`, bounces 8,
    Blackman-Harris 1.5, `threads` (0 = all cores), Cycles on the CPU without adaptive
    sampling, denoising, clamping or glossy blur."""
    bpy.ops.wm.open_mainfile(filepath=str(path), load_ui=False)
    scene = bpy.context.scene
    r = scene.render
    r.resolution_x = r.resolution_y = res
    r.resolution_percentage = 100
    if threads > 0:
        r.threads_mode = "FIXED"
        r.threads = threads
    else:
        r.threads_mode = "AUTO"
    c = scene.cycles
    c.device = "CPU"
    c.samples = samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = MAX_BOUNCES
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.pixel_filter_type = "BLACKMAN_HARRIS"
    c.filter_width = FILTER_WIDTH
    return scene


def configure_stratum(scene: bpy.types.Scene, samples: int, threads: int = 0) -> None:
    """Stratum as the scene's engine with the shared settings; everything else (integrator,
    estimator, triangle sampling, sampler) stays at its default."""
    scene.render.engine = "STRATUM"
    s = scene.stratum
    s.samples = samples
    s.max_bounces = MAX_BOUNCES
    s.filter_type = "blackman_harris"
    s.filter_width = FILTER_WIDTH
    s.threads = threads


class CaptureStdout:
    """Captures what native code writes to file descriptor 1 (Blender's status lines), each line
    with the time.perf_counter() at which it arrived: Blender flushes every status line, and
    its own "Time:" field has a resolution of 10 ms, a third of Cycles' whole synchronisation of
    the 10 000-instance scene. A thread reads the pipe; Blender releases the GIL while it
    renders, and the pipe is widened so a burst of lines does not wait for the reader."""

    def __enter__(self) -> Self:
        sys.stdout.flush()
        self.lines: list[tuple[float, str]] = []
        read_end, write_end = os.pipe()
        with contextlib.suppress(OSError, AttributeError):  # Linux only; a wider buffer helps
            fcntl.fcntl(write_end, fcntl.F_SETPIPE_SZ, 1 << 20)
        self._saved = os.dup(1)
        os.dup2(write_end, 1)
        os.close(write_end)
        self._reader = threading.Thread(target=self._read, args=(read_end,), daemon=True)
        self._reader.start()
        return self

    def _read(self, fd: int) -> None:
        pending = b""
        with os.fdopen(fd, "rb", buffering=0) as pipe:
            while chunk := pipe.read(1 << 16):
                now = time.perf_counter()
                *complete, pending = (pending + chunk).split(b"\n")
                self.lines += [(now, line.decode("utf-8", "replace")) for line in complete]
        if pending:
            self.lines.append((time.perf_counter(), pending.decode("utf-8", "replace")))

    def __exit__(self, *exc: object) -> None:
        sys.stdout.flush()
        try:
            import ctypes

            ctypes.CDLL(None).fflush(None)  # flush C stdio buffers into the capture
        except (OSError, AttributeError) as err:  # best effort: lines may be lost, not numbers
            print(f"bench: could not flush C stdio: {err}", file=sys.stderr)
        os.dup2(self._saved, 1)  # closes the pipe's last write end: the reader sees its end
        os.close(self._saved)
        self._reader.join()
        self.text = "\n".join(line for _, line in self.lines)


def cycles_split(lines: list[tuple[float, str]], start: float) -> tuple[float | None, float | None]:
    """(seconds from `start` to the first 'Sample' status line, to the last status line), from
    the arrival times of CaptureStdout's lines."""
    first_sample = last = None
    for t, line in lines:
        if not line.startswith("Fra:"):
            continue
        if "| Sample " in line and first_sample is None:
            first_sample = t - start
        last = t - start
    return first_sample, last


def cycles_sync_stages(lines: list[tuple[float, str]]) -> dict[str, float | None]:
    """Seconds of Cycles' object sync and scene update, from the arrival times of its status
    lines (CaptureStdout), which read
    "Fra:1 Mem:.. | Time:00:00.22 | Mem:.., Peak:.. | Scene, ViewLayer | <stage> | <detail>"."""
    first_sync = initializing = sample0 = None
    for t, line in lines:
        parts = [p.strip() for p in line.split("|")]
        at = next((i for i, p in enumerate(parts) if p.startswith("Time:")), None)
        if not line.startswith("Fra:") or at is None or len(parts) <= at + 3:
            continue
        stage = parts[at + 3]
        if stage.startswith("Synchronizing") and first_sync is None:
            first_sync = t
        elif stage.startswith("Initializing") and initializing is None:
            initializing = t
        elif stage.startswith("Sample 0") and sample0 is None:
            sample0 = t
    if first_sync is None or initializing is None or sample0 is None:
        return {"object_sync": None, "scene_update": None, "sync_total": None}
    return {"object_sync": initializing - first_sync, "scene_update": sample0 - initializing,
            "sync_total": sample0 - first_sync}


def render_cycles(scene: bpy.types.Scene, write_exr: Path | None = None,
                  ) -> dict[str, float | None]:
    """F12 with Cycles: the total, the sync (before the first 'Sample' line) and the path
    tracing time (the rest, from the status lines; None under the bpy wheel, which prints
    none). With `write_exr`, the result is also saved there as a 32-bit linear EXR."""
    scene.render.engine = "CYCLES"
    if write_exr is not None:
        settings = scene.render.image_settings
        settings.file_format = "OPEN_EXR"
        settings.color_depth = "32"
        settings.color_mode = "RGBA"
        scene.render.use_file_extension = False
        scene.render.filepath = str(write_exr)
    with CaptureStdout() as cap:
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=write_exr is not None)
        total = time.perf_counter() - t0
    sync, last = cycles_split(cap.lines, t0)
    trace = (last - sync) if (sync is not None and last is not None) else None
    return {"total": total, "sync": sync, "trace": trace}


def read_exr_rgb(path: Path) -> np.ndarray:
    """The RGB of an EXR as float64 (height, width, 3), through Blender's image loader (EXR
    float buffers are loaded unchanged: scene-linear)."""
    image = bpy.data.images.load(str(path))
    try:
        width, height = image.size
        pixels = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)[:, :, :3].astype(np.float64)


def stratum_reason() -> str:
    """'' when Stratum can render here (the add-on is then registered), else why not."""
    try:
        import stratum
        from stratum import native
    except ImportError as exc:
        return f"add-on not importable: {exc}"
    try:
        native.load_library()
    except native.StratumError as exc:
        return str(exc)
    if not hasattr(bpy.types.Scene, "stratum"):
        stratum.register()
    return ""


def stratum_library_id() -> str:
    """The first 16 hex digits of libstratum.so's SHA-256: the renderer's version in cache
    keys (the package version does not change with the library)."""
    import hashlib

    from stratum import native

    return hashlib.sha256(Path(native.load_library()._name).read_bytes()).hexdigest()[:16]


class StratumScene:
    """The scene's render geometry exported once into a native scene; render() then runs the
    native Renderer with the scene's settings plus `overrides`, as many times as asked. The
    settings are read here, so renders may follow after another file was opened."""

    def __init__(self, scene: bpy.types.Scene) -> None:
        from stratum import native
        from stratum.engine.frame import renderer_settings
        from stratum.export.sync import export_scene

        self.settings = renderer_settings(scene)
        from stratum.export.render_geometry import use_render_geometry

        use_render_geometry(scene)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        depsgraph.update()
        self.native = native.Scene()
        t0 = time.perf_counter()
        self.summary = export_scene(depsgraph, self.native)
        self.export_seconds = time.perf_counter() - t0

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *exc: object) -> None:
        self.native.close()

    def render(self, overrides: dict[str, int | float | str] | None = None,
               pixels: bool = False, passes: tuple[str, ...] = ()) -> dict[str, Any]:
        """One render: build and path-tracing seconds, wall time start -> done, rays, samples
        per second (pixels x samples / path-tracing seconds) and, with `pixels`, the linear RGB
        as float64 (height, width, 3); each of `passes` (which the overrides' "passes" must
        hold) under its name."""
        from stratum import native

        settings = self.settings | (overrides or {})
        with native.Renderer(self.native) as renderer:
            for name, value in settings.items():
                renderer.set(name, value)
            t0 = time.perf_counter()
            renderer.start()
            while not renderer.wait(50):
                pass
            wall = time.perf_counter() - t0
            p = renderer.progress()
            width, height = renderer.image_size
            out: dict[str, Any] = {
                "build": p.build_seconds, "trace": p.render_seconds, "wall": wall,
                "rays": p.rays, "samples_done": p.samples_done,
                "light_tree_seconds": p.counter("light_tree.seconds"),
                "light_tree_bytes": p.counter("light_tree.bytes"),
                "samples_per_s": (width * height * p.samples_done / p.render_seconds
                                  if p.render_seconds > 0 else 0.0)}
            if pixels:
                rgba = renderer.read_pixels().reshape(height, width, 4)
                out["rgb"] = rgba[:, :, :3].astype(np.float64)
            for name in passes:
                out[name] = renderer.read_pass(name)
        return out


def run_main(main: Callable[[], int]) -> None:
    """Runs main and exits with its status; inside Blender through os._exit, since Blender's
    --python does not propagate sys.exit codes reliably."""
    import traceback

    code = 1
    try:
        code = main()
    except Exception:  # noqa: BLE001 - printed, status 1
        traceback.print_exc()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
    if IN_BLENDER:
        os._exit(code)
    sys.exit(code)


# ---- the 1M-triangle and 10 000-instance scenes (export and memory sections) ------------------

EXPORT_RES = 32
MONKEY_LEVELS = 5  # 1968 quads after the first level, x4 per further level: 503 808 quads
INSTANCES = 10_000


def _bmesh() -> Any:
    """bmesh, importable only once bpy is (the bpy wheel registers it on import)."""
    import bmesh

    return bmesh


def _empty_scene() -> bpy.types.Scene:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    cam.location = (0.0, -4.0, 0.0)
    cam.rotation_euler = (math.pi / 2, 0.0, 0.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.rotation_euler = (0.6, 0.0, 0.4)
    scene.collection.objects.link(sun)
    r = scene.render
    r.resolution_x = r.resolution_y = EXPORT_RES
    r.resolution_percentage = 100
    c = scene.cycles
    c.device = "CPU"
    c.samples = 1
    c.use_denoising = False
    c.use_adaptive_sampling = False
    return scene


def build_monkey_1m() -> bpy.types.Scene:
    """Suzanne with MONKEY_LEVELS Catmull-Clark levels applied to its mesh (no modifier left:
    neither renderer's timing includes the subdivision)."""
    scene = _empty_scene()
    bmesh = _bmesh()
    bm = bmesh.new()
    bmesh.ops.create_monkey(bm)
    base = bpy.data.meshes.new("monkey")
    bm.to_mesh(base)
    bm.free()
    ob = bpy.data.objects.new("monkey", base)
    scene.collection.objects.link(ob)
    mod = ob.modifiers.new("subdivision", "SUBSURF")
    mod.levels = mod.render_levels = MONKEY_LEVELS
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    dense = bpy.data.meshes.new_from_object(ob.evaluated_get(depsgraph))
    ob.modifiers.clear()
    ob.data = dense
    return scene


def build_monkey_1m_smooth() -> bpy.types.Scene:
    """The same monkey shade-smooth: Stratum then sends 3 normals per triangle (its only normal
    format), Cycles vertex normals."""
    scene = build_monkey_1m()
    mesh = scene.objects["monkey"].data
    mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
    mesh.update()
    return scene


def build_instances_10k() -> bpy.types.Scene:
    """INSTANCES instances of one cube: a parent whose vertices (a square grid) instance its
    child (instance_type VERTS); Blender also renders the child itself."""
    scene = _empty_scene()
    side = math.ceil(math.sqrt(INSTANCES))
    idx = np.arange(INSTANCES)
    verts = np.zeros((INSTANCES, 3), dtype=np.float32)
    verts[:, 0] = (idx % side - (side - 1) / 2) * 0.03
    verts[:, 2] = (idx // side - (side - 1) / 2) * 0.03
    grid = bpy.data.meshes.new("grid")
    grid.vertices.add(INSTANCES)
    grid.vertices.foreach_set("co", verts.ravel())
    grid.update()
    parent = bpy.data.objects.new("grid", grid)
    parent.instance_type = "VERTS"
    scene.collection.objects.link(parent)
    bmesh = _bmesh()
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=0.01)
    cube = bpy.data.meshes.new("cube")
    bm.to_mesh(cube)
    bm.free()
    child = bpy.data.objects.new("cube", cube)
    child.parent = parent
    scene.collection.objects.link(child)
    return scene


def build_emissive_100k() -> bpy.types.Scene:
    """A flat grid of EMISSIVE_SIDE^2 quads (100 352 triangles) with an Emission material, seen
    from the camera: every triangle is a light, so Stratum's default light selection (auto)
    builds its light tree over 100k leaves (issue 16: "build time and memory reported")."""
    scene = _empty_scene()
    bmesh = _bmesh()
    bm = bmesh.new()
    bmesh.ops.create_grid(bm, x_segments=EMISSIVE_SIDE, y_segments=EMISSIVE_SIDE, size=1.0)
    mesh = bpy.data.meshes.new("emitter")
    bm.to_mesh(mesh)
    bm.free()
    material = bpy.data.materials.new("emission")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 2.0
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])
    mesh.materials.append(material)
    ob = bpy.data.objects.new("emitter", mesh)
    ob.rotation_euler = (math.pi / 2, 0.0, 0.0)
    scene.collection.objects.link(ob)
    return scene


EMISSIVE_SIDE = 224  # 224^2 quads = 100 352 triangles

EXPORT_CASES: tuple[tuple[str, Callable[[], bpy.types.Scene]], ...] = (
    ("monkey_1m", build_monkey_1m), ("monkey_1m_smooth", build_monkey_1m_smooth),
    ("instances_10k", build_instances_10k), ("emissive_100k", build_emissive_100k))
