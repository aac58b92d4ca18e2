"""The Bump node against Cycles (issue 18): a Diffuse plane whose Normal comes from a Bump node,
lit by a sun of angle 0, seen from above, direct light only, in the running Blender.

Runs in Blender 3.4 (`blender -b --factory-startup -noaudio --python tests/blender/run_in_blender.py
-- tests/blender/test_bump_agreement.py`) and under the bpy wheel.

With a delta sun, no bounce and a 0.01 px box filter, each pixel is one deterministic sample:
0.8/pi x E x max(cos, 0) x the bump shadowing term of the running Cycles, all functions of the
bumped normal. The heights are linear in the object's coordinates (through Separate XYZ and Math),
so the bumped normal is the same for any finite-difference step: Cycles steps by the ray
differential, Stratum by a thousandth of the ray length (docs/shader_nodes.md), and both give
the exact gradient. The pixels then agree to float rounding: |S - C| <= 1e-4 |C| + 1e-6.
Curved heights are covered by the procedural feature scene (its bump-mapped sphere), within the
feature tolerances.
"""

from __future__ import annotations

import math

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
# name: (x slope, y slope, distance, strength, invert)
CASES = {
    "slope_x": (0.5, 0.0, 1.0, 1.0, False),
    "slope_xy": (0.3, -0.4, 1.0, 1.0, False),
    "distance_half_inverted": (0.5, 0.2, 0.5, 1.0, True),
    "strength_half": (0.6, 0.0, 1.0, 0.5, False),
}
BUMP_OUT = OUT.parent / (OUT.name + "-bump")


def _scene(case: str) -> bpy.types.Scene:
    sx, sy, distance, strength, invert = CASES[case]
    scene = new_scene(RES)
    # Black through its nodes too: Blender 5.0's new worlds are grey Background nodes.
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    mat = bpy.data.materials.new(case)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    coords = nt.nodes.new("ShaderNodeTexCoord")
    separate = nt.nodes.new("ShaderNodeSeparateXYZ")
    along_x = nt.nodes.new("ShaderNodeMath")
    along_x.operation = "MULTIPLY"
    along_x.inputs[1].default_value = sx
    height = nt.nodes.new("ShaderNodeMath")
    height.operation = "MULTIPLY_ADD"
    height.inputs[1].default_value = sy
    bump = nt.nodes.new("ShaderNodeBump")
    bump.invert = invert
    bump.inputs["Distance"].default_value = distance
    bump.inputs["Strength"].default_value = strength
    nt.links.new(coords.outputs["Object"], separate.inputs[0])
    nt.links.new(separate.outputs["X"], along_x.inputs[0])
    nt.links.new(separate.outputs["Y"], height.inputs[0])
    nt.links.new(along_x.outputs[0], height.inputs[2])
    nt.links.new(height.outputs[0], bump.inputs["Height"])
    nt.links.new(bump.outputs["Normal"], diffuse.inputs["Normal"])
    nt.links.new(diffuse.outputs[0], out.inputs["Surface"])
    mesh = bpy.data.meshes.new("plane")
    mesh.from_pydata([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(mat)
    scene.collection.objects.link(bpy.data.objects.new("plane", mesh))
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 3.0
    sun.angle = 0.0
    sun_object = bpy.data.objects.new("sun", sun)
    sun_object.rotation_euler = (math.radians(25.0), math.radians(-35.0), 0.0)
    scene.collection.objects.link(sun_object)
    add_top_ortho_camera(scene)
    return scene


def _render(case: str, engine: str) -> np.ndarray:
    return render_pixel_centres(_scene(case), engine, BUMP_OUT / f"{case}_{engine.lower()}.exr",
                                RES, max_bounces=0)


@pytest.mark.parametrize("case", list(CASES))
def test_bump_agrees_with_cycles(case: str, stratum_addon, library) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    cycles = _render(case, "CYCLES")
    stratum = _render(case, "STRATUM")
    flat = 0.8 / math.pi * 3.0 * math.cos(math.radians(25.0)) * math.cos(math.radians(35.0))
    # The bump must change the shading (else the test compares two flat planes).
    assert abs(cycles.mean() - flat) > 0.02 * flat, f"{case}: Cycles {cycles.mean()}, flat {flat}"
    tolerance = 1e-4 * np.abs(cycles) + 1e-6
    worst = np.unravel_index(np.argmax(np.abs(stratum - cycles) - tolerance), cycles.shape)
    assert (np.abs(stratum - cycles) <= tolerance).all(), (
        f"{case}: pixel {worst[:2]} channel {worst[2]}: Cycles {cycles[worst]:.6f}, Stratum "
        f"{stratum[worst]:.6f}")
