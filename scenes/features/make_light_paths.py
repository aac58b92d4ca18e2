"""Build scenes/features/light_paths.blend: what a file tuned for Cycles carries in its Light
Paths, Light Path nodes, view layer and compositing switches (issue 34), for the feature
agreement (tests/blender/test_feature_agreement.py, cases light_paths and environment_off).

Run with Blender 3.4, so that the file opens in 3.4 and in every later Blender:

    blender -b --factory-startup --python scenes/features/make_light_paths.py -- scenes/features

Two scenes, 64 x 64, Standard view transform:

* "light_paths": a grey room corner (floor and back wall) with a clear glass sphere, a mirror
  panel, a red box and a small glass cube, lit by an area lamp (light group "key"), a point lamp
  (group "fill") and the world (group "sky"). The world is the Light Path trick of a background
  the camera sees (a bright blue) that is not what lights the scene (a dim warm white): Mix by
  Is Camera Ray. The glass cube is the cheaper-glass-shadow trick: Mix(Glass, Transparent) by Is
  Shadow Ray. A small white plane on the floor at the right is a shadow catcher, a sphere above
  it casting onto it. Cycles' Light Paths values are set as a tuned file sets them: max 8,
  diffuse 2, glossy 2, transmission 6, transparent 8, indirect clamp 10, Filter Glossy 1,
  reflective caustics on, refractive caustics off (the glass sphere casts a black shadow but for
  its transparent cube neighbour), so Stratum renders them under its light_paths rule.
* "environment_off": a floor and a sphere under a bright uniform world, lit also by a sun, with
  the view layer's Environment switched off (the world neither shows nor lights) and a material
  override (a light grey Principled on every object).

Light and shadow linking exist from Blender 4.0 on: the test adds them when it runs in one
(this file is written by 3.4).
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_building import aim, feature_render_settings, node_material, output_path

RES = 64


def link(scene, obj):
    scene.collection.objects.link(obj)
    return obj


def box_mesh(name, half):
    mesh = bpy.data.meshes.new(name)
    h = half
    verts = [(x, y, z) for z in (-h, h) for y in (-h, h) for x in (-h, h)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    return mesh


def sphere_mesh(name, radius, segments=32, rings=16):
    verts, faces = [(0.0, 0.0, -radius)], []
    for j in range(1, rings):
        phi = math.pi * j / rings - math.pi / 2
        for i in range(segments):
            theta = 2 * math.pi * i / segments
            verts.append((radius * math.cos(phi) * math.cos(theta),
                          radius * math.cos(phi) * math.sin(theta), radius * math.sin(phi)))
    verts.append((0.0, 0.0, radius))
    top = len(verts) - 1
    ring = lambda j, i: 1 + (j - 1) * segments + i % segments
    for i in range(segments):
        faces.append((0, ring(1, i + 1), ring(1, i)))
        faces.append((top, ring(rings - 1, i), ring(rings - 1, i + 1)))
    for j in range(1, rings - 1):
        for i in range(segments):
            faces.append((ring(j, i), ring(j, i + 1), ring(j + 1, i + 1), ring(j + 1, i)))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    for poly in mesh.polygons:
        poly.use_smooth = True
    mesh.update()
    return mesh


def quad_mesh(name, corners):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(corners, [], [(0, 1, 2, 3)])
    mesh.update()
    return mesh


def place(scene, name, mesh, material, location, rotation=(0.0, 0.0, 0.0)):
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    obj.rotation_euler = rotation
    return link(scene, obj)


def bsdf_material(name, node_type, color, **inputs):
    mat, nodes, links, out = node_material(name)
    bsdf = nodes.new(node_type)
    if "Color" in bsdf.inputs:
        bsdf.inputs["Color"].default_value = (*color, 1.0)
    else:
        bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    for key, value in inputs.items():
        bsdf.inputs[key].default_value = value
    links.new(bsdf.outputs[0], out.inputs["Surface"])
    return mat


def glass_with_clear_shadow(name):
    """Glass for camera and scattered rays, Transparent for shadow rays (Light Path's Is Shadow
    Ray as the factor): the glass casts a light shadow without caustics."""
    mat, nodes, links, out = node_material(name)
    glass = nodes.new("ShaderNodeBsdfGlass")
    glass.inputs["Roughness"].default_value = 0.0
    glass.inputs["IOR"].default_value = 1.45
    clear = nodes.new("ShaderNodeBsdfTransparent")
    path = nodes.new("ShaderNodeLightPath")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(path.outputs["Is Shadow Ray"], mix.inputs["Fac"])
    links.new(glass.outputs[0], mix.inputs[1])
    links.new(clear.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    return mat


def camera_only_world(name, seen, lighting):
    """The camera sees `seen` (colour, strength); every other ray meets `lighting`."""
    world = bpy.data.worlds.new(name)
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    out = next(n for n in nodes if n.type == "OUTPUT_WORLD")
    for node in list(nodes):
        if node is not out:
            nodes.remove(node)
    backgrounds = []
    for colour, strength in (lighting, seen):
        bg = nodes.new("ShaderNodeBackground")
        bg.inputs["Color"].default_value = (*colour, 1.0)
        bg.inputs["Strength"].default_value = strength
        backgrounds.append(bg)
    path = nodes.new("ShaderNodeLightPath")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    links.new(backgrounds[0].outputs[0], mix.inputs[1])
    links.new(backgrounds[1].outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs[0])  # the World Output's Surface
    world.color = seen[0]
    return world


def lamp(scene, name, kind, location, energy, color, target, **props):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    data.color = color
    for key, value in props.items():
        setattr(data, key, value)
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    aim(obj, target)
    return link(scene, obj)


def camera(scene, location, target, lens):
    data = bpy.data.cameras.new(scene.name)
    data.lens = lens
    data.sensor_fit = "AUTO"
    obj = bpy.data.objects.new(scene.name + "_camera", data)
    obj.location = location
    aim(obj, target)
    scene.camera = link(scene, obj)


def build_light_paths(scene):
    feature_render_settings(scene, RES)
    c = scene.cycles
    c.max_bounces = 8
    c.diffuse_bounces = 2
    c.glossy_bounces = 2
    c.transmission_bounces = 6
    c.transparent_max_bounces = 8
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 10.0
    c.blur_glossy = 1.0
    c.caustics_reflective = True
    c.caustics_refractive = False
    grey = bsdf_material("lp_grey", "ShaderNodeBsdfDiffuse", (0.7, 0.7, 0.7))
    place(scene, "floor", quad_mesh("floor", [(-3, -3, 0), (3, -3, 0), (3, 3, 0), (-3, 3, 0)]),
          grey, (0.0, 0.0, 0.0))
    place(scene, "wall", quad_mesh("wall", [(-3, 0, 0), (3, 0, 0), (3, 0, 3), (-3, 0, 3)]),
          bsdf_material("lp_wall", "ShaderNodeBsdfDiffuse", (0.6, 0.65, 0.7)), (0.0, 1.6, 0.0))
    place(scene, "glass_ball", sphere_mesh("glass_ball", 0.45),
          bsdf_material("lp_glass", "ShaderNodeBsdfGlass", (1.0, 1.0, 1.0), Roughness=0.0, IOR=1.45),
          (-0.2, 0.2, 0.45))
    place(scene, "mirror", quad_mesh("mirror", [(-0.6, 0, 0), (0.6, 0, 0), (0.6, 0, 1.4), (-0.6, 0, 1.4)]),
          bsdf_material("lp_mirror", "ShaderNodeBsdfGlossy", (0.9, 0.9, 0.9), Roughness=0.0),
          (1.3, 1.0, 0.05), (0.0, 0.0, math.radians(-30.0)))
    place(scene, "red_box", box_mesh("red_box", 0.3),
          bsdf_material("lp_red", "ShaderNodeBsdfPrincipled", (0.7, 0.08, 0.05), Roughness=0.35),
          (-1.3, 0.6, 0.3), (0.0, 0.0, math.radians(25.0)))
    place(scene, "clear_cube", box_mesh("clear_cube", 0.2), glass_with_clear_shadow("lp_clear_glass"),
          (0.45, -0.5, 0.2))
    catcher = place(scene, "catcher", quad_mesh("catcher", [(-0.5, -0.5, 0), (0.5, -0.5, 0), (0.5, 0.5, 0),
                                                           (-0.5, 0.5, 0)]),
                    bsdf_material("lp_catcher", "ShaderNodeBsdfDiffuse", (0.8, 0.8, 0.8)), (1.6, -1.1, 0.01))
    catcher.is_shadow_catcher = True
    place(scene, "caster", sphere_mesh("caster", 0.2),
          bsdf_material("lp_caster", "ShaderNodeBsdfDiffuse", (0.2, 0.4, 0.8)), (1.5, -1.0, 0.6))
    key = lamp(scene, "key", "AREA", (-1.5, -2.0, 3.0), 100.0, (1.0, 0.95, 0.9), (0.0, 0.0, 0.0),
               shape="SQUARE", size=1.0)
    fill = lamp(scene, "fill", "POINT", (2.0, -1.5, 1.8), 60.0, (0.7, 0.8, 1.0), (0.0, 0.0, 0.0),
                shadow_soft_size=0.2)
    scene.world = camera_only_world("lp_world", seen=((0.3, 0.5, 1.0), 1.0), lighting=((1.0, 0.95, 0.85), 0.3))
    layer = scene.view_layers[0]
    for name in ("key", "fill", "sky"):
        layer.lightgroups.add(name=name)
    key.lightgroup = "key"
    fill.lightgroup = "fill"
    scene.world.lightgroup = "sky"
    camera(scene, (0.6, -5.0, 2.4), (0.0, 0.3, 0.5), 35.0)


def build_environment_off(scene):
    feature_render_settings(scene, RES)
    world = bpy.data.worlds.new("eo_world")
    world.use_nodes = True
    bg = next(n for n in world.node_tree.nodes if n.type == "BACKGROUND")
    bg.inputs["Color"].default_value = (0.8, 0.9, 1.0, 1.0)
    bg.inputs["Strength"].default_value = 2.0
    scene.world = world
    place(scene, "eo_floor", quad_mesh("eo_floor", [(-4, -4, 0), (4, -4, 0), (4, 4, 0), (-4, 4, 0)]),
          bsdf_material("eo_red", "ShaderNodeBsdfDiffuse", (0.8, 0.2, 0.1)), (0.0, 0.0, 0.0))
    place(scene, "eo_ball", sphere_mesh("eo_ball", 0.6),
          bsdf_material("eo_blue", "ShaderNodeBsdfDiffuse", (0.1, 0.2, 0.8)), (0.0, 0.0, 0.6))
    sun = bpy.data.lights.new("eo_sun", "SUN")
    sun.energy = 3.0
    sun.angle = math.radians(4.0)
    sun_obj = link(scene, bpy.data.objects.new("eo_sun", sun))
    sun_obj.rotation_euler = (math.radians(40.0), 0.0, math.radians(30.0))
    layer = scene.view_layers[0]
    layer.use_sky = False
    layer.material_override = bsdf_material("eo_override", "ShaderNodeBsdfPrincipled", (0.75, 0.75, 0.75),
                                            Roughness=0.5)
    camera(scene, (0.0, -4.0, 2.5), (0.0, 0.0, 0.4), 40.0)


def main():
    bpy.context.preferences.filepaths.save_version = 0  # no .blend1 backups
    folder = output_path("scenes/features/make_light_paths.py -- scenes/features")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    first = bpy.context.scene
    first.name = "light_paths"
    build_light_paths(first)
    build_environment_off(bpy.data.scenes.new("environment_off"))
    bpy.context.window.scene = first
    path = os.path.join(folder, "light_paths.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True, relative_remap=True)
    print("saved", path, os.path.getsize(path), "bytes")


main()
