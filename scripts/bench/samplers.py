"""Samples per second of every sampler, and the cost of solid-angle against area triangle
sampling (issue 15, targets 1 and 3), on the Cornell box through the native Renderer.

    blender -b --factory-startup --python scripts/run_in_blender.py -- scripts.bench.samplers \
        [--res 128 --samples 64 --rounds 3]

The scene is exported once; every render is a fresh native Renderer on it with Stratum's
defaults (integrator path, estimator mis) and one setting changed. Renders are interleaved
(round 1: every sampler once, round 2: every sampler again, ...) so that a change of the
machine's load reaches all of them alike, and each figure is the fastest of --rounds runs (other
processes only add time). Samples per second = pixels x samples / path-tracing seconds
(progress().render_seconds). Reported: each sampler's samples/s and its ratio to `random`
(target for the Owen-scrambled sobol, zsobol and halton_owen: within 5 % of random, i.e.
samples/s >= 0.95 x random's), and the path-tracing time with triangle_sampling=solid_angle
over that with area (target <= 1.08). Written to out/bench/samplers.json and printed.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from scripts.bench.common import (
    CORNELL,
    StratumScene,
    configure_stratum,
    open_scene,
    run_main,
    script_argv,
    stratum_reason,
)
from scripts.bench.results import write_section

OWEN_SCRAMBLED = ("sobol", "zsobol", "halton_owen")


def parse_args() -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="scripts.bench.samplers")
    p.add_argument("--res", type=int, default=128)
    p.add_argument("--samples", type=int, default=64)
    p.add_argument("--rounds", type=int, default=3, help="interleaved runs of each setting")
    p.add_argument("--threads", type=int, default=0, help="0 = all cores")
    return p.parse_args(script_argv())


def interleaved(st: StratumScene, variants: dict[str, dict[str, int | float | str]],
                rounds: int) -> dict[str, dict[str, float]]:
    """Each variant's fastest path-tracing time and best samples/s over `rounds` interleaved
    rounds."""
    best: dict[str, dict[str, float]] = {}
    for _ in range(rounds):
        for name, overrides in variants.items():
            r = st.render(overrides)
            if r["samples_done"] == 0:
                raise RuntimeError(f"{name}: the render finished no sample")
            b = best.setdefault(name, {"trace": r["trace"], "samples_per_s": r["samples_per_s"]})
            b["trace"] = min(b["trace"], r["trace"])
            b["samples_per_s"] = max(b["samples_per_s"], r["samples_per_s"])
    return best


def main() -> int:
    args = parse_args()
    reason = stratum_reason()
    if reason:
        print(f"bench.samplers: Stratum not available ({reason})", file=sys.stderr)
        return 2
    from stratum import native

    samplers = [entry.name for entry in native.registry("sampler")]
    scene = open_scene(CORNELL, args.res, args.samples, args.threads)
    configure_stratum(scene, args.samples, args.threads)
    with StratumScene(scene) as st:
        by_sampler = interleaved(st, {name: {"sampler": name} for name in samplers},
                                 args.rounds)
        triangles = interleaved(st, {mode: {"triangle_sampling": mode}
                                     for mode in ("solid_angle", "area")}, args.rounds)
    random_rate = by_sampler["random"]["samples_per_s"]
    lines = [(f"Samplers on the Cornell box, {args.res}x{args.res}, {args.samples} spp, fastest "
              f"of {args.rounds} interleaved runs (native Renderer, defaults otherwise):"),
             f"  {'sampler':18s}{'M samples/s':>12s}{'/ random':>10s}{'seconds':>9s}"]
    for name in samplers:
        b = by_sampler[name]
        mark = "   Owen-scrambled: target >= 0.95" if name in OWEN_SCRAMBLED else ""
        lines.append(f"  {name:18s}{b['samples_per_s'] / 1e6:12.3f}"
                     f"{b['samples_per_s'] / random_rate:9.3f}x{b['trace']:9.3f}{mark}")
    cost = triangles["solid_angle"]["trace"] / triangles["area"]["trace"]
    lines += ["", (f"Triangle sampling, same scene and runs: solid_angle "
                   f"{triangles['solid_angle']['trace']:.3f} s, area "
                   f"{triangles['area']['trace']:.3f} s, cost ratio {cost:.3f} (target <= 1.08)")]
    print("\n".join(lines))
    data: dict[str, Any] = {"res": args.res, "samples": args.samples, "rounds": args.rounds,
                            "threads": args.threads, "samplers": by_sampler,
                            "owen_scrambled": list(OWEN_SCRAMBLED),
                            "triangle_sampling": triangles}
    print(f"written {write_section('samplers', data)}")
    return 0


if __name__ == "__main__":
    run_main(main)
