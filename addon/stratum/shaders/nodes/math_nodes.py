"""Math node (ShaderNodeMath), 3.x and 4.x/5.x alike: three Value inputs (the third read by
Wrap, Compare, Multiply Add and the smooth minimum and maximum); the operation by Blender's
identifier, in the order the native math node numbers them (Cycles' NodeMathType, svm/types.h)."""

from __future__ import annotations

from typing import Any

from .compiler import NodeCompiler, Unsupported
from .registry import translator

MATH_OPERATIONS = (
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "SINE", "COSINE", "TANGENT", "ARCSINE", "ARCCOSINE",
    "ARCTANGENT", "POWER", "LOGARITHM", "MINIMUM", "MAXIMUM", "ROUND", "LESS_THAN", "GREATER_THAN",
    "MODULO", "ABSOLUTE", "ARCTAN2", "FLOOR", "CEIL", "FRACT", "SQRT", "INVERSE_SQRT", "SIGN",
    "EXPONENT", "RADIANS", "DEGREES", "SINH", "COSH", "TANH", "TRUNC", "SNAP", "WRAP", "COMPARE",
    "MULTIPLY_ADD", "PINGPONG", "SMOOTH_MIN", "SMOOTH_MAX", "FLOORED_MODULO")


def math_node(c: NodeCompiler, a: int, b: int, d: int, operation: str, clamp: bool = False) -> int:
    """A native math node on registers a, b and d (the third input)."""
    return c.builder.node("math", (MATH_OPERATIONS.index(operation), int(clamp)), (a, b, d),
                          (1,))[0]


def color_times(c: NodeCompiler, color: int, factor: int) -> int:
    """Register of a colour (three registers) times a float register, as an Emission's or a
    Background's Color x Strength: one multiply per channel, gathered into one vector."""
    zero = c.builder.constant(0.0)
    return c.builder.combine(*(math_node(c, color + k, factor, zero, "MULTIPLY")
                               for k in range(3)))


@translator("ShaderNodeMath")
def translate_math(c: NodeCompiler, node: Any) -> dict[str, int]:
    operation = str(node.operation)
    if operation not in MATH_OPERATIONS:
        raise Unsupported(f"Math node '{node.name}': operation {operation} is not supported")
    a, b, d = (c.input(node, k, "float") for k in range(3))
    return {"Value": math_node(c, a, b, d, operation, bool(getattr(node, "use_clamp", False)))}
