"""Blender shader node graphs compiled into native shader programs (pure Python, no bpy).

    c = NodeCompiler(version, warn)
    register = c.value(socket, "color")
    program = c.builder.program            # native.ShaderProgram

The compiler (compiler.py) walks links through reroutes, muted nodes and node groups and
compiles each node once; each family of nodes has a module of translators (registry.py), all
imported here so that TRANSLATORS is complete. docs/shader_nodes.md lists every supported node,
its native program node and its tolerance against Cycles."""

from __future__ import annotations

from . import (  # noqa: F401  (they register their translators)
    color_nodes,
    image_node,
    input_nodes,
    math_nodes,
    noise_textures,
    pattern_textures,
    ramp_nodes,
    sky_texture,
    surface_inputs,
    surface_nodes,
    vector_nodes,
    voronoi_textures,
)
from .builder import ProgramBuilder
from .compiler import NodeCompiler, Unsupported, socket_kind
from .registry import TRANSLATORS, translator

__all__ = ["TRANSLATORS", "NodeCompiler", "ProgramBuilder", "Unsupported", "socket_kind",
           "translator"]
