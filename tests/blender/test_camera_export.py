"""Camera export: orthographic cameras and depth of field (Blender's camera.dof, the same API
in 3.4 and 5.0) reach native.Camera with Cycles' values (blender/camera.cpp)."""

from __future__ import annotations

import math
from typing import Any

import bpy
import numpy as np
import pytest
from stratum import native
from stratum.export.common import ExportError
from stratum.export.sync import export_scene


def test_orthographic_camera(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()
    cam = b.scene.camera.data
    cam.type = "ORTHO"
    cam.ortho_scale = 3.25
    cam.sensor_fit = "VERTICAL"
    cam.shift_x, cam.shift_y = 0.125, -0.25
    cam.clip_start, cam.clip_end = 0.5, 40.0
    export_scene(b.depsgraph(), recording_scene)
    c = recording_scene.camera
    assert c.type == native.CAMERA_ORTHOGRAPHIC
    assert c.ortho_scale == pytest.approx(3.25)
    assert c.sensor_fit == native.SENSOR_FIT_VERTICAL
    assert (c.shift_x, c.shift_y) == pytest.approx((0.125, -0.25))
    assert (c.clip_start, c.clip_end) == pytest.approx((0.5, 40.0))
    assert c.aperture_radius == 0.0  # DOF off by default


def test_perspective_camera_without_dof_is_a_pinhole(scene_builder: Any,
                                                    recording_scene: Any) -> None:
    b = scene_builder().basic()
    export_scene(b.depsgraph(), recording_scene)
    c = recording_scene.camera
    assert c.type == native.CAMERA_PERSPECTIVE
    assert c.aperture_radius == 0.0


def test_panoramic_camera_is_rejected_naming_the_type(scene_builder: Any,
                                                     recording_scene: Any) -> None:
    b = scene_builder().basic()
    b.scene.camera.data.type = "PANO"
    with pytest.raises(ExportError, match="PANO"):
        export_scene(b.depsgraph(), recording_scene)


def test_depth_of_field_distance(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()
    cam = b.scene.camera.data
    cam.lens = 35.0
    dof = cam.dof
    dof.use_dof = True
    dof.aperture_fstop = 1.4
    dof.focus_distance = 7.5
    dof.aperture_blades = 6
    dof.aperture_rotation = math.radians(20.0)
    export_scene(b.depsgraph(), recording_scene)
    c = recording_scene.camera
    # Cycles: lens[mm] * 1e-3 / (2 fstop) scene units.
    assert c.aperture_radius == pytest.approx(35.0e-3 / 2.8)
    assert c.focus_distance == pytest.approx(7.5)
    assert c.aperture_blades == 6
    assert c.aperture_rotation == pytest.approx(math.radians(20.0))


def test_depth_of_field_focus_object_is_the_distance_along_the_view_axis(
        scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()  # camera at (0, -6, 0) looking along +Y
    target = bpy.data.objects.new("FocusTarget", None)
    target.location = (2.0, 3.0, -1.0)  # 9 along the view axis, off the axis sideways
    b.link(target)
    cam = b.scene.camera.data
    cam.dof.use_dof = True
    cam.dof.focus_distance = 1.0  # ignored when there is a focus object
    cam.dof.focus_object = target
    export_scene(b.depsgraph(), recording_scene)
    c = recording_scene.camera
    assert c.focus_distance == pytest.approx(9.0, abs=1e-5)
    assert c.aperture_blades == 0  # Blender's default: round
    m = np.asarray(c.transform).reshape(4, 4)
    assert m[:3, 2] == pytest.approx([0.0, -1.0, 0.0], abs=1e-6)  # looks down local -Z = +Y


def test_orthographic_depth_of_field(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()
    cam = b.scene.camera.data
    cam.type = "ORTHO"
    cam.dof.use_dof = True
    cam.dof.aperture_fstop = 4.0
    cam.dof.focus_distance = 5.0
    export_scene(b.depsgraph(), recording_scene)
    # Cycles: 1 / (2 fstop) for orthographic cameras.
    assert recording_scene.camera.aperture_radius == pytest.approx(1.0 / 8.0)
    assert recording_scene.camera.focus_distance == pytest.approx(5.0)
