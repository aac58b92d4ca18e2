"""Rendering through the engine (needs the native library; skipped until it is built)."""

from __future__ import annotations

import math
import time
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import bpy
import numpy as np
import pytest
from stratum.engine import StratumRenderEngine, final_render

from conftest import REPO, engine_reports
from exr_file import read_image

CORNELL = REPO / "scenes" / "cornell_box.blend"


def _render_to_exr(scene: Any, path: Path) -> np.ndarray:
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    errors = engine_reports("ERROR")
    assert not errors, errors
    assert path.is_file(), f"render did not write {path}"
    return read_image(path)


def test_render_small_scene(library: Any, scene_builder: Any, tmp_path: Path) -> None:
    b = scene_builder().basic()
    b.scene.stratum.samples = 4
    pixels = _render_to_exr(b.scene, tmp_path / "small.exr")
    assert pixels.shape[:2] == (32, 32)
    assert np.isfinite(pixels).all()
    assert pixels[..., :3].max() > 0.0
    summary = StratumRenderEngine.last_summary
    assert summary is not None and summary.instances == 1


def test_nan_vertex_render_reports_error(library: Any, scene_builder: Any) -> None:
    b = scene_builder().basic()
    broken = b.mesh_object("BrokenMesh", location=(3.0, 0.0, 0.0))
    broken.data.vertices[2].co = (0.0, math.nan, 0.0)  # (RNA clamps inf to FLT_MAX)
    message = ""
    try:  # background renders raise RuntimeError on an ERROR report in some versions
        bpy.ops.render.render()
    except RuntimeError as exc:
        message = str(exc)
    errors = engine_reports("ERROR")
    assert errors, "the engine did not report an error"
    assert "BrokenMesh" in errors[0]
    if message:
        assert "BrokenMesh" in message


def test_missing_library_is_reported(stratum_addon: Any, scene_builder: Any,
                                     monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    from stratum import native

    scene_builder().basic()
    monkeypatch.setattr(native.library, "_lib", None)  # the loaded library is held there
    monkeypatch.setenv("STRATUM_LIBRARY", str(tmp_path / "missing" / "libstratum.so"))
    try:
        bpy.ops.render.render()
    except RuntimeError:
        pass
    errors = engine_reports("ERROR")
    assert errors and "libstratum.so" in errors[0]


class FakeRenderPass:
    def __init__(self, n: int) -> None:
        self.pixels = np.zeros(n, dtype=np.float32)
        self.rect = self

    def foreach_set(self, data: np.ndarray) -> None:
        self.pixels[:] = np.asarray(data, dtype=np.float32).reshape(-1)


class FakeEngine:
    """Duck-typed RenderEngine for driving final_render.render_progressively directly."""

    def __init__(self, width: int, height: int, break_after_updates: int | None) -> None:
        self.render_pass = FakeRenderPass(width * height * 4)
        self.break_after = break_after_updates
        self.updates = 0
        self.break_time: float | None = None
        self.ended = False
        self.reports: list[tuple[str, str]] = []

    def begin_result(self, x: int, y: int, w: int, h: int) -> Any:
        layer = SimpleNamespace(passes={"Combined": self.render_pass})
        return SimpleNamespace(layers=[layer])

    def update_result(self, result: Any) -> None:
        self.updates += 1

    def end_result(self, result: Any) -> None:
        self.ended = True

    def test_break(self) -> bool:
        if self.break_after is not None and self.updates >= self.break_after:
            if self.break_time is None:
                self.break_time = time.perf_counter()
            return True
        return False

    def update_progress(self, value: float) -> None:
        assert 0.0 <= value <= 1.0

    def update_stats(self, a: str, b: str) -> None:
        pass

    def _report(self, level: str, message: str) -> None:
        self.reports.append((level, message))


def _native_renderer(native: Any, b: Any, samples: int, size: int) -> Any:
    from stratum.export.sync import export_scene

    with native.Scene() as scene:
        export_scene(b.depsgraph(), scene)
        renderer = native.Renderer(scene)
    for name, value in {"width": size, "height": size, "samples": samples, "seed": 0,
                        "max_bounces": 4}.items():
        renderer.set(name, value)
    return renderer


def test_progressive_updates(library: Any, scene_builder: Any) -> None:
    b = scene_builder().basic()
    engine = FakeEngine(16, 16, None)
    with _native_renderer(library, b, 8, 16) as renderer:
        final_render.render_progressively(engine, renderer, 16, 16)
        assert renderer.progress().samples_done == 8
    assert engine.ended and engine.updates >= 1 and not engine.reports
    assert np.isfinite(engine.render_pass.pixels).all()
    assert engine.render_pass.pixels.max() > 0.0


def test_cancel_through_engine_loop(library: Any, scene_builder: Any) -> None:
    """Esc (test_break) must stop the render within 0.5 s and keep the partial image."""
    b = scene_builder().basic()
    engine = FakeEngine(64, 64, break_after_updates=1)
    with _native_renderer(library, b, 1_000_000, 64) as renderer:
        final_render.render_progressively(engine, renderer, 64, 64)
        stopped = time.perf_counter()
        progress = renderer.progress()
    assert engine.break_time is not None
    assert stopped - engine.break_time < 0.5, f"stopped {stopped - engine.break_time:.3f}s late"
    assert progress.done and progress.cancelled
    assert 0 < progress.samples_done < 1_000_000
    assert np.isfinite(engine.render_pass.pixels).all()
    assert engine.render_pass.pixels.max() > 0.0


def test_cornell_box(library: Any, stratum_addon: Any, tmp_path: Path) -> None:
    if not CORNELL.is_file():
        pytest.skip(f"{CORNELL} does not exist yet")
    bpy.ops.wm.open_mainfile(filepath=str(CORNELL))
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    scene.render.resolution_x = scene.render.resolution_y = 32
    scene.render.resolution_percentage = 100
    scene.stratum.samples = 4
    pixels = _render_to_exr(scene, tmp_path / "cornell.exr")
    assert np.isfinite(pixels).all()
    assert pixels[..., :3].mean() > 0.0
    summary = StratumRenderEngine.last_summary
    assert summary is not None and summary.instances >= summary.meshes >= 1


def _registry_names(kind: str) -> list[str]:
    """Names of a native registry at collection time ([] when the library is not built)."""
    from stratum import native

    try:
        return [e.name for e in native.registry(kind)]
    except native.StratumError:
        return []


def _names_or_skip(kind: str) -> list[Any]:
    names = _registry_names(kind)
    return names or [pytest.param(None, marks=pytest.mark.skip(reason="library not built"))]


def _tiny(scene: Any, size: int = 16) -> None:
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.stratum.samples = 4
    scene.stratum.max_bounces = 2


def _open_cornell() -> Any:
    if not CORNELL.is_file():
        pytest.skip(f"{CORNELL} does not exist yet")
    bpy.ops.wm.open_mainfile(filepath=str(CORNELL))
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    return scene


@pytest.mark.parametrize("sampler", _names_or_skip("sampler"))
def test_every_sampler_renders_the_cornell_box(library: Any, stratum_addon: Any,
                                               tmp_path: Path, sampler: str) -> None:
    scene = _open_cornell()
    _tiny(scene)
    scene.stratum.sampler = sampler
    pixels = _render_to_exr(scene, tmp_path / f"{sampler}.exr")
    assert pixels.shape[:2] == (16, 16)
    assert np.isfinite(pixels).all(), sampler
    assert pixels[..., :3].max() > 0.0, sampler


@pytest.mark.parametrize("hemisphere", _names_or_skip("hemisphere"))
def test_every_hemisphere_renders_the_cornell_box(library: Any, stratum_addon: Any,
                                                  tmp_path: Path, hemisphere: str) -> None:
    scene = _open_cornell()
    _tiny(scene)
    scene.stratum.hemisphere = hemisphere
    pixels = _render_to_exr(scene, tmp_path / f"{hemisphere}.exr")
    assert np.isfinite(pixels).all(), hemisphere
    assert pixels[..., :3].mean() > 0.0, hemisphere


@pytest.mark.parametrize("hemisphere", _names_or_skip("hemisphere"))
def test_ao_integrator_renders_openness(library: Any, stratum_addon: Any, tmp_path: Path,
                                        hemisphere: str) -> None:
    """integrator='ao' renders grey openness: in [0,1] per sample with the cosine
    distribution; the other two are unbiased but a single sample may leave [0,1], so their
    few-sample pixels are only checked on average."""
    if "ao" not in _registry_names("integrator"):
        pytest.skip("the 'ao' integrator is not registered")
    scene = _open_cornell()
    _tiny(scene)
    scene.stratum.samples = 16 if hemisphere == "cosine" else 64
    scene.stratum.integrator = "ao"
    scene.stratum.hemisphere = hemisphere
    scene.stratum.ao_distance = 0.5
    rgb = _render_to_exr(scene, tmp_path / f"ao_{hemisphere}.exr")[..., :3]
    assert np.isfinite(rgb).all()
    np.testing.assert_allclose(rgb[..., 0], rgb[..., 1], atol=1e-6)
    np.testing.assert_allclose(rgb[..., 0], rgb[..., 2], atol=1e-6)
    if hemisphere == "cosine":
        assert rgb.min() >= 0.0 and rgb.max() <= 1.0 + 1e-6
    assert 0.0 <= rgb.mean() <= 1.0
    assert rgb.min() < 1.0, "nothing is occluded inside a closed box"
    assert rgb.max() > 0.0
