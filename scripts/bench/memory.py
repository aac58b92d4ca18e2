"""Peak memory of Stratum vs Cycles (issue 15, target 7) on the 1M-triangle monkeys (flat and
smooth) and the 10 000-instance scene of the export section.

    blender -b --factory-startup --python scripts/run_in_blender.py -- scripts.bench.memory \
        [--rebuild]

Each scene is built once (common.py's builders) and saved to
out/bench_cache/<name>-<key>.blend, the key a hash of the builders' source and Blender's version
(reused while it exists; --rebuild makes it again). Then, for each renderer, a fresh Blender
process (the same executable, --factory-startup) opens that file and renders 1 spp at 32 x 32
through F12 (bpy.ops.render.render); it reads VmHWM (peak resident set) from /proc/self/status
just before the render and just after. Reported: both peaks, the renderer's own increase (after
- before) and the ratio Stratum / Cycles of the peak (target <= 1) and of the increase. Written
to out/bench/memory.json and printed. Linux only (/proc).
"""

from __future__ import annotations

import argparse
import hashlib
import inspect
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import bpy

from scripts import REPO
from scripts.bench import common
from scripts.bench.common import (
    CACHE,
    EXPORT_CASES,
    EXPORT_RES,
    IN_BLENDER,
    run_main,
    script_argv,
    stratum_reason,
)
from scripts.bench.results import vm_hwm_kib, write_section

RENDERERS = ("CYCLES", "STRATUM")
RESULT_PREFIX = "BENCH_MEMORY "


def parse_args() -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="scripts.bench.memory")
    p.add_argument("--rebuild", action="store_true", help="build the cached scenes again")
    p.add_argument("--case", action="append", default=None,
                   choices=[name for name, _ in EXPORT_CASES])
    p.add_argument("--child", choices=RENDERERS, default=None,
                   help="(internal) render the open file with this engine and print VmHWM")
    return p.parse_args(script_argv())


def peak_kib() -> int:
    return vm_hwm_kib(Path("/proc/self/status").read_text())


def child(engine: str) -> int:
    """In the fresh process: render the open file with `engine`, print the peaks as JSON."""
    scene = bpy.context.scene
    if engine == "STRATUM":
        reason = stratum_reason()
        if reason:
            print(f"bench.memory: Stratum not available ({reason})", file=sys.stderr)
            return 2
        scene.stratum.samples = 1
    scene.render.engine = engine
    scene.render.resolution_x = scene.render.resolution_y = EXPORT_RES
    scene.cycles.samples = 1
    before = peak_kib()
    bpy.ops.render.render()
    after = peak_kib()
    print(RESULT_PREFIX + json.dumps({"before_kib": before, "after_kib": after}), flush=True)
    return 0


def cached_scene(name: str, build: Any, rebuild: bool) -> Path:
    """The scene `build` makes, saved once; keyed by the builders' source, their sizes and
    Blender's version, so that a changed builder or another Blender makes it again (and the
    file it replaces is removed)."""
    builders = (common._empty_scene, common.build_monkey_1m, build)
    key = "".join(inspect.getsource(f) for f in builders)
    key += f"{common.MONKEY_LEVELS} {common.INSTANCES} {bpy.app.version_string}"
    path = CACHE / f"{name}-{hashlib.sha256(key.encode()).hexdigest()[:12]}.blend"
    if rebuild or not path.is_file():
        build()
        path.parent.mkdir(parents=True, exist_ok=True)
        bpy.ops.wm.save_as_mainfile(filepath=str(path), compress=False)
        for stale in CACHE.glob(f"{name}-*.blend"):
            if stale != path:
                stale.unlink()
    return path


def measure(path: Path, engine: str) -> dict[str, int]:
    """One fresh Blender process rendering `path` with `engine`: its peaks in KiB."""
    cmd = [bpy.app.binary_path, "-b", "--factory-startup", "-noaudio", str(path),
           "--python", str(REPO / "scripts" / "run_in_blender.py"), "--", "scripts.bench.memory",
           "--child", engine]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=900, check=False)
    for line in proc.stdout.splitlines():
        if line.startswith(RESULT_PREFIX):
            return json.loads(line[len(RESULT_PREFIX):])
    raise RuntimeError(f"{engine} on {path.name}: no result (exit {proc.returncode}): "
                       f"{proc.stderr[-2000:]}")


def main() -> int:
    args = parse_args()
    if args.child:
        return child(args.child)
    if not IN_BLENDER:
        print("bench.memory: run it with Blender's executable (it starts one per render)",
              file=sys.stderr)
        return 1
    cases: dict[str, Any] = {}
    lines = [(f"Peak memory (VmHWM, MiB), a fresh Blender per render, 1 spp {EXPORT_RES}x"
              f"{EXPORT_RES}:"),
             f"  {'scene':18s}{'renderer':>9s}{'before':>9s}{'peak':>9s}{'increase':>10s}"]
    for name, build in EXPORT_CASES:
        if args.case and name not in args.case:
            continue
        path = cached_scene(name, build, args.rebuild)
        cases[name] = {engine.lower(): measure(path, engine) for engine in RENDERERS}
        for engine in ("cycles", "stratum"):
            r = cases[name][engine]
            lines.append(f"  {name:18s}{engine:>9s}{r['before_kib'] / 1024:9.0f}"
                         f"{r['after_kib'] / 1024:9.0f}"
                         f"{(r['after_kib'] - r['before_kib']) / 1024:10.0f}")
        c, s = cases[name]["cycles"], cases[name]["stratum"]
        inc_c, inc_s = c["after_kib"] - c["before_kib"], s["after_kib"] - s["before_kib"]
        lines.append(f"  {'':18s}ratio Stratum/Cycles: peak {s['after_kib'] / c['after_kib']:.2f}x"
                     f", increase {inc_s / inc_c if inc_c > 0 else float('nan'):.2f}x")
    print("\n".join(lines))
    print(f"written {write_section('memory', {'res': EXPORT_RES, 'cases': cases})}")
    return 0


if __name__ == "__main__":
    run_main(main)
