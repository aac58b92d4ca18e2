"""The scene camera -> native camera."""

from __future__ import annotations

from typing import Any

import bpy
import numpy as np

from .. import native
from .common import ExportError, matrix_to_array


def _panorama(cam: Any, name: str) -> dict[str, Any]:
    """Equirectangular panorama ranges: Cycles 3.x keeps them in camera.cycles, 4.x+ on the
    camera itself. Other panorama types are an error naming the type."""
    source = cam.cycles if bpy.app.version < (4, 0, 0) and hasattr(cam, "cycles") else cam
    kind = getattr(source, "panorama_type", "")
    if kind != "EQUIRECTANGULAR":
        raise ExportError(f"Camera '{name}': camera type PANO with panorama type {kind} is not "
                          "supported (only EQUIRECTANGULAR, perspective and orthographic)")
    return {
        "type": native.CAMERA_EQUIRECTANGULAR,
        "latitude_min": float(source.latitude_min),
        "latitude_max": float(source.latitude_max),
        "longitude_min": float(source.longitude_min),
        "longitude_max": float(source.longitude_max),
    }


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
    if cam.type == "PANO":
        kind = _panorama(cam, cam_ob.name)
    elif cam.type in native.CAMERA_TYPES:
        kind = {"type": native.CAMERA_TYPES[cam.type]}
    else:
        raise ExportError(f"Camera '{cam_ob.name}': camera type {cam.type} is not supported "
                          "(only perspective, orthographic and equirectangular panorama)")

    m = matrix_to_array(ob.matrix_world).reshape(4, 4).astype(np.float64)
    # Drop object scale: a scaled camera must not change the projection.
    axes = m[:3, :3]
    lengths = np.linalg.norm(axes, axis=0)
    if not np.all(np.isfinite(m)) or np.any(lengths < 1e-12):
        raise ExportError(f"Camera '{cam_ob.name}' has a degenerate transform")
    m[:3, :3] = axes / lengths
    return native.Camera(
        **kind,
        ortho_scale=float(cam.ortho_scale),
        **_depth_of_field(cam, m, depsgraph),
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


def _depth_of_field(cam: Any, camera_to_world: np.ndarray, depsgraph: Any) -> dict[str, Any]:
    """Cycles' thin lens from camera.dof (blender/camera.cpp): aperture radius
    lens[mm] * 1e-3 / (2 fstop) in scene units (orthographic: 1 / (2 fstop)), fstop clamped to
    1e-5; focus distance dof.focus_distance, or with a focus object the distance from the
    camera to the object's origin along the camera's view axis; blades below 3 mean round."""
    dof = cam.dof
    if not dof.use_dof:
        return {}
    fstop = max(float(dof.aperture_fstop), 1e-5)
    if cam.type == "ORTHO":
        radius = 1.0 / (2.0 * fstop)
    else:
        radius = float(cam.lens) * 1e-3 / (2.0 * fstop)
    focus = float(dof.focus_distance)
    target = dof.focus_object
    if target is not None:
        if depsgraph is not None:
            target = target.evaluated_get(depsgraph)
        target_pos = np.array(target.matrix_world.translation, dtype=np.float64)
        view_axis = camera_to_world[:3, 2]  # unit: the transform's scale was removed
        focus = abs(float(np.dot(view_axis, camera_to_world[:3, 3] - target_pos)))
    blades = int(dof.aperture_blades)
    return {
        "aperture_radius": radius,
        # The core needs a positive depth; Cycles' focus at 0 is degenerate anyway.
        "focus_distance": max(focus, 1e-6),
        "aperture_blades": blades if blades >= 3 else 0,
        "aperture_rotation": float(dof.aperture_rotation),
    }
