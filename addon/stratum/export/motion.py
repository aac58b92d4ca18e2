"""Motion blur: object transforms at shutter open and close.

Cycles (blender/sync.cpp, BlenderSync::sync_motion) re-evaluates the scene at the shutter's
ends with RenderEngine.frame_set and keeps, per object, the transforms there. The shutter spans
motion_blur_shutter frames around the current frame, placed by the motion blur position
(3.x: scene.cycles.motion_blur_position, 4.x+: scene.render.motion_blur_position; default
CENTER): START [f, f + s], CENTER [f - s/2, f + s/2], END [f - s, f].
Only instances whose transform differs between the two ends are sent as moving. A shutter that
is NaN, or reaches beyond Blender's frame range (RNA keeps 1e30), renders without motion blur,
with a warning.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .common import instance_matrices

MAXFRAME = 1048574  # Blender's largest frame number (DNA_scene_types.h MAXFRAME)


def instance_key(instance: Any, ob: Any) -> tuple[Any, ...]:
    """Identifies one object instance across depsgraph evaluations."""
    if instance.is_instance:
        parent = instance.parent
        return (parent.name if parent is not None else "", ob.name,
                tuple(instance.persistent_id))
    return (ob.name,)


def shutter_settings(bl_scene: Any) -> tuple[bool, float, str]:
    """(motion blur on, shutter in frames, position) of a scene."""
    render = bl_scene.render
    position = getattr(render, "motion_blur_position", None)
    if position is None:
        position = getattr(getattr(bl_scene, "cycles", None), "motion_blur_position", "CENTER")
    return bool(render.use_motion_blur), float(render.motion_blur_shutter), str(position)


def shutter_interval(bl_scene: Any) -> tuple[float, float]:
    frame = float(bl_scene.frame_current) + float(getattr(bl_scene, "frame_subframe", 0.0))
    _, shutter, position = shutter_settings(bl_scene)
    shutter = max(shutter, 0.0)
    if position == "START":
        return frame, frame + shutter
    if position == "END":
        return frame - shutter, frame
    return frame - 0.5 * shutter, frame + 0.5 * shutter


def _transforms(depsgraph: Any) -> dict[tuple[Any, ...], np.ndarray]:
    keys: list[tuple[tuple[Any, ...], int]] = []
    index = -1
    for index, instance in enumerate(depsgraph.object_instances):
        ob = instance.object
        if ob is not None and ob.type not in {"LIGHT", "CAMERA"}:
            keys.append((instance_key(instance, ob), index))
    matrices = instance_matrices(depsgraph, index + 1)
    return {key: matrices[row] for key, row in keys}


def _split(frame: float) -> tuple[int, float]:
    whole = math.floor(frame)
    return int(whole), frame - whole


def shutter_transforms(depsgraph: Any, bl_scene: Any,
                       frame_set: Callable[[int, float], None] | None,
                       warn: Callable[[str], None]
                       ) -> dict[tuple[Any, ...], tuple[np.ndarray, np.ndarray]] | None:
    """{instance key: (transform at open, transform at close)} of the instances that move over
    the shutter, or None without motion blur. Leaves the depsgraph at the current frame."""
    shutter = float(bl_scene.render.motion_blur_shutter)
    if not bl_scene.render.use_motion_blur or shutter <= 0.0:
        return None
    if not all(math.isfinite(t) and abs(t) <= MAXFRAME for t in shutter_interval(bl_scene)):
        warn(f"Scene '{bl_scene.name}': motion blur shutter = {shutter:g} frames is not a frame "
             "interval Blender can evaluate; rendered without motion blur")
        return None
    if frame_set is None:
        original = getattr(bl_scene, "original", bl_scene)

        def frame_set(frame: int, subframe: float) -> None:
            original.frame_set(frame, subframe=subframe)

    current = (int(bl_scene.frame_current), float(getattr(bl_scene, "frame_subframe", 0.0)))
    open_time, close_time = shutter_interval(bl_scene)
    try:
        frame_set(*_split(open_time))
        at_open = _transforms(depsgraph)
        frame_set(*_split(close_time))
        at_close = _transforms(depsgraph)
    finally:
        frame_set(*current)
    moving: dict[tuple[Any, ...], tuple[np.ndarray, np.ndarray]] = {}
    for key, start in at_open.items():
        end = at_close.get(key)
        if end is not None and not np.array_equal(start, end):
            moving[key] = (start, end)
    return moving
