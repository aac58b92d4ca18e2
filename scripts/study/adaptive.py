"""The adaptive-sampling part of `make study` (issue 16, item 4 and acceptance 4): adaptive
against fixed sampling at equal time, per sampler, on the Cornell box and Wolf;
out/study/adaptive.md. run.py runs it.

| run                      | scene      | what it tests                                       |
|--------------------------|------------|-----------------------------------------------------|
| adaptive_<scene>_<sampler> | cornell_box, wolf | the path tracer fixed, with use_adaptive_sampling |
|                          |            | (metric relative, Cycles': threshold 0.02) and with   |
|                          |            | metric mse (threshold per scene), min samples 16, at  |
|                          |            | 64-1024 spp: MSE at equal time, adaptive / fixed      |
|                          |            | (target <= 0.7)                                       |

One `stratum compare` per scene and sampler (sobol, zsobol, random), three estimators each; for
the adaptive ones "spp" is the most samples a pixel may take. The metric mse's threshold is the
image's RMS error relative to its mean brightness, so it is a scene's own: per scene the one at
which pixels take about a fifth of the most samples on average (Cornell box 0.1, Wolf 0.03,
measured at 64², sobol: 228 and 165 of 1024). Equal time as in estimators.py (MSE
interpolated in log-log at the largest path-tracing time both reached). Cycles' own adaptive
sampling against its fixed sampling, measured the same way (noise MSE x seconds), is in `make
bench` (scripts/bench/adaptive.py), read here when present.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from scripts import REPO
from scripts.bench.results import noise_mse_seconds
from scripts.study.estimators import equal_time
from scripts.study.results import fmt, series_means

# The metric mse's threshold per scene file (the module doc); scripts/bench/adaptive.py uses it too.
MSE_THRESHOLDS = {"cornell_box": 0.1, "wolf": 0.03}
# scene -> (file, resolution, the metric mse's threshold)
SCENES = {"cornell": ("scenes/cornell_box.blend", "128x128", MSE_THRESHOLDS["cornell_box"]),
          "wolf": ("scenes/wolf.blend", "160x120", MSE_THRESHOLDS["wolf"])}
SAMPLERS = ("sobol", "zsobol", "random")
THRESHOLD = 0.02
FIXED = "mis-power"
BENCH_ADAPTIVE = REPO / "out" / "bench" / "adaptive.json"


def run_name(scene: str, sampler: str) -> str:
    return f"adaptive_{scene}_{sampler}"


def plan_runs(quick: bool, run_type: Any) -> list[Any]:
    """The runs as run.py Runs."""
    if quick:
        spp, seeds, reference_spp, min_samples = [8, 16], 2, 64, 4
    else:
        spp, seeds, reference_spp, min_samples = [64, 256, 1024], 4, 4096, 16
    runs = []
    for scene, (path, resolution, mse_threshold) in SCENES.items():
        specs = (f"path,path:use_adaptive_sampling=1,adaptive_threshold={THRESHOLD},"
                 f"adaptive_min_samples={min_samples},"
                 f"path:use_adaptive_sampling=1,adaptive_threshold={mse_threshold},"
                 f"adaptive_min_samples={min_samples},adaptive_metric=mse")
        for sampler in SAMPLERS:
            extra = ["--integrator", specs, "--reference-integrator", "path",
                     "--reference-sampler", "sobol"]
            runs.append(run_type(run_name(scene, sampler), path, sampler, spp, seeds,
                                 "32x32" if quick else resolution, reference_spp, extra))
    return runs


def metric_of(series: str) -> str:
    """relative or mse, from an adaptive series' label (estimators.make_label)."""
    return "mse" if "metric-mse" in series else "relative"


def scene_table(results: dict[str, dict[str, Any]]) -> tuple[list[str], dict[str, Any]]:
    lines = [("| sampler | metric | most spp | fixed MSE | adaptive MSE | path-tracing s fixed / "
              "adaptive | MSE at equal time, adaptive / fixed |"), "|---|---|---|---|---|---|---|"]
    numbers: dict[str, Any] = {}
    for sampler, res in results.items():
        spps = sorted(int(s) for s in res["spp"])
        top = spps[-1]
        mse, seconds = series_means(res, "mse"), series_means(res, "trace_seconds")
        for adaptive in (s for s in res["series"] if s != FIXED):
            # Equal time between fixed sampling and this adaptive series alone.
            pair = {**res, "series": [k for k in res["series"] if k in (FIXED, adaptive)]}
            budget, at_budget = equal_time(pair)
            ratio = at_budget[adaptive][0] / at_budget[FIXED][0]
            metric = metric_of(adaptive)
            numbers.setdefault(sampler, {})[metric] = {
                "series": adaptive, "equal_time_seconds": budget, "ratio": ratio,
                "mse": {FIXED: mse[(FIXED, top)], adaptive: mse[(adaptive, top)]}}
            lines.append(f"| {sampler} | {metric} | {top} | {fmt(mse[(FIXED, top)])} | "
                         f"{fmt(mse[(adaptive, top)])} | {fmt(seconds[(FIXED, top)], 3)} / "
                         f"{fmt(seconds[(adaptive, top)], 3)} | {fmt(ratio, 3)} |")
    return lines, numbers


def cycles_lines(path: Path) -> tuple[list[str], dict[str, Any]]:
    if not path.is_file():
        return [(f"(not measured: {path} is missing; `make bench` runs "
                 "scripts/bench/adaptive.py)")], {}
    data = json.loads(path.read_text())
    lines = [(f"{data['res']}x{data['res']}, fixed {data['samples']} spp, adaptive up to "
              f"{data['max_samples']}, {data['seeds']} seeds; noise MSE x path-tracing seconds "
              "of adaptive over fixed."), "", "| scene | renderer | (metric) threshold | / fixed |",
             "|---|---|---|---|"]
    numbers: dict[str, Any] = {}
    for scene, r in data["scenes"].items():
        groups = [("Cycles", r["cycles"]["cycles"]), *r["stratum"].items()]
        for who, runs in groups:
            fixed = noise_mse_seconds(runs["fixed"])
            for label, run in runs.items():
                if label == "fixed":
                    continue
                value = noise_mse_seconds(run) / fixed
                numbers.setdefault(scene, {}).setdefault(who, {})[label] = value
                lines.append(f"| {scene} | {who} | {label.removeprefix('adaptive ')} | "
                             f"{fmt(value, 3)} |")
    return lines, numbers


def write_page(out: Path, load: Any) -> tuple[str, dict[str, Any]]:
    """out/adaptive.md from the runs' results.json and bench/adaptive.py's figures; returns its
    text and the numbers (for headline.json)."""
    parts = ["# Adaptive sampling study (issue 16)", "",
             ("Generated by `scripts/study/run.py` (`make study`). MSE is the mean over seeds "
              "against the reference; equal time: MSE interpolated in log-log at the largest "
              "path-tracing time both reached. For the adaptive runs \"most spp\" is the most "
              "samples a pixel may take."), ""]
    numbers: dict[str, Any] = {}
    for scene in SCENES:
        results = {s: r for s in SAMPLERS if (r := load(out, run_name(scene, s))) is not None}
        if not results:
            continue
        lines, numbers[scene] = scene_table(results)
        parts += [(f"## {scene}: adaptive (relative: threshold {THRESHOLD:g}; mse: threshold "
                   f"{SCENES[scene][2]:g}) against fixed sampling"), "", *lines, ""]
    lines, numbers["bench"] = cycles_lines(BENCH_ADAPTIVE)
    parts += ["## With Cycles' adaptive sampling (make bench)", "", *lines, ""]
    text = "\n".join(parts)
    (out / "adaptive.md").write_text(text)
    print(f"study: wrote {out / 'adaptive.md'}")
    return text, numbers
