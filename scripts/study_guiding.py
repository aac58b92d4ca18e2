"""The path-guiding part of `make study` (issue 17, acceptance 5, claim 10): guided against
unguided path tracing at equal time on scenes/guiding_room.blend, for Stratum and for Cycles'
own path guiding (the bpy 5.0 wheel); out/study/guiding.md, guiding.json and
figures/guiding_mse.png. scripts/study.py runs it; alone:

    .venv/bin/python scripts/study_guiding.py [--out out/study] [--quick]

Series (each at SPP samples per pixel, seeds 1..SEEDS, all threads, max bounces 8,
Blackman-Harris 1.5 px: bench_common.open_scene's shared settings):

| series             | renderer | settings                                                  |
|--------------------|----------|-----------------------------------------------------------|
| bsdf               | Stratum  | path, light_sampling bsdf                                 |
| mis                | Stratum  | path, light_sampling mis (the default)                    |
| guided mis         | Stratum  | path, light_sampling mis, use_guiding 1                   |
| guided bsdf        | Stratum  | path, light_sampling bsdf, use_guiding 1                  |
| cycles             | Cycles   | use_guiding off                                           |
| cycles guided      | Cycles   | use_guiding, use_surface_guiding on; training samples,    |
|                    |          | guiding probability and distribution at Cycles' defaults  |

Stratum renders with sampler sobol (its default) and the guiding settings' defaults; where the
library has no `use_guiding` (it refuses the setting) the guided series are marked not
available. Cycles' series are measured only where Cycles was built with path guiding
(`_cycles.with_path_guiding`: True in the 5.0 wheel, False in Debian's 3.4).

Error: each renderer against its own reference, the mean of two halves of REFERENCE_SPP / 2
(Stratum: mis, sobol; Cycles: unguided), seeds 1001 and 1002, cached in
out/bench_cache/quality/ as scripts/bench_quality.py does; noise MSE = MSE - Var(reference)
(bench_results.noise_mse), so neither reference's residual noise nor a small difference
between the two renderers' converged images enters the ratios. The two references are compared
on the page (per-channel means, and their MSE against the sum of their noise variances), and
Cycles' MSE against Stratum's reference is given too. Time: Stratum's path-tracing seconds
(progress().render_seconds, training included); Cycles prints no status lines under the wheel,
so its time is (total(N) - total(1)) N / (N - 1), as in bench_quality. Equal time: each
series' mean noise MSE against its mean time, interpolated in log-log at the largest time
every series reached (study_estimators.equal_time; * = extrapolated). Memory: the guiding
tree's nodes and bytes from the render's progress (guiding_nodes, guiding_bytes) or its log
line "guiding tree: N nodes, X MiB", when the library reports them.

Targets (issue 17, claim 10): Stratum guided mis <= 0.5x Stratum mis and <= Cycles guided, in
noise MSE at equal time.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import re
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))
from study_estimators import equal_time, fmt

SCENE = REPO / "scenes" / "guiding_room.blend"
STRATUM_SERIES: dict[str, dict[str, int | str]] = {
    "bsdf": {"light_sampling": "bsdf"},
    "mis": {"light_sampling": "mis"},
    "guided mis": {"light_sampling": "mis", "use_guiding": 1},
    "guided bsdf": {"light_sampling": "bsdf", "use_guiding": 1},
}
CYCLES_SERIES = {"cycles": False, "cycles guided": True}  # label -> use_guiding
REFERENCE_SEEDS = (1001, 1002)
BLOCK = 10  # px: the reference comparison's blocks (8 x 6 of them at 80x60)
DARK = 0.016  # linear; tests/blender/test_feature_agreement.py's threshold
MEMORY_LINE = re.compile(r"guiding tree:\s*([\d,]+)\s*nodes,\s*([\d.]+)\s*MiB")


@dataclass(frozen=True)
class Config:
    width: int
    height: int
    spp: tuple[int, ...]
    seeds: int
    reference_spp: int


# Default: ~8 min on 2 shared cores (load 8), references cached. Cycles trains its guiding field
# for the first 128 samples (guiding_training_samples' default), so the longest series renders
# well past it: at 256 spp its guided MSE was 0.96x its unguided, at 1024 spp 0.76x (96x72).
DEFAULT = Config(80, 60, (128, 1024), 2, 2048)
QUICK = Config(32, 24, (4, 16), 1, 64)


# ---- pure: memory, equal time, the page -------------------------------------------------------


def guiding_memory(progress: Any, log: str) -> dict[str, float] | None:
    """{nodes, mib} of the guiding tree: from the progress' guiding_nodes / guiding_bytes when
    the library has them and they are non-zero, else from the last "guiding tree: N nodes, X
    MiB" line of the render's log; None when neither reports it."""
    nodes, size = getattr(progress, "guiding_nodes", 0.0), getattr(progress, "guiding_bytes", 0.0)
    if nodes and size:
        return {"nodes": float(nodes), "mib": float(size) / 2**20}
    found = MEMORY_LINE.findall(log)
    if not found:
        return None
    n, mib = found[-1]
    return {"nodes": float(n.replace(",", "")), "mib": float(mib)}


def series_results(runs: dict[str, list[dict[str, Any]]]) -> dict[str, Any]:
    """study_estimators' results layout (series, spp, summary rows of mean mse and trace_seconds)
    from runs: label -> [{spp, noise_mse, seconds}, ...] over seeds; series without runs are
    left out."""
    rows: dict[tuple[str, int], list[dict[str, Any]]] = {}
    for label, items in runs.items():
        for item in items:
            rows.setdefault((label, int(item["spp"])), []).append(item)
    summary = []
    for (label, spp), items in rows.items():
        for metric, key in (("mse", "noise_mse"), ("trace_seconds", "seconds")):
            summary.append({"series": label, "spp": spp, "metric": metric,
                            "mean": sum(i[key] for i in items) / len(items)})
    return {"series": [s for s in runs if runs[s]],
            "spp": sorted({spp for _, spp in rows}), "summary": summary}


def ratio(numbers: dict[str, Any], a: str, b: str) -> float | None:
    """Equal-time MSE of series a over series b (None when either is missing)."""
    at = numbers.get("equal_time", {})
    return at[a]["mse"] / at[b]["mse"] if a in at and b in at else None


def verdict(value: float | None, target: float) -> str:
    if value is None:
        return "not measured"
    return f"{value:.3g} ({'met' if value <= target else 'not met'}: target <= {target:g})"


def analyse(data: dict[str, Any]) -> dict[str, Any]:
    """data (measure()'s record) + equal-time MSE per series: {"budget", "equal_time": {label:
    {mse, extrapolated}}}."""
    runs = {label: s["runs"] for label, s in data["series"].items() if s.get("runs")}
    if not runs:
        return {"budget": None, "equal_time": {}}
    budget, at = equal_time(series_results(runs))
    return {"budget": budget,
            "equal_time": {label: {"mse": m, "extrapolated": ex} for label, (m, ex) in at.items()}}


def page(data: dict[str, Any], numbers: dict[str, Any]) -> str:
    """The markdown of out/study/guiding.md."""
    spps, budget = data["spp"], numbers["budget"]
    show_memory = any(s.get("memory") for s in data["series"].values())
    lines = ["# Path guiding study (issue 17, claim 10)", "",
             (f"Generated by `scripts/study_guiding.py` (`make study`). {data['scene']}, "
              f"{data['width']}x{data['height']}, {len(data['seeds'])} seeds, max bounces 8; "
              f"references of {data['reference_spp']} spp, each renderer its own (module doc). "
              f"Noise MSE = MSE against the renderer's reference less the reference's variance; "
              f"equal time: noise MSE interpolated in log-log at the largest path-tracing time "
              f"every series reached (* = extrapolated). Load average "
              f"{' / '.join(f'{x:.2f}' for x in data['load_average'])}; Blender "
              f"{data['blender']}, Cycles path guiding "
              f"{'compiled in' if data['cycles_guiding'] else 'absent'}."), "",
             "| series | renderer | " + " | ".join(f"noise MSE {n} spp" for n in spps)
             + " | " + " | ".join(f"s at {n} spp" for n in spps)
             + f" | MSE at {fmt(budget)} s | / Stratum mis | / Cycles |"
             + (" guiding tree |" if show_memory else ""),
             "|---|---|" + "---|" * (2 * len(spps) + 3) + ("---|" if show_memory else "")]
    for label, s in data["series"].items():
        by_spp = {n: [r for r in s.get("runs", []) if r["spp"] == n] for n in spps}
        mse = [fmt(sum(r["noise_mse"] for r in rs) / len(rs)) if rs else "-"
               for rs in by_spp.values()]
        sec = [fmt(sum(r["seconds"] for r in rs) / len(rs)) if rs else "-"
               for rs in by_spp.values()]
        at = numbers["equal_time"].get(label)
        if at is None:
            cells = [s.get("unavailable") or "not measured", "", ""]
        else:
            cells = [fmt(at["mse"]) + ("*" if at["extrapolated"] else ""),
                     fmt(ratio(numbers, label, "mis")), fmt(ratio(numbers, label, "cycles"))]
        memory = s.get("memory")
        mem = (f"{memory['nodes']:.0f} nodes, {memory['mib']:.2f} MiB" if memory else "")
        lines.append(f"| {label} | {s['renderer']} | " + " | ".join(mse + sec + cells) + " |"
                     + (f" {mem} |" if show_memory else ""))
    refs = data["references"]
    lines += ["", "## The two references", "",
              (f"Mean RGB Stratum {fmt_rgb(refs['stratum_mean'])}, Cycles "
               f"{fmt_rgb(refs['cycles_mean'])} (Stratum / Cycles "
               f"{fmt_rgb([a / b for a, b in zip(refs['stratum_mean'], refs['cycles_mean'])])}); "
               f"MSE between them {fmt(refs['mse_between'])} against their summed noise "
               f"variances {fmt(refs['noise_sum'])}; {refs['worst_block']['block']} px block "
               f"means (channels >= {DARK} linear: {refs['worst_block']['compared']} of "
               f"{refs['worst_block']['of']}) differ by {fmt(refs['worst_block']['mean'])} on "
               f"average, {fmt(refs['worst_block']['worst'])} at most. Cycles' MSE against its own reference / "
               f"against Stratum's: " + ", ".join(
                   f"{label} at {v['spp']} spp {fmt(v['own'])} / {fmt(v['stratum'])}"
                   for label, v in refs["cycles_vs_stratum"].items()) + "."),
              "", "## Against the targets", "",
              f"- Cycles guided / Cycles unguided: {fmt(ratio(numbers, 'cycles guided', 'cycles'))}",
              f"- Stratum bsdf / Stratum mis: {fmt(ratio(numbers, 'bsdf', 'mis'))}",
              f"- Stratum guided mis / Stratum mis: {verdict(ratio(numbers, 'guided mis', 'mis'), 0.5)}",
              f"- Stratum guided bsdf / Stratum bsdf: {fmt(ratio(numbers, 'guided bsdf', 'bsdf'))}",
              ("- Stratum guided mis / Cycles guided: "
               f"{verdict(ratio(numbers, 'guided mis', 'cycles guided'), 1.0)}"), ""]
    return "\n".join(lines)


def worst_block(stratum: Any, cycles: Any, block: int = BLOCK) -> dict[str, float]:
    """The largest |Stratum / Cycles - 1| over block x block block means and RGB channels (as
    tests/blender/test_feature_agreement.py compares), among blocks whose Cycles mean is at
    least DARK (its threshold: below it a 5 % error is under one 8-bit display level)."""
    import numpy as np

    h, w = (stratum.shape[0] // block) * block, (stratum.shape[1] // block) * block

    def means(image: Any) -> Any:
        return image[:h, :w].reshape(h // block, block, w // block, block, 3).mean(axis=(1, 3))

    s, c = means(stratum), means(cycles)
    bright = c >= DARK
    rel = np.abs(s[bright] / c[bright] - 1.0)
    return {"block": block, "compared": int(bright.sum()), "of": int(bright.size),
            "worst": float(rel.max()) if rel.size else math.nan,
            "mean": float(rel.mean()) if rel.size else math.nan}


def fmt_rgb(values: list[float]) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in values) + ")"


def figure(data: dict[str, Any], path: Path) -> Path | None:
    """Noise MSE against path-tracing time, one line per measured series."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.0, 4.2))
    drawn = False
    for label, s in data["series"].items():
        results = series_results({label: s.get("runs", [])})
        if not results["series"]:
            continue
        pts = sorted((r["mean"], m["mean"]) for r in results["summary"]
                     for m in results["summary"] if r["metric"] == "trace_seconds"
                     and m["metric"] == "mse" and r["spp"] == m["spp"])
        ax.plot(*zip(*pts), marker="o", ms=3, ls="--" if s["renderer"] == "Cycles" else "-",
                label=f"{s['renderer']} {label}")
        drawn = True
    if not drawn:
        plt.close(fig)
        return None
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("path-tracing time [s]")
    ax.set_ylabel("noise MSE")
    ax.set_title(f"{Path(data['scene']).name}, {data['width']}x{data['height']}", fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


# ---- measuring (bpy: the 5.0 wheel) -----------------------------------------------------------


def open_room(config: Config, spp: int) -> Any:
    """The room with bench_common's shared settings at config's size and `spp`, both
    renderers' (Stratum: configure_stratum; the engine is switched per render)."""
    import bench_common

    scene = bench_common.open_scene(SCENE, config.width, spp)
    scene.render.resolution_y = config.height
    bench_common.configure_stratum(scene, spp)
    return scene


def cycles_render(config: Config, tmp: Path, seed: int, spp: int, guided: bool) -> tuple[Any, float]:
    """Cycles' linear RGB and path-tracing seconds; the time as bench_quality.cycles_render
    (status lines, or total(N) - total(1) scaled when there are none)."""
    from bench_common import read_exr_rgb, render_cycles

    def run(samples: int, name: str) -> tuple[Any, dict[str, float | None]]:
        scene = open_room(config, samples)
        c = scene.cycles
        default = type(c).bl_rna.properties["sampling_pattern"].default
        if default:
            c.sampling_pattern = default
        c.seed, c.use_animated_seed = seed, False
        if hasattr(c, "use_light_tree"):
            c.use_light_tree = True
        if hasattr(c, "use_guiding"):
            c.use_guiding = guided
            c.use_surface_guiding = guided
        exr = tmp / name
        r = render_cycles(scene, write_exr=exr)
        return read_exr_rgb(exr), r

    image, r = run(spp, f"cycles-{seed}-{int(guided)}.exr")
    if r["trace"] is not None:
        return image, r["trace"]
    _, one = run(1, f"cycles-{seed}-{int(guided)}-1.exr")
    assert r["total"] is not None and one["total"] is not None
    return image, max(r["total"] - one["total"], 0.0) * spp / (spp - 1)


def stratum_render(st: Any, overrides: dict[str, Any]) -> tuple[Any, float, dict[str, float] | None]:
    """(linear RGB, path-tracing seconds, guiding memory) of one render of the exported scene
    st (bench_common.StratumScene) with its settings plus overrides. Raises StratumError for a
    setting the library does not have."""
    import numpy as np
    from bench_common import CaptureStdout
    from stratum import native

    with native.Renderer(st.native) as renderer:
        for name, value in (st.settings | overrides).items():
            renderer.set(name, value)
        with CaptureStdout() as log:
            renderer.start()
            while not renderer.wait(50):
                pass
        p = renderer.progress()
        width, height = renderer.image_size
        rgb = renderer.read_pixels().reshape(height, width, 4)[:, :, :3].astype(np.float64)
    return rgb, p.render_seconds, guiding_memory(p, log.text)


def measure(config: Config) -> dict[str, Any]:
    """Renders every series and both references (module doc); returns the record page() and
    analyse() read."""
    import importlib
    import os

    import bpy
    from bench_common import StratumScene, stratum_library_id, stratum_reason
    from bench_quality import cache_path, cached_halves
    from bench_results import mse, noise_mse, reference_noise
    from stratum import native

    reason = stratum_reason()
    if reason:
        raise SystemExit(f"study_guiding: Stratum not available ({reason})")
    has_guiding = "use_guiding" in {s.name for s in native.settings()}
    # Cycles' C module is importable once bpy is (it is not a package of its own).
    cycles_guiding = bool(getattr(importlib.import_module("_cycles"), "with_path_guiding", False))
    key = {"scene": "guiding_room", "file": hashlib.sha256(SCENE.read_bytes()).hexdigest(), "res": [config.width, config.height], "samples": config.reference_spp,
           "seeds": REFERENCE_SEEDS}
    series: dict[str, dict[str, Any]] = {
        label: {"renderer": "Stratum", "settings": s, "runs": []} for label, s in STRATUM_SERIES.items()}
    series |= {label: {"renderer": "Cycles", "guided": g, "runs": []}
               for label, g in CYCLES_SERIES.items()}
    with tempfile.TemporaryDirectory(prefix="study_guiding") as tmp_name:
        tmp = Path(tmp_name)
        with StratumScene(open_room(config, config.reference_spp)) as st:
            halves = {
                "stratum": cached_halves(
                    cache_path("guiding_room", "stratum", key | {"library": stratum_library_id()}),
                    lambda seed: stratum_render(st, {"seed": seed, "sampler": "sobol",
                                                     "samples": config.reference_spp // 2})[0]),
                "cycles": cached_halves(
                    cache_path("guiding_room", "cycles", key | {
                        "blender": bpy.app.version_string,
                        "build": bpy.app.build_hash.decode(errors="replace")}),
                    lambda seed: cycles_render(config, tmp, seed, config.reference_spp // 2,
                                               False)[0])}
            for label, s in series.items():
                if s["renderer"] == "Stratum" and "use_guiding" in s["settings"] and not has_guiding:
                    s["unavailable"] = "not available (the library has no use_guiding)"
                if s["renderer"] == "Cycles" and s["guided"] and not cycles_guiding:
                    s["unavailable"] = "not available (Cycles built without path guiding)"
            # Seeds in turn, each by every series, so the machine's load reaches all alike.
            for seed in range(1, config.seeds + 1):
                for spp in config.spp:
                    for label, s in series.items():
                        if s.get("unavailable"):
                            continue
                        if s["renderer"] == "Cycles":
                            image, seconds = cycles_render(config, tmp, seed, spp, s["guided"])
                            memory = None
                        else:
                            try:
                                image, seconds, memory = stratum_render(
                                    st, s["settings"] | {"seed": seed, "samples": spp})
                            except native.StratumError as err:
                                s["unavailable"] = f"not available ({err})"
                                continue
                        a, b = halves["stratum" if s["renderer"] == "Stratum" else "cycles"][:2]
                        s["runs"].append({"seed": seed, "spp": spp, "seconds": seconds,
                                          "noise_mse": noise_mse(image, a, b),
                                          "mse_vs_own_reference": mse(image, (a + b) / 2),
                                          "mse_vs_stratum_reference": mse(
                                              image, (halves["stratum"][0] + halves["stratum"][1]) / 2)})
                        if memory:
                            s["memory"] = memory
                        print(f"study_guiding: {label} seed {seed} {spp} spp: {seconds:.2f} s, "
                              f"noise MSE {s['runs'][-1]['noise_mse']:.4g}", flush=True)
    (sa, sb, _), (ca, cb, _) = halves["stratum"], halves["cycles"]
    references = {"stratum_mean": list((sa + sb).mean(axis=(0, 1)) / 2),
                  "cycles_mean": list((ca + cb).mean(axis=(0, 1)) / 2),
                  "mse_between": mse((sa + sb) / 2, (ca + cb) / 2),
                  "noise_sum": reference_noise(sa, sb) + reference_noise(ca, cb),
                  "worst_block": worst_block((sa + sb) / 2, (ca + cb) / 2)}
    return {"scene": str(SCENE.relative_to(REPO)), "width": config.width, "height": config.height,
            "spp": list(config.spp), "seeds": list(range(1, config.seeds + 1)),
            "reference_spp": config.reference_spp, "load_average": list(os.getloadavg()),
            "blender": bpy.app.version_string, "cycles_guiding": cycles_guiding,
            "cycles_pattern": bpy.context.scene.cycles.sampling_pattern,
            "stratum_guiding": has_guiding, "references": references, "series": series}


def cycles_against_stratum_reference(data: dict[str, Any]) -> dict[str, dict[str, float]]:
    """Per Cycles series at its largest spp: mean MSE (without the noise correction) against
    its own reference and against Stratum's; their difference is what the choice of reference
    would add."""
    out: dict[str, dict[str, float]] = {}
    for label, s in data["series"].items():
        runs = [r for r in s.get("runs", []) if s["renderer"] == "Cycles"]
        if not runs:
            continue
        top = max(r["spp"] for r in runs)
        runs = [r for r in runs if r["spp"] == top]
        out[label] = {"spp": top,
                      "own": sum(r["mse_vs_own_reference"] for r in runs) / len(runs),
                      "stratum": sum(r["mse_vs_stratum_reference"] for r in runs) / len(runs)}
    return out


def write(out: Path, data: dict[str, Any]) -> str:
    numbers = analyse(data)
    data["references"]["cycles_vs_stratum"] = cycles_against_stratum_reference(data)
    text = page(data, numbers)
    out.mkdir(parents=True, exist_ok=True)
    (out / "guiding.md").write_text(text)
    (out / "guiding.json").write_text(json.dumps(data | {"analysis": numbers}, indent=1,
                                                 default=float))
    png = figure(data, out / "figures" / "guiding_mse.png")
    print(f"study_guiding: wrote {out / 'guiding.md'}" + (f" and {png}" if png else ""))
    return text


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(REPO / "out" / "study"))
    p.add_argument("--quick", action="store_true", help="toy sizes, to test the pipeline")
    p.add_argument("--page-only", action="store_true",
                   help="no rendering: rebuild guiding.md from guiding.json")
    args = p.parse_args(argv)
    out = Path(args.out).resolve()
    if args.page_only:
        data = json.loads((out / "guiding.json").read_text())
        data.pop("analysis", None)
    else:
        data = measure(QUICK if args.quick else DEFAULT)
    print(write(out, data))
    return 0


if __name__ == "__main__":
    sys.exit(main())
