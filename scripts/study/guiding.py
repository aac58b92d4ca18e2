"""The path-guiding part of `make study` (issue 17, acceptance 5, claim 10): guided against
unguided path tracing at equal time on scenes/guiding_room.blend, for Stratum and for Cycles'
own path guiding (the bpy 5.0 wheel); out/study/guiding.md, guiding.json and
figures/guiding_mse.png. run.py runs it (the part `guiding`); alone:

    .venv/bin/python -m scripts.study.guiding [--out out/study] [--quick] [--page-only]

This module measures (bpy); guiding_page.py computes and writes the page.

Series (each at DEFAULT.spp samples per pixel, seeds 1..DEFAULT.seeds, all threads, max
bounces 8, Blackman-Harris 1.5 px: scripts/bench/common.py's open_scene settings):

| series             | renderer | settings                                                  |
|--------------------|----------|-----------------------------------------------------------|
| bsdf               | Stratum  | path, light_sampling bsdf                                 |
| mis                | Stratum  | path, light_sampling mis (the default)                    |
| guided mis         | Stratum  | path, light_sampling mis, use_guiding 1                   |
| guided bsdf        | Stratum  | path, light_sampling bsdf, use_guiding 1                  |
| cycles             | Cycles   | use_guiding off                                           |
| cycles guided      | Cycles   | use_guiding, use_surface_guiding on; training samples,    |
|                    |          | guiding probability and distribution at Cycles' defaults  |

Stratum renders with sampler sobol (SAMPLER) and the guiding settings' defaults; where the
library has no `use_guiding` (it refuses the setting) the guided series are marked not
available. Cycles' series are measured only where Cycles was built with path guiding
(`_cycles.with_path_guiding`: True in the 5.0 wheel, False in Debian's 3.4).

Error: each renderer against its own reference, the mean of two halves of reference_spp / 2
(Stratum: mis, sobol; Cycles: unguided), seeds 1001 and 1002, cached in
out/bench_cache/quality/ as scripts/bench/quality.py does; noise MSE = MSE - Var(reference)
(bench.results.noise_mse), so neither reference's residual noise nor a small difference
between the two renderers' converged images enters the ratios. The two references are compared
on the page (per-channel means, and their MSE against the sum of their noise variances), and
Cycles' MSE against Stratum's reference is given too. Time: Stratum's path-tracing seconds
(progress().render_seconds, training included); Cycles prints no status lines under the wheel,
so its time is (total(N) - total(1)) N / (N - 1), as in bench.quality. Equal time: each
series' mean noise MSE against its mean time, interpolated in log-log at the largest time
every series reached (estimators.equal_time; * = extrapolated). Memory: the guiding
tree's nodes and bytes from the render's progress (guiding.nodes, guiding.bytes) or its log
line "guiding tree: N nodes, X MiB", when the library reports them.

Targets (issue 17, claim 10): Stratum guided mis <= 0.5x Stratum mis and <= Cycles guided, in
noise MSE at equal time.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from scripts import REPO
from scripts.study.guiding_page import (
    analyse,
    cycles_against_stratum_reference,
    figure,
    guiding_memory,
    page,
    worst_block,
)

SCENE = REPO / "scenes" / "guiding_room.blend"
STRATUM_SERIES: dict[str, dict[str, int | str]] = {
    "bsdf": {"light_sampling": "bsdf"},
    "mis": {"light_sampling": "mis"},
    "guided mis": {"light_sampling": "mis", "use_guiding": 1},
    "guided bsdf": {"light_sampling": "bsdf", "use_guiding": 1},
}
CYCLES_SERIES = {"cycles": False, "cycles guided": True}  # label -> use_guiding
# Cycles' guiding settings left at their defaults, recorded on the page.
CYCLES_GUIDING_SETTINGS = ("guiding_training_samples", "surface_guiding_probability",
                           "guiding_distribution_type", "guiding_directional_sampling_type",
                           "use_guiding_direct_light", "use_guiding_mis_weights",
                           "use_deterministic_guiding")
REFERENCE_SEEDS = (1001, 1002)
# Owen-scrambled Sobol for every Stratum render (series and reference), against Cycles' own
# default pattern (Tabulated Sobol in 5.0): each renderer's best-behaved unbiased sampler.
SAMPLER = "sobol"


@dataclass(frozen=True)
class Config:
    width: int
    height: int
    spp: tuple[int, ...]
    seeds: int
    reference_spp: int


# Default: 7 min on 2 shared cores at load 11, both references included (cached afterwards: the
# Stratum one per library build). Cycles trains its guiding field for the first 128 samples
# (guiding_training_samples' default), so the longest series renders well past it: its guided
# MSE was 1.02x its unguided at 128 spp and 0.83x at 1024 spp (equal samples).
DEFAULT = Config(80, 60, (128, 1024), 2, 2048)
QUICK = Config(32, 24, (8, 32), 1, 128)


# ---- measuring (bpy: the 5.0 wheel) -----------------------------------------------------------


def open_room(config: Config, spp: int) -> Any:
    """The room with bench.common's shared settings at config's size and `spp`, both
    renderers' (Stratum: configure_stratum; the engine is switched per render)."""
    from scripts.bench import common

    scene = common.open_scene(SCENE, config.width, spp)
    scene.render.resolution_y = config.height
    common.configure_stratum(scene, spp)
    return scene


def cycles_render(config: Config, tmp: Path, seed: int, spp: int, guided: bool) -> tuple[Any, float]:
    """Cycles' linear RGB and path-tracing seconds (status lines, or bench.quality's
    (total(N) - total(1)) N / (N - 1) where there are none), its light tree on."""
    from scripts.bench.common import read_exr_rgb, render_cycles

    def run(samples: int) -> tuple[Any, dict[str, float | None]]:
        scene = open_room(config, samples)
        c = scene.cycles
        c.seed, c.use_animated_seed = seed, False
        if hasattr(c, "use_light_tree"):
            c.use_light_tree = True
        if hasattr(c, "use_guiding"):
            c.use_guiding = c.use_surface_guiding = guided
        exr = tmp / f"cycles-{seed}-{int(guided)}-{samples}.exr"
        r = render_cycles(scene, write_exr=exr)
        return read_exr_rgb(exr), r

    image, r = run(spp)
    if r["trace"] is not None:
        return image, r["trace"]
    one = run(1)[1]
    assert r["total"] is not None and one["total"] is not None
    return image, max(r["total"] - one["total"], 0.0) * spp / (spp - 1)


def stratum_render(st: Any, overrides: dict[str, Any]) -> tuple[Any, float, dict[str, float] | None]:
    """(linear RGB, path-tracing seconds, guiding memory) of one render of the exported scene
    st (bench.common.StratumScene) with its settings plus overrides. Raises StratumError for a
    setting the library does not have."""
    import numpy as np
    from stratum import native

    from scripts.bench.common import CaptureStdout

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


def references(config: Config, st: Any, tmp: Path) -> dict[str, tuple[Any, Any]]:
    """{renderer: (half a, half b)}: Stratum's (mis, sobol) and Cycles' (unguided) reference
    halves, cached as scripts/bench/quality.py caches its own."""
    import bpy

    from scripts.bench.common import stratum_library_id
    from scripts.bench.quality import cache_path, cached_halves

    key = {"scene": "guiding_room", "file": hashlib.sha256(SCENE.read_bytes()).hexdigest(),
           "res": [config.width, config.height], "samples": config.reference_spp,
           "seeds": REFERENCE_SEEDS}
    half = config.reference_spp // 2
    stratum = cached_halves(
        cache_path("guiding_room", "stratum", key | {"library": stratum_library_id()}),
        lambda seed: stratum_render(st, {"seed": seed, "sampler": SAMPLER, "samples": half})[0])
    cycles = cached_halves(
        cache_path("guiding_room", "cycles", key | {
            "blender": bpy.app.version_string, "build": bpy.app.build_hash.decode(errors="replace")}),
        lambda seed: cycles_render(config, tmp, seed, half, False)[0])
    return {"Stratum": stratum[:2], "Cycles": cycles[:2]}


def compare_references(halves: dict[str, tuple[Any, Any]]) -> dict[str, Any]:
    """The two references side by side: means, MSE between them against the noise alone, and
    block means (worst_block)."""
    from scripts.bench.results import mse, reference_noise

    (sa, sb), (ca, cb) = halves["Stratum"], halves["Cycles"]
    return {"stratum_mean": list((sa + sb).mean(axis=(0, 1)) / 2),
            "cycles_mean": list((ca + cb).mean(axis=(0, 1)) / 2),
            "mse_between": mse((sa + sb) / 2, (ca + cb) / 2),
            "noise_sum": reference_noise(sa, sb) + reference_noise(ca, cb),
            "worst_block": worst_block((sa + sb) / 2, (ca + cb) / 2)}


def measure(config: Config) -> dict[str, Any]:
    """Renders both references and every series (module doc); returns the record page() and
    analyse() read."""
    import importlib
    import os

    import bpy
    from stratum import native

    from scripts.bench.common import StratumScene, stratum_reason
    from scripts.bench.results import mse, noise_mse

    reason = stratum_reason()
    if reason:
        raise SystemExit(f"study.guiding: Stratum not available ({reason})")
    has_guiding = "use_guiding" in {s.name for s in native.settings()}
    # Cycles' C module is importable once bpy is (it is not a package of its own).
    cycles_guiding = bool(getattr(importlib.import_module("_cycles"), "with_path_guiding", False))
    series: dict[str, dict[str, Any]] = {
        label: {"renderer": "Stratum", "settings": s, "runs": []}
        for label, s in STRATUM_SERIES.items()}
    series |= {label: {"renderer": "Cycles", "guided": g, "runs": []}
               for label, g in CYCLES_SERIES.items()}
    for s in series.values():
        if "use_guiding" in s.get("settings", {}) and not has_guiding:
            s["unavailable"] = "not available (the library has no use_guiding)"
        if s.get("guided") and not cycles_guiding:
            s["unavailable"] = "not available (Cycles built without path guiding)"
    with tempfile.TemporaryDirectory(prefix="study_guiding") as tmp_name, \
            StratumScene(open_room(config, config.reference_spp)) as st:
        tmp = Path(tmp_name)
        halves = references(config, st, tmp)
        stratum_reference = sum(halves["Stratum"]) / 2
        # Seeds in turn, each by every series, so the machine's load reaches all alike.
        for seed, spp in ((seed, n) for seed in range(1, config.seeds + 1) for n in config.spp):
            for label, s in ((k, v) for k, v in series.items() if not v.get("unavailable")):
                memory = None
                if s["renderer"] == "Cycles":
                    image, seconds = cycles_render(config, tmp, seed, spp, s["guided"])
                else:
                    try:
                        image, seconds, memory = stratum_render(
                            st, s["settings"] | {"seed": seed, "samples": spp, "sampler": SAMPLER})
                    except native.StratumError as err:  # a setting the library refuses
                        s["unavailable"] = f"not available ({err})"
                        continue
                a, b = halves[s["renderer"]]
                s["runs"].append({"seed": seed, "spp": spp, "seconds": seconds,
                                  "noise_mse": noise_mse(image, a, b),
                                  "mse_vs_own_reference": mse(image, (a + b) / 2),
                                  "mse_vs_stratum_reference": mse(image, stratum_reference)})
                s["memory"] = memory or s.get("memory")
                print(f"study.guiding: {label} seed {seed} {spp} spp: {seconds:.2f} s, "
                      f"noise MSE {s['runs'][-1]['noise_mse']:.4g}", flush=True)
    return {"scene": str(SCENE.relative_to(REPO)), "width": config.width, "height": config.height,
            "spp": list(config.spp), "seeds": list(range(1, config.seeds + 1)),
            "reference_spp": config.reference_spp, "load_average": list(os.getloadavg()),
            "blender": bpy.app.version_string, "cycles_guiding": cycles_guiding,
            "cycles_pattern": bpy.context.scene.cycles.sampling_pattern, "stratum_sampler": SAMPLER,
            "cycles_guiding_settings": {name: getattr(bpy.context.scene.cycles, name)
                                        for name in CYCLES_GUIDING_SETTINGS
                                        if hasattr(bpy.context.scene.cycles, name)},
            "stratum_guiding": has_guiding, "references": compare_references(halves),
            "series": series}


def write(out: Path, data: dict[str, Any]) -> str:
    numbers = analyse(data)
    data["references"]["cycles_vs_stratum"] = cycles_against_stratum_reference(data)
    text = page(data, numbers)
    out.mkdir(parents=True, exist_ok=True)
    (out / "guiding.md").write_text(text)
    (out / "guiding.json").write_text(json.dumps(data | {"analysis": numbers}, indent=1,
                                                 default=float))
    png = figure(data, out / "figures" / "guiding_mse.png")
    print(f"study.guiding: wrote {out / 'guiding.md'}" + (f" and {png}" if png else ""))
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
