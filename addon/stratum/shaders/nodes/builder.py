"""`ProgramBuilder`: a shader program under construction (pure Python, no bpy).

Registers are allocated as they are asked for: constants hold the unlinked sockets' values, each
node's outputs get fresh registers. The first `native.SHADER_INPUT_REGISTERS` are the renderer's
inputs (geometry of the shading point), read through `input()`."""

from __future__ import annotations

import math
from collections.abc import Sequence

from ... import native

FLOAT = 1
VECTOR = 3


class ProgramBuilder:
    def __init__(self) -> None:
        self.program = native.ShaderProgram()
        self._constants: dict[tuple[float, ...], int] = {}

    @property
    def empty(self) -> bool:
        return not self.program.nodes

    def input(self, name: str) -> int:
        """The register of a renderer input (native.SHADER_INPUTS: "position", "uv", ...)."""
        return native.SHADER_INPUTS[name][0]

    def constant(self, values: float | Sequence[float]) -> int:
        """A register (or three) holding `values`; equal constants share registers. A value that
        is NaN or infinite is stored as 0 (the ABI takes finite constants; the compiler warns
        about the socket first)."""
        vals = (values,) if isinstance(values, (int, float)) else tuple(values)
        clean = tuple(float(v) if math.isfinite(float(v)) else 0.0 for v in vals)
        found = self._constants.get(clean)
        if found is not None:
            return found
        at = len(self.program.registers)
        self.program.registers.extend(clean)
        self._constants[clean] = at
        return at

    def allocate(self, width: int) -> int:
        at = len(self.program.registers)
        self.program.registers.extend([0.0] * width)
        return at

    def node(self, kind: str, modes: Sequence[int] = (), inputs: Sequence[int] = (),
             outputs: Sequence[int] = (), data: Sequence[float] = ()) -> list[int]:
        """Appends a node of type `kind` (native.node_type) and returns the registers of its
        outputs, one per width in `outputs` (1 float, 3 vector/colour)."""
        if len(modes) > 6 or len(inputs) > 12 or len(outputs) > 6:
            raise ValueError(f"node {kind}: at most 6 modes, 12 inputs and 6 outputs")
        out = [self.allocate(width) for width in outputs]
        offset = len(self.program.data)
        clean = [float(v) if math.isfinite(float(v)) else 0.0 for v in data]
        self.program.data.extend(clean)
        self.program.nodes.append(native.ShaderNode(
            type=native.node_type(kind), modes=tuple(int(m) for m in modes),
            inputs=tuple(int(i) for i in inputs), outputs=tuple(out), data_offset=offset,
            data_count=len(clean)))
        return out

    def node_into(self, kind: str, modes: Sequence[int], inputs: Sequence[int],
                  outputs: Sequence[int], data: Sequence[float] = ()) -> None:
        """As node(), writing to the given output registers (e.g. one component of a vector)."""
        offset = len(self.program.data)
        clean = [float(v) if math.isfinite(float(v)) else 0.0 for v in data]
        self.program.data.extend(clean)
        self.program.nodes.append(native.ShaderNode(
            type=native.node_type(kind), modes=tuple(int(m) for m in modes),
            inputs=tuple(int(i) for i in inputs), outputs=tuple(int(o) for o in outputs),
            data_offset=offset, data_count=len(clean)))

    def combine(self, x: int, y: int, z: int) -> int:
        """Three float registers gathered into one vector (three copies, unless they already
        lie in a row)."""
        if y == x + 1 and z == x + 2:
            return x
        out = self.allocate(VECTOR)
        for k, src in enumerate((x, y, z)):
            self.node_into("copy", (0,), (src,), (out + k,))
        return out

    # ---- conversions between socket kinds (Cycles' svm/convert.h) ------------------------------

    def copy(self, kind: int, register: int, width: int) -> int:
        """A COPY node: kind 0 float, 1 vector, 2 float->vector, 3 vector->float (mean)."""
        return self.node("copy", (kind,), (register,), (width,))[0]

    def to_float_from_vector(self, register: int) -> int:
        return self.copy(3, register, FLOAT)

    def to_float_from_color(self, register: int, color_config: int) -> int:
        """A COPY node of kind 4: the luminance with the weights of colour configuration
        `color_config` (blender_versions.color_config)."""
        return self.node("copy", (4, color_config), (register,), (FLOAT,))[0]

    def broadcast(self, register: int) -> int:
        return self.copy(2, register, VECTOR)
