"""Geometry computed by the library without a scene: the angle-weighted vertex normals of a
polygon mesh (stratum_vertex_normals), the same bits on every call and for any thread count."""

from __future__ import annotations

import numpy as np

from .library import _check, load_library
from .marshalling import _float_ptr, _uint32, _uint_ptr


def vertex_normals(positions: np.ndarray, corner_vertices: np.ndarray, face_starts: np.ndarray,
                   face_sizes: np.ndarray, face_normals: np.ndarray,
                   threads: int = 0) -> np.ndarray:
    """Vertex normals (N, 3) float32 of a polygon mesh: positions (N, 3), the vertex of each
    face corner (L,), each face's first corner and corner count (F,), face normals (F, 3).
    Each normal is the normalised sum over the vertex's corners of (face normal) x (interior
    angle), Blender 3.x's definition (stratum.h). `threads` 0 uses every core; the result is
    the same for any count. Bad input raises StratumError naming the value."""
    lib = load_library()
    p = np.ascontiguousarray(positions, dtype=np.float32).reshape(-1, 3)
    corners = np.ascontiguousarray(corner_vertices, dtype=np.uint32).reshape(-1)
    starts = np.ascontiguousarray(face_starts, dtype=np.uint32).reshape(-1)
    sizes = np.ascontiguousarray(face_sizes, dtype=np.uint32).reshape(-1)
    normals = np.ascontiguousarray(face_normals, dtype=np.float32).reshape(-1, 3)
    if not len(starts) == len(sizes) == len(normals):
        raise ValueError(f"vertex_normals: {len(starts)} face starts, {len(sizes)} face sizes and "
                         f"{len(normals)} face normals")
    out = np.empty_like(p)
    status = lib.stratum_vertex_normals(
        _uint32(len(p), "vertex count"), _float_ptr(p), _uint32(len(starts), "face count"),
        _uint_ptr(starts), _uint_ptr(sizes), _float_ptr(normals),
        _uint32(len(corners), "corner count"), _uint_ptr(corners), _uint32(threads, "threads"),
        _float_ptr(out))
    _check(lib, status, "stratum_vertex_normals")
    return out


__all__ = ["vertex_normals"]
