"""The closure nodes of a shader tree (BSDFs, Emission, Holdout, Principled) as native closures,
and the records the walk of stratum.shader_graph produces (pure Python).

ClosureNodes is the half of shader_graph.Flattener that reads one closure node: its sockets,
their texture and program bindings, the Principled socket generations and Alpha. The walk (Mix
and Add Shaders, weights, warnings) is shader_graph's; the table of nodes and inputs is in
shader_graph's docstring."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

from . import native
from .fallbacks import COAT, COAT_IOR, IOR, SPECULAR, UNIT
from .shader_nodes.math_nodes import math_node

Rgb = tuple[float, float, float]

GLOSSY_NODES = ("ShaderNodeBsdfGlossy", "ShaderNodeBsdfAnisotropic")
VOLUME_NODES = frozenset({"ShaderNodeVolumeScatter", "ShaderNodeVolumeAbsorption",
                          "ShaderNodeVolumePrincipled", "ShaderNodeVolumeCoefficients"})
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


class ClosureNodes:
    """Reading closure nodes; mixed into shader_graph.Flattener, whose socket readers (scalar,
    color, texture, emission_program, ...) and walk state (_program_weight) it uses."""

    # ---- BSDF nodes ---------------------------------------------------------------------------

    def _reflectance(self, node: Any, name: str) -> Rgb:
        return self.color(node, name, DEFAULT_GREY, UNIT)

    def _roughness(self, node: Any) -> float:
        return self.scalar(node, "Roughness", 0.5, UNIT)

    def _distribution(self, node: Any, roughness: float) -> int:
        dist = getattr(node, "distribution", "GGX")
        if dist == "MULTI_GGX":
            return native.MICROFACET_MULTISCATTER_GGX
        if dist not in ("GGX", "SHARP") and roughness > 0.0:
            self.warn(node, f"distribution {dist} of '{node.name}' is rendered as GGX")
        return native.MICROFACET_GGX

    def _simple(self, node: Any) -> tuple[native.Material, list[Binding]] | None:
        """Closure and bindings of a single-closure node, or None if not supported."""
        kind = node.bl_idname
        bindings: list[Binding] = []
        if kind == "ShaderNodeBsdfDiffuse":
            self.texture(node, "Color", native.PARAM_BASE_COLOR, bindings)
            self.texture(node, "Normal", native.PARAM_NORMAL, bindings)
            self.unsupported_link(node, "Roughness")
            if self.raw(node, "Roughness", 0.0) != 0.0:
                self.warn(node, f"Diffuse '{node.name}': roughness (Oren-Nayar) is rendered as "
                                "Lambertian")
            return native.Material(model=native.closure_model("diffuse"),
                                   base_color=self._reflectance(node, "Color")), bindings
        if kind in GLOSSY_NODES or kind == "ShaderNodeBsdfGlass":
            self.texture(node, "Color", native.PARAM_BASE_COLOR, bindings)
            self.texture(node, "Roughness", native.PARAM_ROUGHNESS, bindings)
            self.texture(node, "Normal", native.PARAM_NORMAL, bindings)
            roughness = 0.0 if getattr(node, "distribution", "") == "SHARP" else \
                self._roughness(node)
            if kind in GLOSSY_NODES and self.raw(node, "Anisotropy", 0.0) != 0.0:
                self.warn(node, f"'{node.name}': anisotropy is rendered as isotropic")
            glass = kind == "ShaderNodeBsdfGlass"
            if glass:
                self.unsupported_link(node, "IOR", bindings)
            return native.Material(
                model=native.closure_model("glass" if glass else "glossy"),
                base_color=self._reflectance(node, "Color"), roughness=roughness,
                ior=self.scalar(node, "IOR", 1.5, IOR),
                distribution=self._distribution(node, roughness)), bindings
        if kind == "ShaderNodeBsdfTransparent":
            self.texture(node, "Color", native.PARAM_BASE_COLOR, bindings)
            return native.Material(model=native.closure_model("transparent"),
                                   base_color=self._reflectance(node, "Color")), bindings
        if kind == "ShaderNodeEmission":
            emission = self.emission(node, "Color", "Strength", (1.0, 1.0, 1.0), 1.0)
            if self.emission_program(node, "Color", "Strength", bindings):
                emission = (0.0, 0.0, 0.0)
            return native.Material(model=native.closure_model("emission"),
                                   base_color=(0.0, 0.0, 0.0), emission=emission), bindings
        if kind == "ShaderNodeHoldout":
            return native.Material(model=native.closure_model("holdout"),
                                   base_color=(0.0, 0.0, 0.0)), bindings
        return None

    def _principled(self, node: Any, weight: Rgb, weight_binding: Binding | None) -> None:
        v2 = node.inputs.get("Specular IOR Level") is not None or self.version >= (4, 0, 0)
        names = PRINCIPLED_V2 if v2 else PRINCIPLED_V1
        unsupported = [name for name, off in names["unsupported"]
                       if (socket := node.inputs.get(name)) is not None
                       and (socket.is_linked or float(socket.default_value) != off)]
        if unsupported:
            self.warn(node, f"Principled '{node.name}': " + ", ".join(f"'{n}'" for n in unsupported)
                      + " not supported (rendered without)")
        bindings: list[Any] = []
        for name, param in names["bindable"]:
            if param != native.PARAM_EMISSION:
                self.texture(node, name, param, bindings)
        for name in names["constant"]:
            if name != "Emission Strength":
                self.unsupported_link(node, name, bindings)
        programmed_emission = self.emission_program(node, names["emission"], "Emission Strength",
                                                    bindings)
        roughness = self._roughness(node)
        material = native.Material(
            model=native.closure_model("principled_v2" if v2 else "principled_v1"),
            base_color=self._reflectance(node, "Base Color"),
            roughness=roughness,
            metallic=self.scalar(node, "Metallic", 0.0, UNIT),
            specular=self.scalar(node, names["specular"], 0.5, SPECULAR),
            ior=self.scalar(node, "IOR", 1.5, IOR),
            emission=(0.0, 0.0, 0.0) if programmed_emission else self.emission(
                node, names["emission"], "Emission Strength", (0.0, 0.0, 0.0), 1.0),
            distribution=(native.MICROFACET_MULTISCATTER_GGX
                          if v2 and getattr(node, "distribution", "GGX") == "MULTI_GGX"
                          else native.MICROFACET_GGX),
            transmission=self.scalar(node, names["transmission"], 0.0, UNIT),
            coat=self.scalar(node, names["coat"], 0.0, COAT),
            coat_roughness=self.scalar(node, names["coat_roughness"], 0.03, UNIT),
            coat_ior=self.scalar(node, "Coat IOR", 1.5, COAT_IOR),
            coat_tint=self.color(node, "Coat Tint", (1.0, 1.0, 1.0), UNIT),
        )
        if not v2 and getattr(node, "distribution", "GGX") == "MULTI_GGX":
            self.warn(node, f"Principled '{node.name}': Multiscatter GGX is rendered as GGX "
                            "(Cycles 3.x model)")
        self._principled_alpha(node, weight, weight_binding, material, bindings)

    def _principled_alpha(self, node: Any, weight: Rgb, weight_binding: Binding | None,
                          material: native.Material, bindings: list[Binding]) -> None:
        """Alpha < 1 is Mix(Transparent, Principled, Alpha), as Cycles compiles it."""
        alpha_bindings: list[Any] = []
        self.texture(node, "Alpha", native.PARAM_WEIGHT, alpha_bindings)
        transparent = native.Material(model=native.closure_model("transparent"),
                                      base_color=(1.0, 1.0, 1.0))
        if alpha_bindings and isinstance(alpha_bindings[0], ProgramInput):
            # A node-driven alpha: transparent x (1 - saturate(a)), the BSDF x saturate(a).
            zero, one = self.nodes.builder.constant(0.0), self.nodes.builder.constant(1.0)
            alpha_register = alpha_bindings[0].register
            saturated = math_node(self.nodes, alpha_register, one, zero, "MULTIPLY", clamp=True)
            rest = math_node(self.nodes, one, saturated, zero, "SUBTRACT")
            self._emit(weight, weight_binding, transparent, [], rest)
            self._emit(weight, weight_binding, material, bindings, saturated)
            return
        if alpha_bindings:
            alpha = alpha_bindings[0]
            if weight_binding is not None:
                self.warn(node, f"Principled '{node.name}': an image Alpha inside an "
                                "image-driven Mix Shader is not supported; using Alpha 1")
                self._emit(weight, weight_binding, material, bindings)
                return
            self._emit(weight, replace(alpha, scale=-1.0, offset=1.0), transparent, [])
            self._emit(weight, alpha, material, bindings)
            return
        alpha = self.scalar(node, "Alpha", 1.0, UNIT)
        if alpha < 1.0:
            self._emit(_scale(weight, 1.0 - alpha), weight_binding, transparent, [])
        self._emit(_scale(weight, alpha), weight_binding, material, bindings)


# Principled BSDF sockets per generation (Blender 3.x "v1", 4.x/5.x "v2").
PRINCIPLED_V1: dict[str, Any] = {
    "bindable": (("Base Color", native.PARAM_BASE_COLOR), ("Roughness", native.PARAM_ROUGHNESS),
                 ("Metallic", native.PARAM_METALLIC), ("Normal", native.PARAM_NORMAL),
                 ("Specular", native.PARAM_SPECULAR),
                 ("Transmission", native.PARAM_TRANSMISSION), ("Emission", native.PARAM_EMISSION)),
    "constant": ("IOR", "Clearcoat", "Clearcoat Roughness", "Emission Strength"),
    "unsupported": (("Subsurface", 0.0), ("Sheen", 0.0), ("Anisotropic", 0.0),
                    ("Specular Tint", 0.0), ("Transmission Roughness", 0.0)),
    "specular": "Specular", "emission": "Emission", "transmission": "Transmission",
    "coat": "Clearcoat", "coat_roughness": "Clearcoat Roughness",
}
PRINCIPLED_V2: dict[str, Any] = {
    "bindable": (("Base Color", native.PARAM_BASE_COLOR), ("Roughness", native.PARAM_ROUGHNESS),
                 ("Metallic", native.PARAM_METALLIC), ("Normal", native.PARAM_NORMAL),
                 ("Specular IOR Level", native.PARAM_SPECULAR),
                 ("Transmission Weight", native.PARAM_TRANSMISSION),
                 ("Emission Color", native.PARAM_EMISSION)),
    "constant": ("IOR", "Coat Weight", "Coat Roughness", "Coat IOR", "Coat Tint",
                 "Emission Strength"),
    "unsupported": (("Subsurface Weight", 0.0), ("Sheen Weight", 0.0), ("Anisotropic", 0.0),
                    ("Thin Film Thickness", 0.0), ("Diffuse Roughness", 0.0)),
    "specular": "Specular IOR Level", "emission": "Emission Color",
    "transmission": "Transmission Weight", "coat": "Coat Weight",
    "coat_roughness": "Coat Roughness",
}


def _scale(weight: Rgb, factor: float) -> Rgb:
    return (weight[0] * factor, weight[1] * factor, weight[2] * factor)
