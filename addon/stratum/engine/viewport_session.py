"""The Rendered viewport's session: the live native scene of a depsgraph, the renderers that
refine the view, and the latest frame, without any GPU (viewport_draw.py draws the frames).

    session = ViewportSession()
    session.update(depsgraph, updates)   # RenderEngine.view_update: export or live edits
    session.set_view(view)               # view_draw: camera, size, border (view.py)
    session.set_settings(settings)       # samples, samplers, split view, start pixel size
    frame = session.frame()              # the newest pixels; never waits on a renderer
    refining = session.poll()            # True while something renders or is to start
    session.free()                       # no renderer left running

Every change (a scene edit, another view, other settings) cancels the renderers and starts them
again once they have stopped; nothing here waits on a renderer (wait(0) only), so the UI thread
that calls it never blocks. A restart first renders start passes, as Cycles does: one sample at
a pixel size N chosen so that the view's longer side is at most `start_resolution` pixels, then
one at N/2, N/4, ... (each about 4 times the work of the previous one: all of them together
cost about a third of the last), then the view's own resolution (pixel size 1) up to
`samples`; then the renderers end and the session is idle: no CPU is used until the next
change. A frame is replaced only once the stage that follows it has a whole sample in every
pixel, so an edit never shows a black or half-filled image.

Split view: the rendered rectangle (the view, or its border) is cut at `split_position`; the
left part is rendered by a renderer with `sampler`, the right by one with `compare_sampler`, both
on the same native scene, at the same sample count and seed, each a border (crop) render of the
same frame. A crop render's pixels equal the same pixels of a full render (the camera and the
sampler see full-frame coordinates: native renderer.cpp), so each part equals, pixel for pixel,
a single-sampler frame of its sampler.

Denoising hook (use_preview_denoising): set_denoiser(denoise, passes) makes the view's own
resolution render also hold the named passes (the renderer setting `passes`, e.g. the
denoiser's albedo and normal); when that stage has converged, the frame shown is
denoise(colour (h, w, 4), {pass name: (h, w, channels)}), each array composed from the lanes
as the colour is (a split view's parts stay each its own sampler's). Start passes are never
denoised.
"""

from __future__ import annotations

import math
import time
import weakref
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .. import native
from ..export.common import ExportSummary
from ..export.sync import SceneSync
from ..export.updates import IdUpdate

Rect = tuple[int, int, int, int]  # x, y, width, height in pixels, bottom-left origin
# denoise(colour (h, w, 4), {pass name: (h, w, channels)}) -> the colour to show (h, w, 4)
Denoiser = Callable[[np.ndarray, dict[str, np.ndarray]], np.ndarray]

# While a pass fills in tiles, its pixels are copied for display at most this often.
REREAD_SECONDS = 0.25
# Setting names the session decides itself: the view gives the frame, the session the rest.
VIEW_SETTINGS = ("width", "height", "crop_x", "crop_y", "crop_width", "crop_height")


@dataclass(frozen=True)
class View:
    """What the 3D view shows: its camera, its size in pixels, and the region of it to render
    (None: all of it)."""

    camera: native.Camera
    width: int
    height: int
    border: Rect | None = None

    def key(self) -> tuple[Any, ...]:
        from ..export.common import comparable

        return (comparable(self.camera), self.width, self.height, self.border)


@dataclass(frozen=True)
class ViewportSettings:
    """The renderers' settings: `native` holds every native setting but the frame's (seed,
    bounces, integrator, threads, ...; `samples` and `sampler` are the fields below)."""

    samples: int = 16
    sampler: str = "sobol"
    compare_sampler: str | None = None  # None: no split view
    split_position: float = 0.5  # 0..1 of the rendered width, from its left
    start_resolution: int = 0  # longer side of the first start pass, pixels; 0: none
    native: dict[str, int | float | str] = field(default_factory=dict)


@dataclass
class Frame:
    """The newest image: pixels (height, width, 4) float32, linear RGBA, rows bottom to top, to
    be drawn over `rect` (x, y, width, height, in view pixels: the start pass is drawn
    enlarged); `divider`: the view x of the split line, None without a split."""

    pixels: np.ndarray
    rect: tuple[float, float, float, float]
    divider: float | None
    samples: int  # samples done in every pixel (0: the first pass filling in over a start pass)
    final: bool  # at the view's own resolution with a sample in every pixel
    generation: int  # counts restarts: a frame of generation g shows the scene and view of g
    serial: int  # changes whenever the pixels do


@dataclass
class _Lane:
    """One renderer and the columns [x0, x1) of the view it renders (view pixels)."""

    renderer: Any
    sampler: str
    x0: int
    x1: int
    serial: int = -1
    started: bool = False


class ViewportSession:
    def __init__(self, new_scene: Callable[[], Any] = native.Scene,
                 new_renderer: Callable[[Any], Any] = native.Renderer) -> None:
        _sessions.add(self)
        self._freed = False
        self._sync = SceneSync(new_scene, require_camera=False, viewport=True)
        self._new_renderer = new_renderer
        self._lanes: list[_Lane] = []
        self._retired: list[_Lane] = []  # cancelled lanes of a replaced scene, to close
        self._view: View | None = None
        self._settings = ViewportSettings()
        self._exported = False
        self._restart = False  # a change waits for the renderers to stop
        self._stage = 0  # the running stage's pixel size (1: the view's own); 0: idle
        self._generation = 0
        self._frame: Frame | None = None
        self._read_at = 0.0  # time.monotonic() of the last read of the pixels
        self._read_stage_size = 0  # the stage (pixel size) they were read from
        self._serial = 0
        self._denoise: Denoiser | None = None
        self._denoise_passes: tuple[str, ...] = ()
        self.last_summary: ExportSummary | None = None

    # ---- changes -------------------------------------------------------------------------

    def update(self, depsgraph: Any, updates: Iterable[IdUpdate] | None = None) -> str:
        """Brings the native scene in step with `depsgraph`: a full export the first time and
        whenever the changes cannot be live edits, else live edits. Returns what was done:
        "full", "edits" or "" (nothing changed for the renderer). Raises ExportError as
        SceneSync does; the session then exports in full at the next update."""
        if not self._exported:
            return self._full(depsgraph)
        result = self._sync.update(depsgraph, updates)
        if result.needs_full:
            return self._full(depsgraph)
        if result.edits:
            self._apply_camera()  # the scene camera may have been sent over the view's
            self._request_restart()
            return "edits"
        return ""

    def _full(self, depsgraph: Any) -> str:
        self._retire_lanes()
        self._exported = False
        self.last_summary = self._sync.full(depsgraph)
        self._exported = True
        self._apply_camera()
        self._request_restart()
        return "full"

    def set_view(self, view: View) -> None:
        if self._view is not None and self._view.key() == view.key():
            return
        self._view = view
        self._apply_camera()
        self._request_restart()

    def set_settings(self, settings: ViewportSettings) -> None:
        if settings == self._settings:
            return
        split_changed = (settings.compare_sampler, settings.sampler) != \
            (self._settings.compare_sampler, self._settings.sampler)
        self._settings = settings
        if split_changed:
            self._retire_lanes()  # other samplers per lane: lanes are made anew
        self._request_restart()

    def set_denoiser(self, denoise: Denoiser | None, passes: tuple[str, ...] = ()) -> None:
        """The denoiser applied to converged frames (module docstring); None: none."""
        if (denoise, passes) == (self._denoise, self._denoise_passes):
            return
        self._denoise, self._denoise_passes = denoise, passes
        self._request_restart()

    def _apply_camera(self) -> None:
        if self._exported and self._view is not None:
            self._sync.scene.set_camera(self._view.camera)

    def _request_restart(self) -> None:
        self._generation += 1
        self._restart = True
        for lane in self._lanes:
            lane.renderer.cancel()

    def _retire_lanes(self) -> None:
        for lane in self._lanes:
            lane.renderer.cancel()
            self._retired.append(lane)
        self._lanes = []

    # ---- progress --------------------------------------------------------------------------

    @property
    def generation(self) -> int:
        return self._generation

    @property
    def converged(self) -> bool:
        return self._stage == 0 and not self._restart and self._frame is not None

    def poll(self) -> bool:
        """Moves the session on without waiting: closes renderers that have stopped, starts the
        next stage when the previous one has ended. True while rendering or about to."""
        self._retired = [lane for lane in self._retired if not _close_if_stopped(lane)]
        if not self._exported or self._view is None:
            return False
        if self._restart:
            if not all(_stopped(lane) for lane in self._lanes):
                return True
            self._restart = False
            self._start_stage(self._start_pixel_size())
            return True
        if self._stage and all(_stopped(lane) for lane in self._lanes):
            self._read_stage(ended=True)
            if self._stage > 1:
                self._start_stage(self._stage // 2)
                return True
            self._stage = 0
            self._finish_frame()
        return self._stage != 0

    def frame(self) -> Frame | None:
        """The newest frame (None before the first); reads the renderers' pixels if they
        changed since, without waiting. Every stage's image is returned by at least one call:
        a call whose poll() ended a stage returns that stage's last image."""
        serial = self._serial
        self.poll()
        if self._serial == serial and self._stage and not self._restart:
            self._read_stage()
        return self._frame

    # ---- stages -----------------------------------------------------------------------------

    def _start_pixel_size(self) -> int:
        """The first stage's pixel size: the smallest that brings the view's longer side to at
        most start_resolution pixels (1: no start pass)."""
        view, resolution = self._view, self._settings.start_resolution
        assert view is not None
        if resolution <= 0:
            return 1
        return max(1, math.ceil(max(view.width, view.height) / resolution))

    def _stage_geometry(self, n: int) -> tuple[int, int, Rect, float]:
        """(width, height, rendered rectangle, split column) of the frame of the stage of pixel
        size n, in its own pixels: the view at 1/n of its resolution, rounded up."""
        view = self._view
        assert view is not None
        border = view.border or (0, 0, view.width, view.height)
        width, height = math.ceil(view.width / n), math.ceil(view.height / n)
        x0, y0 = border[0] // n, border[1] // n
        x1 = min(math.ceil((border[0] + border[2]) / n), width)
        y1 = min(math.ceil((border[1] + border[3]) / n), height)
        split = x0 + self._settings.split_position * (x1 - x0)
        return width, height, (x0, y0, max(x1 - x0, 1), max(y1 - y0, 1)), split

    def _ensure_lanes(self) -> None:
        if self._lanes:
            return
        s = self._settings
        samplers = [s.sampler] if s.compare_sampler is None else [s.sampler, s.compare_sampler]
        self._lanes = [_Lane(self._new_renderer(self._sync.scene), sampler, 0, 0)
                       for sampler in samplers]

    def _start_stage(self, n: int) -> None:
        self._ensure_lanes()
        width, height, rect, split = self._stage_geometry(n)
        x, y, w, h = rect
        column = min(max(round(split), x), x + w)
        bounds = [(x, x + w)] if len(self._lanes) == 1 else [(x, column), (column, x + w)]
        s = self._settings
        for lane, (x0, x1) in zip(self._lanes, bounds, strict=True):
            lane.x0, lane.x1, lane.serial = x0, x1, -1
            if x1 <= x0:
                continue  # the split leaves this side empty
            r = lane.renderer
            for name, value in s.native.items():
                if name not in VIEW_SETTINGS and name not in ("samples", "sampler"):
                    r.set(name, value)
            r.set("bvh", "dynamic")  # a transform edit is a top-level recommit
            r.set("sampler", lane.sampler)
            r.set("samples", 1 if n > 1 else s.samples)
            r.set("passes", ",".join(self._denoise_passes) if n == 1 and self._denoise else "")
            r.set("width", width)
            r.set("height", height)
            whole = (x0, y, x1 - x0, h) == (0, 0, width, height)
            for name, value in zip(("crop_x", "crop_y", "crop_width", "crop_height"),
                                   (0, 0, 0, 0) if whole else (x0, y, x1 - x0, h), strict=True):
                r.set(name, value)
            r.start()
            lane.started = True
        self._stage = n

    def _active(self) -> list[_Lane]:
        return [lane for lane in self._lanes if lane.x1 > lane.x0]

    def _read_stage(self, ended: bool = False) -> None:
        """Makes the running stage's image the frame once every pixel has a sample, and
        re-reads it when a renderer published more: at once for more samples in every pixel
        or when the stage has `ended`, else (tiles of the next pass) at most every
        REREAD_SECONDS, so that the UI thread does not copy the image at every redraw."""
        lanes = self._active()
        if not lanes:
            return
        progress = [lane.renderer.progress() for lane in lanes]
        if any(p.cancelled for p in progress):
            return
        samples = min(p.samples_done for p in progress)
        shown = self._frame
        # Before every pixel has a sample the previous frame stays; only the view's own
        # resolution, which takes longest, fills in tile by tile over the start passes.
        if samples < 1 and (self._stage != 1 or shown is None
                            or shown.generation != self._generation):
            return
        if all(p.update_serial == lane.serial for p, lane in zip(progress, lanes, strict=True)):
            return
        now = time.monotonic()
        if not ended and shown is not None and shown.generation == self._generation and \
                self._read_stage_size == self._stage and shown.samples == samples and \
                now - self._read_at < REREAD_SECONDS:
            return
        self._read_at, self._read_stage_size = now, self._stage
        width, height, rect, split = self._stage_geometry(self._stage)
        x, y, w, h = rect
        pixels = self._compose(lambda renderer, out: renderer.read_pixels(out), 4, h)
        for p, lane in zip(progress, lanes, strict=True):
            lane.serial = p.update_serial
        view = self._view
        assert view is not None
        sx, sy = view.width / width, view.height / height
        if samples < 1 and shown is not None:
            # A pixel all zero (RGBA) has no sample yet, or is transparent black: there the
            # start pass shows through until the pass ends.
            pixels = np.where(np.any(pixels != 0.0, axis=2, keepdims=True), pixels,
                              resample(shown, (x, y, w, h)))
        divider = split * sx if len(self._lanes) > 1 else None
        self._serial += 1
        self._frame = Frame(pixels, (x * sx, y * sy, w * sx, h * sy), divider, samples,
                            self._stage == 1 and samples >= 1, self._generation, self._serial)

    def _compose(self, read: Callable[[Any, np.ndarray], Any], channels: int,
                 height: int) -> np.ndarray:
        """One image of the running stage's rendered rectangle from its lanes' parts."""
        lanes = self._active()
        x = lanes[0].x0
        out = np.empty((height, lanes[-1].x1 - x, channels), dtype=np.float32)
        for lane in lanes:
            part = np.empty((height, lane.x1 - lane.x0, channels), dtype=np.float32)
            read(lane.renderer, part)
            out[:, lane.x0 - x:lane.x1 - x] = part
        return out

    def _finish_frame(self) -> None:
        frame = self._frame
        if self._denoise is None or frame is None or not frame.final:
            return
        height = frame.pixels.shape[0]
        channels = {p.name: p.channels for p in native.passes()}
        passes = {name: self._compose(_pass_reader(name), channels[name], height)
                  for name in self._denoise_passes}
        self._serial += 1
        self._frame = replace(frame, pixels=self._denoise(frame.pixels, passes),
                              serial=self._serial)

    # ---- end ---------------------------------------------------------------------------------

    def free(self) -> None:
        """Cancels and closes every renderer (closing joins a cancelled render, which ends
        within one sample of its pixels) and the native scene."""
        self._retire_lanes()
        for lane in self._retired:
            lane.renderer.close()
        self._retired = []
        self._sync.close()
        self._exported = False
        self._stage = 0
        self._restart = False
        self._freed = True

    def running_renderers(self) -> int:
        """How many of the session's renderers have a render running (for tests)."""
        return sum(not _stopped(lane) for lane in self._lanes + self._retired)


_sessions: weakref.WeakSet[ViewportSession] = weakref.WeakSet()


def running_sessions() -> int:
    """How many sessions exist and are not freed (for UI tests: leaving Rendered shading frees
    the engine, whose session must then be gone or freed, with no renderer left)."""
    return sum(not session._freed for session in list(_sessions))


def resample(frame: Frame, rect: Rect) -> np.ndarray:
    """The frame's pixels, nearest neighbour, at the view pixels of `rect`."""
    fx, fy, fw, fh = frame.rect
    rows, columns = frame.pixels.shape[:2]
    x, y, w, h = rect
    i = np.clip(((np.arange(w) + x + 0.5 - fx) * columns / fw).astype(np.intp), 0, columns - 1)
    j = np.clip(((np.arange(h) + y + 0.5 - fy) * rows / fh).astype(np.intp), 0, rows - 1)
    return frame.pixels[j[:, None], i[None, :]]


def _pass_reader(name: str) -> Callable[[Any, np.ndarray], None]:
    def read(renderer: Any, out: np.ndarray) -> None:
        out[...] = renderer.read_pass(name)

    return read


def _stopped(lane: _Lane) -> bool:
    """True when the lane's renderer has no render running (never started, ended or
    cancelled and stopped)."""
    return not lane.started or lane.renderer.wait(0)


def _close_if_stopped(lane: _Lane) -> bool:
    if _stopped(lane):
        lane.renderer.close()
        return True
    return False
