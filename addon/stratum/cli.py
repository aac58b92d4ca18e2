"""`stratum` command line: list samplers, render a .blend through Blender with Stratum.

Works without bpy: `render` runs Blender ($STRATUM_BLENDER or `blender`) in the background
with a small script that registers the add-on from this checkout and renders one frame.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

from . import native

ADDON_PARENT = Path(__file__).resolve().parent.parent  # the folder that holds stratum/

# Runs inside Blender; receives its arguments as JSON after "--".
_BLENDER_SCRIPT = r"""
import json, os, sys, traceback
args = json.loads(sys.argv[sys.argv.index("--") + 1])
sys.path.insert(0, args["addon_parent"])
code = 1
try:
    import bpy
    import stratum
    from stratum.engine import StratumRenderEngine
    stratum.register()
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    s = scene.stratum
    for name in ("samples", "seed", "max_bounces", "sampler"):
        if args.get(name) is not None:
            setattr(s, name, args[name])
    if args.get("resolution"):
        scene.render.resolution_x, scene.render.resolution_y = args["resolution"]
        scene.render.resolution_percentage = 100
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
except Exception:
    traceback.print_exc()
    code = 1
sys.stdout.flush()
sys.stderr.flush()
os._exit(code)
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


def blender_executable() -> str | None:
    exe = os.environ.get("STRATUM_BLENDER", "blender")
    return shutil.which(exe) or (exe if os.path.isfile(exe) else None)


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
        print("stratum: Blender not found (set STRATUM_BLENDER)", file=sys.stderr)
        return 2
    output = Path(ns.output).resolve()
    output.parent.mkdir(parents=True, exist_ok=True)
    payload = {
        "addon_parent": str(ADDON_PARENT),
        "samples": ns.samples,
        "seed": ns.seed,
        "max_bounces": ns.max_bounces,
        "sampler": ns.sampler,
        "resolution": list(ns.resolution) if ns.resolution else None,
        "output": str(output),
    }
    cmd = [blender, "-b", "--factory-startup", str(scene), "--python-expr", _BLENDER_SCRIPT,
           "--", json.dumps(payload)]
    proc = subprocess.run(cmd, check=False)
    if proc.returncode != 0:
        print(f"stratum: Blender render failed (exit code {proc.returncode})", file=sys.stderr)
        return 1
    print(f"stratum: wrote {output}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="stratum", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("samplers", help="list the native samplers")
    p.set_defaults(func=_cmd_samplers)

    p = sub.add_parser("render", help="render a .blend with Stratum (runs Blender)")
    p.add_argument("scene", help="the .blend file")
    p.add_argument("-o", "--output", required=True, help="output image (PNG, EXR, ...)")
    p.add_argument("--samples", "--spp", dest="samples", type=int, help="samples per pixel")
    p.add_argument("--sampler", help="sampler name (see `stratum samplers`)")
    p.add_argument("--seed", type=int)
    p.add_argument("--max-bounces", dest="max_bounces", type=int)
    p.add_argument("--resolution", type=_parse_resolution, help="WxH, e.g. 64x64")
    p.set_defaults(func=_cmd_render)
    return parser


def main(argv: list[str] | None = None) -> int:
    ns = build_parser().parse_args(argv)
    return int(ns.func(ns))


if __name__ == "__main__":
    sys.exit(main())
