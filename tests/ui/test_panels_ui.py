"""Stratum's render-properties panels in Blender 3.4's real UI (issue 16, acceptance 5): Blender
draws the Sampling and Light Paths panels and their subpanels with its own layouts, without an
error, and adaptive sampling's switch changes what they show. What each panel draws, and what
greys out when, is checked in both Blenders by tests/blender/test_render_panels.py; the
screenshots out/ui/render_panels/*.png are for a reviewer's eye.
"""

from __future__ import annotations

from typing import Any

import pytest
from conftest import OUT, REPO, run_scenario

CORNELL = REPO / "scenes" / "cornell_box.blend"
OPENED = ("STRATUM_RENDER_PT_sampling", "STRATUM_RENDER_PT_sampling_viewport",
          "STRATUM_RENDER_PT_sampling_viewport_split",
          "STRATUM_RENDER_PT_sampling_viewport_split.header",
          "STRATUM_RENDER_PT_sampling_render", "STRATUM_RENDER_PT_sampling_denoising",
          "STRATUM_RENDER_PT_sampling_advanced", "STRATUM_RENDER_PT_sampling_lights",
          "STRATUM_RENDER_PT_light_paths", "STRATUM_RENDER_PT_light_paths_max_bounces",
          "STRATUM_RENDER_PT_light_paths_clamping", "STRATUM_RENDER_PT_light_paths_caustics",
          "STRATUM_RENDER_PT_light_paths_roulette",
          "STRATUM_RENDER_PT_light_paths_direct_light",
          "STRATUM_RENDER_PT_light_paths_control_variate")


@pytest.fixture(scope="module")
def panels() -> dict[str, Any]:
    return run_scenario("scenario_render_panels.py", CORNELL, "render_panels",
                        screen=(1280, 1400))


def test_blender_draws_every_opened_panel_without_an_error(panels: dict[str, Any]) -> None:
    assert not panels.get("draw_errors"), panels["draw_errors"]
    assert set(OPENED) <= set(panels["drawn"]), panels["drawn"]
    log = (OUT / "render_panels" / "blender.log").read_text(errors="replace")
    assert "Traceback" not in log, log


def test_the_adaptive_switch_and_the_integrator_change_the_panels(
        panels: dict[str, Any]) -> None:
    """The greyed threshold and Min Samples, and Samples read Max Samples, when adaptive
    sampling is switched on; Light Paths greys out for ambient occlusion."""
    assert panels["on"] != panels["off"], panels
    assert panels["ao"] != panels["on"], panels


def test_screenshots_are_kept(panels: dict[str, Any]) -> None:
    out = OUT / "render_panels"
    for name in ("adaptive_off", "adaptive_on", "ambient_occlusion"):
        assert (out / f"{name}.png").stat().st_size > 0, name
