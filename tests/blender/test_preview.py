"""Material, light and world thumbnails rendered by Stratum (issue 14, acceptance 6):
engine/preview.py through Blender's own preview job in both Blenders.

How the preview is triggered: bpy.ops.ed.lib_id_generate_preview (tests/blender/preview_job.py)
starts Blender's preview job, which renders the preview scene through the engine's render()
with is_preview. The bpy 5.0 wheel runs it in background mode (the job thread renders; the
test waits for the pixels). Blender 3.4 in background mode crashes in the job thread after
render() returns, whatever the engine (a render() that does nothing crashes the same way), so
there the test runs Blender 3.4 with its UI under Xvfb, where the job ends as in a user's
session.

The CPU bound is the acceptance's: under 2 s of CPU for a thumbnail. It is measured as the
process CPU time (time.process_time: every thread, so the native render threads too) of the
render() call: export, BVH build and path tracing. Under Xvfb it also counts what Blender's UI
thread does meanwhile, so it is an upper bound there. Measured here: 0.7 s (wheel) and 1.1 s
(3.4 under Xvfb) on 2 shared cores.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest

bpy = pytest.importorskip("bpy")

HERE = Path(__file__).resolve().parent
CPU_BOUND_SECONDS = 2.0
ICON_SIZE = [128, 128]  # ICON_SIZE_PREVIEW, what lib_id_generate_preview renders


def test_preview_samples_spend_a_fixed_budget_of_pixel_samples(stratum_addon: Any) -> None:
    from stratum.engine.preview import (
        MAX_SAMPLES,
        MIN_SAMPLES,
        PIXEL_SAMPLE_BUDGET,
        preview_samples,
    )

    assert preview_samples(128, 128) == 16
    assert preview_samples(256, 256) == 4
    assert preview_samples(32, 32) == MAX_SAMPLES  # an icon does not take 256 samples
    assert preview_samples(2000, 1000) == MIN_SAMPLES  # a huge panel still gets one
    for w, h in ((128, 128), (200, 150), (360, 360)):
        assert w * h * preview_samples(w, h) <= PIXEL_SAMPLE_BUDGET


def test_preview_settings_are_the_frames_with_fewer_samples_and_bounces(
        scene_builder: Any) -> None:
    from stratum.engine.frame import renderer_settings
    from stratum.engine.preview import MAX_BOUNCES, preview_settings

    b = scene_builder().basic()
    b.set_resolution(128, 128)
    b.scene.stratum.samples = 1024
    b.scene.stratum.max_bounces = 12
    settings = preview_settings(b.scene)
    assert settings["samples"] == 16 and settings["max_bounces"] == MAX_BOUNCES
    frame = renderer_settings(b.scene)
    assert {k: v for k, v in settings.items() if k not in ("samples", "max_bounces")} == \
        {k: v for k, v in frame.items() if k not in ("samples", "max_bounces")}
    b.scene.stratum.max_bounces = 2
    assert preview_settings(b.scene)["max_bounces"] == 2


def _thumbnails(tmp_path: Path) -> dict[str, Any]:
    if bpy.app.version >= (4, 0, 0):
        import preview_job

        return preview_job.run_waiting()
    xvfb = shutil.which("xvfb-run")
    if xvfb is None:
        pytest.skip("Blender 3.4 renders previews only with its UI, and xvfb-run is missing")
    out = tmp_path / "thumbnails.json"
    command = [xvfb, "-a", "-s", "-screen 0 1280x800x24", bpy.app.binary_path,
               "--factory-startup", "-noaudio", "--python", str(HERE / "preview_job.py"),
               "--", str(out)]
    done = subprocess.run(command, check=False, capture_output=True, text=True, timeout=300)
    assert out.is_file(), f"exit {done.returncode}\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return json.loads(out.read_text())


def test_thumbnails_render_through_blenders_preview_job(library: Any, tmp_path: Path) -> None:
    results = _thumbnails(tmp_path)
    for kind in ("material", "light", "world"):
        r = results[kind]
        assert r["render"] is not None, f"{kind}: Stratum's render() was not called"
        assert r["render"]["size"] == ICON_SIZE and r["image_size"] == ICON_SIZE, r
        assert max(r["mean_rgba"][:3]) > 0.05, f"{kind}: black preview {r}"
        # What the preview scene cannot show is kept out of the F12 reports.
        for report in r["render"]["reports"]:
            assert report not in r["render"]["engine_reports"], r["render"]
    material = results["material"]
    assert material["render"]["cpu_seconds"] < CPU_BOUND_SECONDS, material
    # The shape in the middle wears the red material (display-referred 8-bit values: the
    # preview image is what Blender shows).
    red, green, blue = material["centre_rgb"]
    assert red > 1.5 * green and red > 1.5 * blue, material
    # The world preview is the blue world.
    red, green, blue = results["world"]["centre_rgb"]
    assert blue > 1.5 * red and blue > green, results["world"]
