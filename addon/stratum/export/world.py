"""The scene world -> native constant background, or an equirectangular environment image.

Supported: World Output <- Background (Color, Strength) with Color either a value or linked
from an Environment Texture node (equirectangular projection) whose Vector input is unlinked
(the ray direction) or a Mapping node that only turns about Z, fed by Texture Coordinate
"Generated" (the ray direction in a world). Backgrounds mixed by Mix and Add Shaders (a Light
Path output on a Mix Shader's Fac: a world the camera sees and another that lights) become the
world's program. The image's pixels are taken from Blender
(`image.pixels`): float images hold scene-linear values; byte images hold values in their
colour space. Only images whose colour space is linear are converted exactly; any other
colour space gives a warning (OCIO conversion is pending) and its pixels are used as Blender
gives them. The native side looks the image up nearest-texel (Cycles' "Closest"); Cycles'
default "Linear" differs only within a texel.

Invalid values (docs/invalid_values.md): a NaN colour component or strength is
0 and a negative strength 0 (Cycles' film drops the non-finite samples, and Stratum has no
light that subtracts), colour x strength is limited to the largest float, and environment
pixels that are NaN, infinite or negative are 0; each with one warning naming the world.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import bpy
import numpy as np

from ..shaders.fallbacks import NON_NEGATIVE, Rgb, clamp, clamp_rgb, finite_product
from .common import (
    ExportSummary,
    active_output,
    linked_from,
    rgb,
    socket_value,
    uses_nodes,
)

# Colour spaces whose pixel values are linear (Blender 3.x and 4.x/5.x names).
LINEAR_COLOR_SPACES = frozenset({
    "Linear", "Linear Rec.709", "Linear Rec.2020", "Linear CIE-XYZ E", "Linear CIE-XYZ D65",
    "Linear FilmLight E-Gamut", "Non-Color", "Raw", "scene_linear", "Linear ACES", "Linear ACEScg",
})


@dataclass
class Environment:
    rgb: np.ndarray  # (height, width, 3) float32, rows top (+Z) to bottom
    strength: float
    rotation: np.ndarray  # 3x3 world-to-environment rotation


def _rotation_z(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]], dtype=np.float32)


def _mapping_rotation(node: Any) -> np.ndarray | None:
    """World-to-environment rotation of an Environment Texture's Vector input, or None when
    it is not one Stratum can express (only a rotation about Z of the ray direction)."""
    vector = node.inputs["Vector"]
    if not vector.is_linked:
        return np.eye(3, dtype=np.float32)
    mapping = vector.links[0].from_node
    if mapping.bl_idname != "ShaderNodeMapping" or mapping.vector_type not in {
            "POINT", "VECTOR", "TEXTURE"}:
        return None
    source = mapping.inputs["Vector"]
    if not source.is_linked or source.links[0].from_node.bl_idname != "ShaderNodeTexCoord" \
            or source.links[0].from_socket.name != "Generated":
        return None
    values = {}
    for name in ("Location", "Rotation", "Scale"):
        socket = mapping.inputs.get(name)
        if socket is None or socket.is_linked:
            return None
        values[name] = [float(x) for x in socket.default_value]
    rx, ry, rz = values["Rotation"]
    sx, sy, sz = values["Scale"]
    # POINT: R·(S·d) + L; VECTOR: R·(S·d); TEXTURE: the inverse. A uniform positive scale does
    # not change a direction; a location would, except for VECTOR.
    moves = mapping.vector_type != "VECTOR" and any(abs(x) > 1e-6 for x in values["Location"])
    if abs(rx) > 1e-6 or abs(ry) > 1e-6 or moves or not (sx > 0 and sx == sy == sz):
        return None
    return _rotation_z(-rz if mapping.vector_type == "TEXTURE" else rz)


def _background_node(scene: Any) -> Any | None:
    node = _world_root(scene)
    return node if node is not None and node.bl_idname == "ShaderNodeBackground" else None


def _environment_node(background: Any) -> Any | None:
    color = background.inputs["Color"]
    node = linked_from(color) if color.is_linked else None
    return node if node is not None and node.bl_idname == "ShaderNodeTexEnvironment" else None


def _color(world: Any, label: str, value: Any, summary: ExportSummary) -> Rgb:
    """A colour >= 0 (`label` names it in the warning, e.g. "'Color' of 'Background'")."""
    color, problem = clamp_rgb(rgb(value), NON_NEGATIVE)
    if problem is not None:
        summary.warn(f"World '{world.name}': {label} {problem}")
    return color


def _strength(world: Any, background: Any, summary: ExportSummary) -> float:
    strength, problem = clamp(float(socket_value(background, "Strength")), NON_NEGATIVE)
    if problem is not None:
        summary.warn(f"World '{world.name}': 'Strength' of '{background.name}' {problem}")
    return strength


def convert_world(scene: Any, summary: ExportSummary) -> Rgb:
    world = scene.world
    if world is None:
        return (0.0, 0.0, 0.0)
    if not uses_nodes(world):
        return _color(world, "'Color'", world.color, summary)
    node_tree = world.node_tree
    output = active_output(node_tree, "ShaderNodeOutputWorld")
    surface = output.inputs.get("Surface") if output is not None else None
    node = linked_from(surface) if surface is not None else None
    if node is None:
        return (0.0, 0.0, 0.0)  # as Cycles: nothing connected renders black
    if node.bl_idname in _SHADER_MIXES:
        return (0.0, 0.0, 0.0)  # a mix of Backgrounds: convert_world_program's program replaces it
    if node.bl_idname != "ShaderNodeBackground":
        summary.warn(f"World '{world.name}': shader node '{node.name}' ({node.bl_idname}) is "
                     "not supported; using the world colour (constant background only)")
        return _color(world, "'Color'", world.color, summary)
    # Linked inputs are exported by convert_world_program or, for an Environment Texture on
    # Color, by convert_environment: either replaces this constant.
    color = _color(world, f"'Color' of '{node.name}'", socket_value(node, "Color"), summary)
    radiance, limited = finite_product(color, _strength(world, node, summary))
    if limited:
        summary.warn(f"World '{world.name}': 'Color' x 'Strength' of '{node.name}' exceeds the "
                     "largest float; limited to it")
    return radiance


@dataclass
class WorldProgram:
    """A world whose Background is driven by nodes: the program, the register of its radiance
    (colour x strength) and the size of the map the renderer bakes it into."""

    program: Any  # native.ShaderProgram
    register: int
    width: int
    height: int

    def key(self) -> tuple[Any, ...]:
        return (self.program.key(), self.register, self.width, self.height)


def _uses_program(background: Any) -> bool:
    """Whether the Background's inputs need the node program: anything linked except an
    Environment Texture alone on Color (exported as an image, looked up exactly)."""
    color, strength = background.inputs["Color"], background.inputs["Strength"]
    if strength.is_linked:
        return True
    return color.is_linked and _environment_node(background) is None


# Shader nodes that combine Backgrounds in a world (Cycles sums the weighted background closures):
# the usual way to show the camera one world and light the scene with another (Light Path).
_SHADER_MIXES = ("ShaderNodeMixShader", "ShaderNodeAddShader")


def _world_root(scene: Any) -> Any | None:
    """The shader node on the world's output: a Background, or a Mix or Add Shader."""
    world = scene.world
    if world is None or not uses_nodes(world):
        return None
    output = active_output(world.node_tree, "ShaderNodeOutputWorld")
    surface = output.inputs.get("Surface") if output is not None else None
    return linked_from(surface) if surface is not None else None


def _radiance(compiler: Any, node: Any | None, warn: Any) -> int:
    """Register of the radiance (three registers) of the shader `node` of a world: a
    Background's Color x Strength, a Mix Shader's (1 - saturate(Fac)) A + saturate(Fac) B (as
    Cycles' svm_node_mix_closure), an Add Shader's A + B; nothing linked is black."""
    from ..shaders.nodes.math_nodes import color_times, math_node

    builder = compiler.builder
    zero, one = builder.constant(0.0), builder.constant(1.0)
    if node is None:
        return builder.constant((0.0, 0.0, 0.0))
    if node.bl_idname == "ShaderNodeBackground":
        return color_times(compiler, compiler.value(node.inputs["Color"], "color"),
                           compiler.value(node.inputs["Strength"], "float"))
    if node.bl_idname == "ShaderNodeAddShader":
        a, b = (_radiance(compiler, linked_from(node.inputs[k]), warn) for k in (0, 1))
        return builder.combine(*(math_node(compiler, a + k, b + k, zero, "ADD") for k in range(3)))
    if node.bl_idname == "ShaderNodeMixShader":
        fac = compiler.value(node.inputs[0], "float")
        saturated = math_node(compiler, fac, one, zero, "MULTIPLY", clamp=True)
        rest = math_node(compiler, one, saturated, zero, "SUBTRACT")
        a, b = (_radiance(compiler, linked_from(node.inputs[k]), warn) for k in (1, 2))
        kept = [math_node(compiler, a + k, rest, zero, "MULTIPLY") for k in range(3)]
        return builder.combine(*(math_node(compiler, b + k, saturated, kept[k], "MULTIPLY_ADD")
                                 for k in range(3)))
    warn(f"shader node '{node.name}' ({node.bl_idname}) inside a mix of Backgrounds is not "
         "supported; it adds nothing")
    return builder.constant((0.0, 0.0, 0.0))


def convert_world_program(scene: Any, summary: ExportSummary) -> WorldProgram | None:
    """The world's node program (Background Color x Strength at each direction, or a mix of
    Backgrounds), or None when the world is a constant or an environment image."""
    root = _world_root(scene)
    mixed = root is not None and root.bl_idname in _SHADER_MIXES
    if not mixed:
        background = _background_node(scene)
        if background is None or not _uses_program(background):
            return None
    from ..shaders.nodes import NodeCompiler

    world = scene.world

    def warn(message: str) -> None:
        summary.warn(f"World '{world.name}': {message}")

    compiler = NodeCompiler(tuple(bpy.app.version), lambda node, message: warn(message),
                            world=True)
    register = _radiance(compiler, root, warn)
    if compiler.images:
        summary.warn(f"World '{world.name}': image textures inside the world's nodes are not "
                     "supported; they read black")
    # Cycles' Settings > Map Resolution sizes its importance map; Stratum also looks the baked
    # map up, so it keeps at least 1024 x 512 texels (0.35 degrees).
    cycles = getattr(world, "cycles", None)
    resolution = int(getattr(cycles, "sampling_map_resolution", 1024) or 1024)
    width = min(max(resolution, 1024), 4096)
    return WorldProgram(compiler.builder.program, register, width, width // 2)


def convert_environment(scene: Any, summary: ExportSummary) -> Environment | None:
    """The world's Environment Texture as an image for the native side, or None (then the
    constant background of convert_world applies)."""
    background = _background_node(scene)
    node = _environment_node(background) if background is not None else None
    if node is None or _uses_program(background):
        return None
    world = scene.world
    image = node.image
    if image is None:
        summary.warn(f"World '{world.name}': Environment Texture '{node.name}' has no image; "
                     "using a constant background")
        return None
    if node.projection != "EQUIRECTANGULAR":
        summary.warn(f"World '{world.name}': Environment Texture projection {node.projection} "
                     "is not supported; using a constant background")
        return None
    rotation = _mapping_rotation(node)
    if rotation is None:
        summary.warn(f"World '{world.name}': the Environment Texture's Vector input is not "
                     "supported (only Texture Coordinate Generated -> Mapping turning about Z); "
                     "using the unrotated equirectangular mapping")
        rotation = np.eye(3, dtype=np.float32)
    width, height = (int(v) for v in image.size)
    channels = int(image.channels)
    if width == 0 or height == 0 or channels == 0:
        summary.warn(f"World '{world.name}': image '{image.name}' has no pixels; using a "
                     "constant background")
        return None
    space = image.colorspace_settings.name
    if space not in LINEAR_COLOR_SPACES:
        summary.warn(f"World '{world.name}': image '{image.name}' is in colour space '{space}'; "
                     "its conversion to linear (OCIO) is pending, so its pixels are used as "
                     "Blender stores them")
    pixels = np.empty(width * height * channels, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(height, width, channels)[::-1]  # Blender: rows bottom to top
    if channels >= 3:
        img = pixels[:, :, :3]
    else:
        img = np.repeat(pixels[:, :, :1], 3, axis=2)
    img = np.ascontiguousarray(img, dtype=np.float32)
    invalid = ~(img >= 0.0) | np.isinf(img)  # NaN fails >= 0
    if invalid.any():
        summary.warn(f"World '{world.name}': image '{image.name}' has {int(invalid.sum())} "
                     "NaN, infinite or negative pixel values; rendered as 0")
        img[invalid] = 0.0
    return Environment(img, _strength(world, background, summary), rotation)
