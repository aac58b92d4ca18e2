"""Build the Cornell box variants of the estimator study (issue 6) from scenes/cornell_box.blend.

Run (Blender 3.4, so the files open in 3.4 and in every later Blender):

    blender -b --factory-startup --python scenes/make_cornell_variants.py -- scenes/

Writes into the given folder:

| file                     | change from cornell_box.blend                                     |
|--------------------------|-------------------------------------------------------------------|
| cornell_large_light.blend| the 0.5 x 0.5 m light quad scaled by LARGE_SCALE in x and y (1.8 x 1.8 m, 81 % of the ceiling) at the same total power: emission strength / LARGE_SCALE² |
| cornell_glossy.blend     | floor, both boxes and the sphere in a glossy metal (Principled, Metallic 1, Roughness GLOSSY_ROUGHNESS, base colour the box's white); the small light |

The bundled box is the "small light" case: its light is 1/16 of the ceiling, 0.064 sr seen
from the floor's centre (0.25 m² at 1.98 m). The large one keeps the light's power
Φ = π·L·A (Lambertian emitter): L·A is held constant, so the two boxes differ only in how the
same light is spread, which is the variable of the textbook's claims (§5: NEE wins for small
lights, BSDF sampling for large lights and glossy surfaces). Only bpy.data and
bpy.ops.wm.open_mainfile / save_as_mainfile are used, so the script also runs under the bpy
wheel.
"""
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
# Blender does not put a --python script's folder on sys.path; scene_building.py is there.
sys.path.insert(0, HERE)
from scene_building import output_path

SOURCE = os.path.join(HERE, "cornell_box.blend")
LARGE_SCALE = 3.6  # 0.5 m * 3.6 = 1.8 m: inside the 2 m ceiling with a 0.1 m margin
GLOSSY_ROUGHNESS = 0.2  # Blender's roughness; GGX alpha = roughness² = 0.04: a narrow lobe
GLOSSY_OBJECTS = ("Floor", "TallBox", "ShortBox", "Sphere")


def light_strength_input():
    mat = bpy.data.materials["Light"]
    node = next(n for n in mat.node_tree.nodes if n.type == "EMISSION")
    return node.inputs["Strength"]


def make_large_light(path):
    bpy.ops.wm.open_mainfile(filepath=SOURCE)
    light = bpy.data.objects["LightQuad"]
    if tuple(light.scale) != (1.0, 1.0, 1.0):
        raise SystemExit(f"{SOURCE}: LightQuad is already scaled {tuple(light.scale)}")
    light.scale = (LARGE_SCALE, LARGE_SCALE, 1.0)
    strength = light_strength_input()
    strength.default_value = strength.default_value / LARGE_SCALE ** 2
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    print("saved", path, "light strength", strength.default_value)


def make_glossy(path):
    bpy.ops.wm.open_mainfile(filepath=SOURCE)
    white = bpy.data.materials["White"]
    glossy = white.copy()
    glossy.name = "GlossyMetal"
    bsdf = next(n for n in glossy.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Metallic"].default_value = 1.0
    bsdf.inputs["Roughness"].default_value = GLOSSY_ROUGHNESS
    meshes = {bpy.data.objects[name].data for name in GLOSSY_OBJECTS}  # the boxes share one
    for mesh in meshes:
        if list(mesh.materials) != [white]:
            raise SystemExit(f"{SOURCE}: mesh {mesh.name} is not White only")
        mesh.materials[0] = glossy
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=True)
    print("saved", path)


def main():
    folder = output_path("scenes/make_cornell_variants.py -- scenes/", exactly_one=True)
    make_large_light(os.path.join(folder, "cornell_large_light.blend"))
    make_glossy(os.path.join(folder, "cornell_glossy.blend"))


main()
