"""Measure Cycles' material and light conventions on tiny synthetic scenes.

Measured: the image means of docs/cycles_models.md's "Measured" table (Blender 3.4.1 and 5.0.1);
held by tests/native/bsdf/test_bsdf.cpp (Bsdf.DirectionalAlbedoMatchesCycles) for the BSDF rows.

    blender -b --factory-startup -noaudio --python scripts/run_in_blender.py -- \
        scripts.cycles_reference.conventions CASE...                       # Blender 3.4
    .venv/bin/python -m scripts.cycles_reference.conventions CASE...       # the bpy wheel (5.0)

Prints `CASE mean_r mean_g mean_b` of a linear EXR render.
Every scene is a 20x20 m plane at z=0 seen by an orthographic camera, so each pixel sees the same
geometry and the image mean is one radiance value (or the emitter itself in the `*_cam` cases).
"""
import math
import os
import sys
import tempfile

import bpy

V4 = bpy.app.version >= (4, 0, 0)


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = int(os.environ.get("PROBE_SPP", "256"))
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0
    scene.render.resolution_x = scene.render.resolution_y = 32
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    world = bpy.data.worlds.new("w")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    return scene


def camera(scene, elevation_deg=90.0, target=(0, 0, 0), scale=2.0):
    cam = bpy.data.cameras.new("cam")
    cam.type = "ORTHO"
    cam.ortho_scale = scale
    obj = bpy.data.objects.new("cam", cam)
    scene.collection.objects.link(obj)
    el = math.radians(elevation_deg)
    obj.location = (target[0], target[1] - 10 * math.cos(el), target[2] + 10 * math.sin(el))
    obj.rotation_euler = (math.pi / 2 - el, 0, 0)
    scene.camera = obj


def plane(scene, material, size=20.0):
    bpy.ops.mesh.primitive_plane_add(size=size, location=(0, 0, 0))
    bpy.context.active_object.data.materials.append(material)


def material(kind, color=0.8):
    mat = bpy.data.materials.new(kind)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    out = nodes["Material Output"]
    for n in list(nodes):
        if n != out:
            nodes.remove(n)
    if kind == "diffuse":
        bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    else:
        bsdf = nodes.new("ShaderNodeBsdfPrincipled")
        if kind == "principled_r1s0":
            bsdf.inputs["Roughness"].default_value = 1.0
            bsdf.inputs["Specular IOR Level" if V4 else "Specular"].default_value = 0.0
    bsdf.inputs["Color" if kind == "diffuse" else "Base Color"].default_value = (color, color, color, 1)
    mat.node_tree.links.new(bsdf.outputs[0], out.inputs["Surface"])
    return mat


def light(scene, kind, energy, location, size=None):
    data = bpy.data.lights.new(kind, kind)
    data.energy = energy
    if size is not None:
        if kind == "AREA":
            data.size = size
        elif kind == "SUN":
            data.angle = size
        else:
            data.shadow_soft_size = size
    obj = bpy.data.objects.new(kind, data)
    obj.location = location
    scene.collection.objects.link(obj)
    return obj


def render_mean(scene):
    path = os.path.join(tempfile.mkdtemp(), "probe.exr")
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    px = list(img.pixels)
    n = len(px) // 4
    return [sum(px[c::4]) / n for c in range(3)]


def render_row(scene):
    """Green channel of the middle row (y = 16 of 32, x = 16..31: centre to the right edge)."""
    path = os.path.join(tempfile.mkdtemp(), "probe.exr")
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    px = list(img.pixels)
    w = img.size[0]
    return [px[4 * (16 * w + x) + 1] for x in range(16, 32)]


def run(case):
    scene = reset()
    if case.startswith("furnace_"):
        # Uniform white sky of radiance 1: the pixel is the directional albedo for the view angle.
        _, kind, elev = case.split("_", 2)
        kind = {"d": "diffuse", "p": "principled_r1s0", "pdef": "principled_default"}[kind]
        scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
        plane(scene, material(kind))
        camera(scene, float(elev))
    elif case == "area_cam":
        # Camera looking straight at a 1x1 m area light of 100 W (pointing down, camera below).
        light(scene, "AREA", 100.0, (0, 0, 5), size=1.0)
        camera(scene, -90.0, target=(0, 0, 5), scale=0.5)
        scene.camera.location = (0, 0, 0)
        scene.camera.rotation_euler = (math.pi, 0, 0)  # look up (+z) at the light
    elif case == "area_plane":
        # 100 W, 0.2 m square area light 2 m above a white-ish diffuse plane: E ~ L*A/d^2.
        light(scene, "AREA", 100.0, (0, 0, 2), size=0.2)
        plane(scene, material("diffuse"))
        camera(scene, 90.0, scale=0.05)
    elif case == "point_plane":
        light(scene, "POINT", 1000.0, (0, 0, 2), size=0.0)
        plane(scene, material("diffuse"))
        camera(scene, 90.0, scale=0.05)
    elif case.startswith("spot_plane"):
        # Spot light 2 m above the plane, pointing down: 1000 W, cone 60 deg, blend 0.5, r = 0.
        # The 2.5 m view covers the cone (edge at 2 tan 30 = 1.155 m); pixels are printed.
        obj = light(scene, "SPOT", 1000.0, (0, 0, 2), size=0.0)
        obj.data.spot_size = math.radians(60.0)
        obj.data.spot_blend = 0.5
        plane(scene, material("diffuse"))
        camera(scene, 90.0, scale=2.56)
        print("RESULT", case, "row", " ".join(f"{v:.4f}" for v in render_row(scene)))
        return
    elif case == "sun_plane":
        light(scene, "SUN", 3.0, (0, 0, 2), size=0.0)
        plane(scene, material("diffuse"))
        camera(scene, 90.0)
    elif case == "emission_cam":
        mat = bpy.data.materials.new("e")
        mat.use_nodes = True
        nodes = mat.node_tree.nodes
        em = nodes.new("ShaderNodeEmission")
        em.inputs["Strength"].default_value = 5.0
        mat.node_tree.links.new(em.outputs[0], nodes["Material Output"].inputs["Surface"])
        plane(scene, mat)
        camera(scene, 90.0)
    elif case == "world_cam":
        scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 2.0
        camera(scene, 90.0)
    elif case.startswith("bounces_"):
        # Closed white diffuse box lit by an emissive ceiling: mean vs max_bounces shows whether
        # emission is collected by the ray leaving the last allowed bounce.
        scene.cycles.max_bounces = int(case.split("_")[1])
        bpy.ops.mesh.primitive_cube_add(size=2.0)
        cube = bpy.context.active_object
        cube.data.materials.append(material("diffuse", 0.5))
        cam = bpy.data.cameras.new("cam")
        obj = bpy.data.objects.new("cam", cam)
        scene.collection.objects.link(obj)
        obj.location = (0, 0, -0.9)
        scene.camera = obj
        scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
        emitter = bpy.data.materials.new("ceiling")
        emitter.use_nodes = True
        em = emitter.node_tree.nodes.new("ShaderNodeEmission")
        emitter.node_tree.links.new(em.outputs[0], emitter.node_tree.nodes["Material Output"].inputs["Surface"])
        bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0, 0, 0.99), rotation=(math.pi, 0, 0))
        bpy.context.active_object.data.materials.append(emitter)
    elif case == "defaults":
        mat = bpy.data.materials.new("d")
        mat.use_nodes = True
        p = mat.node_tree.nodes.get("Principled BSDF")
        vals = {s.name: tuple(s.default_value) if hasattr(s.default_value, "__len__") else s.default_value
                for s in p.inputs if hasattr(s, "default_value")}
        print("DEFAULTS distribution", p.distribution, vals)
        d = bpy.data.lights.new("a", "AREA")
        print("DEFAULTS area light energy", d.energy, "size", d.size)
        return
    print("RESULT", case, " ".join(f"{v:.5f}" for v in render_mean(scene)))


if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    for c in args:
        run(c)
