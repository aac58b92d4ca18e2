"""Blender images -> native textures, each image once per render.

Source of the pixels, in Blender's order of precedence:
  * packed (image.packed_file): the file's bytes (file_data) with its name (format by extension);
  * a file (image.filepath made absolute, relative to the image's library): OpenImageIO reads it;
  * generated or painted-in-memory images (no file): Image.pixels (rows bottom to top, as the
    C ABI takes them).
Colour space: image.colorspace_settings.name, converted by the native side with OpenColorIO using
Blender's own config (the one this Blender ships). Float pixel buffers are already scene-linear
in Blender's memory, so they are sent as "Non-Color" (no conversion).

Missing file: Cycles renders magenta (1, 0, 1) where an image cannot be loaded
(intern/cycles/scene/image.cpp, TEX_IMAGE_MISSING_R/G/B); so does Stratum, with a warning naming
the image. A colour space the native side does not know: a warning, then the image is read as
Blender's default for its kind (sRGB for byte images, linear for float ones).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from functools import lru_cache
from typing import Any

import bpy
import numpy as np

from .. import native

MISSING_RGBA = (1.0, 0.0, 1.0, 1.0)
INTERPOLATIONS = {"Closest": native.TEXTURE_CLOSEST, "Linear": native.TEXTURE_LINEAR,
                  "Cubic": native.TEXTURE_LINEAR, "Smart": native.TEXTURE_LINEAR}
EXTENSIONS = {"REPEAT": native.TEXTURE_REPEAT, "EXTEND": native.TEXTURE_EXTEND,
              "CLIP": native.TEXTURE_CLIP, "MIRROR": native.TEXTURE_MIRROR}


@lru_cache(maxsize=1)
def blender_ocio_config() -> str | None:
    """The OCIO config Blender itself uses: $OCIO if set (Blender honours it), else
    datafiles/colormanagement/config.ocio under the LOCAL resources (official builds and the bpy
    wheel) or the SYSTEM ones (Linux distribution packages, e.g. Debian's /usr/share/blender)."""
    env = os.environ.get("OCIO")
    if env and os.path.isfile(env):
        return env
    for kind in ("LOCAL", "SYSTEM"):
        root = bpy.utils.resource_path(kind)
        if not root:
            continue
        path = os.path.join(root, "datafiles", "colormanagement", "config.ocio")
        if os.path.isfile(path):
            return path
    return None


def _image_file_path(image: Any) -> str:
    return bpy.path.abspath(image.filepath, library=image.library)


def _file_name(image: Any) -> str:
    """A name whose extension tells OpenImageIO the packed file's format."""
    for candidate in (image.filepath, getattr(image.packed_file, "filepath", ""), image.name):
        base = os.path.basename(bpy.path.abspath(candidate)) if candidate else ""
        if os.path.splitext(base)[1]:
            return base
    fmt = str(getattr(image, "file_format", "PNG")).lower()
    return f"{image.name}.{ {'jpeg': 'jpg', 'open_exr': 'exr', 'targa': 'tga'}.get(fmt, fmt)}"


def _pixels(image: Any) -> np.ndarray:
    width, height = (int(v) for v in image.size)
    channels = int(image.channels)
    buf = np.empty(width * height * channels, dtype=np.float32)
    image.pixels.foreach_get(buf)
    return buf.reshape(height, width, channels)


def missing_texture(node: Any) -> native.Texture:
    return native.Texture(pixels=np.array([[MISSING_RGBA]], dtype=np.float32),
                          color_space="Non-Color", interpolation=native.TEXTURE_CLOSEST,
                          extension=EXTENSIONS.get(node.extension, native.TEXTURE_REPEAT))


def describe_image(node: Any, warn: Callable[[str], None]) -> native.Texture:
    """The native texture of an Image Texture node (magenta with a warning when the image
    cannot be read, as Cycles)."""
    image = node.image
    if node.interpolation not in INTERPOLATIONS:
        warn(f"interpolation {node.interpolation} of '{node.name}' is rendered as Linear")
    if getattr(node, "projection", "FLAT") != "FLAT":
        warn(f"projection {node.projection} of '{node.name}' is rendered as Flat")
    common: dict[str, Any] = {
        "ocio_config": blender_ocio_config(),
        "interpolation": INTERPOLATIONS.get(node.interpolation, native.TEXTURE_LINEAR),
        "extension": EXTENSIONS.get(node.extension, native.TEXTURE_REPEAT),
        "color_space": str(image.colorspace_settings.name),
    }
    if image.source == "TILED":
        warn(f"image '{image.name}' is a UDIM tile set, which is not supported; rendered "
             "magenta")
        return missing_texture(node)
    if image.packed_file is not None:
        return native.Texture(file_data=bytes(image.packed_file.data),
                              file_name=_file_name(image), **common)
    if image.source in {"FILE", "SEQUENCE", "MOVIE"} and image.filepath:
        if image.source != "FILE":
            warn(f"image '{image.name}' is a {image.source.lower()}; its file is read as one "
                 "still image")
        if getattr(image, "is_dirty", False) and image.has_data:
            warn(f"image '{image.name}' has unsaved changes; rendering its pixels in memory")
        else:
            path = _image_file_path(image)
            if not os.path.isfile(path):
                warn(f"image '{image.name}': file '{path}' not found; rendered magenta as Cycles "
                     "does")
                return missing_texture(node)
            return native.Texture(path=path, **common)
    width, height = (int(v) for v in image.size)
    if width == 0 or height == 0 or not image.has_data:
        warn(f"image '{image.name}' has no pixels; rendered magenta as Cycles does")
        return missing_texture(node)
    if image.is_float:
        common["color_space"] = "Non-Color"  # Blender keeps float buffers scene-linear
    return native.Texture(pixels=_pixels(image), **common)


class TextureTable:
    """Native texture ids, one per (image, interpolation, extension) per render."""

    def __init__(self, scene: Any, warn: Callable[[Any, str], None]) -> None:
        self._scene = scene
        self._warn = warn  # (image node, message)
        self._ids: dict[tuple[int, str, str], int] = {}
        self.count = 0

    def id_for(self, node: Any) -> int:
        image = node.image
        key = (image.as_pointer() if image is not None else 0, str(node.interpolation),
               str(node.extension))
        found = self._ids.get(key)
        if found is not None:
            return found
        if image is None:
            self._warn(node, f"Image Texture '{node.name}' has no image; rendered magenta as "
                             "Cycles does")
            texture = missing_texture(node)
        else:
            texture = describe_image(node, lambda message: self._warn(node, message))
        texture_id = self._add(node, texture)
        self._ids[key] = texture_id
        self.count += 1
        return texture_id

    def _add(self, node: Any, texture: native.Texture) -> int:
        try:
            return self._scene.add_texture(texture)
        except native.StratumError as exc:
            if exc.status == native.ERROR_IO:
                self._warn(node, f"image '{node.image.name}' cannot be read ({exc}); rendered "
                                 "magenta as Cycles does")
                return self._scene.add_texture(missing_texture(node))
            if exc.status != native.ERROR_INVALID_ARGUMENT or texture.pixels is not None and \
                    texture.color_space == "Non-Color":
                raise
            fallback = "Non-Color" if node.image.is_float else "sRGB"
            self._warn(node, f"image '{node.image.name}': {exc}; read as '{fallback}' instead")
            texture.color_space = fallback
            return self._scene.add_texture(texture)
