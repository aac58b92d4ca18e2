"""`Renderer`: renders a Scene on native worker threads; `Progress` is what it reports
while it runs."""

from __future__ import annotations

import ctypes
import os
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from .abi import _Progress
from .library import _check, _Handle
from .marshalling import _float_ptr
from .scene import Scene
from .settings import passes


@dataclass(frozen=True)
class Progress:
    done: bool
    cancelled: bool
    samples_done: int
    samples_total: int
    update_serial: int
    rays: float
    build_seconds: float
    render_seconds: float
    fraction_done: float
    # Each pixel holds samples_done or samples_in_progress samples; samples_average is their
    # mean over the image from the work finished, moving as tiles finish (stratum.h).
    samples_in_progress: int
    samples_average: float
    # What the render's features report, by name ("light_tree.seconds", "radiosity.patches",
    # "guiding.nodes", ...: stratum/render.h lists them); 0.0 for a feature the render does not use.
    counters: Mapping[str, float] = field(default_factory=dict)

    def counter(self, name: str) -> float:
        """The counter `name`; 0.0 when the progress holds none of that name (a Progress made
        without counters)."""
        return self.counters.get(name, 0.0)


class Renderer(_Handle):
    """Renders a Scene on native worker threads. Edits of the scene made after the renderer
    (Scene.set_instance, set_material, ...) reach it at its next start(); the scene may be
    closed before it."""

    _destroy_name = "stratum_renderer_destroy"

    def __init__(self, scene: Scene, **settings: int | float | str) -> None:
        super().__init__()
        _check(self._lib,
               self._lib.stratum_renderer_create(scene.handle, ctypes.byref(self._ptr)),
               "stratum_renderer_create")
        self._width = 0
        self._height = 0
        self._crop_width = 0  # a border render reads and writes only its region
        self._crop_height = 0
        self._started = False
        for name, value in settings.items():
            self.set(name, value)

    def close(self) -> None:
        # A render still running must stop before its handle is freed.
        ptr = getattr(self, "_ptr", None)
        if ptr and getattr(self, "_started", False):
            done = ctypes.c_int32(0)
            self._lib.stratum_renderer_cancel(ptr)
            self._lib.stratum_renderer_wait(ptr, 60000, ctypes.byref(done))
        super().close()

    def set(self, name: str, value: int | float | str) -> None:
        """Sets a named setting; the C function is chosen by the Python type of value."""
        key = name.encode()
        if isinstance(value, bool | int | np.integer):
            status = self._lib.stratum_renderer_set_int(self.handle, key, int(value))
            if name in ("width", "height", "crop_width", "crop_height"):
                setattr(self, f"_{name}", int(value))
        elif isinstance(value, float | np.floating):
            status = self._lib.stratum_renderer_set_float(self.handle, key, float(value))
        elif isinstance(value, str):
            status = self._lib.stratum_renderer_set_string(self.handle, key, value.encode())
        else:
            raise TypeError(f"setting {name!r}: unsupported type {type(value).__name__}")
        _check(self._lib, status, f"setting {name}")

    @property
    def width(self) -> int:
        return self._width

    @property
    def height(self) -> int:
        return self._height

    @property
    def image_size(self) -> tuple[int, int]:
        """(width, height) of the image read_pixels returns: the border region if one is set."""
        if self._crop_width > 0 and self._crop_height > 0:
            return self._crop_width, self._crop_height
        return self._width, self._height

    def start(self) -> None:
        _check(self._lib, self._lib.stratum_renderer_start(self.handle), "stratum_renderer_start")
        self._started = True

    def notices(self) -> list[str]:
        """What the render cannot show and why, one sentence each; [] when nothing: what the
        chosen estimator cannot render in this scene (e.g. BSDF sampling alone never finds a
        point light; set by start()), placements skipped by the scene build (added when the
        build ends) and samples or rays dropped as not finite (added when the render ends)."""
        out = ctypes.c_char_p()
        _check(self._lib, self._lib.stratum_renderer_notices(self.handle, ctypes.byref(out)),
               "stratum_renderer_notices")
        text = out.value.decode("utf-8", "replace") if out.value else ""
        return [line for line in text.split("\n") if line]

    def cancel(self) -> None:
        _check(self._lib, self._lib.stratum_renderer_cancel(self.handle),
               "stratum_renderer_cancel")

    def wait(self, timeout_ms: int) -> bool:
        """Waits up to timeout_ms; True when the render has ended."""
        done = ctypes.c_int32(0)
        _check(self._lib,
               self._lib.stratum_renderer_wait(self.handle, int(timeout_ms), ctypes.byref(done)),
               "stratum_renderer_wait")
        return bool(done.value)

    def progress(self) -> Progress:
        p = _Progress()
        _check(self._lib, self._lib.stratum_renderer_progress(self.handle, ctypes.byref(p)),
               "stratum_renderer_progress")
        return Progress(
            done=bool(p.done),
            cancelled=bool(p.cancelled),
            samples_done=int(p.samples_done),
            samples_total=int(p.samples_total),
            update_serial=int(p.update_serial),
            rays=float(p.rays),
            build_seconds=float(p.build_seconds),
            render_seconds=float(p.render_seconds),
            fraction_done=float(p.fraction_done),
            samples_in_progress=int(p.samples_in_progress),
            samples_average=float(p.samples_average),
            counters=self._counters(),
        )

    def _counters(self) -> dict[str, float]:
        counters: dict[str, float] = {}
        name = ctypes.c_char_p()
        value = ctypes.c_double()
        for index in range(self._lib.stratum_progress_counter_count()):
            status = self._lib.stratum_renderer_progress_counter(
                self.handle, index, ctypes.byref(name), ctypes.byref(value))
            _check(self._lib, status, "stratum_renderer_progress_counter")
            counters[(name.value or b"").decode()] = float(value.value)
        return counters

    def radiosity_iterations(self) -> np.ndarray:
        """The radiosity solve of the last render, one row per solver iteration: the textbook's
        Delta E, Delta E over the mean radiance, the residual (radiance) and the solver's seconds
        so far (stratum/render.h); no rows for the other integrators."""
        rows = int(self.progress().counter("radiosity.iterations"))
        out = np.empty((rows, 4), dtype=np.float64)
        _check(self._lib,
               self._lib.stratum_renderer_read_radiosity_iterations(
                   self.handle, out.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), out.size),
               "stratum_renderer_read_radiosity_iterations")
        return out

    def read_pixels(self, out: np.ndarray | None = None) -> np.ndarray:
        """Copies the current image (linear RGBA, rows bottom to top) into `out` (a contiguous
        float32 array of width*height*4 values, any shape) with one native copy."""
        if out is None:
            width, height = self.image_size
            out = np.empty(width * height * 4, dtype=np.float32)
        if out.dtype != np.float32 or not out.flags.c_contiguous or not out.flags.writeable:
            raise ValueError("read_pixels: out must be a writeable C-contiguous float32 array")
        _check(self._lib,
               self._lib.stratum_renderer_read_pixels(self.handle, _float_ptr(out), out.size),
               "stratum_renderer_read_pixels")
        return out

    def read_pass(self, name: str) -> np.ndarray:
        """Copies the current values of pass `name` (see passes(); the render holds Combined
        and the passes its setting `passes` names) as a (height, width, channels) float32
        array of the image's size, row 0 at the bottom as in read_pixels."""
        channels = {p.name: p.channels for p in passes()}
        if name not in channels:
            raise ValueError(f"read_pass: unknown pass {name!r}; passes: {', '.join(channels)}")
        width, height = self.image_size
        out = np.empty((height, width, channels[name]), dtype=np.float32)
        _check(self._lib,
               self._lib.stratum_renderer_read_pass(self.handle, name.encode(), _float_ptr(out),
                                                    out.size),
               "stratum_renderer_read_pass")
        return out

    def read_lightgroup(self, group: int) -> np.ndarray:
        """Copies the current RGB of light group `group` (1..the setting `lightgroups`) as a
        (height, width, 3) float32 array, row 0 at the bottom as in read_pixels."""
        width, height = self.image_size
        out = np.empty((height, width, 3), dtype=np.float32)
        _check(self._lib,
               self._lib.stratum_renderer_read_lightgroup(self.handle, group, _float_ptr(out),
                                                          out.size),
               "stratum_renderer_read_lightgroup")
        return out

    def write_image(self, path: str | os.PathLike[str]) -> None:
        _check(self._lib,
               self._lib.stratum_renderer_write_image(self.handle, os.fsencode(path)),
               "stratum_renderer_write_image")

    def read_sums(self) -> bytes:
        """The exact sums of the last render (ended, not cancelled) of its sample indices
        [sample_offset, sample_offset + sample_count): bytes another renderer of the same frame
        adds with add_sums (stratum.h "one frame's samples over many renders")."""
        size = ctypes.c_size_t(0)
        _check(self._lib, self._lib.stratum_renderer_sums_size(self.handle, ctypes.byref(size)),
               "stratum_renderer_sums_size")
        out = ctypes.create_string_buffer(size.value)
        _check(self._lib, self._lib.stratum_renderer_read_sums(self.handle, out, size.value),
               "stratum_renderer_read_sums")
        return out.raw

    def add_sums(self, sums: bytes) -> None:
        """Adds the sums of a render of an adjacent sample range of this frame (read_sums);
        a renderer that has rendered nothing takes them as its image. The image and passes
        then show both ranges, bit-identical to one render of them."""
        _check(self._lib, self._lib.stratum_renderer_add_sums(self.handle, sums, len(sums)),
               "stratum_renderer_add_sums")
