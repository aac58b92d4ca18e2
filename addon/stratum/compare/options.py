"""The options of `stratum compare`: the argparse definitions (add_arguments) and their
validation into an `Options` (no side effects: nothing is written or run before every value
has been checked, and each bad value gives one line naming it)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from . import estimators as est
from . import plan as planning

DEFAULT_SPP = "1,4,16"
DEFAULT_SEEDS = 4
DEFAULT_REFERENCE_RENDERS = 4


class UsageError(Exception):
    """Bad input; the message is one line naming it."""


def _listed(setting: str) -> str:
    """The choices of a setting as help lists them: "random, lcg, ..."."""
    from .. import native

    return ", ".join(native.setting(setting).choice_names())


def _assignment(name: str) -> str:
    """NAME=VALUE of an estimator setting as help shows it, with the library's default."""
    from .. import native

    setting = native.setting(name)
    syntax = est.value_syntax(name)
    value = syntax if setting.choices else f"<{syntax}>"
    return f"{name}={value} (default {setting.default})"


def _library_help() -> dict[str, str]:
    """Help texts made from the library's settings: the samplers, integrators and hemisphere
    distributions, and the estimator settings with their values and defaults. Without the
    library (`stratum --help` must still work) they say that its names are not listed; the
    reason shows when the command runs."""
    from .. import native

    try:
        return {
            "samplers": f"sampler names ({_listed('sampler')})",
            "integrators": f"{_listed('integrator')} (the native registry)",
            "hemispheres": _listed("hemisphere"),
            "assignments": ", ".join(_assignment(name) for name in est.SETTING_NAMES),
        }
    except native.StratumError:
        unlisted = "(not listed: the native library cannot be loaded)"
        return {"samplers": f"sampler names {unlisted}",
                "integrators": f"a name of the native integrator registry {unlisted}",
                "hemispheres": f"a name of the native hemisphere registry {unlisted}",
                "assignments": f"{', '.join(est.SETTING_NAMES)}, values {unlisted}"}


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The `compare` subcommand's options (values are parsed and checked by run_compare, so
    every bad value gives one line on stderr). Names, values and defaults of samplers,
    integrators and estimator settings come from the library."""
    listed = _library_help()
    p.add_argument("scene", help="the .blend file")
    p.add_argument("--samplers", default="all",
                   help=f"comma-separated {listed['samplers']}, or 'all' (default)")
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
                   f"continues the spec before it). INTEGRATOR: {listed['integrators']}. "
                   f"NAME=VALUE: {listed['assignments']}. "
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
    p.add_argument("--hemisphere",
                   help=f"hemisphere distribution: {listed['hemispheres']} (default: the "
                   "scene's)")
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


def _setting_int(text: str | None, option: str, name: str) -> int | None:
    """An integer option that becomes render setting `name`, checked against its range."""
    from .. import native

    try:
        setting = native.setting(name)
    except native.StratumError as exc:
        raise UsageError(str(exc)) from None
    value = _int(text, option, int(setting.minimum))
    if value is not None and value > setting.maximum:
        raise UsageError(f"{option} {value} must be <= {setting.maximum}")
    return value


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
        self.max_bounces = _setting_int(args.max_bounces, "--max-bounces", "max_bounces")
        self.resolution = _resolution(args.resolution) if args.resolution else None
        self.crop = _crop(args.crop) if args.crop else None
        self.out = Path(args.out) if args.out else Path(f"compare-{self.scene.stem}")
        if self.out.exists() and not self.out.is_dir():
            raise UsageError(f"--out {self.out} exists and is not a folder")
        self.jobs = _int(args.jobs, "--jobs", 1)
        self.threads = _setting_int(args.threads, "--threads", "threads")
        self.scheduler: str | None = args.scheduler

    def _parse_estimators(self, args: argparse.Namespace) -> None:
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
