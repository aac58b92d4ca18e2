"""Build the Cornell box test scene and save it as a compressed .blend.

Run (Blender 3.4, so that the file opens in 3.4 and in every later Blender):

    blender -b --factory-startup --python scenes/make_cornell_box.py -- scenes/cornell_box.blend

Only bpy.data is used (no operators that need a UI context), so the script also runs under
the `bpy` wheel. Geometry is written with Mesh.from_pydata; every wall normal points into the
box. What the scene exercises:

* 5 walls: floor, ceiling, back (white 0.8), left (red), right (green); each a Principled BSDF
  material made the default way (use_nodes = True) with only Base Color changed;
* two boxes, rotated as in the classic scene, that are two objects sharing ONE mesh datablock
  ("BoxMesh", a unit cube) with different non-uniform object scales: the exporter must
  instance one mesh under two transforms;
* one smooth-shaded UV sphere (32 x 16) on the short box: interpolated normals;
* the light: an emissive quad (Emission shader, strength EMISSION_STRENGTH) just below the
  ceiling, facing down. An emissive mesh, not a Blender lamp, because its radiance is the same
  unambiguous number in Cycles and in Stratum;
* a perspective camera (40 mm, sensor fit AUTO) looking into the open front; black world.

Box coordinates: x in [-1, 1] (left..right), y in [-1, 1] (open front..back), z in [0, 2].
"""
import math
import os
import sys

import bpy

# Blender does not put a --python script's folder on sys.path; scene_building.py is there.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_building import (
    clear_scene,
    emission,
    mesh_object,
    output_path,
    perspective_camera,
    png_render_settings,
    principled,
    quad,
    save,
    uniform_world,
)

EMISSION_STRENGTH = 15.0  # radiance of the light quad (W/(sr m^2) in Blender's convention)
LIGHT_HALF = 0.25  # the light quad is 0.5 x 0.5 m
WHITE = (0.8, 0.8, 0.8)
RED = (0.8, 0.05, 0.05)
GREEN = (0.05, 0.8, 0.05)


def build_walls(white, red, green):
    # Each quad is listed counter-clockwise as seen from inside the box -> normals face inward.
    quad("Floor", [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], white)
    quad("Ceiling", [(-1, -1, 2), (-1, 1, 2), (1, 1, 2), (1, -1, 2)], white)
    quad("BackWall", [(-1, 1, 0), (1, 1, 0), (1, 1, 2), (-1, 1, 2)], white)
    quad("LeftWall", [(-1, -1, 0), (-1, 1, 0), (-1, 1, 2), (-1, -1, 2)], red)
    quad("RightWall", [(1, -1, 0), (1, -1, 2), (1, 1, 2), (1, 1, 0)], green)


def build_boxes(white):
    """Two objects, one mesh: the unit cube [-0.5, 0.5]^3 with its base moved to z = 0."""
    v = [(x, y, z) for z in (0.0, 1.0) for y in (-0.5, 0.5) for x in (-0.5, 0.5)]
    # vertex index = x + 2y + 4z (each 0/1); faces counter-clockwise from outside
    faces = [(0, 2, 3, 1),  # bottom (-z)
             (4, 5, 7, 6),  # top (+z)
             (0, 1, 5, 4),  # front (-y)
             (2, 6, 7, 3),  # back (+y)
             (0, 4, 6, 2),  # left (-x)
             (1, 3, 7, 5)]  # right (+x)
    tall = mesh_object("TallBox", v, faces, white)
    tall.data.name = "BoxMesh"
    tall.location = (-0.36, 0.3, 0.0)
    tall.rotation_euler = (0.0, 0.0, math.radians(17.0))
    tall.scale = (0.58, 0.58, 1.2)
    short = mesh_object("ShortBox", None, None, white, mesh=tall.data)  # linked duplicate
    short.location = (0.36, -0.3, 0.0)
    short.rotation_euler = (0.0, 0.0, math.radians(-18.0))
    short.scale = (0.58, 0.58, 0.6)
    return tall, short


def build_sphere(material, center, radius, segments=32, rings=16):
    verts = [(0.0, 0.0, radius)]
    for i in range(1, rings):
        theta = math.pi * i / rings
        for j in range(segments):
            phi = 2.0 * math.pi * j / segments
            verts.append((radius * math.sin(theta) * math.cos(phi),
                          radius * math.sin(theta) * math.sin(phi),
                          radius * math.cos(theta)))
    verts.append((0.0, 0.0, -radius))
    bottom = len(verts) - 1

    def ring(i, j):  # vertex of ring i (1..rings-1), segment j
        return 1 + (i - 1) * segments + (j % segments)

    faces = [(0, ring(1, j), ring(1, j + 1)) for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            faces.append((ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)))
    faces += [(ring(rings - 1, j + 1), ring(rings - 1, j), bottom) for j in range(segments)]
    sphere = mesh_object("Sphere", verts, faces, material, smooth=True)
    sphere.location = center
    return sphere


def build_light(material):
    h = LIGHT_HALF
    # Clockwise seen from above = counter-clockwise seen from below: normal points down (-z).
    light = quad("LightQuad", [(-h, -h, 0), (-h, h, 0), (h, h, 0), (h, -h, 0)], material)
    light.location = (0.0, 0.0, 1.98)
    return light


def build_camera():
    cam = perspective_camera(lens=40.0, clip_start=0.1, location=(0.0, -3.4, 1.0))
    # Blender cameras look down local -Z with +Y up: rotating 90 deg about X looks along +Y.
    cam.rotation_euler = (math.radians(90.0), 0.0, 0.0)
    return cam


def setup_render(scene):
    png_render_settings(scene, 256, 256)
    c = scene.cycles
    c.device = "CPU"
    c.samples = 128
    c.use_denoising = False
    c.max_bounces = 8
    c.diffuse_bounces = 8
    c.glossy_bounces = 8
    c.transmission_bounces = 8
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0


def main():
    path = output_path("scenes/make_cornell_box.py -- scenes/cornell_box.blend")
    clear_scene()
    scene = bpy.context.scene
    scene.name = "CornellBox"
    white = principled("White", WHITE)
    red = principled("Red", RED)
    green = principled("Green", GREEN)
    light = emission("Light", (1.0, 1.0, 1.0), EMISSION_STRENGTH)
    build_walls(white, red, green)
    build_boxes(white)
    build_sphere(white, center=(0.36, -0.3, 0.6 + 0.25), radius=0.25)
    build_light(light)
    build_camera()
    uniform_world(scene, (0.0, 0.0, 0.0))
    setup_render(scene)
    save(path)


main()
