"""Blender images -> native textures, each image once per render.

Source of the pixels, in Blender's order of precedence:
  * packed (image.packed_file): the file's bytes (file_data) with its name (format by extension);
  * a file (image.filepath made absolute, relative to the image's library): OpenImageIO reads it;
  * generated or painted-in-memory images (no file): Image.pixels (rows bottom to top, as the
    C ABI takes them).
Colour space: image.colorspace_settings.name, converted by the native side with OpenColorIO using
Blender's own config (the one this Blender ships). Float pixel buffers are already scene-linear
(and premultiplied) in Blender's memory, so they are sent straight-alpha as "Non-Color" (no
conversion). A colour space the native side cannot convert because its OpenColorIO cannot read
Blender 4.x/5.x's config (color_management.py) is converted here with Blender's PyOpenColorIO:
the pixels then come from Image.pixels (byte images: the file's values / 255, in the image's
colour space; float images: scene linear already) and are sent scene-linear.

Missing file: Cycles renders magenta (1, 0, 1) where an image cannot be loaded
(intern/cycles/scene/image.cpp, TEX_IMAGE_MISSING_R/G/B); so does Stratum, with a warning naming
the image. A colour space the native side does not know: a warning, then the image is read as
Blender's default for its kind (sRGB for byte images, linear for float ones). Texels that are NaN
or infinite (in the file, in Image.pixels, or after the colour conversion) become transparent
black natively, as in Cycles, and the image's count is warned about by name. An image whose
header claims more pixels than half of the machine's memory can hold as float RGBA (a 165-byte
PNG may claim 65535 x 65535) is refused before it is read: magenta, with the reason.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from functools import lru_cache
from typing import Any

import bpy
import numpy as np

from .. import native
from .color_management import SceneLinearConversion, conversion_for

MISSING_RGBA = (1.0, 0.0, 1.0, 1.0)
# The native side's name for scene-linear Rec.709 whatever config it has (built in without one).
SCENE_LINEAR_BUILTIN = "Linear Rec.709"
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


def _float_pixels_straight(image: Any) -> np.ndarray:
    """A float image's Image.pixels with straight alpha, as the C ABI takes them: Blender keeps
    float buffers premultiplied (an EXR pixel (0.5, 0.25, 0.1, 0.5) read as sRGB comes back as
    0.5 * linear(1.0, 0.5, 0.2)); colour where alpha is 0 is left as it is."""
    px = _pixels(image)
    if px.shape[2] == 4:
        alpha = px[..., 3:4]
        np.divide(px[..., :3], alpha, out=px[..., :3], where=alpha > 0.0)
    return px


def _rgba(px: np.ndarray) -> np.ndarray:
    """(height, width, 1..4) pixels as (height, width, 4) RGBA: grey to RGB, opaque when there
    is no alpha channel (as OpenImageIO's reading does natively)."""
    channels = px.shape[2]
    if channels == 4:
        return np.ascontiguousarray(px, dtype=np.float32)
    rgba = np.ones((*px.shape[:2], 4), dtype=np.float32)
    rgba[..., :3] = px[..., :3] if channels >= 3 else px[..., :1]
    if channels == 2:
        rgba[..., 3] = px[..., 1]
    return rgba


def _converted_texture(image: Any, conversion: SceneLinearConversion,
                       common: dict[str, Any], warn: Callable[[str], None],
                       node: Any) -> native.Texture:
    """The image's pixels converted to scene linear here (the native side cannot convert its
    colour space): byte images from their colour space with Blender's PyOpenColorIO, float
    images as Blender already converted them when it loaded them."""
    width, height = (int(v) for v in image.size)
    if width == 0 or height == 0 or not image.has_data:
        warn(f"image '{image.name}' cannot be read; rendered magenta as Cycles does")
        return missing_texture(node)
    if image.is_float:
        return native.Texture(pixels=_float_pixels_straight(image),
                              **{**common, "color_space": "Non-Color"})
    rgba = conversion.apply(_rgba(_pixels(image)))
    space = "Non-Color" if conversion.is_data else SCENE_LINEAR_BUILTIN
    return native.Texture(pixels=rgba, **{**common, "color_space": space})


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
    conversion = conversion_for(common["ocio_config"], common["color_space"])
    if image.packed_file is not None:
        if conversion is not None:
            return _converted_texture(image, conversion, common, warn, node)
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
            if conversion is not None:
                return _converted_texture(image, conversion, common, warn, node)
            return native.Texture(path=path, **common)
    width, height = (int(v) for v in image.size)
    if width == 0 or height == 0 or not image.has_data:
        warn(f"image '{image.name}' has no pixels; rendered magenta as Cycles does")
        return missing_texture(node)
    if conversion is not None:
        return _converted_texture(image, conversion, common, warn, node)
    if image.is_float:
        common["color_space"] = "Non-Color"  # Blender keeps float buffers scene-linear
        return native.Texture(pixels=_float_pixels_straight(image), **common)
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
        texture_id = self._add_or_fallback(node, texture)
        replaced = self._scene.texture_info(texture_id).replaced_texels
        if replaced:
            self._warn(node, f"image '{node.image.name}': {replaced} texel(s) are NaN or infinite "
                             "(in the file, or after conversion to scene linear); rendered as "
                             "black, as Cycles does")
        return texture_id

    def _add_or_fallback(self, node: Any, texture: native.Texture) -> int:
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
