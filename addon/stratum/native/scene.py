"""`Scene`: a native scene under construction, filled from the descriptions of descriptions.py,
saved and loaded as a scene file."""

from __future__ import annotations

import ctypes
import os
from collections.abc import Mapping, Sequence
from dataclasses import asdict
from typing import Any

import numpy as np

from . import programs
from .abi import (
    CAMERA_TYPES,
    NO_PROGRAM,
    SENSOR_FITS,
    _CameraDesc,
    _ClosureDesc,
    _InstanceDesc,
    _LightDesc,
    _MaterialDesc,
    _MeshDesc,
    _TextureBinding,
    _TextureDesc,
    _TextureInfo,
)
from .descriptions import Camera, Instance, Light, Material, Texture, TextureBinding, TextureInfo
from .library import StratumError, _check, _Handle, load_library
from .marshalling import _fields, _float_ptr, _matrix16, _set_struct, _uint32, _uint_ptr
from .programs import ProgramBinding, ShaderProgram

# Weighted closures of a closure material: [(weight RGB, material), ...].
Closures = Sequence[tuple[Sequence[float], Mapping[str, Any] | Material]]


def _material_desc(material: Mapping[str, Any] | Material,
                   what: str = "material") -> _MaterialDesc:
    """The struct of `material` (missing fields: Material's defaults); errors name `what`."""
    desc = _MaterialDesc()
    values = asdict(Material())
    values.update(_fields(material))
    _set_struct(desc, values, what)
    return desc


def _closure_descs(closures: Closures) -> ctypes.Array[_ClosureDesc]:
    n = len(closures)
    if n == 0:
        raise ValueError("closure material: at least one closure is needed")
    descs = (_ClosureDesc * n)()
    for i, (weight, material) in enumerate(closures):
        descs[i].closure = _material_desc(material, f"closure {i}")
        _set_struct(descs[i], {"weight": weight}, f"closure {i}")
    return descs


def _instance_desc(instance: Instance) -> _InstanceDesc:
    desc = _InstanceDesc()
    desc.mesh_id = _uint32(instance.mesh_id, "instance mesh_id")
    # memmove, not per-element assignment: scenes place tens of thousands of instances.
    start = _matrix16(instance.transform, "instance transform")
    ctypes.memmove(desc.transform, start.ctypes.data, 64)
    if instance.transform_end is not None:
        end = _matrix16(instance.transform_end, "instance transform_end")
        ctypes.memmove(desc.transform_end, end.ctypes.data, 64)
        desc.motion = 1
    desc.visibility = _uint32(instance.visibility, "instance visibility")
    desc.holdout = 1 if instance.holdout else 0
    desc.pass_index = _uint32(instance.pass_index, "instance pass_index")
    desc.lightgroup = _uint32(instance.lightgroup, "instance lightgroup")
    return desc


def _light_desc(light: Mapping[str, Any] | Light | None, fields: Mapping[str, Any]) -> _LightDesc:
    """The struct of `light` (None: the defaults) with `fields` overriding its values."""
    values = asdict(Light())
    if light is not None:
        values.update(_fields(light))
    values.update(fields)
    values["transform"] = _matrix16(values["transform"], "light transform")
    desc = _LightDesc()
    _set_struct(desc, values, "light")
    return desc


def _optional_floats(values: Any, what: str, width: int, count: int,
                     unit: str) -> np.ndarray | None:
    """`values` as contiguous float32 of width floats per each of `count` units, or None."""
    if values is None:
        return None
    array = np.ascontiguousarray(values, dtype=np.float32)
    if array.size != count * width:
        raise ValueError(f"{what}: {array.size} floats for {count} {unit} "
                         f"(expected {count * width})")
    return array


class Scene(_Handle):
    """A native scene under construction: materials, meshes, instances, lights, camera."""

    _destroy_name = "stratum_scene_destroy"

    def __init__(self, _adopt: ctypes.c_void_p | None = None) -> None:
        super().__init__()
        if _adopt is not None:
            self._ptr = _adopt
        else:
            _check(self._lib, self._lib.stratum_scene_create(ctypes.byref(self._ptr)),
                   "stratum_scene_create")

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Scene:
        lib = load_library()
        ptr = ctypes.c_void_p()
        _check(lib, lib.stratum_scene_load(os.fsencode(path), ctypes.byref(ptr)),
               "stratum_scene_load")
        return cls(_adopt=ptr)

    def save(self, path: str | os.PathLike[str]) -> None:
        _check(self._lib, self._lib.stratum_scene_save(self.handle, os.fsencode(path)),
               "stratum_scene_save")

    def measure_ray_throughput(self, width: int, height: int, samples: int, max_bounces: int,
                               threads: int = 0) -> tuple[float, float]:
        """Embree alone on the path tracer's ray mix: (rays traced, seconds), the ceiling
        `make bench` compares Stratum's rays/s with."""
        rays, seconds = ctypes.c_double(), ctypes.c_double()
        _check(self._lib, self._lib.stratum_scene_measure_ray_throughput(
            self.handle, _uint32(width, "width"), _uint32(height, "height"),
            _uint32(samples, "samples"), _uint32(max_bounces, "max_bounces"),
            _uint32(threads, "threads"), ctypes.byref(rays), ctypes.byref(seconds)),
            "stratum_scene_measure_ray_throughput")
        return rays.value, seconds.value

    def add_material(self, material: Mapping[str, Any] | Material) -> int:
        out = ctypes.c_uint32()
        _check(self._lib,
               self._lib.stratum_scene_add_material(self.handle,
                                                    ctypes.byref(_material_desc(material)),
                                                    ctypes.byref(out)),
               "stratum_scene_add_material")
        return int(out.value)

    def add_closure_material(self, closures: Closures) -> int:
        """A material made of weighted closures [(weight RGB, material), ...]."""
        descs = _closure_descs(closures)
        out = ctypes.c_uint32()
        fn = self._lib.stratum_scene_add_closure_material
        _check(self._lib, fn(self.handle, descs, len(descs), ctypes.byref(out)),
               "stratum_scene_add_closure_material")
        return int(out.value)

    def add_texture(self, texture: Texture) -> int:
        desc = _TextureDesc()
        keep: list[Any] = []  # buffers referenced by desc, alive until the (copying) call returns
        if texture.path is not None:
            desc.path = os.fsencode(texture.path)
        if texture.file_data is not None:
            data = ctypes.create_string_buffer(bytes(texture.file_data), len(texture.file_data))
            keep.append(data)
            desc.file_data = ctypes.cast(data, ctypes.c_void_p)
            desc.file_size = len(texture.file_data)
        if texture.file_name is not None:
            desc.file_name = texture.file_name.encode()
        if texture.pixels is not None:
            px = np.ascontiguousarray(texture.pixels, dtype=np.float32)
            if px.ndim == 2:
                px = px[:, :, None]
            if px.ndim != 3:
                raise ValueError(f"texture pixels: expected (height, width, channels), got "
                                 f"{px.shape}")
            keep.append(px)
            desc.pixels = _float_ptr(px)
            desc.height, desc.width, desc.channels = (int(v) for v in px.shape)
        desc.color_space = texture.color_space.encode()
        if texture.ocio_config is not None:
            desc.ocio_config = os.fsencode(texture.ocio_config)
        desc.interpolation = int(texture.interpolation)
        desc.extension = int(texture.extension)
        out = ctypes.c_uint32()
        fn = self._lib.stratum_scene_add_texture
        status = fn(self.handle, ctypes.byref(desc), ctypes.byref(out))
        del keep
        _check(self._lib, status, "stratum_scene_add_texture")
        return int(out.value)

    def texture_info(self, texture_id: int) -> TextureInfo:
        out = _TextureInfo()
        fn = self._lib.stratum_scene_texture_info
        _check(self._lib, fn(self.handle, int(texture_id), ctypes.byref(out)),
               "stratum_scene_texture_info")
        return TextureInfo(int(out.width), int(out.height), int(out.replaced_texels))

    def bind_texture(self, binding: TextureBinding) -> None:
        desc = _TextureBinding()
        _set_struct(desc, _fields(binding), "texture binding")
        fn = self._lib.stratum_scene_bind_texture
        _check(self._lib, fn(self.handle, ctypes.byref(desc)), "stratum_scene_bind_texture")

    def add_mesh(
        self,
        positions: np.ndarray,
        triangles: np.ndarray,
        material_ids: np.ndarray,
        corner_normals: np.ndarray | None = None,
        corner_uvs: np.ndarray | None = None,
        vertex_normals: np.ndarray | None = None,
        corner_tangents: np.ndarray | None = None,
    ) -> int:
        """positions (N,3) float32, triangles (T,3) uint32, material_ids (T,) uint32,
        corner_normals (T,3,3) float32, corner_uvs (T,3,2) float32, vertex_normals (N,3)
        float32 (at most one kind of normals), corner_tangents (T,3,4) float32 (MikkTSpace
        tangent and bitangent sign per corner). Arrays already of the right dtype and contiguous
        are passed without a copy."""
        pos = np.ascontiguousarray(positions, dtype=np.float32)
        tri = np.ascontiguousarray(triangles, dtype=np.uint32)
        mat = np.ascontiguousarray(material_ids, dtype=np.uint32)
        if pos.size % 3:
            raise ValueError(f"positions: size {pos.size} is not a multiple of 3")
        if tri.size % 3:
            raise ValueError(f"triangles: size {tri.size} is not a multiple of 3")
        n_vert, n_tri = pos.size // 3, tri.size // 3
        if mat.size != n_tri:
            raise ValueError(f"material_ids: {mat.size} values for {n_tri} triangles")
        desc = _MeshDesc()
        desc.positions = _float_ptr(pos)
        desc.vertex_count = n_vert
        desc.triangles = _uint_ptr(tri)
        desc.triangle_count = n_tri
        desc.material_ids = _uint_ptr(mat)
        # The optional arrays, each checked against the triangles or vertices it describes.
        tangents = _optional_floats(corner_tangents, "corner_tangents", 12, n_tri, "triangles")
        vnrm = _optional_floats(vertex_normals, "vertex_normals", 3, n_vert, "vertices")
        nrm = _optional_floats(corner_normals, "corner_normals", 9, n_tri, "triangles")
        uvs = _optional_floats(corner_uvs, "corner_uvs", 6, n_tri, "triangles")
        for field, values in (("corner_tangents", tangents), ("vertex_normals", vnrm),
                              ("corner_normals", nrm), ("corner_uvs", uvs)):
            if values is not None:
                setattr(desc, field, _float_ptr(values))
        out = ctypes.c_uint32()
        status = self._lib.stratum_scene_add_mesh(self.handle, ctypes.byref(desc),
                                                  ctypes.byref(out))
        # keep the arrays alive until the (copying) call has returned
        del pos, tri, mat, nrm, uvs, vnrm, tangents
        _check(self._lib, status, "stratum_scene_add_mesh")
        return int(out.value)

    def add_instance(self, mesh_id: int, matrix: Any) -> None:
        m = _matrix16(matrix, "instance transform")
        _check(self._lib,
               self._lib.stratum_scene_add_instance(self.handle, int(mesh_id), _float_ptr(m)),
               "stratum_scene_add_instance")

    def add_instances(self, mesh_ids: np.ndarray, transforms: np.ndarray) -> None:
        """Static instances in bulk: mesh_ids (N,) and transforms (N, 4, 4) row-major, in one C
        call (scenes place 10 000s). All or nothing: a rejected instance raises StratumError
        whose `index` is its row, and none of the batch is added."""
        ids = np.ascontiguousarray(mesh_ids, dtype=np.uint32).reshape(-1)
        mats = np.ascontiguousarray(transforms, dtype=np.float32).reshape(-1, 16)
        if len(ids) != len(mats):
            raise ValueError(f"add_instances: {len(ids)} mesh ids for {len(mats)} transforms")
        failed = ctypes.c_uint32(0xFFFFFFFF)
        status = self._lib.stratum_scene_add_instances(
            self.handle, _uint32(len(ids), "instance count"), _uint_ptr(ids), _float_ptr(mats),
            ctypes.byref(failed))
        try:
            _check(self._lib, status, "stratum_scene_add_instances")
        except StratumError as exc:
            index = failed.value if failed.value != 0xFFFFFFFF else None
            raise StratumError(exc.status, exc.message, index=index) from None

    def add_instance_ex(self, instance: Instance) -> None:
        """An instance with motion (transform_end not None), ray visibility, holdout and pass
        index."""
        fn = self._lib.stratum_scene_add_instance_ex
        _check(self._lib, fn(self.handle, ctypes.byref(_instance_desc(instance))),
               "stratum_scene_add_instance_ex")

    def add_light(self, light: Mapping[str, Any] | Light | None = None, **fields: Any) -> None:
        desc = _light_desc(light, fields)
        _check(self._lib, self._lib.stratum_scene_add_light(self.handle, ctypes.byref(desc)),
               "stratum_scene_add_light")

    # Live edits (stratum.h "live edits"): each replaces one part of a scene renderers may
    # have been made from, validated as when it was added; a renderer sees the edits at its
    # next start. Indices count instances and lights in the order they were added.

    def set_instance(self, index: int, instance: Instance) -> None:
        fn = self._lib.stratum_scene_set_instance
        _check(self._lib, fn(self.handle, _uint32(index, "instance index"),
                             ctypes.byref(_instance_desc(instance))),
               "stratum_scene_set_instance")

    def set_material(self, material_id: int, material: Mapping[str, Any] | Material) -> None:
        fn = self._lib.stratum_scene_set_material
        _check(self._lib, fn(self.handle, _uint32(material_id, "material_id"),
                             ctypes.byref(_material_desc(material))),
               "stratum_scene_set_material")

    def set_material_pass_index(self, material_id: int, pass_index: int) -> None:
        """Material > Settings > Pass Index (the IndexMA pass); 0 until set."""
        fn = self._lib.stratum_scene_set_material_pass_index
        _check(self._lib, fn(self.handle, _uint32(material_id, "material_id"),
                             _uint32(pass_index, "material pass_index")),
               "stratum_scene_set_material_pass_index")

    def set_closure_material(self, material_id: int, closures: Closures) -> None:
        """Replaces material `material_id` by weighted closures [(weight RGB, material), ...].
        Its texture bindings stay: they name closures by index."""
        descs = _closure_descs(closures)
        fn = self._lib.stratum_scene_set_closure_material
        _check(self._lib, fn(self.handle, _uint32(material_id, "material_id"), descs,
                             len(descs)),
               "stratum_scene_set_closure_material")

    def set_light(self, index: int, light: Mapping[str, Any] | Light) -> None:
        fn = self._lib.stratum_scene_set_light
        _check(self._lib, fn(self.handle, _uint32(index, "light index"),
                             ctypes.byref(_light_desc(light, {}))),
               "stratum_scene_set_light")

    def set_camera(self, camera: Mapping[str, Any] | Camera | None = None,
                   **fields: Any) -> None:
        values = asdict(Camera())
        if camera is not None:
            values.update(_fields(camera))
        values.update(fields)
        fit = values["sensor_fit"]
        if isinstance(fit, str):
            if fit not in SENSOR_FITS:
                raise ValueError(f"camera: unknown sensor_fit {fit!r}")
            values["sensor_fit"] = SENSOR_FITS[fit]
        kind = values["type"]
        if isinstance(kind, str):
            if kind not in CAMERA_TYPES:
                raise ValueError(f"camera: unknown type {kind!r} (known: {sorted(CAMERA_TYPES)})")
            values["type"] = CAMERA_TYPES[kind]
        values["transform"] = _matrix16(values["transform"], "camera transform")
        desc = _CameraDesc()
        _set_struct(desc, values, "camera")
        _check(self._lib, self._lib.stratum_scene_set_camera(self.handle, ctypes.byref(desc)),
               "stratum_scene_set_camera")

    # Shader node programs (stratum/shader_nodes.h; marshalling in programs.py).
    def add_shader_program(self, program: ShaderProgram) -> int:
        return programs.add_program(self._lib, self.handle, program)

    def set_shader_program(self, program_id: int, program: ShaderProgram) -> None:
        programs.set_program(self._lib, self.handle, program_id, program)

    def bind_program(self, binding: ProgramBinding) -> None:
        programs.bind_program(self._lib, self.handle, binding)

    def set_background_program(self, program_id: int, register_index: int, width: int = 1024,
                               height: int = 512) -> None:
        programs.set_background_program(self._lib, self.handle, program_id, register_index,
                                        width, height)

    def set_light_program(self, light_id: int, program_id: int | None,
                          register_index: int = 0) -> None:
        """Scales light `light_id`'s emission by the RGB of `register_index` of program
        `program_id`, evaluated at each distance to the lamp (RAY_LENGTH: a Light Falloff in the
        lamp's node tree); None removes it. A program reading any other renderer input is
        refused."""
        programs.set_light_program(self._lib, self.handle, light_id,
                                   NO_PROGRAM if program_id is None else program_id,
                                   register_index)

    def evaluate_program(self, program_id: int, inputs: np.ndarray, first: int,
                         count: int) -> np.ndarray:
        return programs.evaluate_program(self._lib, self.handle, program_id, inputs, first, count)

    def set_instance_object_info(self, first: int, random: np.ndarray | None,
                                 color: np.ndarray | None = None) -> None:
        """Object Info's Random (n floats in [0, 1]) and Color and Alpha (n x 4) of instances
        first .. first + n - 1; None leaves that part."""
        programs.set_instance_object_info(self._lib, self.handle, first, random, color)

    def set_light_linking(self, lights: bool, first: int, receiver_light_set: np.ndarray | None,
                          blocker_shadow_set: np.ndarray | None,
                          light_set_membership: np.ndarray | None,
                          shadow_set_membership: np.ndarray | None) -> None:
        """Light and shadow linking sets (ids 0..63) and memberships (64-bit masks) of
        instances (lights False) or lamps (True: memberships only, the sets None) first ..
        first + n - 1; None leaves that part (stratum_scene_set_light_linking)."""
        programs.set_light_linking(self._lib, self.handle, lights, first, receiver_light_set,
                                   blocker_shadow_set, light_set_membership,
                                   shadow_set_membership)

    def set_mesh_attribute(self, mesh_id: int, slot: int, vector: bool,
                           corner_rgba: np.ndarray) -> None:
        """A mesh attribute in slot 0..3: (triangles, 3, 4) RGBA per corner; `vector` when its
        Fac is the mean of RGB (a 3-vector or colour), else the first component."""
        programs.set_mesh_attribute(self._lib, self.handle, mesh_id, slot, vector, corner_rgba)

    def set_mesh_texture_space(self, mesh_id: int, location: Sequence[float],
                               size: Sequence[float]) -> None:
        programs.set_mesh_texture_space(self._lib, self.handle, mesh_id, location, size)

    def set_background(self, rgb: Sequence[float] | np.ndarray) -> None:
        c = np.ascontiguousarray(np.asarray(rgb, dtype=np.float32).reshape(-1)[:3])
        if c.size != 3:
            raise ValueError("background: expected 3 floats (linear RGB)")
        _check(self._lib, self._lib.stratum_scene_set_background(self.handle, _float_ptr(c)),
               "stratum_scene_set_background")

    def set_world_lightgroup(self, lightgroup: int) -> None:
        """The light group of the world (0 none, k in 1..MAX_LIGHT_GROUPS)."""
        _check(self._lib,
               self._lib.stratum_scene_set_world_lightgroup(self.handle,
                                                           _uint32(lightgroup, "world lightgroup")),
               "stratum_scene_set_world_lightgroup")

    def set_environment(self, rgb: np.ndarray, strength: float = 1.0,
                        rotation: Sequence[float] | np.ndarray | None = None) -> None:
        """Equirectangular environment image: rgb is (height, width, 3) linear RGB, rows top
        (+Z) to bottom, as stratum_scene_set_environment documents; rotation is the 3x3
        world-to-environment rotation (None = identity)."""
        img = np.ascontiguousarray(np.asarray(rgb, dtype=np.float32))
        if img.ndim != 3 or img.shape[2] != 3:
            raise ValueError(f"environment: expected a (height, width, 3) array, got {img.shape}")
        rot = None
        if rotation is not None:
            rot = np.ascontiguousarray(np.asarray(rotation, dtype=np.float32).reshape(-1))
            if rot.size != 9:
                raise ValueError("environment rotation: expected 9 floats (3x3 row-major)")
        _check(self._lib, self._lib.stratum_scene_set_environment(
            self.handle, _float_ptr(img), img.shape[1], img.shape[0], float(strength),
            None if rot is None else _float_ptr(rot)), "stratum_scene_set_environment")

