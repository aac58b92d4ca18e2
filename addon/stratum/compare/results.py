"""The results of a comparison: the reference, every render's metrics against it, summaries
over seeds and convergence slopes per series, as the results.json document and results.csv."""

from __future__ import annotations

import csv
import io
import json
import os
from pathlib import Path
from typing import Any

from . import plan as planning
from .options import Options
from .plan import Config, SceneSettings

METRICS = ("mse", "rel_mse", "flip_ldr", "flip_hdr")
CSV_COLUMNS = ("series", "estimator", "integrator", "estimator_settings", "sampler", "spp",
               "seed", "path", "seconds", "trace_seconds", "mse", "rel_mse",
               "flip_ldr", "flip_hdr", "below_noise_floor")


def series_name(label: str, sampler: str, several_estimators: bool,
                several_samplers: bool) -> str:
    """The name of an (estimator, sampler) series in tables and plots (module doc)."""
    if several_estimators and several_samplers:
        return f"{label}/{sampler}"
    return label if several_estimators else sampler


def _summaries(renders: list[dict[str, Any]], series: list[str], spps: list[int],
               noise_floor: dict[str, float | None]) -> list[dict[str, Any]]:
    from .metrics import NOISE_FLOOR_FACTOR, mean_ci95

    rows = []
    for name in series:
        for spp in spps:
            group = [r for r in renders if r["series"] == name and r["spp"] == spp]
            first = group[0]
            for metric in (*METRICS, "seconds", "trace_seconds"):
                mean, low, high = mean_ci95([r[metric] for r in group])
                row: dict[str, Any] = {"series": name, "estimator": first["estimator"],
                                       "sampler": first["sampler"], "spp": spp,
                                       "metric": metric,
                                       "mean": mean, "ci95_low": low, "ci95_high": high,
                                       "n": len(group)}
                floor = noise_floor.get(metric)
                if metric in ("mse", "rel_mse"):
                    row["below_noise_floor"] = bool(
                        floor is not None and mean <= NOISE_FLOOR_FACTOR * floor)
                rows.append(row)
    return rows


def _slopes(summary: list[dict[str, Any]],
            series: list[str]) -> dict[str, dict[str, float | None]]:
    from .metrics import loglog_slope

    out: dict[str, dict[str, float | None]] = {}
    for name in series:
        means = {(r["metric"], r["spp"]): r["mean"] for r in summary if r["series"] == name}
        spps = sorted({spp for _, spp in means})
        entry: dict[str, float | None] = {
            m: loglog_slope(spps, [means[(m, n)] for n in spps]) for m in METRICS}
        mse = [means[("mse", n)] for n in spps]
        entry["mse_vs_seconds"] = loglog_slope([means[("seconds", n)] for n in spps], mse)
        entry["mse_vs_trace_seconds"] = loglog_slope(
            [means[("trace_seconds", n)] for n in spps], mse)
        out[name] = entry
    return out


def write_results(out: Path, results: dict[str, Any]) -> None:
    """Writes out/results.json and out/results.csv, each replacing the old file at once."""
    _write_text_atomic(out / "results.json", json.dumps(results, indent=1))
    _write_text_atomic(out / "results.csv", _csv_text(results["renders"]))


def _write_text_atomic(path: Path, text: str) -> None:
    tmp = path.with_name(f".tmp-{os.getpid()}-{path.name}")
    tmp.write_text(text)
    os.replace(tmp, path)


def _csv_text(renders: list[dict[str, Any]]) -> str:
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=list(CSV_COLUMNS), extrasaction="ignore",
                            lineterminator="\n")
    writer.writeheader()
    for r in renders:
        writer.writerow({k: (repr(v) if isinstance(v, float) else
                             json.dumps(v, sort_keys=True) if isinstance(v, dict) else v)
                         for k, v in r.items()})
    return buf.getvalue()


def compute_results(opts: Options, out: Path, settings: SceneSettings, tests: list[Config],
                    refs: list[Config], estimators: list[Any],
                    reference_estimator: Any) -> dict[str, Any]:
    """Reference (mean + noise floor, written to renders/reference.exr), metrics per render,
    summary and slopes: the results.json document."""
    import numpy as np

    from .exr import read_rgb, write_rgb
    from .metrics import NOISE_FLOOR_FACTOR, all_metrics, crop_region, reference_noise_floor

    if opts.reference_image is not None:
        reference = opts.reference_image
        floor: dict[str, float | None] = {"mse": None, "rel_mse": None}
    else:
        reference, floor = reference_noise_floor([read_rgb(out / c.exr) for c in refs],
                                                 opts.crop)
    write_rgb(out / planning.REFERENCE_PATH, reference.astype(np.float32))
    ref_region = crop_region(np.asarray(reference, dtype=np.float32), opts.crop)

    several_estimators = len(estimators) > 1
    several_samplers = len(opts.samplers) > 1
    series = [series_name(e.label, s, several_estimators, several_samplers)
              for e in estimators for s in opts.samplers]
    renders: list[dict[str, Any]] = []
    for config in tests:
        sidecar = planning.read_sidecar(out, config)
        if sidecar is None:
            raise RuntimeError(f"{config.label}: render missing after the run")
        image = crop_region(read_rgb(out / config.exr), opts.crop)
        values = all_metrics(image, ref_region)
        below = {m: bool(floor[m] is not None and values[m] <= NOISE_FLOOR_FACTOR * floor[m])
                 for m in ("mse", "rel_mse")}
        est = config.estimator
        renders.append({"series": series_name(est.label, config.sampler, several_estimators,
                                              several_samplers),
                        "estimator": est.label, "integrator": est.integrator,
                        "estimator_settings": dict(est.settings),
                        "sampler": config.sampler, "spp": config.spp, "seed": config.seed,
                        "path": config.exr, "seconds": float(sidecar["seconds"]),
                        "trace_seconds": float(sidecar.get("trace_seconds", sidecar["seconds"])),
                        **values, "below_noise_floor": below["mse"] or below["rel_mse"],
                        "mse_below_noise_floor": below["mse"],
                        "rel_mse_below_noise_floor": below["rel_mse"]})
    summary = _summaries(renders, series, opts.spp, floor)
    return {
        "scene": str(opts.scene), "scene_sha256": settings.scene_sha256,
        "resolution": list(settings.resolution),
        "crop": list(opts.crop) if opts.crop else None,
        "integrator": (estimators[0].integrator if len(estimators) == 1
                       else [e.integrator for e in estimators]),
        "estimators": [{"label": e.label, "spec": e.spec, "integrator": e.integrator,
                        "settings": dict(e.settings)} for e in estimators],
        "common_settings": dict(opts.common),
        "hemisphere": settings.hemisphere,
        "max_bounces": settings.max_bounces,
        "series": series, "samplers": opts.samplers, "spp": opts.spp, "seeds": opts.seeds,
        "reference": {"path": planning.REFERENCE_PATH,
                      "spp": opts.reference_spp if opts.reference_image is None else None,
                      "seeds": opts.reference_seeds,
                      "source": "file" if opts.reference_image is not None else "rendered",
                      "sampler": opts.reference_sampler,
                      "estimator": (None if reference_estimator is None else {
                          "label": reference_estimator.label,
                          "spec": reference_estimator.spec,
                          "integrator": reference_estimator.integrator,
                          "settings": dict(reference_estimator.settings)}),
                      "file": str(opts.reference_file) if opts.reference_file else None,
                      "parts": [c.exr for c in refs],
                      "noise_floor": floor, "noise_floor_factor": NOISE_FLOOR_FACTOR},
        "renders": renders, "summary": summary,
        "slopes": _slopes(summary, series),
        "metric_notes": {
            "rel_mse_epsilon": 1e-2,
            "flip_ldr": "mean LDR-FLIP of sRGB(clamp(linear, 0, 1)) images",
            "flip_hdr": "mean HDR-FLIP of the linear images",
            "seconds": "wall time of Blender's render call (export + BVH + path tracing)",
            "trace_seconds": "the native renderer's path tracing time"},
    }
