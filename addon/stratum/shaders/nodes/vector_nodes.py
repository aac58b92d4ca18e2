"""Vector and converter nodes: Vector Math, Map Range, Clamp, Mapping, Vector Rotate, Normal and
Vector Transform. Their sockets are the same in Blender 3.4 and 4.x/5.x (Map Range's vector form
reads the `_FLOAT3` sockets); where Cycles' kernels changed between versions, the native node
takes a revision mode chosen from the Blender version (docs/shader_nodes.md).

| node (bl_idname)          | native node      | modes                                         |
|---------------------------|------------------|-----------------------------------------------|
| ShaderNodeVectorMath      | vector_math      | operation (Cycles' order), revision           |
| ShaderNodeMapRange        | map_range        | data type, interpolation, clamp               |
| ShaderNodeClamp           | clamp            | MINMAX / RANGE                                |
| ShaderNodeMapping         | mapping          | POINT / TEXTURE / VECTOR / NORMAL             |
| ShaderNodeVectorRotate    | vector_rotate    | rotation type, invert                         |
| ShaderNodeNormal          | normal           | -                                             |
| ShaderNodeVectorTransform | vector_transform | type, from, to (equal spaces only), revision  |

Vector Transform between two different spaces needs the object's or camera's transform, which a
program does not carry: Unsupported (one warning; the Vector input's value is used)."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler, Unsupported
from .registry import translator

# Cycles' NodeVectorMathType order (kernel/svm/types.h); POWER and SIGN are new in Blender 5.0.
VECTOR_OPERATIONS = (
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "CROSS_PRODUCT", "PROJECT", "REFLECT", "DOT_PRODUCT",
    "DISTANCE", "LENGTH", "SCALE", "NORMALIZE", "SNAP", "FLOOR", "CEIL", "MODULO", "FRACTION",
    "ABSOLUTE", "MINIMUM", "MAXIMUM", "WRAP", "SINE", "COSINE", "TANGENT", "REFRACT",
    "FACEFORWARD", "MULTIPLY_ADD", "POWER", "SIGN")
INTERPOLATIONS = ("LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP")
CLAMP_TYPES = ("MINMAX", "RANGE")
MAPPING_TYPES = ("POINT", "TEXTURE", "VECTOR", "NORMAL")
ROTATION_TYPES = ("AXIS_ANGLE", "X_AXIS", "Y_AXIS", "Z_AXIS", "EULER_XYZ")
# Cycles' NodeVectorTransformType and ConvertSpace orders.
TRANSFORM_TYPES = ("VECTOR", "POINT", "NORMAL")
SPACES = ("WORLD", "OBJECT", "CAMERA")


def _pick(node: Any, prop: str, names: tuple[str, ...], default: str) -> int:
    value = str(getattr(node, prop, default))
    if value not in names:
        raise Unsupported(f"{node.bl_idname} '{node.name}': {prop} {value} is not supported")
    return names.index(value)


@translator("ShaderNodeVectorMath")
def vector_math(c: NodeCompiler, node: Any) -> dict[str, int]:
    op = _pick(node, "operation", VECTOR_OPERATIONS, "ADD")
    a = c.input(node, "Vector", "vector")
    b = c.input(node, "Vector_001", "vector")
    d = c.input(node, "Vector_002", "vector")
    scale = c.input(node, "Scale", "float")
    vec, val = c.builder.node("vector_math", (op, blender_versions.vector_math_revision(c.version)),
                              (a, b, d, scale), (3, 1))
    return {"Vector": vec, "Value": val}


FLOAT_RANGE = ("Value", "From Min", "From Max", "To Min", "To Max", "Steps")
VECTOR_RANGE = ("Vector", "From_Min_FLOAT3", "From_Max_FLOAT3", "To_Min_FLOAT3", "To_Max_FLOAT3",
                "Steps_FLOAT3")


@translator("ShaderNodeMapRange")
def map_range(c: NodeCompiler, node: Any) -> dict[str, int]:
    data_type = str(getattr(node, "data_type", "FLOAT"))
    if data_type not in ("FLOAT", "FLOAT_VECTOR"):
        raise Unsupported(f"Map Range '{node.name}': data type {data_type} is not supported")
    vector = data_type == "FLOAT_VECTOR"
    interpolation = _pick(node, "interpolation_type", INTERPOLATIONS, "LINEAR")
    keys, kind = (VECTOR_RANGE, "vector") if vector else (FLOAT_RANGE, "float")
    inputs = [c.input(node, k, kind) for k in keys]
    clamp = int(bool(getattr(node, "clamp", False)))
    (out,) = c.builder.node("map_range", (int(vector), interpolation, clamp), inputs,
                            (3 if vector else 1,))
    return {"Vector": out} if vector else {"Result": out}


@translator("ShaderNodeClamp")
def clamp(c: NodeCompiler, node: Any) -> dict[str, int]:
    kind = _pick(node, "clamp_type", CLAMP_TYPES, "MINMAX")
    inputs = [c.input(node, k, "float") for k in ("Value", "Min", "Max")]
    return {"Result": c.builder.node("clamp", (kind,), inputs, (1,))[0]}


@translator("ShaderNodeMapping")
def mapping(c: NodeCompiler, node: Any) -> dict[str, int]:
    kind = _pick(node, "vector_type", MAPPING_TYPES, "POINT")
    inputs = [c.input(node, k, "vector") for k in ("Vector", "Location", "Rotation", "Scale")]
    return {"Vector": c.builder.node("mapping", (kind,), inputs, (3,))[0]}


@translator("ShaderNodeVectorRotate")
def vector_rotate(c: NodeCompiler, node: Any) -> dict[str, int]:
    kind = _pick(node, "rotation_type", ROTATION_TYPES, "AXIS_ANGLE")
    invert = int(bool(getattr(node, "invert", False)))
    inputs = [c.input(node, "Vector", "vector"), c.input(node, "Center", "vector"),
              c.input(node, "Axis", "vector"), c.input(node, "Angle", "float"),
              c.input(node, "Rotation", "vector")]
    return {"Vector": c.builder.node("vector_rotate", (kind, invert), inputs, (3,))[0]}


@translator("ShaderNodeNormal")
def normal(c: NodeCompiler, node: Any) -> dict[str, int]:
    # The node's direction is its Normal output's own value (Cycles' NormalNode direction).
    direction = c.constant_of(node.outputs[0], "vector")
    vec, dot = c.builder.node("normal", (), (c.input(node, "Normal", "vector"), direction),
                              (3, 1))
    return {"Normal": vec, "Dot": dot}


@translator("ShaderNodeVectorTransform")
def vector_transform(c: NodeCompiler, node: Any) -> dict[str, int]:
    kind = _pick(node, "vector_type", TRANSFORM_TYPES, "VECTOR")
    source = _pick(node, "convert_from", SPACES, "WORLD")
    target = _pick(node, "convert_to", SPACES, "OBJECT")
    if source != target:
        raise Unsupported(f"Vector Transform '{node.name}': {SPACES[source]} to {SPACES[target]} "
                          "needs the object's or camera's transform, which Stratum's node "
                          "programs do not carry")
    revision = blender_versions.vector_transform_revision(c.version)
    vec = c.input(node, "Vector", "vector")
    return {"Vector": c.builder.node("vector_transform", (kind, source, target, revision), (vec,),
                                     (3,))[0]}
