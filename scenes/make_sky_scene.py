"""Build scenes/features/sky.blend: an outdoor scene lit only by a Nishita Sky Texture world.

    blender -b --factory-startup --python scenes/make_sky_scene.py -- scenes/features/sky.blend

A grey ground plane, a red box, a white sphere and a green slab under a Nishita sky (Blender 3.4
names; Blender 5.0 converts the node to its own sky types on load): the sun 25 degrees up with
the default disc (0.545 degrees), turned so that the objects' shadows fall across the ground in
view. Background strength 0.05 keeps the sunlit ground near 0.5 in a 64 x 64 Standard-view
render. The sun is most of the light (its disc carries about 85% of a horizontal plane's
irradiance) and both engines importance-sample it through their environment maps, so a few
hundred samples converge.
"""

from __future__ import annotations

import math
import os
import sys

import bmesh
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_building import (
    aim,
    clear_scene,
    mesh_object,
    output_path,
    perspective_camera,
    png_render_settings,
    principled,
    quad,
    save,
)


def box(name: str, lo: tuple[float, float, float], hi: tuple[float, float, float],
        material: bpy.types.Material) -> bpy.types.Object:
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return mesh_object(name, verts, faces, material)


def sphere(name: str, center: tuple[float, float, float], radius: float,
           material: bpy.types.Material) -> bpy.types.Object:
    mesh = bpy.data.meshes.new(name + "Mesh")
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=32, v_segments=16, radius=radius)
    bm.to_mesh(mesh)
    bm.free()
    mesh.materials.append(material)
    for poly in mesh.polygons:
        poly.use_smooth = True
    obj = mesh_object(name, None, None, material, mesh=mesh)
    obj.location = center
    return obj


def sky_world(scene: bpy.types.Scene) -> None:
    world = bpy.data.worlds.new("nishita")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    bg = nodes["Background"]
    bg.inputs["Strength"].default_value = 0.05
    sky = nodes.new("ShaderNodeTexSky")
    sky.sky_type = "NISHITA"
    sky.sun_disc = True
    sky.sun_elevation = math.radians(25.0)
    sky.sun_rotation = math.radians(140.0)
    sky.altitude = 100.0
    sky.air_density = 1.0
    sky.dust_density = 1.0
    sky.ozone_density = 1.0
    sky.location = (bg.location.x - 250, bg.location.y)
    links.new(sky.outputs["Color"], bg.inputs["Color"])
    world.color = (0.4, 0.5, 0.7)
    scene.world = world


def main() -> None:
    path = output_path("scenes/make_sky_scene.py -- OUT.blend", exactly_one=True)
    clear_scene()
    scene = bpy.context.scene
    ground = principled("ground", (0.5, 0.5, 0.5), 0.8)
    quad("Ground", [(-40, -40, 0), (40, -40, 0), (40, 40, 0), (-40, 40, 0)], ground)
    box("Box", (-1.4, -0.6, 0.0), (-0.4, 0.4, 1.0), principled("red", (0.7, 0.12, 0.1), 0.5))
    sphere("Sphere", (0.8, 0.2, 0.6), 0.6, principled("white", (0.8, 0.8, 0.8), 0.3))
    box("Slab", (1.6, -1.2, 0.0), (2.6, 0.2, 0.3), principled("green", (0.15, 0.5, 0.15), 0.6))
    cam = perspective_camera(35.0, 0.1, (0.0, -6.5, 3.2))
    aim(cam, (0.0, 0.3, 0.4))
    sky_world(scene)
    png_render_settings(scene, 64, 64)
    save(path)


main()
