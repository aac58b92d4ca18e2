"""Renders Sky Texture worlds in Cycles (run inside Blender) and writes, per case, each pixel's
direction and colour to a JSON file.

Measured: Cycles' sky per pixel direction, every sky type of Blender 3.4, 4.5 and 5.0 (4.2's
pixels equal 4.5's); held by tests/native/shading/test_sky_nodes.cpp (SkyNodes.*MatchesCycles34,
*MatchesCycles45*, *MatchesCycles50) and tests/python/test_sky_nodes.py (the Preetham zenith,
Hosek-Wilkie) as reference pixels.

    blender -b --factory-startup -noaudio --python scripts/run_in_blender.py -- \
        scripts.cycles_reference.sky out.json                       # Blender 3.4
    .venv/bin/python -m scripts.cycles_reference.sky out.json       # the bpy wheel (5.0)
    .venv-bpy-4.5/bin/python -m scripts.cycles_reference.sky out.json  # an LTS wheel (4.5)

The camera is an equirectangular panorama (64 x 32, 1 sample, filter width 0.01: pixel
centres). The pixel directions are rendered too (a world of Generated * 0.5 + 0.5), so no
camera convention is assumed. Cases: the sky types Blender offers (3.x: PREETHAM,
HOSEK_WILKIE, NISHITA; 5.x: PREETHAM, HOSEK_WILKIE, SINGLE_SCATTERING, MULTIPLE_SCATTERING)."""

from __future__ import annotations

import json
import math
import os
import sys
import tempfile
from typing import Any

import bpy  # type: ignore[import-not-found]

WIDTH, HEIGHT = 64, 32


def cases() -> dict[str, dict[str, Any]]:
    types = [e.identifier for e in bpy.types.ShaderNodeTexSky.bl_rna.properties["sky_type"]
             .enum_items]
    out: dict[str, dict[str, Any]] = {
        "preetham": {"sky_type": "PREETHAM", "sun_direction": (0.3, 0.4, 0.6), "turbidity": 3.0},
        "hosek": {"sky_type": "HOSEK_WILKIE", "sun_direction": (-0.5, 0.2, 0.4),
                  "turbidity": 4.0, "ground_albedo": 0.5},
    }
    scattering = [t for t in ("NISHITA", "SINGLE_SCATTERING", "MULTIPLE_SCATTERING") if t in types]
    for t in scattering:
        low = t.lower()
        out[f"{low}_sky"] = {"sky_type": t, "sun_elevation": math.radians(15.0),
                             "sun_rotation": math.radians(30.0), "altitude": 100.0,
                             "air_density": 1.0, "ozone_density": 1.5, "sun_disc": False,
                             "dust": 2.0}
        out[f"{low}_disc"] = {"sky_type": t, "sun_elevation": math.radians(30.0),
                              "sun_rotation": math.radians(-40.0), "sun_size": math.radians(40.0),
                              "sun_intensity": 0.7, "altitude": 1000.0, "sun_disc": True,
                              "dust": 1.0}
        out[f"{low}_setting"] = {"sky_type": t, "sun_elevation": math.radians(3.0),
                                 "sun_rotation": math.radians(200.0),
                                 "sun_size": math.radians(30.0), "sun_disc": True, "dust": 0.5}
    return out


def set_world(world: Any, case: dict[str, Any] | None) -> None:
    nt = world.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputWorld")
    bg = nt.nodes.new("ShaderNodeBackground")
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    if case is None:
        coord = nt.nodes.new("ShaderNodeTexCoord")
        mad = nt.nodes.new("ShaderNodeVectorMath")
        mad.operation = "MULTIPLY_ADD"
        mad.inputs[1].default_value = (0.5, 0.5, 0.5)
        mad.inputs[2].default_value = (0.5, 0.5, 0.5)
        nt.links.new(coord.outputs["Generated"], mad.inputs[0])
        nt.links.new(mad.outputs["Vector"], bg.inputs["Color"])
        return
    sky = nt.nodes.new("ShaderNodeTexSky")
    for key, value in case.items():
        if key == "dust":
            name = "dust_density" if hasattr(sky, "dust_density") else "aerosol_density"
            setattr(sky, name, value)
        else:
            setattr(sky, key, value)
    nt.links.new(sky.outputs["Color"], bg.inputs["Color"])


def render(path: str) -> list[float]:
    scene = bpy.context.scene
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    pixels = list(img.pixels)
    bpy.data.images.remove(img)
    return pixels


def main() -> None:
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    target = argv[0] if argv else "sky_reference.json"
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 0.01
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    for ob in list(scene.objects):
        if ob.type != "CAMERA":
            bpy.data.objects.remove(ob)
    cam = scene.camera
    cam.rotation_euler = (math.pi / 2, 0.0, 0.0)
    if hasattr(cam.data, "panorama_type"):  # 4.x and later
        cam.data.type = "PANO"
        cam.data.panorama_type = "EQUIRECTANGULAR"
    else:
        cam.data.type = "PANO"
        cam.data.cycles.panorama_type = "EQUIRECTANGULAR"
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    tmp = tempfile.mkdtemp()
    set_world(world, None)
    raw = render(os.path.join(tmp, "dirs.exr"))
    dirs = [[2.0 * raw[4 * i + k] - 1.0 for k in range(3)] for i in range(WIDTH * HEIGHT)]
    result: dict[str, Any] = {"blender": list(bpy.app.version), "width": WIDTH,
                              "height": HEIGHT, "directions": dirs, "cases": {}}
    for name, case in cases().items():
        set_world(world, case)
        raw = render(os.path.join(tmp, f"{name}.exr"))
        result["cases"][name] = {
            "settings": {k: list(v) if isinstance(v, tuple) else v for k, v in case.items()},
            "rgb": [[raw[4 * i + k] for k in range(3)] for i in range(WIDTH * HEIGHT)]}
    with open(target, "w") as f:
        json.dump(result, f)
    print("wrote", target)


if __name__ == "__main__":
    main()
