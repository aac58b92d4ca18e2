"""Nodes that read the shading point or hold constants: Texture Coordinate, Geometry, Object
Info, UV Map, Attribute, Color Attribute, Camera Data, Wireframe, Tangent, Light Path, Value, RGB,
Separate XYZ and Combine XYZ.

| node (bl_idname)        | outputs -> renderer input (native.SHADER_INPUTS)                     |
|-------------------------|-----------------------------------------------------------------------|
| ShaderNodeTexCoord      | Generated, Normal (object space), UV, Object, Camera, Window,         |
|                         | Reflection (2 dot(N, I) N - I, world space, as Cycles); not Window    |
| ShaderNodeNewGeometry   | Position, Normal, Tangent, True Normal, Incoming, Parametric,         |
|                         | Backfacing (Pointiness, Random Per Island: not supported)             |
| ShaderNodeObjectInfo    | Location, Color, Alpha, Object Index, Material Index, Random          |
| ShaderNodeUVMap         | UV (the mesh's one UV set; another map's name is warned about)        |
| ShaderNodeAttribute,    | Color, Vector, Fac, Alpha of a mesh attribute (Geometry type) by name, |
| ShaderNodeVertexColor   | through one of 4 attribute slots (empty name: the render colour)       |
| ShaderNodeCameraData    | View Vector, View Z Depth, View Distance of the renderer's `camera`  |
|                         | point (native camera_data); in a world: not supported (warned)        |
| ShaderNodeWireframe     | Fac: 1 within Size / 2 of the hit triangle's edges (native wireframe: |
|                         | `position`, `triangle`, and with Pixel Size `true_normal`,            |
|                         | `incoming`, `pixel_footprint`); 0 in the world, as Cycles             |
| ShaderNodeTangent       | Tangent (native tangent): radial about X, Y or Z from `generated`,    |
|                         | through `normal_transform`; UV map: `mikktspace_tangent`, of the one  |
|                         | UV map a mesh carries (another map named: export/geometry.py warns)  |
| ShaderNodeLightPath     | each output its renderer input (`is_camera_ray` ... `portal_depth`,  |
|                         | Ray Length `ray_length`): what the integrator fills in, as Cycles'    |
|                         | path state in each context; 5.0's Is Volume Scatter Ray and Portal    |
|                         | Depth too (both 0: Stratum has no volumes nor Ray Portal)             |
| ShaderNodeScript        | not supported (OSL): SCRIPT_UNSUPPORTED, and the consuming socket's  |
|                         | own value, as Cycles without OSL drops the node and its links         |

Texture Coordinate's Object output of another object (its Object field set) and From Instancer
are not supported: one warning, and the node's own object is used. A Script node's closure
output adds no closure (stratum.shaders.closures), again as Cycles without OSL."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler, Unsupported
from .registry import translator


@translator("ShaderNodeTexCoord")
def texture_coordinate(c: NodeCompiler, node: Any) -> dict[str, int]:
    if getattr(node, "object", None) is not None:
        c.warn(node, f"Texture Coordinate '{node.name}': the Object output of another object is "
                     "not supported; using this object's coordinates", "object")
    if getattr(node, "from_instancer", False):
        c.warn(node, f"Texture Coordinate '{node.name}': From Instancer is not supported",
               "instancer")
    return {"Generated": c.geometry("generated"), "Normal": c.geometry("object_normal"),
            "UV": c.geometry("uv"), "Object": c.geometry("object"), "Camera": c.geometry("camera"),
            "Reflection": c.geometry("reflection")}


@translator("ShaderNodeNewGeometry")
def geometry(c: NodeCompiler, node: Any) -> dict[str, int]:
    return {"Position": c.geometry("position"), "Normal": c.geometry("normal"),
            "Tangent": c.geometry("tangent"), "True Normal": c.geometry("true_normal"),
            "Incoming": c.geometry("incoming"), "Parametric": c.geometry("parametric"),
            "Backfacing": c.geometry("backfacing")}


@translator("ShaderNodeObjectInfo")
def object_info(c: NodeCompiler, node: Any) -> dict[str, int]:
    return {"Location": c.geometry("object_location"), "Color": c.geometry("object_color"),
            "Alpha": c.geometry("object_alpha"), "Object Index": c.geometry("object_index"),
            "Material Index": c.geometry("material_index"), "Random": c.geometry("object_random")}


@translator("ShaderNodeUVMap")
def uv_map(c: NodeCompiler, node: Any) -> dict[str, int]:
    if str(getattr(node, "uv_map", "")):
        c.warn(node, f"UV Map '{node.name}': the mesh's active render UV map is used (Stratum "
                     f"carries one UV set), not '{node.uv_map}'", "uv_map")
    return {"UV": c.geometry("uv")}


# The key the exporter gives Color Attribute's empty name: the mesh's render colour attribute.
RENDER_COLOR = "\0render_color"


def _attribute_outputs(c: NodeCompiler, key: str, outputs: tuple[str, ...]) -> dict[str, int]:
    base = c.attribute(key)
    registers = {"Color": base, "Vector": base, "Alpha": base + 3, "Fac": base + 4}
    return {name: registers[name] for name in outputs}


@translator("ShaderNodeAttribute")
def attribute(c: NodeCompiler, node: Any) -> dict[str, int]:
    kind = str(getattr(node, "attribute_type", "GEOMETRY"))
    if kind != "GEOMETRY":
        raise Unsupported(f"Attribute '{node.name}': type {kind} is not supported (only "
                          "Geometry attributes)")
    return _attribute_outputs(c, str(node.attribute_name), ("Color", "Vector", "Fac", "Alpha"))


@translator("ShaderNodeVertexColor")
def color_attribute(c: NodeCompiler, node: Any) -> dict[str, int]:
    name = str(getattr(node, "layer_name", ""))
    return _attribute_outputs(c, name or RENDER_COLOR, ("Color", "Alpha"))


@translator("ShaderNodeCameraData")
def camera_data(c: NodeCompiler, node: Any) -> dict[str, int]:
    # Cycles reads sd->P unmoved inside a Bump's Height (its camera node has no bump offset),
    # hence the renderer's own input rather than c.geometry's stand-in.
    if c.world:
        raise Unsupported(f"Camera Data '{node.name}' in a world is not supported (the world is "
                          "baked per direction, without the camera)")
    vector, depth, distance = c.builder.node("camera_data", (), (c.builder.input("camera"),),
                                             (3, 1, 1))
    return {"View Vector": vector, "View Z Depth": depth, "View Distance": distance}


# Light Path's outputs (3.4's, and 5.0's two more) and the renderer inputs that hold them.
LIGHT_PATH_OUTPUTS = {
    "Is Camera Ray": "is_camera_ray", "Is Shadow Ray": "is_shadow_ray",
    "Is Diffuse Ray": "is_diffuse_ray", "Is Glossy Ray": "is_glossy_ray",
    "Is Singular Ray": "is_singular_ray", "Is Reflection Ray": "is_reflection_ray",
    "Is Transmission Ray": "is_transmission_ray", "Is Volume Scatter Ray": "is_volume_scatter_ray",
    "Ray Length": "ray_length", "Ray Depth": "ray_depth", "Diffuse Depth": "diffuse_depth",
    "Glossy Depth": "glossy_depth", "Transparent Depth": "transparent_depth",
    "Transmission Depth": "transmission_depth", "Portal Depth": "portal_depth",
}


@translator("ShaderNodeLightPath")
def light_path(c: NodeCompiler, node: Any) -> dict[str, int]:
    # The renderer's own inputs: Cycles' node reads the path state and sd->ray_length, which a
    # Bump's offset points do not move.
    return {out.name: c.builder.input(LIGHT_PATH_OUTPUTS[out.name]) for out in node.outputs
            if out.name in LIGHT_PATH_OUTPUTS}


@translator("ShaderNodeWireframe")
def wireframe(c: NodeCompiler, node: Any) -> dict[str, int]:
    # Inside a Bump's Height the position is the offset point's (c.geometry), as Cycles 4.4+.
    if "position" in c.overrides and not blender_versions.wireframe_at_bump_offsets(c.version):
        c.warn(node, f"Wireframe '{node.name}' inside a Bump's Height: this Blender's Cycles "
                     "adds a difference quotient at the point, which is not reproduced; "
                     "evaluated at the offset points as Blender 4.4 and later", "bump")
    size = c.input(node, "Size", "float")
    triangle = c.builder.input("triangle")
    fac = c.builder.node("wireframe", (int(bool(getattr(node, "use_pixel_size", False))),), (
        c.geometry("position"), size, c.geometry("true_normal"), c.geometry("incoming"),
        c.geometry("pixel_footprint"), triangle, triangle + 3, triangle + 6), (1,))[0]
    return {"Fac": fac}


TANGENT_DIRECTIONS = ("RADIAL", "UV_MAP")  # native mode 0
TANGENT_AXES = ("X", "Y", "Z")  # native mode 1


@translator("ShaderNodeTangent")
def tangent(c: NodeCompiler, node: Any) -> dict[str, int]:
    direction = str(getattr(node, "direction_type", "RADIAL"))
    axis = str(getattr(node, "axis", "Z"))
    if direction not in TANGENT_DIRECTIONS or axis not in TANGENT_AXES:
        raise Unsupported(f"Tangent '{node.name}': direction {direction}, axis {axis} is not "
                          "supported")
    if direction == "UV_MAP":
        c.uv_tangent_maps[node.name] = str(getattr(node, "uv_map", ""))
    # Cycles' svm_node_tangent reads the point unmoved inside a Bump's Height (it has no bump
    # offset), hence the renderer's own inputs rather than c.geometry's stand-ins.
    b = c.builder
    transform = b.input("normal_transform")
    out = b.node("tangent", (TANGENT_DIRECTIONS.index(direction), TANGENT_AXES.index(axis)), (
        b.input("generated"), b.input("normal"), transform, transform + 3, transform + 6,
        b.input("mikktspace_tangent")), (3,))[0]
    return {"Tangent": out}


def script_unsupported(node: Any) -> str:
    """The warning for a Script node: Cycles without Open Shading Language (its default, SVM,
    and any GPU) makes no node of it, so what it feeds reads as unlinked."""
    return (f"Script '{node.name}': OSL scripts are not supported (Stratum renders it as Cycles "
            "does without Open Shading Language, as if it were not linked)")


@translator("ShaderNodeScript")
def script(c: NodeCompiler, node: Any) -> dict[str, int]:
    raise Unsupported(script_unsupported(node))


@translator("ShaderNodeValue")
def value(c: NodeCompiler, node: Any) -> dict[str, int]:
    return {"Value": c.constant_of(node.outputs[0], "float")}


@translator("ShaderNodeRGB")
def rgb(c: NodeCompiler, node: Any) -> dict[str, int]:
    return {"Color": c.constant_of(node.outputs[0], "color")}


@translator("ShaderNodeSeparateXYZ")
def separate_xyz(c: NodeCompiler, node: Any) -> dict[str, int]:
    v = c.input(node, "Vector", "vector")
    return {"X": v, "Y": v + 1, "Z": v + 2}


@translator("ShaderNodeCombineXYZ")
def combine_xyz(c: NodeCompiler, node: Any) -> dict[str, int]:
    x, y, z = (c.input(node, k, "float") for k in ("X", "Y", "Z"))
    return {"Vector": c.builder.combine(x, y, z)}

