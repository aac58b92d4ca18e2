"""Image files crafted byte by byte for the image cases (no binary blobs in the repository).

PNG layout (ISO/IEC 15948): the 8-byte signature, then chunks of length (4 bytes, big endian),
type (4), data, and CRC-32 over type and data; IHDR holds width, height, bit depth, colour type,
compression, filter and interlace. Chunks carry correct CRCs so that libpng gets past them and
reaches what each case is about (a header that lies, a truncated stream).
"""

from __future__ import annotations

import struct
import zlib

SIGNATURE = b"\x89PNG\r\n\x1a\n"
RGB = 2  # PNG colour type: truecolour


def chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(
        ">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png(width: int, height: int, rgb: tuple[int, int, int], bit_depth: int = 8) -> bytes:
    """A valid RGB PNG of one colour; channel values in [0, 2**bit_depth)."""
    fmt = ">3B" if bit_depth == 8 else ">3H"
    row = b"\x00" + struct.pack(fmt, *rgb) * width  # filter type 0 (None) per row
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, RGB, 0, 0, 0)
    return (SIGNATURE + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(row * height, 9))
            + chunk(b"IEND", b""))


def lying_png(width: int = 65535, height: int = 65535) -> bytes:
    """A PNG of about 100 bytes whose header claims width x height: one short IDAT, IEND.
    A reader that allocates width*height pixels from the header before decoding asks for
    65535^2 * 4 floats = 69 GB."""
    ihdr = struct.pack(">IIBBBBB", width, height, 8, RGB, 0, 0, 0)
    return (SIGNATURE + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\x00" * 64, 9))
            + chunk(b"IEND", b""))


def truncated_png() -> bytes:
    """The first half of a valid 64x64 PNG of noise-free colour (cut inside IDAT)."""
    whole = png(64, 64, (200, 40, 40))
    return whole[: len(whole) // 2]


def garbage(size: int = 4096) -> bytes:
    """Deterministic bytes that are no image format (a linear congruential sequence)."""
    out = bytearray(size)
    state = 12345
    for i in range(size):
        state = (1103515245 * state + 12345) & 0x7FFFFFFF
        out[i] = state >> 16 & 0xFF
    return bytes(out)
