"""Cycles against Stratum for the vector and converter nodes, one node at a time.

    blender -b --factory-startup -noaudio --python scripts/check_vector_nodes_cycles.py   # 3.4
    .venv/bin/python scripts/check_vector_nodes_cycles.py                                 # 5.0

Each case drives the world's Background colour with one node's output (a float as grey), renders
2 x 2 pixels with Cycles (1 sample, Standard view, EXR) and compares pixel 0 with the same node
compiled by stratum.shaders.nodes and evaluated natively (addon/stratum/lib must hold the built
library). The node's first input is fed through x * Light Path's Is Camera Ray (1 for camera
rays) so that neither Blender nor Cycles folds the node as a constant: the render kernel
evaluates it, as it does in real materials. Stratum does not translate Light Path and uses the
multiplier's value, 1 (its warning is expected). Fresnel and Layer Weight are seen at normal
incidence (the world's normal is the view). Prints one line per case and exits 1 if a relative
difference exceeds 1e-3."""

from __future__ import annotations

import os
import sys
import tempfile
from typing import Any

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "addon"))
from stratum import native
from stratum.shaders.nodes import NodeCompiler

VERSION = tuple(bpy.app.version)
OUT = os.path.join(tempfile.mkdtemp(), "node.exr")
Case = tuple[str, str, dict[str, Any], dict[str, Any]]


def setup() -> Any:
    scene = bpy.context.scene
    for ob in list(bpy.data.objects):
        if ob.type != "CAMERA":
            bpy.data.objects.remove(ob)
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 1
    scene.cycles.device = "CPU"
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.render.resolution_x = scene.render.resolution_y = 2
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = OUT
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    return world.node_tree


def cycles_pixel() -> np.ndarray:
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(OUT, check_existing=False)
    px = np.array(img.pixels[:], dtype=np.float32).reshape(-1, 4)
    bpy.data.images.remove(img)
    return px[0, :3]


def stratum_pixel(socket: Any) -> tuple[np.ndarray, list[str]]:
    warnings: list[str] = []
    c = NodeCompiler(VERSION, lambda node, message: warnings.append(message))
    register = c.value(socket, "color")
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    for name in ("normal", "incoming"):
        at = native.SHADER_INPUTS[name][0]
        inputs[at:at + 3] = (0, 0, 1)
    with native.Scene() as scene:
        pid = scene.add_shader_program(c.builder.program)
        return scene.evaluate_program(pid, inputs, register, 3), warnings


def run_case(tree: Any, case: Case) -> tuple[np.ndarray, np.ndarray, list[str]]:
    idname, output, props, values = case
    tree.nodes.clear()
    background = tree.nodes.new("ShaderNodeBackground")
    world_output = tree.nodes.new("ShaderNodeOutputWorld")
    tree.links.new(background.outputs[0], world_output.inputs[0])
    node = tree.nodes.new(idname)
    for key, value in props.items():
        setattr(node, key, value)
    for key, value in values.items():
        next(s for s in node.inputs if s.identifier == key).default_value = value
    first = next(s for s in node.inputs if s.enabled)
    light_path = tree.nodes.new("ShaderNodeLightPath")
    if first.type == "VECTOR":
        scale = tree.nodes.new("ShaderNodeVectorMath")
        scale.operation = "SCALE"
        scale.inputs["Vector"].default_value = first.default_value
        scale.inputs["Scale"].default_value = 1.0
        tree.links.new(light_path.outputs["Is Camera Ray"], scale.inputs["Scale"])
        tree.links.new(scale.outputs["Vector"], first)
    else:
        times = tree.nodes.new("ShaderNodeMath")
        times.operation = "MULTIPLY"
        times.inputs[0].default_value = first.default_value
        times.inputs[1].default_value = 1.0
        tree.links.new(light_path.outputs["Is Camera Ray"], times.inputs[1])
        tree.links.new(times.outputs[0], first)
    out = next(s for s in node.outputs if s.identifier == output)
    tree.links.new(out, background.inputs["Color"])
    theirs = cycles_pixel()
    ours, warnings = stratum_pixel(background.inputs["Color"])
    return theirs, ours, warnings


def cases() -> list[Case]:
    out: list[Case] = []
    a, b, c = (0.7, 1.3, 2.1), (0.5, 0.4, 1.7), (0.2, 0.9, 0.35)
    operations = bpy.types.ShaderNodeVectorMath.bl_rna.properties["operation"].enum_items
    for op in (item.identifier for item in operations):
        output = "Value" if op in ("DOT_PRODUCT", "DISTANCE", "LENGTH") else "Vector"
        out.append(("ShaderNodeVectorMath", output, {"operation": op},
                    {"Vector": a, "Vector_001": b, "Vector_002": c, "Scale": 0.6}))
    big = {"Vector": (123456.7, 1e9, 5.3), "Vector_001": (0.3, 3.0, 0.7),
           "Vector_002": (0.0, 0.0, 0.1)}
    for op in ("MODULO", "WRAP", "SNAP"):
        out.append(("ShaderNodeVectorMath", "Vector", {"operation": op}, big))
    out.append(("ShaderNodeVectorMath", "Vector", {"operation": "WRAP"},
                {"Vector": (-3.7, 12345.6, 0.5), "Vector_001": (0.4, 0.7, 2.0),
                 "Vector_002": (0.1, -0.3, 2.0)}))
    out.append(("ShaderNodeVectorMath", "Vector", {"operation": "DIVIDE"},
                {"Vector": (-3.7, 1.6, 0.5), "Vector_001": (0.4, 0.0, -0.3)}))
    out.append(("ShaderNodeVectorMath", "Vector", {"operation": "REFRACT"},
                {"Vector": (0.6, 0.0, -0.8), "Vector_001": (0.0, 0.0, 1.0), "Scale": 1.6}))
    if VERSION >= (5, 0, 0):
        out.append(("ShaderNodeVectorMath", "Vector", {"operation": "POWER"},
                    {"Vector": (-2.0, 2.0, 0.0), "Vector_001": (3.0, 0.5, 0.0)}))
        out.append(("ShaderNodeVectorMath", "Vector", {"operation": "SIGN"},
                    {"Vector": (-2.0, 2.0, 0.0)}))
    for interpolation in ("LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP"):
        for clamp in (False, True):
            props = {"interpolation_type": interpolation, "clamp": clamp}
            out.append(("ShaderNodeMapRange", "Result", props,
                        {"Value": 0.37, "From Min": 0.1, "From Max": 0.9, "To Min": 0.2,
                         "To Max": 1.7}))
            out.append(("ShaderNodeMapRange", "Vector", {**props, "data_type": "FLOAT_VECTOR"},
                        {"Vector": (0.37, 1.4, 0.6), "From_Min_FLOAT3": (0.1, 0.2, 0.5),
                         "From_Max_FLOAT3": (0.9, 1.0, 1.5), "To_Min_FLOAT3": (0.2, 0.1, 0.3),
                         "To_Max_FLOAT3": (1.7, 2.0, 0.9)}))
    for kind in ("MINMAX", "RANGE"):
        out.append(("ShaderNodeClamp", "Result", {"clamp_type": kind},
                    {"Value": 0.8, "Min": 0.9, "Max": 0.3}))
    for kind in ("POINT", "TEXTURE", "VECTOR", "NORMAL"):
        out.append(("ShaderNodeMapping", "Vector", {"vector_type": kind},
                    {"Vector": (0.3, 0.8, 0.5), "Location": (1.0, 0.5, 0.7),
                     "Rotation": (0.3, -0.4, 1.1), "Scale": (1.5, 0.7, 2.0)}))
    for kind in ("AXIS_ANGLE", "X_AXIS", "Y_AXIS", "Z_AXIS", "EULER_XYZ"):
        for invert in (False, True):
            out.append(("ShaderNodeVectorRotate", "Vector",
                        {"rotation_type": kind, "invert": invert},
                        {"Vector": (0.3, 0.8, 0.5), "Center": (0.2, 0.1, 0.4),
                         "Axis": (0.3, 0.5, 1.0), "Angle": 0.7, "Rotation": (0.3, -0.4, 1.1)}))
    for kind in ("POINT", "VECTOR", "NORMAL"):
        for space in ("WORLD", "OBJECT", "CAMERA"):
            out.append(("ShaderNodeVectorTransform", "Vector",
                        {"vector_type": kind, "convert_from": space, "convert_to": space},
                        {"Vector": (0.3, 0.8, 0.5)}))
    out.append(("ShaderNodeNormal", "Dot", {}, {"Normal": (0.3, 0.8, 0.5)}))
    for ior in (1.45, 2.5):
        out.append(("ShaderNodeFresnel", "Fac", {}, {"IOR": ior}))
    for blend in (0.2, 0.5, 0.8):
        out.append(("ShaderNodeLayerWeight", "Fresnel", {}, {"Blend": blend}))
    for t in (700.0, 1000.0, 1500.0, 2500.0, 4000.0, 6500.0, 9000.0, 15000.0):
        out.append(("ShaderNodeBlackbody", "Color", {}, {"Temperature": t}))
    for nm in (380.0, 420.0, 475.5, 555.0, 610.0, 700.0, 779.0):
        out.append(("ShaderNodeWavelength", "Color", {}, {"Wavelength": nm}))
    return out


def main() -> int:
    tree = setup()
    worst: dict[str, float] = {}
    for case in cases():
        theirs, ours, warnings = run_case(tree, case)
        rel = float(np.max(np.abs(theirs - ours) / np.maximum(np.abs(theirs), 1e-3)))
        name = case[0].removeprefix("ShaderNode")
        worst[name] = max(worst.get(name, 0.0), rel)
        others = [w for w in warnings if "Light Path" not in w]
        flag = "  <<< differs" if rel > 1e-3 else ""
        print(f"{name:16s} {case[2]!s:70.70s} cycles={np.round(theirs, 5)} "
              f"stratum={np.round(ours, 5)} rel={rel:.1e}{flag} {others or ''}")
    print(f"Blender {VERSION}: worst relative difference per node: "
          + ", ".join(f"{k} {v:.1e}" for k, v in worst.items()))
    return 1 if max(worst.values()) > 1e-3 else 0


if __name__ == "__main__":
    sys.exit(main())
