"""Runs corpus cases one after another inside one Blender process and appends one JSON line per
event to a results file (Blender's own stdout is noise):

    {"case": NAME, "event": "start"}
    {"case": NAME, "event": "done", "failures": [...], "reports": [[level, text], ...],
     "stats": {...}, "seconds": S}

Blender 3.4:  blender -b --factory-startup -noaudio --python worker.py -- ARGS
bpy wheel:    python worker.py ARGS
ARGS: --results FILE --tmp DIR [--capture DIR] CASE...

With --capture, every native scene the engine renders is saved (stratum_scene_save) as
DIR/CASE.json with its renderer settings in DIR/CASE.settings.json, before the render starts:
replay.py renders them again with a stratum-native binary (e.g. the ASan build). A crash
kills this process; the runner records the case in progress as crashed and starts a new worker
for the rest.
"""

from __future__ import annotations

import json
import os
import sys
import time
import traceback
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
for path in (str(REPO / "addon"), str(HERE.parent)):
    if path not in sys.path:
        sys.path.insert(0, path)

import bpy
import numpy as np

from corpus import all_cases
from corpus.case import BLENDER_ERROR, Case, Render, judge
from corpus.stage import Stage
from exr_file import read_image


class Capture:
    """Saves the native scene and settings of each render under a name (when enabled)."""

    def __init__(self, folder: Path | None) -> None:
        self.folder = folder
        self.name: str | None = None


def install_capture(capture: Capture) -> None:
    """Wraps native.Renderer (looked up by the engine at render time) so that the scene is saved
    when a renderer is made from it and the settings when it starts."""
    from stratum import native

    base = native.Renderer

    class CapturingRenderer(base):  # type: ignore[misc, valid-type]
        def __init__(self, scene: Any, **settings: Any) -> None:
            self._capture_settings: dict[str, Any] = {}
            self._capture_stem: Path | None = None
            if capture.folder is not None and capture.name is not None:
                self._capture_stem = capture.folder / capture.name
                scene.save(self._capture_stem.with_suffix(".json"))
            super().__init__(scene, **settings)

        def set(self, name: str, value: Any) -> None:
            self._capture_settings[name] = value
            super().set(name, value)

        def start(self) -> None:
            if self._capture_stem is not None:
                self._capture_stem.with_suffix(".settings.json").write_text(
                    json.dumps(self._capture_settings))
            super().start()

    native.Renderer = CapturingRenderer


def render(scene: Any, path: Path) -> Render:
    """Renders the scene to a 32-bit float EXR and reads it back; the engine's reports, plus
    the render operator's own error when Blender stopped before the engine (e.g. no camera)."""
    from stratum.engine import StratumRenderEngine

    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    path.unlink(missing_ok=True)
    StratumRenderEngine.last_reports = []
    operator_error = ""
    try:
        bpy.ops.render.render(write_still=True)
    except RuntimeError as exc:
        operator_error = str(exc).strip()
    result = Render(list(StratumRenderEngine.last_reports))
    engine_errors = result.messages("ERROR")
    # The operator repeats the engine's ERROR; keep only what Blender said on its own.
    if operator_error and not any(m in operator_error for m in engine_errors):
        result.reports.append((BLENDER_ERROR, operator_error))
    if path.is_file():
        result.pixels = read_image(path)
    return result


def stats(pixels: np.ndarray | None) -> dict[str, Any]:
    if pixels is None:
        return {"image": False}
    finite = np.isfinite(pixels)
    rgb = np.where(finite, pixels, 0.0)[..., :3].reshape(-1, 3)
    return {"image": True, "width": int(pixels.shape[1]), "height": int(pixels.shape[0]),
            "non_finite": int(np.count_nonzero(~finite)),
            "mean": [float(v) for v in rgb.mean(axis=0)],
            "max": float(rgb.max()) if rgb.size else 0.0}


def run_case(c: Case, tmp: Path, capture: Capture) -> dict[str, Any]:
    started = time.perf_counter()
    folder = tmp / c.name
    folder.mkdir(parents=True, exist_ok=True)
    c.build(Stage(folder))
    capture.name = c.name
    try:
        result = render(bpy.context.scene, folder / "render.exr")
    finally:
        capture.name = None
    reference = None
    if c.expect.same_as is not None and result.pixels is not None:
        c.expect.same_as(Stage(folder))
        reference = render(bpy.context.scene, folder / "reference.exr")
    return {"failures": judge(c, result, reference), "reports": result.reports,
            "stats": stats(result.pixels),
            "reference_reports": reference.reports if reference else None,
            "seconds": round(time.perf_counter() - started, 3)}


def main(argv: list[str]) -> int:
    args = argv[argv.index("--") + 1:] if "--" in argv else argv[1:]
    results = tmp = capture_dir = None
    names: list[str] = []
    it = iter(args)
    for arg in it:
        if arg == "--results":
            results = Path(next(it))
        elif arg == "--tmp":
            tmp = Path(next(it))
        elif arg == "--capture":
            capture_dir = Path(next(it))
        else:
            names.append(arg)
    if results is None or tmp is None:
        print("usage: worker.py --results FILE --tmp DIR [--capture DIR] CASE...",
              file=sys.stderr)
        return 2
    import stratum

    stratum.register()
    capture = Capture(capture_dir)
    if capture_dir is not None:
        capture_dir.mkdir(parents=True, exist_ok=True)
        install_capture(capture)
    cases = all_cases()
    with results.open("a", encoding="utf-8") as out:
        def emit(record: dict[str, Any]) -> None:
            out.write(json.dumps(record) + "\n")
            out.flush()
            os.fsync(out.fileno())

        for name in names:
            emit({"case": name, "event": "start"})
            try:
                record = run_case(cases[name], tmp, capture)
            except Exception as exc:  # noqa: BLE001 - a broken case is that case's failure
                record = {"failures": [f"the case itself raised {type(exc).__name__}: {exc}",
                                       traceback.format_exc()],
                          "reports": [], "stats": {"image": False}, "seconds": 0.0}
            emit({"case": name, "event": "done", "version": bpy.app.version_string, **record})
    return 0


if __name__ == "__main__":
    code = 1
    try:
        code = main(sys.argv)
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
