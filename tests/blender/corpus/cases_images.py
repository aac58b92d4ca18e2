"""Images on the base cube's Base Color: every image that cannot be read renders magenta (as
Cycles does) with a WARNING naming it, whatever the reason: missing, empty, corrupt, truncated,
a header claiming 65535x65535 (Stratum allocated 69 GB before reading a pixel), a directory or a
FIFO (stratum_scene_add_texture blocked forever), packed garbage. Readable oddities (16 bit,
1x1, a PNG named .jpg) render their colour; NaN texels do not reach the film."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import bpy

from . import files
from .case import case, centre_colour, clean, lit_centre, magenta_centre, warning
from .stage import Stage


def _file_case(name: str, what: str, image: str, write: Any) -> None:
    """A case whose cube shows the image file that write(path) makes (or does not make)."""

    def build(s: Stage) -> None:
        path = s.tmp / f"{image}.png"
        write(path)
        s.textured_cube(s.file_image(image, path))

    case(name, "images", what, warning(image, pixels=magenta_centre))(build)


_file_case("img_missing_file", "an image whose file does not exist", "LostTexture",
           lambda path: None)
_file_case("img_zero_bytes", "an image file of 0 bytes", "EmptyTexture",
           lambda path: path.write_bytes(b""))
_file_case("img_garbage", "4 KiB of bytes that are no image, named .png", "GarbageTexture",
           lambda path: path.write_bytes(files.garbage()))
_file_case("img_truncated_png", "a valid PNG cut in half", "TruncatedTexture",
           lambda path: path.write_bytes(files.truncated_png()))
_file_case("img_header_65535", "a 100-byte PNG whose IHDR claims 65535x65535 (valid CRCs)",
           "BombTexture", lambda path: path.write_bytes(files.lying_png()))
_file_case("img_directory", "an image path that is a directory", "FolderTexture",
           lambda path: path.mkdir())
_file_case("img_fifo", "an image path that is a FIFO (blocked forever natively)",
           "PipeTexture", lambda path: os.mkfifo(path))


@case("img_dev_zero", "images", "an image path that is /dev/zero (endless zeros)",
      warning("ZeroDevice", pixels=magenta_centre))
def img_dev_zero(s: Stage) -> None:
    s.textured_cube(s.file_image("ZeroDevice", "/dev/zero"))


@case("img_packed_garbage", "images", "a packed image whose bytes are no image",
      warning("PackedGarbage", pixels=magenta_centre))
def img_packed_garbage(s: Stage) -> None:
    image = bpy.data.images.new("PackedGarbage", 4, 4)
    data = files.garbage(2048)
    image.pack(data=data, data_len=len(data))
    image.source = "FILE"
    image.filepath = "//packed_garbage.png"
    s.textured_cube(image)


def _png_case(name: str, what: str, image: str, png: bytes, suffix: str = ".png",
              rgb: tuple[float, float, float] = (1.0, 0.0, 0.0)) -> None:
    def build(s: Stage) -> None:
        path = s.tmp / f"{image}{suffix}"
        path.write_bytes(png)
        s.textured_cube(s.file_image(image, path))

    case(name, "images", what, clean(quiet=True, pixels=centre_colour(rgb)))(build)


_png_case("img_16bit_png", "a 16-bit RGB PNG (green)", "DeepTexture",
          files.png(4, 4, (0, 65535, 0), bit_depth=16), rgb=(0.0, 1.0, 0.0))
_png_case("img_1x1", "a 1x1 PNG (red)", "DotTexture", files.png(1, 1, (255, 0, 0)))
_png_case("img_wrong_extension", "a PNG named .jpg (red; read by content, as Blender does)",
          "MisnamedTexture", files.png(4, 4, (255, 0, 0)), suffix=".jpg")


def _float_exr(s: Stage, name: str, value: float, path: Path) -> None:
    """Writes a 4x4 32-bit float EXR whose RGB are all `value` through Blender's image writer.
    Image.save() would write half floats in Blender 3.4, where a NaN came back as -0.125; the
    render settings' 32-bit depth keeps the value."""
    source = bpy.data.images.new(f"{name}Source", 4, 4, float_buffer=True)
    source.pixels.foreach_set([value, value, value, 1.0] * 16)
    settings = s.scene.render.image_settings
    kept = (settings.file_format, settings.color_depth)
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    source.save_render(str(path), scene=s.scene)
    settings.file_format, settings.color_depth = kept
    bpy.data.images.remove(source)


@case("img_exr_nan_pixels", "images", "an EXR texture whose texels are NaN",
      warning("NanTexture", words=("nan", "finite", "pixel", "texel")))
def img_exr_nan_pixels(s: Stage) -> None:
    path = s.tmp / "nan_texels.exr"
    _float_exr(s, "NanTexture", float("nan"), path)
    s.textured_cube(s.file_image("NanTexture", path))


@case("img_exr_huge_pixels", "images", "an EXR texture whose texels are 3e38 (sRGB: decode to Inf)",
      warning("HugeTexture", words=("finite",), pixels=lit_centre))
def img_exr_huge_pixels(s: Stage) -> None:
    path = s.tmp / "huge_texels.exr"
    _float_exr(s, "HugeTexture", 3e38, path)
    s.textured_cube(s.file_image("HugeTexture", path))
