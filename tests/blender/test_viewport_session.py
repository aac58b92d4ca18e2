"""The Rendered viewport's session logic (engine/viewport_session.py, engine/viewport.py) on the
Cornell box, in background mode (Blender 3.4 and the bpy 5.0 wheel; the GPU draw is tested by
the Xvfb UI test): it refines to preview_samples and stops; an edit restarts it and the frame it
converges to is, bit for bit, a fresh full render of the edited scene with the same settings;
free() leaves no renderer; the split view's parts are the single-sampler frames of its two
samplers, pixel for pixel.

The view is the scene camera's, built from the matrices a 3D view in camera view hands the
engine (view_matrix = the camera's inverse, window_matrix = Object.calc_matrix_camera at the
view's size), so the session's camera mapping is tested too: its render equals the scene
camera's render up to float rounding.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest
from stratum.engine.viewport import camera_from_matrices, settings_from_scene
from stratum.engine.viewport_session import (
    Frame,
    View,
    ViewportSession,
    ViewportSettings,
    resample,
)
from stratum.export.camera import convert_camera
from stratum.export.sync import SceneSync
from stratum.export.updates import IdUpdate, collect_updates

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "scenes" / "cornell_box.blend"
WIDTH, HEIGHT = 40, 30
SAMPLES = 8
DEADLINE_S = 120.0


@pytest.fixture
def cornell(stratum_addon: Any) -> Any:
    bpy.ops.wm.open_mainfile(filepath=str(CORNELL), load_ui=False)
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    s = scene.stratum
    s.preview_samples = SAMPLES
    s.preview_start_resolution = 0
    s.seed = 5
    s.threads = 2
    s.max_bounces = 3
    s.sampler = "sobol"
    # A point light, so that a light's power can be edited (the box is lit by an emitter).
    light = bpy.data.lights.new("Point", "POINT")
    light.energy = 20.0
    light_ob = bpy.data.objects.new("Point", light)
    light_ob.location = (0.3, -0.4, 1.5)
    scene.collection.objects.link(light_ob)
    return scene


def _depsgraph() -> Any:
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    return depsgraph


def camera_view(depsgraph: Any, width: int = WIDTH, height: int = HEIGHT) -> View:
    """The View of a 3D view in camera view showing exactly the camera's frame."""
    scene = depsgraph.scene_eval
    ob = scene.camera.evaluated_get(depsgraph)
    window = ob.calc_matrix_camera(depsgraph, x=width, y=height)
    camera = camera_from_matrices(ob.matrix_world.inverted(), window,
                                  ob.data.type == "PERSP", convert_camera(scene, depsgraph))
    return View(camera, width, height)


@contextmanager
def recorded_updates() -> Iterator[list[IdUpdate]]:
    """The depsgraph updates of the evaluations made inside the block (depsgraph.updates is
    empty again once Depsgraph.update() returns: see test_scene_sync.py)."""
    updates: list[IdUpdate] = []

    def keep(scene: Any, depsgraph: Any) -> None:
        updates.extend(collect_updates(depsgraph))

    bpy.app.handlers.depsgraph_update_post.append(keep)
    try:
        yield updates
    finally:
        bpy.app.handlers.depsgraph_update_post.remove(keep)


def converge(session: ViewportSession) -> tuple[Frame, list[Frame]]:
    """Calls frame() until the session is idle; the converged frame and every distinct frame
    seen on the way."""
    seen: list[Frame] = []
    deadline = time.monotonic() + DEADLINE_S
    while True:
        frame = session.frame()
        if frame is not None and (not seen or seen[-1].serial != frame.serial):
            seen.append(frame)
        if session.converged:  # frame() polls; a poll here could skip a stage's frame
            break
        assert time.monotonic() < deadline, "the viewport session did not converge"
        time.sleep(0.002)
    frame = session.frame()
    assert frame is not None
    return frame, seen


def fresh_render(depsgraph: Any, view: View, settings: ViewportSettings,
                 sampler: str | None = None, pass_name: str = "") -> np.ndarray:
    """A new full export of the depsgraph with the view's camera, rendered by a new renderer
    with the session's settings (view size, preview samples, dynamic BVH): (h, w, 4), or
    the pass `pass_name` (h, w, channels)."""
    native_settings = {k: v for k, v in settings.native.items()
                       if not k.startswith("crop_")}
    native_settings |= {"width": view.width, "height": view.height, "samples": settings.samples,
                        "sampler": sampler or settings.sampler, "bvh": "dynamic",
                        "passes": pass_name}
    with SceneSync() as sync:
        sync.full(depsgraph)
        sync.scene.set_camera(view.camera)
        from stratum import native

        with native.Renderer(sync.scene, **native_settings) as renderer:
            pixels = _render(renderer).reshape(view.height, view.width, 4)
            return renderer.read_pass(pass_name) if pass_name else pixels


def _render(renderer: Any) -> np.ndarray:
    renderer.start()
    deadline = time.monotonic() + DEADLINE_S
    while not renderer.wait(100):
        assert time.monotonic() < deadline, "render did not finish"
    return renderer.read_pixels().copy()


def _session(scene: Any, depsgraph: Any, **overrides: Any) -> tuple[ViewportSession, View]:
    session = ViewportSession()
    session.update(depsgraph)
    session.set_settings(replace(settings_from_scene(scene), **overrides))
    view = camera_view(depsgraph)
    session.set_view(view)
    return session, view


CAMERAS: dict[str, dict[str, Any]] = {
    "as saved": {},
    "shifted (an off-centre frustum)": {"shift_x": 0.12, "shift_y": -0.07},
    "vertical sensor fit": {"sensor_fit": "VERTICAL", "sensor_height": 30.0, "lens": 40.0},
    "orthographic": {"type": "ORTHO", "ortho_scale": 2.4, "shift_x": 0.05},
}


@pytest.mark.parametrize("name", list(CAMERAS))
def test_view_camera_renders_the_scene_camera(library: Any, cornell: Any, name: str) -> None:
    """The camera built from the view's matrices renders what the scene camera renders: the
    same rays up to float rounding of the projection (lens and shift recovered from it)."""
    for key, value in CAMERAS[name].items():
        setattr(cornell.camera.data, key, value)
    depsgraph = _depsgraph()
    settings = settings_from_scene(cornell)
    view = camera_view(depsgraph)
    from_view = fresh_render(depsgraph, view, settings)
    from_scene = fresh_render(depsgraph, View(convert_camera(cornell, depsgraph), WIDTH, HEIGHT),
                              settings)
    # Rounding moves a few rays across an edge: most pixels are equal to float precision, and
    # the mean difference is far below that of a one-pixel shift of the image (about 5% of
    # the mean in the Cornell box at this size).
    assert np.mean(np.isclose(from_view, from_scene, rtol=1e-4, atol=1e-6)) > 0.9
    assert np.abs(from_view - from_scene).mean() < 2e-3 * from_scene.mean()


def test_orthographic_view_clipping_from_behind_the_eye(library: Any, cornell: Any) -> None:
    """A user orthographic view clips from a negative near distance (Blender: -clip_end/2);
    the native camera, which needs 0 < clip_start, is moved back along its axis instead: the
    same parallel rays, so the same image as the scene's orthographic camera up to rounding."""
    cornell.camera.data.type = "ORTHO"
    cornell.camera.data.ortho_scale = 2.4
    depsgraph = _depsgraph()
    ob = cornell.camera.evaluated_get(depsgraph)
    window = ob.calc_matrix_camera(depsgraph, x=WIDTH, y=HEIGHT)
    near, far = -10.0, 10.0
    window[2][2], window[2][3] = -2.0 / (far - near), -(far + near) / (far - near)
    camera = camera_from_matrices(ob.matrix_world.inverted(), window, False)
    assert camera.clip_start > 0.0 and camera.clip_end - camera.clip_start == pytest.approx(20.0)
    settings = settings_from_scene(cornell)
    from_view = fresh_render(depsgraph, View(camera, WIDTH, HEIGHT), settings)
    from_scene = fresh_render(depsgraph, View(convert_camera(cornell, depsgraph), WIDTH, HEIGHT),
                              settings)
    assert np.mean(np.isclose(from_view, from_scene, rtol=1e-4, atol=1e-6)) > 0.9
    assert np.abs(from_view - from_scene).mean() < 2e-3 * from_scene.mean()


def test_session_converges_to_preview_samples_and_stops(library: Any, cornell: Any) -> None:
    # The longer side, 40 pixels, at most 10: start passes at pixel sizes 4, then 2.
    cornell.stratum.preview_start_resolution = 10
    depsgraph = _depsgraph()
    session, view = _session(cornell, depsgraph)
    try:
        frame, seen = converge(session)
        assert frame.final and frame.samples == SAMPLES
        assert frame.pixels.shape == (HEIGHT, WIDTH, 4)
        assert frame.rect == (0.0, 0.0, float(WIDTH), float(HEIGHT))
        # The start passes came first, each one sample, drawn enlarged over the whole view.
        starts = [f for f in seen if not f.final and f.samples > 0]
        assert [f.pixels.shape for f in starts] == [
            (math.ceil(HEIGHT / n), math.ceil(WIDTH / n), 4) for n in (4, 2)]
        assert all(f.samples == 1 and f.rect == frame.rect for f in starts)
        # Then, maybe, the view's own resolution filling in over the last start pass.
        filling = [i for i, f in enumerate(seen) if f.samples == 0]
        assert all(seen[i].pixels.shape == frame.pixels.shape for i in filling)
        last_start = next(i for i, f in enumerate(seen) if f is starts[-1])
        assert all(i > last_start for i in filling)
        assert seen[-1] is frame
        # Idle: nothing runs, and polling starts nothing.
        assert session.running_renderers() == 0
        time.sleep(0.05)
        assert not session.poll() and session.frame() is frame
        # The converged frame is the fresh full render of the scene with the same settings.
        expected = fresh_render(depsgraph, view, replace(settings_from_scene(cornell)))
        np.testing.assert_array_equal(frame.pixels, expected)
    finally:
        session.free()


def test_viewport_adaptive_sampling_converges_to_the_adaptive_render(library: Any,
                                                                     cornell: Any) -> None:
    """With the viewport's own Noise Threshold on, the converged frame is the fresh render with
    those settings, whose pixels stopped at different counts (the F12 settings stay off)."""
    cornell.stratum.use_preview_adaptive_sampling = True
    cornell.stratum.preview_adaptive_threshold = 0.1
    cornell.stratum.preview_adaptive_min_samples = 4
    assert not cornell.stratum.use_adaptive_sampling
    depsgraph = _depsgraph()
    session, view = _session(cornell, depsgraph)
    try:
        frame, _ = converge(session)
        assert frame.final and frame.samples == SAMPLES
        settings = settings_from_scene(cornell)
        assert settings.native["use_adaptive_sampling"] == 1
        np.testing.assert_array_equal(frame.pixels, fresh_render(depsgraph, view, settings))
        counts = fresh_render(depsgraph, view, settings, None, "Debug Sample Count")
        assert counts.min() < SAMPLES <= counts.max(), (counts.min(), counts.max())
    finally:
        session.free()


def _move_box() -> None:
    bpy.data.objects["TallBox"].location.x += 0.12


def _recolour_white() -> None:
    material = bpy.data.materials["White"]
    bsdf = next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Base Color"].default_value = (0.2, 0.7, 0.9, 1.0)


def _dim_light() -> None:
    bpy.data.lights["Point"].energy = 60.0


def _move_camera() -> None:
    camera = bpy.data.objects["Camera"]
    camera.location.x += 0.2
    camera.rotation_euler.z += 0.05


EDITS: dict[str, tuple[Callable[[], None], str]] = {
    "move an object": (_move_box, "edits"),
    "change a material colour": (_recolour_white, "edits"),
    "change a light's power": (_dim_light, "edits"),
    "move the camera": (_move_camera, "edits"),
}


@pytest.mark.parametrize("name", list(EDITS))
def test_edit_restarts_and_converges_to_a_fresh_render(library: Any, cornell: Any,
                                                       name: str) -> None:
    edit, expected_kind = EDITS[name]
    depsgraph = _depsgraph()
    session, view = _session(cornell, depsgraph)
    try:
        before, _ = converge(session)
        generation = session.generation
        with recorded_updates() as updates:
            edit()
            depsgraph = _depsgraph()
        assert session.update(depsgraph, updates) == expected_kind
        view = camera_view(depsgraph)  # view_draw hands the (camera) view over again
        session.set_view(view)
        assert session.generation > generation
        after, _ = converge(session)
        assert after.generation == session.generation and after.samples == SAMPLES
        assert not np.array_equal(after.pixels, before.pixels), "the edit changed nothing"
        expected = fresh_render(depsgraph, view, settings_from_scene(cornell))
        np.testing.assert_array_equal(after.pixels, expected)
    finally:
        session.free()


def test_view_change_restarts(library: Any, cornell: Any) -> None:
    """Another view size (a resized viewport) restarts the render at that size, and an equal
    view does not restart it."""
    depsgraph = _depsgraph()
    session, _ = _session(cornell, depsgraph)
    try:
        converge(session)
        generation = session.generation
        session.set_view(camera_view(depsgraph))  # the same view again
        assert session.generation == generation and not session.poll()
        bigger = camera_view(depsgraph, WIDTH + 8, HEIGHT + 6)
        session.set_view(bigger)
        frame, _ = converge(session)
        assert frame.pixels.shape == (HEIGHT + 6, WIDTH + 8, 4)
        expected = fresh_render(depsgraph, bigger, settings_from_scene(cornell))
        np.testing.assert_array_equal(frame.pixels, expected)
    finally:
        session.free()


def test_border_renders_only_its_region(library: Any, cornell: Any) -> None:
    depsgraph = _depsgraph()
    session, view = _session(cornell, depsgraph)
    try:
        border = (7, 5, 20, 13)
        session.set_view(replace(view, border=border))
        frame, _ = converge(session)
        x, y, w, h = border
        assert frame.pixels.shape == (h, w, 4) and frame.rect == border
        full = fresh_render(depsgraph, view, settings_from_scene(cornell))
        np.testing.assert_array_equal(frame.pixels, full[y:y + h, x:x + w])
    finally:
        session.free()


def test_free_leaves_no_renderer_running(library: Any, cornell: Any) -> None:
    from stratum import native

    made: list[Any] = []

    def new_renderer(scene: Any) -> Any:
        made.append(native.Renderer(scene))
        return made[-1]

    depsgraph = _depsgraph()
    session = ViewportSession(new_renderer=new_renderer)
    session.update(depsgraph)
    session.set_settings(replace(settings_from_scene(cornell), samples=100000,
                                 compare_sampler="random"))
    session.set_view(camera_view(depsgraph))
    deadline = time.monotonic() + DEADLINE_S
    while session.running_renderers() < 2:  # both halves of the split view render
        session.poll()
        assert time.monotonic() < deadline
        time.sleep(0.01)
    from stratum.engine.viewport_session import running_sessions

    assert running_sessions() >= 1
    session.free()
    assert len(made) == 2 and all(r.closed for r in made)
    assert session.running_renderers() == 0 and not session.poll()
    assert running_sessions() == 0  # the other tests' sessions are freed too


SAMPLERS = ("random", "sobol", "halton_owen", "bluenoise", "zsobol", "fibonacci")


@pytest.mark.parametrize("sampler", SAMPLERS)
def test_crop_render_equals_the_full_render(library: Any, cornell: Any, sampler: str) -> None:
    """What the split view relies on: a crop of the frame renders, pixel for pixel, the same
    pixels of the full frame, for every sampler."""
    depsgraph = _depsgraph()
    settings = settings_from_scene(cornell)
    view = camera_view(depsgraph)
    full = fresh_render(depsgraph, view, settings, sampler)
    with SceneSync() as sync:
        sync.full(depsgraph)
        sync.scene.set_camera(view.camera)
        crop = {"crop_x": 13, "crop_y": 4, "crop_width": 21, "crop_height": 19}
        native_settings = settings.native | crop | {
            "width": WIDTH, "height": HEIGHT, "samples": SAMPLES, "sampler": sampler,
            "bvh": "dynamic"}
        with library.Renderer(sync.scene, **native_settings) as renderer:
            part = _render(renderer).reshape(19, 21, 4)
    np.testing.assert_array_equal(part, full[4:23, 13:34])


@pytest.mark.parametrize(("left", "right", "position"), [
    ("sobol", "random", 0.5), ("halton_owen", "bluenoise", 0.3)])
def test_split_view_parts_equal_single_sampler_frames(library: Any, cornell: Any, left: str,
                                                      right: str, position: float) -> None:
    depsgraph = _depsgraph()
    cornell.stratum.sampler = left
    cornell.stratum.use_split_view = True
    cornell.stratum.compare_sampler = right
    cornell.stratum.split_position = position
    settings = settings_from_scene(cornell)
    assert (settings.sampler, settings.compare_sampler) == (left, right)
    session, _ = _session(cornell, depsgraph)
    frames: dict[str, np.ndarray] = {}
    try:
        split, _ = converge(session)
        for sampler in (left, right):  # single-sampler viewport frames
            session.set_settings(replace(settings, sampler=sampler, compare_sampler=None))
            frames[sampler] = converge(session)[0].pixels
    finally:
        session.free()
    column = round(position * WIDTH)
    assert split.divider == pytest.approx(position * WIDTH)
    assert split.samples == SAMPLES and split.pixels.shape == (HEIGHT, WIDTH, 4)
    np.testing.assert_array_equal(split.pixels[:, :column], frames[left][:, :column])
    np.testing.assert_array_equal(split.pixels[:, column:], frames[right][:, column:])
    # The samplers differ, so the comparison shows something.
    assert not np.array_equal(frames[left], frames[right])


def test_denoiser_hook_sees_the_converged_frame_and_its_passes(library: Any,
                                                               cornell: Any) -> None:
    """set_denoiser (use_preview_denoising): called once, on the converged frame at the view's
    own resolution with the passes it asked for (composed across a split view's parts); the
    frame then shows what it returned. Start passes are not denoised."""
    cornell.stratum.preview_start_resolution = 10
    depsgraph = _depsgraph()
    calls: list[tuple[np.ndarray, dict[str, np.ndarray]]] = []

    def denoise(colour: np.ndarray, passes: dict[str, np.ndarray]) -> np.ndarray:
        calls.append((colour.copy(), passes))
        return np.full_like(colour, 0.25)

    session, view = _session(cornell, depsgraph, compare_sampler="random")
    session.set_denoiser(denoise, ("Normal",))
    try:
        frame, seen = converge(session)
    finally:
        session.free()
    assert len(calls) == 1 and not any(np.all(f.pixels == 0.25) for f in seen[:-1])
    colour, passes = calls[0]
    assert colour.shape == (HEIGHT, WIDTH, 4) and passes["Normal"].shape == (HEIGHT, WIDTH, 3)
    # The colour and the normals are those of the converged split frame.
    settings = settings_from_scene(cornell)
    half = WIDTH // 2
    for name, image in (("", colour), ("Normal", passes["Normal"])):
        np.testing.assert_array_equal(
            image[:, :half], fresh_render(depsgraph, view, settings, None, name)[:, :half])
        np.testing.assert_array_equal(
            image[:, half:], fresh_render(depsgraph, view, settings, "random", name)[:, half:])
    assert np.all(frame.pixels == 0.25) and frame.final


def _context(depsgraph: Any, window: Any, view_perspective: str = "CAMERA",
             **space: Any) -> Any:
    """What view_draw's context holds for view_from_context: a 3D view of WIDTH x HEIGHT
    looking through the scene camera with the window matrix given."""
    from types import SimpleNamespace

    ob = depsgraph.scene_eval.camera.evaluated_get(depsgraph)
    return SimpleNamespace(
        region=SimpleNamespace(width=WIDTH, height=HEIGHT),
        region_data=SimpleNamespace(view_matrix=ob.matrix_world.inverted(), window_matrix=window,
                                    view_perspective=view_perspective, is_perspective=True),
        space_data=SimpleNamespace(**space))


def test_camera_view_border_is_the_render_border_inside_the_camera_frame(
        library: Any, cornell: Any) -> None:
    """In camera view zoomed out by 2 (the window matrix's scale halved), the camera frame
    (square: the scene renders 256 x 256; its width fitted to the view's, 40) is 20 x 20
    pixels in the middle of the 40 x 30 view, x 10..30, y 5..25, and the scene's render
    border (the middle half of the frame) x 15..25, y 10..20."""
    from stratum.engine.viewport import view_from_context

    r = cornell.render
    r.use_border = True
    r.border_min_x = r.border_min_y = 0.25
    r.border_max_x = r.border_max_y = 0.75
    depsgraph = _depsgraph()
    ob = cornell.camera.evaluated_get(depsgraph)
    window = ob.calc_matrix_camera(depsgraph, x=WIDTH, y=HEIGHT)
    window[0][0] *= 0.5
    window[1][1] *= 0.5
    view = view_from_context(_context(depsgraph, window), depsgraph)
    assert (view.width, view.height, view.border) == (WIDTH, HEIGHT, (15, 10, 10, 10))
    # Outside camera view the view's own render border applies, as fractions of the view.
    view = view_from_context(_context(depsgraph, window, "PERSP", use_render_border=True,
                                      render_border_min_x=0.1, render_border_min_y=0.5,
                                      render_border_max_x=0.6, render_border_max_y=1.0),
                             depsgraph)
    assert view.border == (4, 15, 20, 15)


def test_half_float_safe_keeps_every_pixel_finite_in_rgba16f() -> None:
    from stratum.engine.viewport_draw import HALF_MAX, half_float_safe

    pixels = np.array([1e6, -1e6, np.nan, np.inf, -np.inf, 3.0, 65504.0], dtype=np.float32)
    safe = half_float_safe(pixels)
    assert np.all(np.isfinite(safe.astype(np.float16)))
    np.testing.assert_array_equal(safe, [HALF_MAX, -HALF_MAX, 0.0, HALF_MAX, -HALF_MAX, 3.0,
                                         65504.0])


def test_a_start_pass_resampled_to_the_view_pixels() -> None:
    """What shows through where the view's own resolution has no sample yet: the start pass
    frame (pixel size 4 over a 40 x 30 view: 10 x 8 pixels drawn over the whole view, 3.75
    view pixels high each) picked by nearest neighbour at each view pixel's centre."""
    small = np.arange(8 * 10 * 4, dtype=np.float32).reshape(8, 10, 4)
    frame = Frame(small, (0.0, 0.0, 40.0, 30.0), None, 1, False, 1, 1)
    out = resample(frame, (0, 0, 40, 30))
    assert out.shape == (30, 40, 4)
    np.testing.assert_array_equal(out[0, 0], small[0, 0])
    np.testing.assert_array_equal(out[29, 39], small[7, 9])  # y 29.5 / 3.75 -> 7
    np.testing.assert_array_equal(out[5, 13], small[1, 3])  # y 5.5 / 3.75 -> 1, x 13.5 / 4 -> 3
    # A border: the part of the frame under view pixels x 8..17, y 4..11.
    np.testing.assert_array_equal(resample(frame, (8, 4, 10, 8)), out[4:12, 8:18])


def test_use_preview_denoising_denoises_the_converged_frame(library: Any, cornell: Any) -> None:
    """use_preview_denoising: engine/denoise.py's filter on the converged frame, with the
    guide passes the library renders; with OIDN missing, the frame stays undenoised and the
    error (DenoiserUnavailable) reaches the caller, which view_draw reports once."""
    from stratum.engine import denoise
    from stratum.engine.viewport import denoise_preview, preview_denoiser

    assert preview_denoiser(cornell) == (None, ())
    cornell.stratum.use_preview_denoising = True
    denoiser, passes = preview_denoiser(cornell)
    assert denoiser is denoise_preview
    assert passes == tuple(name for name in denoise.library_guides() if name)
    depsgraph = _depsgraph()
    session, view = _session(cornell, depsgraph)
    session.set_denoiser(denoiser, passes)
    noisy = fresh_render(depsgraph, view, settings_from_scene(cornell))
    try:
        try:
            expected = denoise.denoise_rgba(noisy, *(
                fresh_render(depsgraph, view, settings_from_scene(cornell), None, name)
                for name in passes))
        except library.DenoiserUnavailable:
            with pytest.raises(library.DenoiserUnavailable):
                converge(session)
            frame = session.frame()
            assert frame is not None and frame.samples == SAMPLES
            np.testing.assert_array_equal(frame.pixels, noisy)
            return
        frame, _ = converge(session)
        np.testing.assert_array_equal(frame.pixels, expected)
        assert not np.array_equal(frame.pixels, noisy)
    finally:
        session.free()
