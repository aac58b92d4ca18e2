"""`stratum compare`: render a scene with several estimators, samplers, sample counts and seeds
through Blender, compare every render with a reference, and write results.json, results.csv and
the report (stratum.compare.report.write_report).

Estimators (--integrator, a list of specs such as `path:light_sampling=bsdf`; estimators.py)
are an axis like samplers: configurations are estimator x sampler x spp x seed. Each
(estimator, sampler) pair is one series of the tables and plots, named by the estimator's label
when several estimators are compared with one sampler, by the sampler when one estimator is
compared with several samplers (the sampler study), and `label/sampler` when both vary.

Flow: validate every argument (nothing is written before that succeeds) -> open the scene in
Blender once to read its resolution and Stratum settings -> plan configurations and skip the
ones already rendered (plan.py: cache key = scene sha256 + settings + seed) -> render the rest
in batches (runner.py: local Blender processes or a Dask cluster) -> reference = mean of the
reference renders, with its noise floor (or the given EXR) -> metrics per render, 95 %
intervals over seeds, log-log slopes (metrics.py) -> results.json / results.csv -> report.

Times: "seconds" is the wall time of Blender's render call (export + BVH + path tracing) in a
process that may share the CPU with --jobs - 1 others; "trace_seconds" is the path tracing
alone. Both depend on --jobs and --threads; images do not (bit-identical for any thread count).
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import os
import sys
from pathlib import Path
from typing import Any

from ..blender_process import NOT_FOUND_MESSAGE, blender_executable
from . import plan as planning
from .plan import Config, SceneSettings

METRICS = ("mse", "rel_mse", "flip_ldr", "flip_hdr")
CSV_COLUMNS = ("series", "estimator", "integrator", "estimator_settings", "sampler", "spp",
               "seed", "path", "seconds", "trace_seconds", "mse", "rel_mse",
               "flip_ldr", "flip_hdr", "below_noise_floor")
DEFAULT_SPP = "1,4,16"
DEFAULT_SEEDS = 4
DEFAULT_REFERENCE_RENDERS = 4


class UsageError(Exception):
    """Bad input; the message is one line naming it."""


# ---- argument parsing and validation (no side effects) -------------------------------------


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The `compare` subcommand's options (values are parsed and checked by run_compare, so
    every bad value gives one line on stderr)."""
    p.add_argument("scene", help="the .blend file")
    p.add_argument("--samplers", default="all",
                   help="comma-separated sampler names, or 'all' (default; see `stratum "
                   "samplers`)")
    p.add_argument("--spp", default=DEFAULT_SPP,
                   help=f"comma-separated samples per pixel (default {DEFAULT_SPP})")
    p.add_argument("--seeds", default=str(DEFAULT_SEEDS), metavar="K",
                   help=f"seeds 0..K-1 per configuration (default {DEFAULT_SEEDS})")
    ref = p.add_mutually_exclusive_group()
    ref.add_argument("--reference-spp", dest="reference_spp", metavar="N",
                     help="spp of each reference render (default 16 x the largest --spp)")
    ref.add_argument("--reference", metavar="FILE.exr",
                     help="use this linear EXR as the reference instead of rendering one")
    p.add_argument("--reference-renders", dest="reference_renders",
                   default=str(DEFAULT_REFERENCE_RENDERS), metavar="R",
                   help="reference = mean of R renders with seeds disjoint from the tested "
                   "ones; their spread gives its noise floor "
                   f"(default {DEFAULT_REFERENCE_RENDERS})")
    p.add_argument("--reference-sampler", dest="reference_sampler", metavar="NAME",
                   help="sampler of the reference renders (default sobol)")
    p.add_argument("--integrator", metavar="SPECS",
                   help="comma-separated estimator specs INTEGRATOR[:NAME=VALUE,...], e.g. "
                   "'path:light_sampling=bsdf,path:light_sampling=nee,"
                   "path:light_sampling=mis,mis_heuristic=balance,direct' (an item NAME=VALUE "
                   "continues the spec before it). INTEGRATOR: path, direct, ao, light (the "
                   "native registry). NAME=VALUE: light_sampling=mis|nee|bsdf, "
                   "mis_heuristic=power|balance|max, light_selection=mixed|power|uniform, "
                   "triangle_sampling=solid_angle|area, "
                   "rr_mode=throughput|albedo|off, rr_min_depth=N, control_variate=L_a. "
                   "Each spec gets a short label for tables and plots (path: bsdf, nee, "
                   "mis-<heuristic>; others: the integrator's name; +<setting> for other "
                   "settings it names). Default: the scene's integrator and settings")
    p.add_argument("--set", dest="set_values", action="append", default=[],
                   metavar="NAME=VALUE",
                   help="an estimator setting for every configuration and the reference "
                   "(repeatable; a spec's own value wins)")
    p.add_argument("--reference-integrator", dest="reference_integrator", metavar="SPEC",
                   help="estimator of the reference renders (default: the one --integrator "
                   "estimator, or 'path', the path tracer's default, when several are "
                   "compared)")
    p.add_argument("--hemisphere", help="hemisphere distribution (default: the scene's)")
    p.add_argument("--max-bounces", dest="max_bounces", help="default: the scene's")
    p.add_argument("--resolution", metavar="WxH", help="default: the scene's render size")
    p.add_argument("--crop", metavar="X,Y,W,H",
                   help="compare only this region (x, y from the top left); the full image is "
                   "still rendered")
    p.add_argument("--out", metavar="DIR", help="output folder (default compare-<scene name>)")
    p.add_argument("--jobs", metavar="J",
                   help="Blender processes at once (default 1); with --scheduler, the number "
                   "of batches (default: the cluster's worker threads)")
    p.add_argument("--threads", metavar="T",
                   help="render threads per Blender (default: cores / jobs locally, the "
                   "scene's setting on a cluster)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="render on this Dask distributed scheduler (e.g. tcp://host:8786)")


def _int(text: str | None, what: str, minimum: int) -> int | None:
    if text is None:
        return None
    try:
        value = int(str(text).strip())
    except ValueError:
        raise UsageError(f"{what} {text!r} is not an integer") from None
    if value < minimum:
        raise UsageError(f"{what} {value} must be >= {minimum}")
    return value


def _int_list(text: str, what: str, minimum: int) -> list[int]:
    parts = [t for t in str(text).split(",") if t.strip()]
    if not parts:
        raise UsageError(f"{what} is empty")
    values = [_int(t, what, minimum) for t in parts]
    return sorted({int(v) for v in values if v is not None})


def _resolution(text: str) -> tuple[int, int]:
    parts = text.lower().split("x")
    if len(parts) != 2:
        raise UsageError(f"--resolution {text!r}: expected WxH, e.g. 64x64")
    w = _int(parts[0], "--resolution width", 1)
    h = _int(parts[1], "--resolution height", 1)
    assert w is not None and h is not None
    return w, h


def _crop(text: str) -> tuple[int, int, int, int]:
    parts = text.split(",")
    if len(parts) != 4:
        raise UsageError(f"--crop {text!r}: expected X,Y,W,H")
    x, y = (_int(v, "--crop x/y", 0) for v in parts[:2])
    w, h = (_int(v, "--crop width/height", 1) for v in parts[2:])
    return int(x or 0), int(y or 0), int(w or 0), int(h or 0)


def _registry(kind: str) -> list[str]:
    from .. import native

    try:
        return [e.name for e in native.registry(kind)]
    except native.StratumError as exc:
        raise UsageError(str(exc)) from None


def _check_name(value: str | None, kind: str, option: str) -> None:
    if value is None:
        return
    names = _registry(kind)
    if value not in names:
        raise UsageError(f"unknown {kind} {value!r} for {option}; available: {', '.join(names)}")


def _check_blend(scene: Path) -> None:
    if not scene.is_file():
        raise UsageError(f"scene file not found: {scene}")
    try:
        with open(scene, "rb") as f:
            magic = f.read(7)
    except OSError as exc:
        raise UsageError(f"cannot read scene file {scene}: {exc.strerror}") from None
    # Plain, gzip- or zstd-compressed .blend.
    if not (magic == b"BLENDER" or magic[:2] == b"\x1f\x8b" or magic[:4] == b"\x28\xb5\x2f\xfd"):
        raise UsageError(f"not a .blend file: {scene}")


class Options:
    """Validated options of one comparison."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.scene = Path(args.scene)
        _check_blend(self.scene)
        all_samplers = _registry("sampler")
        names = [s.strip() for s in str(args.samplers).split(",") if s.strip()]
        if names == ["all"]:
            self.samplers = all_samplers
        else:
            if not names:
                raise UsageError("--samplers is empty")
            for name in names:
                if name not in all_samplers:
                    raise UsageError(f"unknown sampler {name!r}; available: "
                                     f"{', '.join(all_samplers)}")
            self.samplers = list(dict.fromkeys(names))
        self.spp = _int_list(args.spp, "--spp", 1)
        k = _int(args.seeds, "--seeds", 1)
        assert k is not None
        if k >= planning.REFERENCE_SEED_BASE:
            raise UsageError(f"--seeds {k} must be < {planning.REFERENCE_SEED_BASE}")
        self.seeds = list(range(k))
        self.reference_file = Path(args.reference) if args.reference else None
        self.reference_image = None
        if self.reference_file is not None:
            from .exr import ExrError, read_rgb

            try:
                self.reference_image = read_rgb(self.reference_file)
            except ExrError as exc:
                raise UsageError(f"unreadable reference: {exc}") from None
        self.reference_spp = _int(args.reference_spp, "--reference-spp", 1)
        if self.reference_file is None and self.reference_spp is None:
            self.reference_spp = 16 * max(self.spp)
        r = _int(args.reference_renders, "--reference-renders", 1)
        assert r is not None
        self.reference_seeds = [planning.REFERENCE_SEED_BASE + i for i in range(r)]
        self.reference_sampler = args.reference_sampler
        if self.reference_file is None:
            if self.reference_sampler is None:
                self.reference_sampler = "sobol" if "sobol" in all_samplers else all_samplers[0]
            _check_name(self.reference_sampler, "sampler", "--reference-sampler")
        else:
            self.reference_sampler = None
            self.reference_seeds = []
        self._parse_estimators(args)
        _check_name(args.hemisphere, "hemisphere", "--hemisphere")
        self.hemisphere: str | None = args.hemisphere
        self.max_bounces = _int(args.max_bounces, "--max-bounces", 0)
        self.resolution = _resolution(args.resolution) if args.resolution else None
        self.crop = _crop(args.crop) if args.crop else None
        self.out = Path(args.out) if args.out else Path(f"compare-{self.scene.stem}")
        if self.out.exists() and not self.out.is_dir():
            raise UsageError(f"--out {self.out} exists and is not a folder")
        self.jobs = _int(args.jobs, "--jobs", 1)
        self.threads = _int(args.threads, "--threads", 0)
        self.scheduler: str | None = args.scheduler

    def _parse_estimators(self, args: argparse.Namespace) -> None:
        from . import estimators as est

        try:
            self.common = est.parse_settings(getattr(args, "set_values", None) or [], "--set")
            integrators = _registry("integrator")
            self.specs = (est.parse_specs(args.integrator, integrators)
                          if args.integrator is not None else None)
            ref_text = getattr(args, "reference_integrator", None)
            if ref_text is not None and self.reference_file is not None:
                raise UsageError("--reference-integrator renders a reference; it cannot be "
                                 "combined with --reference FILE.exr")
            self.reference_spec = (est.parse_spec(ref_text, integrators)
                                   if ref_text is not None else None)
            if self.specs is not None:
                est.resolve_all(self.specs, self.common)  # duplicates, before any rendering
        except est.SpecError as exc:
            raise UsageError(str(exc)) from None

    def estimators(self, probe: dict[str, Any]) -> tuple[list[Any], Any]:
        """(estimators compared, reference estimator or None): the specs resolved against
        --set and the scene's settings (probe); without --integrator, the scene's own
        integrator and settings."""
        from . import estimators as est

        scene = probe.get("estimator_settings") or {}
        try:
            specs = self.specs
            if specs is None:
                specs = [est.Spec(str(probe["integrator"]), (), str(probe["integrator"]))]
            compared = est.resolve_all(specs, self.common, scene)
            if self.reference_file is not None:
                return compared, None
            if self.reference_spec is not None:
                reference = est.resolve(self.reference_spec, self.common, scene)
            elif len(compared) == 1:
                reference = compared[0]
            else:
                reference = est.resolve(est.parse_spec(est.PATH, [est.PATH]), self.common,
                                        scene)
        except est.SpecError as exc:
            raise UsageError(str(exc)) from None
        return compared, reference

    def check_against(self, resolution: tuple[int, int]) -> None:
        """Checks that need the render size (known after the scene was opened)."""
        w, h = resolution
        if self.crop is not None:
            x, y, cw, ch = self.crop
            if x + cw > w or y + ch > h:
                raise UsageError(f"--crop {x},{y},{cw},{ch} is outside the {w}x{h} image")
        if self.reference_image is not None:
            rh, rw = self.reference_image.shape[:2]
            if (rw, rh) != (w, h):
                raise UsageError(f"reference {self.reference_file} is {rw}x{rh}, the renders "
                                 f"are {w}x{h} (use --resolution {rw}x{rh})")


# ---- results ------------------------------------------------------------------------------


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


# ---- the command ---------------------------------------------------------------------------


def _fail(message: str, code: int) -> int:
    print(f"stratum compare: {message}", file=sys.stderr)
    return code


def run_compare(args: argparse.Namespace) -> int:
    from . import runner

    try:
        opts = Options(args)
        if blender_executable() is None:
            raise UsageError(NOT_FOUND_MESSAGE)
        probe = runner.probe_scene(opts.scene)
        resolution = opts.resolution or (int(probe["resolution"][0]),
                                         int(probe["resolution"][1]))
        opts.check_against(resolution)
    except UsageError as exc:
        return _fail(str(exc), 2)
    except runner.BatchError as exc:
        return _fail(f"cannot open {opts.scene} in Blender: {exc}", 2)

    try:
        estimators, reference_estimator = opts.estimators(probe)
    except UsageError as exc:
        return _fail(str(exc), 2)
    settings = SceneSettings(
        scene_sha256=planning.sha256_file(opts.scene), resolution=resolution,
        hemisphere=opts.hemisphere or str(probe["hemisphere"]),
        max_bounces=(opts.max_bounces if opts.max_bounces is not None
                     else int(probe["max_bounces"])))
    tests, refs = planning.plan(settings, estimators, opts.samplers, opts.spp, opts.seeds,
                                reference_estimator, opts.reference_sampler,
                                opts.reference_spp, opts.reference_seeds)
    out = opts.out
    try:
        (out / planning.REFERENCE_DIR).mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        return _fail(f"cannot create {out}: {exc.strerror}", 1)
    runner.remove_stale_temporaries(out)
    every = refs + tests
    pending = [c for c in every if planning.read_sidecar(out, c) is None]
    progress = runner.ProgressBar(pending, already_done=len(every) - len(pending))
    if not pending:
        print(f"stratum compare: all {len(every)} configurations already rendered",
              file=sys.stderr)
    else:
        if len(pending) < len(every):
            print(f"stratum compare: resuming: {len(every) - len(pending)} of {len(every)} "
                  "configurations already rendered", file=sys.stderr)
        progress.show()
        try:
            if opts.scheduler:
                _run_on_cluster(opts, out, settings, pending, progress)
            else:
                jobs = opts.jobs or 1
                threads = (opts.threads if opts.threads is not None
                           else max(1, (os.cpu_count() or 1) // jobs))
                batches = planning.split_batches(pending, jobs)
                runner.run_local(opts.scene, batches, settings, out, jobs, threads, progress)
        except runner.BatchError as exc:
            return _fail(str(exc), 1)
        except KeyboardInterrupt:
            return _fail("interrupted (finished configurations are kept; run again to "
                         "resume)", 130)

    try:
        results = compute_results(opts, out, settings, tests, refs, estimators,
                                  reference_estimator)
    except Exception as exc:  # noqa: BLE001 - one line, not a traceback
        return _fail(f"cannot compute the results: {type(exc).__name__}: {exc}", 1)
    _write_text_atomic(out / "results.json", json.dumps(results, indent=1))
    _write_text_atomic(out / "results.csv", _csv_text(results["renders"]))
    print(f"stratum compare: wrote {out / 'results.json'} and {out / 'results.csv'}")
    return _report(out, results)


def _run_on_cluster(opts: Options, out: Path, settings: SceneSettings, pending: list[Config],
                    progress: Any) -> None:
    from . import runner

    try:
        from distributed import Client
    except ImportError as exc:
        raise runner.BatchError(f"--scheduler needs dask distributed ({exc})") from None
    try:
        client = Client(opts.scheduler, timeout="20s")
    except Exception as exc:  # noqa: BLE001 - connection errors of any kind
        raise runner.BatchError(f"cannot connect to the Dask scheduler {opts.scheduler}: "
                                f"{exc}") from None
    try:
        count = opts.jobs or max(1, sum(client.nthreads().values()))
        batches = planning.split_batches(pending, count)
        progress.current = f"{len(batches)} batches on {opts.scheduler}"
        runner.run_dask(opts.scene, batches, settings, out, client, opts.threads, progress)
    finally:
        client.close()


def _report(out: Path, results: dict[str, Any]) -> int:
    try:
        from .report import write_report
    except ModuleNotFoundError as exc:
        if exc.name == f"{__name__}.report":
            return _fail("the report module stratum/compare/report.py is missing, so no report "
                         f"was made (results.json and results.csv are in {out})", 1)
        return _fail(f"the report needs a missing module: {exc}", 1)
    path = write_report(out, results)
    print(f"stratum compare: wrote {path}")
    return 0
