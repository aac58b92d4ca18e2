"""Cycles vs Stratum on one controlled Principled scene (the bpy 5.0 wheel).

Measured: Cycles 5.0.1's directional albedo of the Principled BSDF (v2, GGX and Multiscatter
GGX, docs/cycles_models.md); held by tests/native/bsdf/test_bsdf.cpp
(Principled.V2DirectionalAlbedoMatchesCycles50).

A 20 m plane with one Principled BSDF under a long-lens camera at elevation VIEW (degrees
above the plane), max_bounces 0, so the image mean is one value of the BSDF:
  furnace : uniform world of radiance 1, no lights -> directional albedo A(theta_v) (NEE + MIS
            of the world, both engines).
  sun:EL  : black world, sun of strength 1 at elevation EL in the plane of the camera, on the
            opposite side (mirror configuration when EL == VIEW) -> f_r(wo, wi) cos(theta_i).
Material options: dist=GGX|MULTI_GGX, ior=, level= (Specular IOR Level), rough=, base=.
Usage: .venv/bin/python -m scripts.cycles_reference.principled_v2 ENGINE LIGHT VIEW [key=value ...]
(ENGINE cycles|stratum)
Prints `RESULT engine light view opts mean_r mean_g mean_b`. Keep renders small (shared machine).
"""
import math
import os
import sys
import tempfile

import bpy


def build(light, view, opts):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x = scene.render.resolution_y = int(opts.get("res", 16))
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    world = bpy.data.worlds.new("w")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (1, 1, 1, 1)
    bg.inputs["Strength"].default_value = 1.0 if light == "furnace" else 0.0
    scene.world = world

    mat = bpy.data.materials.new("p")
    mat.use_nodes = True
    p = mat.node_tree.nodes["Principled BSDF"]
    p.distribution = opts.get("dist", "MULTI_GGX")
    base = float(opts.get("base", 0.8))
    p.inputs["Base Color"].default_value = (base, base, base, 1)
    p.inputs["Roughness"].default_value = float(opts.get("rough", 0.5))
    p.inputs["IOR"].default_value = float(opts.get("ior", 1.5))
    p.inputs["Specular IOR Level"].default_value = float(opts.get("level", 0.5))
    p.inputs["Metallic"].default_value = float(opts.get("metal", 0.0))
    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0, 0, 0))
    bpy.context.active_object.data.materials.append(mat)

    cam = bpy.data.cameras.new("cam")
    # Long-lens perspective (Stratum has no orthographic camera): 10 m away, 3600 mm lens on a
    # 36 mm sensor -> 0.1 m field, view directions within 0.3 degrees of the nominal angle.
    cam.type = "PERSP"
    cam.sensor_fit = "HORIZONTAL"
    cam.sensor_width = 36.0
    cam.lens = 3600.0
    cam.clip_start = 1.0
    cam.clip_end = 100.0
    obj = bpy.data.objects.new("cam", cam)
    scene.collection.objects.link(obj)
    el = math.radians(view)
    obj.location = (0, -10 * math.cos(el), 10 * math.sin(el))
    obj.rotation_euler = (math.pi / 2 - el, 0, 0)
    scene.camera = obj

    if light.startswith("sun:"):
        sel = math.radians(float(light.split(":")[1]))
        sun = bpy.data.lights.new("sun", "SUN")
        sun.energy = 1.0
        sun.angle = 0.0
        sobj = bpy.data.objects.new("sun", sun)
        # Sun on the +y side (camera is on -y): light travels along -(0, cos, sin).
        sobj.rotation_euler = (-(math.pi / 2 - sel), 0, 0)
        scene.collection.objects.link(sobj)
    return scene


def configure(scene, engine, opts):
    spp = int(opts.get("spp", 1024))
    seed = int(opts.get("seed", 1))
    if engine == "cycles":
        scene.render.engine = "CYCLES"
        c = scene.cycles
        c.device = "CPU"
        c.samples = spp
        c.seed = seed
        c.use_adaptive_sampling = False
        c.use_denoising = False
        c.max_bounces = 0
        c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
        c.light_sampling_threshold = 0.0
        c.blur_glossy = 0.0
    else:
        import stratum
        stratum.register()
        scene.render.engine = "STRATUM"
        s = scene.stratum
        s.samples = spp
        s.seed = seed
        s.max_bounces = 0
        s.threads = int(opts.get("threads", 1))


def render_mean(scene):
    path = os.path.join(tempfile.mkdtemp(), "ab.exr")
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    px = list(img.pixels)
    n = len(px) // 4
    return [sum(px[c::4]) / n for c in range(3)]


def main(argv):
    engine, light, view = argv[0], argv[1], float(argv[2])
    opts = dict(a.split("=", 1) for a in argv[3:])
    scene = build(light, view, opts)
    configure(scene, engine, opts)
    m = render_mean(scene)
    tag = ",".join(f"{k}={v}" for k, v in sorted(opts.items()))
    print("RESULT", engine, light, view, tag, " ".join(f"{v:.6f}" for v in m), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
