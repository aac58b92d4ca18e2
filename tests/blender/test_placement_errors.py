"""Transforms and native rejections reach Blender naming the object (issue 12, point 1, Python
side): a degenerate instance (zero scale) is skipped with a warning naming the object; a NaN
transform is an ERROR naming the object and the element; a value the native library refuses is
an ERROR naming the camera / object / light and the field, never an ABI function.

The tests marked `needs_native_bounds` pass once the native library bounds camera placement,
ortho scale, positions and light transforms (the native half of point 1); until then the
native side accepts those values and no ERROR is raised (nothing is rendered by them here, so
nothing can abort)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest
from stratum import native
from stratum.export.common import ExportError
from stratum.export.sync import export_scene

from conftest import engine_reports, render_still

NAN = float("nan")


def _warnings(summary: Any, who: str) -> list[str]:
    return [w for w in summary.warnings if who in w]


def _linked_duplicate(b: Any, name: str, scale: tuple[float, float, float]) -> Any:
    """A second object sharing the cube's mesh (so the mesh is instanced), scaled."""
    twin = b.mesh_object(name, data=b.scene.objects["Cube"].data, location=(2.5, 0.0, 0.0))
    twin.scale = scale
    return twin


@pytest.mark.parametrize("scale", [(1.0, 0.0, 1.0), (1e-18, 1e-18, 1e-18)])
def test_degenerate_linked_duplicate_is_skipped_naming_it(scene_builder: Any,
                                                          recording_scene: Any,
                                                          scale: tuple[float, ...]) -> None:
    b = scene_builder().basic()
    _linked_duplicate(b, "Flat", scale)
    b.mesh_object("Thin", location=(-2.5, 0.0, 0.0)).scale = (1.0, 1e-8, 1.0)  # traceable
    summary = export_scene(b.depsgraph(), recording_scene)
    (warning,) = _warnings(summary, "Object 'Flat'")
    assert "zero scale" in warning and "skipped" in warning
    assert sorted(summary.object_instances) == ["Cube", "Thin"]
    assert len(recording_scene.instances) == 2


def test_moving_instance_degenerate_at_shutter_close_is_skipped(scene_builder: Any,
                                                                recording_scene: Any) -> None:
    b = scene_builder().basic()
    squash = b.mesh_object("Squash", location=(2.5, 0.0, 0.0))
    driver = squash.driver_add("scale", 1).driver
    driver.type = "SCRIPTED"
    driver.expression = "frame - 1.25"  # 0 at the shutter's close: [0.75, 1.25] around 1
    b.scene.frame_set(1)
    b.scene.render.use_motion_blur = True
    b.scene.render.motion_blur_shutter = 0.5
    summary = export_scene(b.depsgraph(), recording_scene)
    assert len(_warnings(summary, "Object 'Squash'")) == 1
    assert "Squash" not in summary.object_instances and summary.moving_instances == 0


def test_degenerate_linked_duplicate_renders_with_a_warning(library: Any, scene_builder: Any,
                                                            tmp_path: Path) -> None:
    """The issue's abort (Embree's assertion on the object-space ray of a zero-scale instance):
    now a warning and an image."""
    b = scene_builder().basic()
    b.set_resolution(16, 16)
    b.scene.stratum.samples = 1
    _linked_duplicate(b, "Flat", (1.0, 0.0, 1.0))
    pixels = render_still(b.scene, tmp_path / "flat.exr")
    assert not engine_reports("ERROR")
    assert any("Object 'Flat'" in w for w in engine_reports("WARNING"))
    assert pixels is not None and np.isfinite(pixels).all() and pixels[..., :3].max() > 0.0


def test_nan_transform_is_an_error_naming_object_and_element(scene_builder: Any,
                                                             recording_scene: Any,
                                                             tmp_path: Path) -> None:
    b = scene_builder().basic()
    b.scene.objects["Cube"].location = (NAN, 0.0, 0.0)
    with pytest.raises(ExportError) as info:
        export_scene(b.depsgraph(), recording_scene)
    assert str(info.value) == "Object 'Cube': transform element 3 = nan is not finite"
    render_still(b.scene, tmp_path / "nan.exr")
    assert engine_reports("ERROR") == [f"Stratum: {info.value}"]


@pytest.mark.parametrize("kind", ["POINT", "AREA"])
def test_nan_light_transform_is_an_error_naming_the_light(scene_builder: Any,
                                                          recording_scene: Any,
                                                          kind: str) -> None:
    b = scene_builder().basic()
    lamp = b.link(bpy.data.objects.new("Lamp", bpy.data.lights.new("Lamp", kind)))
    lamp.location = (0.0, NAN, 0.0)
    with pytest.raises(ExportError) as info:
        export_scene(b.depsgraph(), recording_scene)
    assert str(info.value) == "Light 'Lamp': transform element 7 = nan is not finite"


class _RejectingScene:
    """A recording scene whose add_instances refuses the row translated to x >= 7, as the
    native library reports a refused row of the batch (StratumError.index)."""

    def __init__(self, recording: Any) -> None:
        self._recording = recording

    def __getattr__(self, name: str) -> Any:
        return getattr(self._recording, name)

    def add_instances(self, mesh_ids: Any, transforms: Any) -> None:
        far = np.flatnonzero(np.asarray(transforms)[:, 0, 3] >= 7.0)
        if len(far):
            raise native.StratumError(
                native.ERROR_INVALID_ARGUMENT,
                "stratum_scene_add_instance: instance transform element 3 = 7 is too far",
                index=int(far[0]))
        self._recording.add_instances(mesh_ids, transforms)


def test_refused_instance_row_is_named_by_its_object(scene_builder: Any,
                                                     recording_scene: Any) -> None:
    b = scene_builder().basic()
    b.mesh_object("Near", location=(3.0, 0.0, 0.0))
    b.mesh_object("Far", location=(7.0, 0.0, 0.0))
    b.mesh_object("Nearer", location=(-3.0, 0.0, 0.0))
    with pytest.raises(ExportError) as info:
        export_scene(b.depsgraph(), _RejectingScene(recording_scene))
    assert str(info.value) == "Object 'Far': instance transform element 3 = 7 is too far"


# ---- rejected by the native library's bounds (issue 12 point 1, native half) ---------------

needs_native_bounds = pytest.mark.usefixtures("library")


def _export_error(b: Any) -> str:
    with native.Scene() as scene, pytest.raises(ExportError) as info:
        export_scene(b.depsgraph(), scene)
    message = str(info.value)
    assert "stratum_" not in message
    return message


@needs_native_bounds
@pytest.mark.parametrize("kind", ["PERSP", "EQUIRECTANGULAR"])
def test_camera_far_from_the_origin_is_an_error_naming_it(scene_builder: Any, kind: str) -> None:
    b = scene_builder().basic()
    camera = b.scene.camera
    camera.location = (1e19, 0.0, 0.0)
    if kind == "EQUIRECTANGULAR":
        camera.data.type = "PANO"
        settings = camera.data.cycles if bpy.app.version < (4, 0, 0) else camera.data
        settings.panorama_type = "EQUIRECTANGULAR"
    assert _export_error(b).startswith("Camera 'Camera': ")


@needs_native_bounds
def test_huge_ortho_scale_is_an_error_naming_the_camera(scene_builder: Any) -> None:
    b = scene_builder().basic()
    b.scene.camera.data.type = "ORTHO"
    b.scene.camera.data.ortho_scale = 1e20
    message = _export_error(b)
    assert message.startswith("Camera 'Camera': ") and "ortho" in message


@needs_native_bounds
def test_vertex_at_1e30_is_an_error_naming_object_and_vertex(scene_builder: Any) -> None:
    """Embree drops such a triangle silently (the issue's vanishing triangle)."""
    b = scene_builder().basic()
    far = bpy.data.meshes.new("Far")
    far.from_pydata([(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1e30)], [], [(0, 1, 2)])
    b.mesh_object("Spike", data=far)
    message = _export_error(b)
    assert message.startswith("Object 'Spike': ") and "vertex 2" in message


@needs_native_bounds
def test_object_far_from_the_origin_is_an_error_naming_it(scene_builder: Any) -> None:
    b = scene_builder().basic()
    b.mesh_object("Distant", location=(0.0, 1e19, 0.0))
    assert _export_error(b).startswith("Object 'Distant': ")


@needs_native_bounds
def test_light_far_from_the_origin_is_an_error_naming_it(scene_builder: Any) -> None:
    b = scene_builder().basic()
    b.scene.objects["Light"].location = (0.0, 0.0, -1e19)
    assert _export_error(b).startswith("Light 'Light': ")


def test_rotated_and_scaled_instances_stay_untouched(scene_builder: Any,
                                                     recording_scene: Any) -> None:
    """The degenerate test skips nothing ordinary: 200 linked duplicates with random
    rotations and scales from 1e-3 to 1e3 are all placed, with their own matrices."""
    b = scene_builder().basic()
    rng = np.random.default_rng(7)
    mesh = b.scene.objects["Cube"].data
    for i in range(200):
        ob = b.mesh_object(f"Copy{i}", data=mesh, location=tuple(rng.uniform(-50, 50, 3)))
        ob.rotation_euler = tuple(rng.uniform(-math.pi, math.pi, 3))
        ob.scale = tuple(10.0 ** rng.uniform(-3, 3, 3))
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.instances == 201 and not summary.warnings


@pytest.mark.parametrize("path", ["lens", "ortho_scale", "clip_end", "shift_x",
                                  "dof.aperture_fstop", "dof.focus_distance"])
def test_nan_camera_property_is_an_error_naming_it(scene_builder: Any, recording_scene: Any,
                                                   path: str) -> None:
    b = scene_builder().basic()
    cam = b.scene.camera.data
    cam.dof.use_dof = True
    owner, _, attr = path.rpartition(".")
    setattr(cam.dof if owner else cam, attr, NAN)
    with pytest.raises(ExportError) as info:
        export_scene(b.depsgraph(), recording_scene)
    assert str(info.value) == f"Camera 'Camera': '{path}' = nan is not a finite number"


@pytest.mark.parametrize("shutter", [NAN, 1e30])
def test_shutter_blender_cannot_evaluate_renders_without_motion_blur(
        scene_builder: Any, recording_scene: Any, shutter: float) -> None:
    b = scene_builder().basic()
    b.scene.render.use_motion_blur = True
    b.scene.render.motion_blur_shutter = shutter
    summary = export_scene(b.depsgraph(), recording_scene)
    (warning,) = [w for w in summary.warnings if "motion blur" in w]
    assert warning.startswith("Scene 'Scene': ") and summary.moving_instances == 0
