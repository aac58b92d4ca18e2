"""Build the feature scenes (one small .blend per feature group) that Stratum is compared on.

Run with Blender 3.4, so that every file opens in 3.4 and in every later Blender:

    blender -b --factory-startup --python scenes/features/make_features.py -- scenes/features

Writes into the given folder (the images the scenes reference go to <folder>/textures/):

* materials.blend: twelve spheres in three rows of four on a ground plane (see MATERIALS);
* lights.blend: every Blender light type over a white floor, colours and powers varied;
* world.blend: objects under a generated HDRI (textures/sky.exr: a sky gradient, a ground and a
  sun disc), the only light;
* camera.blend: three scenes sharing one set of objects: "dof" (f-stop, focus object, five
  rotated blades), "ortho" (orthographic camera), "motion" (a sphere moving across the
  shutter, object motion blur);
* instancing.blend: 3200 instances of one mesh: vertex instancing (a 40 x 40 vertex grid
  instancing a child monkey) inside a collection that is excluded from the view layer and
  placed twice by collection-instance empties;
* procedural.blend: six spheres and a cube on a brick ground whose materials are procedural
  (noise -> color ramp, voronoi cells, checker, a distorted wave, a bump from noise, two BSDFs
  mixed by noise, roughness from a gradient), lit by an area lamp and a sun.

Everything is made with bpy.data, bmesh and numpy (no UI operators, no geometry nodes, no
particles): the files open in Blender 3.4 and 5.0. The render settings stored in the files are
64 x 64, Standard view transform; tests/blender/test_feature_agreement.py sets the sampling.
Images are generated here: the textured sphere's base colour (PACKED into materials.blend, so
the packed-image path is exercised), its roughness and tangent-space normal maps and the
cut-out's RGBA image (PNG files next to the .blend, referenced relatively), and the HDRI.
"""

import math
import os
import sys

import bmesh
import bpy
import numpy as np

# Blender does not put a --python script's folder on sys.path; scene_building.py is one up.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_building import (
    aim,
    emission,
    feature_render_settings,
    node_material,
    output_path,
)

RES = 64
RNG = np.random.default_rng(5)


# ---- building blocks --------------------------------------------------------------------------


def reset(scene_name):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.name = scene_name
    feature_render_settings(scene, RES)
    return scene


def principled(name, color, roughness=0.5, metallic=0.0, **inputs):
    mat, nodes, links, out = node_material(name)
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.distribution = "GGX"
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    for key, value in inputs.items():
        bsdf.inputs[key].default_value = value
    links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    mat.diffuse_color = (*color, 1.0)
    return mat, bsdf


def diffuse(name, color):
    mat, nodes, links, out = node_material(name)
    node = nodes.new("ShaderNodeBsdfDiffuse")
    node.inputs["Color"].default_value = (*color, 1.0)
    links.new(node.outputs["BSDF"], out.inputs["Surface"])
    return mat


def link(obj, collection=None):
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def mesh_from_bmesh(name, build, smooth=False, uvs=False):
    bm = bmesh.new()
    if uvs:
        bm.loops.layers.uv.new("UVMap")
    build(bm)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    for poly in mesh.polygons:
        poly.use_smooth = smooth
    mesh.update()
    return mesh


def sphere_mesh(name, radius, segments=32, rings=16):
    return mesh_from_bmesh(
        name, lambda bm: bmesh.ops.create_uvsphere(bm, u_segments=segments, v_segments=rings,
                                                   radius=radius, calc_uvs=True),
        smooth=True, uvs=True)


def cube_mesh(name, size):
    return mesh_from_bmesh(name, lambda bm: bmesh.ops.create_cube(bm, size=size))


def plane(name, half, material, z=0.0):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(-half, -half, z), (half, -half, z), (half, half, z), (-half, half, z)],
                     [], [(0, 1, 2, 3)])
    mesh.materials.append(material)
    mesh.update()
    return link(bpy.data.objects.new(name, mesh))


def mesh_object(name, mesh, material, location, collection=None):
    if material is not None and len(mesh.materials) == 0:
        mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    return link(obj, collection)


def camera(name, location, target, lens=50.0, collection=None):
    cam = bpy.data.cameras.new(name)
    cam.lens = lens
    cam.sensor_fit = "AUTO"
    obj = bpy.data.objects.new(name, cam)
    obj.location = location
    aim(obj, target)
    link(obj, collection)
    return obj


def light(name, kind, location, energy, color, target=None, collection=None, **props):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    data.color = color
    for key, value in props.items():
        setattr(data, key, value)
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    if target is not None:
        aim(obj, target)
    return link(obj, collection)


def uniform_world(name, color, strength=1.0):
    world = bpy.data.worlds.new(name)
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (*color, 1.0)
    bg.inputs["Strength"].default_value = strength
    world.color = color
    bpy.context.scene.world = world
    return world


def image_from_array(name, rgba, colorspace, path=None, pack=False):
    """A PNG image of rgba ((h, w, 4), rows bottom to top, values as stored); saved to path
    (and then referenced from it) or packed into the .blend."""
    h, w = rgba.shape[:2]
    img = bpy.data.images.new(name, w, h, alpha=True)
    img.pixels.foreach_set(np.ascontiguousarray(rgba, dtype=np.float32).ravel())
    img.file_format = "PNG"
    if path is not None:
        img.filepath_raw = path
        img.save()
        img.source = "FILE"
        img.filepath = path
        img.reload()
    if pack:
        img.pack()
    img.colorspace_settings.name = colorspace
    return img


# ---- generated images ---------------------------------------------------------------------------


def checker_rgba(size=64, cells=8):
    yy, xx = np.mgrid[0:size, 0:size]
    odd = ((xx * cells // size) + (yy * cells // size)) % 2 == 1
    rgba = np.ones((size, size, 4))
    rgba[odd, :3] = (0.85, 0.65, 0.15)  # sRGB-encoded values (the image is sRGB)
    rgba[~odd, :3] = (0.15, 0.35, 0.75)
    return rgba


def roughness_rgba(size=64, stripes=6):
    xx = np.mgrid[0:size, 0:size][1]
    value = np.where((xx * stripes // size) % 2 == 0, 0.15, 0.7)
    rgba = np.ones((size, size, 4))
    rgba[..., :3] = value[..., None]
    return rgba


def normal_rgba(size=64, bumps=4):
    """Tangent-space normals of a field of round bumps (height h = sin^2 of a bump grid)."""
    yy, xx = (np.mgrid[0:size, 0:size] + 0.5) / size
    k = bumps * math.pi
    amplitude = 0.08
    dhdx = amplitude * k * np.sin(2 * k * xx) * np.sin(k * yy) ** 2
    dhdy = amplitude * k * np.sin(2 * k * yy) * np.sin(k * xx) ** 2
    n = np.stack([-dhdx, -dhdy, np.ones_like(xx)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    rgba = np.ones((size, size, 4))
    rgba[..., :3] = 0.5 * n + 0.5
    return rgba


def cutout_rgba(size=64, holes=4):
    """White-ish with a grid of round holes (alpha 0)."""
    yy, xx = (np.mgrid[0:size, 0:size] + 0.5) / size
    fx, fy = (xx * holes) % 1.0 - 0.5, (yy * holes) % 1.0 - 0.5
    rgba = np.ones((size, size, 4))
    rgba[..., :3] = (0.9, 0.9, 0.85)
    rgba[..., 3] = np.where(fx * fx + fy * fy < 0.3**2, 0.0, 1.0)
    return rgba


def sky_rgba(width=256, height=128, sun_elevation=35.0, sun_azimuth=-60.0, sun_radius=3.0):
    """Equirectangular linear radiance: a blue gradient sky, a brown ground, a sun disc of
    angular radius sun_radius degrees. Rows bottom (nadir) to top; column u maps to the azimuth
    (u - 0.5) * 2 pi, Blender's equirectangular convention (u = 0.5 looks along +X)."""
    v = (np.arange(height) + 0.5) / height
    u = (np.arange(width) + 0.5) / width
    uu, vv = np.meshgrid(u, v)
    elevation = (vv - 0.5) * math.pi
    azimuth = (uu - 0.5) * 2.0 * math.pi
    t = np.clip(elevation / (math.pi / 2), 0.0, 1.0)
    rgba = np.ones((height, width, 4))
    horizon, zenith = np.array([0.9, 0.95, 1.0]), np.array([0.15, 0.3, 0.8])
    sky = horizon + (zenith - horizon) * np.sqrt(t)[..., None]
    ground = np.array([0.25, 0.18, 0.12])
    rgba[..., :3] = np.where((elevation > 0)[..., None], sky, ground)
    se, sa = math.radians(sun_elevation), math.radians(sun_azimuth)
    sun = np.array([math.cos(se) * math.cos(sa), math.cos(se) * math.sin(sa), math.sin(se)])
    d = np.stack([np.cos(elevation) * np.cos(azimuth), np.cos(elevation) * np.sin(azimuth),
                  np.sin(elevation)], axis=-1)
    in_sun = d @ sun > math.cos(math.radians(sun_radius))
    rgba[in_sun, :3] = (120.0, 110.0, 90.0)
    return rgba


def save_exr(name, rgba, path):
    h, w = rgba.shape[:2]
    img = bpy.data.images.new(name, w, h, alpha=True, float_buffer=True)
    img.pixels.foreach_set(np.ascontiguousarray(rgba, dtype=np.float32).ravel())
    scene = bpy.context.scene
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "16"
    settings.color_mode = "RGB"
    settings.exr_codec = "ZIP"
    img.save_render(path, scene=scene)
    bpy.data.images.remove(img)


# ---- materials.blend -----------------------------------------------------------------------------

# Three rows of four (back row first, left to right as seen by the camera).
MATERIALS = (
    "metal_smooth", "metal_medium", "metal_rough", "coat",
    "glass", "rough_glass", "diffuse", "textured",
    "mix", "add", "cutout", "plastic",
)


def textured_material(textures):
    """Principled with an image texture on Base Color (packed), one on Roughness and a
    tangent-space normal map, all through the sphere's UV map."""
    mat, bsdf = principled("textured", (0.8, 0.8, 0.8), roughness=0.4)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = "UVMap"
    base = nodes.new("ShaderNodeTexImage")
    base.image = image_from_array("checker", checker_rgba(), "sRGB", pack=True)
    rough = nodes.new("ShaderNodeTexImage")
    rough.image = image_from_array("roughness", roughness_rgba(), "Non-Color",
                                   path=os.path.join(textures, "roughness.png"))
    normal_tex = nodes.new("ShaderNodeTexImage")
    normal_tex.image = image_from_array("normal", normal_rgba(), "Non-Color",
                                        path=os.path.join(textures, "normal.png"))
    normal_map = nodes.new("ShaderNodeNormalMap")
    normal_map.space = "TANGENT"
    normal_map.uv_map = "UVMap"
    normal_map.inputs["Strength"].default_value = 1.0
    for tex in (base, rough, normal_tex):
        links.new(uv.outputs["UV"], tex.inputs["Vector"])
    links.new(base.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(rough.outputs["Color"], bsdf.inputs["Roughness"])
    links.new(normal_tex.outputs["Color"], normal_map.inputs["Color"])
    links.new(normal_map.outputs["Normal"], bsdf.inputs["Normal"])
    return mat


def glossy_node(nodes, color, roughness):
    node = nodes.new("ShaderNodeBsdfGlossy")
    node.distribution = "GGX"
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Roughness"].default_value = roughness
    return node


def two_shader_material(name, kind):
    """Mix Shader (factor 0.35) or Add Shader of a Diffuse and a Glossy BSDF."""
    mat, nodes, links, out = node_material(name)
    dif = nodes.new("ShaderNodeBsdfDiffuse")
    if kind == "mix":
        dif.inputs["Color"].default_value = (0.9, 0.35, 0.1, 1.0)
        gloss = glossy_node(nodes, (0.9, 0.9, 0.9), 0.15)
        mix = nodes.new("ShaderNodeMixShader")
        mix.inputs["Fac"].default_value = 0.35
        links.new(dif.outputs["BSDF"], mix.inputs[1])
        links.new(gloss.outputs["BSDF"], mix.inputs[2])
    else:
        dif.inputs["Color"].default_value = (0.1, 0.3, 0.45, 1.0)
        gloss = glossy_node(nodes, (0.4, 0.4, 0.4), 0.3)
        mix = nodes.new("ShaderNodeAddShader")
        links.new(dif.outputs["BSDF"], mix.inputs[0])
        links.new(gloss.outputs["BSDF"], mix.inputs[1])
    links.new(mix.outputs["Shader"], out.inputs["Surface"])
    return mat


def cutout_material(textures):
    """Principled whose Base Color and Alpha come from an RGBA image with round holes."""
    mat, bsdf = principled("cutout", (0.9, 0.9, 0.85), roughness=0.5)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image_from_array("cutout", cutout_rgba(), "sRGB",
                                 path=os.path.join(textures, "cutout.png"))
    tex.image.alpha_mode = "STRAIGHT"
    links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(tex.outputs["Alpha"], bsdf.inputs["Alpha"])
    mat.blend_method = "CLIP"  # viewport only; Cycles always treats alpha stochastically
    return mat


def glass_node_material(name, roughness, ior):
    mat, nodes, links, out = node_material(name)
    glass = nodes.new("ShaderNodeBsdfGlass")
    glass.distribution = "GGX"
    glass.inputs["Color"].default_value = (0.95, 0.95, 1.0, 1.0)
    glass.inputs["Roughness"].default_value = roughness
    glass.inputs["IOR"].default_value = ior
    links.new(glass.outputs["BSDF"], out.inputs["Surface"])
    return mat


def build_materials(folder, textures):
    scene = reset("materials")
    mats = {
        "metal_smooth": principled("metal_smooth", (0.95, 0.75, 0.35), 0.05, 1.0)[0],
        "metal_medium": principled("metal_medium", (0.9, 0.9, 0.9), 0.3, 1.0)[0],
        "metal_rough": principled("metal_rough", (0.95, 0.55, 0.45), 0.6, 1.0)[0],
        "coat": principled("coat", (0.7, 0.08, 0.05), 0.5, 0.0,
                           Clearcoat=1.0, **{"Clearcoat Roughness": 0.05})[0],
        "glass": principled("glass", (1.0, 1.0, 1.0), 0.0, 0.0, Transmission=1.0,
                            IOR=1.45)[0],
        "rough_glass": glass_node_material("rough_glass", 0.25, 1.5),
        "diffuse": diffuse("diffuse", (0.2, 0.45, 0.8)),
        "textured": textured_material(textures),
        "mix": two_shader_material("mix", "mix"),
        "add": two_shader_material("add", "add"),
        "cutout": cutout_material(textures),
        "plastic": principled("plastic", (0.1, 0.6, 0.15), 0.3, 0.0)[0],
    }
    for i, name in enumerate(MATERIALS):
        row, col = divmod(i, 4)
        location = (-1.5 + col, 1.1 - 1.1 * row, 0.4)
        mesh_object(name, sphere_mesh(name, 0.4), mats[name], location)
    plane("ground", 15.0, principled("ground", (0.5, 0.5, 0.5), 0.6)[0])
    scene.camera = camera("camera", (0.0, -5.2, 3.4), (0.0, 0.0, 0.3), lens=42.0)
    # A large, soft key light and a bright sky: caustics through the glass spheres and off
    # the metals (paths ground -> specular -> light, found only by BSDF sampling) then come
    # from large sources and converge at test sample counts.
    light("key", "AREA", (2.5, -2.5, 4.0), 400.0, (1.0, 0.95, 0.9), target=(0.0, 0.0, 0.0),
          shape="SQUARE", size=4.0)
    uniform_world("sky", (0.55, 0.6, 0.7), 1.0)
    save(folder, "materials.blend")


# ---- lights.blend --------------------------------------------------------------------------------


def build_lights(folder):
    scene = reset("lights")
    plane("floor", 8.0, diffuse("floor", (0.75, 0.75, 0.75)))
    grey = principled("block", (0.6, 0.6, 0.6), 0.5)[0]
    cube = cube_mesh("block", 0.35)
    down = {"target": None}  # without a target a light points down its local -Z: down
    h = 1.4
    s = 2.6
    light("point", "POINT", (-s, s, h), 60.0, (1.0, 0.8, 0.55), shadow_soft_size=0.3, **down)
    light("spot", "SPOT", (0.0, s, h + 0.4), 90.0, (0.6, 0.8, 1.0), shadow_soft_size=0.1,
          spot_size=math.radians(55.0), spot_blend=0.35, **down)
    light("area_square", "AREA", (s, s, h), 20.0, (0.55, 1.0, 0.5), shape="SQUARE", size=0.6,
          **down)
    light("area_rectangle", "AREA", (-s, 0.0, h), 25.0, (1.0, 0.5, 0.9), shape="RECTANGLE",
          size=1.2, size_y=0.3, **down)
    light("area_disk", "AREA", (s, 0.0, h), 20.0, (1.0, 0.6, 0.25), shape="DISK", size=0.7,
          **down)
    light("area_ellipse", "AREA", (-s, -s, h), 25.0, (0.4, 0.9, 1.0), shape="ELLIPSE",
          size=1.0, size_y=0.45, **down)
    light("point_large", "POINT", (0.0, -s, h), 45.0, (1.0, 1.0, 1.0), shadow_soft_size=0.6,
          **down)
    sun = light("sun", "SUN", (0.0, 0.0, 5.0), 0.4, (1.0, 0.95, 0.8), angle=math.radians(8.0))
    sun.rotation_euler = (math.radians(35.0), 0.0, math.radians(30.0))
    glow = emission("glow", (0.3, 0.5, 1.0), 6.0)
    mesh_object("emitter", sphere_mesh("emitter", 0.25, 16, 8), glow, (s, -s, 0.6))
    for x, y in ((-s, s), (0.0, s), (s, s), (-s, 0.0), (s, 0.0), (-s, -s), (0.0, -s),
                 (0.0, 0.0), (s, -s)):
        mesh_object("block", cube, grey, (x + 0.45, y - 0.35, 0.175))
    scene.camera = camera("camera", (0.0, -0.01, 11.0), (0.0, 0.0, 0.0), lens=50.0)
    uniform_world("black", (0.0, 0.0, 0.0), 1.0)
    save(folder, "lights.blend")


# ---- world.blend ---------------------------------------------------------------------------------


def build_world(folder, textures):
    scene = reset("world")
    sky_path = os.path.join(textures, "sky.exr")
    save_exr("sky", sky_rgba(), sky_path)
    world = bpy.data.worlds.new("hdri")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = bpy.data.images.load(sky_path)
    env.image.colorspace_settings.name = "Linear"
    env.projection = "EQUIRECTANGULAR"
    links.new(env.outputs["Color"], nodes["Background"].inputs["Color"])
    nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world
    plane("ground", 20.0, diffuse("ground", (0.6, 0.6, 0.6)))
    mesh_object("ball", sphere_mesh("ball", 0.5), diffuse("white", (0.8, 0.8, 0.8)),
                (-0.7, 0.5, 0.5))
    mesh_object("mirror_ball", sphere_mesh("mirror_ball", 0.5),
                principled("chrome", (0.9, 0.9, 0.9), 0.1, 1.0)[0], (0.7, 0.3, 0.5))
    mesh_object("block", cube_mesh("block", 0.6), principled("red", (0.7, 0.1, 0.08), 0.4)[0],
                (0.1, 1.6, 0.3))
    scene.camera = camera("camera", (0.3, -3.0, 0.9), (0.0, 0.8, 0.7), lens=26.0)
    save(folder, "world.blend")


# ---- camera.blend --------------------------------------------------------------------------------


def build_camera(folder):
    first = reset("dof")
    props = bpy.data.collections.new("props")
    plane_mesh = bpy.data.meshes.new("floor")
    plane_mesh.from_pydata([(-8, -8, 0), (8, -8, 0), (8, 8, 0), (-8, 8, 0)], [], [(0, 1, 2, 3)])
    plane_mesh.materials.append(diffuse("floor", (0.6, 0.6, 0.6)))
    link(bpy.data.objects.new("floor", plane_mesh), props)
    colors = [(0.8, 0.15, 0.1), (0.9, 0.7, 0.1), (0.15, 0.6, 0.2), (0.1, 0.3, 0.8),
              (0.7, 0.2, 0.7)]
    for i, color in enumerate(colors):
        y = -1.5 + 1.6 * i
        x = -1.2 + 0.6 * i
        mesh_object(f"box{i}", cube_mesh(f"box{i}", 0.7), principled(f"c{i}", color, 0.45)[0],
                    (x, y, 0.35), props)
    focus = mesh_object("focus_ball", sphere_mesh("focus_ball", 0.45),
                        principled("focus", (0.85, 0.85, 0.85), 0.25)[0], (0.3, 0.2, 0.45),
                        props)
    light("key", "AREA", (3.0, -3.0, 5.0), 500.0, (1.0, 0.95, 0.9), target=(0, 0, 0),
          collection=props, shape="DISK", size=2.0)
    world = uniform_world("sky", (0.35, 0.4, 0.5), 1.0)

    scenes = {"dof": first}
    for name in ("ortho", "motion"):
        scene = bpy.data.scenes.new(name)
        feature_render_settings(scene, RES)
        scene.world = world
        scenes[name] = scene
    for scene in scenes.values():
        scene.collection.children.link(props)

    dof = camera("cam_dof", (1.2, -5.0, 1.6), (0.0, 0.8, 0.4), lens=50.0,
                 collection=scenes["dof"].collection)
    d = dof.data.dof
    d.use_dof = True
    d.focus_object = focus
    d.aperture_fstop = 0.5
    d.aperture_blades = 5
    d.aperture_rotation = math.radians(20.0)
    d.aperture_ratio = 1.0
    scenes["dof"].camera = dof

    ortho = camera("cam_ortho", (4.0, -5.0, 5.0), (0.0, 0.8, 0.3),
                   collection=scenes["ortho"].collection)
    ortho.data.type = "ORTHO"
    ortho.data.ortho_scale = 6.0
    scenes["ortho"].camera = ortho

    motion = scenes["motion"]
    cam = camera("cam_motion", (0.0, -5.5, 2.5), (0.0, 0.5, 0.5), lens=40.0,
                 collection=motion.collection)
    motion.camera = cam
    mover = mesh_object("mover", sphere_mesh("mover", 0.4),
                        mover_material(), (-1.0, -1.5, 0.9), motion.collection)
    # Linear motion through frames 1..3; rendered at frame 2 with a one-frame shutter centred
    # on it, so the sphere sweeps x in [-0.5, 0.5] (+-0.5 frame) during the exposure.
    mover.keyframe_insert("location", frame=1)
    mover.location = (1.0, -1.5, 0.9)
    mover.keyframe_insert("location", frame=3)
    for fcurve in mover.animation_data.action.fcurves:
        for key in fcurve.keyframe_points:
            key.interpolation = "LINEAR"
    motion.frame_start, motion.frame_end = 1, 3
    motion.frame_set(2)
    motion.render.use_motion_blur = True
    motion.render.motion_blur_shutter = 1.0
    motion.cycles.motion_blur_position = "CENTER"
    save(folder, "camera.blend")


def mover_material():
    return principled("mover", (0.9, 0.9, 0.9), 0.35)[0]


# ---- instancing.blend ----------------------------------------------------------------------------

GRID = 40  # GRID x GRID vertex instances per field
FIELDS = ((-2.6, 0.0, math.radians(10.0)), (2.6, 0.5, math.radians(-15.0)))


def build_instancing(folder):
    scene = reset("instancing")
    field = bpy.data.collections.new("field")
    scene.collection.children.link(field)
    spacing = 0.12
    xs = (np.arange(GRID) - (GRID - 1) / 2) * spacing
    gx, gy = np.meshgrid(xs, xs)
    jitter = RNG.uniform(-0.03, 0.03, size=(2, GRID, GRID))
    verts = np.stack([gx + jitter[0], gy + jitter[1], np.zeros_like(gx)], axis=-1)
    grid_mesh = bpy.data.meshes.new("grid")
    grid_mesh.from_pydata(verts.reshape(-1, 3).tolist(), [], [])
    grid_mesh.update()
    grid = link(bpy.data.objects.new("grid", grid_mesh), field)
    grid.instance_type = "VERTS"
    monkey = mesh_from_bmesh("monkey", lambda bm: bmesh.ops.create_monkey(bm), smooth=True)
    child = mesh_object("monkey", monkey, principled("orange", (0.9, 0.4, 0.1), 0.4)[0],
                        (0.0, 0.0, 0.05), field)
    child.scale = (0.05, 0.05, 0.05)
    child.rotation_euler = (math.radians(-70.0), 0.0, 0.0)
    child.parent = grid
    # The field collection itself is not rendered: excluded from the view layer, it appears
    # only through the two collection-instance empties.
    scene.view_layers[0].layer_collection.children["field"].exclude = True
    for i, (x, y, angle) in enumerate(FIELDS):
        empty = bpy.data.objects.new(f"field{i}", None)
        empty.instance_type = "COLLECTION"
        empty.instance_collection = field
        empty.location = (x, y, 0.0)
        empty.rotation_euler = (0.0, 0.0, angle)
        link(empty)
    plane("ground", 12.0, diffuse("ground", (0.55, 0.55, 0.5)))
    scene.camera = camera("camera", (0.0, -6.0, 4.0), (0.0, 0.3, 0.0), lens=38.0)
    sun = light("sun", "SUN", (0, 0, 5), 2.5, (1.0, 0.95, 0.85), angle=math.radians(4.0))
    sun.rotation_euler = (math.radians(40.0), 0.0, math.radians(-35.0))
    uniform_world("sky", (0.3, 0.38, 0.5), 1.0)
    save(folder, "instancing.blend")


# ---- procedural.blend ----------------------------------------------------------------------------


def _texture(nodes, kind, **inputs):
    node = nodes.new(kind)
    for key, value in inputs.items():
        node.inputs[key].default_value = value
    return node


def _noise(nodes, scale, detail):
    return _texture(nodes, "ShaderNodeTexNoise", Scale=scale, Detail=detail, Roughness=0.55)


def procedural_materials():
    """The procedural materials of procedural.blend, by object name: every texture feeds a
    Principled BSDF input (or a Bump, or a Mix Shader's factor) through the nodes real files
    use."""
    mats = {}
    # Noise -> Color Ramp -> Base Color.
    mat, bsdf = principled("noise_ramp", (0.8, 0.8, 0.8), roughness=0.45)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    noise = _noise(nodes, 4.0, 4.0)
    ramp = nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].position, ramp.color_ramp.elements[0].color = (
        0.35, (0.9, 0.45, 0.08, 1.0))
    ramp.color_ramp.elements[1].position, ramp.color_ramp.elements[1].color = (
        0.65, (0.08, 0.25, 0.7, 1.0))
    links.new(noise.outputs["Fac"], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], bsdf.inputs["Base Color"])
    mats["noise_ramp"] = mat
    # Voronoi cells: each cell's random colour.
    mat, bsdf = principled("voronoi_cells", (0.8, 0.8, 0.8), roughness=0.5)
    voronoi = _texture(mat.node_tree.nodes, "ShaderNodeTexVoronoi", Scale=6.0)
    mat.node_tree.links.new(voronoi.outputs["Color"], bsdf.inputs["Base Color"])
    mats["voronoi_cells"] = mat
    # Checker on the cube.
    mat, bsdf = principled("checker", (0.8, 0.8, 0.8), roughness=0.5)
    checker = _texture(mat.node_tree.nodes, "ShaderNodeTexChecker", Scale=4.0,
                       Color1=(0.85, 0.85, 0.8, 1.0), Color2=(0.1, 0.35, 0.12, 1.0))
    mat.node_tree.links.new(checker.outputs["Color"], bsdf.inputs["Base Color"])
    mats["checker_cube"] = mat
    # A wave with distortion, through a Mix (Color) of two colours.
    mat, bsdf = principled("wave_distorted", (0.8, 0.8, 0.8), roughness=0.4)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    wave = _texture(nodes, "ShaderNodeTexWave", Scale=3.0, Distortion=6.0, Detail=2.0)
    mix = nodes.new("ShaderNodeMixRGB")
    mix.inputs["Color1"].default_value = (0.75, 0.12, 0.1, 1.0)
    mix.inputs["Color2"].default_value = (0.95, 0.85, 0.6, 1.0)
    links.new(wave.outputs["Fac"], mix.inputs["Fac"])
    links.new(mix.outputs["Color"], bsdf.inputs["Base Color"])
    mats["wave_distorted"] = mat
    # A bump from noise.
    mat, bsdf = principled("bump_noise", (0.7, 0.7, 0.72), roughness=0.35)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    noise = _noise(nodes, 8.0, 2.0)
    bump = _texture(nodes, "ShaderNodeBump", Strength=0.6, Distance=0.1)
    links.new(noise.outputs["Fac"], bump.inputs["Height"])
    links.new(bump.outputs["Normal"], bsdf.inputs["Normal"])
    mats["bump_noise"] = mat
    # Two BSDFs mixed by a noise factor.
    mat, nodes, links, out = node_material("mix_by_noise")
    dif = nodes.new("ShaderNodeBsdfDiffuse")
    dif.inputs["Color"].default_value = (0.8, 0.25, 0.1, 1.0)
    gloss = glossy_node(nodes, (0.9, 0.9, 0.9), 0.3)
    noise = _noise(nodes, 5.0, 2.0)
    shader_mix = nodes.new("ShaderNodeMixShader")
    links.new(noise.outputs["Fac"], shader_mix.inputs["Fac"])
    links.new(dif.outputs["BSDF"], shader_mix.inputs[1])
    links.new(gloss.outputs["BSDF"], shader_mix.inputs[2])
    links.new(shader_mix.outputs["Shader"], out.inputs["Surface"])
    mats["mix_by_noise"] = mat
    # Roughness from a gradient (0.3 .. 0.8 across the object) on a metal.
    mat, bsdf = principled("gradient_roughness", (0.95, 0.7, 0.4), 0.5, 1.0)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    gradient = nodes.new("ShaderNodeTexGradient")
    scale = nodes.new("ShaderNodeMath")
    scale.operation = "MULTIPLY_ADD"
    scale.inputs[1].default_value = 0.5
    scale.inputs[2].default_value = 0.3
    links.new(gradient.outputs["Fac"], scale.inputs[0])
    links.new(scale.outputs["Value"], bsdf.inputs["Roughness"])
    mats["gradient_roughness"] = mat
    # The ground: bricks.
    mat, bsdf = principled("brick_ground", (0.8, 0.8, 0.8), roughness=0.8)
    brick = _texture(mat.node_tree.nodes, "ShaderNodeTexBrick", Scale=6.0,
                     Color1=(0.55, 0.2, 0.12, 1.0), Color2=(0.4, 0.3, 0.25, 1.0),
                     Mortar=(0.75, 0.75, 0.7, 1.0))
    mat.node_tree.links.new(brick.outputs["Color"], bsdf.inputs["Base Color"])
    mats["ground"] = mat
    return mats


def build_procedural(folder):
    """procedural.blend: six spheres and a cube on a brick ground, each material procedural
    (procedural_materials), lit by an area lamp and a sun; black world."""
    scene = reset("procedural")
    mats = procedural_materials()
    spheres = ("noise_ramp", "voronoi_cells", "wave_distorted", "bump_noise", "mix_by_noise",
               "gradient_roughness")
    spots = ((-1.5, 1.4), (0.0, 1.4), (1.5, 1.4), (-1.5, 0.0), (1.5, 0.0), (0.0, -1.4))
    for name, (x, y) in zip(spheres, spots):
        mesh_object(name, sphere_mesh(name, 0.6), mats[name], (x, y, 0.6))
    # UV maps on every mesh, as real files have them (the spheres' come from sphere_mesh).
    cube = mesh_from_bmesh("checker_cube",
                           lambda bm: bmesh.ops.create_cube(bm, size=1.0, calc_uvs=True),
                           uvs=True)
    mesh_object("checker_cube", cube, mats["checker_cube"], (0.0, 0.0, 0.5))
    ground = mesh_from_bmesh("ground",
                             lambda bm: bmesh.ops.create_grid(bm, x_segments=1, y_segments=1,
                                                              size=6.0, calc_uvs=True),
                             uvs=True)
    mesh_object("ground", ground, mats["ground"], (0.0, 0.0, 0.0))
    scene.camera = camera("camera", (0.0, -5.0, 4.6), (0.0, 0.15, 0.3), lens=40.0)
    light("key", "AREA", (-2.5, -2.5, 4.0), 300.0, (1.0, 0.95, 0.9), target=(0.0, 0.0, 0.0),
          shape="SQUARE", size=3.0)
    sun = light("sun", "SUN", (0.0, 0.0, 5.0), 2.5, (1.0, 0.97, 0.9), angle=math.radians(5.0))
    sun.rotation_euler = (math.radians(40.0), 0.0, math.radians(-35.0))
    uniform_world("black", (0.0, 0.0, 0.0), 1.0)
    save(folder, "procedural.blend")


# ---- main ----------------------------------------------------------------------------------------


def save(folder, name):
    path = os.path.join(folder, name)
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True, relative_remap=True)
    print("saved", path, os.path.getsize(path), "bytes")


def main():
    bpy.context.preferences.filepaths.save_version = 0  # no .blend1 backups
    folder = output_path("scenes/features/make_features.py -- scenes/features")
    textures = os.path.join(folder, "textures")
    os.makedirs(textures, exist_ok=True)
    build_materials(folder, textures)
    build_lights(folder)
    build_world(folder, textures)
    build_camera(folder)
    build_instancing(folder)
    build_procedural(folder)


main()
