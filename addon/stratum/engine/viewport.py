"""What the Rendered viewport renders, read from Blender: the view's camera, size and border
(View), and the session's settings (ViewportSettings).

The view's camera comes from the region's matrices, which already hold everything Blender
draws with: the view orientation (view_matrix, world -> view), and the projection
(window_matrix), which in camera view includes the camera's lens, sensor fit and shift and the
view's camera zoom and offset (an off-centre frustum). A native camera expresses any such
frustum, as long as its pixels are square:

* perspective, P = window_matrix (OpenGL convention, as Blender builds it in
  perspective_m4 / window_translate_m4): P00 = 2n/(r-l), P02 = (r+l)/(r-l), P11 = 2n/(t-b),
  P12 = (t+b)/(t-b), P22 = -(f+n)/(f-n), P23 = -2fn/(f-n). With a horizontal sensor fit of
  width S and lens L the native view plane at unit depth is S/L wide (scene/camera.cpp), so
  L = S·P00/2; shift_x = (r+l)/(2(r-l)) = P02/2; shift_y is in units of the fitted width:
  ((t+b)/2n)/(S/L) = P12·P00/(2·P11); clip n = P23/(P22-1), f = P23/(P22+1).
* orthographic: P00 = 2/(r-l), P03 = -(r+l)/(r-l), P11, P13 alike, P22 = -2/(f-n),
  P23 = -(f+n)/(f-n): ortho_scale = 2/P00, shift_x = -P03/2, shift_y = -P13·P00/(2·P11),
  n = (P23+1)/P22, f = (P23-1)/P22. Blender's orthographic views clip from a negative near
  distance; the native camera wants 0 < clip_start, so the camera is moved back along its
  view axis until the near plane is in front of it (the same rays: they are parallel).

In camera view the scene camera's own description (depth of field, type) is kept and its
projection replaced by the view's; an equirectangular camera is rendered as it is (its frame
has no window matrix). The border: the view's own render border (View3D.use_render_border),
or in camera view the scene's render border inside the camera frame (as Cycles does).
"""

from __future__ import annotations

import math
import time
import traceback
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from .. import blender_settings, native, properties
from ..export.camera import convert_camera
from ..export.common import ExportError
from . import denoise
from .frame import library_value, renderer_settings
from .viewport_session import Denoiser, Rect, View, ViewportSession, ViewportSettings

SENSOR_MM = 36.0


def camera_from_matrices(view_matrix: Any, window_matrix: Any, perspective: bool,
                         base: native.Camera | None = None) -> native.Camera:
    """The native camera whose rays are those of the view (module docstring); `base` gives
    the fields the matrices do not (depth of field)."""
    view = np.array(view_matrix, dtype=np.float64).reshape(4, 4)
    p = np.array(window_matrix, dtype=np.float64).reshape(4, 4)
    camera_to_world = np.linalg.inv(view)
    # Blender's view matrices carry no scale, but a camera view inherits the object's: the
    # native camera wants unit axes (the projection alone sets the field of view).
    camera_to_world[:3, :3] /= np.linalg.norm(camera_to_world[:3, :3], axis=0)
    base = base if base is not None else native.Camera()
    if perspective:
        near, far = p[2, 3] / (p[2, 2] - 1.0), p[2, 3] / (p[2, 2] + 1.0)
        projection = {"type": native.CAMERA_PERSPECTIVE, "lens_mm": SENSOR_MM * p[0, 0] / 2.0,
                      "shift_x": p[0, 2] / 2.0, "shift_y": p[1, 2] * p[0, 0] / (2.0 * p[1, 1])}
    else:
        near, far = (p[2, 3] + 1.0) / p[2, 2], (p[2, 3] - 1.0) / p[2, 2]
        projection = {"type": native.CAMERA_ORTHOGRAPHIC, "ortho_scale": 2.0 / p[0, 0],
                      "shift_x": -p[0, 3] / 2.0,
                      "shift_y": -p[1, 3] * p[0, 0] / (2.0 * p[1, 1])}
        # Move back so that the near plane is 1/1000 of the depth range in front of the camera.
        back = max(0.0, 1e-3 * (far - near) - near)
        camera_to_world[:3, 3] += camera_to_world[:3, 2] * back
        near, far = near + back, far + back
    return replace(base, **projection, sensor_width_mm=SENSOR_MM,
                   sensor_height_mm=base.sensor_height_mm,
                   sensor_fit=native.SENSOR_FITS["HORIZONTAL"], clip_start=float(near),
                   clip_end=float(far),
                   transform=np.ascontiguousarray(camera_to_world.astype(np.float32).ravel()))


def camera_frame(camera_object: Any, scene: Any, view_matrix: Any, window_matrix: Any,
                 width: int, height: int) -> tuple[float, float, float, float]:
    """The scene camera's frame in the view, in view pixels (x0, y0, x1, y1), bottom-left
    origin: the corners of Camera.view_frame projected by the view's matrices."""
    corners = camera_object.data.view_frame(scene=scene)
    to_world = np.array(camera_object.matrix_world, dtype=np.float64)
    m = np.array(window_matrix, dtype=np.float64) @ np.array(view_matrix, dtype=np.float64)
    xs, ys = [], []
    for corner in corners:
        clip = m @ to_world @ np.array([*corner, 1.0])
        xs.append((clip[0] / clip[3] + 1.0) * 0.5 * width)
        ys.append((clip[1] / clip[3] + 1.0) * 0.5 * height)
    return min(xs), min(ys), max(xs), max(ys)


def _border(fractions: tuple[float, float, float, float],
            frame: tuple[float, float, float, float], width: int, height: int) -> Rect | None:
    """The border given as fractions (min x, min y, max x, max y) of `frame` (view pixels),
    cut to the view; None when it is empty or the whole view."""
    fx0, fy0, fx1, fy1 = frame
    x0 = max(int(math.floor(fx0 + fractions[0] * (fx1 - fx0))), 0)
    y0 = max(int(math.floor(fy0 + fractions[1] * (fy1 - fy0))), 0)
    x1 = min(int(math.ceil(fx0 + fractions[2] * (fx1 - fx0))), width)
    y1 = min(int(math.ceil(fy0 + fractions[3] * (fy1 - fy0))), height)
    if x1 - x0 < 1 or y1 - y0 < 1 or (x0, y0, x1, y1) == (0, 0, width, height):
        return None
    return x0, y0, x1 - x0, y1 - y0


def view_from_context(context: Any, depsgraph: Any) -> View:
    """The View of the 3D view being drawn (RenderEngine.view_draw's context)."""
    region, rv3d, space = context.region, context.region_data, context.space_data
    width, height = max(int(region.width), 1), max(int(region.height), 1)
    scene = depsgraph.scene_eval if hasattr(depsgraph, "scene_eval") else depsgraph.scene
    view_matrix, window_matrix = rv3d.view_matrix, rv3d.window_matrix
    in_camera = rv3d.view_perspective == "CAMERA" and scene.camera is not None
    base = convert_camera(scene, depsgraph) if in_camera else None
    if base is not None and base.type == native.CAMERA_EQUIRECTANGULAR:
        camera = base
    else:
        camera = camera_from_matrices(view_matrix, window_matrix, rv3d.is_perspective, base)
    border = None
    if in_camera and scene.render.use_border:
        r = scene.render
        frame = camera_frame(scene.camera.evaluated_get(depsgraph), scene, view_matrix,
                             window_matrix, width, height)
        border = _border((r.border_min_x, r.border_min_y, r.border_max_x, r.border_max_y),
                         frame, width, height)
    elif not in_camera and getattr(space, "use_render_border", False):
        border = _border((space.render_border_min_x, space.render_border_min_y,
                          space.render_border_max_x, space.render_border_max_y),
                         (0.0, 0.0, float(width), float(height)), width, height)
    return View(camera, width, height, border)


def settings_from_scene(scene: Any) -> ViewportSettings:
    """The viewport's settings: the scene's render settings (engine/frame.py) with the
    viewport's sample count, adaptive sampling, start resolution and split view
    (scene.stratum)."""
    s = scene.stratum
    # The viewport's own stand-ins for library settings (adaptive sampling) replace the F12
    # render's values.
    native_settings = renderer_settings(scene) | {
        setting: library_value(getattr(s, name))
        for name, setting in blender_settings.VIEWPORT_SETTINGS.items()}
    return ViewportSettings(
        samples=int(s.preview_samples),
        sampler=str(s.sampler),
        compare_sampler=str(s.compare_sampler) if s.use_split_view else None,
        split_position=float(s.split_position),
        start_resolution=int(s.preview_start_resolution),
        native=native_settings,
    )


def preview_denoiser(scene: Any) -> tuple[Denoiser | None, tuple[str, ...]]:
    """What ViewportSession.set_denoiser takes for scene.stratum.use_preview_denoising: the
    OIDN filter of engine/denoise.py and the guide passes the library can render (albedo and
    normal); (None, ()) when it is off."""
    if not getattr(scene.stratum, "use_preview_denoising", False):
        return None, ()
    return denoise_preview, tuple(name for name in denoise.library_guides() if name)


def denoise_preview(colour: np.ndarray, passes: dict[str, np.ndarray]) -> np.ndarray:
    """A converged viewport frame denoised with the guides preview_denoiser asked for.
    Raises native.DenoiserUnavailable (reported once by viewport_call; the frame stays)."""
    albedo, normal = denoise.library_guides()
    return denoise.denoise_rgba(colour, passes.get(albedo) if albedo else None,
                                passes.get(normal) if normal else None)


# ---- the engine's view_update / view_draw ------------------------------------------------

REDRAW_SECONDS = 1.0 / 30.0  # how often a refining viewport is redrawn
# While the drawn frame shows a scene or view older than the session's (a change was just made),
# the session is polled this often and the view redrawn as soon as the first new frame is there:
# waiting out a whole REDRAW_SECONDS added up to 33 ms to a change's latency. For at most
# FAST_POLL_LIMIT after the frame went stale, then back to REDRAW_SECONDS (a big scene's first
# frame can take seconds).
FAST_POLL_SECONDS = 0.004
FAST_POLL_LIMIT = 0.5


class ViewportState:
    """What one RenderEngine instance keeps for the viewport it draws."""

    def __init__(self) -> None:
        self.session = ViewportSession()
        self.drawer: Any | None = None  # viewport_draw.FrameDrawer, made at the first draw
        self.error = ""  # the export error the view shows until the next update
        self.reported = ""  # the last error reported: a redraw does not report it again
        self.redraw_pending = False
        self.drawn_generation = -1  # generation of the frame last drawn
        # The newest generation seen while an older frame was drawn, and since when.
        self.stale_generation = -1
        self.stale_since = 0.0
        self.freed = False

    def free(self) -> None:
        self.freed = True
        self.session.free()
        if self.drawer is not None:
            self.drawer.free()


# ViewportState per engine, by id(engine): the engine's own attributes are gone once Blender has
# removed its RNA, which can be before the Python object is collected (and its __del__ runs).
_states: dict[int, ViewportState] = {}


def free_viewport(engine_id: int) -> None:
    """Frees the viewport of the engine of this id (its __del__)."""
    state = _states.pop(engine_id, None)
    if state is not None:
        state.free()


def viewport_call(engine: Any, call: Callable[[ViewportState], None]) -> None:
    """Runs view_update or view_draw for `engine` (its ViewportState made on first use);
    whatever goes wrong is reported once through engine._report, never raised into Blender."""
    if properties.load_error:
        message = f"the native library could not be loaded ({properties.load_error})"
    else:
        state = _states.get(id(engine))
        if state is None:
            state = _states[id(engine)] = ViewportState()
        try:
            call(state)
            return
        except (ExportError, native.StratumError) as exc:
            message = str(exc)
        except Exception as exc:  # noqa: BLE001 - nothing may crash Blender
            traceback.print_exc()
            message = f"internal error: {type(exc).__name__}: {exc}"
        if message == state.reported:
            return
        state.reported = message
    engine._report("ERROR", f"Stratum: {message}")


def view_update(state: ViewportState, depsgraph: Any) -> None:
    """RenderEngine.view_update: the scene's changes sent (depsgraph.updates is read here,
    while Blender reports them). Raises what the export raises; the engine reports it."""
    state.error = ""
    scene = depsgraph.scene
    try:
        state.session.update(depsgraph)
        state.session.set_settings(settings_from_scene(scene))
    except Exception as exc:
        state.error = str(exc)
        raise


def view_draw(state: ViewportState, engine: Any, context: Any, depsgraph: Any) -> None:
    """RenderEngine.view_draw: the view's camera and size handed to the session, its newest
    frame drawn, and redraws scheduled while it refines."""
    import bpy

    scene = depsgraph.scene
    session = state.session
    session.set_settings(settings_from_scene(scene))
    session.set_denoiser(*preview_denoiser(scene))
    session.set_view(view_from_context(context, depsgraph))
    if state.error:
        engine.update_stats("", f"Stratum: {state.error}")
        return
    # A missing denoiser leaves the converged frame undenoised: it is drawn (now, or by the
    # redraw scheduled below), the error reported after.
    frame, denoiser_error = _denoiser_safe(session.frame)
    if frame is not None:
        if state.drawer is None:
            from .viewport_draw import FrameDrawer

            state.drawer = FrameDrawer()
        state.drawer.draw(engine, scene, frame, context.preferences.system.ui_scale)
        state.drawn_generation = frame.generation
        total = scene.stratum.preview_samples
        stage = " (start resolution)" if frame.samples > 0 and not frame.final else ""
        engine.update_stats("", f"Sample {frame.samples}/{total}{stage}")
    refining, poll_error = _denoiser_safe(session.poll)
    if (refining or poll_error is not None) and not state.redraw_pending:
        state.redraw_pending = True
        # A timer, not engine.tag_redraw from a later call: the engine may be freed by then.
        bpy.app.timers.register(lambda: _redraw_views(state),
                                first_interval=_redraw_interval(state))
    # Raised anew, with no exception left in this frame's locals: an exception held by a frame
    # its traceback holds is a reference cycle, which would keep the engine (and its session)
    # alive after Blender frees it, until the garbage collector runs.
    message = str(denoiser_error or poll_error or "")
    del denoiser_error, poll_error
    if message:
        raise native.DenoiserUnavailable(message)


def _denoiser_safe(call: Callable[[], Any]) -> tuple[Any, native.DenoiserUnavailable | None]:
    """call()'s result and None; if the denoiser failed in it (the session has then shown the
    converged frame undenoised), call()'s result again and the error."""
    try:
        return call(), None
    except native.DenoiserUnavailable as exc:
        return call(), exc


def _stale(state: ViewportState) -> bool:
    """Whether the frame drawn last shows an older scene or view than the session renders;
    notes when a newer generation is first seen (stale_since, which _redraw_interval reads)."""
    generation = state.session.generation
    if generation == state.drawn_generation:
        return False
    if generation != state.stale_generation:
        state.stale_generation = generation
        state.stale_since = time.monotonic()
    return True


def _redraw_interval(state: ViewportState) -> float:
    if _stale(state) and time.monotonic() - state.stale_since < FAST_POLL_LIMIT:
        return FAST_POLL_SECONDS
    return REDRAW_SECONDS


def _redraw_views(state: ViewportState) -> float | None:
    """Tags every 3D view in Rendered shading for a redraw (the view_draw that follows reads
    the session's newest pixels). A timer callback: returns None to run once, or the seconds
    until it runs again while a stale frame waits for the first new one."""
    import bpy

    if state.freed:
        state.redraw_pending = False
        return None
    if _stale(state) and _redraw_interval(state) == FAST_POLL_SECONDS:
        try:
            frame = state.session.frame()
        except Exception:  # noqa: BLE001 - the redraw's view_draw reports it; a timer must not raise
            frame = None
            ready = True
        else:
            ready = frame is not None and frame.generation == state.session.generation
        if not ready:
            return FAST_POLL_SECONDS
    state.redraw_pending = False
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "VIEW_3D" and area.spaces.active.shading.type == "RENDERED":
                area.tag_redraw()
