"""Long sessions (issue 12, point 8): 200 consecutive renders of the Cornell box in one Blender
process keep its resident memory flat.

Runs in both Blenders, each in a fresh process (`make test-sessions`; tests/blender/conftest.py
keeps this folder out of the general in-Blender runs, whose earlier tests would blur the
baseline). VmRSS is read from /proc/self/status after every render. The first WARM_UP renders
fill Blender's and Stratum's lazily built state (render result buffers, the OCIO processor,
Python's allocator pools); the growth is then the median of the last 10 readings over the
median of the 10 readings after the warm-up, so one transient allocation at either end does not
decide it. The bound, 1 %, is the issue's.
"""

from __future__ import annotations

import statistics
from pathlib import Path
from typing import Any

import bpy

from conftest import REPO, engine_reports

CORNELL = REPO / "scenes" / "cornell_box.blend"
RENDERS = 200
WARM_UP = 20
WINDOW = 10
MAX_GROWTH = 0.01


def _rss_kib() -> int:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    raise RuntimeError("VmRSS not in /proc/self/status")


def test_200_renders_keep_resident_memory_flat(library: Any) -> None:
    bpy.ops.wm.open_mainfile(filepath=str(CORNELL))
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = 32, 32, 100
    scene.stratum.samples = 1
    rss: list[int] = []
    for _ in range(RENDERS):
        bpy.ops.render.render()
        errors = engine_reports("ERROR")
        assert not errors, errors
        rss.append(_rss_kib())
    before = statistics.median(rss[WARM_UP:WARM_UP + WINDOW])
    after = statistics.median(rss[-WINDOW:])
    growth = (after - before) / before
    print(f"\nRSS over {RENDERS} renders ({bpy.app.version_string}): first {rss[0]} KiB, after "
          f"warm-up {before:.0f} KiB, last {after:.0f} KiB, growth {100 * growth:+.3f} %, "
          f"max {max(rss)} KiB")
    assert growth < MAX_GROWTH, (f"RSS grew {100 * growth:.2f} % over {RENDERS - WARM_UP} "
                                 f"renders after warm-up: {rss}")
