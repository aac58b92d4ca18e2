"""Every channel of an uncompressed scanline EXR (what Blender writes as OPEN_EXR_MULTILAYER
with exr_codec 'NONE'), read with numpy alone: Blender 3.4's Python has no OpenEXR module and
bpy's image loader shows one pass of a multilayer file. Format: the OpenEXR file layout
(magic, version, attributes up to an empty name, one offset per scanline, then per scanline
its y, its byte count and each channel's row in the header's (alphabetical) channel order)."""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np

_MAGIC = 20000630
_PIXEL_TYPES = {1: np.dtype("<f2"), 2: np.dtype("<f4")}  # HALF, FLOAT (UINT is not used here)


def _cstring(data: bytes, at: int) -> tuple[str, int]:
    end = data.index(b"\0", at)
    return data[at:end].decode(), end + 1


def read_channels(path: Path) -> dict[str, np.ndarray]:
    """channel name ("ViewLayer.Combined.R", ...) -> float32 (height, width), rows top first."""
    data = path.read_bytes()
    magic, version = struct.unpack_from("<ii", data, 0)
    if magic != _MAGIC or version & 0x1200:  # tiled or multi-part files are not read here
        raise ValueError(f"{path}: not a single-part scanline EXR")
    at, header = 8, {}
    while True:
        name, at = _cstring(data, at)
        if not name:
            break
        kind, at = _cstring(data, at)
        (size,) = struct.unpack_from("<i", data, at)
        header[name] = (kind, data[at + 4:at + 4 + size])
        at += 4 + size
    if header["compression"][1] != b"\0":
        raise ValueError(f"{path}: compressed; write it with exr_codec 'NONE'")
    xmin, ymin, xmax, ymax = struct.unpack("<4i", header["dataWindow"][1])
    width, height = xmax - xmin + 1, ymax - ymin + 1
    channels, raw = [], header["channels"][1]
    pos = 0
    while raw[pos:pos + 1] != b"\0":
        name, pos = _cstring(raw, pos)
        (pixel_type,) = struct.unpack_from("<i", raw, pos)
        channels.append((name, _PIXEL_TYPES[pixel_type]))
        pos += 16
    offsets = struct.unpack_from(f"<{height}Q", data, at)
    out = {name: np.empty((height, width), dtype=np.float32) for name, _ in channels}
    for offset in offsets:
        y, _size = struct.unpack_from("<ii", data, offset)
        pos = offset + 8
        for name, dtype in channels:
            out[name][y - ymin] = np.frombuffer(data, dtype=dtype, count=width, offset=pos)
            pos += width * dtype.itemsize
    return out


def read_pass(path: Path, pass_name: str, layer: str = "ViewLayer") -> np.ndarray:
    """One pass of a multilayer EXR as float32 (height, width, channels), rows top first."""
    channels = read_channels(path)
    prefix = f"{layer}.{pass_name}."
    names = [name for name in channels if name.startswith(prefix)]
    if not names:
        raise KeyError(f"{path}: no pass {pass_name!r} in layer {layer!r}; channels: "
                       f"{sorted(channels)}")
    order = "RGBAXYZ"
    names.sort(key=lambda n: order.index(n[len(prefix):]) if n[len(prefix):] in order else 99)
    return np.stack([channels[name] for name in names], axis=-1)
