"""The scene camera -> native camera.

A camera value that is NaN or infinite (RNA keeps NaN in lens, ortho scale, clipping, shift,
f-stop, focus distance, panorama ranges) cannot be rendered: an ExportError names the camera
and the property. Finite values the renderer cannot use (a camera 1e19 from the origin, an
ortho scale of 1e20) are refused by the native library, also by name.
"""

from __future__ import annotations

import math
from typing import Any

import bpy
import numpy as np

from .. import blender_versions, native
from .common import ExportError, matrix_to_array


def _panorama(cam: Any, name: str) -> dict[str, Any]:
    """Equirectangular panorama ranges: Cycles 3.x keeps them in camera.cycles, 4.x+ on the
    camera itself. Other panorama types are an error naming the type."""
    in_cycles = blender_versions.panorama_in_cycles_settings(bpy.app.version)
    source = cam.cycles if in_cycles and hasattr(cam, "cycles") else cam
    kind = getattr(source, "panorama_type", "")
    if kind != "EQUIRECTANGULAR":
        raise ExportError(f"Camera '{name}': camera type PANO with panorama type {kind} is not "
                          "supported (only EQUIRECTANGULAR, perspective and orthographic)")
    ranges = {key: _finite(source, key, name) for key in (
        "latitude_min", "latitude_max", "longitude_min", "longitude_max")}
    return {"type": native.CAMERA_EQUIRECTANGULAR, **ranges}


def _finite(owner: Any, path: str, name: str) -> float:
    """float(owner.<path>) (dots allowed), or an ExportError naming the camera and property."""
    value: Any = owner
    for part in path.split("."):
        value = getattr(value, part)
    value = float(value)
    if not math.isfinite(value):
        raise ExportError(f"Camera '{name}': '{path}' = {value:g} is not a finite number")
    return value


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
    bad = np.flatnonzero(~np.isfinite(m.reshape(16)))
    if len(bad):
        raise ExportError(f"Camera '{cam_ob.name}': transform element {bad[0]} = "
                          f"{m.reshape(16)[bad[0]]:g} is not finite")
    # Drop object scale: a scaled camera must not change the projection.
    axes = m[:3, :3]
    lengths = np.linalg.norm(axes, axis=0)
    if np.any(lengths < 1e-12):
        raise ExportError(f"Camera '{cam_ob.name}': its transform has zero scale along an axis "
                          "(no view direction)")
    m[:3, :3] = axes / lengths
    name = cam_ob.name
    return native.Camera(
        **kind,
        ortho_scale=_finite(cam, "ortho_scale", name),
        **_depth_of_field(cam, m, depsgraph, name),
        lens_mm=_finite(cam, "lens", name),
        sensor_width_mm=_finite(cam, "sensor_width", name),
        sensor_height_mm=_finite(cam, "sensor_height", name),
        sensor_fit=native.SENSOR_FITS.get(cam.sensor_fit, native.SENSOR_FIT_AUTO),
        shift_x=_finite(cam, "shift_x", name),
        shift_y=_finite(cam, "shift_y", name),
        clip_start=_finite(cam, "clip_start", name),
        clip_end=_finite(cam, "clip_end", name),
        transform=np.ascontiguousarray(m.astype(np.float32).reshape(16)),
    )


def _depth_of_field(cam: Any, camera_to_world: np.ndarray, depsgraph: Any,
                    name: str) -> dict[str, Any]:
    """Cycles' thin lens from camera.dof (blender/camera.cpp): aperture radius
    lens[mm] * 1e-3 / (2 fstop) in scene units (orthographic: 1 / (2 fstop)), fstop clamped to
    1e-5; focus distance dof.focus_distance, or with a focus object the distance from the
    camera to the object's origin along the camera's view axis; blades below 3 mean round."""
    dof = cam.dof
    if not dof.use_dof:
        return {}
    fstop = max(_finite(cam, "dof.aperture_fstop", name), 1e-5)
    if cam.type == "ORTHO":
        radius = 1.0 / (2.0 * fstop)
    else:
        radius = _finite(cam, "lens", name) * 1e-3 / (2.0 * fstop)
    focus = _finite(cam, "dof.focus_distance", name)
    target = dof.focus_object
    if target is not None:
        if depsgraph is not None:
            target = target.evaluated_get(depsgraph)
        target_pos = np.array(target.matrix_world.translation, dtype=np.float64)
        view_axis = camera_to_world[:3, 2]  # unit: the transform's scale was removed
        focus = abs(float(np.dot(view_axis, camera_to_world[:3, 3] - target_pos)))
        if not math.isfinite(focus):
            raise ExportError(f"Camera '{name}': its focus object '{target.name}' is not at a "
                              "finite position")
    blades = int(dof.aperture_blades)
    return {
        "aperture_radius": radius,
        # The core needs a positive depth; Cycles' focus at 0 is degenerate anyway.
        "focus_distance": max(focus, 1e-6),
        "aperture_blades": blades if blades >= 3 else 0,
        "aperture_rotation": _finite(cam, "dof.aperture_rotation", name),
    }
