"""The scene camera -> native camera."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import native
from .common import ExportError, matrix_to_array


def convert_camera(scene: Any, depsgraph: Any) -> native.Camera:
    cam_ob = scene.camera
    if cam_ob is None:
        raise ExportError(f"Scene '{scene.name}' has no active camera: add a camera and make "
                          "it active (Scene Properties > Camera)")
    if cam_ob.type != "CAMERA":
        raise ExportError(f"Active camera object '{cam_ob.name}' is not a camera "
                          f"(type {cam_ob.type})")
    ob = cam_ob.evaluated_get(depsgraph) if depsgraph is not None else cam_ob
    cam = ob.data
    if cam.type != "PERSP":
        raise ExportError(f"Camera '{cam_ob.name}': camera type {cam.type} is not supported "
                          "(only perspective, PERSP)")
    m = matrix_to_array(ob.matrix_world).reshape(4, 4).astype(np.float64)
    # Drop object scale: a scaled camera must not change the projection.
    axes = m[:3, :3]
    lengths = np.linalg.norm(axes, axis=0)
    if not np.all(np.isfinite(m)) or np.any(lengths < 1e-12):
        raise ExportError(f"Camera '{cam_ob.name}' has a degenerate transform")
    m[:3, :3] = axes / lengths
    return native.Camera(
        lens_mm=float(cam.lens),
        sensor_width_mm=float(cam.sensor_width),
        sensor_height_mm=float(cam.sensor_height),
        sensor_fit=native.SENSOR_FITS.get(cam.sensor_fit, native.SENSOR_FIT_AUTO),
        shift_x=float(cam.shift_x),
        shift_y=float(cam.shift_y),
        clip_start=float(cam.clip_start),
        clip_end=float(cam.clip_end),
        transform=np.ascontiguousarray(m.astype(np.float32).reshape(16)),
    )
