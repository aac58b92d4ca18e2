"""Stratum vs Cycles: path tracing on the Cornell box, Wolf and the materials scene, and the
export of 1M triangles and 10 000 instances. Same resolution, samples, bounces, filter, threads.

    blender -b --factory-startup --python scripts/run_in_blender.py -- scripts.bench.speed \
        [--samples 64 --res 256] [--only render|export] [--scene scenes/wolf.blend]

(--only render: the scenes only; --only export: the export only; also runs under the bpy wheel:
.venv/bin/python -m scripts.bench.speed). Prints a table and writes it to out/bench.txt, and
the figures to out/bench/render.json and out/bench/export.json for the summary (summary.py).
For each scene (--scene, repeatable; default the Cornell box, Wolf (215k triangles) and
scenes/features/materials.blend (textures, glass, coat)):

* Cycles: total F12 time (bpy.ops.render.render) and its split into scene synchronisation
  (everything before the first "Sample" status line) and path tracing, timed by when the
  status lines Blender prints in background mode arrive (captured from file descriptor 1 during
  the render; their own "Time:" field counts in steps of 10 ms);
* Stratum at its default settings (integrator path, estimator mis, solid-angle triangles,
  sampler random), through the add-on's exporter and stratum.native.Renderer directly: export
  time (depsgraph -> native scene), BVH build time and path-tracing time as reported by the
  native library (progress().build_seconds / render_seconds), and the wall time start -> done;
* Stratum total F12 time through the engine, comparable with Cycles' F12 time;
* the ratios Stratum / Cycles (total, and path tracing alone), measured in this one run;
* on the Cornell box, the ceiling: Embree alone on the same ray mix (camera, then one bounce
  and one shadow ray per vertex), measured right after in the same process.

Then the export section (acceptance 3 of issue 5), each scene built in this script:

* monkey_1m: Suzanne subdivided 5 times (Catmull-Clark, applied: 503 808 quads = 1 007 616
  triangles, one object), a camera and a sun;
* instances_10k: 10 000 instances of one 12-triangle cube (vertex instancing) plus the child
  object itself, a camera and a sun;
* emissive_100k: a grid of 100 352 emissive triangles (every one a light), a camera and a sun:
  Stratum's light tree build (seconds, MB: the progress counters light_tree.seconds /
  light_tree.bytes) is printed and recorded beside its BVH build.

For each, Stratum's export (depsgraph -> native scene, timed around export_scene) and BVH build
(progress().build_seconds of a 1-sample 32 x 32 render) against Cycles' synchronisation of the
same scene, timed by the arrival of the status lines Cycles prints during a 1-sample 32 x 32
render (Blender 3.4's `blender -b`; the bpy module prints none, so there only the F12 total is
given):

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

Each measurement, of the scenes and of the export, is repeated --repeats times (default 3), the
renderers taking turns, and the minimum of each quantity reported (other processes on shared
cores only add time). Each ratio comes from this one run.

Exit status: 0 when both renderers ran, 2 when Stratum is not available (Cycles numbers are
still printed), 1 on an error.
"""

from __future__ import annotations

import argparse
import os
import time
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any

import bpy
import numpy as np

from scripts import REPO
from scripts.bench.common import (
    CORNELL,
    EXPORT_CASES,
    EXPORT_RES,
    MATERIALS,
    MAX_BOUNCES,
    OUT,
    WOLF,
    CaptureStdout,
    StratumScene,
    build_monkey_1m,
    configure_stratum,
    cycles_sync_stages,
    open_scene,
    render_cycles,
    run_main,
    script_argv,
    stratum_reason,
)
from scripts.bench.results import write_section


def parse_args() -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="scripts.bench.speed")
    p.add_argument("--samples", type=int, default=64)
    p.add_argument("--res", type=int, default=256)
    p.add_argument("--threads", type=int, default=0, help="0 = all cores")
    p.add_argument("--scene", type=Path, action="append", default=None,
                   help="a scene to render (repeatable; default: Cornell box, Wolf, materials)")
    p.add_argument("--repeats", type=int, default=3,
                   help="runs of each measurement, renderers taking turns (the minimum is reported)")
    p.add_argument("--only", choices=("render", "export"), default=None,
                   help="run only the scene render comparison or only the export section")
    args = p.parse_args(script_argv())
    args.scene = [p.resolve() for p in args.scene or [CORNELL, WOLF, MATERIALS]]
    return args


def bench_stratum_direct(path: Path, args: argparse.Namespace) -> dict[str, float]:
    scene = open_scene(path, args.res, args.samples, args.threads)
    configure_stratum(scene, args.samples, args.threads)
    with StratumScene(scene) as st:
        r = st.render()
        r["export"] = st.export_seconds
        r["triangles"] = st.summary.triangles
        if path == CORNELL:
            # The ceiling, measured right after in the same process: Embree alone on the same
            # ray mix (camera, then one bounce and one shadow ray per vertex).
            r["raw_rays"], r["raw_seconds"] = st.native.measure_ray_throughput(
                args.res, args.res, args.samples, MAX_BOUNCES, args.threads)
    return r


def bench_stratum_engine(path: Path, args: argparse.Namespace) -> float:
    scene = open_scene(path, args.res, args.samples, args.threads)
    configure_stratum(scene, args.samples, args.threads)
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


def bench_scene(path: Path, args: argparse.Namespace, reason: str,
                ) -> tuple[list[str], dict[str, Any], str]:
    """One scene's comparison: its lines, its figures and the reason Stratum was not measured
    ('' when it was)."""
    # The renderers take turns, --repeats times, and each quantity's minimum is kept: a burst
    # of load from other processes then cannot fall on one renderer only.
    cycles_runs, stratum_runs, f12_runs = [], [], []
    for _ in range(args.repeats):
        cycles_runs.append(render_cycles(open_scene(path, args.res, args.samples, args.threads)))
        if reason:
            continue
        try:
            stratum_runs.append(bench_stratum_direct(path, args))
            f12_runs.append({"total": bench_stratum_engine(path, args)})
        except Exception as exc:  # noqa: BLE001 - report, keep the Cycles numbers
            traceback.print_exc()
            reason = f"Stratum failed: {type(exc).__name__}: {exc}"
    cyc = fastest(cycles_runs)
    st: dict[str, Any] | None = None
    st_total = None
    if not reason:
        st = fastest(stratum_runs)
        st_total = fastest(f12_runs)["total"]
        # Rates from the fastest times (a minimum of rates would keep the slowest run's).
        st["rays_per_s"] = st["rays"] / st["trace"] if st["trace"] > 0 else 0.0
        st["samples_per_s"] = args.res ** 2 * st["samples_done"] / st["trace"] if st["trace"] > 0 else 0.0
        if "raw_rays" in st:
            st["raw_rays_per_s"] = st["raw_rays"] / st["raw_seconds"] if st["raw_seconds"] > 0 else 0.0
    lines = [
        f"{path.relative_to(REPO)}:",
        f"{'':28s}{'seconds':>10s}",
        f"{'Cycles  sync (pre-sampling)':28s}{fmt(cyc['sync']):>10s}",
        f"{'Cycles  path tracing':28s}{fmt(cyc['trace']):>10s}",
        f"{'Cycles  total (F12)':28s}{fmt(cyc['total']):>10s}",
    ]
    if cyc["trace"] is None:
        lines.append("  (Cycles split n/a: no status lines printed; the bpy module prints none)")
    if st is None:
        return lines + ["", f"Stratum: not measured ({reason})", ""], {"cycles": cyc}, reason
    lines += [
        f"{'Stratum export':28s}{fmt(st['export']):>10s}   ({st['triangles']} triangles)",
        f"{'Stratum BVH build':28s}{fmt(st['build']):>10s}",
        (f"{'Stratum path tracing':28s}{fmt(st['trace']):>10s}"
         f"   ({st['rays_per_s'] / 1e6:.2f} M rays/s)"),
        f"{'Stratum start->done':28s}{fmt(st['wall']):>10s}",
        f"{'Stratum total (F12)':28s}{fmt(st_total):>10s}",
        "",
        f"ratio Stratum/Cycles, total (F12):    {ratio(st_total, cyc['total'])}",
        f"ratio Stratum/Cycles, path tracing:   {ratio(st['trace'], cyc['trace'])}",
    ]
    if "raw_rays_per_s" in st:
        lines += [
            "",
            f"{'raw Embree, same ray mix':28s}{st['raw_rays_per_s'] / 1e6:10.2f} M rays/s",
            f"ratio Stratum/raw Embree, rays/s:     {ratio(st['rays_per_s'], st['raw_rays_per_s'])}",
        ]
    return lines + [""], {"cycles": cyc, "stratum": st, "stratum_f12": st_total}, reason


def bench_export_case(build: Callable[[], bpy.types.Scene], stratum_ok: bool,
                      ) -> dict[str, float | int | None]:
    scene = build()
    scene.render.engine = "CYCLES"
    with CaptureStdout() as cap:
        t0 = time.perf_counter()
        bpy.ops.render.render()
        total = time.perf_counter() - t0
    out: dict[str, float | int | None] = {"cycles_f12": total, **cycles_sync_stages(cap.lines)}
    if not stratum_ok:
        return out
    from stratum import native
    from stratum.engine.frame import renderer_settings
    from stratum.export.sync import export_scene

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
                "light_tree": p.counter("light_tree.seconds"),
                "light_tree_bytes": p.counter("light_tree.bytes"),
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
    from stratum.export.sync import export_scene

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
        if r.get("light_tree"):
            # Built before the first sample (within the render, not the BVH build).
            lines.append(f"  {'Stratum light tree build':30s}{fmt(r['light_tree']):>10s}   "
                         f"{(r['light_tree_bytes'] or 0) / 1e6:.1f} MB")
    return lines


def main() -> int:
    args = parse_args()
    cores = os.cpu_count()
    lines = [
        (f"Stratum vs Cycles: {args.res}x{args.res}, {args.samples} spp, max_bounces "
         f"{MAX_BOUNCES}, threads {args.threads or f'all ({cores})'}, Blender "
         f"{bpy.app.version_string}"),
        "",
    ]
    reason = stratum_reason()
    if args.only != "export":
        scenes: dict[str, Any] = {}
        for path in args.scene:
            scene_lines, scenes[path.stem], reason = bench_scene(path, args, reason)
            lines += scene_lines
        write_section("render", {"res": args.res, "samples": args.samples,
                                 "threads": args.threads, "repeats": args.repeats, "blender": bpy.app.version_string,
                                 "scenes": scenes})

    if args.only != "render":
        lines += [(f"Export and BVH build (1 spp, {EXPORT_RES}x{EXPORT_RES}, seconds, minimum "
                   f"of {args.repeats} runs):")]
        cases: dict[str, Any] = {}
        for name, build in EXPORT_CASES:
            runs = [bench_export_case(build, not reason) for _ in range(args.repeats)]
            cases[name] = fastest(runs)
            lines += export_lines(name, cases[name])
        live: dict[str, Any] = {}
        if not reason:
            lines += ["", ("Live edit: monkey_1m moved after its first render, same renderer "
                           f"(1 spp, {EXPORT_RES}x{EXPORT_RES}, seconds, minimum of "
                           f"{args.repeats} runs):")]
            for layout in ("dynamic", "static"):
                r = live[layout] = fastest([bench_live_edit(layout) for _ in range(args.repeats)])
                lines.append(f"  bvh {layout:8s} full build {fmt(r['full']):>8s}   update "
                             f"{fmt(r['update']):>8s}   update/full "
                             f"{100 * r['update'] / r['full']:.1f} %")
        write_section("export", {"repeats": args.repeats, "blender": bpy.app.version_string,
                                 "cases": cases, "live_edit": live})
    table = "\n".join(lines)
    print(table)
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "bench.txt").write_text(table + "\n")
    print(f"written {OUT / 'bench.txt'}")
    return 2 if reason else 0


if __name__ == "__main__":
    run_main(main)
