"""Fixtures for the Blender tests (Blender 3.4 via run_in_blender.py, and the bpy 5.0 wheel).

The same files run in both: scenes are built through bpy.data (no context-dependent
operators), and everything version-specific is feature-tested.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from exr_file import read_image

REPO = Path(__file__).resolve().parents[2]
# Run by their own targets, not by the general runs of this folder: the hostile-scene corpus
# starts Blender in subprocesses from the venv (make test-corpus), the long-session tests want a
# fresh Blender process each (make test-sessions). An explicit `pytest tests/blender/<dir>`
# still runs them.
collect_ignore = ["corpus", "session"]
ADDON_DIR = REPO / "addon"
if str(ADDON_DIR) not in sys.path:
    sys.path.insert(0, str(ADDON_DIR))

bpy = pytest.importorskip("bpy")

# The Blender part of `make check` (`pytest -m smoke`, in the bpy wheel), a few of this folder's
# minutes: the add-on registers, renders, its images equal the recorded hashes, and the Cornell
# box agrees with Cycles.
SMOKE = {"test_registration.py", "test_render.py", "test_image_hashes.py",
         "test_cycles_agreement.py"}


# Tests of the native library's own behaviour on an exported scene (estimators, samplers, the
# error pass, the renderer's determinism): the same code in every Blender, while what differs
# between versions (the export, Cycles' models) is compared in each Blender by the other files.
# `make test` runs them in one Blender, the bpy wheel of the newest Blender (5.x); Blender 3.4
# and the LTS wheels skip them, unless STRATUM_EVERY_BLENDER=1 (make test must stay within 45
# minutes: issue 33).
ONE_BLENDER = {"test_estimator_agreement.py", "test_error_calibration.py",
               "test_sampler_quality.py"}
ONE_BLENDER_TESTS = {"test_every_sampler_and_integrator_repeats_one_image"}


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "smoke: the Blender tests of make check (SMOKE)")


def _one_blender(item: pytest.Item) -> bool:
    return item.path.name in ONE_BLENDER or getattr(item, "originalname", "") in ONE_BLENDER_TESTS


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    skip_here = bpy.app.version[0] < 5 and not os.environ.get("STRATUM_EVERY_BLENDER")
    for item in items:
        if item.path.name in SMOKE:
            item.add_marker(pytest.mark.smoke)
        if skip_here and _one_blender(item):
            item.add_marker(pytest.mark.skip(
                reason="native behaviour, run in the newest Blender's wheel (conftest.ONE_BLENDER)"))


@pytest.fixture(scope="session")
def stratum_addon() -> Iterator[Any]:
    """The registered add-on (registered once per session)."""
    import stratum

    stratum.register()
    yield stratum
    stratum.unregister()


@pytest.fixture(scope="session")
def library(stratum_addon: Any) -> Any:
    """stratum.native with the native library loaded; skips when it is not built yet."""
    from stratum import native

    try:
        native.load_library()
    except native.StratumError as exc:
        pytest.skip(f"native library not available: {exc}")
    return native


class RecordingScene:
    """Stands in for native.Scene in export tests: records what the exporter sends, so the
    exporter is tested without the native library."""

    def __init__(self) -> None:
        self.materials: list[Any] = []
        self.meshes: list[dict[str, np.ndarray | None]] = []
        self.instances: list[tuple[int, np.ndarray]] = []
        self.lights: list[Any] = []
        self.camera: Any = None
        self.background: Any = None
        self.world_lightgroup = 0
        self.environment: Any = None
        self.textures: list[Any] = []
        self.bindings: list[Any] = []
        self.instance_descs: dict[int, Any] = {}
        self.programs: list[Any] = []
        self.program_bindings: list[Any] = []
        self.background_program: Any = None
        self.object_info: Any = None
        self.texture_spaces: dict[int, Any] = {}
        self.mesh_attributes: dict[tuple[int, int], Any] = {}
        self.light_programs: dict[int, tuple[int, int]] = {}  # light -> (program, register)

    def add_material(self, material: Any) -> int:
        self.materials.append(material)
        return len(self.materials) - 1

    def add_mesh(self, positions: np.ndarray, triangles: np.ndarray, material_ids: np.ndarray,
                 corner_normals: np.ndarray | None = None,
                 corner_uvs: np.ndarray | None = None,
                 vertex_normals: np.ndarray | None = None,
                 corner_tangents: np.ndarray | None = None) -> int:
        self.meshes.append({
            "positions": np.array(positions), "triangles": np.array(triangles),
            "material_ids": np.array(material_ids),
            "corner_normals": None if corner_normals is None else np.array(corner_normals),
            "corner_uvs": None if corner_uvs is None else np.array(corner_uvs),
            "vertex_normals": None if vertex_normals is None else np.array(vertex_normals),
            "corner_tangents": None if corner_tangents is None else np.array(corner_tangents),
        })
        return len(self.meshes) - 1

    def add_instance(self, mesh_id: int, matrix: Any) -> None:
        self.instances.append((mesh_id, np.array(matrix, dtype=np.float32).reshape(4, 4)))

    def add_light(self, light: Any) -> None:
        self.lights.append(light)

    def set_camera(self, camera: Any) -> None:
        self.camera = camera

    def set_background(self, rgb: Any) -> None:
        self.background = tuple(rgb)

    def set_world_lightgroup(self, lightgroup: int) -> None:
        self.world_lightgroup = lightgroup

    def set_environment(self, rgb: Any, strength: float = 1.0, rotation: Any = None) -> None:
        self.environment = {"rgb": np.array(rgb), "strength": strength, "rotation": rotation}

    # Issue-5 entry points. Closure materials share the material id space (as natively);
    # add_instance_ex instances are listed in `instances` too, their descriptions in
    # `instance_descs` (by position in `instances`).
    def add_closure_material(self, closures: Any) -> int:
        self.materials.append([(tuple(w), m) for w, m in closures])
        return len(self.materials) - 1

    def add_texture(self, texture: Any) -> int:
        self.textures.append(texture)
        return len(self.textures) - 1

    def texture_info(self, texture_id: int) -> Any:
        """Size and non-finite texel count of pixel textures; files are not decoded here, so a
        file texture reports size 0 x 0 and no replaced texels."""
        from stratum.native import TextureInfo
        pixels = self.textures[texture_id].pixels
        if pixels is None:
            return TextureInfo(0, 0, 0)
        texels = np.asarray(pixels, dtype=np.float32)
        replaced = int(np.count_nonzero(~np.isfinite(texels).all(axis=-1)))
        return TextureInfo(int(texels.shape[1]), int(texels.shape[0]), replaced)

    def bind_texture(self, binding: Any) -> None:
        self.bindings.append(binding)

    def add_instances(self, mesh_ids: Any, transforms: Any) -> None:
        matrices = np.array(transforms, dtype=np.float32).reshape(-1, 4, 4)
        self.instances.extend(zip((int(i) for i in mesh_ids), matrices, strict=True))

    def add_instance_ex(self, instance: Any) -> None:
        self.instance_descs[len(self.instances)] = instance
        self.instances.append((instance.mesh_id,
                               np.array(instance.transform, dtype=np.float32).reshape(4, 4)))

    # Issue-18 entry points: node programs, their bindings, the world's program, Object Info
    # and texture spaces.
    def add_shader_program(self, program: Any) -> int:
        self.programs.append(program)
        return len(self.programs) - 1

    def set_shader_program(self, program_id: int, program: Any) -> None:
        self.programs[program_id] = program

    def bind_program(self, binding: Any) -> None:
        self.program_bindings.append(binding)

    def set_background_program(self, program_id: int, register: int, width: int = 1024,
                               height: int = 512) -> None:
        self.background_program = (program_id, register, width, height)

    def set_instance_object_info(self, first: int, random: Any, color: Any = None) -> None:
        self.object_info = (first, None if random is None else np.array(random),
                            None if color is None else np.array(color))

    def set_mesh_attribute(self, mesh_id: int, slot: int, vector: bool, rgba: Any) -> None:
        self.mesh_attributes[(mesh_id, slot)] = (vector, np.array(rgba))

    def set_mesh_texture_space(self, mesh_id: int, location: Any, size: Any) -> None:
        self.texture_spaces[mesh_id] = (tuple(location), tuple(size))

    def set_light_program(self, light_id: int, program_id: int | None,
                          register_index: int = 0) -> None:
        if program_id is None:
            self.light_programs.pop(light_id, None)
        else:
            self.light_programs[light_id] = (program_id, register_index)


CUBE_VERTS = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
              (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
CUBE_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
              (3, 0, 4, 7)]


class SceneBuilder:
    """Small scenes built with bpy.data only."""

    def __init__(self) -> None:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        self.scene = bpy.context.scene
        self.scene.render.engine = "STRATUM"
        self.set_resolution(32, 32)
        self.scene.stratum.samples = 4

    def set_resolution(self, width: int, height: int) -> None:
        r = self.scene.render
        r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100

    def link(self, ob: Any) -> Any:
        self.scene.collection.objects.link(ob)
        return ob

    def camera(self, location: tuple[float, float, float] = (0.0, -6.0, 0.0)) -> Any:
        cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
        cam.location = location
        cam.rotation_euler = (math.pi / 2, 0.0, 0.0)  # look along +Y
        self.link(cam)
        self.scene.camera = cam
        return cam

    def mesh_data(self, name: str = "Cube") -> Any:
        me = bpy.data.meshes.new(name)
        me.from_pydata(CUBE_VERTS, [], CUBE_FACES)
        me.update()
        return me

    def mesh_object(self, name: str = "Cube", data: Any = None,
                    location: tuple[float, float, float] = (0.0, 0.0, 0.0),
                    material: Any = None) -> Any:
        ob = bpy.data.objects.new(name, data if data is not None else self.mesh_data(name))
        ob.location = location
        if material is not None:
            ob.data.materials.append(material)
        return self.link(ob)

    def point_light(self, energy: float = 500.0,
                    location: tuple[float, float, float] = (0.0, -3.0, 3.0)) -> Any:
        light = bpy.data.lights.new("Light", "POINT")
        light.energy = energy
        ob = bpy.data.objects.new("Light", light)
        ob.location = location
        return self.link(ob)

    def world(self, color: tuple[float, float, float] = (0.05, 0.05, 0.05)) -> Any:
        world = bpy.data.worlds.new("World")
        world.color = color
        if world.node_tree is not None:
            bg = world.node_tree.nodes.get("Background")
            if bg is not None:
                bg.inputs["Color"].default_value = (*color, 1.0)
                bg.inputs["Strength"].default_value = 1.0
        self.scene.world = world
        return world

    def basic(self) -> SceneBuilder:
        """Camera, a cube, a light, a dim grey world."""
        self.camera()
        self.mesh_object("Cube")
        self.point_light()
        self.world()
        return self

    def depsgraph(self) -> Any:
        dg = bpy.context.evaluated_depsgraph_get()
        dg.update()
        return dg


@pytest.fixture
def scene_builder(stratum_addon: Any) -> Callable[[], SceneBuilder]:
    """Returns a factory: each call resets Blender to an empty factory scene."""
    return SceneBuilder


@pytest.fixture
def recording_scene() -> RecordingScene:
    return RecordingScene()


def engine_reports(level: str) -> list[str]:
    """The messages the Stratum engine reported at `level` ("ERROR", "WARNING", ...) during the
    last render."""
    from stratum.engine import StratumRenderEngine

    return [m for lvl, m in StratumRenderEngine.last_reports if lvl == level]


def render_still(scene: Any, path: Path) -> np.ndarray | None:
    """Renders to an EXR and returns its pixels (None if nothing was written). An ERROR report
    may surface as RuntimeError from the operator in background mode: that is Blender's
    reporting, not an exception escaping the engine."""
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    try:
        bpy.ops.render.render(write_still=True)
    except RuntimeError:
        pass
    return read_image(path) if path.is_file() else None
