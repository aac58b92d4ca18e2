"""The radiosity integrator through the add-on (issue 17): the bundled Cornell box renders with
it from Blender (its settings reach the library from scene.stratum), its non-diffuse materials
are named once in a warning, and the status line reports the solve's patches, memory, time and
iterations."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest

from conftest import REPO, engine_reports
from exr_file import read_image

CORNELL = REPO / "scenes" / "cornell_box.blend"


def test_stats_line_shows_the_radiosity_solve(stratum_addon: Any) -> None:
    from stratum import native
    from stratum.engine.final_render import format_stats

    fields: dict[str, Any] = {
        "done": False, "cancelled": False, "samples_done": 4, "samples_total": 16,
        "update_serial": 1, "rays": 1e6, "build_seconds": 0.1, "render_seconds": 1.0,
        "fraction_done": 0.25, "samples_in_progress": 8, "samples_average": 4.0}
    without = format_stats(native.Progress(**fields), 2.0)
    assert "Radiosity" not in without
    solved = format_stats(native.Progress(**fields, counters={
        "radiosity.patches": 17496.0, "radiosity.bytes": 36.2e6, "radiosity.seconds": 1.234,
        "radiosity.iterations": 9.0}), 2.0)
    assert solved == without + " | Radiosity 17496 patches, 36.2 MB, 1.23 s, 9 iterations"


def test_cornell_box_renders_with_radiosity(library: Any, stratum_addon: Any,
                                            tmp_path: Path) -> None:
    if not CORNELL.is_file():
        pytest.skip(f"{CORNELL} does not exist yet")
    bpy.ops.wm.open_mainfile(filepath=str(CORNELL))
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    scene.render.resolution_x = scene.render.resolution_y = 16
    scene.render.resolution_percentage = 100
    s = scene.stratum
    s.samples = 4
    s.integrator = "radiosity"
    s.radiosity_patch_size = 0.5
    s.radiosity_solver = "gauss_seidel"
    s.radiosity_tolerance = 1e-4
    s.radiosity_rays = 64
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.filepath = str(tmp_path / "radiosity.exr")
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    assert not engine_reports("ERROR"), engine_reports("ERROR")
    pixels = read_image(tmp_path / "radiosity.exr")
    assert pixels.shape[:2] == (16, 16)
    assert np.isfinite(pixels).all()
    assert pixels[..., :3].mean() > 0.0
    # The box's Principled materials are rendered by their diffuse albedo: one warning says so.
    approximated = [m for m in engine_reports("WARNING") if "radiosity treats every surface" in m]
    assert len(approximated) == 1, engine_reports("WARNING")
    assert "principled" in approximated[0]
