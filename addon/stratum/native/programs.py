"""Shader node programs as the C ABI takes them (stratum/shader_nodes.h): the marshalling of
`ShaderProgram` and the entry points, used by `Scene`'s program methods.

A program is straight-line nodes over float registers; `stratum.shaders.nodes` compiles Blender
node graphs into one. This module only moves it across the ABI."""

from __future__ import annotations

import ctypes
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .abi import (
    LINK_INSTANCES,
    LINK_LIGHTS,
    PROGRAM_PARAMS,
    SHADER_INPUT_REGISTERS,
    _ProgramBinding,
    _ShaderNode,
    _ShaderProgramDesc,
)
from .library import _check
from .marshalling import _float_ptr, _uint32


@dataclass(frozen=True)
class ShaderNode:
    """One node: its type (models.node_type(name)), up to 6 modes, the registers of up to 12
    inputs and 6 outputs, and its range of the program's data."""

    type: int
    modes: tuple[int, ...] = ()
    inputs: tuple[int, ...] = ()
    outputs: tuple[int, ...] = ()
    data_offset: int = 0
    data_count: int = 0


@dataclass
class ShaderProgram:
    nodes: list[ShaderNode] = field(default_factory=list)
    registers: list[float] = field(default_factory=lambda: [0.0] * SHADER_INPUT_REGISTERS)
    data: list[float] = field(default_factory=list)

    def key(self) -> tuple[Any, ...]:
        """A value equal for equal programs (what a live edit compares)."""
        return (tuple(self.nodes), tuple(self.registers), tuple(self.data))


@dataclass(frozen=True)
class ProgramBinding:
    material_id: int
    closure_index: int
    param: str  # a key of abi.PROGRAM_PARAMS
    program_id: int
    register_index: int


def _program_desc(program: ShaderProgram) -> tuple[_ShaderProgramDesc, list[Any]]:
    """The struct and the arrays it points into (kept alive by the caller)."""
    n = len(program.nodes)
    nodes = (_ShaderNode * max(n, 1))()
    for i, node in enumerate(program.nodes):
        d = nodes[i]
        d.type = int(node.type)
        for k, v in enumerate(node.modes):
            d.modes[k] = int(v)
        for k, v in enumerate(node.inputs):
            d.inputs[k] = _uint32(v, f"program node {i} input {k}")
        for k, v in enumerate(node.outputs):
            d.outputs[k] = _uint32(v, f"program node {i} output {k}")
        d.data_offset = _uint32(node.data_offset, f"program node {i} data_offset")
        d.data_count = _uint32(node.data_count, f"program node {i} data_count")
    registers = np.ascontiguousarray(np.asarray(program.registers, dtype=np.float32))
    data = np.ascontiguousarray(np.asarray(program.data if program.data else [0.0],
                                           dtype=np.float32))
    desc = _ShaderProgramDesc(nodes, n, _float_ptr(registers), registers.size, _float_ptr(data),
                              len(program.data))
    return desc, [nodes, registers, data]


def add_program(lib: Any, handle: Any, program: ShaderProgram) -> int:
    desc, keep = _program_desc(program)
    out = ctypes.c_uint32()
    status = lib.stratum_scene_add_shader_program(handle, ctypes.byref(desc), ctypes.byref(out))
    del keep
    _check(lib, status, "stratum_scene_add_shader_program")
    return int(out.value)


def set_program(lib: Any, handle: Any, program_id: int, program: ShaderProgram) -> None:
    desc, keep = _program_desc(program)
    status = lib.stratum_scene_set_shader_program(handle, _uint32(program_id, "program_id"),
                                                  ctypes.byref(desc))
    del keep
    _check(lib, status, "stratum_scene_set_shader_program")


def bind_program(lib: Any, handle: Any, binding: ProgramBinding) -> None:
    if binding.param not in PROGRAM_PARAMS:
        raise ValueError(f"program binding param {binding.param!r} is not one of "
                         f"{sorted(PROGRAM_PARAMS)}")
    desc = _ProgramBinding(_uint32(binding.material_id, "material_id"),
                           _uint32(binding.closure_index, "closure_index"),
                           PROGRAM_PARAMS[binding.param], _uint32(binding.program_id, "program_id"),
                           _uint32(binding.register_index, "register_index"))
    _check(lib, lib.stratum_scene_bind_program(handle, ctypes.byref(desc)),
           "stratum_scene_bind_program")


def set_background_program(lib: Any, handle: Any, program_id: int, register_index: int,
                           width: int, height: int) -> None:
    _check(lib, lib.stratum_scene_set_background_program(
        handle, _uint32(program_id, "program_id"), _uint32(register_index, "register_index"),
        _uint32(width, "width"), _uint32(height, "height")), "stratum_scene_set_background_program")


def set_light_program(lib: Any, handle: Any, light_id: int, program_id: int,
                      register_index: int) -> None:
    _check(lib, lib.stratum_scene_set_light_program(
        handle, _uint32(light_id, "light_id"), _uint32(program_id, "program_id"),
        _uint32(register_index, "register_index")), "stratum_scene_set_light_program")


def evaluate_program(lib: Any, handle: Any, program_id: int, inputs: np.ndarray, first: int,
                     count: int) -> np.ndarray:
    regs = np.zeros(SHADER_INPUT_REGISTERS, dtype=np.float32)
    flat = np.asarray(inputs, dtype=np.float32).reshape(-1)
    regs[:flat.size] = flat[:SHADER_INPUT_REGISTERS]
    out = np.zeros(max(count, 1), dtype=np.float32)
    _check(lib, lib.stratum_scene_evaluate_program(handle, _uint32(program_id, "program_id"),
                                                   _float_ptr(regs), _uint32(first, "first"),
                                                   _uint32(count, "count"), _float_ptr(out)),
           "stratum_scene_evaluate_program")
    return out[:count]


def set_mesh_texture_space(lib: Any, handle: Any, mesh_id: int, location: Any, size: Any) -> None:
    loc = np.ascontiguousarray(np.asarray(location, dtype=np.float32).reshape(3))
    half = np.ascontiguousarray(np.asarray(size, dtype=np.float32).reshape(3))
    _check(lib, lib.stratum_scene_set_mesh_texture_space(handle, _uint32(mesh_id, "mesh_id"),
                                                         _float_ptr(loc), _float_ptr(half)),
           "stratum_scene_set_mesh_texture_space")


def set_instance_object_info(lib: Any, handle: Any, first: int, random: Any, color: Any) -> None:
    arrays = []
    count = None
    for values, width in ((random, 1), (color, 4)):
        if values is None:
            arrays.append(None)
            continue
        flat = np.ascontiguousarray(np.asarray(values, dtype=np.float32).reshape(-1))
        n = flat.size // width
        if count is not None and n != count:
            raise ValueError("object info: random and color describe different instance counts")
        count = n
        arrays.append(flat)
    pointers = [_float_ptr(a) if a is not None else None for a in arrays]
    _check(lib, lib.stratum_scene_set_instance_object_info(
        handle, _uint32(first, "first"), _uint32(count or 0, "count"), *pointers),
        "stratum_scene_set_instance_object_info")


def set_light_linking(lib: Any, handle: Any, lights: bool, first: int, receiver: Any,
                      blocker: Any, light_membership: Any, shadow_membership: Any) -> None:
    arrays = []
    count = None
    for values, dtype, ctype in ((receiver, np.uint8, ctypes.c_uint8),
                                 (blocker, np.uint8, ctypes.c_uint8),
                                 (light_membership, np.uint64, ctypes.c_uint64),
                                 (shadow_membership, np.uint64, ctypes.c_uint64)):
        if values is None:
            arrays.append(None)
            continue
        flat = np.ascontiguousarray(np.asarray(values, dtype=dtype).reshape(-1))
        if count is not None and flat.size != count:
            raise ValueError("light linking: the arrays describe different counts")
        count = flat.size
        arrays.append((flat, ctype))
    pointers = [a[0].ctypes.data_as(ctypes.POINTER(a[1])) if a is not None else None
                for a in arrays]
    _check(lib, lib.stratum_scene_set_light_linking(
        handle, LINK_LIGHTS if lights else LINK_INSTANCES, _uint32(first, "first"),
        _uint32(count or 0, "count"), *pointers), "stratum_scene_set_light_linking")


def set_mesh_attribute(lib: Any, handle: Any, mesh_id: int, slot: int, vector: bool,
                       corner_rgba: Any) -> None:
    rgba = np.ascontiguousarray(np.asarray(corner_rgba, dtype=np.float32).reshape(-1))
    if rgba.size % 12:
        raise ValueError("mesh attribute: expected 12 floats (3 corners x RGBA) per triangle")
    _check(lib, lib.stratum_scene_set_mesh_attribute(
        handle, _uint32(mesh_id, "mesh_id"), _uint32(slot, "slot"), 1 if vector else 0,
        _float_ptr(rgba), rgba.size // 12), "stratum_scene_set_mesh_attribute")
