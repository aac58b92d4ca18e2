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

EMISSION_STRENGTH = 15.0  # radiance of the light quad (W/(sr m^2) in Blender's convention)
LIGHT_HALF = 0.25  # the light quad is 0.5 x 0.5 m
WHITE = (0.8, 0.8, 0.8)
RED = (0.8, 0.05, 0.05)
GREEN = (0.05, 0.8, 0.05)


def output_path():
    argv = sys.argv
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if not args:
        raise SystemExit("usage: blender -b --factory-startup --python scenes/make_cornell_box.py"
                         " -- scenes/cornell_box.blend")
    return os.path.abspath(args[0])


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras):
        for block in list(coll):
            if block.users == 0:
                coll.remove(block)


def principled(name, color):
    """Blender's default Principled BSDF (use_nodes = True) with only Base Color set."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = next(n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    mat.diffuse_color = (*color, 1.0)  # viewport colour only
    return mat


def emission(name, strength):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    for node in list(nodes):
        if node.type != "OUTPUT_MATERIAL":
            nodes.remove(node)
    out = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
    emit = nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    emit.inputs["Strength"].default_value = strength
    emit.location = (out.location.x - 250, out.location.y)
    links.new(emit.outputs["Emission"], out.inputs["Surface"])
    return mat


def mesh_object(name, verts, faces, material, mesh=None, smooth=False):
    if mesh is None:
        mesh = bpy.data.meshes.new(name + "Mesh")
        mesh.from_pydata(verts, [], faces)
        mesh.materials.append(material)
        for poly in mesh.polygons:
            poly.use_smooth = smooth
        mesh.validate()
        mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def quad(name, corners, material):
    """A single quad; the corners are counter-clockwise seen from the side the normal faces."""
    return mesh_object(name, corners, [(0, 1, 2, 3)], material)


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
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.type = "PERSP"
    cam_data.lens = 40.0
    cam_data.sensor_fit = "AUTO"
    cam_data.sensor_width = 36.0
    cam_data.clip_start = 0.1
    cam_data.clip_end = 100.0
    cam = bpy.data.objects.new("Camera", cam_data)
    bpy.context.scene.collection.objects.link(cam)
    # Blender cameras look down local -Z with +Y up: rotating 90 deg about X looks along +Y.
    cam.location = (0.0, -3.4, 1.0)
    cam.rotation_euler = (math.radians(90.0), 0.0, 0.0)
    bpy.context.scene.camera = cam
    return cam


def setup_world(scene):
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.color = (0.0, 0.0, 0.0)
    world.use_nodes = True
    bg = next((n for n in world.node_tree.nodes if n.type == "BACKGROUND"), None)
    if bg is not None:
        bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        bg.inputs["Strength"].default_value = 1.0


def setup_render(scene):
    r = scene.render
    r.resolution_x = 256
    r.resolution_y = 256
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.image_settings.file_format = "PNG"
    r.image_settings.color_mode = "RGB"
    r.film_transparent = False
    # Leave CYCLES here: the STRATUM enum value cannot be stored unless the add-on is
    # registered; `-E STRATUM` selects it at render time.
    r.engine = "CYCLES"
    scene.view_settings.view_transform = "Standard"  # PNG = plain sRGB encoding of linear
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.display_settings.display_device = "sRGB"
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
    path = output_path()
    clear_scene()
    scene = bpy.context.scene
    scene.name = "CornellBox"
    white = principled("White", WHITE)
    red = principled("Red", RED)
    green = principled("Green", GREEN)
    light = emission("Light", EMISSION_STRENGTH)
    build_walls(white, red, green)
    build_boxes(white)
    build_sphere(white, center=(0.36, -0.3, 0.6 + 0.25), radius=0.25)
    build_light(light)
    build_camera()
    setup_world(scene)
    setup_render(scene)
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    print("saved", path)


main()
