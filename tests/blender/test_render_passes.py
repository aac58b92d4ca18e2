"""Render passes through F12 (engine/render_passes.py): with the view layer's pass toggles on,
the multilayer EXR Blender writes holds Depth, Normal, Position, Denoising Albedo/Normal, the
object and material index, the sample count and the error pass, with the values of their closed
forms on a tilted plane.

The scene: a camera at the origin looking down −Z with a 90° field of view (lens 18 mm on a
36 mm sensor), 16 × 16 pixels, a box filter of width 1 (every sample inside its pixel), and a
plane through (0, 0, −D) whose normal (sin a, 0, cos a) is tilted 30° toward +x, Diffuse BSDF
of a known colour, covering the left half of the frame; the right half sees the world colour.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest

from conftest import engine_reports
from exr_file import read_channels
from multilayer_passes import result_name, set_multilayer_exr

SIZE = 16
DISTANCE = 3.0
TILT = math.radians(30.0)
ALBEDO = (0.2, 0.5, 0.8)
WORLD = (0.3, 0.6, 0.9)
SAMPLES = 8
OBJECT_INDEX = 6  # Object > Relations > Pass Index of the plane
MATERIAL_INDEX = 9  # Material > Settings > Pass Index of its material

def tilted_plane_scene(builder: Any) -> Any:
    scene = builder.scene
    builder.set_resolution(SIZE, SIZE)
    scene.stratum.samples = SAMPLES
    scene.stratum.filter_type = "box"
    scene.stratum.filter_width = 1.0
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.lens = 18.0
    cam.data.sensor_width = 36.0
    builder.link(cam)
    scene.camera = cam
    c, s = math.cos(TILT), math.sin(TILT)
    # Along t1 = (cos a, 0, −sin a) over [−20, 0], along y over [−20, 20]: the edge through
    # (0, 0, −D) is seen at the image centre.
    corners = [(x, y) for x, y in ((-20.0, -20.0), (0.0, -20.0), (0.0, 20.0), (-20.0, 20.0))]
    verts = [(x * c, y, -DISTANCE - x * s) for x, y in corners]
    mesh = bpy.data.meshes.new("Plane")
    mesh.from_pydata(verts, [], [(0, 1, 2, 3)])
    mesh.update()
    material = bpy.data.materials.new("Albedo")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    for node in list(nodes):
        if node.type != "OUTPUT_MATERIAL":
            nodes.remove(node)
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*ALBEDO, 1.0)
    material.node_tree.links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    material.pass_index = MATERIAL_INDEX
    plane = builder.mesh_object("Plane", data=mesh, material=material)
    plane.pass_index = OBJECT_INDEX
    builder.world(WORLD)
    layer = scene.view_layers[0]
    layer.use_pass_z = True
    layer.use_pass_normal = True
    layer.use_pass_position = True
    layer.use_pass_object_index = True
    layer.use_pass_material_index = True
    layer.use_pass_vector = True
    layer.use_pass_emit = True
    layer.use_pass_mist = True
    layer.use_pass_ambient_occlusion = True
    scene.world.mist_settings.start = 0.0
    scene.world.mist_settings.depth = 10.0
    scene.world.mist_settings.falloff = "LINEAR"
    layer.use_pass_environment = True
    layer.stratum.use_pass_denoising_data = True
    layer.stratum.use_pass_sample_count = True
    layer.stratum.use_pass_error = True
    return scene


def plane_depth(u: np.ndarray) -> np.ndarray:
    """Depth along the view axis where the ray through film point (u, ·, −1) meets the plane."""
    return DISTANCE * math.cos(TILT) / (math.cos(TILT) - u * math.sin(TILT))


def render_passes_f12(scene: Any, path: Path, monkeypatch: pytest.MonkeyPatch
                      ) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """F12 to a 32-bit multilayer EXR: its channels by name, and the passes as the engine left
    them in Blender's render result ((height, width, channels), row 0 at the bottom)."""
    from stratum.engine import render_passes

    in_result: dict[str, np.ndarray] = {}
    write = render_passes.ResultPasses.write

    def write_and_read_back(self: Any, renderer: Any, result: Any) -> None:
        write(self, renderer, result)
        for render_pass in result.layers[0].passes:
            buf = np.empty((SIZE * SIZE, render_pass.channels), dtype=np.float32)
            try:  # 3.x/4.0 take an (N, channels) array, 4.1+ a flat one
                render_pass.rect.foreach_get(buf)
            except (TypeError, ValueError, RuntimeError):
                render_pass.rect.foreach_get(buf.reshape(-1))
            in_result[render_pass.name] = buf.reshape(SIZE, SIZE, render_pass.channels)

    monkeypatch.setattr(render_passes.ResultPasses, "write", write_and_read_back)
    settings = scene.render.image_settings
    set_multilayer_exr(settings)
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    assert not engine_reports("ERROR"), engine_reports("ERROR")
    return read_channels(path), in_result


def test_f12_writes_the_passes_with_their_closed_form_values(library: Any, scene_builder: Any,
                                                             tmp_path: Path,
                                                             monkeypatch: pytest.MonkeyPatch) -> None:
    scene = tilted_plane_scene(scene_builder())
    channels, in_result = render_passes_f12(scene, tmp_path / "passes.exr", monkeypatch)
    layer = scene.view_layers[0].name

    def image(native_name: str, letters: str) -> np.ndarray:
        """(height, width, channels), row 0 at the bottom as the render result's."""
        pass_name = result_name(native_name)
        names = [f"{layer}.{pass_name}.{c}" for c in letters]
        missing = [n for n in names if n not in channels]
        assert not missing, f"{missing} not in {sorted(channels)}"
        exr = np.stack([channels[n] for n in names], axis=-1)[::-1]
        # The file holds what the engine left in the render result.
        np.testing.assert_array_equal(exr, in_result[pass_name])
        return exr

    depth = image("Depth", "Z")[..., 0]
    normal = image("Normal", "XYZ")
    position = image("Position", "XYZ")
    albedo = image("Denoising Albedo", "RGB")
    denoising_normal = image("Denoising Normal", "XYZ")
    count = image("Debug Sample Count", "X")[..., 0]
    error = image("Stratum Error", "RGB")
    emit = image("Emit", "RGB")
    env = image("Env", "RGB")
    mist = image("Mist", "Z")[..., 0]
    ao = image("AO", "RGB")
    object_index = image("IndexOB", "X")[..., 0]
    material_index = image("IndexMA", "X")[..., 0]
    vector = image("Vector", "XYZW")
    assert depth.shape == (SIZE, SIZE)

    plane, sky = np.s_[:, : SIZE // 2], np.s_[:, SIZE // 2:]
    n = np.array([math.sin(TILT), 0.0, math.cos(TILT)], dtype=np.float32)
    # Depth: sample 0 of pixel x lies in u ∈ [−1 + x/8, −1 + (x + 1)/8].
    u0 = -1.0 + np.arange(SIZE // 2) / 8.0
    assert np.all(depth[plane] >= plane_depth(u0)[None, :] * (1 - 1e-5))
    assert np.all(depth[plane] <= plane_depth(u0 + 0.125)[None, :] * (1 + 1e-5))
    np.testing.assert_array_equal(depth[sky], np.float32(1e10))
    # Position: the same sample's hit, on the plane, at that depth.
    np.testing.assert_allclose(-position[plane][..., 2], depth[plane], rtol=1e-5)
    np.testing.assert_allclose(position[plane] @ n, -DISTANCE * n[2], atol=1e-5)
    np.testing.assert_array_equal(position[sky], 0.0)
    # Normal: the face's, in world space; Denoising Normal in Cycles' camera space (z forward).
    np.testing.assert_allclose(normal[plane], np.broadcast_to(n, normal[plane].shape), atol=1e-6)
    np.testing.assert_array_equal(normal[sky], 0.0)
    np.testing.assert_allclose(denoising_normal[plane],
                               np.broadcast_to(n * [1, 1, -1], normal[plane].shape), atol=1e-6)
    # Denoising Albedo: the Diffuse colour, and the world colour where the world is seen.
    np.testing.assert_allclose(albedo[plane], np.broadcast_to(ALBEDO, albedo[plane].shape), atol=1e-6)
    np.testing.assert_allclose(albedo[sky], np.broadcast_to(WORLD, albedo[sky].shape), atol=1e-6)
    np.testing.assert_array_equal(count, float(SAMPLES))
    # Nothing emits; the world seen directly is all of Env there, and none on the plane.
    np.testing.assert_array_equal(emit, 0.0)
    np.testing.assert_allclose(env[sky], np.broadcast_to(WORLD, env[sky].shape), atol=1e-6)
    np.testing.assert_array_equal(env[plane], 0.0)
    # Mist: linear from the camera to 10 units, the world's settings; sample 0's distance
    # |Position| stands for the pixel's samples, whose distances differ by < 0.15 units across
    # a pixel here (16 px over 90°, the plane 1.9-3 units away): 0.015 of mist.
    np.testing.assert_allclose(mist[plane], np.linalg.norm(position[plane], axis=-1) / 10.0, atol=0.02)
    np.testing.assert_array_equal(mist[sky], 1.0)
    # AO: nothing but the flat plane, so every direction above it is open; none where no
    # surface is seen.
    np.testing.assert_array_equal(ao[plane], 1.0)
    np.testing.assert_array_equal(ao[sky], 0.0)
    # The index passes: the plane's object and material pass index, 0 where the world is seen.
    np.testing.assert_array_equal(object_index[plane], float(OBJECT_INDEX))
    np.testing.assert_array_equal(material_index[plane], float(MATERIAL_INDEX))
    np.testing.assert_array_equal(object_index[sky], 0.0)
    np.testing.assert_array_equal(material_index[sky], 0.0)
    # No motion vectors (engine/render_passes.py): 0, not Blender's initial 10000.
    np.testing.assert_array_equal(vector, 0.0)
    # The world seen directly is constant: its samples do not spread, its error is 0.
    np.testing.assert_array_equal(error[sky], 0.0)
    assert np.all(np.isfinite(error)) and np.all(error >= 0.0)


def test_update_render_passes_registers_what_the_toggles_ask_for(stratum_addon: Any,
                                                                 scene_builder: Any) -> None:
    from stratum.engine import render_passes

    scene = tilted_plane_scene(scene_builder())
    layer = scene.view_layers[0]
    registered: list[tuple[str, int, str, str]] = []

    class Recorder:
        def register_pass(self, scene: Any, layer: Any, name: str, channels: int, chan_id: str,
                          kind: str) -> None:
            registered.append((name, channels, chan_id, kind))

    render_passes.register_passes(Recorder(), scene, layer)
    assert [r[0] for r in registered] == [result_name(name) for name in (
        "Depth", "Mist", "Normal", "Position", "Vector", "IndexOB", "IndexMA", "Emit", "Env",
        "AO")] + ["Denoising Normal", "Denoising Albedo", "Debug Sample Count", "Stratum Error"]
    layer.use_pass_z = False
    layer.stratum.use_pass_denoising_data = False
    layer.use_pass_emit = False
    layer.use_pass_mist = False
    layer.use_pass_ambient_occlusion = False
    layer.use_pass_object_index = False
    layer.use_pass_material_index = False
    # Vector is the add-on's zeros, not a native pass.
    assert render_passes.native_setting(render_passes.enabled_passes(layer)) == (
        "Normal,Position,Env,Debug Sample Count,Stratum Error")
    # Every other pass the add-on offers is one the library holds, with the same channel count.
    held = {p.name: p.channels for p in library_passes()}
    for _, _, specs in render_passes.TOGGLES:
        for spec in specs:
            assert held.get(spec.name) == (spec.channels if spec.native else None), spec.name


def test_each_blender_toggle_registers_what_cycles_registers(stratum_addon: Any,
                                                             scene_builder: Any) -> None:
    """Name, channels and kind of the pass each of Blender's own view-layer toggles adds are
    those Cycles' add-on of the running Blender lists (its engine.list_render_passes), so a
    compositor or EXR setup made with Cycles finds them (Blender 5.0 renamed several)."""
    from stratum.engine import render_passes

    cycles_engine = pytest.importorskip("cycles.engine")
    scene = scene_builder().scene
    scene.cycles.use_denoising = False  # else Cycles lists its Noisy Image with every toggle
    layer = scene.view_layers[0]
    toggles = [(prop, specs) for owner, prop, specs in render_passes.TOGGLES
               if owner == "view_layer"]
    registered: list[tuple[str, int, str, str]] = []

    class Recorder:
        def register_pass(self, scene: Any, layer: Any, name: str, channels: int,
                          chan_id: str, kind: str) -> None:
            registered.append((name, channels, chan_id, kind))

    for prop, _ in toggles:
        setattr(layer, prop, False)
    for prop, specs in toggles:
        setattr(layer, prop, True)
        registered.clear()
        render_passes.register_passes(Recorder(), scene, layer)
        cycles = [(name, len(chan_id), chan_id, kind) for name, chan_id, kind
                  in cycles_engine.list_render_passes(scene, layer) if name != "Combined"]
        assert registered == cycles, prop
        assert len(specs) == len(cycles)
        setattr(layer, prop, False)


def library_passes() -> tuple[Any, ...]:
    from stratum import native

    try:
        return native.passes()
    except native.StratumError as exc:
        pytest.skip(f"native library not available: {exc}")


def test_the_passes_panel_shows_for_stratum(stratum_addon: Any) -> None:
    assert "STRATUM" in bpy.types.VIEWLAYER_PT_layer_passes.COMPAT_ENGINES
    assert hasattr(bpy.types, "STRATUM_VIEWLAYER_PT_passes_data")


def test_the_passes_join_those_the_denoiser_asked_for(stratum_addon: Any,
                                                      scene_builder: Any) -> None:
    """With denoising on, the denoiser has already put its guides into the native `passes`
    setting: the view layer's passes are added after them, without repeats, and the world's
    mist settings come with the Mist pass."""
    from stratum.engine import render_passes

    scene = tilted_plane_scene(scene_builder())
    added: list[str] = []

    class Recorder:
        def add_pass(self, name: str, channels: int, chan_id: str, layer: str = "") -> None:
            added.append(name)

    passes = render_passes.ResultPasses(Recorder(), scene.view_layers[0], scene.world)
    settings: dict[str, Any] = {"samples": 4, "passes": "Denoising Albedo,Denoising Normal"}
    passes.configure(settings)
    names = settings["passes"].split(",")
    assert names[:2] == ["Denoising Albedo", "Denoising Normal"]
    assert len(names) == len(set(names))
    assert set(added) - {"Vector"} <= {result_name(name) for name in names}
    assert "Vector" in added and "Vector" not in names
    assert "Depth" in names and "Mist" in names
    assert (settings["mist_start"], settings["mist_depth"], settings["mist_falloff"]) == (0.0, 10.0, 1.0)


def test_f12_writes_the_colour_passes(library: Any, scene_builder: Any, tmp_path: Path,
                                      monkeypatch: pytest.MonkeyPatch) -> None:
    """Blender's Diffuse/Glossy/Transmission Color toggles give DiffCol, GlossCol and TransCol
    (Cycles' names): the Diffuse BSDF plane's colour is all diffuse, the world adds nothing."""
    scene = tilted_plane_scene(scene_builder())
    layer = scene.view_layers[0]
    layer.use_pass_diffuse_color = True
    layer.use_pass_glossy_color = True
    layer.use_pass_transmission_color = True
    channels, in_result = render_passes_f12(scene, tmp_path / "colours.exr", monkeypatch)
    plane, sky = np.s_[:, : SIZE // 2], np.s_[:, SIZE // 2:]
    for pass_name in map(result_name, ("DiffCol", "GlossCol", "TransCol")):
        assert pass_name in in_result, f"{pass_name} not in {sorted(in_result)}"
        names = [f"{layer.name}.{pass_name}.{c}" for c in "RGB"]
        assert all(n in channels for n in names), sorted(channels)
        exr = np.stack([channels[n] for n in names], axis=-1)[::-1]
        np.testing.assert_array_equal(exr, in_result[pass_name])
    diffuse = in_result[result_name("DiffCol")]
    np.testing.assert_allclose(diffuse[plane], np.broadcast_to(ALBEDO, diffuse[plane].shape), atol=1e-6)
    np.testing.assert_array_equal(diffuse[sky], 0.0)
    np.testing.assert_array_equal(in_result[result_name("GlossCol")], 0.0)
    np.testing.assert_array_equal(in_result[result_name("TransCol")], 0.0)
