"""Build the "Wolf" scene (high-polygon model on a floor) and save it as a compressed .blend.

Run (Blender 3.4, so that the file opens in 3.4 and in every later Blender):

    blender -b --factory-startup --python scenes/make_wolf.py -- scenes/wolf.blend

The coursework (seed 001, section 5) evaluates its samplers on "Wolf": a detailed model made in
Blender standing on a floor, with SPP 1, 2, 8 and magnified crops of the floor beside it. This
is a scene in that spirit, built procedurally so that the file stays tiny:

* the wolf is a skeleton of ~60 vertices and edges, each vertex with a skin radius, turned into
  a quad cage by a Skin modifier and smoothed by a Subdivision Surface modifier whose *render*
  level (RENDER_LEVELS) gives > 200k triangles. Only the skeleton is stored; Stratum's exporter
  takes the evaluated render depsgraph, so the modifiers are applied at export time;
* smooth shading (Skin's smooth-shade option), one Principled material (grey-brown, rough);
* a large floor quad (Principled, light grey) on which the wolf casts a soft shadow;
* one large disk area light plus a dim blue-grey world, so that the floor around the wolf has
  a wide penumbra, contact shadows under the paws and indirect light: the regions where
  sampler noise is visible. (One light, not a sun plus a fill: with two lights of very
  different power, Stratum's light choice made salt-and-pepper noise that dominated
  everything else at 128 spp);
* a 50 mm perspective camera at three-quarter view, slightly above the wolf.

Only bpy.data plus `modifiers.new` are used (no operators that need a UI context), so the
script also runs under the `bpy` wheel.
"""

from __future__ import annotations

import math
import os
import sys

import bpy

# Blender does not put a --python script's folder on sys.path; scene_building.py is there.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_building import (
    Vec,
    aim,
    clear_scene,
    output_path,
    perspective_camera,
    png_render_settings,
    principled,
    save,
    uniform_world,
)

RENDER_LEVELS = 4  # Subdivision Surface render level: each cage quad -> 4^4 = 256 quads
VIEWPORT_LEVELS = 1
FUR = (0.32, 0.27, 0.22)  # base colour of the wolf
FLOOR = (0.55, 0.55, 0.55)
WORLD = (0.05, 0.06, 0.08)  # dim blue-grey sky
AREA_POWER = 250.0  # W
AREA_SIZE = 1.5  # m, disk diameter: soft shadow with a wide penumbra
AREA_LOCATION = (-1.6, 1.0, 2.2)


class Skeleton:
    """Vertices with skin radii and the edges between them."""

    def __init__(self) -> None:
        self.verts: list[Vec] = []
        self.radii: list[float] = []
        self.edges: list[tuple[int, int]] = []

    def add(self, p: Vec, r: float, parent: int | None = None) -> int:
        self.verts.append(p)
        self.radii.append(r)
        i = len(self.verts) - 1
        if parent is not None:
            self.edges.append((parent, i))
        return i

    def chain(self, parent: int, points: list[tuple[Vec, float]]) -> int:
        """Append a chain of vertices hanging from `parent`; returns the last index."""
        last = parent
        for p, r in points:
            last = self.add(p, r, last)
        return last


def lerp_chain(a: Vec, b: Vec, ra: float, rb: float, n: int) -> list[tuple[Vec, float]]:
    """n points from a (exclusive) to b (inclusive) with linearly varying radius."""
    out = []
    for k in range(1, n + 1):
        t = k / n
        out.append(((a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t,
                     a[2] + (b[2] - a[2]) * t), ra + (rb - ra) * t))
    return out


def wolf_skeleton() -> Skeleton:
    """A standing wolf, facing -x, ~1.3 m from nose to tail tip, shoulder height ~0.75 m."""
    s = Skeleton()
    # Spine from the hips (x = +0.35) to the chest (x = -0.3), body deeper at the chest.
    hips = s.add((0.35, 0.0, 0.62), 0.15)
    mid = s.add((0.1, 0.0, 0.64), 0.16, hips)
    chest = s.add((-0.18, 0.0, 0.63), 0.19, mid)
    withers = s.add((-0.32, 0.0, 0.68), 0.16, chest)
    # Neck forward and only a little up (a wolf carries its head low), then the head and a
    # long tapering snout.
    neck = s.chain(withers, [((-0.45, 0.0, 0.74), 0.13), ((-0.55, 0.0, 0.78), 0.11)])
    head = s.add((-0.63, 0.0, 0.8), 0.1, neck)
    s.chain(head, [((-0.72, 0.0, 0.77), 0.065), ((-0.8, 0.0, 0.745), 0.045),
                   ((-0.86, 0.0, 0.735), 0.03)])
    # Ears: two short pointed chains up from the back of the head.
    for side in (-1.0, 1.0):
        base = s.add((-0.61, 0.05 * side, 0.88), 0.035, head)
        s.chain(base, [((-0.6, 0.06 * side, 0.93), 0.022), ((-0.595, 0.065 * side, 0.97), 0.008)])
    # Tail: from the hips down and back, bushy in the middle.
    s.chain(hips, [((0.5, 0.0, 0.6), 0.06), ((0.6, 0.0, 0.5), 0.075),
                   ((0.66, 0.0, 0.38), 0.07), ((0.69, 0.0, 0.28), 0.04)])
    # Legs: shoulder/hip -> elbow/stifle -> wrist/hock -> paw (slightly splayed).
    for side in (-1.0, 1.0):
        y = 0.09 * side
        fl = s.add((-0.24, y, 0.55), 0.085, chest)
        fl = s.chain(fl, [((-0.22, y, 0.36), 0.05), ((-0.24, y * 1.05, 0.14), 0.035),
                          ((-0.25, y * 1.05, 0.045), 0.032)])
        s.chain(fl, [((-0.3, y * 1.05, 0.03), 0.03)])  # front paw
        hl = s.add((0.33, y, 0.52), 0.1, hips)
        hl = s.chain(hl, [((0.26, y, 0.34), 0.06), ((0.36, y * 1.05, 0.16), 0.035),
                          ((0.34, y * 1.05, 0.045), 0.032)])
        s.chain(hl, [((0.29, y * 1.05, 0.03), 0.03)])  # hind paw
    # Subdivide the long spine/leg edges so the skin cage follows the radii smoothly.
    return refine(s, max_len=0.06)


def refine(s: Skeleton, max_len: float) -> Skeleton:
    """Split every edge longer than max_len into equal parts, interpolating the radius."""
    out = Skeleton()
    out.verts = list(s.verts)
    out.radii = list(s.radii)
    for a, b in s.edges:
        pa, pb = s.verts[a], s.verts[b]
        n = max(1, math.ceil(math.dist(pa, pb) / max_len))
        prev = a
        for p, r in lerp_chain(pa, pb, s.radii[a], s.radii[b], n)[:-1]:
            prev = out.add(p, r, prev)
        out.edges.append((prev, b))
    return out


def build_wolf(material: bpy.types.Material) -> bpy.types.Object:
    sk = wolf_skeleton()
    mesh = bpy.data.meshes.new("WolfSkeleton")
    mesh.from_pydata(sk.verts, sk.edges, [])
    mesh.materials.append(material)
    mesh.validate()
    mesh.update()
    obj = bpy.data.objects.new("Wolf", mesh)
    bpy.context.scene.collection.objects.link(obj)
    skin = obj.modifiers.new("Skin", "SKIN")  # creates the skin vertex layer and a root
    skin.use_smooth_shade = True
    skin.branch_smoothing = 0.5
    for vertex, r in zip(mesh.skin_vertices[0].data, sk.radii):
        vertex.radius = (r, r)
    sub = obj.modifiers.new("Subdivision", "SUBSURF")
    sub.levels = VIEWPORT_LEVELS
    sub.render_levels = RENDER_LEVELS
    sub.quality = 3
    return obj


def build_floor(material: bpy.types.Material, half: float = 6.0) -> bpy.types.Object:
    mesh = bpy.data.meshes.new("FloorMesh")
    mesh.from_pydata([(-half, -half, 0.0), (half, -half, 0.0), (half, half, 0.0),
                      (-half, half, 0.0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    mesh.update()
    obj = bpy.data.objects.new("Floor", mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def build_light() -> None:
    """One large disk light above and to the left, behind the wolf as seen from the camera, so
    the soft shadow falls forward onto the visible floor."""
    data = bpy.data.lights.new("Key", "AREA")
    data.energy = AREA_POWER
    data.shape = "DISK"
    data.size = AREA_SIZE
    data.color = (1.0, 0.95, 0.88)
    light = bpy.data.objects.new("Key", data)
    light.location = AREA_LOCATION
    aim(light, (0.0, 0.0, 0.3))
    bpy.context.scene.collection.objects.link(light)


def build_camera() -> None:
    cam = perspective_camera(lens=50.0, clip_start=0.05, location=(-1.9, -2.6, 1.25))
    aim(cam, (0.0, 0.0, 0.45))


def setup_render(scene: bpy.types.Scene) -> None:
    png_render_settings(scene, 320, 240)
    c = scene.cycles
    c.device = "CPU"
    c.samples = 128
    c.use_denoising = False
    c.max_bounces = 8


def main() -> None:
    path = output_path("scenes/make_wolf.py -- scenes/wolf.blend")
    clear_scene()
    scene = bpy.context.scene
    scene.name = "Wolf"
    build_wolf(principled("Fur", FUR, 0.7))
    build_floor(principled("Floor", FLOOR, 0.8))
    build_light()
    build_camera()
    uniform_world(scene, WORLD)
    setup_render(scene)
    save(path)


main()
