"""Color Attribute and Attribute nodes against Cycles (issue 18): a quad whose mesh carries a
corner colour attribute (the render colour), a point-domain float attribute and a face-domain
vector attribute, each drawn through an Emission plane by one node, rendered by Cycles and by
Stratum at 1 sample per pixel through a 0.01 px box filter, in the running Blender.

Runs in Blender 3.4 (`blender -b --factory-startup -noaudio --python tests/blender/run_in_blender.py
-- tests/blender/test_attribute_nodes.py`) and under the bpy wheel.

Tolerance. The attributes interpolate linearly over each triangle, so a pixel's value moves by
the slope times the distance its sample lies from the centre: both renderers sample within
0.005 px of it, so |S - C| <= 0.01 (slope_x + slope_y) with slope_x the largest difference
between the pixel and its horizontal neighbours in the Cycles image (likewise y), plus 1e-4 for
float rounding of values of order 1. The quad is four triangles around an inner
vertex placed so that no edge runs through a pixel centre; where a corner or face attribute jumps
across an edge, the pixels beside it differ from their neighbours by the jump, which the
formula then allows for the (rare) sample that crosses.
"""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from agreement import (
    OUT,
    add_top_ortho_camera,
    new_scene,
    render_pixel_centres,
    stratum_available,
)

RES = 16
CASES = {
    # name: (node, output, attribute name or "" for the render colour)
    "color_attribute": ("ShaderNodeVertexColor", "Color", ""),
    "color_alpha": ("ShaderNodeVertexColor", "Alpha", ""),
    "point_float_fac": ("ShaderNodeAttribute", "Fac", "height"),
    "point_float_color": ("ShaderNodeAttribute", "Color", "height"),
    "face_vector": ("ShaderNodeAttribute", "Vector", "push"),
    "face_vector_fac": ("ShaderNodeAttribute", "Fac", "push"),
    "missing_alpha": ("ShaderNodeAttribute", "Alpha", "nowhere"),
}
ATTR_OUT = OUT.parent / (OUT.name + "-attributes")


def _quad() -> bpy.types.Mesh:
    mesh = bpy.data.meshes.new("quad")
    # The inner vertex off the centre: no triangle edge through a pixel centre (where a corner or
    # face attribute jumps and the two renderers' samples may fall on either side).
    mesh.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (0.13, -0.07, 0)],
                     [], [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)])
    colors = mesh.color_attributes.new("paint", "FLOAT_COLOR", "CORNER")
    corner = [(0.9, 0.1, 0.2, 0.3), (0.1, 0.8, 0.3, 1.0), (0.5, 0.5, 0.5, 0.6)]
    for i, value in enumerate(colors.data):
        value.color = corner[i % 3]
    mesh.color_attributes.render_color_index = 0
    height = mesh.attributes.new("height", "FLOAT", "POINT")
    for i, value in enumerate(height.data):
        value.value = 0.2 + 0.15 * i
    push = mesh.attributes.new("push", "FLOAT_VECTOR", "FACE")
    for i, value in enumerate(push.data):
        value.vector = (0.1 * (i + 1), 0.5, 1.0 - 0.2 * i)
    mesh.update()
    return mesh


def _scene(case: str) -> bpy.types.Scene:
    scene = new_scene(RES)
    node_type, output, name = CASES[case]
    mat = bpy.data.materials.new(case)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    emission = nt.nodes.new("ShaderNodeEmission")
    node = nt.nodes.new(node_type)
    if node_type == "ShaderNodeVertexColor":
        node.layer_name = name
    else:
        node.attribute_name = name
    socket = emission.inputs["Strength" if output in ("Fac", "Alpha") else "Color"]
    nt.links.new(node.outputs[output], socket)
    nt.links.new(emission.outputs[0], out.inputs["Surface"])
    quad = bpy.data.objects.new("quad", _quad())
    quad.data.materials.append(mat)
    scene.collection.objects.link(quad)
    add_top_ortho_camera(scene)
    return scene


def _render(case: str, engine: str) -> np.ndarray:
    return render_pixel_centres(_scene(case), engine, ATTR_OUT / f"{case}_{engine.lower()}.exr",
                                RES)


def _slope(img: np.ndarray) -> np.ndarray:
    pad = np.pad(img, ((1, 1), (1, 1), (0, 0)), mode="edge")
    sx = np.maximum(np.abs(pad[1:-1, 2:] - img), np.abs(pad[1:-1, :-2] - img))
    sy = np.maximum(np.abs(pad[2:, 1:-1] - img), np.abs(pad[:-2, 1:-1] - img))
    return sx + sy


@pytest.mark.parametrize("case", list(CASES))
def test_attribute_nodes_agree_with_cycles(case: str, stratum_addon, library) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    cycles = _render(case, "CYCLES")
    stratum = _render(case, "STRATUM")
    assert np.abs(cycles).max() > 0.05, f"{case}: Cycles drew nothing ({np.abs(cycles).max()})"
    tolerance = 0.01 * _slope(cycles) + 1e-4
    worst = np.unravel_index(np.argmax(np.abs(stratum - cycles) - tolerance), cycles.shape)
    assert (np.abs(stratum - cycles) <= tolerance).all(), (
        f"{case}: pixel {worst[:2]} channel {worst[2]}: Cycles {cycles[worst]:.6f}, Stratum "
        f"{stratum[worst]:.6f}, tolerance {tolerance[worst]:.2e}")
