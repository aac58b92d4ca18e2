"""Blender materials -> native materials (one id per distinct Blender material)."""

from __future__ import annotations

import math
from typing import Any

import bpy

from .. import native
from .common import (
    ExportSummary,
    active_output,
    linked_from,
    rgb,
    socket_value,
    uses_nodes,
)

DEFAULT_GREY = (0.8, 0.8, 0.8)

# Principled inputs that Stratum does not model: (socket name, value that means "off").
_V1_UNSUPPORTED = (
    ("Subsurface", 0.0),
    ("Transmission", 0.0),
    ("Clearcoat", 0.0),
    ("Sheen", 0.0),
    ("Anisotropic", 0.0),
)
_V2_UNSUPPORTED = (
    ("Subsurface Weight", 0.0),
    ("Transmission Weight", 0.0),
    ("Coat Weight", 0.0),
    ("Sheen Weight", 0.0),
    ("Anisotropic", 0.0),
    ("Thin Film Thickness", 0.0),
)
# Inputs whose values we read; if linked, we fall back to the socket's default value.
_READ_INPUTS = (
    "Base Color", "Roughness", "Metallic", "Specular", "Specular IOR Level", "IOR",
    "Emission", "Emission Color", "Emission Strength",
)


def _clamp01(color: tuple[float, float, float]) -> tuple[float, float, float]:
    return (min(max(color[0], 0.0), 1.0), min(max(color[1], 0.0), 1.0),
            min(max(color[2], 0.0), 1.0))


def _finite(x: float, fallback: float) -> float:
    return x if math.isfinite(x) else fallback


def _emission(color: Any, strength: Any) -> tuple[float, float, float]:
    c = rgb(color) if color is not None else (0.0, 0.0, 0.0)
    s = float(strength) if strength is not None else 1.0
    return (max(c[0] * s, 0.0), max(c[1] * s, 0.0), max(c[2] * s, 0.0))


def _principled(node: Any, issues: list[str]) -> native.Material:
    v2 = bpy.app.version >= (4, 0, 0) or node.inputs.get("Specular IOR Level") is not None
    for name, off in _V2_UNSUPPORTED if v2 else _V1_UNSUPPORTED:
        sock = node.inputs.get(name)
        if sock is None:
            continue
        if sock.is_linked or float(sock.default_value) != off:
            issues.append(name.lower())
    alpha = node.inputs.get("Alpha")
    if alpha is not None and (alpha.is_linked or float(alpha.default_value) < 1.0):
        issues.append("alpha")
    normal = node.inputs.get("Normal")
    if normal is not None and normal.is_linked:
        issues.append("normal map")
    linked = [n for n in _READ_INPUTS
              if node.inputs.get(n) is not None and node.inputs[n].is_linked]
    if linked:
        issues.append("linked " + ", ".join(linked) + " (using the socket values)")

    base = rgb(socket_value(node, "Base Color"))
    clamped = _clamp01(base)
    if clamped != base:
        issues.append("base color outside [0, 1] (clamped)")
    if v2:
        emission = _emission(socket_value(node, "Emission Color"),
                             socket_value(node, "Emission Strength"))
        specular = socket_value(node, "Specular IOR Level")
    else:
        emission = _emission(socket_value(node, "Emission"),
                             socket_value(node, "Emission Strength"))
        specular = socket_value(node, "Specular")
    ior = socket_value(node, "IOR")
    # Cycles 4.x/5.x model both distributions; the 3.x model here is single-scatter GGX only.
    multiscatter = getattr(node, "distribution", "GGX") == "MULTI_GGX"
    if multiscatter and not v2:
        issues.append("Multiscatter GGX (rendered as GGX)")
    return native.Material(
        model=native.MATERIAL_PRINCIPLED_V2 if v2 else native.MATERIAL_PRINCIPLED_V1,
        base_color=clamped,
        roughness=min(max(_finite(float(socket_value(node, "Roughness")), 0.5), 0.0), 1.0),
        metallic=min(max(_finite(float(socket_value(node, "Metallic")), 0.0), 0.0), 1.0),
        specular=max(_finite(float(specular if specular is not None else 0.5), 0.5), 0.0),
        ior=max(_finite(float(ior if ior is not None else 1.5), 1.5), 1e-3),
        emission=emission,
        distribution=(native.MICROFACET_MULTISCATTER_GGX if multiscatter and v2
                      else native.MICROFACET_GGX),
    )


def convert_material(material: Any | None) -> tuple[native.Material, list[str]]:
    """A native material and the list of unsupported features that were approximated."""
    issues: list[str] = []
    if material is None:
        return native.Material(model=native.MATERIAL_DIFFUSE, base_color=DEFAULT_GREY), issues
    if not uses_nodes(material):
        color = _clamp01(rgb(material.diffuse_color))
        return native.Material(model=native.MATERIAL_DIFFUSE, base_color=color), issues

    node_tree = material.node_tree
    output = active_output(node_tree, "ShaderNodeOutputMaterial")
    surface = output.inputs.get("Surface") if output is not None else None
    node = linked_from(surface) if surface is not None else None
    if node is None:
        # Cycles renders an unconnected surface black; keep it visible but say so.
        issues.append("no shader connected to the Material Output (using grey diffuse)")
        return native.Material(model=native.MATERIAL_DIFFUSE, base_color=DEFAULT_GREY), issues

    kind = node.bl_idname
    if kind == "ShaderNodeBsdfPrincipled":
        return _principled(node, issues), issues
    if kind == "ShaderNodeBsdfDiffuse":
        color_sock = node.inputs.get("Color")
        if color_sock is not None and color_sock.is_linked:
            issues.append("linked Color (using the socket value)")
        rough = node.inputs.get("Roughness")
        if rough is not None and (rough.is_linked or float(rough.default_value) != 0.0):
            issues.append("diffuse roughness (Oren-Nayar)")
        color = rgb(socket_value(node, "Color"))
        clamped = _clamp01(color)
        if clamped != color:
            issues.append("color outside [0, 1] (clamped)")
        return native.Material(model=native.MATERIAL_DIFFUSE, base_color=clamped), issues
    if kind == "ShaderNodeEmission":
        linked = [n for n in ("Color", "Strength") if node.inputs[n].is_linked]
        if linked:
            issues.append("linked " + ", ".join(linked) + " (using the socket values)")
        emission = _emission(socket_value(node, "Color"), socket_value(node, "Strength"))
        return native.Material(model=native.MATERIAL_EMISSION, base_color=(0.0, 0.0, 0.0),
                               emission=emission), issues
    issues.append(f"shader node '{node.name}' ({kind}) is not supported (using grey diffuse)")
    return native.Material(model=native.MATERIAL_DIFFUSE, base_color=DEFAULT_GREY), issues


class MaterialTable:
    """Assigns native material ids, once per Blender material (plus one default)."""

    def __init__(self, scene: native.Scene, summary: ExportSummary) -> None:
        self._scene = scene
        self._summary = summary
        self._ids: dict[int, int] = {}
        self._default: int | None = None

    def default_id(self) -> int:
        if self._default is None:
            desc, _ = convert_material(None)
            self._default = self._scene.add_material(desc)
            self._summary.materials += 1
        return self._default

    def id_for(self, material: Any | None) -> int:
        if material is None:
            return self.default_id()
        original = getattr(material, "original", material) or material
        key = original.as_pointer()
        found = self._ids.get(key)
        if found is not None:
            return found
        desc, issues = convert_material(material)
        if issues:
            self._summary.warn(f"Material '{material.name}': " + "; ".join(issues))
        mat_id = self._scene.add_material(desc)
        self._summary.materials += 1
        self._ids[key] = mat_id
        return mat_id
