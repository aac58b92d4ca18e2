"""Pattern textures and the Image node against Cycles itself (issue 18, acceptance 1).

    .venv/bin/python scripts/measure_pattern_nodes.py [--blender blender] [--only 3.4|5.0]

For each case (a node, its settings, the output shown) Cycles renders a 2 x 2 plane seen by an
orthographic camera from above, its Emission colour driven by the node, 32 x 32 pixels, 1
sample, filter width 0.01, float EXR; once in Blender 3.4 (the `blender` binary) and once in
the bpy 5.0 wheel. The cases "generated" and "uv" render the coordinates themselves, so Stratum
evaluates each case's program (compiled by stratum.shaders.nodes from stand-in nodes with the
same settings) at exactly the coordinates Cycles shaded. Prints the worst absolute and relative
difference per case and Blender. The Cycles side runs this file inside Blender with --render-to."""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from types import SimpleNamespace
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
SIZE = 32

MAGIC = [{"node": "ShaderNodeTexMagic", "props": {"turbulence_depth": d},
          "inputs": {"Scale": 3.0, "Distortion": 1.7}, "output": "Color", "name": f"magic d{d}"}
         for d in range(11)]
GRADIENT = [{"node": "ShaderNodeTexGradient", "props": {"gradient_type": t}, "inputs": {},
             "output": "Fac", "name": f"gradient {t}"}
            for t in ("LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL", "QUADRATIC_SPHERE",
                      "RADIAL")]
BRICK_BASE = {"node": "ShaderNodeTexBrick", "output": "Color",
              "inputs": {"Color1": (0.8, 0.3, 0.1, 1), "Color2": (0.1, 0.4, 0.9, 1),
                         "Mortar": (0.05, 0.05, 0.05, 1), "Scale": 3.0, "Mortar Size": 0.05,
                         "Mortar Smooth": 0.4, "Bias": 0.1}}
WAVE_BASE = {"node": "ShaderNodeTexWave", "output": "Fac",
             "inputs": {"Scale": 2.0, "Distortion": 0.0, "Phase Offset": 0.7}}
WAVE = [
    *({**WAVE_BASE, "props": {"wave_type": "BANDS", "bands_direction": d, "wave_profile": p},
       "name": f"wave bands {d} {p}"}
      for d in ("X", "Y", "Z", "DIAGONAL") for p in ("SIN", "SAW", "TRI")),
    *({**WAVE_BASE, "props": {"wave_type": "RINGS", "rings_direction": d, "wave_profile": "SIN"},
       "name": f"wave rings {d}"} for d in ("X", "Y", "Z", "SPHERICAL")),
    *({**WAVE_BASE, "props": {"wave_type": t, "wave_profile": "SAW"},
       "inputs": {"Scale": 2.0, "Distortion": 4.0, "Detail": detail, "Detail Scale": 1.7,
                  "Detail Roughness": 0.6}, "name": f"wave {t} distorted detail {detail}"}
      for t in ("BANDS", "RINGS") for detail in (0.0, 2.5, 7.0)),
]
CASES: list[dict[str, Any]] = [
    {"node": None, "name": "generated", "output": "Generated"},
    {"node": None, "name": "uv", "output": "UV"},
    {"node": "ShaderNodeTexChecker", "props": {}, "inputs": {"Scale": 5.0}, "output": "Color",
     "name": "checker"},
    {"node": "ShaderNodeTexChecker", "props": {}, "inputs": {"Scale": 3.3}, "output": "Fac",
     "name": "checker fac"},
    *GRADIENT,
    {**BRICK_BASE, "props": {}, "name": "brick default"},
    {**BRICK_BASE, "props": {"offset": 0.3, "offset_frequency": 3, "squash": 1.6,
                             "squash_frequency": 2}, "name": "brick offset squash"},
    {**BRICK_BASE, "props": {}, "output": "Fac", "name": "brick fac"},
    {**BRICK_BASE, "props": {}, "output": "Fac", "name": "brick smooth mortar fac",
     "inputs": {**BRICK_BASE["inputs"], "Mortar Size": 0.1, "Mortar Smooth": 1.0, "Scale": 2.93}},
    *MAGIC,
    *WAVE,
    {"node": "ShaderNodeTexImage", "props": {"interpolation": "Closest"}, "output": "Color",
     "inputs": {}, "name": "image closest"},
    {"node": "ShaderNodeTexImage", "props": {"interpolation": "Linear"}, "output": "Color",
     "inputs": {}, "name": "image linear"},
    {"node": "ShaderNodeTexImage", "props": {"interpolation": "Linear"}, "output": "Alpha",
     "inputs": {}, "name": "image alpha"},
    # Alpha also drives the Emission strength, so Cycles divides the colour by alpha (mode 2):
    # the pixel is that colour times alpha.
    {"node": "ShaderNodeTexImage", "props": {"interpolation": "Linear"}, "output": "Color",
     "inputs": {}, "name": "image colour, alpha linked", "alpha_strength": True},
]


def image_pixels() -> list[float]:
    """A 5 x 4 RGBA float image, alpha varying, colour premultiplied (rows bottom to top)."""
    px = []
    for j in range(4):
        for i in range(5):
            a = 1.0 if (i + j) % 3 else 0.35 + 0.1 * i
            px += [(0.1 + 0.2 * i) * a, (0.9 - 0.2 * j) * a, (0.3 + 0.05 * (i * j % 4)) * a, a]
    return px


def write_image(path: Path) -> None:
    """The image as an OpenEXR file (associated alpha, as EXR is), written by Blender."""
    import bpy

    img = bpy.data.images.new("source", 5, 4, alpha=True, float_buffer=True)
    img.pixels = image_pixels()
    img.filepath_raw = str(path)
    img.file_format = "OPEN_EXR"
    img.save()
    bpy.data.images.remove(img)


def node_sockets(bl_idname: str) -> dict[str, Any]:
    """The node's sockets (identifier, type, default) and properties in this Blender."""
    import bpy

    tree = bpy.data.node_groups.new("probe", "ShaderNodeTree")
    node = tree.nodes.new(bl_idname)

    def default(s: Any) -> Any:
        v = getattr(s, "default_value", 0.0)
        return list(v) if hasattr(v, "__len__") else v

    props = {p: getattr(node, p) for p in ("gradient_type", "offset", "offset_frequency",
                                             "squash", "squash_frequency", "turbulence_depth",
                                             "projection", "interpolation", "extension",
                                             "wave_type", "bands_direction", "rings_direction",
                                             "wave_profile")
             if hasattr(node, p)}
    found = {"in": [(s.identifier, s.type, default(s)) for s in node.inputs],
             "out": [(s.identifier, s.type, 0.0) for s in node.outputs], "props": props}
    bpy.data.node_groups.remove(tree)
    return found


# ---- the Cycles side (inside Blender) ---------------------------------------------------------

def render_cycles(out: Path, image_path: Path) -> None:
    import bpy
    import numpy as np

    bpy.ops.wm.read_factory_settings(use_empty=True)
    if not image_path.exists():
        write_image(image_path)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 1
    scene.cycles.device = "CPU"
    if hasattr(scene.cycles, "use_denoising"):
        scene.cycles.use_denoising = False
    scene.cycles.filter_width = 0.01
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    scene.render.film_transparent = False
    bpy.ops.mesh.primitive_plane_add(size=2.0, location=(0, 0, 0))
    plane = bpy.context.object
    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 2.0
    cam = bpy.data.objects.new("cam", cam_data)
    cam.location = (0, 0, 1)
    scene.collection.objects.link(cam)
    scene.camera = cam
    world = bpy.data.worlds.new("w")
    world.color = (0, 0, 0)
    scene.world = world
    image = bpy.data.images.load(str(image_path))
    image.colorspace_settings.name = "Linear" if bpy.app.version < (4, 0, 0) else \
        "Linear Rec.709"
    results: dict[str, Any] = {}
    for case in CASES:
        mat = bpy.data.materials.new(case["name"])
        if bpy.app.version < (5, 0, 0):  # 5.0 materials always have their node tree
            mat.use_nodes = True
        nt = mat.node_tree
        nt.nodes.clear()
        out_node = nt.nodes.new("ShaderNodeOutputMaterial")
        emission = nt.nodes.new("ShaderNodeEmission")
        emission.inputs["Strength"].default_value = 1.0
        nt.links.new(emission.outputs[0], out_node.inputs["Surface"])
        if case["node"] is None:
            coord = nt.nodes.new("ShaderNodeTexCoord")
            nt.links.new(coord.outputs[case["output"]], emission.inputs["Color"])
        else:
            node = nt.nodes.new(case["node"])
            for key, value in case.get("props", {}).items():
                setattr(node, key, value)
            for key, value in case.get("inputs", {}).items():
                node.inputs[key].default_value = value
            if case["node"] == "ShaderNodeTexImage":
                node.image = image
            socket = next(s for s in node.outputs if s.identifier == case["output"])
            nt.links.new(socket, emission.inputs["Color"])
            if case.get("alpha_strength"):
                nt.links.new(node.outputs["Alpha"], emission.inputs["Strength"])
        plane.data.materials.clear()
        plane.data.materials.append(mat)
        path = Path(tempfile.mkdtemp()) / "r.exr"
        scene.render.filepath = str(path)
        bpy.ops.render.render(write_still=True)
        img = bpy.data.images.load(str(path))
        px = np.empty(SIZE * SIZE * 4, dtype=np.float32)
        img.pixels.foreach_get(px)
        results[case["name"]] = px.reshape(SIZE, SIZE, 4)[..., :3].tolist()
        bpy.data.images.remove(img)
    sockets = {n: node_sockets(n) for n in {c["node"] for c in CASES if c["node"]}}
    out.write_text(json.dumps({"version": list(bpy.app.version), "results": results,
                               "sockets": sockets}))


# ---- the Stratum side -------------------------------------------------------------------------

class _Socket:
    def __init__(self, identifier: str, type_: str, value: Any) -> None:
        self.identifier = self.name = identifier
        self.type = type_
        self.default_value = value
        self.links: list[Any] = []
        self.enabled = True

    @property
    def is_linked(self) -> bool:
        return bool(self.links)


def _stand_in(case: dict[str, Any], sockets: dict[str, Any]) -> Any:
    """A node with Blender's sockets (read from the real node of this Blender)."""
    inputs = [_Socket(k, t, tuple(v) if isinstance(v, list) else v) for k, t, v in sockets["in"]]
    for s in inputs:
        if s.identifier in case.get("inputs", {}):
            s.default_value = case["inputs"][s.identifier]
    outputs = [_Socket(k, t, 0.0) for k, t, _ in sockets["out"]]
    props = {**sockets["props"], **case.get("props", {})}
    node = SimpleNamespace(bl_idname=case["node"], name=case["name"], inputs=inputs,
                           outputs=outputs, mute=False, **props)
    if case["node"] == "ShaderNodeTexImage":
        node.image = SimpleNamespace(name="img", alpha_mode="STRAIGHT", colorspace_settings=
                                     SimpleNamespace(name="Linear", is_data=False))
        if case["output"] == "Alpha" or case.get("alpha_strength"):
            next(o for o in outputs if o.identifier == "Alpha").links.append(object())
    return node


def stratum_values(case: dict[str, Any], version: tuple[int, int, int], coords: dict[str, Any],
                   sockets: dict[str, Any], image_path: Path) -> Any:
    import numpy as np
    from stratum import native
    from stratum.shaders.nodes import NodeCompiler

    warnings: list[str] = []
    c = NodeCompiler(version, lambda n, m: warnings.append(m))
    node = _stand_in(case, sockets[case["node"]])
    target = _Socket("Color", "RGBA", (0, 0, 0, 1))
    out = next(o for o in node.outputs if o.identifier == case["output"])
    target.links = [SimpleNamespace(from_node=node, from_socket=out, is_muted=False,
                                    is_valid=True)]
    reg = c.value(target, "color")
    alpha = None
    if case.get("alpha_strength"):
        alpha_out = next(o for o in node.outputs if o.identifier == "Alpha")
        alpha = c.output(node, alpha_out)
    if warnings:
        raise SystemExit(f"{case['name']}: {warnings}")
    scene = native.Scene()
    if c.images:
        scene.add_texture(native.Texture(
            path=str(image_path), color_space="Non-Color",
            interpolation=native.TEXTURE_CLOSEST if case["props"]["interpolation"] == "Closest"
            else native.TEXTURE_LINEAR, extension=native.TEXTURE_REPEAT))
    pid = scene.add_shader_program(c.builder.program)
    result = np.zeros((SIZE, SIZE, 3), dtype=np.float32)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    for j in range(SIZE):
        for i in range(SIZE):
            inputs[15:18] = coords["generated"][j][i]
            inputs[12:15] = coords["uv"][j][i]
            inputs[14] = 0.0
            result[j, i] = scene.evaluate_program(pid, inputs, reg, 3)
            if alpha is not None:
                result[j, i] *= scene.evaluate_program(pid, inputs, alpha, 1)[0]
    return result


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--render-to", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--image", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--only", choices=("3.4", "5.0"))
    parser.add_argument("--work", type=Path, help="keep (and reuse) Cycles' renders here")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else None)
    if args.render_to:
        render_cycles(args.render_to, args.image)
        return
    import numpy as np

    work = args.work or Path(tempfile.mkdtemp(prefix="stratum_patterns_"))
    work.mkdir(parents=True, exist_ok=True)
    image_path = work / "image.exr"
    runs = {"3.4": [args.blender, "-b", "--factory-startup", "-noaudio", "--python", __file__,
                    "--"],
            "5.0": [sys.executable, __file__]}
    for label, command in runs.items():
        if args.only and args.only != label:
            continue
        out = work / f"cycles_{label}.json"
        if not out.exists():
            subprocess.run([*command, "--render-to", str(out), "--image", str(image_path)],
                           check=True, stdout=subprocess.DEVNULL,
                           env={**os.environ, "PYTHONPATH": ""})
        data = json.loads(out.read_text())
        version = tuple(data["version"])
        res = {k: np.array(v, dtype=np.float32) for k, v in data["results"].items()}
        coords = {"generated": res["generated"], "uv": res["uv"]}
        print(f"Blender {'.'.join(map(str, version))}: worst |difference| (and relative) per case")
        for case in CASES:
            if case["node"] is None:
                continue
            mine = stratum_values(case, version, coords, data["sockets"], image_path)
            theirs = res[case["name"]]
            diff = np.abs(mine - theirs)
            rel = diff / np.maximum(np.abs(theirs), 1e-3)
            worst = np.unravel_index(np.argmax(diff), diff.shape)
            print(f"  {case['name']:28s} abs {diff.max():.2e}  rel {rel.max():.2e}  "
                  f"pixels > 1e-3 rel: {int((rel > 1e-3).any(axis=2).sum())}  at {worst[:2]}")


if __name__ == "__main__":
    main()
