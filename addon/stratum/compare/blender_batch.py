"""Runs inside Blender (3.4's Python, or a Python with the bpy wheel): renders a batch of
`stratum compare` configurations of the scene Blender has opened, one after the other, so the
Blender start-up is paid once per batch.

    blender -b --factory-startup -noaudio SCENE.blend --python blender_batch.py -- BATCH.json

BATCH.json: {"mode": "render" | "probe", "addon_parent": folder holding stratum/,
"output_dir": str, "threads": int | null, "configs": [entry, ...], "probe_output": str}, an
entry as made by plan.batch_entry. For each entry the script sets scene.stratum (sampler,
samples, seed, integrator, hemisphere, max_bounces, threads, and the estimator settings of
estimators.SETTING_NAMES: light sampling and selection, Russian roulette, control variate,
adaptive sampling) and the render resolution, renders with the STRATUM engine, saves the Render
Result as a linear 32-bit float OpenEXR (as scripts/render/render_to_files.py does), then writes the
JSON sidecar (key, render time, EXR size and sha256). An estimator setting without a
scene.stratum property (an add-on older than issue 6's Blender side) fails the configuration,
naming the property: never a render with a silently different estimator.
EXR and sidecar go to a temporary name first and are renamed into place, the sidecar last: a
configuration counts as done only when its sidecar exists. A configuration that fails is
reported and the batch goes on; the script then exits with status 1. After each one it prints
`STRATUM_COMPARE_DONE {json}` on stdout (the runner's progress bar reads it).

"seconds" is the wall time of bpy.ops.render.render() (scene export, BVH build and path
tracing); "trace_seconds" is the native renderer's own render time (path tracing only). Each
sampler's one-off set-up in the process (bluenoise's texture) is done before, untimed.

Probe mode writes the scene's render size and Stratum settings to probe_output instead.
Any failure prints `stratum compare: <message>` on stderr and exits with status 1.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

DONE_PREFIX = "STRATUM_COMPARE_DONE "
START_PREFIX = "STRATUM_COMPARE_START "

RenderFn = Callable[[dict[str, Any], Path], dict[str, Any]]


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _tmp_name(path: Path) -> Path:
    # The extension stays last: Blender's writers look at it.
    return path.with_name(f".tmp-{os.getpid()}-{path.name}")


def write_json_atomic(path: Path, data: dict[str, Any]) -> None:
    tmp = _tmp_name(path)
    tmp.write_text(json.dumps(data, indent=1, sort_keys=True))
    os.replace(tmp, path)


def run_batch(payload: dict[str, Any], render_fn: RenderFn) -> None:
    """Renders every entry with render_fn(entry, exr_path) -> timings, then commits its EXR and
    its sidecar (in that order, each by rename). A failed entry is reported on stderr and the
    batch goes on with the next one (what succeeds stays usable by a resume); raises at the
    end if any failed."""
    out_dir = Path(payload["output_dir"])
    failures: list[str] = []
    for entry in payload["configs"]:
        print(START_PREFIX + json.dumps({"key": entry["key"], "label": entry["label"]}),
              flush=True)
        try:
            timings = _render_entry(out_dir, entry, render_fn)
        except Exception as exc:  # noqa: BLE001 - reported, then the next configuration
            message = f"{entry['label']}: {_first_line(exc)}"
            print(f"stratum compare: render failed: {message}", file=sys.stderr, flush=True)
            failures.append(message)
            continue
        print(DONE_PREFIX + json.dumps({"key": entry["key"], "label": entry["label"],
                                        "seconds": timings.get("seconds")}), flush=True)
    if failures:
        raise RuntimeError(f"{len(failures)} of {len(payload['configs'])} renders failed; "
                           f"first: {failures[0]}")


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return f"{type(exc).__name__}: {text.splitlines()[0] if text else ''}"


def _render_entry(out_dir: Path, entry: dict[str, Any], render_fn: RenderFn) -> dict[str, Any]:
    exr = out_dir / entry["exr"]
    exr.parent.mkdir(parents=True, exist_ok=True)
    tmp = _tmp_name(exr)
    try:
        timings = render_fn(entry, tmp)
        if not tmp.is_file():
            raise RuntimeError("the render wrote no image")
        os.replace(tmp, exr)
    finally:
        if tmp.exists():
            tmp.unlink()
    sidecar = {"key": entry["key"], "settings": entry, "exr": entry["exr"],
               "exr_size": exr.stat().st_size, "exr_sha256": _sha256(exr), **timings}
    write_json_atomic(out_dir / entry["sidecar"], sidecar)
    return timings


def _setup_blender(payload: dict[str, Any]) -> tuple[Any, Any]:
    """Registers the add-on from the checkout; returns (bpy, scene)."""
    sys.path.insert(0, payload["addon_parent"])
    import bpy

    import stratum

    stratum.register()
    return bpy, bpy.context.scene


def _render_size(scene: Any) -> list[int]:
    r = scene.render
    scale = r.resolution_percentage / 100.0
    return [max(int(r.resolution_x * scale), 1), max(int(r.resolution_y * scale), 1)]


def set_estimator_settings(props: Any, settings: dict[str, Any]) -> None:
    """Sets every estimator setting on scene.stratum (`props`). Raises, naming it, when the
    add-on has no property for one."""
    for name, value in settings.items():
        if not hasattr(props, name):
            raise RuntimeError(f"scene.stratum has no property {name!r} (needed for "
                               f"{name}={value!r}): the add-on predates this setting")
        setattr(props, name, value)


def _probe(payload: dict[str, Any]) -> None:
    bpy, scene = _setup_blender(payload)
    from stratum.compare.estimators import SETTING_NAMES

    s = scene.stratum
    info = {"resolution": _render_size(scene), "integrator": str(s.integrator),
            "hemisphere": str(s.hemisphere), "max_bounces": int(s.max_bounces),
            "sampler": str(s.sampler), "samples": int(s.samples),
            "estimator_settings": {n: getattr(s, n) for n in SETTING_NAMES if hasattr(s, n)},
            "blender_version": list(bpy.app.version)}
    write_json_atomic(Path(payload["probe_output"]), info)


def _blender_render_fn(payload: dict[str, Any]) -> RenderFn:
    bpy, scene = _setup_blender(payload)
    from stratum import native
    from stratum.engine import StratumRenderEngine
    from stratum.engine_id import ENGINE_ID

    # Remember the native renderer's last progress report: its render_seconds is the path
    # tracing time without export and BVH build.
    last: dict[str, Any] = {}
    original_progress = native.Renderer.progress

    def progress(self: Any) -> Any:
        p = original_progress(self)
        last["progress"] = p
        return p

    native.Renderer.progress = progress  # type: ignore[method-assign]

    scene.render.engine = ENGINE_ID
    scene.render.use_compositing = False
    scene.render.use_sequencer = False
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.color_mode = "RGBA"
    threads = payload.get("threads")
    warmed: set[str] = set()

    def render(entry: dict[str, Any], path: Path) -> dict[str, Any]:
        if entry["sampler"] not in warmed:
            # Untimed: a sampler's one-off set-up (bluenoise builds its texture, ~1-2 s, once
            # per process) would otherwise land on whichever render comes first.
            native.sampler_points(entry["sampler"], 1, 0, 4, 4, (0, 0), (0, 1), 1)
            warmed.add(entry["sampler"])
        s = scene.stratum
        s.sampler = entry["sampler"]
        s.samples = int(entry["samples"])
        s.seed = int(entry["seed"])
        s.integrator = entry["integrator"]
        set_estimator_settings(s, entry["estimator_settings"])
        s.hemisphere = entry["hemisphere"]
        if entry.get("max_bounces") is not None:
            s.max_bounces = int(entry["max_bounces"])
        if threads is not None:
            s.threads = int(threads)
        scene.render.resolution_x, scene.render.resolution_y = entry["resolution"]
        scene.render.resolution_percentage = 100
        last.clear()
        started = time.perf_counter()
        bpy.ops.render.render()
        seconds = time.perf_counter() - started
        errors = [m for level, m in StratumRenderEngine.last_reports if level == "ERROR"]
        if errors:
            raise RuntimeError(f"{entry['label']}: {errors[0]}")
        bpy.data.images["Render Result"].save_render(filepath=str(path), scene=scene)
        trace = last.get("progress")
        return {"seconds": seconds,
                "trace_seconds": float(trace.render_seconds) if trace else seconds,
                # e.g. the renderer's notices (what the estimator cannot render in this scene)
                "warnings": [m for level, m in StratumRenderEngine.last_reports
                             if level == "WARNING"]}

    return render


def main(argv: list[str]) -> int:
    try:
        payload = json.loads(Path(argv[argv.index("--") + 1]).read_text())
        if payload.get("mode") == "probe":
            _probe(payload)
        else:
            run_batch(payload, _blender_render_fn(payload))
        return 0
    except Exception as exc:  # noqa: BLE001 - every failure becomes one message and status 1
        print(f"stratum compare: {_first_line(exc)}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    code = main(sys.argv)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)  # Blender would otherwise go on (or tear down slowly) after the script
