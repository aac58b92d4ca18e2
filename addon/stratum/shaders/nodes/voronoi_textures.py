"""Voronoi Texture (ShaderNodeTexVoronoi) and White Noise Texture (ShaderNodeTexWhiteNoise).

Both Blender generations name the sockets alike (Vector, W, Scale, Smoothness, Exponent,
Randomness; 4.0+ adds Detail, Roughness, Lacunarity and the `normalize` option); the outputs are
Distance, Color, Position, W and Radius, and White Noise's Value and Color. The native node's
`generation` mode picks Cycles' evaluation of the file's Blender (docs/shader_nodes.md):

| Blender  | generation | what differs                                                       |
|----------|------------|--------------------------------------------------------------------|
| < 4.0    | 0          | one octave; searches start at distance 8                            |
| 4.0-4.4  | 1          | fractal octaves; smooth F1 of smoothness 0 is F1                   |
| 4.5      | 2          | F1 and the n-sphere radius compare squared distances               |
| 5.0+     | 3          | cells hashed by integer coordinates (PCG) in 2D-4D                  |

Cycles 4.0-4.2 read a linked Lacunarity from the Smoothness socket's link (and ignore a linked
Lacunarity); that is reproduced, with a warning. An unlinked Vector is the Generated coordinate
for Voronoi but the socket's own value for White Noise (as Cycles: one colour all over)."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler, Unsupported
from .registry import translator

DIMENSIONS = ("1D", "2D", "3D", "4D")
FEATURES = ("F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS")
METRICS = ("EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI")


def _enum(node: Any, attribute: str, values: tuple[str, ...], default: str, what: str) -> int:
    value = str(getattr(node, attribute, default))
    if value not in values:
        raise Unsupported(f"{what} '{node.name}': {attribute} {value} is not supported")
    return values.index(value)


def _float_or(c: NodeCompiler, node: Any, key: str, default: float) -> int:
    """The input's register, or a constant where the node has no such socket (3.x's Detail)."""
    if c.has_input(node, key):
        return c.input(node, key, "float")
    return c.builder.constant(default)


@translator("ShaderNodeTexVoronoi")
def voronoi_texture(c: NodeCompiler, node: Any) -> dict[str, int]:
    dimensions = _enum(node, "voronoi_dimensions", DIMENSIONS, "3D", "Voronoi Texture")
    feature = _enum(node, "feature", FEATURES, "F1", "Voronoi Texture")
    metric = _enum(node, "distance", METRICS, "EUCLIDEAN", "Voronoi Texture")
    gen = blender_versions.voronoi_generation(c.version)
    vector = c.vector_or(node, "Vector", "generated")
    w = c.input(node, "W", "float")
    scale = c.input(node, "Scale", "float")
    smoothness = c.input(node, "Smoothness", "float")
    lacunarity = _float_or(c, node, "Lacunarity", 2.0)
    if (blender_versions.voronoi_lacunarity_from_smoothness(c.version)
            and c.has_input(node, "Lacunarity")):
        # Cycles 4.0-4.2 loads Lacunarity from Smoothness's stack slot: a linked Smoothness
        # feeds it, and otherwise the unlinked Lacunarity value is used even when linked.
        smooth_socket = c.socket(node, "Smoothness")
        lac_socket = c.socket(node, "Lacunarity")
        if c.linked(smooth_socket) or c.linked(lac_socket):
            c.warn(node, f"Voronoi Texture '{node.name}': Blender {c.version[0]}.{c.version[1]} "
                         "reads Lacunarity from the Smoothness link; reproduced as Cycles does",
                   "lacunarity")
        lacunarity = smoothness if c.linked(smooth_socket) else c.constant_of(lac_socket, "float")
    detail = _float_or(c, node, "Detail", 0.0)
    roughness = _float_or(c, node, "Roughness", 0.5)
    exponent = c.input(node, "Exponent", "float")
    randomness = c.input(node, "Randomness", "float")
    normalize = bool(getattr(node, "normalize", False)) and gen > 0
    distance, color, position, w_out, radius = c.builder.node(
        "voronoi", (dimensions, feature, metric, gen, int(normalize)),
        (vector, w, scale, detail, roughness, lacunarity, smoothness, exponent, randomness),
        (1, 3, 3, 1, 1))
    return {"Distance": distance, "Color": color, "Position": position, "W": w_out,
            "Radius": radius}


@translator("ShaderNodeTexWhiteNoise")
def white_noise_texture(c: NodeCompiler, node: Any) -> dict[str, int]:
    dimensions = _enum(node, "noise_dimensions", DIMENSIONS, "3D", "White Noise Texture")
    # Cycles declares White Noise's Vector without a default link (shader_nodes.cpp): unlinked, it
    # is the socket's own value (a constant colour), not the Generated coordinate.
    vector = c.input(node, "Vector", "vector")
    w = c.input(node, "W", "float")
    value, color = c.builder.node("white_noise", (dimensions,), (vector, w), (1, 3))
    return {"Value": value, "Color": color}
