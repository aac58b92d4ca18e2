"""The many-light scene of issue 16 (scenes/many_lights_hall.blend, built by
scenes/make_many_lights_hall.py) holds what the study needs and opens in both Blenders; the
status line shows the light tree's build time and memory once a render has built it
(tests/python/test_light_tree_stats.py checks the native figures)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

bpy = pytest.importorskip("bpy")

REPO = Path(__file__).resolve().parents[2]
HALL = REPO / "scenes" / "many_lights_hall.blend"


def test_hall_has_a_thousand_small_varied_lamps() -> None:
    bpy.ops.wm.open_mainfile(filepath=str(HALL), load_ui=False)
    lamps = [o for o in bpy.data.objects if o.type == "LIGHT"]
    assert len(lamps) == 1000
    assert {o.data.type for o in lamps} == {"POINT"}
    radii = [o.data.shadow_soft_size for o in lamps]
    powers = [o.data.energy for o in lamps]
    assert 0.02 - 1e-6 <= min(radii) and max(radii) <= 0.05 + 1e-6
    # Powers over a factor 50 and several colours: power and uniform selection differ.
    assert max(powers) / min(powers) == pytest.approx(50.0, rel=1e-4)
    assert len({tuple(round(c, 3) for c in o.data.color) for o in lamps}) >= 5
    # Invisible to the camera (no single-pixel discs in error measures), seen by other rays.
    assert not any(o.visible_camera for o in lamps)
    assert all(o.visible_diffuse and o.visible_glossy for o in lamps)
    assert bpy.context.scene.camera is not None
    assert sum(1 for o in bpy.data.objects if o.name.startswith("Column")) == 12
    # Shared light datablocks keep the file small.
    assert len(bpy.data.lights) <= 7 * 8
    assert HALL.stat().st_size < 400_000


def test_stats_line_shows_the_light_tree(stratum_addon: Any) -> None:
    from stratum import native
    from stratum.engine.final_render import format_stats

    fields: dict[str, Any] = {
        "done": False, "cancelled": False, "samples_done": 4, "samples_total": 16,
        "update_serial": 1, "rays": 1e6, "build_seconds": 0.1, "render_seconds": 1.0,
        "fraction_done": 0.25, "samples_in_progress": 8, "samples_average": 4.0}
    without = format_stats(native.Progress(**fields), 2.0)
    assert "Light tree" not in without
    with_tree = format_stats(native.Progress(**fields, counters={"light_tree.seconds": 0.0123,
                                                                 "light_tree.bytes": 172_000.0}),
                             2.0)
    assert with_tree == without + " | Light tree 12 ms, 0.17 MB"
