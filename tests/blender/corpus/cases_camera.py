"""Cameras: placement far from the origin (1e19 aborted Blender in Embree, perspective and
equirectangular), NaN placement and lens, orthographic scale 1e20, lens extremes, clip start
after clip end, depth of field with a tiny f-stop and focus at 0, no camera, a mesh as camera."""

from __future__ import annotations

import math
from typing import Any

import bpy

from .case import case, clean, culprit, error, lit_centre, survive
from .stage import Stage

NAN = float("nan")
PLACEMENT = ("location", "position", "transform", "matrix", "far", "large", "bound", "origin")


def _camera(s: Stage, name: str, location: tuple[float, float, float] = (0.0, -6.0, 0.0),
            **fields: Any) -> Any:
    """The base scene seen by camera `name` at `location` (looking along +Y), with `fields`
    set on its camera data (names with a dot go one level down: 'dof.aperture_fstop')."""
    s.base()
    ob = s.camera(name, location)
    for field_name, value in fields.items():
        target = ob.data
        *path, attr = field_name.split(".")
        for part in path:
            target = getattr(target, part)
        setattr(target, attr, value)
    return ob


def _camera_case(name: str, what: str, expect: Any, camera: str,
                 location: tuple[float, float, float] = (0.0, -6.0, 0.0), **fields: Any) -> None:
    case(name, "camera", what, expect)(lambda s: _camera(s, camera, location, **fields))


_camera_case("cam_far_1e19", "a perspective camera 1e19 m from the origin (Embree abort)",
             culprit("FarCamera", words=PLACEMENT), "FarCamera", (0.0, -1e19, 0.0))
_camera_case("cam_far_1e12", "a perspective camera 1e12 m from the origin",
             survive("RemoteCamera", words=PLACEMENT), "RemoteCamera", (0.0, -1e12, 0.0))
_camera_case("cam_ortho_scale_1e20", "an orthographic camera of ortho_scale 1e20 (Embree abort)",
             culprit("WideCamera", words=("ortho",)), "WideCamera", type="ORTHO",
             ortho_scale=1e20)
_camera_case("cam_ortho_scale_tiny", "an orthographic camera of ortho_scale 1e-9",
             survive("NarrowCamera", words=("ortho",)), "NarrowCamera", type="ORTHO",
             ortho_scale=1e-9)
_camera_case("cam_nan_ortho_scale", "an orthographic camera of ortho_scale NaN",
             culprit("NanOrtho", words=("ortho",)), "NanOrtho", type="ORTHO", ortho_scale=NAN)
_camera_case("cam_lens_1mm", "a 1 mm lens (Blender's minimum)",
             clean(quiet=True, pixels=lit_centre), "FisheyeLike", lens=1.0)
_camera_case("cam_lens_1e9", "a lens of 1e9 mm (a field of view of 4e-8 rad)",
             survive("Telescope", words=("lens", "focal")), "Telescope", lens=1e9)
_camera_case("cam_nan_lens", "a lens of NaN mm", culprit("NanLens", words=("lens", "focal")),
             "NanLens", lens=NAN)
_camera_case("cam_clip_start_after_end", "clip start 10 m, clip end 1 m",
             survive("Clipped", words=("clip",)), "Clipped", clip_start=10.0, clip_end=1.0)
_camera_case("cam_nan_clip_end", "clip end NaN", culprit("NanClip", words=("clip",)), "NanClip",
             clip_end=NAN)
_camera_case("cam_clip_end_1e30", "clip end 1e30 m", clean(pixels=lit_centre),
             "DeepClip", clip_end=1e30)
_camera_case("cam_fstop_zero", "depth of field with f-stop 0 (an aperture of thousands of m)",
             survive("WideAperture", words=("aperture", "f-stop", "fstop")), "WideAperture",
             **{"dof.use_dof": True, "dof.aperture_fstop": 0.0, "dof.focus_distance": 6.0})
_camera_case("cam_aperture_5e31", "a lens of 1e30 mm at f-stop 0: an aperture radius of 5e31 m",
             culprit("GiantLens", words=("aperture", "lens", "focal")), "GiantLens", lens=1e30,
             **{"dof.use_dof": True, "dof.aperture_fstop": 0.0, "dof.focus_distance": 6.0})
_camera_case("cam_focus_zero", "depth of field focused at 0 m",
             survive("NoFocus", words=("focus",)), "NoFocus",
             **{"dof.use_dof": True, "dof.aperture_fstop": 2.8, "dof.focus_distance": 0.0})
_camera_case("cam_nan_location", "a camera at (NaN, -6, 0)", culprit("NanCamera", words=PLACEMENT),
             "NanCamera", (NAN, -6.0, 0.0))


@case("cam_equirectangular_far", "camera",
      "an equirectangular panorama 1e19 m from the origin (Embree abort)",
      culprit("FarPanorama", words=PLACEMENT))
def cam_equirectangular_far(s: Stage) -> None:
    ob = _camera(s, "FarPanorama", (0.0, -1e19, 0.0), type="PANO")
    source = ob.data.cycles if bpy.app.version < (4, 0, 0) else ob.data
    source.panorama_type = "EQUIRECTANGULAR"


@case("cam_zero_scale", "camera", "a camera object scaled 0", survive("FlatCamera"))
def cam_zero_scale(s: Stage) -> None:
    _camera(s, "FlatCamera").scale = (0.0, 0.0, 0.0)


@case("cam_rotation_nan", "camera", "a camera rotated by NaN",
      culprit("SpinningCamera", words=PLACEMENT + ("rotation",)))
def cam_rotation_nan(s: Stage) -> None:
    _camera(s, "SpinningCamera").rotation_euler = (NAN, 0.0, math.pi)


@case("cam_none", "camera", "a scene without a camera", error(words=("camera",)))
def cam_none(s: Stage) -> None:
    s.mesh("Cube")
    s.light()
    s.world()


@case("cam_mesh_as_camera", "camera", "a mesh object as the scene camera",
      survive("NotACamera", words=("camera",)))
def cam_mesh_as_camera(s: Stage) -> None:
    s.base()
    ob = s.mesh("NotACamera", location=(0.0, -6.0, 0.0), scale=(0.1, 0.1, 0.1))
    ob.rotation_euler = (math.pi / 2, 0.0, 0.0)
    s.scene.camera = ob
