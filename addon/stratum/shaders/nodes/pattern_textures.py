"""Pattern textures: Checker, Gradient, Brick, Magic and Wave, the same
sockets in Blender 3.4 and 4.x/5.x (5.x names the Fac output "Factor"; its identifier stays
"Fac").

| node (bl_idname)      | native   | modes                                              |
|-----------------------|----------|----------------------------------------------------|
| ShaderNodeTexChecker  | checker  | none                                               |
| ShaderNodeTexGradient | gradient | gradient_type (Cycles' NodeGradientType order)     |
| ShaderNodeTexBrick    | brick    | offset_frequency, squash_frequency, smoothing      |
|                       |          | generation (0 before Blender 3.5, 1 after); data:  |
|                       |          | offset, squash                                     |
| ShaderNodeTexMagic    | magic    | turbulence_depth                                   |
| ShaderNodeTexWave     | wave     | wave_type, bands_direction, rings_direction,       |
|                       |          | wave_profile, noise generation (its distortion)    |

An unlinked Vector is the "generated" renderer input, as Cycles. A node whose hidden texture
mapping (node.texture_mapping, Cycles' TextureMapping) is not the identity gives a warning: it
is not applied."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler, Unsupported
from .registry import translator

# Cycles' NodeGradientType (svm/types.h) numbers the types in this order.
GRADIENT_TYPES = ("LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "RADIAL", "QUADRATIC_SPHERE",
                  "SPHERICAL")
MAX_FREQUENCY = 255  # the native brick node's limit (Blender's is 99)
MAX_TURBULENCE_DEPTH = 10


def warn_texture_mapping(c: NodeCompiler, node: Any) -> None:
    """One warning when the node's own texture mapping (set only from Python or old files) is
    not the identity: Cycles applies it, Stratum does not."""
    mapping = getattr(node, "texture_mapping", None)
    if mapping is None:
        return
    identity = (all(float(v) == 0.0 for v in getattr(mapping, "translation", (0, 0, 0)))
                and all(float(v) == 0.0 for v in getattr(mapping, "rotation", (0, 0, 0)))
                and all(float(v) == 1.0 for v in getattr(mapping, "scale", (1, 1, 1)))
                and not getattr(mapping, "use_min", False)
                and not getattr(mapping, "use_max", False)
                and tuple(str(getattr(mapping, f"mapping_{a}", a.upper())) for a in "xyz")
                == ("X", "Y", "Z"))
    if not identity:
        c.warn(node, f"'{node.name}' ({node.bl_idname}): its texture mapping (not the identity) is "
                     "not supported; the vector is used unmapped", "texture_mapping")


def vector(c: NodeCompiler, node: Any) -> int:
    warn_texture_mapping(c, node)
    return c.vector_or(node, "Vector", "generated")


def color_fac(registers: list[int]) -> dict[str, int]:
    return {"Color": registers[0], "Fac": registers[1]}


@translator("ShaderNodeTexChecker")
def checker(c: NodeCompiler, node: Any) -> dict[str, int]:
    inputs = (vector(c, node), c.input(node, "Color1", "color"), c.input(node, "Color2", "color"),
              c.input(node, "Scale", "float"))
    return color_fac(c.builder.node("checker", (), inputs, (3, 1)))


@translator("ShaderNodeTexGradient")
def gradient(c: NodeCompiler, node: Any) -> dict[str, int]:
    kind = str(getattr(node, "gradient_type", "LINEAR"))
    if kind not in GRADIENT_TYPES:
        raise Unsupported(f"Gradient Texture '{node.name}': type {kind} is not supported")
    return color_fac(c.builder.node("gradient", (GRADIENT_TYPES.index(kind),), (vector(c, node),),
                                    (3, 1)))


def _frequency(node: Any, name: str) -> int:
    value = int(getattr(node, name, 2))
    if not 0 <= value <= MAX_FREQUENCY:
        raise Unsupported(f"Brick Texture '{node.name}': {name} {value} is outside "
                          f"0..{MAX_FREQUENCY}")
    return value


@translator("ShaderNodeTexBrick")
def brick(c: NodeCompiler, node: Any) -> dict[str, int]:
    # Blender 3.5 clamped the mortar's smoothstep (they differ for a negative Mortar Smooth).
    generation = blender_versions.brick_generation(c.version)
    modes = (_frequency(node, "offset_frequency"), _frequency(node, "squash_frequency"),
             generation)
    inputs = (vector(c, node), c.input(node, "Color1", "color"), c.input(node, "Color2", "color"),
              c.input(node, "Mortar", "color"), c.input(node, "Scale", "float"),
              c.input(node, "Mortar Size", "float"), c.input(node, "Mortar Smooth", "float"),
              c.input(node, "Bias", "float"), c.input(node, "Brick Width", "float"),
              c.input(node, "Row Height", "float"))
    data = (float(getattr(node, "offset", 0.5)), float(getattr(node, "squash", 1.0)))
    return color_fac(c.builder.node("brick", modes, inputs, (3, 1), data))


@translator("ShaderNodeTexMagic")
def magic(c: NodeCompiler, node: Any) -> dict[str, int]:
    depth = int(getattr(node, "turbulence_depth", 2))
    if not 0 <= depth <= MAX_TURBULENCE_DEPTH:
        raise Unsupported(f"Magic Texture '{node.name}': turbulence depth {depth} is outside "
                          f"0..{MAX_TURBULENCE_DEPTH}")
    inputs = (vector(c, node), c.input(node, "Scale", "float"),
              c.input(node, "Distortion", "float"))
    return color_fac(c.builder.node("magic", (depth,), inputs, (3, 1)))


WAVE_TYPES = ("BANDS", "RINGS")
BANDS_DIRECTIONS = ("X", "Y", "Z", "DIAGONAL")
RINGS_DIRECTIONS = ("X", "Y", "Z", "SPHERICAL")
WAVE_PROFILES = ("SIN", "SAW", "TRI")


def _choice(node: Any, prop: str, choices: tuple[str, ...]) -> int:
    value = str(getattr(node, prop, choices[0]))
    if value not in choices:
        raise Unsupported(f"Wave Texture '{node.name}': {prop} {value} is not supported")
    return choices.index(value)


@translator("ShaderNodeTexWave")
def wave(c: NodeCompiler, node: Any) -> dict[str, int]:
    modes = (_choice(node, "wave_type", WAVE_TYPES),
             _choice(node, "bands_direction", BANDS_DIRECTIONS),
             _choice(node, "rings_direction", RINGS_DIRECTIONS),
             _choice(node, "wave_profile", WAVE_PROFILES),
             blender_versions.noise_generation(c.version))
    inputs = (vector(c, node), *(c.input(node, k, "float") for k in (
        "Scale", "Distortion", "Detail", "Detail Scale", "Detail Roughness", "Phase Offset")))
    return color_fac(c.builder.node("wave", modes, inputs, (3, 1)))
