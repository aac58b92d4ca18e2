"""Scene export: evaluated depsgraph -> native.Scene, numpy arrays only.

    summary = export_scene(depsgraph, native_scene, should_stop, frame_set)

exports a whole scene into a native scene the caller owns: SceneSync.full (sync.py), which
also keeps a native scene in step with later changes of the depsgraph (SceneSync.update).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .common import ExportCancelled, ExportError, ExportSummary
from .materials import convert_material
from .meshes import mesh_arrays
from .sync import SceneSync, UpdateResult
from .updates import IdUpdate, collect_updates

__all__ = [
    "ExportCancelled",
    "ExportError",
    "ExportSummary",
    "IdUpdate",
    "SceneSync",
    "UpdateResult",
    "collect_updates",
    "convert_material",
    "export_scene",
    "mesh_arrays",
]


def export_scene(
    depsgraph: Any,
    scene: Any,
    should_stop: Callable[[], bool] | None = None,
    frame_set: Callable[[int, float], None] | None = None,
) -> ExportSummary:
    """Exports the evaluated scene of `depsgraph` into `scene` (a native.Scene, or a stand-in
    with its methods): SceneSync.full, whose docstring says what is raised and reported."""
    return SceneSync(lambda: scene).full(depsgraph, should_stop, frame_set)
