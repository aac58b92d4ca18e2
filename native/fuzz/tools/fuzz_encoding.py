"""The value encodings of the ABI fuzzer's programs (native/fuzz/README.md), for the assembler
fuzz_corpus.py: the operation codes, the special floats by name, a float field's
one-byte scaled form (signed, positive, unit) or raw bits, descriptor mutation lists, small
integers, transform matrices (presets and element changes) and raw strings. The operations
built from them are in fuzz_ops.py.
"""

from __future__ import annotations

import struct

# ByteReader::special_floats(), by index.
SPECIAL = {
    "0": 0,
    "-0": 1,
    "denorm": 2,
    "-denorm": 3,
    "flt_min": 4,
    "1e-38": 5,
    "1e-18": 6,
    "1e-9": 7,
    "1e-4": 8,
    "1e4": 9,
    "1e9": 10,
    "1e18": 11,
    "flt_large": 12,
    "1e19": 13,
    "1e30": 14,
    "3e38": 15,
    "flt_max": 16,
    "inf": 17,
    "nan": 18,
    "-1e19": 19,
    "-1e30": 20,
    "-3e38": 21,
    "-flt_max": 22,
    "-inf": 23,
    "-nan": 24,
    "1": 25,
    "-1": 26,
    "pi": 27,
    "2pi": 28,
    "0.5": 29,
    "65536": 30,
    "-1e-18": 31,
}

OPS = {
    name: code
    for code, name in enumerate(
        [
            "material",
            "closure_material",
            "texture",
            "bind_texture",
            "mesh",
            "instance",
            "instance_ex",
            "light",
            "camera",
            "background",
            "environment",
            "new_scene",
            "save_load",
            "render",
            "rerender",
            "throughput",
            "sampling",
            "models",
        ]
    )
}
OPS["instances"] = 254  # operations added later take the top byte values (native/fuzz/program.cpp)
OPS["vertex_normals"] = 253
OPS["shader_program"] = 252
OPS["bind_program"] = 251


def special(name: str) -> bytes:
    return bytes([SPECIAL[name]])


def raw(v: float) -> bytes:
    return bytes([0xE0]) + struct.pack("<f", v)


def _scaled(v: float | str, kind: str) -> bytes:
    """A float field value: a special by name, the one-byte scaled form when exact, else raw."""
    if isinstance(v, str):
        return special(v)
    if kind == "signed":
        s = v * 16 + 128
    elif kind == "positive":
        s = v * 16 + 32
    else:
        s = v * 191 + 32
    if s == int(s) and 32 <= s < 224:
        return bytes([int(s)])
    return raw(v)


def signed(v: float | str) -> bytes:
    return _scaled(v, "signed")


def positive(v: float | str) -> bytes:
    return _scaled(v, "positive")


def unit(v: float | str) -> bytes:
    return _scaled(v, "unit")


def mutations(fields: dict[str, tuple[int, str]], changes: dict[str, float | str]) -> bytes:
    """The mutation list of a descriptor: count, then (field index, value) pairs."""
    out = bytes([len(changes)])
    for name, value in changes.items():
        index, kind = fields[name]
        out += bytes([index])
        out += _scaled(value, kind) if kind != "int" else small_int(int(value))
    return out


def small_int(v: int) -> bytes:
    """draw_small_int: selectors from 16 on give s % 12 - 2, so 24 + (v + 2) gives v in -2..9."""
    assert -2 <= v <= 9
    return bytes([24 + v + 2])


def matrix(preset: int = 0, args: bytes = b"", changes: dict[int, float | str] | None = None) -> bytes:
    out = bytes([preset]) + args
    changes = changes or {}
    out += bytes([len(changes)])
    for element, value in changes.items():
        out += bytes([element]) + signed(value)
    return out


def translate(x: float | str, y: float | str, z: float | str, **kw) -> bytes:
    return matrix(1, signed(x) + signed(y) + signed(z), **kw)


def scale(s: float | str, **kw) -> bytes:
    return matrix(2, positive(s), **kw)


def axis_scale(x: float | str, y: float | str, z: float | str, **kw) -> bytes:
    return matrix(3, signed(x) + signed(y) + signed(z), **kw)


def rotate(axis: int, angle: float | str, **kw) -> bytes:
    return matrix(4, bytes([axis]) + signed(angle), **kw)


def raw_string(s: str) -> bytes:
    return bytes([240, len(s)]) + s.encode()
