"""F12 progress cadence (issue 14): how often an F12 render of the Cornell box (512 x 512,
64 spp, 8 bounces by default) copies new pixels into Blender's render result and moves its
"Sample N/M" counter.

    blender -b --factory-startup --python scripts/run_in_blender.py -- scripts.bench.progress \
        [--res 512 --samples 64]

(also under the bpy wheel: .venv/bin/python -m scripts.bench.progress). The render goes through
the engine's own loop (engine/final_render.py render_progressively), wrapped so that each
update_result and each status line is timed (time.perf_counter) with the renderer's progress
at that moment. Reported: result updates per second of rendering, the longest gap between two
updates, the longest time the shown sample count stood still, and how many updates and counter
values came during the last pass (samples 32 to 64: half of the render). Appended to
out/bench.txt.

Measured on this machine's 2 shared cores (Blender 3.4, 2026-11, under load: 130-140 s
renders): before tiles were split to 16² and the counter counted samples per pixel, 3.1
result updates a second but gaps of up to 2.9 s, and the counter stood at 32/64 for 94 s (1
value in the last pass); after, 1.3 updates a second (result_interval's ladder), gaps of at
most 0.86 s, the counter never still for more than 0.49 s (308 values in the last pass).
"""

from __future__ import annotations

import argparse
import itertools
import os
import re
import sys
import time
import traceback
from pathlib import Path
from typing import Any

import bpy

from scripts import REPO

OUT = REPO / "out"
IN_BLENDER = Path(sys.argv[0]).name.startswith("blender")


def parse_args() -> argparse.Namespace:
    argv = (sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []) if IN_BLENDER \
        else sys.argv[1:]
    p = argparse.ArgumentParser(prog="scripts.bench.progress")
    p.add_argument("--samples", type=int, default=64)
    p.add_argument("--res", type=int, default=512)
    p.add_argument("--scene", type=Path, default=REPO / "scenes" / "cornell_box.blend")
    return p.parse_args(argv)


class Timeline:
    """Forwards to the engine and the renderer, timing what the loop shows."""

    def __init__(self, engine: Any, renderer: Any) -> None:
        self.engine, self.renderer = engine, renderer
        self.progress: Any = None
        self.results: list[tuple[float, Any]] = []  # (time, progress)
        self.counters: list[tuple[float, float, Any]] = []  # (time, shown sample count, progress)

    def progress_now(self) -> Any:
        self.progress = self.renderer.progress()
        return self.progress


class RecordingEngine:
    def __init__(self, timeline: Timeline) -> None:
        self._t = timeline

    def __getattr__(self, name: str) -> Any:
        return getattr(self._t.engine, name)

    def update_result(self, result: Any) -> None:
        self._t.results.append((time.perf_counter(), self._t.progress))
        self._t.engine.update_result(result)

    def update_stats(self, stats: str, info: str) -> None:
        found = re.match(r"Sample ([\d.]+)/", info)
        if found:
            self._t.counters.append((time.perf_counter(), float(found.group(1)), self._t.progress))
        self._t.engine.update_stats(stats, info)


class RecordingRenderer:
    def __init__(self, timeline: Timeline) -> None:
        self._t = timeline

    def __getattr__(self, name: str) -> Any:
        return getattr(self._t.renderer, name)

    def progress(self) -> Any:
        return self._t.progress_now()


def render(args: argparse.Namespace) -> Timeline:
    import stratum

    bpy.ops.wm.open_mainfile(filepath=str(args.scene), load_ui=False)
    stratum.register()
    from stratum.engine import StratumRenderEngine, final_render

    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    scene.render.resolution_x = scene.render.resolution_y = args.res
    scene.render.resolution_percentage = 100
    scene.stratum.samples = args.samples
    scene.stratum.max_bounces = 8
    timelines: list[Timeline] = []
    original = final_render.render_progressively

    def recorded(engine: Any, renderer: Any, width: int, height: int, *rest: Any) -> None:
        timeline = Timeline(engine, renderer)
        timelines.append(timeline)
        original(RecordingEngine(timeline), RecordingRenderer(timeline), width, height, *rest)

    final_render.render_progressively = recorded
    try:
        bpy.ops.render.render()
    finally:
        final_render.render_progressively = original
    errors = [m for level, m in StratumRenderEngine.last_reports if level == "ERROR"]
    if errors or not timelines:
        raise RuntimeError("; ".join(errors) or "the engine did not render")
    return timelines[0]


def report(args: argparse.Namespace, t: Timeline) -> list[str]:
    times = [at for at, _ in t.results]
    start, end = times[0], times[-1]
    gaps = [b - a for a, b in itertools.pairwise(times)]
    # The longest time the shown count stood still, up to the end of the render.
    still, since, shown = 0.0, t.counters[0][0], t.counters[0][1]
    for at, count, _ in t.counters:
        if count != shown:
            still, since, shown = max(still, at - since), at, count
    still = max(still, t.counters[-1][0] - since)
    half = args.samples // 2
    last_pass_results = sum(1 for _, p in t.results
                            if p is not None and p.samples_done == half and not p.done)
    last_pass_counts = {c for _, c, p in t.counters
                        if p is not None and p.samples_done == half and not p.done}
    return [
        "",
        (f"F12 progress: {args.scene.name}, {args.res}x{args.res}, {args.samples} spp, "
         f"8 bounces, Blender {bpy.app.version_string}"),
        f"  render (first to last result update)  {end - start:8.2f} s",
        (f"  result updates                        {len(times):8d}"
         f"   ({(len(times) - 1) / (end - start):.2f} per second)"),
        f"  longest gap between result updates    {max(gaps):8.2f} s",
        f"  longest time the sample count stood   {still:8.2f} s",
        (f"  in the last pass ({half}->{args.samples}): {last_pass_results} result updates, "
         f"{len(last_pass_counts)} sample counts shown"),
    ]


def main() -> int:
    args = parse_args()
    lines = report(args, render(args))
    text = "\n".join(lines)
    print(text)
    OUT.mkdir(parents=True, exist_ok=True)
    with (OUT / "bench.txt").open("a") as out:
        out.write(text + "\n")
    return 0


if __name__ == "__main__":
    code = 1
    try:
        code = main()
    except Exception:  # noqa: BLE001
        traceback.print_exc()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
    if IN_BLENDER:  # Blender's --python does not propagate sys.exit codes reliably
        os._exit(code)
    sys.exit(code)
