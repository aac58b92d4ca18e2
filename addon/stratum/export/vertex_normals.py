"""Vertex normals that are the same on every export of the same mesh.

Blender before 4.1 computes a mesh's vertex normals in parallel, 1024 faces per task, each
face adding its contribution to its vertices' normals with an atomic float add (3.x
mesh_normals.cc: add_v3_v3_atomic). Float addition is not
associative, so a vertex whose faces fall into two tasks gets a sum whose last bits depend on
which task ran first: the same .blend gives slightly different `vertex_normals` on every
evaluation (measured in 3.4.1: 16 different arrays in 20 evaluations of a 32 768-face
sphere), hence renders that differ in the 7th digit of a few pixels -- the determinism promise
broken by the input, not by the renderer. Face normals are computed per face (deterministic)
and Blender 4.1+ gathers each vertex's faces in a fixed order (deterministic), so only the
older versions need this module.

The normals are Blender's definition, recomputed in a fixed order by the library
(stratum_vertex_normals, native/src/scene/vertex_normals.h): a vertex's normal is the
normalized sum over its face corners of (face normal) x (the corner's interior angle), the
angle-weighted pseudo-normal of Thürmer & Wüthrich 1998 that Blender uses, evaluated in
double from Blender's float32 positions and face normals and rounded once, summed in face
order on any number of threads. It replaced a numpy evaluation (float32 corner terms): 0.3 s
single-threaded on a 1M-triangle mesh, and its bits followed the numpy build (float32 arccos
is SVML's on AVX-512 machines); the library's follow the definition to float rounding.
"""

from __future__ import annotations

import numpy as np

from .. import native
from .common import ExportError


def angle_weighted_vertex_normals(positions: np.ndarray, corner_vert: np.ndarray,
                                  loop_start: np.ndarray, loop_total: np.ndarray,
                                  face_normals: np.ndarray) -> np.ndarray | None:
    """Vertex normals (N, 3) float32 of a polygon mesh, the same floats on every call: Blender's
    definition (see the module docstring) from its arrays -- vertex positions (N, 3), the vertex
    of each face corner (L,), each face's first corner and corner count (F,), and Blender's
    face normals (F, 3). None when a face normal is not finite (a face too large for Blender's
    float32 cross product), which the exporter treats as it treats non-finite normals: the mesh
    is shaded with its geometric normals. Arrays the library refuses (Blender's never are)
    raise ExportError naming the value."""
    if not np.isfinite(face_normals).all():
        return None
    try:
        return native.vertex_normals(positions, corner_vert, loop_start, loop_total, face_normals)
    except native.StratumError as exc:
        raise ExportError(f"vertex normals: {exc}") from exc


__all__ = ["angle_weighted_vertex_normals"]
