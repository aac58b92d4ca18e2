"""Rendered-viewport latency (issue 14, acceptance 3): the time from a change to the first new
frame the viewport session (addon/stratum/engine/viewport_session.py) has to draw.

    blender -b --factory-startup -noaudio --python scripts/run_in_blender.py -- \
        scripts.bench.viewport [--steps 5]
    .venv/bin/python -m scripts.bench.viewport

(`make bench` runs it in Blender 3.4.) The view is 800 x 600, the scene camera's (camera view:
view matrix and window matrix as a 3D view hands them to the engine, window matrix from
Object.calc_matrix_camera). Each case is timed from the change (made in Blender, evaluated,
handed to the session as view_update / view_draw would) until session.frame() returns a frame
of the new generation, polling every millisecond; the session is refining when the change comes
(a user orbits or drags while it renders), so cancelling the running render is included.
Reported: median and maximum over --steps changes, with start passes (start resolution 64, the
default: the first frame is one sample at 62 x 47, pixel size 13) and without (start resolution
0: the first frame is one sample at 800 x 600).

* orbit: the view rotated by 2 degrees about the vertical axis through the box (Cornell box);
* material: the White material's base colour changed (Cornell box), a live edit;
* transform: the monkey of the 1M-triangle scene (common.py's build_monkey_1m) moved, a live edit
  and a top-level BVH recommit (bvh = dynamic).

Targets (issue 14): orbit <= 100 ms, transform <= 200 ms, material <= 100 ms. Cycles' viewport
cannot be timed the same way in background mode (it needs a drawn 3D view): not reported.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import bpy
import numpy as np

from scripts import REPO

OUT = REPO / "out"
CORNELL = REPO / "scenes" / "cornell_box.blend"
WIDTH, HEIGHT = 800, 600
IN_BLENDER = Path(sys.argv[0]).name.startswith("blender")


def parse_args() -> argparse.Namespace:
    argv = (sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []) if IN_BLENDER \
        else sys.argv[1:]
    p = argparse.ArgumentParser(prog="scripts.bench.viewport")
    p.add_argument("--steps", type=int, default=5, help="changes timed per case")
    return p.parse_args(argv)


def _depsgraph() -> Any:
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    return depsgraph


def camera_view(depsgraph: Any, rotate_z: float = 0.0,
                pivot: tuple[float, float, float] = (0.0, 0.0, 1.0)) -> Any:
    """The 800 x 600 camera view, its view orbited by rotate_z radians about the vertical axis
    through `pivot` (an orbit step)."""
    from mathutils import Matrix
    from stratum.engine.viewport import camera_from_matrices
    from stratum.engine.viewport_session import View

    scene = depsgraph.scene_eval
    ob = scene.camera.evaluated_get(depsgraph)
    window = ob.calc_matrix_camera(depsgraph, x=WIDTH, y=HEIGHT)
    orbit = Matrix.Translation(pivot) @ Matrix.Rotation(rotate_z, 4, "Z") @ \
        Matrix.Translation(tuple(-v for v in pivot))
    view_matrix = (orbit @ ob.matrix_world).inverted()
    return View(camera_from_matrices(view_matrix, window, True), WIDTH, HEIGHT)


def first_new_frame(session: Any) -> float:
    """Seconds until session.frame() returns a frame of the session's current generation."""
    start = time.perf_counter()
    while True:
        frame = session.frame()
        if frame is not None and frame.generation == session.generation:
            return time.perf_counter() - start
        time.sleep(0.001)


def session_for(scene: Any, start_resolution: int) -> tuple[Any, Any]:
    from stratum.engine.viewport import settings_from_scene
    from stratum.engine.viewport_session import ViewportSession

    scene.render.engine = "STRATUM"
    scene.stratum.preview_samples = 1024  # still refining whenever a change comes
    scene.stratum.preview_start_resolution = start_resolution
    depsgraph = _depsgraph()
    session = ViewportSession()
    session.update(depsgraph)
    session.set_settings(settings_from_scene(scene))
    session.set_view(camera_view(depsgraph))
    first_new_frame(session)
    return session, depsgraph


def timed_edits(session: Any, edit: Callable[[int], None], steps: int) -> list[float]:
    """Each step: edit(step) in Blender, the depsgraph evaluated and its updates sent
    (view_update), the view handed over again (view_draw), then the first new frame."""
    from stratum.export.updates import collect_updates

    times = []
    updates: list[Any] = []

    def keep(scene: Any, depsgraph: Any) -> None:
        updates.extend(collect_updates(depsgraph))

    for step in range(steps):
        updates.clear()
        bpy.app.handlers.depsgraph_update_post.append(keep)
        start = time.perf_counter()
        try:
            edit(step)
            depsgraph = _depsgraph()
        finally:
            bpy.app.handlers.depsgraph_update_post.remove(keep)
        kind = session.update(depsgraph, updates)
        if kind != "edits":
            raise RuntimeError(f"the edit was sent as {kind!r}, not as live edits")
        session.set_view(camera_view(depsgraph))
        times.append(time.perf_counter() - start + first_new_frame(session))
        time.sleep(0.2)  # let it refine a little before the next change
    return times


def bench_orbit(start_resolution: int, steps: int) -> list[float]:
    bpy.ops.wm.open_mainfile(filepath=str(CORNELL), load_ui=False)
    session, depsgraph = session_for(bpy.context.scene, start_resolution)
    try:
        times = []
        for step in range(1, steps + 1):
            view = camera_view(depsgraph, rotate_z=math.radians(2.0 * step))
            start = time.perf_counter()
            session.set_view(view)
            times.append(time.perf_counter() - start + first_new_frame(session))
            time.sleep(0.2)
        return times
    finally:
        session.free()


def bench_material(start_resolution: int, steps: int) -> list[float]:
    bpy.ops.wm.open_mainfile(filepath=str(CORNELL), load_ui=False)
    session, _ = session_for(bpy.context.scene, start_resolution)
    bsdf = next(n for n in bpy.data.materials["White"].node_tree.nodes
                if n.type == "BSDF_PRINCIPLED")

    def recolour(step: int) -> None:
        grey = 0.5 + 0.05 * step
        bsdf.inputs["Base Color"].default_value = (grey, 0.6, 0.7, 1.0)

    try:
        return timed_edits(session, recolour, steps)
    finally:
        session.free()


def bench_transform(start_resolution: int, steps: int) -> list[float]:
    from scripts.bench.common import build_monkey_1m

    scene = build_monkey_1m()
    session, _ = session_for(scene, start_resolution)
    monkey = scene.objects["monkey"]

    def move(step: int) -> None:
        monkey.location.x = 0.05 * (step + 1)

    try:
        return timed_edits(session, move, steps)
    finally:
        session.free()


def line(name: str, times: list[float], target: float) -> str:
    ms = np.array(times) * 1e3
    return (f"  {name:34s}median {statistics.median(ms):7.1f} ms   max {ms.max():7.1f} ms"
            f"   (target <= {target * 1e3:.0f} ms)")


def main() -> int:
    args = parse_args()
    import stratum

    stratum.register()
    lines = [(f"Rendered viewport latency, {WIDTH}x{HEIGHT}, change -> first new frame, "
              f"{args.steps} changes each, Blender {bpy.app.version_string}:")]
    for resolution in (64, 0):
        lines.append(f" start resolution {resolution}:")
        lines.append(line("orbit 2 deg (Cornell box)", bench_orbit(resolution, args.steps), 0.1))
        lines.append(line("material colour (Cornell box)", bench_material(resolution, args.steps),
                          0.1))
        lines.append(line("transform (monkey, 1M triangles)",
                          bench_transform(resolution, args.steps), 0.2))
        print("\n".join(lines), flush=True)
    table = "\n".join(lines)
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "bench_viewport.txt").write_text(table + "\n")
    print(f"written {OUT / 'bench_viewport.txt'}")
    return 0


if __name__ == "__main__":
    import os
    import traceback

    code = 1
    try:
        code = main()
    except Exception:  # noqa: BLE001
        traceback.print_exc()
    sys.stdout.flush()
    if IN_BLENDER:  # Blender's --python does not propagate sys.exit codes reliably
        os._exit(code)
    sys.exit(code)
