"""Build the ambient-occlusion test scene of the sampler study and save it as a compressed .blend.

Run (Blender 3.4, so that the file opens in 3.4 and in every later Blender; after `make build`,
because the script registers the add-on from this checkout to store the AO settings):

    blender -b --factory-startup --python scenes/make_ao_study.py -- scenes/ao_study.blend

The article (seed 000, tables 2-3) compares hemisphere distributions and Fibonacci lattices on
the ambient-occlusion factor (eq. 20) of a scene with crevices. The Cornell box is a poor AO
test: its large open walls are fully unoccluded at any sensible AO distance, so most pixels
are exactly 1 and carry no error. This scene is mostly contact regions and crevices instead:

* a floor with a corner (two walls meeting at 90 degrees) behind the objects;
* a comb of thin parallel slabs (narrow slots: deep crevices);
* three spheres touching each other and the floor (point contacts, rings of occlusion);
* a torus lying on the floor (a circular crevice inside and out);
* a staircase of boxes (concave edges at every step) and a box leaning against a wall.

The integrator is stored as 'ao' with AO_DISTANCE chosen so that the AO image has mid-tones
over most of the frame (measured: see scenes/README.md). Every object has a Principled
material (unused by AO, so the scene also path-traces). Only bpy.data is used apart from
saving; the stored engine is Cycles (`-E STRATUM` selects Stratum at render time).
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path

import bpy

# Blender does not put a --python script's folder on sys.path; scene_building.py is there.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_building import (
    Face,
    Vec,
    aim,
    clear_scene,
    mesh_object,
    output_path,
    perspective_camera,
    png_render_settings,
    principled,
    quad,
    save,
    uniform_world,
)

AO_DISTANCE = 1.0  # m; objects are 0.2-0.8 m across (0.5 left 41 % of pixels exactly 1)
GREY = (0.7, 0.7, 0.7)


def box(name: str, lo: Vec, hi: Vec, material: bpy.types.Material,
        rotation_z: float = 0.0) -> bpy.types.Object:
    """Axis-aligned box [lo, hi] (faces outward), optionally rotated about z through its
    centre."""
    cx, cy = (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2
    hx, hy = (hi[0] - lo[0]) / 2, (hi[1] - lo[1]) / 2
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (-hy, hy) for x in (-hx, hx)]
    faces: list[Face] = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2),
                         (1, 3, 7, 5)]
    obj = mesh_object(name, v, faces, material)
    obj.location = (cx, cy, 0.0)
    obj.rotation_euler = (0.0, 0.0, rotation_z)
    return obj


def sphere(name: str, center: Vec, radius: float, material: bpy.types.Material,
           segments: int = 48, rings: int = 24) -> bpy.types.Object:
    verts: list[Vec] = [(0.0, 0.0, radius)]
    for i in range(1, rings):
        theta = math.pi * i / rings
        for j in range(segments):
            phi = 2.0 * math.pi * j / segments
            verts.append((radius * math.sin(theta) * math.cos(phi),
                          radius * math.sin(theta) * math.sin(phi), radius * math.cos(theta)))
    verts.append((0.0, 0.0, -radius))
    bottom = len(verts) - 1

    def ring(i: int, j: int) -> int:
        return 1 + (i - 1) * segments + (j % segments)

    faces: list[Face] = [(0, ring(1, j), ring(1, j + 1)) for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            faces.append((ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)))
    faces += [(ring(rings - 1, j + 1), ring(rings - 1, j), bottom) for j in range(segments)]
    obj = mesh_object(name, verts, faces, material, smooth=True)
    obj.location = center
    return obj


def torus(name: str, center: Vec, major: float, minor: float, material: bpy.types.Material,
          n_major: int = 64, n_minor: int = 24) -> bpy.types.Object:
    verts: list[Vec] = []
    for i in range(n_major):
        u = 2.0 * math.pi * i / n_major
        for j in range(n_minor):
            v = 2.0 * math.pi * j / n_minor
            r = major + minor * math.cos(v)
            verts.append((r * math.cos(u), r * math.sin(u), minor * math.sin(v)))
    faces: list[Face] = []
    for i in range(n_major):
        for j in range(n_minor):
            a = i * n_minor + j
            b = ((i + 1) % n_major) * n_minor + j
            c = ((i + 1) % n_major) * n_minor + (j + 1) % n_minor
            d = i * n_minor + (j + 1) % n_minor
            faces.append((a, b, c, d))
    obj = mesh_object(name, verts, faces, material, smooth=True)
    obj.location = center
    return obj


def build_objects(m: bpy.types.Material) -> None:
    # Floor and a corner: back wall at y = 1.2, left wall at x = -1.6.
    quad("Floor", [(-1.6, -3.0, 0.0), (3.0, -3.0, 0.0), (3.0, 1.2, 0.0), (-1.6, 1.2, 0.0)], m)
    quad("BackWall", [(-1.6, 1.2, 0.0), (3.0, 1.2, 0.0), (3.0, 1.2, 2.0), (-1.6, 1.2, 2.0)], m)
    quad("LeftWall", [(-1.6, -3.0, 0.0), (-1.6, 1.2, 0.0), (-1.6, 1.2, 2.0), (-1.6, -3.0, 2.0)],
         m)
    # A comb of thin slabs in the back-left corner region: slots 0.08 m wide, 0.5 m deep.
    for k in range(6):
        x0 = -1.3 + k * 0.12
        box(f"Slab{k}", (x0, 0.3, 0.0), (x0 + 0.04, 0.8, 0.45), m)
    # Three touching spheres of radius 0.22 (centres 0.44 apart) in the middle.
    r = 0.22
    for k, (x, y) in enumerate([(0.0, -0.2), (0.44, -0.2), (0.22, -0.2 + 0.44 * math.sqrt(0.75))]):
        sphere(f"Sphere{k}", (x, y, r), r, m)
    # A torus lying on the floor, front left.
    torus("Torus", (-0.8, -0.75, 0.12), 0.32, 0.12, m)
    # A staircase of four boxes against the back wall, right.
    for k in range(4):
        box(f"Step{k}", (1.0 + 0.2 * k, 0.4, 0.0), (1.9, 1.2, 0.15 * (k + 1)), m)
    # A box leaning on the right part of the back wall region, front right.
    lean = box("Leaning", (0.9, -0.9, 0.0), (1.5, -0.4, 0.35), m, rotation_z=math.radians(25.0))
    lean.data.name = "LeaningMesh"
    box("Small", (1.55, -0.6, 0.0), (1.75, -0.4, 0.2), m, rotation_z=math.radians(-10.0))


def build_camera() -> None:
    cam = perspective_camera(lens=32.0, clip_start=0.05, location=(0.4, -2.7, 2.0))
    aim(cam, (0.2, 0.1, 0.2))


def store_stratum_settings(scene: bpy.types.Scene) -> None:
    """Register the add-on from this checkout and store integrator 'ao' + AO_DISTANCE in the
    scene (they are saved as the scene's `stratum` properties and read back by the add-on)."""
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "addon"))
    import stratum

    stratum.register()
    s = scene.stratum
    s.integrator = "ao"
    s.hemisphere = "cosine"
    s.ao_distance = AO_DISTANCE
    s.samples = 16
    s.sampler = "random"


def main() -> None:
    path = output_path("scenes/make_ao_study.py -- scenes/ao_study.blend")
    clear_scene()
    scene = bpy.context.scene
    scene.name = "AOStudy"
    build_objects(principled("Grey", GREY))
    build_camera()
    uniform_world(scene, (1.0, 1.0, 1.0))  # white sky: Cycles' AO look under path tracing
    png_render_settings(scene, 256, 192)
    store_stratum_settings(scene)
    save(path)


main()
