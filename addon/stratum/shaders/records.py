"""What flattening a surface tree produces (pure Python): closures, each with its RGB weight,
its native material and what drives its parameters (image bindings, registers of the
material's node program), and the weight a closure node is reached with."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from .. import native

Rgb = tuple[float, float, float]

DEFAULT_GREY: Rgb = (0.8, 0.8, 0.8)


@dataclass(frozen=True)
class ImageRef:
    """An Image Texture node and the UV layer it reads ("" = the mesh's active render UV)."""

    node: Any
    uv_map: str = ""


@dataclass(frozen=True)
class Binding:
    """A texture driving one closure parameter: value = offset + scale * texel."""

    param: int
    image: ImageRef
    channel: int = -1  # -1 = RGB (luminance for a scalar parameter), 3 = alpha
    scale: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True)
class ProgramInput:
    """A closure parameter driven by the material's node program: the register holding it
    (native.PROGRAM_PARAMS names the parameter)."""

    param: str
    register: int


@dataclass
class Closure:
    weight: Rgb
    material: native.Material
    bindings: list[Binding] = field(default_factory=list)
    programs: list[ProgramInput] = field(default_factory=list)


@dataclass(frozen=True)
class ClosureWeight:
    """What scales the closures of a closure node: `rgb`, the sum over the paths reaching it of
    the constant factors along each (stratum.shaders.flow); `image`, the factor of the
    image-driven Mix Shader above it, if any; `program`, the program register holding the
    product of the node-driven Mix factors above it, if any."""

    rgb: Rgb
    image: Binding | None = None
    program: int | None = None
