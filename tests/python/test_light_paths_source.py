"""Where a scene's Light Paths settings come from (blender_settings.light_paths_from_cycles): the
rule of LIGHT_PATHS_SOURCES, without Blender. The same rule on real scenes, and Cycles' values
reaching the library, are tests/blender/test_light_path_settings.py."""

from __future__ import annotations

import pytest
from stratum import blender_settings
from stratum.blender_settings import light_paths_from_cycles


@pytest.mark.parametrize(("source", "available", "tuned", "cycles"), [
    ("AUTO", True, True, True),     # a file tuned for Cycles renders as in Cycles
    ("AUTO", True, False, False),   # a new or untouched scene renders unbiased
    ("AUTO", False, False, False),  # no Cycles add-on: nothing to read
    ("STRATUM", True, True, False),
    ("CYCLES", True, False, True),  # Cycles' defaults, clamping included
    ("CYCLES", False, False, False),
])
def test_the_source_rule(source: str, available: bool, tuned: bool, cycles: bool) -> None:
    assert light_paths_from_cycles(source, available, tuned) is cycles


def test_every_cycles_light_path_setting_is_a_stratum_property() -> None:
    # Switching the source swaps values, never which settings are sent.
    assert set(blender_settings.CYCLES_LIGHT_PATHS) <= set(blender_settings.PROPERTIES)
    assert blender_settings.LIGHT_PATHS_DEFAULT in {s[0] for s in blender_settings.LIGHT_PATHS_SOURCES}
