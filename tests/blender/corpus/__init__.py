"""The hostile-scene corpus (issue 12, point 5): small malformed Blender scenes, each rendered by
Stratum in a worker subprocess of Blender 3.4 and of the bpy wheel, so that a crash fails one
case instead of killing the run.

    case.py       Case and Expect: what a case builds and what its outcome must be (no bpy)
    stage.py      the scene a case builds on, with bpy.data only (both Blender generations)
    cases_*.py    the cases, by area
    worker.py     runs inside Blender: builds, renders, checks, writes one JSON line per case
    runner.py     runs workers (no bpy): restarts after a crash, kills a hung case
    table.py      the outcome table (case -> outcome -> message) as Markdown and JSON
    replay.py     renders captured scenes with a stratum-native binary (the ASan run)
    test_corpus.py  one pytest test per (case, Blender)
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .case import Case

AREAS = ("geometry", "objects", "materials", "images", "lights", "camera", "settings", "world")


def all_cases() -> dict[str, Case]:
    """Every case by name, in area order (imports the case modules, which need bpy)."""
    from .case import CASES

    for area in AREAS:
        importlib.import_module(f"{__name__}.cases_{area}")
    return dict(CASES)
