"""`stratum` command line: list samplers, print or plot a sampler's points, render a .blend
through Blender with Stratum.

Works without bpy: `render` runs Blender ($STRATUM_BLENDER or `blender`) in the background
with a small script that registers the add-on from this checkout and renders one frame;
`points` calls the native library directly (matplotlib only for --plot); `compare` renders
many configurations (estimators x samplers x spp x seeds) through Blender and compares them
(stratum.compare; Dask, OpenEXR and FLIP are imported only when it runs).

The package is what runs outside Blender and is not in the user's zip (scripts/package.py):
this module (the parser and the subcommands; `main` is the console entry point and
`python -m stratum.cli`), blender_process.py (finding and running Blender) and distributed.py
(`render --scheduler`, over Dask).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

from .. import native
from ..version import __version__
from .blender_process import (
    NOT_FOUND_MESSAGE,
    blender_executable,
    overrides_from_options,
    script_command,
)

# Runs inside Blender after blender_process's shared start (arguments, add-on, settings).
_RENDER_SCRIPT = r"""
from stratum.engine import StratumRenderEngine
out = args["output"]
ext = os.path.splitext(out)[1].lower()
fmt = {".png": "PNG", ".exr": "OPEN_EXR", ".jpg": "JPEG", ".jpeg": "JPEG",
       ".tif": "TIFF", ".tiff": "TIFF", ".hdr": "HDR"}.get(ext, "PNG")
scene.render.image_settings.file_format = fmt
scene.render.filepath = out
scene.render.use_file_extension = False
try:
    bpy.ops.render.render(write_still=True)
except RuntimeError as exc:
    print(f"stratum: render failed: {exc}", file=sys.stderr)
errors = [m for level, m in StratumRenderEngine.last_reports if level == "ERROR"]
for level, m in StratumRenderEngine.last_reports:
    print(f"stratum: {level.lower()}: {m}", file=sys.stderr)
code = 0 if not errors and os.path.isfile(out) else 1
"""


def _parse_resolution(text: str) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"bad resolution {text!r}; expected WxH") from exc
    if w <= 0 or h <= 0:
        raise argparse.ArgumentTypeError(f"bad resolution {text!r}; sizes must be > 0")
    return w, h


def _cmd_samplers(_: argparse.Namespace) -> int:
    try:
        entries = native.registry("sampler")
    except native.StratumError as exc:
        print(f"stratum: {exc}", file=sys.stderr)
        return 2
    width = max((len(e.name) for e in entries), default=0)
    for e in entries:
        print(f"{e.name:<{width}}  {e.description}")
    return 0


UINT32_MAX = 0xFFFFFFFF


def _parse_pair(text: str, what: str) -> tuple[int, int]:
    parts = text.split(",")
    try:
        a, b = (int(v) for v in parts)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(
            f"bad {what} {text!r}; expected two integers A,B") from exc
    return a, b


def _parse_dims(text: str) -> tuple[int, int]:
    return _parse_pair(text, "--dims")


def _parse_pixel(text: str) -> tuple[int, int]:
    return _parse_pair(text, "--pixel")


class UsageError(Exception):
    """A bad command-line value; the message names it."""


def _registry_names(kind: str) -> list[str]:
    return [e.name for e in native.registry(kind)]


def _validate_points_args(ns: argparse.Namespace) -> None:
    """Checks what the native call would reject, with messages in command-line terms."""
    if ns.sampler is None:
        raise UsageError("--sampler is required (see `stratum samplers`)")
    samplers = _registry_names("sampler")
    if ns.sampler not in samplers:
        raise UsageError(f"unknown sampler {ns.sampler!r}; available: {', '.join(samplers)}")
    if ns.count is None:
        raise UsageError("--count is required")
    if ns.count <= 0:
        raise UsageError(f"--count {ns.count} must be > 0")
    if ns.dims is None:
        raise UsageError("--dims A,B is required (see `stratum points --list-dims`)")
    for d in ns.dims:
        if not 0 <= d <= UINT32_MAX:
            raise UsageError(f"--dims: dimension {d} is out of range [0, {UINT32_MAX}]")
    if ns.samples is not None and ns.samples <= 0:
        raise UsageError(f"--samples {ns.samples} must be > 0")
    if not 0 <= ns.seed <= UINT32_MAX:
        raise UsageError(f"--seed {ns.seed} is out of range [0, {UINT32_MAX}]")
    width, height = ns.resolution
    x, y = ns.pixel
    if not (0 <= x < width and 0 <= y < height):
        raise UsageError(f"--pixel {x},{y} is outside the {width}x{height} image")
    if ns.hemisphere is not None:
        distributions = _registry_names("hemisphere")
        if ns.hemisphere not in distributions:
            raise UsageError(f"unknown hemisphere distribution {ns.hemisphere!r}; "
                             f"available: {', '.join(distributions)}")


def _list_dims() -> None:
    camera = native.camera_dimensions()
    stride = native.bounce_dimension_stride()
    blocks = [("camera", 0, camera)] + [
        (f"bounce {k}", camera + k * stride, stride) for k in range(2)]
    for title, start, size in blocks:
        print(f"{title} (dimensions {start}-{start + size - 1}):")
        for d in range(start, start + size):
            print(f"  {d:3d}  {native.dimension_name(d)}")
    print(f"Bounce blocks repeat with stride {stride}: bounce k uses dimensions "
          f"{camera} + {stride}*k .. {camera} + {stride}*k + {stride - 1}, named bounce<k>.*.")
    print("Dimensions 0,1 are the pixel-filter pair; a pair (2j, 2j+1) is read as the "
          "sampler's 2D point, as the integrators do.")


def _plot_points(path: Path, points: np.ndarray, directions: np.ndarray | None,
                 title: str, labels: tuple[str, str]) -> None:
    """Scatter with marginal histograms: of the 2D points, or (with directions) of the unit
    vectors projected onto the tangent plane, next to a side view (x, z)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(points)
    size = max(0.5, min(8.0, 4000.0 / max(n, 1)))
    bins = max(10, min(64, int(np.sqrt(n))))
    hemisphere = directions is not None
    ratios = [4, 1, 0.7, 4] if hemisphere else [4, 1]  # hemisphere: spacer, side view
    # Cells of equal width and height per ratio unit keep the scatter square, so the marginal
    # histograms line up with its axes.
    fig = plt.figure(figsize=(6.5 * sum(ratios) / 5.0, 6.5))
    grid = fig.add_gridspec(2, len(ratios), width_ratios=ratios, height_ratios=[1, 4],
                            wspace=0.08, hspace=0.08)
    main = fig.add_subplot(grid[1, 0])
    top = fig.add_subplot(grid[0, 0], sharex=main)
    right = fig.add_subplot(grid[1, 1], sharey=main)
    if hemisphere:
        xs, ys = directions[:, 0], directions[:, 1]
        lo, hi = -1.0, 1.0
        main.add_patch(plt.Circle((0.0, 0.0), 1.0, fill=False, color="0.6", lw=0.8))
        main.set_xlabel("x (tangent)")
        main.set_ylabel("y (tangent)")
    else:
        xs, ys = points[:, 0], points[:, 1]
        lo, hi = 0.0, 1.0
        main.set_xlabel(labels[0])
        main.set_ylabel(labels[1])
    main.scatter(xs, ys, s=size, color="tab:blue", linewidths=0)
    main.set_xlim(lo, hi)
    main.set_ylim(lo, hi)
    top.hist(xs, bins=bins, range=(lo, hi), color="tab:blue", alpha=0.7)
    right.hist(ys, bins=bins, range=(lo, hi), orientation="horizontal", color="tab:blue",
               alpha=0.7)
    top.tick_params(labelbottom=False)
    right.tick_params(labelleft=False)
    if hemisphere:
        side = fig.add_subplot(grid[:, 3])
        side.scatter(directions[:, 0], directions[:, 2], s=size, color="tab:orange",
                     linewidths=0)
        theta = np.linspace(0.0, np.pi, 200)
        side.plot(np.cos(theta), np.sin(theta), color="0.6", lw=0.8)
        side.set_xlim(-1.0, 1.0)
        side.set_ylim(0.0, 1.0)
        side.set_aspect("equal")
        side.set_xlabel("x")
        side.set_ylabel("z (normal)")
        side.set_title("side view (x, z)")
    fig.suptitle(title)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _cmd_points(ns: argparse.Namespace) -> int:
    try:
        if ns.list_dims:
            _list_dims()
            return 0
        _validate_points_args(ns)
        samples = ns.samples if ns.samples is not None else ns.count
        width, height = ns.resolution
        points = native.sampler_points(ns.sampler, samples, ns.seed, width, height, ns.pixel,
                                       ns.dims, ns.count)
        directions = None
        if ns.hemisphere is not None:
            directions, _ = native.warp_hemisphere(ns.hemisphere, points)
    except (UsageError, native.StratumError, ValueError) as exc:
        print(f"stratum points: {exc}", file=sys.stderr)
        return 2
    if ns.plot is not None:
        names = (native.dimension_name(ns.dims[0]), native.dimension_name(ns.dims[1]))
        title = (f"{ns.sampler}: {ns.count} points of pixel {ns.pixel[0]},{ns.pixel[1]}, "
                 f"dims {ns.dims[0]} ({names[0]}), {ns.dims[1]} ({names[1]}), seed {ns.seed}")
        if ns.hemisphere is not None:
            title += f", hemisphere {ns.hemisphere}"
        try:
            _plot_points(Path(ns.plot), points, directions, title, names)
        except ImportError as exc:
            print(f"stratum points: --plot needs matplotlib ({exc})", file=sys.stderr)
            return 2
        except OSError as exc:
            print(f"stratum points: cannot write {ns.plot}: {exc}", file=sys.stderr)
            return 1
        print(f"stratum: wrote {ns.plot}")
        return 0
    rows = directions if directions is not None else points
    sys.stdout.write("".join(",".join(f"{float(v):.9g}" for v in row) + "\n" for row in rows))
    return 0


def _cmd_render(ns: argparse.Namespace) -> int:
    if ns.sampler is not None:
        try:
            names = [e.name for e in native.registry("sampler")]
        except native.StratumError as exc:
            print(f"stratum: {exc}", file=sys.stderr)
            return 2
        if ns.sampler not in names:
            print(f"stratum: unknown sampler {ns.sampler!r}; available: {', '.join(names)}",
                  file=sys.stderr)
            return 2
    for name in ("samples", "max_bounces"):
        value = getattr(ns, name)
        if value is not None and value < (1 if name == "samples" else 0):
            print(f"stratum: --{name.replace('_', '-')} {value} is out of range",
                  file=sys.stderr)
            return 2
    if ns.seed is not None and ns.seed < 0:
        print(f"stratum: --seed {ns.seed} must be >= 0", file=sys.stderr)
        return 2
    scene = Path(ns.scene)
    if not scene.is_file():
        print(f"stratum: scene file not found: {scene}", file=sys.stderr)
        return 2
    blender = blender_executable()
    if blender is None:
        print(f"stratum: {NOT_FOUND_MESSAGE}", file=sys.stderr)
        return 2
    output = Path(ns.output).resolve()
    output.parent.mkdir(parents=True, exist_ok=True)
    if ns.scheduler:
        from .distributed import command_line_render

        return command_line_render(ns, blender, scene, output)
    cmd = script_command(blender, scene, _RENDER_SCRIPT, overrides_from_options(ns),
                         ns.resolution, output=str(output))
    proc = subprocess.run(cmd, check=False)
    if proc.returncode != 0:
        print(f"stratum: Blender render failed (exit code {proc.returncode})", file=sys.stderr)
        return 1
    print(f"stratum: wrote {output}")
    return 0


def version_report() -> str:
    """`stratum --version`: the add-on's version and the native library it loads (or why not)."""
    status = native.library_status()
    if status.version is None:
        return f"stratum {__version__}\nnative library: not loaded: {status.error}"
    return f"stratum {__version__}\nnative library {status.version}: {status.path}"


class _VersionAction(argparse.Action):
    """Prints version_report() and exits 0; the library is loaded only when asked."""

    def __init__(self, option_strings: list[str], dest: str, **_: object) -> None:
        super().__init__(option_strings, dest, nargs=0,
                         help="print Stratum's version and its native library's, then exit")

    def __call__(self, parser: argparse.ArgumentParser, *_: object) -> None:
        print(version_report())
        parser.exit()


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="stratum", description=__doc__)
    parser.add_argument("--version", action=_VersionAction)
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("samplers", help="list the native samplers")
    p.set_defaults(func=_cmd_samplers)

    p = sub.add_parser(
        "points", help="print or plot a sampler's points for one pixel",
        description="Prints the first --count samples of one pixel in two dimensions as CSV "
        "('x,y' in [0,1), or unit vectors 'x,y,z' with --hemisphere), or plots them with their "
        "marginal histograms (--plot). Sample indices beyond --samples are allowed.")
    p.add_argument("--list-dims", action="store_true",
                   help="print the named dimension layout and exit")
    p.add_argument("--sampler", help="sampler name (see `stratum samplers`)")
    p.add_argument("--count", type=int, help="number of points (sample indices 0..N-1)")
    p.add_argument("--dims", type=_parse_dims, metavar="A,B",
                   help="the two dimensions (see --list-dims); 0,1 = pixel filter")
    p.add_argument("--pixel", type=_parse_pixel, default=(0, 0), metavar="X,Y",
                   help="pixel (default 0,0)")
    p.add_argument("--seed", type=int, default=0, help="sampler seed (default 0)")
    p.add_argument("--samples", "--spp", dest="samples", type=int,
                   help="samples per pixel the sampler is set up for (default: --count)")
    p.add_argument("--resolution", type=_parse_resolution, default=(64, 64), metavar="WxH",
                   help="image size the sampler is set up for (default 64x64)")
    p.add_argument("--hemisphere", metavar="DIST",
                   help="warp the points through a hemisphere distribution (uniform_angles, "
                   "uniform, cosine) and print unit vectors")
    out = p.add_mutually_exclusive_group()
    out.add_argument("--csv", action="store_true", help="print CSV (the default)")
    out.add_argument("--plot", metavar="FILE.png", help="draw the points to a PNG")
    p.set_defaults(func=_cmd_points)

    p = sub.add_parser("render", help="render a .blend with Stratum (runs Blender)")
    p.add_argument("scene", help="the .blend file")
    p.add_argument("-o", "--output", required=True, help="output image (PNG, EXR, ...)")
    p.add_argument("--samples", "--spp", dest="samples", type=int, help="samples per pixel")
    p.add_argument("--sampler", help="sampler name (see `stratum samplers`)")
    p.add_argument("--seed", type=int)
    p.add_argument("--max-bounces", dest="max_bounces", type=int)
    p.add_argument("--resolution", type=_parse_resolution, help="WxH, e.g. 64x64")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="split the frame's samples over the workers of a Dask cluster: a "
                   "scheduler address (tcp://host:8786) or local:N for N local worker processes; "
                   "the image is bit-identical to one machine's (written by the native library: "
                   "linear EXR, or PNG/other by extension, without Blender's view transform)")
    p.set_defaults(func=_cmd_render)

    p = sub.add_parser(
        "compare", help="compare estimators and samplers on a .blend: renders, metrics, report",
        description="Renders every (estimator x sampler x spp x seed) of SCENE through Blender "
        "with the scene's render settings changed, plus a reference (mean of --reference-renders "
        "high-spp renders, or --reference FILE.exr); writes linear EXRs, results.json, "
        "results.csv and a report into --out. Finished configurations are not rendered again.")
    _compare_arguments(p)
    p.set_defaults(func=_cmd_compare)
    return parser


def _compare_arguments(p: argparse.ArgumentParser) -> None:
    from ..compare import add_arguments  # light: no numpy-heavy, dask or FLIP imports

    add_arguments(p)


def _cmd_compare(ns: argparse.Namespace) -> int:
    from ..compare import run_compare

    return run_compare(ns)


def main(argv: list[str] | None = None) -> int:
    ns = build_parser().parse_args(argv)
    return int(ns.func(ns))

