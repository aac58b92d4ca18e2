"""Equal-time quality (issue 15, target 4): noise MSE x path-tracing seconds of Stratum's
samplers relative to Cycles 3.4, each renderer against its own reference.

    blender -b --factory-startup --python scripts/run_in_blender.py -- scripts.bench.quality \
        [--res 128 --samples 64 --seeds 3 --reference-samples 2048 --scene cornell_box
        --scene wolf]

Light selection (issue 16, acceptance 4), with Cycles 5.0 and its light tree (the bpy wheel):

    .venv/bin/python -m scripts.bench.quality --scene many_lights_hall --sampler sobol
        --light-selection tree,tree:1,power,uniform,mixed --section quality_lights

--light-selection makes Stratum's series every --sampler x every listed light_selection (tree:1
is the tree without splitting, light_tree_splits 1; tree alone splits into the default 8; the
reference stays at the scene's default, auto: the tree for the hall; every mode converges to
the same image); Cycles renders with its light tree on (scene.cycles.use_light_tree, Cycles
>= 3.5). Under the bpy wheel Cycles prints no status lines, so its path-tracing time is taken
from two renders' totals: (total(N) - total(1)) N / (N - 1), the 1-spp render holding the
same scene synchronisation and one sample (the 1-spp total is measured once per seed).

Per scene (default the Cornell box and Wolf, at --res squared, bounces 8, Blackman-Harris 1.5,
all threads): Cycles with its default pattern (progressive multi-jitter in 3.4; adaptive
sampling and denoising off) and Stratum at its defaults with each --sampler (default random,
sobol, zsobol, halton_owen) render --samples spp with the seeds 1..--seeds (Cycles'
scene.cycles.seed, Stratum's `seed`). Each renderer's reference is the mean of two halves of
--reference-samples / 2 spp rendered with seeds 1001 and 1002 (Stratum's with `sobol`: every
sampler converges to the same image), so that its own noise can be measured and removed:

  noise MSE = mean over seeds of [MSE(image, reference) - Var(reference)],
  Var(reference) = MSE(half a, half b) / 4     (results.noise_mse)

MSE is the mean over pixels and RGB channels of the linear image (Cycles' through a 32-bit EXR,
Stratum's from Renderer.read_pixels). Seconds are the fastest path-tracing time over the seeds
(Cycles' from its status lines, Stratum's progress().render_seconds); the seeds run in turn,
each by Cycles then by every Stratum sampler, so that the machine's load reaches all alike. The
product's ratio to Cycles' is the figure; targets: the best Stratum sampler <= 0.6x, every
Owen-scrambled sampler within 1.2x of the best. References are cached in out/bench_cache/quality/, keyed by scene file,
settings and renderer version (Blender's version and build hash; libstratum.so's SHA-256), so a
rerun renders only the 64-spp images. Written to out/bench/quality.json and printed.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
import tempfile
from pathlib import Path
from typing import Any

import bpy
import numpy as np

from scripts import REPO
from scripts.bench.common import (
    CACHE,
    CORNELL,
    WOLF,
    StratumScene,
    configure_stratum,
    open_scene,
    read_exr_rgb,
    render_cycles,
    run_main,
    script_argv,
    stratum_library_id,
    stratum_reason,
)
from scripts.bench.results import (
    mse,
    noise_mse,
    noise_mse_seconds,
    reference_noise,
    write_section,
)

SCENES = {"cornell_box": CORNELL, "wolf": WOLF,
          "many_lights_hall": REPO / "scenes" / "many_lights_hall.blend"}
REFERENCE_SEEDS = (1001, 1002)
OWEN_SCRAMBLED = ("sobol", "zsobol", "halton_owen")
# Stratum's reference sampler: Owen-scrambled Sobol is unbiased, its two seeds are independent
# randomisations, and its halves carry far less noise than `random`'s, so the subtracted
# reference variance is small and itself well measured.
REFERENCE_SAMPLER = "sobol"
PATTERN_NAMES = {"PROGRESSIVE_MULTI_JITTER": "pmj", "SOBOL": "sobol-burley"}


def parse_args() -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="scripts.bench.quality")
    p.add_argument("--res", type=int, default=128)
    p.add_argument("--samples", type=int, default=64)
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--reference-samples", type=int, default=2048)
    p.add_argument("--scene", choices=sorted(SCENES), action="append", default=None)
    p.add_argument("--sampler", action="append", default=None)
    p.add_argument("--light-selection", default="",
                   help="comma-separated light_selection values, each optionally :SPLITS (its "
                        "light_tree_splits, e.g. tree:1): Stratum series per sampler x value")
    p.add_argument("--section", default="quality", help="out/bench/<section>.json")
    args = p.parse_args(script_argv())
    args.scene = args.scene or ["cornell_box", "wolf"]
    args.sampler = args.sampler or ["random", *OWEN_SCRAMBLED]
    args.light_selection = [v for v in args.light_selection.split(",") if v]
    return args


def selection_settings(item: str) -> dict[str, str | int]:
    """A --light-selection item, SELECTION or SELECTION:SPLITS (e.g. tree:1, the tree without
    splitting), as library settings."""
    selection, _, splits = item.partition(":")
    settings: dict[str, str | int] = {"light_selection": selection}
    if splits:
        settings["light_tree_splits"] = int(splits)
    return settings


def stratum_series(args: argparse.Namespace) -> dict[str, dict[str, str | int]]:
    """Stratum's series: label -> settings (a sampler, and a light selection when listed)."""
    if not args.light_selection:
        return {s: {"sampler": s} for s in args.sampler}
    return {f"{s} {item}": {"sampler": s} | selection_settings(item)
            for s in args.sampler for item in args.light_selection}


def cache_path(scene: str, renderer: str, key: dict[str, Any]) -> Path:
    digest = hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:16]
    return CACHE / "quality" / f"{scene}-{renderer}-{digest}.npz"


def scene_key(name: str, args: argparse.Namespace) -> dict[str, Any]:
    return {"scene": name, "file": hashlib.sha256(SCENES[name].read_bytes()).hexdigest(),
            "res": args.res, "samples": args.reference_samples, "seeds": REFERENCE_SEEDS}


def cached_halves(path: Path, render_half: Any) -> tuple[np.ndarray, np.ndarray, bool]:
    """The two reference halves from `path`, or rendered by render_half(seed) and stored."""
    if path.is_file():
        with np.load(path) as f:
            return f["a"], f["b"], True
    a, b = (render_half(seed) for seed in REFERENCE_SEEDS)
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(path, a=a, b=b)
    return a, b, False


Halves = tuple[np.ndarray, np.ndarray, bool]


def references(name: str, args: argparse.Namespace, tmp: Path, scene: Any, st: Any
               ) -> tuple[Halves, Halves]:
    """(Stratum's, Cycles') reference halves of scene `name` (cached_halves, keyed by the
    scene file, resolution, samples, library or Blender build). st: the scene's StratumScene."""
    def stratum_half(seed: int) -> np.ndarray:
        return st.render({"sampler": REFERENCE_SAMPLER, "seed": seed,
                          "samples": args.reference_samples // 2}, pixels=True)["rgb"]

    key = scene_key(name, args) | {"renderer": "stratum", "library": stratum_library_id(),
                                   "sampler": REFERENCE_SAMPLER}
    stratum = cached_halves(cache_path(name, "stratum", key), stratum_half)
    # Cycles with a light tree (>= 3.5) renders its references with it on.
    tree = {"light_tree": True} if light_tree_on(scene) else {}
    key = scene_key(name, args) | tree | {
        "renderer": "cycles", "blender": bpy.app.version_string,
        "build": bpy.app.build_hash.decode(errors="replace")}
    cycles = cached_halves(
        cache_path(name, "cycles", key),
        lambda seed: cycles_render(name, args, tmp, seed, args.reference_samples // 2)[0])
    return stratum, cycles


def measure(images: list[np.ndarray], seconds: list[float], a: np.ndarray, b: np.ndarray,
            ) -> dict[str, Any]:
    reference = (a + b) / 2
    return {"mse_vs_reference": float(np.mean([mse(im, reference) for im in images])),
            "noise_mse": float(np.mean([noise_mse(im, a, b) for im in images])),
            "seconds": min(seconds), "seconds_all": seconds}


def light_tree_on(scene: bpy.types.Scene) -> bool | None:
    """Turns Cycles' light tree on where it has one (>= 3.5); None where it has none."""
    c = scene.cycles
    if not hasattr(c, "use_light_tree"):
        return None
    c.use_light_tree = True
    return True


def cycles_render(name: str, args: argparse.Namespace, tmp: Path, seed: int, samples: int,
                  adaptive_threshold: float = 0.0) -> tuple[np.ndarray, float]:
    """Cycles' image (linear RGB) and path-tracing seconds, its default pattern and light
    tree, `seed`; with adaptive_threshold > 0, Cycles' adaptive sampling at that threshold up
    to `samples`. Without status lines (the bpy wheel) the time is (total(N) - total(1))
    N / (N - 1) (module doc)."""
    def open_cycles(spp: int) -> bpy.types.Scene:
        scene = open_scene(SCENES[name], args.res, spp)
        c = scene.cycles
        # The default pattern; 5.0's enum has dynamic items and no default identifier: the
        # scene's own pattern stays (Automatic in a file it did not store one in).
        default = type(c).bl_rna.properties["sampling_pattern"].default
        if default:
            c.sampling_pattern = default
        c.seed = seed
        c.use_animated_seed = False
        if adaptive_threshold > 0.0:
            c.use_adaptive_sampling = True
            c.adaptive_threshold = adaptive_threshold
            c.adaptive_min_samples = 0
        light_tree_on(scene)
        return scene

    exr = tmp / f"cycles-{seed}.exr"
    r = render_cycles(open_cycles(samples), write_exr=exr)
    image = read_exr_rgb(exr)
    if r["trace"] is not None:
        return image, r["trace"]
    if samples < 2:
        raise RuntimeError("Cycles printed no status lines and 1 spp leaves nothing to subtract")
    one = render_cycles(open_cycles(1), write_exr=tmp / f"cycles-{seed}-1spp.exr")
    total, base = r["total"], one["total"]
    assert total is not None and base is not None
    return image, max(total - base, 0.0) * samples / (samples - 1)


def bench_scene(name: str, args: argparse.Namespace, tmp: Path,
                ) -> tuple[dict[str, Any], dict[str, Any]]:
    """(Cycles' figures, Stratum's) on one scene. After the references, the seeds run in turn,
    each rendered by Cycles and then by every Stratum sampler, so that a change of the
    machine's load reaches both renderers alike."""
    scene = open_scene(SCENES[name], args.res, args.samples)
    configure_stratum(scene, args.samples)
    with StratumScene(scene) as st:
        (st_a, st_b, st_cached), (cy_a, cy_b, cy_cached) = references(name, args, tmp, scene, st)
        cycles_runs: list[tuple[np.ndarray, float]] = []
        series = stratum_series(args)
        stratum_runs: dict[str, list[dict[str, Any]]] = {label: [] for label in series}
        for seed in range(1, args.seeds + 1):
            cycles_runs.append(cycles_render(name, args, tmp, seed, args.samples))
            for label, settings in series.items():
                stratum_runs[label].append(st.render(settings | {"seed": seed}, pixels=True))
    pattern = bpy.context.scene.cycles.sampling_pattern
    cyc = measure([im for im, _ in cycles_runs], [t for _, t in cycles_runs], cy_a, cy_b)
    cyc |= {"reference_noise": reference_noise(cy_a, cy_b), "reference_cached": cy_cached,
            "pattern": pattern, "light_tree": light_tree_on(bpy.context.scene),
            "blender": bpy.app.version_string}
    samplers = {s: measure([r["rgb"] for r in runs], [r["trace"] for r in runs], st_a, st_b)
                | {"light_tree_seconds": max(r["light_tree_seconds"] for r in runs),
                   "light_tree_bytes": max(r["light_tree_bytes"] for r in runs)}
                for s, runs in stratum_runs.items()}
    return cyc, {"reference_noise": reference_noise(st_a, st_b), "reference_cached": st_cached,
                 "samplers": samplers}


def scene_lines(name: str, cyc: dict[str, Any], st: dict[str, Any]) -> list[str]:
    base = noise_mse_seconds(cyc)
    lines = [(f"{name}: reference noise (subtracted) Cycles {cyc['reference_noise']:.3e}, "
              f"Stratum {st['reference_noise']:.3e}"),
             (f"  {'':22s}{'MSE vs ref':>12s}{'noise MSE':>12s}{'seconds':>9s}"
              f"{'MSE x s':>11s}{'/ Cycles':>10s}")]
    tree = " light tree" if cyc.get("light_tree") else ""
    rows = [(f"Cycles {PATTERN_NAMES.get(cyc['pattern'], cyc['pattern'])}{tree}", cyc)]
    rows += [(f"Stratum {s}", r) for s, r in st["samplers"].items()]
    for label, r in rows:
        product = noise_mse_seconds(r)
        lines.append(f"  {label:22s}{r['mse_vs_reference']:12.4e}{r['noise_mse']:12.4e}"
                     f"{r['seconds']:9.3f}{product:11.3e}{product / base:9.3f}x")
    return lines


def main() -> int:
    args = parse_args()
    reason = stratum_reason()
    if reason:
        print(f"bench.quality: Stratum not available ({reason})", file=sys.stderr)
        return 2
    if args.section == "quality" and args.light_selection:
        print("bench.quality: --light-selection writes its own --section (e.g. quality_lights)",
              file=sys.stderr)
        return 2
    results: dict[str, Any] = {}
    lines = [(f"Equal-time quality: {args.res}x{args.res}, {args.samples} spp, {args.seeds} "
              f"seeds, references of {args.reference_samples} spp (two independent halves):")]
    with tempfile.TemporaryDirectory(prefix="bench_quality") as tmp:
        for name in args.scene:
            cyc, st = bench_scene(name, args, Path(tmp))
            results[name] = {"cycles": cyc, "stratum": st}
            lines += scene_lines(name, cyc, st)
    print("\n".join(lines))
    data = {"res": args.res, "samples": args.samples, "seeds": args.seeds,
            "reference_samples": args.reference_samples, "owen_scrambled": list(OWEN_SCRAMBLED),
            "scenes": results}
    if args.light_selection:
        data["light_selection"] = args.light_selection
    print(f"written {write_section(args.section, data)}")
    return 0


if __name__ == "__main__":
    run_main(main)
