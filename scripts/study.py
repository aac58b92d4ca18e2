"""`make study`: the sampler study of issue 4, regenerated from scratch into out/study/.

Every part is one `stratum compare` run into out/study/<name>/ (renders, results.json,
results.csv, report.html, figures/); compare skips configurations it has already rendered, so
re-running after an interruption only renders what is missing. Then this script reads every
results.json and writes out/study/summary.md (the headline tables: MSE ratios vs `lcg`, the
coursework's "Standard", slopes, FLIP at low spp, the AO table) and a few figures of its own
into out/study/figures/ (the AO image tables of the article, image grids with magnified
crops). docs/study.md discusses the numbers.

The runs (the source documents' experiments, with more samplers, seeds and spp):

* cornell: scenes/cornell_box.blend, every sampler, 1..128 spp (powers of two), 4 seeds,
  128x128, reference = mean of 4 sobol renders at 1024 spp (coursework: 8, 64, 128 spp);
* wolf: scenes/wolf.blend (215k triangles), every sampler, 1, 2, 4, 8 spp, 4 seeds, 320x240,
  reference 4 x 256 spp (coursework: 1, 2, 8 spp);
* ao_<hemisphere>: scenes/ao_study.blend with integrator ao, each hemisphere distribution of
  the article (uniform_angles, uniform, cosine) x {random ("pseudo-random"), fibonacci (random
  per-pixel shift = rotation about the normal), fibonacci_static (one shift for every pixel)}
  at 8, 16, 32 rays (= spp, one AO ray per sample), 4 seeds. The three runs share one
  reference (rendered by the cosine run; every estimator is unbiased, so it is the same image);
* est_small, est_large, est_glossy: the estimator ladder of issue 6 (bsdf, nee by area and by
  solid angle, mis-balance / power / max, mis-power by area, light, direct) on the Cornell box with a small light, a large light and glossy
  surfaces (scripts/study_estimators.py); out/study/estimators.md has their tables (MSE at
  equal samples and at equal time) and the textbook's claims checked against them.

    .venv/bin/python scripts/study.py [--out out/study] [--jobs 2] [--only cornell,wolf]
                                      [--quick] [--dry-run] [--summary-only]
                                      [--docs docs/study]

--quick runs the same study at toy sizes (to test the pipeline in a minute or two).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "addon"))  # this checkout's stratum, for study_estimators
sys.path.insert(0, str(Path(__file__).resolve().parent))
import study_estimators

BASELINE = "lcg"  # the coursework's "Standard" sampler
AO_HEMISPHERES = ("uniform_angles", "uniform", "cosine")
AO_SAMPLERS = ("random", "fibonacci", "fibonacci_static")
AO_REFERENCE_RUN = "ao_cosine"
# Samplers shown in the image grids: the coursework's five, plus the two Sobol variants.
GRID_SAMPLERS = ("lcg", "halton", "halton_rd", "halton_owen", "bluenoise", "sobol", "zsobol")
# Magnified crops (x, y, w, h from the top left, as fractions of the image): floor regions as in
# the coursework's figures (Cornell: lower left floor; Wolf: the floor in the wolf's shadow).
CROPS = {"cornell": (0.06, 0.66, 0.31, 0.31), "wolf": (0.53, 0.62, 0.2, 0.27)}


@dataclass
class Run:
    name: str
    scene: str
    samplers: str
    spp: list[int]
    seeds: int
    resolution: str | None = None
    reference_spp: int | None = None
    extra: list[str] = field(default_factory=list)
    reference_from: str | None = None  # the name of a run whose reference.exr this one reuses

    def command(self, out: Path, jobs: int) -> list[str]:
        cmd = [sys.executable, "-m", "stratum.cli", "compare", str(REPO / self.scene),
               "--samplers", self.samplers, "--spp", ",".join(str(s) for s in self.spp),
               "--seeds", str(self.seeds), "--out", str(out / self.name), "--jobs", str(jobs)]
        if self.resolution:
            cmd += ["--resolution", self.resolution]
        if self.reference_from is not None:
            cmd += ["--reference", str(out / self.reference_from / "renders" / "reference.exr")]
        elif self.reference_spp is not None:
            cmd += ["--reference-spp", str(self.reference_spp)]
        return cmd + self.extra


def plan_runs(quick: bool) -> list[Run]:
    if quick:
        cornell = Run("cornell", "scenes/cornell_box.blend", "lcg,halton,sobol,bluenoise",
                      [1, 2, 4], 2, "32x32", 32)
        wolf = Run("wolf", "scenes/wolf.blend", "lcg,halton,sobol,bluenoise", [1, 2], 2, "80x60",
                   16)
        ao_spp, ao_seeds, ao_res, ao_ref = [8, 16], 2, "64x48", 64
    else:
        cornell = Run("cornell", "scenes/cornell_box.blend", "all",
                      [1, 2, 4, 8, 16, 32, 64, 128], 4, "128x128", 1024)
        wolf = Run("wolf", "scenes/wolf.blend", "all", [1, 2, 4, 8], 4, None, 256)
        ao_spp, ao_seeds, ao_res, ao_ref = [8, 16, 32], 4, None, 1024
    runs = [cornell, wolf]
    # The cosine run first: it renders the reference the other two reuse.
    for hemisphere in sorted(AO_HEMISPHERES, key=lambda h: h != "cosine"):
        name = f"ao_{hemisphere}"
        runs.append(Run(name, "scenes/ao_study.blend", ",".join(AO_SAMPLERS), ao_spp, ao_seeds,
                        ao_res, ao_ref, ["--integrator", "ao", "--hemisphere", hemisphere],
                        None if name == AO_REFERENCE_RUN else AO_REFERENCE_RUN))
    return runs + study_estimators.plan_runs(quick, Run)


# ---- running ---------------------------------------------------------------------------------


def run_all(runs: list[Run], out: Path, jobs: int, dry_run: bool) -> list[dict[str, Any]]:
    log: list[dict[str, Any]] = []
    for run in runs:
        cmd = run.command(out, jobs)
        print("study:", " ".join(cmd), flush=True)
        if dry_run:
            continue
        start = time.monotonic()
        # This checkout's add-on, not whichever one the venv has installed (editable).
        path = os.pathsep.join(p for p in (str(REPO / "addon"), os.environ.get("PYTHONPATH"))
                               if p)
        code = subprocess.call(cmd, cwd=REPO, env={**os.environ, "PYTHONPATH": path})
        seconds = time.monotonic() - start
        print(f"study: {run.name} finished in {seconds / 60:.1f} min (exit {code})", flush=True)
        log.append({"name": run.name, "command": cmd, "seconds": seconds, "exit_code": code})
        if code != 0:
            raise SystemExit(f"study: `stratum compare` failed for {run.name} (exit {code})")
    return log


# ---- summary -----------------------------------------------------------------------------


def load_results(out: Path, name: str) -> dict[str, Any] | None:
    path = out / name / "results.json"
    return json.loads(path.read_text()) if path.is_file() else None


def mean_of(results: dict[str, Any], sampler: str, spp: int, metric: str) -> float | None:
    for row in results["summary"]:
        if row["sampler"] == sampler and row["spp"] == spp and row["metric"] == metric:
            return float(row["mean"])
    return None


def ci_of(results: dict[str, Any], sampler: str, spp: int,
          metric: str) -> tuple[float, float] | None:
    for row in results["summary"]:
        if row["sampler"] == sampler and row["spp"] == spp and row["metric"] == metric:
            return float(row["ci95_low"]), float(row["ci95_high"])
    return None


def fmt(x: float | None, digits: int = 3) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return f"{x:.{digits}g}"


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
             ("Generated by `scripts/study.py` (`make study`) from out/study/*/results.json. "
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
    estimator_text, headline["estimators"] = study_estimators.write_page(out, load_results)
    if headline["estimators"]:
        parts += ["## Estimators (issue 6)", "", "Also in estimators.md:", "",
                  estimator_text.split("\n", 1)[1].replace("\n## ", "\n### "), ""]
    if log:
        total = sum(r["seconds"] for r in log)
        parts += ["## Run time", "", "| run | minutes |", "|---|---|"]
        parts += [f"| {r['name']} | {r['seconds'] / 60:.1f} |" for r in log]
        parts += [f"| total | {total / 60:.1f} |", ""]
    (out / "summary.md").write_text("\n".join(parts))
    (out / "headline.json").write_text(json.dumps(headline, indent=1))
    print(f"study: wrote {out / 'summary.md'} and {out / 'headline.json'}")


# ---- figures -------------------------------------------------------------------------------


def srgb8(linear: Any) -> Any:
    import numpy as np

    x = np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0)
    s = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)
    return (s * 255.0 + 0.5).astype(np.uint8)


def render_path(res: dict[str, Any], sampler: str, spp: int, seed: int = 0) -> str | None:
    for row in res["renders"]:
        if row["sampler"] == sampler and row["spp"] == spp and row["seed"] == seed:
            return str(row["path"])
    return None


def image_grid(out: Path, name: str, spp: int, gain: float = 1.0) -> Path | None:
    """Reference and each GRID_SAMPLERS render (seed 0) at spp: the full image with the crop
    marked, and the crop magnified and brightened (as in the coursework's figures 35-38)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle
    from stratum.compare.exr import read_rgb

    res = load_results(out, name)
    if res is None:
        return None
    width, height = res["resolution"]
    fx, fy, fw, fh = CROPS[name]
    x, y = int(fx * width), int(fy * height)
    w, h = max(4, int(fw * width)), max(4, int(fh * height))
    columns = [("reference", res["reference"]["path"])]
    columns += [(s, render_path(res, s, spp)) for s in GRID_SAMPLERS if s in res["samplers"]]
    columns = [(label, p) for label, p in columns if p]
    fig, axes = plt.subplots(2, len(columns), figsize=(1.6 * len(columns), 3.4), squeeze=False)
    for i, (label, rel) in enumerate(columns):
        img = read_rgb(out / name / rel)
        axes[0][i].imshow(srgb8(img))
        axes[0][i].add_patch(Rectangle((x, y), w, h, fill=False, edgecolor="yellow", lw=0.8))
        axes[1][i].imshow(srgb8(gain * img[y:y + h, x:x + w]), interpolation="nearest")
        axes[0][i].set_title(label if label == "reference" else f"{label}\n{spp} spp",
                             fontsize=7)
        for ax in (axes[0][i], axes[1][i]):
            ax.set_xticks([])
            ax.set_yticks([])
    fig.suptitle(f"{name}: seed 0 at {spp} spp; bottom: crop x{gain:g} brightness", fontsize=8)
    fig.tight_layout()
    path = out / "figures" / f"{name}_grid_{spp}spp.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def ao_grids(out: Path) -> list[Path]:
    """The article's tables 2 and 3: rows = distributions with pseudo-random numbers (table 2),
    or random / fibonacci / fibonacci_static with the cosine distribution (table 3); columns =
    8, 16, 32 rays; each cell the seed-0 AO image."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from stratum.compare.exr import read_rgb

    paths: list[Path] = []
    tables = {
        "ao_table2_distributions": [(f"ao_{h}", "random", h) for h in AO_HEMISPHERES],
        "ao_table3_fibonacci": [("ao_cosine", s, s) for s in AO_SAMPLERS],
    }
    for fig_name, rows in tables.items():
        loaded = [(load_results(out, run), s, label) for run, s, label in rows]
        loaded = [(r, s, label, run) for (r, s, label), (run, _, _) in zip(loaded, rows)
                  if r is not None]
        if not loaded:
            continue
        spps = loaded[0][0]["spp"]
        fig, axes = plt.subplots(len(loaded), len(spps),
                                 figsize=(2.2 * len(spps), 1.8 * len(loaded)), squeeze=False)
        for i, (res, sampler, label, run) in enumerate(loaded):
            for j, spp in enumerate(spps):
                ax = axes[i][j]
                rel = render_path(res, sampler, spp)
                if rel is not None:
                    ax.imshow(srgb8(read_rgb(out / run / rel)), interpolation="nearest")
                mse = mean_of(res, sampler, spp, "mse")
                ax.set_title(f"{label}, {spp} rays  MSE {fmt(mse, 2)}", fontsize=6)
                ax.set_xticks([])
                ax.set_yticks([])
        fig.tight_layout()
        path = out / "figures" / f"{fig_name}.png"
        fig.savefig(path, dpi=100)
        plt.close(fig)
        paths.append(path)
    return paths


def ratio_plot(out: Path) -> Path | None:
    """MSE / MSE(lcg) vs spp for every sampler, Cornell and Wolf side by side."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = [(n, load_results(out, n)) for n in ("cornell", "wolf")]
    runs = [(n, r) for n, r in runs if r is not None]
    if not runs:
        return None
    fig, axes = plt.subplots(1, len(runs), figsize=(5.2 * len(runs), 3.8), squeeze=False)
    for ax, (name, res) in zip(axes[0], runs):
        colors = plt.get_cmap("tab20").colors
        for k, sampler in enumerate(res["samplers"]):
            xs, ys = [], []
            for spp in res["spp"]:
                m, b = mean_of(res, sampler, spp, "mse"), mean_of(res, BASELINE, spp, "mse")
                if m is not None and b:
                    xs.append(spp)
                    ys.append(m / b)
            style = "-" if sampler in GRID_SAMPLERS else "--"
            ax.plot(xs, ys, style, marker="osv^D<>ph*Xd"[k % 12], ms=3, label=sampler,
                    color=colors[(2 * k) % 20 + (2 * k) // 20])
        ax.axhline(0.5, color="grey", lw=0.6, ls=":")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel("spp")
        ax.set_ylabel("mean MSE / mean MSE of lcg")
        ax.set_title(name)
        ax.grid(True, which="both", lw=0.3)
    axes[0][-1].legend(fontsize=6, ncol=2)
    fig.tight_layout()
    path = out / "figures" / "mse_ratio_to_lcg.png"
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def make_figures(out: Path) -> None:
    (out / "figures").mkdir(parents=True, exist_ok=True)
    made = [image_grid(out, "cornell", 8, gain=2.0), image_grid(out, "wolf", 1, gain=1.0),
            image_grid(out, "wolf", 8, gain=1.0), ratio_plot(out), *ao_grids(out),
            study_estimators.mse_figure(out, load_results)]
    for p in made:
        if p is not None:
            print(f"study: wrote {p}")


# The figures docs/study.md shows: (source under out/study, name under docs/study).
DOC_FIGURES = (
    ("figures/mse_ratio_to_lcg.png", "mse_ratio_to_lcg.png"),
    ("figures/cornell_grid_8spp.png", "cornell_grid_8spp.png"),
    ("figures/wolf_grid_1spp.png", "wolf_grid_1spp.png"),
    ("wolf/figures/error_spectra.png", "wolf_error_spectra.png"),
    ("wolf/figures/convergence_flip_ldr.png", "wolf_convergence_flip_ldr.png"),
    ("figures/ao_table2_distributions.png", "ao_table2_distributions.png"),
    ("figures/ao_table3_fibonacci.png", "ao_table3_fibonacci.png"),
    ("figures/estimators_mse.png", "estimators_mse.png"),
    ("est_small/figures/convergence_mse.png", "est_small_convergence_mse.png"),
    ("est_large/figures/convergence_mse.png", "est_large_convergence_mse.png"),
    ("est_glossy/figures/convergence_mse.png", "est_glossy_convergence_mse.png"),
)
DOC_MAX_BYTES = 300_000


def export_docs(out: Path, docs: Path) -> None:
    """Copies DOC_FIGURES into docs as 256-colour PNGs (each under DOC_MAX_BYTES, halving the
    size until it fits), so the repository stays small."""
    from PIL import Image

    docs.mkdir(parents=True, exist_ok=True)
    for src, name in DOC_FIGURES:
        if not (out / src).is_file():
            print(f"study: {out / src} missing, not copied")
            continue
        img = Image.open(out / src).convert("RGB")
        while True:
            img.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(
                docs / name, optimize=True)
            if (docs / name).stat().st_size <= DOC_MAX_BYTES or img.width < 400:
                break
            img = img.resize((img.width * 3 // 4, img.height * 3 // 4), Image.LANCZOS)
        print(f"study: wrote {docs / name} ({(docs / name).stat().st_size // 1000} KB)")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(REPO / "out" / "study"))
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--only", help="comma-separated run names (cornell, wolf, ao_cosine, "
                   "est_small, est_large, est_glossy, ...)")
    p.add_argument("--quick", action="store_true", help="toy sizes, to test the pipeline")
    p.add_argument("--dry-run", action="store_true", help="print the commands only")
    p.add_argument("--summary-only", action="store_true",
                   help="no rendering: rebuild summary.md and the figures from results.json")
    p.add_argument("--docs", metavar="DIR",
                   help="also copy the figures docs/study.md shows into DIR (e.g. docs/study)")
    args = p.parse_args(argv)
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    runs = plan_runs(args.quick)
    if args.only:
        wanted = set(args.only.split(","))
        unknown = wanted - {r.name for r in runs}
        if unknown:
            p.error(f"unknown run(s) {sorted(unknown)}; runs: {[r.name for r in runs]}")
        runs = [r for r in runs if r.name in wanted]
    log_path = out / "runs.json"
    previous = json.loads(log_path.read_text()) if log_path.is_file() else []
    if not args.summary_only:
        log = run_all(runs, out, args.jobs, args.dry_run)
        if args.dry_run:
            return 0
        done = {r["name"] for r in log}
        log = [r for r in previous if r["name"] not in done] + log
        log_path.write_text(json.dumps(log, indent=1))
    else:
        log = previous
    write_summary(out, log)
    make_figures(out)
    if args.docs:
        export_docs(out, Path(args.docs))
    return 0


if __name__ == "__main__":
    sys.exit(main())
