"""Draws a viewport session's Frame in the 3D view with the `gpu` module (Blender 3.4 to 5.0;
no bgl): the pixels become an RGBA16F texture drawn through Blender's display-space shader
(view transform, look, exposure of the scene's colour management) over the frame's
rectangle, and a thin divider line marks a split view.

Imported only by view_draw: background Blender has no GPU module to draw with.
"""

from __future__ import annotations

from typing import Any

import gpu
import numpy as np
from gpu_extras.batch import batch_for_shader
from gpu_extras.presets import draw_texture_2d

from .viewport_session import Frame

# Largest finite half float: a brighter pixel (an emitter seen directly) would become +inf in
# an RGBA16F texture, and the display transform turns inf into NaN (black) on some drivers.
HALF_MAX = 65504.0
DIVIDER_RGBA = (1.0, 1.0, 1.0, 0.8)
DIVIDER_WIDTH = 1.0  # view pixels (times the UI scale)


def half_float_safe(pixels: np.ndarray) -> np.ndarray:
    """The pixels with what RGBA16F cannot hold made finite: above HALF_MAX clamped to it,
    NaN to 0."""
    return np.nan_to_num(np.clip(pixels, -HALF_MAX, HALF_MAX), nan=0.0, posinf=HALF_MAX,
                         neginf=-HALF_MAX)


def _uniform_color_shader() -> Any:
    try:
        return gpu.shader.from_builtin("UNIFORM_COLOR")  # 4.0+
    except ValueError:
        return gpu.shader.from_builtin("2D_UNIFORM_COLOR")  # 3.x


class FrameDrawer:
    """Holds the texture of the last frame drawn and uploads a new one only when the frame's
    pixels changed (Frame.serial)."""

    def __init__(self) -> None:
        self._texture: Any | None = None
        self._serial = -1

    def draw(self, engine: Any, scene: Any, frame: Frame, ui_scale: float = 1.0) -> None:
        if frame.serial != self._serial or self._texture is None:
            height, width = frame.pixels.shape[:2]
            data = np.ascontiguousarray(half_float_safe(frame.pixels), dtype=np.float32)
            buffer = gpu.types.Buffer("FLOAT", width * height * 4, data.ravel())
            self._texture = gpu.types.GPUTexture((width, height), format="RGBA16F", data=buffer)
            self._serial = frame.serial
        x, y, w, h = frame.rect
        # The renderer's alpha is premultiplied (transparent film): blend as such.
        gpu.state.blend_set("ALPHA_PREMULT")
        engine.bind_display_space_shader(scene)
        draw_texture_2d(self._texture, (x, y), w, h)
        engine.unbind_display_space_shader()
        if frame.divider is not None:
            self._draw_divider(frame.divider, y, h, DIVIDER_WIDTH * ui_scale)
        gpu.state.blend_set("NONE")

    @staticmethod
    def _draw_divider(x: float, y: float, height: float, width: float) -> None:
        x0, x1 = x - 0.5 * width, x + 0.5 * width
        shader = _uniform_color_shader()
        batch = batch_for_shader(shader, "TRIS", {"pos": [(x0, y), (x1, y), (x1, y + height),
                                                          (x0, y + height)]},
                                 indices=[(0, 1, 2), (0, 2, 3)])
        gpu.state.blend_set("ALPHA")
        shader.bind()
        shader.uniform_float("color", DIVIDER_RGBA)
        batch.draw(shader)

    def free(self) -> None:
        self._texture = None
        self._serial = -1
