"""The cost of a 20-node procedural material per shading point, Stratum against Cycles (issue 18:
"evaluating a 20-node procedural material costs <= 1.5x Cycles' per shading point").

    blender -b --factory-startup -noaudio --python scripts/run_in_blender.py -- \
        scripts.bench.shader_nodes [--res 256 --samples 64 --threads 1 --repeats 3]
    .venv/bin/python -m scripts.bench.shader_nodes          # the bpy wheel (no Cycles split)

The scene, built here: a 2 x 2 plane filling the frame of an orthographic camera, a black world,
max bounces 0. Every camera ray hits the plane once and nothing else happens: the shader runs
once per sample and no light is sampled (an Emission-only surface has nothing to sample with).
Two materials on it, rendered in turn:

* P: an Emission whose Color is driven by 20 nodes typical of real files (NODES below: Texture
  Coordinate -> Mapping -> Noise (detail 4) warping a Voronoi, Separate/Combine XYZ, Math,
  Map Range, two Color Ramps, Mix (multiply, overlay, screen), Vector Math, Hue/Saturation,
  Brightness/Contrast);
* C: an Emission with a constant colour.

Both renderers run on the CPU with the same resolution, samples, pixel filter and thread count
(--threads, default 1: the cost of one core, the least disturbed by other processes on shared
cores), no denoising, adaptive sampling or clamping. The times are path tracing only, without the
scene sync: Cycles' from the arrival of its status lines (first "Sample" line -> last line, as
bench.py), Stratum's the native library's render_seconds. Each of the four renders is repeated
--repeats times, the renderers taking turns, and the minimum kept (other processes only add
time). Then, per renderer,

    node cost per shading point = (T_P - T_C) / (pixels x samples)

and the ratio Stratum / Cycles of the two costs (target <= 1.5). Before timing, both renderers
render P once at a few samples and their channel means are compared (2 %): a material that one
of them renders differently would make the ratio meaningless. Written to out/bench/shader_nodes
.json (for scripts/bench/summary.py) and out/bench_shader_nodes.txt.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path
from typing import Any

import bpy
import numpy as np

from scripts.bench.common import (
    OUT,
    StratumScene,
    read_exr_rgb,
    render_cycles,
    run_main,
    script_argv,
    stratum_reason,
)
from scripts.bench.results import write_section

NODES = 20
FILTER_WIDTH = 1.5
CHECK_SAMPLES = 8
CHECK_TOLERANCE = 0.02  # relative, per channel mean (the feature scenes' tolerance)


def parse_args() -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="scripts.bench.shader_nodes")
    p.add_argument("--res", type=int, default=256)
    p.add_argument("--samples", type=int, default=32)
    p.add_argument("--threads", type=int, default=1, help="both renderers (0 = all cores)")
    p.add_argument("--repeats", type=int, default=3)
    return p.parse_args(script_argv())


# ---- the scene --------------------------------------------------------------------------------


def base_scene(res: int, samples: int, threads: int) -> bpy.types.Scene:
    """An empty file with the plane, the orthographic camera and a black world, both renderers'
    settings made equal."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    r = scene.render
    r.resolution_x = r.resolution_y = res
    r.resolution_percentage = 100
    r.threads_mode = "FIXED" if threads > 0 else "AUTO"
    if threads > 0:
        r.threads = threads
    c = scene.cycles
    c.device = "CPU"
    c.samples = samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 0
    c.volume_bounces = c.transparent_max_bounces = 0
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.pixel_filter_type = "BLACKMAN_HARRIS"
    c.filter_width = FILTER_WIDTH
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [], [(0, 1, 2, 3)])
    mesh.uv_layers.new(name="UVMap")  # as a real plane has (and the exporter asks for one)
    mesh.update()
    plane = bpy.data.objects.new("plane", mesh)
    scene.collection.objects.link(plane)
    cam = bpy.data.cameras.new("camera")
    cam.type = "ORTHO"
    cam.ortho_scale = 2.0  # the plane's side: it fills the square frame
    cam_ob = bpy.data.objects.new("camera", cam)
    cam_ob.location = (0.0, 0.0, 5.0)  # looking down -Z at the plane
    scene.collection.objects.link(cam_ob)
    scene.camera = cam_ob
    return scene


def socket(sockets: Any, *names: str) -> Any:
    """The first enabled socket whose identifier or name is one of `names` (in that order): the
    Mix node's sockets are found by identifier (Factor_Float, A_Color...) in 3.4 and 5.0."""
    for name in names:
        for s in sockets:
            if s.identifier == name and getattr(s, "enabled", True):
                return s
        for s in sockets:
            if s.name == name and getattr(s, "enabled", True):
                return s
    raise KeyError(f"no socket {names} among {[s.identifier for s in sockets]}")


def emission_material(name: str) -> tuple[bpy.types.Material, Any, Any]:
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    emission = nt.nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(emission.outputs["Emission"], out.inputs["Surface"])
    # Not a light for Cycles (3.4: sample_as_light; 3.5+: emission_sampling): nothing samples it
    # at max bounces 0, but its light setup would be sync work.
    if hasattr(mat.cycles, "sample_as_light"):
        mat.cycles.sample_as_light = False
    if hasattr(mat.cycles, "emission_sampling"):
        mat.cycles.emission_sampling = "NONE"
    return mat, nt, emission


def constant_material() -> bpy.types.Material:
    mat, _, emission = emission_material("constant")
    emission.inputs["Color"].default_value = (0.8, 0.5, 0.2, 1.0)
    return mat


def procedural_material() -> bpy.types.Material:
    """Emission Color from NODES nodes (Emission and Material Output not counted)."""
    mat, nt, emission = emission_material("procedural")
    n, link = nt.nodes, nt.links.new
    before = len(n)

    def math(op: str, a: Any, b: Any = 0.0, c: Any = 0.0, clamp: bool = False) -> Any:
        node = n.new("ShaderNodeMath")
        node.operation = op
        node.use_clamp = clamp
        for i, v in enumerate((a, b, c)):
            if isinstance(v, float):
                node.inputs[i].default_value = v
            else:
                link(v, node.inputs[i])
        return node.outputs["Value"]

    def mix(blend: str, factor: float | Any, a: Any, b: Any) -> Any:
        node = n.new("ShaderNodeMix")
        node.data_type = "RGBA"
        node.blend_type = blend
        fac = socket(node.inputs, "Factor_Float", "Factor")
        if isinstance(factor, float):
            fac.default_value = factor
        else:
            link(factor, fac)
        link(a, socket(node.inputs, "A_Color"))
        link(b, socket(node.inputs, "B_Color"))
        return socket(node.outputs, "Result_Color")

    def ramp(value: Any, stops: list[tuple[float, tuple[float, float, float]]]) -> Any:
        node = n.new("ShaderNodeValToRGB")
        elements = node.color_ramp.elements
        while len(elements) < len(stops):
            elements.new(0.5)
        for element, (at, rgb) in zip(elements, stops, strict=True):
            element.position = at
            element.color = (*rgb, 1.0)
        link(value, node.inputs["Fac"])
        return node.outputs["Color"]

    coord = n.new("ShaderNodeTexCoord")
    mapping = n.new("ShaderNodeMapping")
    mapping.inputs["Location"].default_value = (0.2, -0.1, 0.0)
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, 0.3)
    mapping.inputs["Scale"].default_value = (1.5, 1.5, 1.5)
    link(coord.outputs["Object"], mapping.inputs["Vector"])
    p = mapping.outputs["Vector"]
    noise = n.new("ShaderNodeTexNoise")
    noise.noise_dimensions = "3D"
    noise.inputs["Scale"].default_value = 4.0
    noise.inputs["Detail"].default_value = 4.0
    noise.inputs["Roughness"].default_value = 0.55
    link(p, noise.inputs["Vector"])
    warp = n.new("ShaderNodeVectorMath")
    warp.operation = "ADD"
    link(p, warp.inputs[0])
    link(noise.outputs["Color"], warp.inputs[1])
    voronoi = n.new("ShaderNodeTexVoronoi")
    voronoi.voronoi_dimensions = "3D"
    voronoi.feature = "F1"
    voronoi.distance = "EUCLIDEAN"
    voronoi.inputs["Scale"].default_value = 3.0
    link(warp.outputs["Vector"], voronoi.inputs["Vector"])
    sep = n.new("ShaderNodeSeparateXYZ")
    link(p, sep.inputs["Vector"])
    stripes = math("SINE", math("MULTIPLY", sep.outputs["X"], 6.0))
    cells = math("MULTIPLY_ADD", stripes, 0.25, voronoi.outputs["Distance"])
    remap = n.new("ShaderNodeMapRange")
    remap.inputs["From Min"].default_value = 0.3
    remap.inputs["From Max"].default_value = 0.7
    link(noise.outputs["Fac"], remap.inputs["Value"])
    ramp_a = ramp(remap.outputs["Result"], [(0.0, (0.05, 0.1, 0.3)), (0.5, (0.6, 0.5, 0.2)),
                                            (1.0, (0.9, 0.9, 0.8))])
    ramp_b = ramp(cells, [(0.1, (1.0, 1.0, 1.0)), (0.6, (0.2, 0.15, 0.1))])
    shaded = mix("OVERLAY", 0.5, mix("MULTIPLY", 0.8, ramp_a, ramp_b), voronoi.outputs["Color"])
    hue = n.new("ShaderNodeHueSaturation")
    hue.inputs["Hue"].default_value = 0.55
    hue.inputs["Saturation"].default_value = 1.2
    link(shaded, hue.inputs["Color"])
    combine = n.new("ShaderNodeCombineXYZ")
    link(cells, combine.inputs["X"])
    link(noise.outputs["Fac"], combine.inputs["Y"])
    link(sep.outputs["Y"], combine.inputs["Z"])
    length = n.new("ShaderNodeVectorMath")
    length.operation = "LENGTH"
    link(combine.outputs["Vector"], length.inputs[0])
    factor = math("MULTIPLY", length.outputs["Value"], 0.5, clamp=True)
    screened = mix("SCREEN", factor, hue.outputs["Color"], noise.outputs["Color"])
    contrast = n.new("ShaderNodeBrightContrast")
    contrast.inputs["Bright"].default_value = 0.05
    contrast.inputs["Contrast"].default_value = 0.1
    link(screened, contrast.inputs["Color"])
    link(contrast.outputs["Color"], emission.inputs["Color"])
    if len(n) - before != NODES:
        raise AssertionError(f"the procedural graph has {len(n) - before} nodes, not {NODES}")
    return mat


def build(kind: str, args: argparse.Namespace, samples: int | None = None) -> bpy.types.Scene:
    scene = base_scene(args.res, args.samples if samples is None else samples, args.threads)
    mat = procedural_material() if kind == "P" else constant_material()
    scene.objects["plane"].data.materials.append(mat)
    return scene


# ---- the renders ------------------------------------------------------------------------------


def stratum_scene(scene: bpy.types.Scene, samples: int, threads: int) -> StratumScene:
    scene.render.engine = "STRATUM"
    s = scene.stratum
    s.samples = samples
    s.max_bounces = 0
    s.filter_type = "blackman_harris"
    s.filter_width = FILTER_WIDTH
    s.threads = threads
    st = StratumScene(scene)
    if st.summary.warnings:
        st.native.close()
        raise RuntimeError(f"Stratum's export warned: {st.summary.warnings}")
    return st


def render_stratum(kind: str, args: argparse.Namespace) -> tuple[float, float]:
    """Stratum's path-tracing seconds (the native render_seconds, without export and BVH) and
    the process's CPU seconds over the render."""
    with stratum_scene(build(kind, args), args.samples, args.threads) as st:
        cpu = time.process_time()
        r = st.render()
        cpu = time.process_time() - cpu
    if r["samples_done"] != args.samples:
        raise RuntimeError(f"Stratum rendered {r['samples_done']} of {args.samples} samples")
    return float(r["trace"]), cpu


def render_cycles_trace(kind: str, args: argparse.Namespace) -> tuple[float | None, float]:
    """Cycles' path-tracing seconds (status lines) and the process's CPU seconds over the whole
    F12 (its sync's share cancels in T_P - T_C but for the compilation of P's 20 nodes)."""
    scene = build(kind, args)
    cpu = time.process_time()
    trace = render_cycles(scene)["trace"]
    return trace, time.process_time() - cpu


def agreement(args: argparse.Namespace) -> dict[str, Any]:
    """Material P at CHECK_SAMPLES by both renderers: each one's channel means and the worst
    relative difference."""
    with tempfile.TemporaryDirectory() as tmp:
        exr = Path(tmp) / "cycles.exr"
        render_cycles(build("P", args, CHECK_SAMPLES), write_exr=exr)
        cycles = read_exr_rgb(exr).mean(axis=(0, 1))
    with stratum_scene(build("P", args, CHECK_SAMPLES), CHECK_SAMPLES, args.threads) as st:
        stratum = st.render(pixels=True)["rgb"].mean(axis=(0, 1))
    worst = float(np.max(np.abs(stratum - cycles) / np.maximum(np.abs(cycles), 1e-6)))
    return {"cycles_mean": cycles.tolist(), "stratum_mean": stratum.tolist(),
            "worst_relative": worst, "agree": worst <= CHECK_TOLERANCE}


def cost_ns(t_p: float | None, t_c: float | None, points: int) -> float | None:
    if t_p is None or t_c is None:
        return None
    return (t_p - t_c) / points * 1e9


def costs(times: dict[str, dict[str, list[float]]], points: int,
          ) -> tuple[dict[str, dict[str, float | None]], dict[str, float | None], float | None]:
    """Per renderer the minimum T_P and T_C, the node cost per point (ns), and the ratio of the
    costs Stratum / Cycles."""
    best = {who: {k: (min(v) if v else None) for k, v in runs.items()}
            for who, runs in times.items()}
    cost = {who: cost_ns(b["P"], b["C"], points) for who, b in best.items()}
    ratio = (cost["stratum"] / cost["cycles"]
             if cost["stratum"] is not None and cost["cycles"] else None)
    return best, cost, ratio


def fmt(x: float | None, spec: str) -> str:
    return "n/a" if x is None else format(x, spec)


def main() -> int:
    args = parse_args()
    reason = stratum_reason()
    points = args.res * args.res * args.samples
    times: dict[str, dict[str, list[float]]] = {"cycles": {"P": [], "C": []},
                                                "stratum": {"P": [], "C": []}}
    check = None if reason else agreement(args)
    started = time.perf_counter()
    cpu_times: dict[str, dict[str, list[float]]] = {"cycles": {"P": [], "C": []},
                                                    "stratum": {"P": [], "C": []}}
    for _ in range(args.repeats):
        for kind in ("P", "C"):
            t, cpu = render_cycles_trace(kind, args)
            if t is not None:
                times["cycles"][kind].append(t)
            cpu_times["cycles"][kind].append(cpu)
            if not reason:
                t, cpu = render_stratum(kind, args)
                times["stratum"][kind].append(t)
                cpu_times["stratum"][kind].append(cpu)
    best, cost, ratio = costs(times, points)
    best_cpu, cost_cpu, ratio_cpu = costs(cpu_times, points)
    threads = args.threads or "all"
    lines = [
        (f"Shader nodes, {NODES}-node procedural material P against constant C: "
         f"{args.res}x{args.res}, {args.samples} spp ({points} shading points), max bounces 0, "
         f"threads {threads} (both), minimum of {args.repeats}, Blender "
         f"{bpy.app.version_string}"),
        "",
        f"{'':10s}{'T_P (s)':>10s}{'T_C (s)':>10s}{'node cost (ns/point)':>24s}",
    ]
    for who in ("cycles", "stratum"):
        b = best[who]
        lines.append(f"{who:10s}{fmt(b['P'], '10.3f')}{fmt(b['C'], '10.3f')}"
                     f"{fmt(cost[who], '24.1f')}")
    lines += ["", (f"ratio Stratum/Cycles, node cost per shading point: "
                   f"{fmt(ratio, '.2f')}x (target <= 1.50x)"),
              (f"the same from the process's CPU time (less sensitive to other processes): "
               f"Cycles {fmt(cost_cpu['cycles'], '.1f')} ns, Stratum "
               f"{fmt(cost_cpu['stratum'], '.1f')} ns, ratio {fmt(ratio_cpu, '.2f')}x")]
    if reason:
        lines.append(f"Stratum: not measured ({reason})")
    if best["cycles"]["P"] is None:
        lines.append("Cycles: no path-tracing split (the bpy module prints no status lines)")
    if check is not None:
        lines.append(
            f"P's channel means at {CHECK_SAMPLES} spp: Cycles "
            f"{', '.join(f'{x:.4f}' for x in check['cycles_mean'])}; Stratum "
            f"{', '.join(f'{x:.4f}' for x in check['stratum_mean'])}; worst relative "
            f"difference {check['worst_relative']:.4f} "
            f"({'agree' if check['agree'] else 'DO NOT agree'} within {CHECK_TOLERANCE:.0%})")
    lines.append(f"({time.perf_counter() - started:.0f} s of renders)")
    write_section("shader_nodes", {
        "res": args.res, "samples": args.samples, "threads": args.threads,
        "repeats": args.repeats, "blender": bpy.app.version_string, "nodes": NODES,
        "times": times, "best": best, "cost_ns": cost, "ratio": ratio, "agreement": check,
        "cpu_times": cpu_times, "best_cpu": best_cpu, "cost_cpu_ns": cost_cpu,
        "ratio_cpu": ratio_cpu})
    table = "\n".join(lines)
    print(table)
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "bench_shader_nodes.txt").write_text(table + "\n")
    if reason:
        return 2
    return 0 if check is not None and check["agree"] else 1


if __name__ == "__main__":
    run_main(main)
