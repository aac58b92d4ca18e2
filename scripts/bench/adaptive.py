"""Adaptive sampling at equal time (issue 16, acceptance 4): noise MSE x path-tracing seconds of
adaptive against fixed sampling, for Stratum and for Cycles 3.4, each against its own reference.

    blender -b --factory-startup --python scripts/run_in_blender.py -- scripts.bench.adaptive \
        [--res 128 --seeds 2 --samples 64 --max-samples 1024 --threshold 0.01 --threshold 0.02
        --scene cornell_box --sampler sobol --sampler zsobol]

Per scene (quality.py's: the Cornell box and Wolf at --res squared, bounces 8,
Blackman-Harris 1.5, references of 2048 spp cached in out/bench_cache/quality/ and shared with
quality.py): fixed sampling at --samples spp, and adaptive sampling up to --max-samples at
each --threshold (Cycles' and Stratum's use_adaptive_sampling / adaptive_threshold, automatic
min samples), seeds 1..--seeds, run in turn so the machine's load reaches all alike. Each run's
figure is noise MSE x seconds (results.noise_mse; the fastest of the seeds' times): for
an unbiased renderer MSE falls as 1/time, so the product is the MSE at equal time up to a
constant (for plain Monte Carlo; the low-discrepancy samplers' MSE falls faster, which favours
the longer of two runs: scripts/study/adaptive.py interpolates at equal time instead). Stratum
also renders with adaptive_metric mse at study/adaptive.py's MSE_THRESHOLDS for the scene (or
--mse-threshold). The ratio adaptive / fixed of the products is the equal-time MSE ratio
(target <= 0.7 for Stratum); Cycles' own ratio is its adaptive sampling's on the same scene.
Mean samples per pixel are from the Debug Sample Count pass (Stratum) and from the render time
ratio (Cycles reports none to Python). Written to out/bench/adaptive.json and printed.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from scripts.bench.common import (
    StratumScene,
    configure_stratum,
    open_scene,
    run_main,
    script_argv,
    stratum_reason,
)
from scripts.bench.quality import SCENES, cycles_render, measure, references
from scripts.bench.results import noise_mse_seconds, write_section
from scripts.study.adaptive import MSE_THRESHOLDS


def parse_args() -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="scripts.bench.adaptive")
    p.add_argument("--res", type=int, default=128)
    p.add_argument("--samples", type=int, default=64)
    p.add_argument("--max-samples", type=int, default=1024)
    p.add_argument("--threshold", type=float, action="append", default=None)
    p.add_argument("--mse-threshold", type=float, default=None,
                   help="threshold of Stratum's adaptive_metric mse (default: the scene's, "
                        "scripts.study.adaptive.MSE_THRESHOLDS)")
    p.add_argument("--seeds", type=int, default=2)
    p.add_argument("--reference-samples", type=int, default=2048)
    p.add_argument("--scene", choices=sorted(SCENES), action="append", default=None)
    p.add_argument("--sampler", action="append", default=None)
    args = p.parse_args(script_argv())
    args.scene = args.scene or ["cornell_box", "wolf"]
    args.sampler = args.sampler or ["sobol", "zsobol", "random"]
    args.threshold = args.threshold or [0.01, 0.05]
    return args


def bench_scene(name: str, args: argparse.Namespace, tmp: Path) -> dict[str, Any]:
    scene = open_scene(SCENES[name], args.res, args.samples)
    configure_stratum(scene, args.samples)
    out: dict[str, Any] = {"cycles": {}, "stratum": {}}
    with StratumScene(scene) as st:
        (st_a, st_b, _), (cy_a, cy_b, _) = references(name, args, tmp, scene, st)
        runs: dict[tuple[str, str], list[tuple[np.ndarray, float, float]]] = {}
        mse_threshold = args.mse_threshold or MSE_THRESHOLDS.get(name, 0.05)
        # (label, threshold, metric); Cycles has the metric relative alone.
        configs = [("fixed", 0.0, "relative"),
                   *((f"adaptive {t:g}", t, "relative") for t in args.threshold),
                   (f"adaptive mse {mse_threshold:g}", mse_threshold, "mse")]
        for seed in range(1, args.seeds + 1):
            for label, threshold, metric in configs:
                if metric == "relative":
                    image, seconds = (
                        cycles_render(name, args, tmp, seed, args.samples) if threshold == 0.0
                        else cycles_render(name, args, tmp, seed, args.max_samples,
                                           adaptive_threshold=threshold))
                    runs.setdefault(("cycles", label), []).append((image, seconds, 0.0))
                for sampler in args.sampler:
                    overrides: dict[str, Any] = {"sampler": sampler, "seed": seed,
                                                 "passes": "Debug Sample Count"}
                    if threshold > 0.0:
                        overrides |= {"samples": args.max_samples, "use_adaptive_sampling": 1,
                                      "adaptive_threshold": threshold, "adaptive_metric": metric}
                    r = st.render(overrides, pixels=True, passes=("Debug Sample Count",))
                    runs.setdefault((sampler, label), []).append(
                        (r["rgb"], r["trace"], float(np.mean(r["Debug Sample Count"]))))
    for (who, label), rs in runs.items():
        a, b = (cy_a, cy_b) if who == "cycles" else (st_a, st_b)
        m = measure([im for im, _, _ in rs], [t for _, t, _ in rs], a, b)
        m["mean_samples"] = float(np.mean([n for _, _, n in rs])) if who != "cycles" else None
        out["cycles" if who == "cycles" else "stratum"].setdefault(who, {})[label] = m
    return out


def scene_lines(name: str, result: dict[str, Any]) -> list[str]:
    lines = [f"{name}:", (f"  {'':30s}{'noise MSE':>12s}{'seconds':>9s}{'mean spp':>10s}"
             f"{'MSE x s':>11s}{'/ fixed':>9s}")]
    groups = [("Cycles", result["cycles"]["cycles"])]
    groups += [(f"Stratum {s}", r) for s, r in result["stratum"].items()]
    for who, rows in groups:
        base = noise_mse_seconds(rows["fixed"])
        for label, r in rows.items():
            product = noise_mse_seconds(r)
            spp = "" if r["mean_samples"] is None else f"{r['mean_samples']:.0f}"
            lines.append(f"  {who + ' ' + label:30s}{r['noise_mse']:12.4e}{r['seconds']:9.3f}"
                         f"{spp:>10s}{product:11.3e}{product / base:8.3f}x")
    return lines


def main() -> int:
    args = parse_args()
    reason = stratum_reason()
    if reason:
        print(f"bench.adaptive: Stratum not available ({reason})", file=sys.stderr)
        return 2
    results: dict[str, Any] = {}
    lines = [(f"Adaptive vs fixed sampling at equal time: {args.res}x{args.res}, fixed "
             f"{args.samples} spp, adaptive up to {args.max_samples}, {args.seeds} seeds")]
    with tempfile.TemporaryDirectory(prefix="bench_adaptive") as tmp:
        for name in args.scene:
            results[name] = bench_scene(name, args, Path(tmp))
            lines += scene_lines(name, results[name])
    print("\n".join(lines))
    data = {"res": args.res, "samples": args.samples, "max_samples": args.max_samples,
            "thresholds": args.threshold, "seeds": args.seeds, "scenes": results}
    print(f"written {write_section('adaptive', data)}")
    return 0


if __name__ == "__main__":
    run_main(main)
