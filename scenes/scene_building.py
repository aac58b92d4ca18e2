"""What the scene generator scripts share: reading the output path, clearing the start-up scene,
the materials, meshes, camera, world and render settings they all build the same way, and
saving.

Used by make_cornell_box.py, make_cornell_variants.py, make_ao_study.py, make_wolf.py and
features/make_features.py. They run inside Blender (`blender -b --factory-startup --python
scenes/make_X.py -- OUT`), which does not put a script's folder on sys.path, so each script
inserts the folder of this module before importing it. Only bpy.data and mathutils are used,
so the scripts also run under the `bpy` wheel.
"""

from __future__ import annotations

import os
import sys

import bpy

Vec = tuple[float, float, float]
Face = tuple[int, ...]


def output_path(usage: str, exactly_one: bool = False) -> str:
    """The first argument after `--` (Blender's own come before it), made absolute. Without
    one (or, with exactly_one, unless there is exactly one), exits naming the command line:
    `usage` is what follows `--python`."""
    argv = sys.argv
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if (len(args) != 1) if exactly_one else not args:
        raise SystemExit(f"usage: blender -b --factory-startup --python {usage}")
    return os.path.abspath(args[0])


def clear_scene() -> None:
    """Removes every object of the start-up file and the meshes, materials, lights and cameras
    no longer used."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras):
        for block in list(coll):
            if block.users == 0:
                coll.remove(block)


def principled(name: str, color: Vec, roughness: float | None = None) -> bpy.types.Material:
    """Blender's default Principled BSDF (use_nodes = True) with only Base Color set, and
    Roughness when given."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = next(n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    if roughness is not None:
        bsdf.inputs["Roughness"].default_value = roughness
    mat.diffuse_color = (*color, 1.0)  # viewport colour only
    return mat


def node_material(name: str) -> tuple[bpy.types.Material, bpy.types.Nodes, bpy.types.NodeLinks,
                                       bpy.types.Node]:
    """A node material holding only its Material Output; returns (material, nodes, links, out)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    for node in list(nodes):
        if node.type != "OUTPUT_MATERIAL":
            nodes.remove(node)
    out = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
    return mat, nodes, links, out


def emission(name: str, color: Vec, strength: float) -> bpy.types.Material:
    """An Emission shader alone: the emitted radiance is color x strength."""
    mat, nodes, links, out = node_material(name)
    emit = nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = (*color, 1.0)
    emit.inputs["Strength"].default_value = strength
    emit.location = (out.location.x - 250, out.location.y)
    links.new(emit.outputs["Emission"], out.inputs["Surface"])
    return mat


def mesh_object(name: str, verts: list[Vec] | None, faces: list[Face] | None,
                material: bpy.types.Material, mesh: bpy.types.Mesh | None = None,
                smooth: bool = False) -> bpy.types.Object:
    """An object in the scene's collection, of a new mesh made of verts and faces (named
    name + "Mesh", one material) or of an existing mesh (a linked duplicate)."""
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


def quad(name: str, corners: list[Vec], material: bpy.types.Material) -> bpy.types.Object:
    """A single quad; the corners are counter-clockwise seen from the side the normal faces."""
    return mesh_object(name, corners, [(0, 1, 2, 3)], material)


def aim(obj: bpy.types.Object, target: Vec) -> None:
    """Point the object's local -Z at target, +Y up (cameras and lights look down -Z)."""
    from mathutils import Vector

    direction = Vector(target) - obj.location
    obj.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()


def perspective_camera(lens: float, clip_start: float, location: Vec) -> bpy.types.Object:
    """The scene's camera "Camera": perspective, a 36 mm sensor fitted automatically, clipping
    from clip_start to 100 m, at location (orient it with rotation_euler or aim)."""
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.type = "PERSP"
    cam_data.lens = lens
    cam_data.sensor_fit = "AUTO"
    cam_data.sensor_width = 36.0
    cam_data.clip_start = clip_start
    cam_data.clip_end = 100.0
    cam = bpy.data.objects.new("Camera", cam_data)
    bpy.context.scene.collection.objects.link(cam)
    cam.location = location
    bpy.context.scene.camera = cam
    return cam


def uniform_world(scene: bpy.types.Scene, color: Vec) -> None:
    """The scene's world (made when there is none) as one colour at strength 1, in its
    Background node and its viewport colour."""
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.color = color
    world.use_nodes = True
    bg = next((n for n in world.node_tree.nodes if n.type == "BACKGROUND"), None)
    if bg is not None:
        bg.inputs["Color"].default_value = (*color, 1.0)
        bg.inputs["Strength"].default_value = 1.0


def feature_render_settings(scene: bpy.types.Scene, res: int) -> None:
    """The feature scenes' stored render settings: Cycles (Stratum is chosen at render time),
    res x res at 100 %, an opaque film, the Standard view transform at exposure 0, 64 samples
    and no denoising (tests/blender/test_feature_agreement.py sets the sampling it compares)."""
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x = r.resolution_y = res
    r.resolution_percentage = 100
    r.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.cycles.samples = 64
    scene.cycles.use_denoising = False


def png_render_settings(scene: bpy.types.Scene, width: int, height: int) -> None:
    """width x height at 100 %, square pixels, RGB PNG output, an opaque film, and the Standard
    view transform on an sRGB display, so a PNG is the plain sRGB encoding of linear."""
    r = scene.render
    r.resolution_x = width
    r.resolution_y = height
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.image_settings.file_format = "PNG"
    r.image_settings.color_mode = "RGB"
    r.film_transparent = False
    # Leave CYCLES here: the STRATUM enum value cannot be stored unless the add-on is
    # registered; `-E STRATUM` selects it at render time.
    r.engine = "CYCLES"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.display_settings.display_device = "sRGB"


def save(path: str) -> None:
    """Saves the open file as a compressed .blend at path."""
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    print("saved", path)
