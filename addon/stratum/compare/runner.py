"""Runs batches of configurations through Blender: locally with --jobs J Blender processes, or
on an existing Dask distributed cluster (--scheduler ADDRESS); shows a plain-text progress bar
on stderr.

Each batch is one `blender -b SCENE --python blender_batch.py -- BATCH.json` process, which
renders its configurations one after the other (start-up paid once per batch) and commits each
EXR + sidecar as it finishes, so an interrupted run keeps what was done.

Dask: each task runs the Blender subprocess on its worker, into a temporary folder of the
worker, and returns the files' bytes (EXR and sidecar); the client writes them into the output
folder (EXR first, sidecar last, each by rename). So the workers need no access to the output
folder. They do need Blender (STRATUM_BLENDER or `blender` on their PATH) and this `stratum`
package importable (the add-on is registered from the worker's copy). The scene is used in
place when the worker sees the same path with the same sha256 (a shared filesystem, as with a
LocalCluster; resources the .blend references by relative path then resolve), otherwise the
client's bytes are written to a temporary .blend on the worker.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any, TextIO

from ..cli.blender_process import (
    ADDON_PARENT,
    NOT_FOUND_MESSAGE,
    background_command,
    blender_executable,
)
from . import blender_batch
from .plan import Config, SceneSettings, batch_entry, sha256_file

BATCH_SCRIPT = Path(__file__).resolve().with_name("blender_batch.py")

EventFn = Callable[[str, dict[str, Any]], None]


class BatchError(Exception):
    """A Blender batch failed; the message is one line."""


def _one_line(text: str) -> str:
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    ours = [ln for ln in lines if ln.startswith("stratum compare:")]
    if ours:
        return ours[-1].removeprefix("stratum compare:").strip()
    return lines[-1] if lines else ""


def run_blender(scene: Path, payload: dict[str, Any], on_event: EventFn | None = None,
                blender: str | None = None) -> None:
    """Runs one Blender process on a batch payload; calls on_event("start"|"done", data) as
    configurations start and finish. Raises BatchError when Blender fails."""
    exe = blender or blender_executable()
    if exe is None:
        raise BatchError(NOT_FOUND_MESSAGE)
    with tempfile.TemporaryDirectory(prefix="stratum-batch-") as tmp:
        payload_path = Path(tmp) / "batch.json"
        payload_path.write_text(json.dumps(payload))
        stderr_path = Path(tmp) / "stderr.txt"
        cmd = background_command(exe, scene, "--python", str(BATCH_SCRIPT), "--",
                                 str(payload_path), audio=False)
        tail: list[str] = []
        with open(stderr_path, "w+") as err:
            proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=err, text=True,
                                    errors="replace")
            assert proc.stdout is not None
            for line in proc.stdout:
                if line.startswith(blender_batch.START_PREFIX):
                    if on_event:
                        on_event("start", json.loads(line[len(blender_batch.START_PREFIX):]))
                elif line.startswith(blender_batch.DONE_PREFIX):
                    if on_event:
                        on_event("done", json.loads(line[len(blender_batch.DONE_PREFIX):]))
                else:
                    tail = (tail + [line])[-20:]
            code = proc.wait()
            err.seek(0)
            stderr = err.read()
    if code != 0:
        reason = _one_line(stderr) or _one_line("".join(tail)) or "no message"
        raise BatchError(f"Blender batch failed (exit code {code}): {reason}")


def make_payload(configs: list[Config], settings: SceneSettings, output_dir: Path,
                 threads: int | None, addon_parent: Path = ADDON_PARENT) -> dict[str, Any]:
    return {"mode": "render", "addon_parent": str(addon_parent), "output_dir": str(output_dir),
            "threads": threads, "configs": [batch_entry(c, settings) for c in configs]}


def probe_scene(scene: Path) -> dict[str, Any]:
    """Opens the scene in Blender and returns its render size and Stratum settings."""
    with tempfile.TemporaryDirectory(prefix="stratum-probe-") as tmp:
        out = Path(tmp) / "probe.json"
        run_blender(scene, {"mode": "probe", "addon_parent": str(ADDON_PARENT),
                            "probe_output": str(out)})
        try:
            return json.loads(out.read_text())
        except (OSError, ValueError) as exc:
            raise BatchError(f"Blender could not read the scene {scene}") from exc


# ---- progress ------------------------------------------------------------------------------


def _clock(seconds: float) -> str:
    s = int(round(seconds))
    if s >= 3600:
        return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}"
    return f"{s // 60}:{s % 60:02d}"


class ProgressBar:
    """`[#####.....] 12/73 configurations  elapsed 0:10  ETA 0:42  now: sobol spp=4 seed=1` on
    stderr. On a terminal the line is redrawn in place; otherwise one line is printed per
    finished configuration (plain text, for logs and CI). The ETA weights the remaining
    configurations by their cost (samples + start-up)."""

    WIDTH = 24

    def __init__(self, configs: list[Config], stream: TextIO | None = None,
                 already_done: int = 0) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.costs = {c.key: c.cost for c in configs}
        self.labels = {c.key: c.label for c in configs}
        self.total_cost = sum(self.costs.values())
        self.done_cost = 0.0
        self.total = len(configs) + already_done
        self.done = already_done
        self.current = ""
        self.started = time.perf_counter()
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self._lock = threading.Lock()
        self._finished: set[str] = set()

    def line(self) -> str:
        fraction = self.done / self.total if self.total else 1.0
        filled = int(round(fraction * self.WIDTH))
        elapsed = time.perf_counter() - self.started
        if self.done_cost > 0 and self.total_cost > self.done_cost:
            eta = _clock(elapsed * (self.total_cost - self.done_cost) / self.done_cost)
        elif self.done >= self.total:
            eta = "0:00"
        else:
            eta = "?"
        text = (f"stratum compare: [{'#' * filled}{'.' * (self.WIDTH - filled)}] "
                f"{self.done}/{self.total} configurations  elapsed {_clock(elapsed)}  ETA {eta}")
        if self.current and self.done < self.total:
            text += f"  now: {self.current}"
        return text

    def _draw(self, final: bool = False) -> None:
        if self.tty:
            self.stream.write("\r\x1b[K" + self.line() + ("\n" if final else ""))
        else:
            self.stream.write(self.line() + "\n")
        self.stream.flush()

    def show(self) -> None:
        with self._lock:
            self._draw()

    def event(self, kind: str, data: dict[str, Any]) -> None:
        key = data.get("key", "")
        with self._lock:
            if kind == "start":
                self.current = self.labels.get(key, data.get("label", ""))
                if self.tty:
                    self._draw()
            elif kind == "done" and key not in self._finished:
                self._finished.add(key)
                self.done += 1
                self.done_cost += self.costs.get(key, 0.0)
                self._draw(final=self.done >= self.total)


# ---- local ---------------------------------------------------------------------------------


def run_local(scene: Path, batches: list[list[Config]], settings: SceneSettings,
              out_dir: Path, jobs: int, threads: int | None, progress: ProgressBar) -> None:
    """Runs the batches with up to `jobs` Blender processes at once; raises the first
    BatchError after every batch has ended (what finished stays committed)."""
    errors: list[BaseException] = []

    def one(batch: list[Config]) -> None:
        try:
            run_blender(scene, make_payload(batch, settings, out_dir, threads), progress.event)
        except BaseException as exc:  # noqa: BLE001 - reported after all batches end
            errors.append(exc)

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        list(pool.map(one, batches))
    if errors:
        raise errors[0]


# ---- Dask ----------------------------------------------------------------------------------


def render_batch_on_worker(scene_path: str, scene_sha256: str, scene_bytes: bytes,
                           payload: dict[str, Any]) -> dict[str, bytes]:
    """A Dask task: renders one batch on this worker, returns {relative path: bytes} of every
    EXR and sidecar (sidecars last)."""
    with tempfile.TemporaryDirectory(prefix="stratum-dask-") as tmp:
        scene = Path(scene_path)
        if not (scene.is_file() and sha256_file(scene) == scene_sha256):
            scene = Path(tmp) / "scene.blend"
            scene.write_bytes(scene_bytes)
        out = Path(tmp) / "out"
        out.mkdir()
        run_blender(scene, dict(payload, output_dir=str(out), addon_parent=str(ADDON_PARENT)))
        files: dict[str, bytes] = {}
        for kind in ("exr", "sidecar"):
            for entry in payload["configs"]:
                files[entry[kind]] = (out / entry[kind]).read_bytes()
        return files


def _write_atomic(path: Path, data: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".tmp-{os.getpid()}-{path.name}")
    tmp.write_bytes(data)
    os.replace(tmp, path)


def run_dask(scene: Path, batches: list[list[Config]], settings: SceneSettings,
             out_dir: Path, client: Any, threads: int | None, progress: ProgressBar) -> None:
    """Sends the batches to a Dask cluster; writes what each returns as it completes."""
    from distributed import as_completed

    scene_bytes = client.scatter(scene.read_bytes(), broadcast=True)
    futures = {}
    for batch in batches:
        payload = make_payload(batch, settings, Path("."), threads)
        future = client.submit(render_batch_on_worker, str(scene.resolve()),
                               settings.scene_sha256, scene_bytes, payload, pure=False)
        futures[future] = batch
    errors: list[BaseException] = []
    for future in as_completed(list(futures)):
        batch = futures[future]
        try:
            files = future.result()
        except Exception as exc:  # noqa: BLE001 - reported after all batches end
            errors.append(exc if isinstance(exc, BatchError) else BatchError(
                f"Dask task failed: {type(exc).__name__}: {_one_line(str(exc))}"))
            continue
        for config in batch:  # EXR before sidecar: the sidecar marks the configuration done
            _write_atomic(out_dir / config.exr, files[config.exr])
            _write_atomic(out_dir / config.sidecar, files[config.sidecar])
            progress.event("done", {"key": config.key})
    if errors:
        raise errors[0]


def remove_stale_temporaries(out_dir: Path) -> None:
    """Deletes temporary files a crashed run left (never trusted, only clutter)."""
    for folder in (out_dir, out_dir / "renders", out_dir / "renders" / "reference_parts"):
        if folder.is_dir():
            for path in folder.glob(".tmp-*"):
                if path.is_file():
                    path.unlink(missing_ok=True)
                else:
                    shutil.rmtree(path, ignore_errors=True)
