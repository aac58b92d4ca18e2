"""The closure nodes of a shader tree (BSDFs, Emission, Holdout, Principled) as native closures
(pure Python). The walk that reaches them (Mix and Add Shaders, weights) is
stratum.shaders.surface, whose docstring tables the nodes and the inputs read."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from .. import blender_versions, native
from .fallbacks import COAT, COAT_IOR, IOR, SPECULAR, UNIT
from .inputs import InputReader
from .nodes import NodeCompiler
from .nodes.input_nodes import script_unsupported
from .nodes.math_nodes import math_node
from .records import DEFAULT_GREY, Binding, Closure, ClosureWeight, ProgramInput, Rgb

GLOSSY_NODES = ("ShaderNodeBsdfGlossy", "ShaderNodeBsdfAnisotropic")
VOLUME_NODES = frozenset({"ShaderNodeVolumeScatter", "ShaderNodeVolumeAbsorption",
                          "ShaderNodeVolumePrincipled", "ShaderNodeVolumeCoefficients"})


def program_product(nodes: NodeCompiler, weight: int | None, factor: int) -> int:
    """Program register of weight x factor (factor alone without a weight)."""
    if weight is None:
        return factor
    return math_node(nodes, weight, factor, nodes.builder.constant(0.0), "MULTIPLY")


class ClosureBuilder:
    """Makes the closures of one material's closure nodes into self.closures, reading their
    inputs through `inputs`."""

    def __init__(self, inputs: InputReader) -> None:
        self.inputs = inputs
        self.nodes = inputs.nodes
        self.version = inputs.version
        self.closures: list[Closure] = []

    def add(self, node: Any, weight: ClosureWeight) -> None:
        """The closures of one shader node that is not a Mix or Add Shader."""
        kind = node.bl_idname
        if kind == "ShaderNodeBsdfPrincipled":
            self._principled(node, weight)
        elif kind in VOLUME_NODES:
            # Cycles evaluates volume closures in volume shaders only (svm_node_closure_volume
            # returns for a surface), so on a surface input they add nothing.
            self.inputs.warn(node, f"volume shader '{node.name}' ({kind}) on a surface input "
                                   "adds nothing, as in Cycles")
        elif kind == "ShaderNodeScript":
            self.inputs.warn(node, script_unsupported(node) + "; it adds no closure")
        else:
            made = self._simple(node)
            if made is None:
                self.inputs.warn(node, f"shader node '{node.name}' ({kind}) is not supported; "
                                       "using a default Principled BSDF")
                made = (self._default_principled(), [])
            self._emit(weight, *made)

    def _emit(self, weight: ClosureWeight, material: native.Material, bindings: list[Any],
              program_weight: int | None = None) -> None:
        """Adds a closure; `program_weight` (a scalar register) multiplies its weight, after
        the Mix factors above it (weight.program)."""
        factor = weight.program
        if program_weight is not None:
            factor = program_product(self.nodes, factor, program_weight)
        if weight.image is None and factor is None and max(weight.rgb) <= 0.0:
            return  # Cycles drops closures of zero weight
        images = [b for b in bindings if isinstance(b, Binding)]
        programs = [b for b in bindings if isinstance(b, ProgramInput)]
        if weight.image is not None:
            images.append(weight.image)
        if factor is not None:
            programs.append(ProgramInput("weight", self.nodes.builder.broadcast(factor)))
        self.closures.append(Closure(weight.rgb, material, images, programs))

    def _default_principled(self) -> native.Material:
        v2 = blender_versions.principled_v2(self.version)
        return native.Material(
            model=native.closure_model("principled_v2" if v2 else "principled_v1"),
            base_color=DEFAULT_GREY, roughness=0.5, specular=0.5, ior=1.5 if v2 else 1.45,
            distribution=native.MICROFACET_MULTISCATTER_GGX if v2 else native.MICROFACET_GGX)

    # ---- BSDF nodes ---------------------------------------------------------------------------

    def _reflectance(self, node: Any, name: str) -> Rgb:
        return self.inputs.color(node, name, DEFAULT_GREY, UNIT)

    def _roughness(self, node: Any) -> float:
        return self.inputs.scalar(node, "Roughness", 0.5, UNIT)

    def _distribution(self, node: Any, roughness: float) -> int:
        dist = getattr(node, "distribution", "GGX")
        if dist == "MULTI_GGX":
            return native.MICROFACET_MULTISCATTER_GGX
        if dist not in ("GGX", "SHARP") and roughness > 0.0:
            self.inputs.warn(node, f"distribution {dist} of '{node.name}' is rendered as GGX")
        return native.MICROFACET_GGX

    def _simple(self, node: Any) -> tuple[native.Material, list[Binding]] | None:
        """Closure and bindings of a single-closure node, or None if not supported."""
        kind = node.bl_idname
        inputs = self.inputs
        bindings: list[Binding] = []
        if kind == "ShaderNodeBsdfDiffuse":
            inputs.texture(node, "Color", "base_color", bindings)
            inputs.texture(node, "Normal", "normal", bindings)
            inputs.constant_link(node, "Roughness")
            if inputs.raw(node, "Roughness", 0.0) != 0.0:
                inputs.warn(node, f"Diffuse '{node.name}': roughness (Oren-Nayar) is rendered "
                                  "as Lambertian")
            return native.Material(model=native.closure_model("diffuse"),
                                   base_color=self._reflectance(node, "Color")), bindings
        if kind in GLOSSY_NODES or kind == "ShaderNodeBsdfGlass":
            inputs.texture(node, "Color", "base_color", bindings)
            inputs.texture(node, "Roughness", "roughness", bindings)
            inputs.texture(node, "Normal", "normal", bindings)
            roughness = 0.0 if getattr(node, "distribution", "") == "SHARP" else \
                self._roughness(node)
            if kind in GLOSSY_NODES and inputs.raw(node, "Anisotropy", 0.0) != 0.0:
                inputs.warn(node, f"'{node.name}': anisotropy is rendered as isotropic")
            glass = kind == "ShaderNodeBsdfGlass"
            if glass:
                inputs.constant_link(node, "IOR", "ior", bindings)
            return native.Material(
                model=native.closure_model("glass" if glass else "glossy"),
                base_color=self._reflectance(node, "Color"), roughness=roughness,
                ior=inputs.scalar(node, "IOR", 1.5, IOR),
                distribution=self._distribution(node, roughness)), bindings
        if kind == "ShaderNodeBsdfTransparent":
            inputs.texture(node, "Color", "base_color", bindings)
            return native.Material(model=native.closure_model("transparent"),
                                   base_color=self._reflectance(node, "Color")), bindings
        if kind == "ShaderNodeEmission":
            emission = inputs.emission(node, "Color", "Strength", (1.0, 1.0, 1.0), 1.0)
            if inputs.emission_program(node, "Color", "Strength", bindings):
                emission = (0.0, 0.0, 0.0)
            return native.Material(model=native.closure_model("emission"),
                                   base_color=(0.0, 0.0, 0.0), emission=emission), bindings
        if kind == "ShaderNodeHoldout":
            return native.Material(model=native.closure_model("holdout"),
                                   base_color=(0.0, 0.0, 0.0)), bindings
        return None

    # ---- Principled BSDF ----------------------------------------------------------------------

    def _principled(self, node: Any, weight: ClosureWeight) -> None:
        inputs = self.inputs
        v2 = blender_versions.principled_v2(self.version, node)
        names = blender_versions.PRINCIPLED_V2 if v2 else blender_versions.PRINCIPLED_V1
        unsupported = [name for name, off in names.unsupported
                       if (socket := node.inputs.get(name)) is not None
                       and (socket.is_linked or float(socket.default_value) != off)]
        if unsupported:
            inputs.warn(node, f"Principled '{node.name}': "
                        + ", ".join(f"'{n}'" for n in unsupported)
                        + " not supported (rendered without)")
        bindings: list[Any] = []
        for name, param in names.bindable:
            if param != "emission":
                inputs.texture(node, name, param, bindings)
        for name, param in names.constant:
            inputs.constant_link(node, name, param, bindings)
        programmed_emission = inputs.emission_program(node, names.emission, "Emission Strength",
                                                      bindings)
        roughness = self._roughness(node)
        material = native.Material(
            model=native.closure_model("principled_v2" if v2 else "principled_v1"),
            base_color=self._reflectance(node, "Base Color"),
            roughness=roughness,
            metallic=inputs.scalar(node, "Metallic", 0.0, UNIT),
            specular=inputs.scalar(node, names.specular, 0.5, SPECULAR),
            ior=inputs.scalar(node, "IOR", 1.5, IOR),
            emission=(0.0, 0.0, 0.0) if programmed_emission else inputs.emission(
                node, names.emission, "Emission Strength", (0.0, 0.0, 0.0), 1.0),
            distribution=(native.MICROFACET_MULTISCATTER_GGX
                          if v2 and getattr(node, "distribution", "GGX") == "MULTI_GGX"
                          else native.MICROFACET_GGX),
            transmission=inputs.scalar(node, names.transmission, 0.0, UNIT),
            coat=inputs.scalar(node, names.coat, 0.0, COAT),
            coat_roughness=inputs.scalar(node, names.coat_roughness, 0.03, UNIT),
            coat_ior=inputs.scalar(node, "Coat IOR", 1.5, COAT_IOR),
            coat_tint=inputs.color(node, "Coat Tint", (1.0, 1.0, 1.0), UNIT),
        )
        if not v2 and getattr(node, "distribution", "GGX") == "MULTI_GGX":
            inputs.warn(node, f"Principled '{node.name}': Multiscatter GGX is rendered as GGX "
                              "(Cycles 3.x model)")
        self._principled_alpha(node, weight, material, bindings)

    def _principled_alpha(self, node: Any, weight: ClosureWeight, material: native.Material,
                          bindings: list[Binding]) -> None:
        """Alpha < 1 is Mix(Transparent, Principled, Alpha), as Cycles compiles it."""
        alpha_bindings: list[Any] = []
        self.inputs.texture(node, "Alpha", "weight", alpha_bindings)
        transparent = native.Material(model=native.closure_model("transparent"),
                                      base_color=(1.0, 1.0, 1.0))
        if alpha_bindings and isinstance(alpha_bindings[0], ProgramInput):
            # A node-driven alpha: transparent x (1 - saturate(a)), the BSDF x saturate(a).
            zero, one = self.nodes.builder.constant(0.0), self.nodes.builder.constant(1.0)
            alpha_register = alpha_bindings[0].register
            saturated = math_node(self.nodes, alpha_register, one, zero, "MULTIPLY", clamp=True)
            rest = math_node(self.nodes, one, saturated, zero, "SUBTRACT")
            self._emit(weight, transparent, [], rest)
            self._emit(weight, material, bindings, saturated)
            return
        if alpha_bindings:
            alpha = alpha_bindings[0]
            if weight.image is not None:
                self.inputs.warn(node, f"Principled '{node.name}': an image Alpha inside an "
                                       "image-driven Mix Shader is not supported; using Alpha 1")
                self._emit(weight, material, bindings)
                return
            self._emit(replace(weight, image=replace(alpha, scale=-1.0, offset=1.0)),
                       transparent, [])
            self._emit(replace(weight, image=alpha), material, bindings)
            return
        alpha = self.inputs.scalar(node, "Alpha", 1.0, UNIT)
        if alpha < 1.0:
            self._emit(replace(weight, rgb=_scale(weight.rgb, 1.0 - alpha)), transparent, [])
        self._emit(replace(weight, rgb=_scale(weight.rgb, alpha)), material, bindings)


def _scale(weight: Rgb, factor: float) -> Rgb:
    return (weight[0] * factor, weight[1] * factor, weight[2] * factor)
