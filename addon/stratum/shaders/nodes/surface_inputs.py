"""Nodes that read the view at the shading point, and colour converters: Fresnel, Layer Weight,
Light Falloff, Blackbody and Wavelength (docs/shader_nodes.md).

Fresnel and Layer Weight read the renderer's incoming direction and back-face flag, and the
node's Normal input when it is linked, else the shading normal, as Cycles does. Light Falloff
reads the renderer's ray length: on a surface the distance the ray travelled, in a lamp's
program the distance to the point on the lamp (export/light_nodes.py), FLT_MAX for the world
and suns, where Cycles changed in 4.4 (blender_versions.light_falloff_revision). Blackbody and
Wavelength take Cycles' colour to the working space by the matrices Cycles derives from the
Blender version's OpenColorIO config (ShaderManager::init_xyz_transforms): its XYZ from the
config's aces_interchange role, Rec.709 through Cycles' built-in XYZ -> Rec.709 matrix. The
config's own matrix stands for Cycles' XYZ -> scene linear: Cycles reaches it through OCIO's
ACES AP0 -> XYZ D65 and back through its 6-digit copy of that matrix, which moves it by less
than 7e-7 relative (docs/blender_versions.md)."""

from __future__ import annotations

from typing import Any

from ... import blender_versions
from .compiler import NodeCompiler
from .registry import translator

Matrix = tuple[tuple[float, float, float], ...]

# Cycles' built-in XYZ (D65) -> Rec.709 matrix.
XYZ_TO_REC709_CYCLES: Matrix = ((3.2404542, -1.5371385, -0.4985314),
                                (-0.9692660, 1.8760108, 0.0415560),
                                (0.0556434, -0.2040259, 1.0572252))
# Blender 3.x config: "Linear ACES" is reached from Linear (Rec.709) through srgb_to_xyz.spimtx,
# so its XYZ -> scene linear is that file's inverse.
SRGB_TO_XYZ_3X: Matrix = ((0.4124564, 0.3575761, 0.1804375),
                          (0.2126729, 0.7151522, 0.0721750),
                          (0.0193339, 0.1191920, 0.9503041))
# Blender 4.0-4.5 config (OCIO profile 2): Linear Rec.709 from Linear CIE-XYZ D65.
XYZ_TO_REC709_4X: Matrix = ((3.2404373564920070, -1.5371305409000549, -0.4985288240756933),
                            (-0.9692674982687597, 1.8760136862977035, 0.0415560804587997),
                            (0.0556434463874256, -0.2040259700872272, 1.0572254813610864))
# Blender 5.0 config (OCIO profile 2.4): the same, with the 7-digit BT.709 matrix.
XYZ_TO_REC709_5X: Matrix = ((3.2409699, -1.5373832, -0.4986108),
                            (-0.9692436, 1.8759675, 0.0415551),
                            (0.0556301, -0.2039770, 1.0569715))


def _inverse(m: Matrix) -> Matrix:
    (a, b, c), (d, e, f), (g, h, i) = m
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return ((( e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det),
            ((f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det),
            ((d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det))


def _product(m: Matrix, n: Matrix) -> Matrix:
    return tuple(tuple(sum(m[r][k] * n[k][col] for k in range(3)) for col in range(3))
                 for r in range(3))


def xyz_to_rgb(version: tuple[int, ...]) -> Matrix:
    """The XYZ -> working RGB matrix Cycles uses in Blender `version`."""
    config = blender_versions.color_config(version)
    if config == 0:
        return _inverse(SRGB_TO_XYZ_3X)
    return XYZ_TO_REC709_4X if config == 1 else XYZ_TO_REC709_5X


IDENTITY: Matrix = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def rec709_to_rgb(version: tuple[int, ...]) -> Matrix:
    """Cycles' Rec.709 -> working RGB: the identity when its XYZ -> RGB is within 0.001 of the
    built-in XYZ -> Rec.709 (the film's is_rec709, true for every default config; 4.x's test
    is 1e-4, which its config's matrix also meets, 1.7e-5 away), else XYZ -> RGB after the
    built-in Rec.709 -> XYZ."""
    xyz = xyz_to_rgb(version)
    if all(abs(xyz[r][k] - XYZ_TO_REC709_CYCLES[r][k]) <= 0.001 for r in range(3)
           for k in range(3)):
        return IDENTITY
    return _product(xyz, _inverse(XYZ_TO_REC709_CYCLES))


def _flat(m: Matrix) -> list[float]:
    return [v for row in m for v in row]


def _view(c: NodeCompiler, node: Any) -> tuple[int, int, int]:
    """Normal (linked, else the shading normal), incoming direction, back-face flag."""
    socket = c.socket(node, "Normal")
    normal = c.value(socket, "vector") if c.linked(socket) else c.geometry("normal")
    return normal, c.geometry("incoming"), c.geometry("backfacing")


@translator("ShaderNodeFresnel")
def fresnel(c: NodeCompiler, node: Any) -> dict[str, int]:
    ior = c.input(node, "IOR", "float")
    normal, incoming, backfacing = _view(c, node)
    return {"Fac": c.builder.node("fresnel", (), (ior, normal, incoming, backfacing), (1,))[0]}


@translator("ShaderNodeLayerWeight")
def layer_weight(c: NodeCompiler, node: Any) -> dict[str, int]:
    blend = c.input(node, "Blend", "float")
    normal, incoming, backfacing = _view(c, node)
    fres, facing = c.builder.node("layer_weight", (), (blend, normal, incoming, backfacing),
                                  (1, 1))
    return {"Fresnel": fres, "Facing": facing}


@translator("ShaderNodeLightFalloff")
def light_falloff(c: NodeCompiler, node: Any) -> dict[str, int]:
    strength = c.input(node, "Strength", "float")
    smooth = c.input(node, "Smooth", "float")
    revision = blender_versions.light_falloff_revision(c.version)
    quadratic, linear, constant = c.builder.node(
        "light_falloff", (revision,), (strength, smooth, c.geometry("ray_length")), (1, 1, 1))
    return {"Quadratic": quadratic, "Linear": linear, "Constant": constant}


@translator("ShaderNodeBlackbody")
def blackbody(c: NodeCompiler, node: Any) -> dict[str, int]:
    t = c.input(node, "Temperature", "float")
    matrix = _flat(rec709_to_rgb(c.version))
    return {"Color": c.builder.node("blackbody", (), (t,), (3,), matrix)[0]}


@translator("ShaderNodeWavelength")
def wavelength(c: NodeCompiler, node: Any) -> dict[str, int]:
    nm = c.input(node, "Wavelength", "float")
    matrix = _flat(xyz_to_rgb(c.version))
    return {"Color": c.builder.node("wavelength", (), (nm,), (3,), matrix)[0]}
