"""Stratum vs Cycles on the Cornell box: same resolution, samples, bounces, filter, threads.

    blender -b --factory-startup --python scripts/bench.py [-- --samples 64 --res 256]
    blender -b --factory-startup --python scripts/bench.py -- --only export   # acceptance 3 only

(also runs under the bpy wheel: .venv/bin/python scripts/bench.py). Prints a table and writes
it to out/bench.txt. Reported:

* Cycles: total F12 time (bpy.ops.render.render) and its split into scene synchronisation
  (everything before the first "Sample" status line) and path tracing, parsed from the status
  lines Blender prints in background mode (captured from file descriptor 1 during the render);
* Stratum, through the add-on's exporter and stratum.native.Renderer directly: export time
  (depsgraph -> native scene), BVH build time and path-tracing time as reported by the native
  library (progress().build_seconds / render_seconds), and the wall time start -> done;
* Stratum total F12 time through the engine, comparable with Cycles' F12 time;
* the ratios Stratum / Cycles (total, and path tracing alone), measured in this one run.

Then the export section (acceptance 3 of issue 5), each scene built in this script:

* monkey_1m: Suzanne subdivided 5 times (Catmull-Clark, applied: 503 808 quads = 1 007 616
  triangles, one object), a camera and a sun;
* instances_10k: 10 000 instances of one 12-triangle cube (vertex instancing) plus the child
  object itself, a camera and a sun.

For each, Stratum's export (depsgraph -> native scene, timed around export_scene) and BVH build
(progress().build_seconds of a 1-sample 32 x 32 render) against Cycles' synchronisation of the
same scene, read from the status lines Cycles prints during a 1-sample 32 x 32 render (Blender
3.4's `blender -b`; the bpy module prints none, so there only the F12 total is given):

* "Cycles object sync": first "Synchronizing object" line -> "Initializing" (Blender data ->
  Cycles scene: meshes, instances, shaders);
* "Cycles scene update": "Initializing" -> "Sample 0" (device update: attributes, normals, the
  BVH build, lights, copies to the device);
* "Cycles sync total" = both: Cycles' whole synchronisation, the analogue of Stratum's export +
  BVH build (Blender's own depsgraph evaluation precedes both renderers and is in neither).

Then the live edit (issue 13, acceptance 3): monkey_1m rendered once, then moved through the
live scene (stratum_scene_set_instance) and rendered again by the same renderer, whose start
applies the edit in place: the update time against the full BVH build, with the `bvh` layout
dynamic (every mesh instanced: a top-level recommit; target under 5 %) and static (the single
placement flattened: its vertices remapped and its BVH rebuilt).

Each export measurement is repeated --repeats times (default 3) and the minimum of each
quantity reported (other processes on shared cores only add time). The ratio
(Stratum export + BVH) / (Cycles sync total) comes from this one run.

Exit status: 0 when both renderers ran, 2 when Stratum is not available (Cycles numbers are
still printed), 1 on an error.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
import tempfile
import time
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any, Self

import bpy
import numpy as np

REPO = Path(__file__).resolve().parents[1]
SCENE = REPO / "scenes" / "cornell_box.blend"
OUT = REPO / "out"
ADDON_DIR = REPO / "addon"

MAX_BOUNCES = 8
FILTER_WIDTH = 1.5


# Inside the Blender executable sys.argv is Blender's; under the bpy wheel it is the script's.
IN_BLENDER = Path(sys.argv[0]).name.startswith("blender")


def parse_args() -> argparse.Namespace:
    if IN_BLENDER:
        argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    else:
        argv = sys.argv[1:]
    p = argparse.ArgumentParser(prog="bench.py")
    p.add_argument("--samples", type=int, default=64)
    p.add_argument("--res", type=int, default=256)
    p.add_argument("--threads", type=int, default=0, help="0 = all cores")
    p.add_argument("--scene", type=Path, default=SCENE)
    p.add_argument("--repeats", type=int, default=3,
                   help="runs of each export measurement (the minimum is reported)")
    p.add_argument("--only", choices=("render", "export"), default=None,
                   help="run only the Cornell box render comparison or only the export section")
    return p.parse_args(argv)


def open_scene(args: argparse.Namespace) -> bpy.types.Scene:
    bpy.ops.wm.open_mainfile(filepath=str(args.scene), load_ui=False)
    scene = bpy.context.scene
    r = scene.render
    r.resolution_x = r.resolution_y = args.res
    r.resolution_percentage = 100
    if args.threads > 0:
        r.threads_mode = "FIXED"
        r.threads = args.threads
    else:
        r.threads_mode = "AUTO"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = MAX_BOUNCES
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.pixel_filter_type = "BLACKMAN_HARRIS"
    c.filter_width = FILTER_WIDTH
    return scene


def configure_stratum(scene: bpy.types.Scene, args: argparse.Namespace) -> None:
    scene.render.engine = "STRATUM"
    s = scene.stratum
    s.samples = args.samples
    s.max_bounces = MAX_BOUNCES
    s.filter_type = "blackman_harris"
    s.filter_width = FILTER_WIDTH
    s.threads = args.threads


class CaptureStdout:
    """Captures what native code writes to file descriptor 1 (Blender's status lines)."""

    def __enter__(self) -> Self:
        sys.stdout.flush()
        self._tmp = tempfile.TemporaryFile(mode="w+b")
        self._saved = os.dup(1)
        os.dup2(self._tmp.fileno(), 1)
        return self

    def __exit__(self, *exc: object) -> None:
        sys.stdout.flush()
        try:
            import ctypes

            ctypes.CDLL(None).fflush(None)  # flush C stdio buffers into the capture
        except (OSError, AttributeError) as err:  # best effort: lines may be lost, not numbers
            print(f"bench: could not flush C stdio: {err}", file=sys.stderr)
        os.dup2(self._saved, 1)
        os.close(self._saved)
        self._tmp.seek(0)
        self.text = self._tmp.read().decode("utf-8", "replace")
        self._tmp.close()


_TIME = re.compile(r"Time:\s*(\d+):(\d+(?:\.\d+)?)")


def cycles_split(log: str) -> tuple[float | None, float | None]:
    """(seconds before the first 'Sample' status line, seconds at the last status line)."""
    first_sample = last = None
    for line in log.splitlines():
        m = _TIME.search(line)
        if not m:
            continue
        t = int(m.group(1)) * 60 + float(m.group(2))
        if "| Sample " in line and first_sample is None:
            first_sample = t
        if line.startswith("Fra:"):
            last = t
    return first_sample, last


def bench_cycles(args: argparse.Namespace) -> dict[str, float | None]:
    scene = open_scene(args)
    scene.render.engine = "CYCLES"
    with CaptureStdout() as cap:
        t0 = time.perf_counter()
        bpy.ops.render.render()
        total = time.perf_counter() - t0
    sync, last = cycles_split(cap.text)
    trace = (last - sync) if (sync is not None and last is not None) else None
    return {"total": total, "sync": sync, "trace": trace}


def stratum_reason() -> str:
    """'' when Stratum can render here, else why not."""
    if str(ADDON_DIR) not in sys.path:
        sys.path.insert(0, str(ADDON_DIR))
    try:
        import stratum
        from stratum import native
    except ImportError as exc:
        return f"add-on not importable: {exc}"
    try:
        native.load_library()
    except native.StratumError as exc:
        return str(exc)
    stratum.register()
    return ""


def bench_stratum_direct(args: argparse.Namespace) -> dict[str, float]:
    from stratum import native
    from stratum.engine.frame import renderer_settings
    from stratum.export import export_scene

    scene = open_scene(args)
    configure_stratum(scene, args)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    t0 = time.perf_counter()
    with native.Scene() as native_scene:
        export_scene(depsgraph, native_scene)
        t_export = time.perf_counter() - t0
        with native.Renderer(native_scene) as renderer:
            for name, value in renderer_settings(scene).items():
                renderer.set(name, value)
            t1 = time.perf_counter()
            renderer.start()
            while not renderer.wait(50):
                pass
            wall = time.perf_counter() - t1
            p = renderer.progress()
        # The ceiling, measured right after in the same process: Embree alone on the same
        # ray mix (camera, then one bounce and one shadow ray per vertex).
        raw_rays, raw_seconds = native_scene.measure_ray_throughput(
            args.res, args.res, args.samples, MAX_BOUNCES, args.threads)
    return {"export": t_export, "build": p.build_seconds, "trace": p.render_seconds,
            "wall": wall, "rays": p.rays, "samples_done": p.samples_done,
            "raw_rays_per_s": raw_rays / raw_seconds if raw_seconds > 0 else 0.0}


def bench_stratum_engine(args: argparse.Namespace) -> float:
    scene = open_scene(args)
    configure_stratum(scene, args)
    t0 = time.perf_counter()
    bpy.ops.render.render()
    total = time.perf_counter() - t0
    from stratum.engine import StratumRenderEngine

    errors = [m for level, m in StratumRenderEngine.last_reports if level == "ERROR"]
    if errors:
        raise RuntimeError("; ".join(errors))
    return total


def fmt(x: float | None) -> str:
    return "n/a" if x is None else f"{x:8.3f}"


def ratio(a: float | None, b: float | None) -> str:
    return "n/a" if not a or not b else f"{a / b:6.2f}x"


# ---- export and BVH build: 1M triangles, 10 000 instances ------------------------------------

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


def cycles_sync_stages(log: str) -> dict[str, float | None]:
    """Seconds of Cycles' object sync and scene update, from its status lines, which read
    "Fra:1 Mem:.. | Time:00:00.22 | Mem:.., Peak:.. | Scene, ViewLayer | <stage> | <detail>"."""
    first_sync = initializing = sample0 = None
    for line in log.splitlines():
        parts = [p.strip() for p in line.split("|")]
        at = next((i for i, p in enumerate(parts) if p.startswith("Time:")), None)
        if not line.startswith("Fra:") or at is None or len(parts) <= at + 3:
            continue
        m = _TIME.search(parts[at])
        if not m:
            continue
        t = int(m.group(1)) * 60 + float(m.group(2))
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


def bench_export_case(build: Callable[[], bpy.types.Scene], stratum_ok: bool,
                      ) -> dict[str, float | int | None]:
    scene = build()
    scene.render.engine = "CYCLES"
    with CaptureStdout() as cap:
        t0 = time.perf_counter()
        bpy.ops.render.render()
        total = time.perf_counter() - t0
    out: dict[str, float | int | None] = {"cycles_f12": total, **cycles_sync_stages(cap.text)}
    if not stratum_ok:
        return out
    from stratum import native
    from stratum.engine.frame import renderer_settings
    from stratum.export import export_scene

    scene = build()
    scene.render.engine = "STRATUM"
    scene.stratum.samples = 1
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    t0 = time.perf_counter()
    with native.Scene() as native_scene:
        summary = export_scene(depsgraph, native_scene)
        t_export = time.perf_counter() - t0
        with native.Renderer(native_scene) as renderer:
            for name, value in renderer_settings(scene).items():
                renderer.set(name, value)
            renderer.start()
            while not renderer.wait(50):
                pass
            p = renderer.progress()
    out.update({"export": t_export, "build": p.build_seconds,
                "triangles": summary.triangles, "instances": summary.instances,
                "instanced_triangles": summary.instanced_triangles})
    return out


def bench_live_edit(layout: str) -> dict[str, float]:
    """monkey_1m exported once into a live native scene and rendered (1 spp, 32 x 32) with the
    `bvh` layout given, then the monkey moved through stratum_scene_set_instance and rendered
    again by the same renderer: its next start applies the edit in place (issue 13). Returns
    the full BVH build time and the update time, both as progress().build_seconds reports."""
    from stratum import native
    from stratum.engine.frame import renderer_settings
    from stratum.export import export_scene

    scene = build_monkey_1m()
    scene.render.engine = "STRATUM"
    scene.stratum.samples = 1
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    with native.Scene() as native_scene:
        export_scene(depsgraph, native_scene)
        with native.Renderer(native_scene) as renderer:
            for name, value in renderer_settings(scene).items():
                renderer.set(name, value)
            renderer.set("bvh", layout)

            def build_seconds() -> float:
                renderer.start()
                while not renderer.wait(50):
                    pass
                return renderer.progress().build_seconds

            full = build_seconds()
            moved = np.eye(4, dtype=np.float32)
            moved[:3, 3] = (0.3, 0.1, -0.2)
            # The monkey is the scene's only mesh object: instance 0 of mesh 0.
            native_scene.set_instance(0, native.Instance(mesh_id=0, transform=moved))
            update = build_seconds()
    return {"full": full, "update": update}


def fastest(runs: list[dict[str, float | int | None]]) -> dict[str, float | int | None]:
    """Per quantity, the minimum over repeated runs: on shared cores, other processes only ever
    add time, so the minimum is the best estimate of the cost itself."""
    out: dict[str, float | int | None] = {}
    for key in runs[0]:
        values = [r[key] for r in runs if r[key] is not None]
        out[key] = min(values) if values else None
    return out


def export_lines(name: str, r: dict[str, float | int | None]) -> list[str]:
    lines = [f"{name}:"]
    if "export" in r:
        lines.append(f"  scene: {r['instances']} instances, {r['triangles']} unique triangles, "
                     f"{r['instanced_triangles']} instanced")
    lines += [
        f"  {'Cycles object sync':30s}{fmt(r['object_sync']):>10s}",
        f"  {'Cycles scene update (BVH...)':30s}{fmt(r['scene_update']):>10s}",
        f"  {'Cycles sync total':30s}{fmt(r['sync_total']):>10s}",
        f"  {'Cycles F12, 1 spp 32x32':30s}{fmt(r['cycles_f12']):>10s}",
    ]
    if "export" in r:
        both = r["export"] + r["build"]
        lines += [
            f"  {'Stratum export':30s}{fmt(r['export']):>10s}",
            f"  {'Stratum BVH build':30s}{fmt(r['build']):>10s}",
            f"  {'Stratum export + BVH':30s}{fmt(both):>10s}",
            f"  ratio Stratum (export + BVH) / Cycles sync total: {ratio(both, r['sync_total'])}",
            # Cycles' F12 time holds its sync and more: this ratio is a lower bound of the one
            # above, the only one available where Cycles prints no status lines (bpy wheel).
            f"  ratio Stratum (export + BVH) / Cycles F12:        {ratio(both, r['cycles_f12'])}",
        ]
    return lines


def main() -> int:
    args = parse_args()
    cores = os.cpu_count()
    lines = [
        (f"Stratum vs Cycles: {args.scene.name}, {args.res}x{args.res}, {args.samples} spp, "
        f"max_bounces {MAX_BOUNCES}, threads {args.threads or f'all ({cores})'}, "
        f"Blender {bpy.app.version_string}"),
        "",
    ]
    reason = stratum_reason()
    st = None
    st_total = None
    cyc: dict[str, float | None] = {"total": None, "sync": None, "trace": None}
    if args.only != "export":
        cyc = bench_cycles(args)
    if not reason and args.only != "export":
        try:
            st = bench_stratum_direct(args)
            st_total = bench_stratum_engine(args)
        except Exception as exc:  # noqa: BLE001 - report, keep the Cycles numbers
            traceback.print_exc()
            reason = f"Stratum failed: {type(exc).__name__}: {exc}"

    if args.only != "export":
        lines += [
            f"{'':28s}{'seconds':>10s}",
            f"{'Cycles  sync (pre-sampling)':28s}{fmt(cyc['sync']):>10s}",
            f"{'Cycles  path tracing':28s}{fmt(cyc['trace']):>10s}",
            f"{'Cycles  total (F12)':28s}{fmt(cyc['total']):>10s}",
        ]
        if cyc["trace"] is None:
            lines.append("  (Cycles split n/a: no status lines printed; the bpy module prints none)")
        if st is not None:
            rays_per_s = st["rays"] / st["trace"] if st["trace"] > 0 else 0.0
            lines += [
                f"{'Stratum export':28s}{fmt(st['export']):>10s}",
                f"{'Stratum BVH build':28s}{fmt(st['build']):>10s}",
                (f"{'Stratum path tracing':28s}{fmt(st['trace']):>10s}"
                f"   ({rays_per_s / 1e6:.2f} M rays/s)"),
                f"{'Stratum start->done':28s}{fmt(st['wall']):>10s}",
                f"{'Stratum total (F12)':28s}{fmt(st_total):>10s}",
                "",
                f"ratio Stratum/Cycles, total (F12):    {ratio(st_total, cyc['total'])}",
                f"ratio Stratum/Cycles, path tracing:   {ratio(st['trace'], cyc['trace'])}",
                "",
                f"{'raw Embree, same ray mix':28s}{st['raw_rays_per_s'] / 1e6:10.2f} M rays/s",
                f"ratio Stratum/raw Embree, rays/s:     {ratio(rays_per_s, st['raw_rays_per_s'])}",
            ]
        else:
            lines += ["", f"Stratum: not measured ({reason})"]

    heading = (f"Export and BVH build (1 spp, {EXPORT_RES}x{EXPORT_RES}, seconds, minimum of "
               f"{args.repeats} runs):")
    lines += ["", heading]
    cases = (("monkey_1m", build_monkey_1m), ("monkey_1m_smooth", build_monkey_1m_smooth),
             ("instances_10k", build_instances_10k))
    for name, build in cases if args.only != "render" else ():
        runs = [bench_export_case(build, not reason) for _ in range(args.repeats)]
        lines += export_lines(name, fastest(runs))
    if args.only != "render" and not reason:
        lines += ["", ("Live edit: monkey_1m moved after its first render, same renderer (1 spp, "
                       f"{EXPORT_RES}x{EXPORT_RES}, seconds, minimum of {args.repeats} runs):")]
        for layout in ("dynamic", "static"):
            r = fastest([bench_live_edit(layout) for _ in range(args.repeats)])
            lines.append(f"  bvh {layout:8s} full build {fmt(r['full']):>8s}   update {fmt(r['update']):>8s}"
                         f"   update/full {100 * r['update'] / r['full']:.1f} %")
    table = "\n".join(lines)
    print(table)
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "bench.txt").write_text(table + "\n")
    print(f"written {OUT / 'bench.txt'}")
    return 2 if reason else 0


if __name__ == "__main__":
    code = 1
    try:
        code = main()
    except Exception:  # noqa: BLE001
        traceback.print_exc()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
    if IN_BLENDER:  # Blender's --python does not propagate sys.exit codes reliably
        os._exit(code)
    sys.exit(code)
