"""Invalid material, light and world values (issue 12, point 3): each is replaced by Cycles'
own clamp (stratum.shaders.fallbacks; docs/invalid_values.md) with one WARNING naming the material /
light / world and the socket or field, and the render finishes with finite pixels.

Every value set here is reachable from Blender's Python (and so from files): measured in 3.4.1
and 5.0.1, RNA keeps NaN in sockets, light and world properties, keeps socket values outside
their UI range (-1, 3e38), stores +Inf as FLT_MAX in sockets and keeps it in Light.energy.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest
from stratum import native
from stratum.export.sync import export_scene
from stratum.shaders.fallbacks import FLT_MAX

from conftest import engine_reports, render_still

NAN = float("nan")
V4 = bpy.app.version >= (4, 0, 0)
EMISSION = "Emission Color" if V4 else "Emission"
SPECULAR = "Specular IOR Level" if V4 else "Specular"


def _principled(name: str, **sockets: Any) -> Any:
    mat = bpy.data.materials.new(name)
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    node = mat.node_tree.nodes["Principled BSDF"]
    for socket, value in sockets.items():
        target = node.inputs[socket]
        target.default_value = (value, value, value, 1.0) if isinstance(
            target.default_value, bpy.types.bpy_prop_array) else value
    return mat


def _warnings(summary: Any, who: str) -> list[str]:
    return [w for w in summary.warnings if who in w]


def _only_material(recording_scene: Any) -> Any:
    (material,) = recording_scene.materials
    if isinstance(material, list):  # a closure material: (weight, closure) pairs
        (_weight, material), = [(w, m) for w, m in material if max(w) > 0.0]
    return material


@pytest.mark.parametrize(("socket", "value", "field", "expected"), [
    ("Base Color", NAN, "base_color", (0.0, 0.0, 0.0)),  # Cycles: max(NaN, 0) = 0
    ("Roughness", NAN, "roughness", 0.0),  # saturatef(NaN) = 0
    ("Roughness", -1.0, "roughness", 0.0),
    ("Metallic", 3e38, "metallic", 1.0),
    ("IOR", 0.0, "ior", 1e-5),  # fmaxf(ior, 1e-5f)
    ("IOR", NAN, "ior", 1e-5),
    (SPECULAR, -1.0, "specular", 0.0),
    ("Emission Strength", NAN, "emission", (0.0, 0.0, 0.0)),
    (EMISSION, NAN, "emission", (0.0, 0.0, 0.0)),
])
def test_principled_socket_falls_back_with_one_warning(scene_builder: Any, recording_scene: Any,
                                                       socket: str, value: float, field: str,
                                                       expected: Any) -> None:
    b = scene_builder().basic()
    extra = {EMISSION: 1.0, "Emission Strength": 1.0} if field == "emission" else {}
    b.scene.objects["Cube"].data.materials.append(_principled("Odd", **(extra | {socket: value})))
    summary = export_scene(b.depsgraph(), recording_scene)
    warnings = _warnings(summary, "Material 'Odd'")
    assert len(warnings) == 1, summary.warnings
    assert f"'{socket}' of 'Principled BSDF'" in warnings[0]
    assert getattr(_only_material(recording_scene), field) == pytest.approx(expected)


def test_nan_alpha_is_fully_transparent_as_in_cycles(scene_builder: Any,
                                                     recording_scene: Any) -> None:
    b = scene_builder().basic()
    b.scene.objects["Cube"].data.materials.append(_principled("Ghost", Alpha=NAN))
    summary = export_scene(b.depsgraph(), recording_scene)
    assert len(_warnings(summary, "'Alpha' of 'Principled BSDF'")) == 1
    assert _only_material(recording_scene).model == native.closure_model("transparent")


def test_one_warning_per_material_and_socket(scene_builder: Any, recording_scene: Any) -> None:
    """Two bad sockets: two warnings; a second object with the material adds none."""
    b = scene_builder().basic()
    mat = _principled("Twice", Roughness=NAN, Metallic=NAN)
    b.scene.objects["Cube"].data.materials.append(mat)
    b.mesh_object("Other", location=(3.0, 0.0, 0.0), material=mat)
    summary = export_scene(b.depsgraph(), recording_scene)
    warnings = _warnings(summary, "Material 'Twice'")
    assert len(warnings) == 2 and sum("'Roughness'" in w for w in warnings) == 1
    assert len(recording_scene.materials) == 1


def test_emission_up_to_the_largest_float(scene_builder: Any, recording_scene: Any) -> None:
    """3e38 is a valid radiance (the native side keeps it finite): no warning. Colour x
    strength beyond FLT_MAX is limited to it, with a warning."""
    b = scene_builder().basic()
    b.scene.objects["Cube"].data.materials.append(
        _principled("Bright", **{EMISSION: 1.0, "Emission Strength": 3e38}))
    b.mesh_object("Other", location=(3.0, 0.0, 0.0),
                  material=_principled("Brighter", **{EMISSION: 2.0, "Emission Strength": 3e38}))
    summary = export_scene(b.depsgraph(), recording_scene)
    assert not _warnings(summary, "'Bright'")
    assert len(_warnings(summary, "'Brighter'")) == 1
    bright, brighter = recording_scene.materials
    assert bright.emission == pytest.approx((3e38,) * 3, rel=1e-6)
    assert brighter.emission == (FLT_MAX,) * 3


def _nodes_material(name: str) -> tuple[Any, Any, Any]:
    mat = bpy.data.materials.new(name)
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    return mat, nt, nt.nodes["Material Output"]


def test_glass_ior_mix_fac_and_emission_strength(scene_builder: Any,
                                                 recording_scene: Any) -> None:
    b = scene_builder().basic()
    mat, nt, out = _nodes_material("Mixed")
    mix = nt.nodes.new("ShaderNodeMixShader")
    glass = nt.nodes.new("ShaderNodeBsdfGlass")
    glow = nt.nodes.new("ShaderNodeEmission")
    mix.inputs[0].default_value = NAN  # saturatef(NaN) = 0: all weight on the first input
    glass.inputs["IOR"].default_value = NAN
    glow.inputs["Strength"].default_value = -4.0
    nt.links.new(glass.outputs[0], mix.inputs[1])
    nt.links.new(glow.outputs[0], mix.inputs[2])
    nt.links.new(mix.outputs[0], out.inputs["Surface"])
    b.scene.objects["Cube"].data.materials.append(mat)
    summary = export_scene(b.depsgraph(), recording_scene)
    warnings = _warnings(summary, "Material 'Mixed'")
    assert len(warnings) == 3, warnings
    for words in (f"of '{mix.name}'", f"'IOR' of '{glass.name}'", f"'Strength' of '{glow.name}'"):
        assert sum(words in w for w in warnings) == 1, (words, warnings)
    material = _only_material(recording_scene)
    assert material.model == native.closure_model("glass") and material.ior == pytest.approx(1e-5)


def test_volume_only_material_is_a_transparent_boundary(scene_builder: Any,
                                                        recording_scene: Any) -> None:
    """Cycles: a material with only a Volume output has a transparent surface (SD_HAS_ONLY_
    VOLUME); Stratum renders no volume and says so, instead of "no shader connected"."""
    b = scene_builder().basic()
    mat, nt, out = _nodes_material("Fog")
    nt.links.new(nt.nodes.new("ShaderNodeVolumeScatter").outputs[0], out.inputs["Volume"])
    b.scene.objects["Cube"].data.materials.append(mat)
    summary = export_scene(b.depsgraph(), recording_scene)
    (warning,) = _warnings(summary, "Material 'Fog'")
    assert "Volume" in warning and "transparent" in warning and "no shader" not in warning
    material = _only_material(recording_scene)
    assert material.model == native.closure_model("transparent") and material.base_color == (1, 1, 1)


def test_volume_shader_on_the_surface_adds_nothing(scene_builder: Any,
                                                   recording_scene: Any) -> None:
    b = scene_builder().basic()
    mat, nt, out = _nodes_material("Misplaced")
    scatter = nt.nodes.new("ShaderNodeVolumeScatter")
    nt.links.new(scatter.outputs[0], out.inputs["Surface"])
    b.scene.objects["Cube"].data.materials.append(mat)
    summary = export_scene(b.depsgraph(), recording_scene)
    (warning,) = _warnings(summary, "Material 'Misplaced'")
    assert scatter.name in warning and "surface" in warning
    assert _only_material(recording_scene).base_color == (0.0, 0.0, 0.0)  # Cycles: black


@pytest.mark.skipif(bpy.app.version >= (5, 0, 0), reason="5.0 always shades with nodes")
def test_material_without_nodes_nan_colour(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()
    mat = bpy.data.materials.new("Plain")
    mat.use_nodes = False
    mat.diffuse_color = (NAN, 0.5, 0.5, 1.0)
    b.scene.objects["Cube"].data.materials.append(mat)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert len(_warnings(summary, "Material 'Plain': 'Color'")) == 1
    assert _only_material(recording_scene).base_color == (0.0, 0.5, 0.5)


LIGHT_CASES = [
    ("POINT", "energy", NAN, "not a number"),
    ("POINT", "energy", float("inf"), "infinite"),  # Light.energy keeps +Inf
    ("POINT", "energy", -10.0, "negative"),
    ("POINT", "shadow_soft_size", NAN, "not a number"),
    ("SPOT", "spot_size", NAN, "not a number"),
    ("SPOT", "spot_blend", NAN, "not a number"),
    ("SUN", "angle", NAN, "not a number"),
    ("AREA", "size", NAN, "not a number"),
    ("AREA", "spread", NAN, "not a number"),
    ("POINT", "exposure", NAN, "not a number"),
]


@pytest.mark.parametrize(("kind", "field", "value", "words"), LIGHT_CASES)
def test_unrenderable_light_is_skipped_naming_the_field(scene_builder: Any, recording_scene: Any,
                                                        kind: str, field: str, value: float,
                                                        words: str) -> None:
    """Cycles' samples of such a light are all non-finite and its film drops them: the light
    renders as nothing there too."""
    b = scene_builder().basic()
    light = bpy.data.lights.new("Odd", kind)
    if not hasattr(light, field):
        pytest.skip(f"Light.{field} does not exist in Blender {bpy.app.version_string}")
    setattr(light, field, value)
    b.link(bpy.data.objects.new("OddLamp", light))
    summary = export_scene(b.depsgraph(), recording_scene)
    (warning,) = _warnings(summary, "Light 'OddLamp'")
    assert f"'{field}'" in warning and words in warning and "skipped" in warning
    assert len(recording_scene.lights) == 1  # the scene's own point light only


def test_light_colour_and_power_limits(scene_builder: Any, recording_scene: Any) -> None:
    b = scene_builder().basic()
    tinted = bpy.data.lights.new("Tinted", "POINT")
    tinted.color = (NAN, 1.0, 1.0)
    b.link(bpy.data.objects.new("TintedLamp", tinted))
    huge = bpy.data.lights.new("Huge", "SUN")
    huge.energy = 3e38
    b.link(bpy.data.objects.new("HugeSun", huge))
    summary = export_scene(b.depsgraph(), recording_scene)
    (warning,) = _warnings(summary, "Light 'TintedLamp'")
    assert "'color'" in warning
    assert not _warnings(summary, "HugeSun")  # a valid float power: the core keeps it finite
    points = sorted(lamp.color for lamp in recording_scene.lights
                    if lamp.type == native.light_type("point"))
    assert points == [(0.0, 1.0, 1.0), (1.0, 1.0, 1.0)]  # the tinted lamp and the scene's
    (sun,) = [lamp for lamp in recording_scene.lights if lamp.type == native.light_type("sun")]
    assert sun.strength == pytest.approx(3e38, rel=1e-6)


def _background(b: Any) -> Any:
    world = b.scene.world or b.world()
    if bpy.app.version < (5, 0, 0):
        world.use_nodes = True
    return world, world.node_tree.nodes["Background"]


@pytest.mark.parametrize(("socket", "value"), [("Color", NAN), ("Strength", NAN),
                                               ("Strength", -2.0)])
def test_world_background_value(scene_builder: Any, recording_scene: Any, socket: str,
                                value: float) -> None:
    b = scene_builder().basic()
    world, background = _background(b)
    background.inputs["Color"].default_value = (0.2, 0.3, 0.4, 1.0)
    target = background.inputs[socket]
    target.default_value = (value, 0.3, 0.4, 1.0) if socket == "Color" else value
    summary = export_scene(b.depsgraph(), recording_scene)
    (warning,) = _warnings(summary, f"World '{world.name}'")
    assert f"'{socket}' of 'Background'" in warning
    expected = (0.0, 0.3, 0.4) if socket == "Color" else (0.0, 0.0, 0.0)
    assert recording_scene.background == pytest.approx(expected)


def test_environment_pixels_nan_inf_negative_are_zero(scene_builder: Any,
                                                      recording_scene: Any) -> None:
    b = scene_builder().basic()
    world, background = _background(b)
    image = bpy.data.images.new("Sky", 4, 2, float_buffer=True)
    # (Setting the colour space regenerates a generated image's pixels: first.)
    image.colorspace_settings.name = "Linear" if bpy.app.version < (4, 0, 0) else \
        "Linear Rec.709"
    pixels = np.full((2, 4, 4), 0.5, dtype=np.float32)
    pixels[0, 0, 0], pixels[0, 1, 1], pixels[1, 2, 2] = NAN, np.inf, -3.0
    image.pixels.foreach_set(pixels.reshape(-1))
    env = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
    env.image = image
    world.node_tree.links.new(env.outputs["Color"], background.inputs["Color"])
    summary = export_scene(b.depsgraph(), recording_scene)
    (warning,) = _warnings(summary, "'Sky'")
    assert f"World '{world.name}'" in warning and "3 NaN, infinite or negative" in warning
    rgb = recording_scene.environment["rgb"]
    assert np.isfinite(rgb).all() and (rgb >= 0).all() and np.count_nonzero(rgb == 0) == 3


def _small(b: Any) -> Any:
    b.set_resolution(16, 16)
    b.scene.stratum.samples = 2
    return b


def test_invalid_values_render_finite_with_warnings(library: Any, scene_builder: Any,
                                                    tmp_path: Path) -> None:
    """End to end: a NaN material, a NaN light and a NaN world colour render without an ERROR,
    with warnings naming them, and every pixel is finite."""
    b = _small(scene_builder().basic())
    b.scene.objects["Cube"].data.materials.append(
        _principled("Odd", Roughness=NAN, **{"Base Color": NAN}))
    b.mesh_object("Lamp", location=(0.0, 0.0, 3.0)).data.materials.append(
        _principled("Glow", **{EMISSION: 1.0, "Emission Strength": 50.0}))
    b.scene.objects["Light"].data.energy = NAN
    _background(b)[1].inputs["Color"].default_value = (NAN, 0.1, 0.1, 1.0)
    pixels = render_still(b.scene, tmp_path / "invalid.exr")
    assert not engine_reports("ERROR")
    warnings = engine_reports("WARNING")
    for who in ("Material 'Odd'", "Light 'Light'", f"World '{b.scene.world.name}'"):
        assert any(who in w for w in warnings), (who, warnings)
    assert pixels is not None and np.isfinite(pixels).all() and pixels[..., :3].max() > 0.0


def test_emission_at_the_largest_float_renders_finite(library: Any, scene_builder: Any,
                                                      tmp_path: Path) -> None:
    """Needs the native side's FLT_MAX-safe emission (issue 12 point 1): an emitter of 3e38
    gives finite, non-zero pixels and no ERROR."""
    b = _small(scene_builder().basic())
    b.scene.objects["Cube"].data.materials.append(
        _principled("Glow", **{EMISSION: 1.0, "Emission Strength": 3e38}))
    pixels = render_still(b.scene, tmp_path / "flt_max.exr")
    assert not engine_reports("ERROR")
    assert pixels is not None and np.isfinite(pixels).all() and pixels[..., :3].max() > 0.0
