"""Noise and Musgrave textures: Cycles against Stratum at exact points, in the Blender running
this script (3.4 or 5.0).

Measured: Cycles' Noise and Musgrave values (worst difference 3.2e-5, docs/shader_nodes.md);
held by tests/native/shading/test_noise_nodes.cpp (NoiseNodesCycles.*) as reference values.

    blender -b --factory-startup -noaudio --python scripts/run_in_blender.py -- \
        scripts.cycles_reference.noise OUT.json
    .venv/bin/python -m scripts.cycles_reference.noise OUT.json      # the bpy wheel (5.0)

Each configuration renders a 2 x 2 plane through an orthographic camera, one sample per pixel, its
Emission driven by the texture. The texture's Vector is the object position snapped to the pixel
(Vector Math Snap) plus an offset, so every sample of a pixel evaluates the texture at one known
point; W, for 1D and 4D, is that point's X. The same node is then compiled by the add-on
(stratum.shaders.nodes) and evaluated at those points by the native library; the JSON holds each
configuration's worst absolute and relative differences and a few sample values."""

from __future__ import annotations

import json
import os
import sys
import tempfile
from typing import Any

import bpy
import numpy as np
from stratum import native
from stratum.shaders.nodes import NodeCompiler

N = 16  # pixels a side; a pixel is 2 / N units
OFFSET = (3.17, -1.41, 0.73)

NOISE_34 = [
    {"node": "noise", "dims": "3D", "Scale": 5.0, "Detail": 2.0, "Roughness": 0.5},
    {"node": "noise", "dims": "3D", "Scale": 3.0, "Detail": 4.5, "Roughness": 0.6,
     "Distortion": 1.3, "out": "Color"},
    {"node": "noise", "dims": "1D", "Scale": 4.0, "Detail": 3.3, "Roughness": 0.7,
     "Distortion": 0.4, "out": "Color"},
    {"node": "noise", "dims": "2D", "Scale": 6.0, "Detail": 0.0, "Roughness": 0.5},
    {"node": "noise", "dims": "4D", "Scale": 2.0, "Detail": 6.0, "Roughness": 0.45,
     "Distortion": 0.8, "out": "Color"},
]
MUSGRAVE_34 = [
    {"node": "musgrave", "dims": "3D", "type": t, "Scale": 4.0, "Detail": 3.5, "Dimension": 1.2,
     "Lacunarity": 2.1, "Offset": 1.0, "Gain": 1.1}
    for t in ("FBM", "MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HYBRID_MULTIFRACTAL",
              "HETERO_TERRAIN")
] + [
    {"node": "musgrave", "dims": d, "type": "RIDGED_MULTIFRACTAL", "Scale": 3.0, "Detail": 5.0,
     "Dimension": 0.8, "Lacunarity": 2.5, "Offset": 1.0, "Gain": 2.0}
    for d in ("1D", "2D", "4D")
]
NOISE_5 = [
    {"node": "noise", "dims": "3D", "Scale": 5.0, "Detail": 2.0, "Roughness": 0.5},
    {"node": "noise", "dims": "3D", "Scale": 3.0, "Detail": 4.5, "Roughness": 0.6,
     "Lacunarity": 2.3, "Distortion": 1.3, "out": "Color"},
    {"node": "noise", "dims": "3D", "Scale": 3.0, "Detail": 3.5, "Roughness": 0.6,
     "normalize": False, "out": "Color"},
    {"node": "noise", "dims": "1D", "Scale": 4.0, "Detail": 3.3, "Roughness": 0.7,
     "Distortion": 0.4, "out": "Color"},
    {"node": "noise", "dims": "2D", "Scale": 6.0, "Detail": 1.5, "Roughness": 1.4},
    {"node": "noise", "dims": "4D", "Scale": 2.0, "Detail": 6.0, "Roughness": 0.45,
     "Distortion": 0.8, "out": "Color"},
] + [
    {"node": "noise", "dims": d, "type": t, "Scale": 4.0, "Detail": 3.5, "Roughness": 0.6,
     "Lacunarity": 2.1, "Offset": 1.0, "Gain": 1.1}
    for t in ("MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HYBRID_MULTIFRACTAL", "HETERO_TERRAIN")
    for d in ("2D", "3D")
] + [
    {"node": "noise", "dims": "3D", "Scale": 1.0, "Detail": 1.0, "Roughness": 0.5,
     "offset": (2.5e6, -1.25e6, 3.0e6)},
]


def reset_scene() -> Any:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 1
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.filter_width = 0.01
    scene.cycles.sample_clamp_direct = 0.0
    scene.cycles.sample_clamp_indirect = 0.0
    scene.render.resolution_x = scene.render.resolution_y = N
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    world = bpy.data.worlds.new("w")
    scene.world = world
    world.color = (0.0, 0.0, 0.0)
    bpy.ops.mesh.primitive_plane_add(size=2.0)
    cam = bpy.data.cameras.new("cam")
    cam.type = "ORTHO"
    cam.ortho_scale = 2.0
    cam_ob = bpy.data.objects.new("cam", cam)
    cam_ob.location = (0.0, 0.0, 5.0)
    scene.collection.objects.link(cam_ob)
    scene.camera = cam_ob
    return scene


def build(config: dict[str, Any]) -> tuple[Any, Any, Any]:
    """The plane's material: the texture's Vector (and W) from the snapped position."""
    mat = bpy.data.materials.new("m")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    coord = nt.nodes.new("ShaderNodeTexCoord")
    snap = nt.nodes.new("ShaderNodeVectorMath")
    snap.operation = "SNAP"
    snap.inputs[1].default_value = (2.0 / N,) * 3
    add = nt.nodes.new("ShaderNodeVectorMath")
    add.operation = "ADD"
    add.inputs[1].default_value = config.get("offset", OFFSET)
    sep = nt.nodes.new("ShaderNodeSeparateXYZ")
    nt.links.new(coord.outputs["Object"], snap.inputs[0])
    nt.links.new(snap.outputs[0], add.inputs[0])
    nt.links.new(add.outputs[0], sep.inputs[0])
    if config["node"] == "noise":
        tex = nt.nodes.new("ShaderNodeTexNoise")
        tex.noise_dimensions = config["dims"]
        if "type" in config:
            tex.noise_type = config["type"]
        if "normalize" in config:
            tex.normalize = config["normalize"]
    else:
        tex = nt.nodes.new("ShaderNodeTexMusgrave")
        tex.musgrave_dimensions = config["dims"]
        tex.musgrave_type = config["type"]
    for key, value in config.items():
        if key[0].isupper() and tex.inputs.get(key) is not None:
            tex.inputs[key].default_value = value
    # Blender 5.0 lists only the sockets the dimensions use.
    if config["dims"] != "1D":
        nt.links.new(add.outputs[0], tex.inputs["Vector"])
    if config["dims"] in ("1D", "4D"):
        nt.links.new(sep.outputs["X"], tex.inputs["W"])
    emission = nt.nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    nt.links.new(tex.outputs[config.get("out", "Fac")], emission.inputs["Color"])
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(emission.outputs[0], out.inputs["Surface"])
    bpy.data.objects["Plane"].data.materials.append(mat)
    return nt, tex, emission


def points(offset: tuple[float, float, float]) -> np.ndarray:
    """The texture's point at each pixel (rows bottom up), as Cycles rounds it: snap(p, b) =
    floor(p / b) b is (i - N/2) b exactly; the offset is added in float32."""
    b = np.float32(2.0 / N)
    k = (np.arange(N, dtype=np.float32) - np.float32(N // 2)) * b
    off = np.asarray(offset, dtype=np.float32)
    p = np.zeros((N, N, 3), dtype=np.float32)
    p[:, :, 0] = k[None, :] + off[0]
    p[:, :, 1] = k[:, None] + off[1]
    p[:, :, 2] = np.float32(0.0) + off[2]
    return p


def stratum_values(nt: Any, tex: Any, emission: Any, pts: np.ndarray) -> np.ndarray:
    """The add-on's program for the same node, its Vector and W rewired to a Generated input that
    holds each pixel's point."""
    coord = nt.nodes.new("ShaderNodeTexCoord")
    sep = nt.nodes.new("ShaderNodeSeparateXYZ")
    nt.links.new(coord.outputs["Generated"], sep.inputs[0])
    if tex.inputs.get("Vector") is not None and tex.inputs["Vector"].is_linked:
        nt.links.new(coord.outputs["Generated"], tex.inputs["Vector"])
    if tex.inputs.get("W") is not None and tex.inputs["W"].is_linked:
        nt.links.new(sep.outputs["X"], tex.inputs["W"])
    warnings: list[str] = []
    c = NodeCompiler(tuple(bpy.app.version), lambda node, msg: warnings.append(msg))
    reg = c.value(emission.inputs["Color"], "color")
    if warnings:
        raise RuntimeError(warnings)
    scene = native.Scene()
    pid = scene.add_shader_program(c.builder.program)
    gen = native.SHADER_INPUTS["generated"][0]
    out = np.zeros((N, N, 3), dtype=np.float32)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    for r in range(N):
        for i in range(N):
            inputs[gen:gen + 3] = pts[r, i]
            out[r, i] = scene.evaluate_program(pid, inputs, reg, 3)
    return out


def cycles_values(scene: Any, path: str) -> np.ndarray:
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    px = np.array(image.pixels[:], dtype=np.float32).reshape(N, N, 4)[:, :, :3]
    bpy.data.images.remove(image)
    return px


def main(out_path: str) -> None:
    version = tuple(bpy.app.version)
    configs = NOISE_34 + MUSGRAVE_34 if version < (4, 1) else NOISE_5
    results = []
    tmp = tempfile.mkdtemp(prefix="noise_agreement_")
    for n, config in enumerate(configs):
        scene = reset_scene()
        nt, tex, emission = build(config)
        cyc = cycles_values(scene, os.path.join(tmp, f"{n}.exr"))
        pts = points(config.get("offset", OFFSET))
        ours = stratum_values(nt, tex, emission, pts)
        diff = np.abs(cyc - ours)
        rel = diff / np.maximum(np.abs(cyc), 1e-3)
        worst = np.unravel_index(np.argmax(rel), rel.shape)
        results.append({
            "config": {k: v for k, v in config.items()},
            "max_abs": float(diff.max()), "max_rel": float(rel.max()),
            "cycles_range": [float(cyc.min()), float(cyc.max())],
            "samples": [{"point": [float(v) for v in pts[r, i]],
                         "cycles": [float(v) for v in cyc[r, i]],
                         "stratum": [float(v) for v in ours[r, i]]}
                        for r, i in ((0, 0), (5, 11), (N - 1, 3))],
            "worst_pixel": [int(worst[0]), int(worst[1])],
        })
        print(f"[{n}] {config} max_abs={diff.max():.3g} max_rel={rel.max():.3g}", flush=True)
    with open(out_path, "w") as f:
        json.dump({"blender": list(version), "results": results}, f, indent=1)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    main(argv[0] if argv else "noise_agreement.json")
