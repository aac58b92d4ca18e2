"""The summary of `make study` (run.py): reads every out/study/<run>/results.json and writes
out/study/summary.md (MSE and FLIP ratios to `lcg`, the coursework's "Standard"; slopes;
absolute errors with their 95 % intervals; the low-pass block MSE; the AO table; the pages of
estimators.py, lights.py, adaptive.py, radiosity.py and guiding.py) and out/study/headline.json
(the same numbers).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from scripts.study import adaptive, estimators, lights, radiosity
from scripts.study.results import ci_of, fmt, load_results, mean_of

BASELINE = "lcg"  # the coursework's "Standard" sampler
AO_HEMISPHERES = ("uniform_angles", "uniform", "cosine")
AO_SAMPLERS = ("random", "fibonacci", "fibonacci_static")


BLOCK = 4  # block size of the low-pass MSE


def block_mse(out: Path, name: str, results: dict[str, Any]) -> dict[tuple[str, int], float]:
    """Mean over seeds of the MSE of the error's BLOCK x BLOCK block means, per (sampler, spp).

    Plain MSE is blind to how the error is arranged: a per-pixel-independent error and the same
    error copied into bands have equal MSE. Averaging BLOCK^2 pixels divides uncorrelated
    (white) error by ~BLOCK^2 and blue-noise error by more, but leaves correlated error
    (banding, structured patterns) nearly intact, so block MSE / MSE measures how visible
    the error's structure is: ~1/16 for white noise, ~1 for banding."""
    import numpy as np
    from stratum.compare.exr import read_rgb

    reference = read_rgb(out / name / results["reference"]["path"]).astype(np.float64)
    h, w = (reference.shape[0] // BLOCK) * BLOCK, (reference.shape[1] // BLOCK) * BLOCK
    sums: dict[tuple[str, int], list[float]] = {}
    for row in results["renders"]:
        err = read_rgb(out / name / row["path"]).astype(np.float64) - reference
        blocks = err[:h, :w].reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK, 3).mean(axis=(1, 3))
        sums.setdefault((row["sampler"], int(row["spp"])), []).append(float(np.mean(blocks ** 2)))
    return {k: float(np.mean(v)) for k, v in sums.items()}


def block_table(results: dict[str, Any], blocks: dict[tuple[str, int], float],
                spps: list[int]) -> tuple[str, dict]:
    """Block MSE ratio to lcg, and block MSE / MSE (the error's structure), per spp."""
    lines = ["| sampler | " + " | ".join(f"{s} spp" for s in spps) + " |",
             "|" + "---|" * (len(spps) + 1)]
    numbers: dict[str, dict[str, Any]] = {}
    for sampler in results["samplers"]:
        cells = []
        numbers[sampler] = {}
        for spp in spps:
            b, b0 = blocks.get((sampler, spp)), blocks.get((BASELINE, spp))
            m = mean_of(results, sampler, spp, "mse")
            ratio = b / b0 if b is not None and b0 else None
            share = b / m if b is not None and m else None
            numbers[sampler][str(spp)] = {"ratio_to_lcg": ratio, "block_over_mse": share}
            cells.append(f"{fmt(ratio, 2)} ({fmt(share, 2)})")
        lines.append(f"| {sampler} | " + " | ".join(cells) + " |")
    return "\n".join(lines), numbers


def ratio_table(results: dict[str, Any], metric: str, spps: list[int]) -> tuple[str, dict]:
    """Markdown table of mean(metric) / mean(metric of lcg) per sampler and spp, plus the MSE
    slope; returns the table and the numbers."""
    samplers = results["samplers"]
    numbers: dict[str, dict[str, Any]] = {}
    head = "| sampler | " + " | ".join(f"{s} spp" for s in spps) + " | MSE slope |"
    lines = [head, "|" + "---|" * (len(spps) + 2)]
    for sampler in samplers:
        cells = []
        numbers[sampler] = {}
        for spp in spps:
            m, b = mean_of(results, sampler, spp, metric), mean_of(results, BASELINE, spp, metric)
            r = m / b if m is not None and b else None
            numbers[sampler][str(spp)] = r
            cells.append(fmt(r, 2))
        slope = results.get("slopes", {}).get(sampler, {}).get("mse")
        numbers[sampler]["mse_slope"] = slope
        lines.append(f"| {sampler} | " + " | ".join(cells) + f" | {fmt(slope, 3)} |")
    return "\n".join(lines), numbers


def absolute_table(results: dict[str, Any], metric: str, spps: list[int]) -> str:
    lines = ["| sampler | " + " | ".join(f"{s} spp" for s in spps) + " |",
             "|" + "---|" * (len(spps) + 1)]
    for sampler in results["samplers"]:
        cells = []
        for spp in spps:
            m, ci = mean_of(results, sampler, spp, metric), ci_of(results, sampler, spp, metric)
            half = (ci[1] - ci[0]) / 2 if ci else None
            cells.append(f"{fmt(m, 3)} ± {fmt(half, 1)}")
        lines.append(f"| {sampler} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def ao_table(out: Path) -> tuple[str, dict]:
    """Per hemisphere x sampler x rays: MSE (mean over seeds), its ratio to random + cosine at
    the same number of rays (the article's best pseudo-random case), and block MSE / MSE (how
    much of the error is spatially correlated: banding)."""
    data: dict[str, dict[str, dict[str, Any]]] = {}
    spps: list[int] = []
    for h in AO_HEMISPHERES:
        res = load_results(out, f"ao_{h}")
        if res is None:
            continue
        spps = res["spp"]
        blocks = block_mse(out, f"ao_{h}", res)
        data[h] = {s: {str(n): {"mse": mean_of(res, s, n, "mse"),
                                "flip_ldr": mean_of(res, s, n, "flip_ldr"),
                                "block_mse": blocks.get((s, n))} for n in spps}
                   for s in res["samplers"]}
    if not data:
        return "(no AO results)", {}
    base = data.get("cosine", {}).get("random", {})
    lines = ["| distribution | sampler | " + " | ".join(f"MSE {n} rays" for n in spps)
             + " | MSE / random+cosine | block MSE / MSE | LDR-FLIP |",
             "|---|---|" + "---|" * (len(spps) + 3)]
    for h, by_sampler in data.items():
        for s, by_spp in by_sampler.items():
            cells = [fmt(by_spp[str(n)]["mse"], 3) for n in spps]
            ratios, shares, flips = [], [], []
            for n in spps:
                v, b0 = by_spp[str(n)], base.get(str(n), {})
                ratios.append(fmt((v["mse"] or math.nan) / (b0.get("mse") or math.nan), 2))
                shares.append(fmt((v["block_mse"] or math.nan) / (v["mse"] or math.nan), 2))
                flips.append(fmt(v["flip_ldr"], 3))
            lines.append(f"| {h} | {s} | " + " | ".join(cells) + " | " + " / ".join(ratios)
                         + " | " + " / ".join(shares) + " | " + " / ".join(flips) + " |")
    return "\n".join(lines), data


def write_summary(out: Path, log: list[dict[str, Any]]) -> None:
    parts = ["# Sampler study: headline numbers", "",
             ("Generated by `scripts/study/run.py` (`make study`) from out/study/*/results.json. "
             "Ratios are mean MSE (or FLIP) over seeds divided by that of `lcg` (the "
             "coursework's Standard sampler) at the same spp; < 1 is better. Slopes are "
             "log-log slopes of mean MSE vs spp (-1 = plain Monte Carlo)."), ""]
    headline: dict[str, Any] = {"runs": log}
    for name in ("cornell", "wolf"):
        res = load_results(out, name)
        if res is None:
            continue
        spps = res["spp"]
        ref = res["reference"]
        parts += [(f"## {name} ({res['resolution'][0]}x{res['resolution'][1]}, "
                  f"{len(res['seeds'])} seeds, reference {ref.get('source')} "
                  f"{ref.get('spp')} spp x {len(ref.get('seeds') or [])}, noise floor MSE "
                  f"{fmt((ref.get('noise_floor') or {}).get('mse'), 2)})"), "",
                  "MSE ratio to lcg:", ""]
        table, numbers = ratio_table(res, "mse", spps)
        parts += [table, "", "FLIP (LDR) ratio to lcg:", ""]
        flip_table, flip_numbers = ratio_table(res, "flip_ldr", spps)
        parts += [flip_table.replace(" MSE slope |", " (MSE slope) |"), "",
                  "Mean MSE ± half the 95 % interval over seeds:", "",
                  absolute_table(res, "mse", spps), "",
                  "Mean LDR-FLIP ± half the 95 % interval:", "",
                  absolute_table(res, "flip_ldr", spps), ""]
        blocks_text, block_numbers = block_table(res, block_mse(out, name, res), spps)
        parts += [(f"Low-pass error: MSE of {BLOCK}x{BLOCK} block means, ratio to lcg (in "
                  "brackets block MSE / MSE: ~1/16 white noise, less for blue noise, more "
                  "for structured error):"), "", blocks_text, ""]
        headline[name] = {"mse_ratio": numbers, "flip_ldr_ratio": flip_numbers,
                          "block_mse": block_numbers,
                          "slopes": res.get("slopes", {}), "reference": ref}
    table, numbers = ao_table(out)
    parts += ["## AO (scenes/ao_study.blend, integrator ao)", "",
              ("Mean over seeds at each number of rays (a / b / c = 8 / 16 / 32 rays). "
              f"Block MSE = MSE of {BLOCK}x{BLOCK} block means of the error: block MSE / MSE "
              "is ~1/16 for independent pixel errors and ~1 for banding."), "",
              table, ""]
    headline["ao_mse"] = numbers
    estimator_text, headline["estimators"] = estimators.write_page(out, load_results)
    if headline["estimators"]:
        parts += ["## Estimators (issue 6)", "", "Also in estimators.md:", "",
                  estimator_text.split("\n", 1)[1].replace("\n## ", "\n### "), ""]
    lights_text, headline["lights"] = lights.write_page(out, load_results)
    parts += ["## Light selection (issue 16)", "", "Also in lights.md:", "",
              lights_text.split("\n", 1)[1].replace("\n## ", "\n### "), ""]
    adaptive_text, headline["adaptive"] = adaptive.write_page(out, load_results)
    parts += ["## Adaptive sampling (issue 16)", "", "Also in adaptive.md:", "",
              adaptive_text.split("\n", 1)[1].replace("\n## ", "\n### "), ""]
    radiosity_text, headline["radiosity"] = radiosity.write_page(out, load_results)
    parts += ["## Radiosity solvers (issue 17)", "", "Also in radiosity.md:", "",
              radiosity_text.split("\n", 1)[1].replace("\n## ", "\n### "), ""]
    # Path guiding's page is written by guiding.py under the bpy wheel (Cycles'
    # guiding), so it is read as that script left it.
    guiding = out / "guiding.md"
    if guiding.exists():
        parts += ["## Path guiding (issue 17)", "", "Also in guiding.md:", "",
                  guiding.read_text().split("\n", 1)[1].replace("\n## ", "\n### "), ""]
    if log:
        total = sum(r["seconds"] for r in log)
        parts += ["## Run time", "", "| run | minutes |", "|---|---|"]
        parts += [f"| {r['name']} | {r['seconds'] / 60:.1f} |" for r in log]
        parts += [f"| total | {total / 60:.1f} |", ""]
    (out / "summary.md").write_text("\n".join(parts))
    (out / "headline.json").write_text(json.dumps(headline, indent=1))
    print(f"study: wrote {out / 'summary.md'} and {out / 'headline.json'}")

