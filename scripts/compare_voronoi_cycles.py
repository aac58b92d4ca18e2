"""Voronoi and White Noise against Cycles: renders a 2x2 plane seen by an orthographic camera
with an Emission shader driven by the node (1 sample, box filter 0.01 px, 32 x 32), reads the
float pixels, evaluates the same node compiled by Stratum's translator at the same Generated
coordinates (a render of the Generated coordinate itself, same rays) and prints the worst
difference per mode and output.

    blender -b --factory-startup -noaudio --python scripts/compare_voronoi_cycles.py -- out.json
    PYTHONPATH=addon .venv/bin/python scripts/compare_voronoi_cycles.py -- out.json   # bpy 5.0

Needs addon/stratum/lib/libstratum.so (the build's)."""

from __future__ import annotations

import json
import os
import sys
import tempfile
from typing import Any

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "addon"))

from stratum import native
from stratum.shaders.nodes import NodeCompiler

SIZE = 32
TMP = tempfile.mkdtemp(prefix="voronoi_cmp_")


def setup() -> tuple[Any, Any]:
    scene = bpy.context.scene
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    bpy.ops.mesh.primitive_plane_add(size=2.0)
    plane = bpy.context.active_object
    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 2.0
    cam = bpy.data.objects.new("cam", cam_data)
    cam.location = (0.0, 0.0, 5.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 1
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    # 3.x: filter_type; 4.x+: pixel_filter_type.
    for name in ("filter_type", "pixel_filter_type"):
        if hasattr(scene.cycles, name):
            setattr(scene.cycles, name, "BOX")
    scene.cycles.filter_width = 0.01
    scene.cycles.seed = 0
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    if scene.world is None:
        scene.world = bpy.data.worlds.new("w")
    scene.world.use_nodes = False
    scene.world.color = (0.0, 0.0, 0.0)
    mat = bpy.data.materials.new("m")
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    emission = nodes.new("ShaderNodeEmission")
    sock(emission.inputs, "Strength").default_value = 1.0
    mat.node_tree.links.new(emission.outputs[0], sock(out.inputs, "Surface"))
    plane.data.materials.append(mat)
    return mat, emission


def render(name: str) -> np.ndarray:
    path = os.path.join(TMP, f"{name}.exr")
    bpy.context.scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    px = np.array(image.pixels[:], dtype=np.float32).reshape(SIZE, SIZE, 4)[..., :3]
    bpy.data.images.remove(image)
    return px.reshape(-1, 3)


def show(mat: Any, emission: Any, socket: Any, combine: Any) -> np.ndarray:
    """Renders what `socket` gives, as the emission colour (a float through Combine XYZ)."""
    links = mat.node_tree.links
    for link in list(sock(emission.inputs, "Color").links):
        links.remove(link)
    links.new(socket, sock(emission.inputs, "Color"))
    return render(socket.node.name + socket.identifier)


def sock(sockets: Any, key: str) -> Any:
    """A socket by identifier (5.0's collections do not find unavailable sockets by name)."""
    return next(s for s in sockets if s.identifier == key)


def stratum_values(node: Any, outputs: list[str], generated: np.ndarray) -> dict[str, np.ndarray]:
    warnings: list[str] = []
    c = NodeCompiler(tuple(bpy.app.version), lambda n, m: warnings.append(m))
    regs = {o: c.output(node, sock(node.outputs, o)) for o in outputs}
    scene = native.Scene()
    pid = scene.add_shader_program(c.builder.program)
    base = native.SHADER_INPUTS["generated"][0]
    result = {o: [] for o in outputs}
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    for g in generated:
        inputs[base:base + 3] = g
        for o in outputs:
            width = 1 if sock(node.outputs, o).type == "VALUE" else 3
            result[o].append(scene.evaluate_program(pid, inputs, regs[o], width))
    if warnings:
        print("warnings:", warnings)
    return {o: np.array(v, dtype=np.float32).reshape(len(generated), -1) for o, v in result.items()}


def compare(cycles: np.ndarray, ours: np.ndarray) -> dict[str, float]:
    if ours.shape[1] == 1:
        cycles = cycles[:, :1]
    diff = np.abs(cycles - ours)
    rel = diff / np.maximum(np.abs(cycles), 1e-3)
    return {"max_abs": float(diff.max()), "max_rel": float(rel.max()),
            "pixels_over_1e-3": int((rel.max(axis=1) > 1e-3).sum())}


def modes(version: tuple[int, ...]) -> list[dict[str, Any]]:
    out: list[dict[str, Any]] = []
    for dims in ("1D", "2D", "3D", "4D"):
        metrics = ("EUCLIDEAN",) if dims == "1D" else ("EUCLIDEAN", "MANHATTAN", "CHEBYCHEV",
                                                       "MINKOWSKI")
        for feature in ("F1", "F2", "SMOOTH_F1"):
            for metric in metrics:
                out.append({"voronoi_dimensions": dims, "feature": feature, "distance": metric})
        for feature in ("DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"):
            out.append({"voronoi_dimensions": dims, "feature": feature, "distance": "EUCLIDEAN"})
    if version >= (4, 0):
        for dims in ("1D", "2D", "3D", "4D"):
            for feature in ("F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE"):
                out.append({"voronoi_dimensions": dims, "feature": feature,
                            "distance": "EUCLIDEAN", "normalize": True, "Detail": 2.5})
    return out


def main() -> None:
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out_path = argv[0] if argv else os.path.join(TMP, "result.json")
    version = tuple(bpy.app.version)
    mat, emission = setup()
    nodes = mat.node_tree.nodes
    coords = nodes.new("ShaderNodeTexCoord")
    generated = show(mat, emission, sock(coords.outputs, "Generated"), None)
    combine = nodes.new("ShaderNodeCombineXYZ")
    results: dict[str, Any] = {"blender": ".".join(map(str, version)), "voronoi": {},
                               "white_noise": {}}

    voronoi = nodes.new("ShaderNodeTexVoronoi")
    voronoi.name = "voronoi"
    sock(voronoi.inputs, "Scale").default_value = 6.5
    sock(voronoi.inputs, "W").default_value = 1.37
    sock(voronoi.inputs, "Exponent").default_value = 1.5
    sock(voronoi.inputs, "Smoothness").default_value = 0.7
    sock(voronoi.inputs, "Randomness").default_value = 0.85
    links = mat.node_tree.links
    for mode in modes(version):
        for key, value in mode.items():
            if key[0].isupper():
                sock(voronoi.inputs, key).default_value = value
            else:
                setattr(voronoi, key, value)
        feature = mode["feature"]
        if feature == "DISTANCE_TO_EDGE":
            outputs = ["Distance"]
        elif feature == "N_SPHERE_RADIUS":
            outputs = ["Radius"]
        else:
            outputs = ["Distance", "Color", "Position", "W"]
        # An unavailable output (Position in 1D, W in 2D/3D) feeds Cycles nothing.
        outputs = [o for o in outputs if getattr(sock(voronoi.outputs, o), "enabled", True)]
        cycles: dict[str, np.ndarray] = {}
        floats = [o for o in outputs if sock(voronoi.outputs, o).type == "VALUE"]
        for link in [lk for s in combine.inputs for lk in s.links]:
            links.remove(link)
        for i, o in enumerate(floats[:3]):
            links.new(sock(voronoi.outputs, o), combine.inputs[i])
        packed = show(mat, emission, combine.outputs[0], None)
        for i, o in enumerate(floats[:3]):
            cycles[o] = packed[:, i:i + 1]
        for o in outputs:
            if o not in floats:
                cycles[o] = show(mat, emission, sock(voronoi.outputs, o), None)
        ours = stratum_values(voronoi, outputs, generated)
        key = "/".join(str(v) for v in mode.values())
        results["voronoi"][key] = {o: compare(cycles[o], ours[o]) for o in outputs}
        print(key, results["voronoi"][key], flush=True)
        if hasattr(voronoi, "normalize"):
            voronoi.normalize = False
        if "Detail" in mode:
            sock(voronoi.inputs, "Detail").default_value = 0.0

    white = nodes.new("ShaderNodeTexWhiteNoise")
    white.name = "white"
    sock(white.inputs, "W").default_value = 0.61
    # Cycles gives White Noise's Vector no default link: linked to Generated to vary.
    links.new(sock(coords.outputs, "Generated"), sock(white.inputs, "Vector"))
    for dims in ("1D", "2D", "3D", "4D"):
        white.noise_dimensions = dims
        for link in list(combine.inputs[0].links):
            links.remove(link)
        links.new(sock(white.outputs, "Value"), combine.inputs[0])
        cycles = {"Value": show(mat, emission, combine.outputs[0], None)[:, :1],
                  "Color": show(mat, emission, sock(white.outputs, "Color"), None)}
        ours = stratum_values(white, ["Value", "Color"], generated)
        results["white_noise"][dims] = {o: compare(cycles[o], ours[o]) for o in cycles}
        print("white", dims, results["white_noise"][dims], flush=True)

    with open(out_path, "w") as f:
        json.dump(results, f, indent=1)


main()
