"""One frame's samples over the workers of a Dask cluster (`stratum render --scheduler`).

The client captures the scene once (a native scene file, `stratum_scene_save`: through Blender
for a .blend, see `export_blend`), sends its bytes and the render settings to every worker, and
gives each worker a disjoint range of the frame's sample indices (the `sample_offset` and
`sample_count` settings; the sampler's sequence stays that of `samples`, since samplers are pure
functions of pixel, index, dimension and seed). Each worker returns the exact fixed-point sums of
its range (`Renderer.read_sums`); the client adds them in range order into one renderer
(`Renderer.add_sums`) and writes its image. Film sums are exact integers (native film/film.h),
so the merged image is bit-identical to one render of all the samples on one machine, for every
sampler and integrator, whatever the number of workers.

Without bpy; Dask (`distributed`) is imported only when a cluster is used.
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .. import native
from .blender_process import overrides_from_options, script_command

# Seconds a client waits for the scheduler before reporting it unreachable.
CONNECT_TIMEOUT = 20


class DistributedError(Exception):
    """A distributed render that cannot go on; the message says why, for the command line."""


@dataclass(frozen=True)
class Frame:
    """What every worker needs: the scene file's bytes and the render settings."""
    scene_file: bytes
    settings: dict[str, int | float | str]


@dataclass(frozen=True)
class RangeResult:
    offset: int
    count: int
    sums: bytes
    notices: tuple[str, ...]


def split_samples(samples: int, parts: int) -> list[tuple[int, int]]:
    """[offset, count) ranges covering 0..samples in order, as even as integers allow (the
    first ones one longer); fewer than `parts` when there are fewer samples."""
    if samples < 1 or parts < 1:
        raise ValueError(f"cannot split {samples} samples into {parts} parts")
    parts = min(parts, samples)
    base, extra = divmod(samples, parts)
    ranges, offset = [], 0
    for k in range(parts):
        count = base + (1 if k < extra else 0)
        ranges.append((offset, count))
        offset += count
    return ranges


def render_range(frame: Frame, offset: int, count: int) -> RangeResult:
    """Renders sample indices [offset, offset + count) of the frame (on a worker) and returns
    their exact sums."""
    with tempfile.TemporaryDirectory(prefix="stratum-worker-") as tmp:
        path = Path(tmp) / "scene.stratum"
        path.write_bytes(frame.scene_file)
        scene = native.Scene.load(path)
    with scene, native.Renderer(scene) as renderer:
        for name, value in frame.settings.items():
            renderer.set(name, value)
        renderer.set("sample_offset", offset)
        renderer.set("sample_count", count)
        renderer.start()
        while not renderer.wait(1000):
            pass
        progress = renderer.progress()  # raises the render thread's failure, if any
        if progress.cancelled:
            raise DistributedError(f"the render of samples [{offset}, {offset + count}) was "
                                   "cancelled")
        return RangeResult(offset, count, renderer.read_sums(), tuple(renderer.notices()))


def merge(frame: Frame, results: Sequence[RangeResult]) -> native.Renderer:
    """A renderer holding the sums of all ranges, added in offset order (any order gives the
    same bits; a fixed one keeps the check of adjacent ranges simple). The caller closes it."""
    with tempfile.TemporaryDirectory(prefix="stratum-client-") as tmp:
        path = Path(tmp) / "scene.stratum"
        path.write_bytes(frame.scene_file)
        scene = native.Scene.load(path)
    with scene:
        renderer = native.Renderer(scene)
    try:
        for name, value in frame.settings.items():
            renderer.set(name, value)
        for result in sorted(results, key=lambda r: r.offset):
            renderer.add_sums(result.sums)
    except BaseException:
        renderer.close()
        raise
    return renderer


def connect(address: str) -> tuple[Any, Any]:
    """(client, cluster) for `address`: a scheduler's address ("tcp://host:8786"), or
    "local:N" for a LocalCluster of N worker processes on this machine (cluster is then the
    LocalCluster to close, else None). Raises DistributedError when it cannot connect."""
    from distributed import Client, LocalCluster

    if address.startswith("local:"):
        try:
            workers = int(address.split(":", 1)[1])
        except ValueError:
            workers = 0
        if workers < 1:
            raise DistributedError(f"--scheduler {address!r}: expected local:N with N >= 1")
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        return Client(cluster), cluster
    try:
        return Client(address, timeout=CONNECT_TIMEOUT), None
    except (OSError, TimeoutError) as exc:
        raise DistributedError(f"cannot reach the Dask scheduler at {address!r}: {exc}") from exc


def render_on_cluster(client: Any, frame: Frame) -> tuple[native.Renderer, list[str]]:
    """Renders the frame's samples split over the client's workers (one range each, pinned to
    it while it lives); returns the merged renderer and the workers' notices (once each)."""
    if int(frame.settings.get("use_adaptive_sampling", 0)):
        raise DistributedError("adaptive sampling (use_adaptive_sampling) stops each pixel on its "
                               "whole sample sequence, which no worker of a split frame holds: "
                               "render on one machine, or with use_adaptive_sampling=0")
    workers = sorted(client.scheduler_info().get("workers", {}))
    if not workers:
        raise DistributedError("the Dask cluster has no workers")
    samples = int(frame.settings.get("samples", 16))
    ranges = split_samples(samples, len(workers))
    # A key of its own (hash=False): a key derived from the content is shared with an earlier
    # render of the same frame, whose release could then drop this one's data ("lost
    # dependencies").
    scattered = client.scatter(frame, broadcast=True, hash=False)
    futures = [client.submit(render_range, scattered, offset, count, pure=False,
                             workers=[worker], allow_other_workers=True)
               for (offset, count), worker in zip(ranges, workers, strict=False)]
    results = []
    for (offset, count), future in zip(ranges, futures, strict=True):
        try:
            results.append(future.result())
        except native.StratumError as exc:
            raise DistributedError(f"a worker failed rendering samples [{offset}, "
                                   f"{offset + count}): {exc}") from exc
        except Exception as exc:  # noqa: BLE001 - any remote failure ends the render, named
            raise DistributedError(f"a worker failed rendering samples [{offset}, "
                                   f"{offset + count}): {type(exc).__name__}: {exc}") from exc
    notices = list(dict.fromkeys(n for r in results for n in r.notices))
    return merge(frame, results), notices


# Runs inside Blender after blender_process's shared start (arguments, add-on, settings):
# captures the evaluated scene as a native scene file and the settings the add-on would render
# it with (engine/frame.py renderer_settings), as JSON.
_EXPORT_SCRIPT = r"""
from stratum import native
from stratum.engine.frame import renderer_settings
from stratum.export.sync import export_scene
from stratum.export.render_geometry import use_render_geometry
use_render_geometry(scene)
depsgraph = bpy.context.evaluated_depsgraph_get()
with native.Scene() as captured:
    summary = export_scene(depsgraph, captured)
    for warning in summary.warnings:
        print(f"stratum: warning: {warning}", file=sys.stderr)
    captured.save(args["scene_file"])
with open(args["settings_file"], "w") as f:
    json.dump(renderer_settings(scene), f)
code = 0
"""


def export_blend(blender: str, blend: Path, overrides: dict[str, int | str],
                 resolution: tuple[int, int] | None) -> Frame:
    """Captures `blend` through Blender in the background (the add-on's own export and
    settings, with `overrides` of scene.stratum properties)."""
    with tempfile.TemporaryDirectory(prefix="stratum-export-") as tmp:
        scene_file, settings_file = Path(tmp) / "scene.stratum", Path(tmp) / "settings.json"
        cmd = script_command(blender, blend, _EXPORT_SCRIPT, overrides, resolution,
                             scene_file=str(scene_file), settings_file=str(settings_file))
        proc = subprocess.run(cmd, check=False, env=os.environ.copy())
        if proc.returncode != 0 or not scene_file.is_file():
            raise DistributedError(f"exporting {blend} through Blender failed "
                                   f"(exit code {proc.returncode})")
        return Frame(scene_file.read_bytes(), json.loads(settings_file.read_text()))


def command_line_render(ns: Any, blender: str, blend: Path, output: Path) -> int:
    """`stratum render BLEND --scheduler ADDRESS`: export, render on the cluster, write
    `output`; an exit code, the failure named on stderr."""
    import sys

    overrides = overrides_from_options(ns)
    client = cluster = None
    try:
        # The scheduler first: an unreachable one is reported before Blender runs.
        client, cluster = connect(ns.scheduler)
        frame = export_blend(blender, blend, overrides, ns.resolution)
        renderer, notices = render_on_cluster(client, frame)
        with renderer:
            renderer.write_image(output)
        for notice in notices:
            print(f"stratum: warning: {notice}", file=sys.stderr)
    except (DistributedError, native.StratumError) as exc:
        print(f"stratum: {exc}", file=sys.stderr)
        return 1
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    print(f"stratum: wrote {output} ({frame.settings.get('samples')} samples over "
          f"{ns.scheduler})")
    return 0
