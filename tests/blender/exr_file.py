"""The tests' one EXR reader: every channel of a scanline EXR, read with numpy and zlib alone,
so the same code runs in Blender 3.4's Python (which has no OpenEXR module), in the bpy wheel
and in the venv (corpus.replay). It reads what the tests write: Blender's OPEN_EXR and
OPEN_EXR_MULTILAYER files and stratum-native's (OpenImageIO), uncompressed or with the
lossless codecs RLE, ZIPS and ZIP; another codec is refused naming it.

Format (the OpenEXR file layout): magic, version, header attributes up to an empty name, one
offset per chunk, then per chunk its first line y, its byte count and its data: for each line,
each channel's row in the header's (alphabetical) channel order. A compressed chunk holds those
bytes run-length or zlib coded after two reversible steps (the bytes split into the even-indexed
then the odd-indexed ones, then each byte stored as its difference from the one before plus
128); a chunk that would not shrink is stored as it is."""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np

_MAGIC = 20000630
_PIXEL_TYPES = {1: np.dtype("<f2"), 2: np.dtype("<f4")}  # HALF, FLOAT (UINT is not used here)
# Compression attribute value -> (name, scanlines per chunk).
_CODECS = {0: ("NONE", 1), 1: ("RLE", 1), 2: ("ZIPS", 1), 3: ("ZIP", 16)}
_CODEC_NAMES = {4: "PIZ", 5: "PXR24", 6: "B44", 7: "B44A", 8: "DWAA", 9: "DWAB"}


def _cstring(data: bytes, at: int) -> tuple[str, int]:
    end = data.index(b"\0", at)
    return data[at:end].decode(), end + 1


def _run_length_decoded(packed: bytes) -> bytes:
    """RLE: a signed count byte n, then -n literal bytes (n < 0) or one byte repeated n + 1
    times."""
    out = bytearray()
    at = 0
    while at < len(packed):
        n = struct.unpack_from("b", packed, at)[0]
        if n < 0:
            out += packed[at + 1:at + 1 - n]
            at += 1 - n
        else:
            out += packed[at + 1:at + 2] * (n + 1)
            at += 2
    return bytes(out)


def _unpredicted(coded: bytes) -> bytes:
    """Undoes the two steps before RLE or zlib: the running sum of (byte - 128) after the
    first byte, modulo 256, then the even-indexed bytes (first half) and the odd-indexed ones
    (second half) put back in place."""
    deltas = np.frombuffer(coded, dtype=np.uint8).astype(np.int64)
    deltas[1:] -= 128
    predicted = (np.cumsum(deltas) & 0xFF).astype(np.uint8)
    out = np.empty_like(predicted)
    half = (len(predicted) + 1) // 2
    out[0::2], out[1::2] = predicted[:half], predicted[half:]
    return out.tobytes()


def read_channels(path: Path) -> dict[str, np.ndarray]:
    """channel name ("R", "ViewLayer.Combined.R", ...) -> float32 (height, width), rows top
    first, in the file's channel order."""
    data = Path(path).read_bytes()
    magic, version = struct.unpack_from("<ii", data, 0)
    if magic != _MAGIC or version & 0x1A00:  # tiled, deep or multi-part files are not read here
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
    compression = header["compression"][1][0]
    if compression not in _CODECS:
        raise ValueError(f"{path}: compression {_CODEC_NAMES.get(compression, compression)} is "
                         f"not read here; write it with exr_codec 'ZIP' or 'NONE'")
    codec, lines_per_chunk = _CODECS[compression]
    xmin, ymin, xmax, ymax = struct.unpack("<4i", header["dataWindow"][1])
    width, height = xmax - xmin + 1, ymax - ymin + 1
    channels, raw = [], header["channels"][1]
    pos = 0
    while raw[pos:pos + 1] != b"\0":
        name, pos = _cstring(raw, pos)
        (pixel_type,) = struct.unpack_from("<i", raw, pos)
        if pixel_type not in _PIXEL_TYPES:
            raise ValueError(f"{path}: channel {name!r} has pixel type {pixel_type}, not HALF "
                             "(1) or FLOAT (2), which are read here")
        channels.append((name, _PIXEL_TYPES[pixel_type]))
        pos += 16
    line_bytes = width * sum(dtype.itemsize for _, dtype in channels)
    chunks = -(-height // lines_per_chunk)
    offsets = struct.unpack_from(f"<{chunks}Q", data, at)
    out = {name: np.empty((height, width), dtype=np.float32) for name, _ in channels}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        lines = min(lines_per_chunk, ymax + 1 - y)
        chunk = data[offset + 8:offset + 8 + size]
        if codec != "NONE" and size < lines * line_bytes:
            coded = zlib.decompress(chunk) if codec.startswith("ZIP") else \
                _run_length_decoded(chunk)
            chunk = _unpredicted(coded)
        if len(chunk) != lines * line_bytes:
            raise ValueError(f"{path}: the chunk at line {y} holds {len(chunk)} bytes, "
                             f"expected {lines * line_bytes}")
        pos = 0
        for row in range(y - ymin, y - ymin + lines):
            for name, dtype in channels:
                out[name][row] = np.frombuffer(chunk, dtype=dtype, count=width, offset=pos)
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


def read_image(path: Path) -> np.ndarray:
    """An RGB or RGBA EXR as Blender's Image.pixels holds it after loading the file: float32
    (height, width, 4), row 0 at the bottom, alpha 1 where the file has none."""
    channels = read_channels(path)
    if not {"R", "G", "B"} <= channels.keys():
        raise KeyError(f"{path}: no R, G, B channels; channels: {sorted(channels)}")
    alpha = channels.get("A", np.ones_like(channels["R"]))
    return np.ascontiguousarray(
        np.stack([channels["R"], channels["G"], channels["B"], alpha], axis=-1)[::-1])
