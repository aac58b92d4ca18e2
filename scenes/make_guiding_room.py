"""Build the path-guiding scene of issue 17 (acceptance 5, claim 10): a closed room lit only
through a light well in its ceiling, and save it as a compressed .blend.

Run (Blender 3.4, so that the file opens in 3.4 and in every later Blender):

    blender -b --factory-startup --python scenes/make_guiding_room.py -- scenes/guiding_room.blend

Guiding pays where light arrives indirectly: where next-event estimation cannot reach the light
(its shadow rays are blocked) and BSDF sampling rarely finds the few directions the light comes
from. The room (ROOM: 4 m x 4 m x 2.6 m, Lambert walls of albedo 0.45-0.75, a box and a tall
block on the floor) is closed but for an opening of OPENING x OPENING in the ceiling; above it
a light well WELL_HEIGHT high with black walls, capped by an emissive quad facing down (the only
light, strength EMISSION). The black well collimates the light: only points inside a cone of
half-angle atan(OPENING / WELL_HEIGHT) ~ 18 degrees below the opening see the emitter, so it
lights a patch of the floor near the front-right corner directly and every other surface only
through the bounce from that patch; shadow rays from anywhere else are all blocked. The camera
(24 mm, in the front-left corner looking at the back wall) sees no directly lit point (the
floor patch and the foot of the two walls beside it; tests/blender/test_guiding_room.py): what
it sees is lit by bounces only. The emitter is a mesh, not a lamp, so BSDF sampling can hit it
(`light_sampling=bsdf` sees it) and its radiance means the same in Cycles and Stratum.

Materials are Diffuse BSDF nodes (Lambert), the world black, the stored resolution 128x96 at
the Standard view transform; the stored engine is Cycles (`-E STRATUM` selects Stratum at
render time).
"""

from __future__ import annotations

import os
import sys

import bpy

# Blender does not put a --python script's folder on sys.path; scene_building.py is there.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_building import (
    Face,
    Vec,
    aim,
    clear_scene,
    emission,
    mesh_object,
    node_material,
    output_path,
    perspective_camera,
    png_render_settings,
    quad,
    save,
    uniform_world,
)

ROOM = (2.0, 2.0, 2.6)  # half width (x), half depth (y), height (m)
OPENING = 0.4  # side of the square opening in the ceiling (m)
OPENING_CENTRE = (1.1, -1.2)  # (x, y) of the opening: over the front-right of the room
WELL_HEIGHT = 1.2  # m from the ceiling to the emitter
EMISSION = 1500.0  # emitter strength (white): the floor patch's irradiance is ~ L A / d^2


def lambert(name: str, color: Vec) -> bpy.types.Material:
    """A Diffuse BSDF (Lambert, roughness 0) of albedo `color`."""
    mat, nodes, links, out = node_material(name)
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*color, 1.0)
    diffuse.location = (out.location.x - 250, out.location.y)
    links.new(diffuse.outputs["BSDF"], out.inputs["Surface"])
    mat.diffuse_color = (*color, 1.0)  # viewport colour only
    return mat


def box(name: str, lo: Vec, hi: Vec, material: bpy.types.Material) -> bpy.types.Object:
    """Axis-aligned box [lo, hi], faces outward."""
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    faces: list[Face] = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2),
                         (1, 3, 7, 5)]
    return mesh_object(name, v, faces, material)


def floor_quad(x0: float, x1: float, y0: float, y1: float, z: float, up: bool) -> list[Vec]:
    """The corners of [x0, x1] x [y0, y1] at height z, counter-clockwise seen from the side
    the normal faces (+z when up)."""
    corners = [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]
    return corners if up else corners[::-1]


def build_room() -> None:
    X, Y, Z = ROOM
    grey = lambert("Grey", (0.7, 0.7, 0.7))
    ceiling = lambert("Ceiling", (0.75, 0.75, 0.75))
    warm = lambert("Warm", (0.75, 0.55, 0.45))
    cool = lambert("Cool", (0.45, 0.6, 0.75))
    quad("Floor", floor_quad(-X, X, -Y, Y, 0.0, up=True), grey)
    # Walls, normals inward.
    quad("BackWall", [(-X, Y, 0.0), (-X, Y, Z), (X, Y, Z), (X, Y, 0.0)], grey)
    quad("FrontWall", [(-X, -Y, 0.0), (X, -Y, 0.0), (X, -Y, Z), (-X, -Y, Z)], grey)
    quad("LeftWall", [(-X, -Y, 0.0), (-X, -Y, Z), (-X, Y, Z), (-X, Y, 0.0)], warm)
    quad("RightWall", [(X, -Y, 0.0), (X, Y, 0.0), (X, Y, Z), (X, -Y, Z)], cool)
    # The ceiling (normals down) around the opening [hx0, hx1] x [hy0, hy1].
    cx, cy = OPENING_CENTRE
    hx0, hx1, hy0, hy1 = cx - OPENING / 2, cx + OPENING / 2, cy - OPENING / 2, cy + OPENING / 2
    for name, (x0, x1, y0, y1) in (("CeilingFront", (-X, X, -Y, hy0)),
                                   ("CeilingBack", (-X, X, hy1, Y)),
                                   ("CeilingLeft", (-X, hx0, hy0, hy1)),
                                   ("CeilingRight", (hx1, X, hy0, hy1))):
        quad(name, floor_quad(x0, x1, y0, y1, Z, up=False), ceiling)
    # The light well: black walls (normals inward) and the emitter facing down on top.
    black = lambert("WellBlack", (0.0, 0.0, 0.0))
    top = Z + WELL_HEIGHT
    quad("WellFront", [(hx0, hy0, Z), (hx1, hy0, Z), (hx1, hy0, top), (hx0, hy0, top)], black)
    quad("WellBack", [(hx0, hy1, Z), (hx0, hy1, top), (hx1, hy1, top), (hx1, hy1, Z)], black)
    quad("WellLeft", [(hx0, hy0, Z), (hx0, hy0, top), (hx0, hy1, top), (hx0, hy1, Z)], black)
    quad("WellRight", [(hx1, hy0, Z), (hx1, hy1, Z), (hx1, hy1, top), (hx1, hy0, top)], black)
    quad("Emitter", floor_quad(hx0, hx1, hy0, hy1, top, up=False),
         emission("Light", (1.0, 1.0, 1.0), EMISSION))
    box("Box", (-0.1, 0.2, 0.0), (0.7, 1.0, 0.8), grey)
    box("Block", (-1.45, 0.95, 0.0), (-0.95, 1.45, 1.6), lambert("Block", (0.6, 0.65, 0.6)))


def main() -> None:
    path = output_path("scenes/make_guiding_room.py -- scenes/guiding_room.blend")
    clear_scene()
    scene = bpy.context.scene
    scene.name = "GuidingRoom"
    build_room()
    cam = perspective_camera(lens=24.0, clip_start=0.05, location=(-1.6, -1.8, 1.4))
    aim(cam, (-0.4, 2.0, 1.35))
    uniform_world(scene, (0.0, 0.0, 0.0))
    png_render_settings(scene, 128, 96)
    save(path)


main()
