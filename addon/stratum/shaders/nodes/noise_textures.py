"""Noise Texture (ShaderNodeTexNoise) and Musgrave Texture (ShaderNodeTexMusgrave, Blender 3.x
and 4.0; 4.1 loads it as a Noise Texture), onto the native `noise` and `musgrave` nodes.

| Blender | Noise sockets read                                | native generation (mode 3)  |
|---------|---------------------------------------------------|-----------------------------|
| 3.x     | Vector, W, Scale, Detail, Roughness, Distortion   | 0: fBM, lacunarity 2        |
| 4.0     | + Lacunarity, `normalize`                         | 1                           |
| 4.1     | + Offset, Gain, `noise_type` (Musgrave's types)   | 2                           |
| 4.2-5.x | the same                                          | 3: large coordinates wrap   |

An unlinked Vector reads the Generated coordinates, as Cycles does; W is read in 1D and 4D only,
Vector in 2D to 4D. The Color output is computed only when something reads it."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler, Unsupported, identifier
from .registry import translator

DIMENSIONS = ("1D", "2D", "3D", "4D")
# Cycles' NodeNoiseType / NodeMusgraveType order (svm/types.h).
FRACTAL_TYPES = ("MULTIFRACTAL", "FBM", "HYBRID_MULTIFRACTAL", "RIDGED_MULTIFRACTAL",
                 "HETERO_TERRAIN")


def _dimensions(node: Any, attribute: str) -> int:
    dims = str(getattr(node, attribute, "3D"))
    if dims not in DIMENSIONS:
        raise Unsupported(f"'{node.name}': dimensions {dims} are not supported")
    return DIMENSIONS.index(dims) + 1


def _fractal_type(node: Any, attribute: str) -> int:
    kind = str(getattr(node, attribute, "FBM"))
    if kind not in FRACTAL_TYPES:
        raise Unsupported(f"'{node.name}': type {kind} is not supported")
    return FRACTAL_TYPES.index(kind)


def _point_inputs(c: NodeCompiler, node: Any, dims: int) -> tuple[int, int]:
    """Registers of Vector and W, reading only the ones the dimensions use (the other is the
    Generated input or the constant 0, which the native node ignores)."""
    vector = c.vector_or(node, "Vector", "generated") if dims > 1 else c.geometry("generated")
    w = c.input(node, "W", "float") if dims in (1, 4) else c.builder.constant(0.0)
    return vector, w


def _optional(c: NodeCompiler, node: Any, key: str, default: float) -> int:
    """A float input that older Blenders lack, or `default`."""
    if c.has_input(node, key):
        return c.input(node, key, "float")
    return c.builder.constant(default)


def _warn_texture_mapping(c: NodeCompiler, node: Any) -> None:
    """The hidden per-node texture mapping (set only from Python), which Cycles applies to the
    Vector: not translated, so a non-identity one is warned about."""
    tm = getattr(node, "texture_mapping", None)
    if tm is None:
        return
    identity = (tuple(tm.translation) == (0.0, 0.0, 0.0) and tuple(tm.rotation) == (0.0, 0.0, 0.0)
                and tuple(tm.scale) == (1.0, 1.0, 1.0) and not tm.use_min and not tm.use_max
                and (tm.mapping_x, tm.mapping_y, tm.mapping_z) == ("X", "Y", "Z"))
    if not identity:
        c.warn(node, f"'{node.name}': its texture mapping (node.texture_mapping) is not "
                     "supported; the Vector is used unmapped", "texture_mapping")


def _output_read(node: Any, key: str) -> bool:
    for out in getattr(node, "outputs", ()):
        if identifier(out) == key:
            return bool(getattr(out, "is_linked", True))
    return False


@translator("ShaderNodeTexNoise")
def noise_texture(c: NodeCompiler, node: Any) -> dict[str, int]:
    dims = _dimensions(node, "noise_dimensions")
    generation = blender_versions.noise_generation(c.version)
    kind = _fractal_type(node, "noise_type") if generation >= 2 else FRACTAL_TYPES.index("FBM")
    normalize = bool(getattr(node, "normalize", True)) if generation >= 1 else True
    _warn_texture_mapping(c, node)
    vector, w = _point_inputs(c, node, dims)
    inputs = (vector, w, c.input(node, "Scale", "float"), c.input(node, "Detail", "float"),
              c.input(node, "Roughness", "float"), _optional(c, node, "Lacunarity", 2.0),
              _optional(c, node, "Offset", 0.0), _optional(c, node, "Gain", 1.0),
              c.input(node, "Distortion", "float"))
    color = _output_read(node, "Color")
    fac, rgb = c.builder.node("noise", (dims - 1, kind, int(normalize), generation, int(color)),
                              inputs, (1, 3))
    return {"Fac": fac, "Color": rgb}


@translator("ShaderNodeTexMusgrave")
def musgrave_texture(c: NodeCompiler, node: Any) -> dict[str, int]:
    dims = _dimensions(node, "musgrave_dimensions")
    kind = _fractal_type(node, "musgrave_type")
    _warn_texture_mapping(c, node)
    vector, w = _point_inputs(c, node, dims)
    inputs = (vector, w, *(c.input(node, k, "float") for k in
                           ("Scale", "Detail", "Dimension", "Lacunarity", "Offset", "Gain")))
    fac = c.builder.node("musgrave", (dims - 1, kind), inputs, (1,))[0]
    # The output is "Fac"; "Height" is accepted too (its label in later 4.0 builds).
    return {"Fac": fac, "Height": fac}
