"""Image colour spaces the native OpenColorIO (Debian's 2.1.2) cannot convert because it cannot
read the Blender's config (a profile newer than its own: 5.0's 2.4; 3.4's and 4.2/4.5's profile
2 it reads): converted by the exporter with Blender's own PyOpenColorIO, to the values
PyOpenColorIO gives; sRGB images, and every image of a config the native side reads, stay on the
native path (file or packed bytes read by the native side, converted there)."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest
from stratum import native
from stratum.export.color_management import blender_pyopencolorio, native_converts
from stratum.export.images import SCENE_LINEAR_BUILTIN, blender_ocio_config
from stratum.export.sync import export_scene

# Colour-space values saved to 8 bits: the file holds floor(v * 255 + 0.5) / 255.
TEXELS = np.array([[0.5, 0.25, 0.1, 1.0], [0.9, 0.6, 0.3, 1.0]], dtype=np.float32)
# ACEScg (AP1 primaries, D60) to linear Rec.709 (D65), rows give R, G, B (ACES TB-2014-004
# primaries with a Bradford adaptation; the matrix Blender's config builds from them).
AP1_TO_REC709 = np.array([[1.70505, -0.62179, -0.08326],
                          [-0.13026, 1.14080, -0.01055],
                          [-0.02400, -0.12897, 1.15297]])


def _saved_image(tmp_path: Path, name: str, float_buffer: bool = False) -> Any:
    """A 2x1 image saved to disk (PNG for bytes, EXR for floats) and loaded back from it."""
    image = bpy.data.images.new(name, 2, 1, alpha=True, float_buffer=float_buffer)
    image.pixels.foreach_set(TEXELS.ravel())
    ext, fmt = ("exr", "OPEN_EXR") if float_buffer else ("png", "PNG")
    image.filepath_raw = str(tmp_path / f"{name}.{ext}")
    image.file_format = fmt
    image.save()
    bpy.data.images.remove(image)
    return bpy.data.images.load(str(tmp_path / f"{name}.{ext}"), check_existing=False)


def _file_values(image: Any) -> np.ndarray:
    """What the image's file holds: Image.pixels of a fresh copy read as Non-Color (Blender
    converts nothing for data)."""
    raw = bpy.data.images.load(image.filepath, check_existing=False)
    raw.colorspace_settings.name = "Non-Color"
    buf = np.empty(len(raw.pixels), dtype=np.float32)
    raw.pixels.foreach_get(buf)
    bpy.data.images.remove(raw)
    return buf.reshape(-1, 4)


def _textured_cube(b: Any, image: Any) -> None:
    mat = bpy.data.materials.new(image.name)
    if bpy.app.version < (5, 0, 0):
        mat.use_nodes = True
    nt = mat.node_tree
    for node in list(nt.nodes):
        if node.bl_idname != "ShaderNodeOutputMaterial":
            nt.nodes.remove(node)
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    tex = nt.nodes.new("ShaderNodeTexImage")
    tex.image = image
    nt.links.new(tex.outputs["Color"], diffuse.inputs["Color"])
    nt.links.new(diffuse.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    ob = b.mesh_object(image.name, material=mat)
    layer = ob.data.uv_layers.new(name="UVMap")
    layer.data.foreach_set("uv", np.full(len(ob.data.loops) * 2, 0.25, dtype=np.float32))


def _pyopencolorio_to_scene_linear(values: np.ndarray, color_space: str) -> np.ndarray:
    ocio = blender_pyopencolorio()
    config = ocio.Config.CreateFromFile(blender_ocio_config())
    cpu = config.getProcessor(color_space, ocio.ROLE_SCENE_LINEAR).getDefaultCPUProcessor()
    out = np.ascontiguousarray(values, dtype=np.float32).copy()
    cpu.applyRGBA(out.reshape(-1))
    return out


def _srgb_to_linear(v: np.ndarray) -> np.ndarray:
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def _requires_blender_ocio() -> None:
    """Skips where the native side reads the Blender's config (Filmic Log is in every config
    and not built in): the exporter converts nothing there (3.4, 4.2, 4.5)."""
    if native_converts(blender_ocio_config(), "Filmic Log"):
        pytest.skip("the native OpenColorIO reads this Blender's config itself")
    assert blender_pyopencolorio() is not None, "a config the native side cannot read, and no " \
        "PyOpenColorIO to convert with"


def _config_profile(config: str) -> tuple[int, int]:
    """The config's ocio_profile_version as (major, minor): "2" is (2, 0)."""
    found = re.search(r"^ocio_profile_version:\s*(\d+)(?:\.(\d+))?", Path(config).read_text(),
                      re.MULTILINE)
    assert found, f"no ocio_profile_version in {config}"
    return int(found[1]), int(found[2] or 0)


def _native_ocio_version(tmp_path: Path) -> tuple[int, int]:
    """The native library's OpenColorIO (major, minor), as it names itself when it refuses a
    config of a profile no OpenColorIO reads."""
    future = tmp_path / "future.ocio"
    future.write_text("ocio_profile_version: 99\n")
    probe = native.Texture(pixels=np.full((1, 1, 4), 0.5, dtype=np.float32),
                           color_space="no such space", ocio_config=str(future))
    with native.Scene() as scratch, pytest.raises(native.StratumError) as refused:
        scratch.add_texture(probe)
    found = re.search(r"OpenColorIO (\d+)\.(\d+)", str(refused.value))
    assert found, str(refused.value)
    return int(found[1]), int(found[2])


def _native_reads(config: str, tmp_path: Path) -> bool:
    """Whether the native OpenColorIO reads the config: OpenColorIO reads the profiles up to its
    own version."""
    return _config_profile(config) <= _native_ocio_version(tmp_path)


def test_native_side_converts_builtin_names_and_the_spaces_of_a_config_it_reads(
        library: Any, tmp_path: Path) -> None:
    config = blender_ocio_config()
    assert native_converts(config, "sRGB")
    assert native_converts(config, "Non-Color")
    # Filmic Log is in every config Stratum meets (3.4 to 5.0), ACEScg from 4.0 on: not built
    # in, so the native side converts them exactly when it reads the config (5.0's profile 2.4
    # is beyond Debian's OpenColorIO 2.1; 3.4's and 4.2/4.5's profile 2 is not).
    reads = _native_reads(config, tmp_path)
    assert native_converts(config, "Filmic Log") == reads
    if "ACEScg" in {s.identifier for s in bpy.types.ColorManagedInputColorspaceSettings
                    .bl_rna.properties["name"].enum_items}:
        assert native_converts(config, "ACEScg") == reads


def test_acescg_byte_image_is_converted_with_blenders_opencolorio(
        library: Any, scene_builder: Any, recording_scene: Any, tmp_path: Path) -> None:
    _requires_blender_ocio()
    b = scene_builder()
    b.camera()
    image = _saved_image(tmp_path, "Acescg")
    image.colorspace_settings.name = "ACEScg"
    _textured_cube(b, image)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    (texture,) = recording_scene.textures
    assert texture.path is None and texture.file_data is None
    assert texture.color_space == SCENE_LINEAR_BUILTIN
    file_values = _file_values(image)
    np.testing.assert_allclose(file_values, np.floor(TEXELS * 255 + 0.5) / 255, atol=1e-6)
    expected = _pyopencolorio_to_scene_linear(file_values, "ACEScg")
    sent = texture.pixels.reshape(-1, 4)
    # The same float32 processor on the same inputs: equal to float32 rounding.
    np.testing.assert_allclose(sent, expected, rtol=0, atol=1e-6)
    # Independently: the published AP1 -> Rec.709 matrix (Bradford D60 -> D65, 5 decimals, so
    # |error| <= 0.5e-5 * sum(rgb) < 1e-5): ACEScg (0.50196, 0.25098, 0.10196) -> (0.69132,
    # 0.21986, 0.07314), as measured with PyOpenColorIO 2.4.2 in Blender 5.0.1.
    np.testing.assert_allclose(sent[:, :3], file_values[:, :3] @ AP1_TO_REC709.T, atol=2e-5)
    # ... and not what sRGB decoding of the same bytes gives (0.21586, 0.05127, 0.01033).
    assert np.abs(sent[:, :3] - _srgb_to_linear(file_values[:, :3])).max() > 0.1
    np.testing.assert_array_equal(sent[:, 3], file_values[:, 3])  # alpha is not converted


def test_acescg_image_exports_to_a_native_scene_without_warnings(
        library: Any, scene_builder: Any, tmp_path: Path) -> None:
    _requires_blender_ocio()
    b = scene_builder()
    b.camera()
    byte_image = _saved_image(tmp_path, "AcesByte")
    byte_image.colorspace_settings.name = "ACEScg"
    packed = _saved_image(tmp_path, "AgxPacked")
    packed.colorspace_settings.name = "AgX Log"
    packed.pack()
    for image in (byte_image, packed):
        _textured_cube(b, image)
    with library.Scene() as scene:
        summary = export_scene(b.depsgraph(), scene)
    assert summary.warnings == []
    assert summary.textures == 2


def test_acescg_float_image_is_sent_as_blender_made_it_scene_linear(
        library: Any, scene_builder: Any, recording_scene: Any, tmp_path: Path) -> None:
    _requires_blender_ocio()
    b = scene_builder()
    b.camera()
    image = _saved_image(tmp_path, "AcesFloat", float_buffer=True)
    image.colorspace_settings.name = "ACEScg"
    _textured_cube(b, image)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    (texture,) = recording_scene.textures
    assert texture.path is None and texture.color_space == "Non-Color"
    # Blender converted the EXR's values to scene linear when it loaded it (opaque texels,
    # so premultiplication changes nothing); that is PyOpenColorIO's ACEScg conversion.
    expected = _pyopencolorio_to_scene_linear(_file_values(image), "ACEScg")
    np.testing.assert_allclose(texture.pixels.reshape(-1, 4), expected, rtol=0, atol=1e-5)


def test_srgb_and_non_color_images_stay_on_the_native_path(
        library: Any, scene_builder: Any, recording_scene: Any, tmp_path: Path) -> None:
    b = scene_builder()
    b.camera()
    srgb = _saved_image(tmp_path, "Srgb")
    data = _saved_image(tmp_path, "Data")
    data.colorspace_settings.name = "Non-Color"
    for image in (srgb, data):
        _textured_cube(b, image)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    by_path = {Path(t.path).name: t for t in recording_scene.textures}
    assert by_path["Srgb.png"].color_space == "sRGB" and by_path["Srgb.png"].pixels is None
    assert by_path["Data.png"].color_space == "Non-Color" and by_path["Data.png"].pixels is None


def test_filmic_log_is_native_where_the_config_is_read_and_converted_here_elsewhere(
        library: Any, scene_builder: Any, recording_scene: Any, tmp_path: Path) -> None:
    """Filmic Log is in every config from 3.4 to 5.0; the native side converts it where it
    reads the config (3.4, 4.2, 4.5), the exporter with PyOpenColorIO elsewhere (5.0)."""
    b = scene_builder()
    b.camera()
    image = _saved_image(tmp_path, "Log")
    image.colorspace_settings.name = "Filmic Log"
    _textured_cube(b, image)
    summary = export_scene(b.depsgraph(), recording_scene)
    assert summary.warnings == []
    (texture,) = recording_scene.textures
    if _native_reads(blender_ocio_config(), tmp_path):
        assert texture.path == str(tmp_path / "Log.png") and texture.pixels is None
        assert texture.color_space == "Filmic Log"
        return
    assert blender_pyopencolorio() is not None, "a config the native side cannot read, and no " \
        "PyOpenColorIO to convert with"
    assert texture.path is None and texture.color_space == SCENE_LINEAR_BUILTIN
    expected = _pyopencolorio_to_scene_linear(_file_values(image), "Filmic Log")
    np.testing.assert_allclose(texture.pixels.reshape(-1, 4), expected, rtol=0, atol=1e-6)
