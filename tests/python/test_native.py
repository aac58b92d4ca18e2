"""The ctypes binding against the real library: registries, validation errors, rendering."""

from __future__ import annotations

import ctypes
import json
import os
import subprocess
import sys
import time
from typing import Any

import numpy as np
import pytest

from conftest import lit_quad_scene


def test_import_without_bpy() -> None:
    code = ("import sys, stratum, stratum.native, stratum.cli; "
            "assert 'bpy' not in sys.modules, 'bpy imported'")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_missing_library_raises_named_error(tmp_path: Any) -> None:
    missing = tmp_path / "libstratum.so"
    code = ("from stratum import native\n"
            "try:\n    native.registry('sampler')\n"
            "except native.LibraryLoadError as e:\n    print('ERR', e)\n")
    env = dict(os.environ, STRATUM_LIBRARY=str(missing))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=True).stdout
    assert out.startswith("ERR") and str(missing) in out


@pytest.mark.parametrize("kind", ["sampler", "filter", "integrator", "hemisphere"])
def test_registries_not_empty(native: Any, kind: str) -> None:
    entries = native.registry(kind)
    assert entries
    for name, label, description in entries:
        assert name and label and description
    names = [e.name for e in entries]
    assert len(set(names)) == len(names)


def test_filters_are_the_documented_ones(native: Any) -> None:
    assert {e.name for e in native.registry("filter")} >= {"box", "blackman_harris"}


def test_version(native: Any) -> None:
    assert native.version()


# ---- the settings and passes the library lists ---------------------------------------------


def test_settings_describe_each_setting_once(native: Any) -> None:
    """The records carry what StratumSettingInfo holds, at the right offsets: known values of
    each kind (a misplaced field would shift them), and for every setting a default that
    lies in its range or among its choices."""
    records = native.settings()
    names = [s.name for s in records]
    assert len(set(names)) == len(names)
    for s in records:
        assert s.label and s.description, s.name
        if s.kind in (native.SettingKind.INT, native.SettingKind.FLOAT):
            assert not s.choices, s.name
            assert s.minimum <= s.default <= s.maximum, s.name
            assert type(s.default) is (int if s.kind == native.SettingKind.INT else float)
        else:
            assert s.choices and isinstance(s.default, str), s.name
            listed = s.default.split(",") if s.default else []
            assert set(listed) <= set(s.choice_names()), s.name
            assert s.kind == native.SettingKind.LIST or len(listed) == 1, s.name
    samples = native.setting("samples")
    assert (samples.kind, samples.minimum, samples.default, samples.open_minimum) == (
        native.SettingKind.INT, 1, 16, False)
    ao = native.setting("ao_distance")
    assert (ao.kind, ao.minimum, ao.maximum, ao.open_minimum, ao.unit, ao.default) == (
        native.SettingKind.FLOAT, 0.0, float("inf"), True, "scene units", 1.0)
    light_sampling = native.setting("light_sampling")
    assert light_sampling.choice_names() == ["mis", "nee", "bsdf"]
    assert light_sampling.default == "mis"
    assert light_sampling.choices[1].label == "Light Sampling"
    assert native.setting("passes").kind == native.SettingKind.LIST
    with pytest.raises(KeyError, match="no_such_setting"):
        native.setting("no_such_setting")


def test_settings_are_read_once(native: Any) -> None:
    assert native.settings() is native.settings()
    assert native.passes() is native.passes()


def test_each_setting_accepts_its_range_and_choices_and_nothing_past_them(
        native: Any, tiny_scene: Any) -> None:
    """What the records say is what Renderer.set accepts: the ends of every range (the
    minimum only when closed), every choice, and the default; one step beyond is refused."""
    with native.Renderer(tiny_scene) as renderer:
        for s in native.settings():
            renderer.set(s.name, s.default)
            if s.kind == native.SettingKind.INT:
                renderer.set(s.name, s.minimum)
                renderer.set(s.name, s.maximum)
                for outside in (s.minimum - 1, s.maximum + 1):
                    with pytest.raises(native.StratumError, match=s.name):
                        renderer.set(s.name, outside)
            elif s.kind == native.SettingKind.FLOAT:
                renderer.set(s.name, s.maximum)
                if s.open_minimum:
                    with pytest.raises(native.StratumError, match=s.name):
                        renderer.set(s.name, s.minimum)
                else:
                    renderer.set(s.name, s.minimum)
                with pytest.raises(native.StratumError, match=s.name):
                    renderer.set(s.name, s.minimum - 1.0)
            else:
                for choice in s.choice_names():
                    renderer.set(s.name, choice)
                if s.kind == native.SettingKind.LIST:
                    renderer.set(s.name, ",".join(s.choice_names()))
                    renderer.set(s.name, "")
                with pytest.raises(native.StratumError, match=s.name):
                    renderer.set(s.name, "no_such_choice")


def test_registry_names_an_unknown_kind(native: Any) -> None:
    with pytest.raises(ValueError, match="bogus"):
        native.registry("bogus")


def test_passes_are_combined_and_the_choices_of_the_passes_setting(native: Any) -> None:
    passes = native.passes()
    assert passes[0] == ("Combined", 4, passes[0].description) and passes[0].description
    assert [p.name for p in passes[1:]] == native.setting("passes").choice_names()
    assert all(p.channels > 0 and p.description for p in passes)


def test_read_pass_returns_an_image_per_pass(native: Any, tiny_scene: Any) -> None:
    """A 10 x 6 render holding the Normal pass: Combined reads as read_pixels does, shaped
    (height, width, 4); Normal is the quad's normal (+z) where the camera sees the quad."""
    with native.Renderer(tiny_scene, width=10, height=6, samples=2, passes="Normal") as r:
        r.start()
        deadline = time.monotonic() + 60
        while not r.wait(100):
            assert time.monotonic() < deadline, "render did not finish"
        combined = r.read_pass("Combined")
        normal = r.read_pass("Normal")
        pixels = r.read_pixels()
        with pytest.raises(ValueError, match="Albedo"):
            r.read_pass("Albedo")
    assert combined.shape == (6, 10, 4) and combined.dtype == np.float32
    np.testing.assert_array_equal(combined.reshape(-1), pixels)
    assert normal.shape == (6, 10, 3) and np.isfinite(normal).all()
    assert normal[3, 5] == pytest.approx([0.0, 0.0, 1.0], abs=1e-5)
    with native.Renderer(tiny_scene, width=4, height=4, samples=1) as r:
        r.start()
        while not r.wait(100):
            pass
        with pytest.raises(native.StratumError, match="Normal"):
            r.read_pass("Normal")  # not held: the setting `passes` does not name it


def test_nan_position_is_rejected_naming_the_value(native: Any) -> None:
    with native.Scene() as scene:
        mat = scene.add_material({"model": native.closure_model("diffuse")})
        positions = np.array([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]], dtype=np.float32)
        with pytest.raises(native.StratumError) as info:
            scene.add_mesh(positions, np.array([[0, 1, 2]], dtype=np.uint32),
                           np.array([mat], dtype=np.uint32))
        assert info.value.status == native.ERROR_INVALID_ARGUMENT
        assert "nan" in str(info.value).lower()


def test_out_of_range_index_is_rejected_naming_the_value(native: Any) -> None:
    with native.Scene() as scene:
        mat = scene.add_material({"model": native.closure_model("diffuse")})
        positions = np.zeros((3, 3), dtype=np.float32)
        with pytest.raises(native.StratumError) as info:
            scene.add_mesh(positions, np.array([[0, 1, 7]], dtype=np.uint32),
                           np.array([mat], dtype=np.uint32))
        assert info.value.status == native.ERROR_INVALID_ARGUMENT
        assert "7" in str(info.value)


def test_unknown_material_id_is_rejected(native: Any) -> None:
    with native.Scene() as scene:
        positions = np.eye(3, dtype=np.float32)
        with pytest.raises(native.StratumError, match="42"):
            scene.add_mesh(positions, np.array([[0, 1, 2]], dtype=np.uint32),
                           np.array([42], dtype=np.uint32))


def test_unknown_setting_is_rejected_naming_it(native: Any, tiny_scene: Any) -> None:
    with native.Renderer(tiny_scene) as renderer:
        with pytest.raises(native.StratumError, match="no_such_setting"):
            renderer.set("no_such_setting", 3)
        with pytest.raises(native.StratumError, match="not_a_sampler"):
            renderer.set("sampler", "not_a_sampler")
        with pytest.raises(native.StratumError):
            renderer.set("samples", "sixty-four")  # wrong kind


def test_tiny_scene_renders_finite_pixels(native: Any, tiny_scene: Any) -> None:
    with native.Renderer(tiny_scene, width=16, height=12, samples=4, seed=1,
                         max_bounces=2) as renderer:
        renderer.start()
        deadline = time.monotonic() + 60
        while not renderer.wait(100):
            assert time.monotonic() < deadline, "render did not finish"
        progress = renderer.progress()
        assert progress.done and not progress.cancelled
        assert progress.samples_done == progress.samples_total == 4
        assert progress.fraction_done == 1.0
        assert progress.rays > 0
        pixels = np.empty(16 * 12 * 4, dtype=np.float32)
        out = renderer.read_pixels(pixels)
        assert out is pixels
    assert np.isfinite(pixels).all()
    assert pixels.reshape(-1, 4)[:, :3].max() > 0.0


def test_read_pixels_rejects_a_wrong_buffer(native: Any, tiny_scene: Any) -> None:
    with native.Renderer(tiny_scene, width=8, height=8, samples=1) as renderer:
        with pytest.raises(ValueError):
            renderer.read_pixels(np.empty(8 * 8 * 4, dtype=np.float64))
        with pytest.raises(native.StratumError):
            renderer.read_pixels(np.empty(10, dtype=np.float32))  # too small: native check


@pytest.mark.parametrize("sampler", ["first", "last"])
def test_every_sampler_renders(native: Any, tiny_scene: Any, sampler: str) -> None:
    entries = native.registry("sampler")
    name = entries[0].name if sampler == "first" else entries[-1].name
    with native.Renderer(tiny_scene, width=8, height=8, samples=2, sampler=name) as renderer:
        renderer.start()
        while not renderer.wait(100):
            pass
        pixels = renderer.read_pixels()
    assert np.isfinite(pixels).all()


def test_cancel_stops_quickly_and_keeps_partial_image(native: Any, tiny_scene: Any) -> None:
    with native.Renderer(tiny_scene, width=64, height=64, samples=1_000_000) as renderer:
        renderer.start()
        deadline = time.monotonic() + 30
        while renderer.progress().samples_done < 1:
            assert time.monotonic() < deadline
            renderer.wait(10)
        t0 = time.perf_counter()
        renderer.cancel()
        while not renderer.wait(10):
            assert time.perf_counter() - t0 < 5
        elapsed = time.perf_counter() - t0
        progress = renderer.progress()
        pixels = renderer.read_pixels()
    assert elapsed < 0.5, f"cancel took {elapsed:.3f}s"
    assert progress.cancelled and 1 <= progress.samples_done < 1_000_000
    assert np.isfinite(pixels).all() and pixels.max() > 0.0


def test_save_and_load_roundtrip(native: Any, tiny_scene: Any, tmp_path: Any) -> None:
    path = tmp_path / "scene.json"
    tiny_scene.save(path)
    assert path.stat().st_size > 0
    with (native.Scene.load(path) as loaded,
          native.Renderer(loaded, width=8, height=8, samples=1) as renderer):
        renderer.start()
        while not renderer.wait(100):
            pass
        assert np.isfinite(renderer.read_pixels()).all()


def test_handles_are_freed_deterministically(native: Any) -> None:
    scene = native.Scene()
    assert not scene.closed
    scene.close()
    assert scene.closed
    scene.close()  # idempotent
    with pytest.raises(native.StratumError, match="closed"):
        scene.add_material({})


def test_write_image(native: Any, tiny_scene: Any, tmp_path: Any) -> None:
    with native.Renderer(tiny_scene, width=8, height=8, samples=1) as renderer:
        renderer.start()
        while not renderer.wait(100):
            pass
        renderer.write_image(tmp_path / "out.exr")
    assert (tmp_path / "out.exr").stat().st_size > 0


# ---- sampling without a scene ------------------------------------------------------------------


def test_hemisphere_registry_has_the_three_distributions(native: Any) -> None:
    assert [e.name for e in native.registry("hemisphere")] == ["uniform_angles", "uniform",
                                                               "cosine"]


def test_integrator_registry_has_path(native: Any) -> None:
    assert "path" in {e.name for e in native.registry("integrator")}


def test_dimension_layout(native: Any) -> None:
    camera, stride = native.camera_dimensions(), native.bounce_dimension_stride()
    assert camera >= 5 and stride >= 7
    assert native.dimension_name(0) == "filter.x"
    assert native.dimension_name(1) == "filter.y"
    assert native.dimension_name(camera) == "bounce0.light_choice"
    assert native.dimension_name(camera + stride) == "bounce1.light_choice"
    names = [native.dimension_name(d) for d in range(camera, camera + stride)]
    assert {"bounce0.bsdf.u", "bounce0.bsdf.v", "bounce0.light.u", "bounce0.light.v"} <= set(names)
    with pytest.raises(ValueError, match="-1"):
        native.dimension_name(-1)


@pytest.mark.parametrize("dims", [(0, 1), (10, 11), (3, 17)])
def test_sampler_points_are_deterministic_and_in_unit_square(native: Any,
                                                             dims: tuple[int, int]) -> None:
    for entry in native.registry("sampler"):
        args = (entry.name, 16, 5, 32, 16, (7, 9), dims, 64)
        first = native.sampler_points(*args)
        again = native.sampler_points(*args)
        assert first.shape == (64, 2) and first.dtype == np.float32
        np.testing.assert_array_equal(first, again, err_msg=entry.name)
        assert (first >= 0).all() and (first < 1).all(), entry.name
        # the first points do not depend on how many are asked for
        np.testing.assert_array_equal(native.sampler_points(*args[:-1], 8), first[:8],
                                      err_msg=entry.name)


def test_sampler_points_depend_on_seed_and_pixel(native: Any) -> None:
    base = native.sampler_points("random", 16, 0, 8, 8, (1, 1), (0, 1), 16)
    assert not np.array_equal(base, native.sampler_points("random", 16, 1, 8, 8, (1, 1), (0, 1),
                                                          16))
    assert not np.array_equal(base, native.sampler_points("random", 16, 0, 8, 8, (2, 1), (0, 1),
                                                          16))


def test_sampler_points_reject_bad_values_naming_them(native: Any) -> None:
    with pytest.raises(native.StratumError, match="no_such_sampler") as info:
        native.sampler_points("no_such_sampler", 4, 0, 8, 8, (0, 0), (0, 1), 4)
    assert info.value.status == native.ERROR_INVALID_ARGUMENT
    with pytest.raises(native.StratumError, match=r"\(8, 3\)"):
        native.sampler_points("random", 4, 0, 8, 8, (8, 3), (0, 1), 4)
    with pytest.raises(native.StratumError, match="samples = 0"):
        native.sampler_points("random", 0, 0, 8, 8, (0, 0), (0, 1), 4)
    with pytest.raises(ValueError, match="pixel x = -1"):
        native.sampler_points("random", 4, 0, 8, 8, (-1, 0), (0, 1), 4)


@pytest.mark.parametrize("distribution", ["uniform_angles", "uniform", "cosine"])
def test_warp_hemisphere_unit_vectors_and_pdf(native: Any, distribution: str) -> None:
    uv = native.sampler_points("random", 256, 0, 1, 1, (0, 0), (0, 1), 256)
    xyz, pdf = native.warp_hemisphere(distribution, uv)
    assert xyz.shape == (256, 3) and pdf.shape == (256,)
    np.testing.assert_allclose(np.linalg.norm(xyz, axis=1), 1.0, atol=1e-5)
    assert (xyz[:, 2] >= 0).all()
    cos_theta = xyz[:, 2].astype(np.float64)
    expected = {
        "uniform_angles": 1.0 / (np.pi**2 * np.sqrt(np.maximum(1.0 - cos_theta**2, 1e-30))),
        "uniform": np.full(256, 1.0 / (2.0 * np.pi)),
        "cosine": cos_theta / np.pi,
    }[distribution]
    np.testing.assert_allclose(pdf, expected, rtol=1e-3)


def test_warp_hemisphere_rejects_bad_points_naming_the_index(native: Any) -> None:
    uv = np.array([[0.1, 0.2], [0.3, np.nan]], dtype=np.float32)
    with pytest.raises(native.StratumError, match=r"uv\[1\]\.v = nan"):
        native.warp_hemisphere("cosine", uv)
    with pytest.raises(native.StratumError, match="spiral"):
        native.warp_hemisphere("spiral", uv[:1])
    with pytest.raises(ValueError, match="shape"):
        native.warp_hemisphere("cosine", np.zeros(4, dtype=np.float32))


def _render_rgb(native: Any, scene: Any, size: int = 16, samples: int = 4) -> np.ndarray:
    with native.Renderer(scene, width=size, height=size, samples=samples, seed=1,
                         max_bounces=1) as renderer:
        renderer.start()
        deadline = time.monotonic() + 60
        while not renderer.wait(100):
            assert time.monotonic() < deadline, "render did not finish"
        pixels = np.empty(size * size * 4, dtype=np.float32)
        renderer.read_pixels(pixels)
    return pixels.reshape(size, size, 4)[..., :3]


def test_orthographic_and_thin_lens_cameras_cross_the_abi(native: Any, tiny_scene: Any) -> None:
    """The appended StratumCameraDesc fields reach the core: an orthographic view of the 2 x 2
    quad from (0, 0, 4) sees only the quad at ortho_scale 1 and the background (0.1) in its
    corners at ortho_scale 8; a thin lens renders; bad values are named."""
    assert native.abi._CameraDesc.type.offset == 24 * 4  # right after the 16-float transform
    assert ctypes_size(native) == 34 * 4  # ... then latitude and longitude ranges
    at = np.eye(4, dtype=np.float32)
    at[2, 3] = 4.0
    tiny_scene.set_camera(native.Camera(transform=at, type="ORTHO", ortho_scale=1.0))
    close = _render_rgb(native, tiny_scene)
    assert (np.abs(close - 0.1) > 1e-3).any(axis=-1).all()  # no background pixel
    tiny_scene.set_camera(native.Camera(transform=at, type=native.CAMERA_ORTHOGRAPHIC,
                                        ortho_scale=8.0))
    far = _render_rgb(native, tiny_scene)
    for y, x in ((0, 0), (0, -1), (-1, 0), (-1, -1)):
        assert far[y, x] == pytest.approx((0.1, 0.1, 0.1), abs=1e-6)
    tiny_scene.set_camera(native.Camera(transform=at, aperture_radius=0.2, focus_distance=4.0,
                                        aperture_blades=5, aperture_rotation=0.3))
    assert np.isfinite(_render_rgb(native, tiny_scene)).all()
    with pytest.raises(native.StratumError, match="aperture_blades"):
        tiny_scene.set_camera(native.Camera(transform=at, aperture_radius=0.2,
                                            focus_distance=4.0, aperture_blades=2))
    with pytest.raises(native.StratumError, match="ortho_scale"):
        tiny_scene.set_camera(native.Camera(transform=at, type="ORTHO", ortho_scale=0.0))
    with pytest.raises(ValueError, match="PANO"):
        tiny_scene.set_camera(native.Camera(transform=at, type="PANO"))


def ctypes_size(native: Any) -> int:

    return ctypes.sizeof(native.abi._CameraDesc)


def test_set_environment_validates_and_renders(native: Any, tiny_scene: Any) -> None:
    img = np.full((4, 8, 3), 0.5, dtype=np.float32)
    with pytest.raises(ValueError, match="height, width, 3"):
        tiny_scene.set_environment(img[..., :2])
    with pytest.raises(ValueError, match="9 floats"):
        tiny_scene.set_environment(img, rotation=np.eye(2))
    bad = img.copy()
    bad[1, 2, 0] = -1.0
    with pytest.raises(native.StratumError, match=r"environment pixel \(2, 1\) channel 0 = -1"):
        tiny_scene.set_environment(bad)
    with pytest.raises(native.StratumError, match="environment strength = -2"):
        tiny_scene.set_environment(img, strength=-2.0)
    # A constant image x strength replaces the 0.1 background: corner pixels see it.
    tiny_scene.set_environment(img, strength=0.4, rotation=np.eye(3))
    with native.Renderer(tiny_scene, width=16, height=12, samples=1, max_bounces=0) as renderer:
        renderer.start()
        deadline = time.monotonic() + 60
        while not renderer.wait(100):
            assert time.monotonic() < deadline, "render did not finish"
        pixels = renderer.read_pixels(np.empty(16 * 12 * 4, dtype=np.float32))
    assert pixels.reshape(12, 16, 4)[0, 0, :3] == pytest.approx([0.2, 0.2, 0.2])


# ---- issue-5 entry points -------------------------------------------------------------------


def _triangle_mesh(native: Any, scene: Any) -> int:
    mat = scene.add_material({"model": native.closure_model("diffuse")})
    return scene.add_mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32),
                          np.array([[0, 1, 2]], dtype=np.uint32), np.array([mat], np.uint32))


def test_add_instances_places_each_transform(native: Any, tmp_path: Any) -> None:
    with native.Scene() as scene:
        mesh = _triangle_mesh(native, scene)
        transforms = np.stack([np.eye(4, dtype=np.float32)] * 3)
        transforms[:, 0, 3] = [1.0, 2.0, 3.0]
        scene.add_instances(np.full(3, mesh), transforms)
        scene.save(tmp_path / "s.json")
    saved = json.loads((tmp_path / "s.json").read_text())
    assert [inst["transform"][3] for inst in saved["instances"]] == [1.0, 2.0, 3.0]


def test_add_instances_rejects_a_bad_mesh_id(native: Any) -> None:
    with native.Scene() as scene, pytest.raises(native.StratumError) as info:
        scene.add_instances(np.array([7]), np.eye(4, dtype=np.float32)[None])
    assert info.value.status == native.ERROR_INVALID_ARGUMENT and "7" in str(info.value)


def test_closure_material_and_texture_binding(native: Any) -> None:
    with native.Scene() as scene:
        mat = scene.add_closure_material([
            ((0.5, 0.5, 0.5), native.Material(model=native.closure_model("transparent"),
                                               base_color=(1.0, 1.0, 1.0))),
            ((0.5, 0.5, 0.5), native.Material(model=native.closure_model("diffuse")))])
        tex = scene.add_texture(native.Texture(pixels=np.ones((2, 2, 4), np.float32),
                                               color_space="Non-Color"))
        scene.bind_texture(native.TextureBinding(mat, 1, native.PARAM_WEIGHT, tex, channel=3))
        with pytest.raises(native.StratumError) as info:
            scene.bind_texture(native.TextureBinding(mat, 5, native.PARAM_WEIGHT, tex))
        assert info.value.status == native.ERROR_INVALID_ARGUMENT
        with pytest.raises(native.StratumError):
            scene.add_closure_material([((-1.0, 0.0, 0.0), native.Material())])


def test_add_instance_ex_motion_visibility_holdout(native: Any, tmp_path: Any) -> None:
    with native.Scene() as scene:
        mesh = _triangle_mesh(native, scene)
        end = np.eye(4, dtype=np.float32)
        end[0, 3] = 1.0
        scene.add_instance_ex(native.Instance(mesh, np.eye(4), end,
                                              native.VISIBLE_CAMERA, holdout=True))
        with pytest.raises(native.StratumError):
            scene.add_instance_ex(native.Instance(mesh + 1, np.eye(4)))


@pytest.mark.parametrize(("name", "bad"), [
    ("light_sampling", "bsdf_only"), ("mis_heuristic", "cube"), ("light_selection", "random"),
    ("triangle_sampling", "spherical"), ("rr_mode", "russian"), ("rr_min_depth", -1),
    ("rr_min_depth", 1025), ("control_variate", -0.5), ("control_variate", float("nan")),
])
def test_estimator_settings_reject_bad_values_naming_them(native: Any, tiny_scene: Any,
                                                          name: str, bad: Any) -> None:
    with native.Renderer(tiny_scene) as renderer, pytest.raises(native.StratumError) as excinfo:
        renderer.set(name, bad)
    message = str(excinfo.value)
    assert name in message and str(bad) in message, message


def _point_lit_quad(native: Any) -> Any:
    """The tiny scene's quad lit only by a point light of radius 0 (no surface to hit), black
    background: every pixel's light comes from the point light."""
    return lit_quad_scene(native, light_radius=0.0, background=0.0)


@pytest.mark.parametrize("light_sampling", ["mis", "nee", "bsdf"])
def test_notices_say_what_bsdf_sampling_cannot_see(native: Any, light_sampling: str) -> None:
    """BSDF sampling alone cannot hit a point light: a notice says so and the image is black;
    the strategies that sample the light have no notice and a lit quad."""
    with _point_lit_quad(native) as scene, native.Renderer(
            scene, width=8, height=8, samples=2, max_bounces=1,
            light_sampling=light_sampling) as renderer:
        assert renderer.notices() == []  # nothing before start
        renderer.start()
        while not renderer.wait(100):
            pass
        notices = renderer.notices()
        rgb = renderer.read_pixels().reshape(-1, 4)[:, :3]
    assert np.isfinite(rgb).all()
    if light_sampling == "bsdf":
        assert notices and all(n.strip() for n in notices), notices
        assert rgb.max() == 0.0
    else:
        assert notices == []
        assert rgb.max() > 0.0
