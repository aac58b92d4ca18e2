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

The normals are Blender's definition, recomputed in a fixed order: a vertex's normal is the
normalized sum over its face corners of (face normal) x (the corner's interior angle), the
angle-weighted pseudo-normal of Thürmer & Wüthrich 1998 that Blender uses. Per-corner terms
are float32 as in Blender; they are summed in float64 in corner order (np.bincount is a
sequential loop), so the result is a pure function of the mesh. Measured against Blender 3.4's
own: within 3 float32 ulps on a coarse sphere; up to 5e-6 on a 64 x 32 sphere, where it is
Blender's float32 sum that strays from the exact value (ours is within 1e-7 of a float64
evaluation).
"""

from __future__ import annotations

import numpy as np

# Vectors are handled as separate x, y, z arrays: gathers and arithmetic on contiguous
# components run several times faster than on (N, 3) rows (1M-triangle smooth mesh: 0.5 s ->
# 0.2 s). The operations and their order are those of the row-wise formulation this replaced
# (numpy's einsum "ij,ij->i"), so the floats are the same: a float32 row's squared length sums
# x^2 + y^2, then + z^2; a float64 row's sums x^2 + z^2, then + y^2 (einsum's two-lane SIMD
# accumulator, measured in numpy 1.24 and 1.26: 0 of 1M rows differ).
Components = tuple[np.ndarray, np.ndarray, np.ndarray]


def _dot(a: Components, b: Components) -> np.ndarray:
    if a[0].dtype == np.float64:
        return (a[0] * b[0] + a[2] * b[2]) + a[1] * b[1]
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _unit(v: Components) -> Components:
    """v scaled to unit length; zero vectors stay zero (Blender's normalize_v3)."""
    length = np.sqrt(_dot(v, v))
    scale = np.divide(1.0, length, out=np.zeros_like(length), where=length > 0.0)
    return v[0] * scale, v[1] * scale, v[2] * scale


def _components(rows: np.ndarray) -> Components:
    return (np.ascontiguousarray(rows[:, 0]), np.ascontiguousarray(rows[:, 1]),
            np.ascontiguousarray(rows[:, 2]))


def angle_weighted_vertex_normals(positions: np.ndarray, corner_vert: np.ndarray,
                                  loop_start: np.ndarray, loop_total: np.ndarray,
                                  face_normals: np.ndarray) -> np.ndarray:
    """Vertex normals (N, 3) float32 of a polygon mesh, the same floats on every call: Blender's
    definition (see the module docstring) from its arrays -- vertex positions (N, 3), the vertex
    of each face corner (L,), each face's first corner and corner count (F,), and Blender's
    face normals (F, 3)."""
    n_vert, n_loops = len(positions), len(corner_vert)
    start = loop_start.astype(np.int64)
    total = loop_total.astype(np.int64)
    # A face's corners are the contiguous loops start .. start + total - 1; each corner's edge
    # runs to the next corner of its face, the last corner's back to the first.
    last = start + total - 1
    next_corner = np.arange(1, n_loops + 1, dtype=np.int64)
    next_corner[last] = start
    prev_corner = np.arange(-1, n_loops - 1, dtype=np.int64)
    prev_corner[start] = last
    vert = corner_vert.astype(np.intp)
    corner_position = tuple(np.take(p, vert) for p in _components(positions))
    edge = _unit(tuple(np.take(p, next_corner) - p for p in corner_position))
    # Interior angle at a corner: between the edges to its previous and next corners, i.e.
    # acos(-(incoming edge . outgoing edge)), clamped as Blender's saacos.
    cos_angle = -_dot(tuple(np.take(e, prev_corner) for e in edge), edge)
    angle = np.arccos(np.clip(cos_angle, -1.0, 1.0)).astype(np.float32)
    # Per corner the float32 term (face normal) x angle, summed per vertex in float64 in corner
    # order (np.bincount is a sequential loop).
    summed = tuple(np.bincount(vert, weights=np.repeat(f, total) * angle, minlength=n_vert)
                   for f in _components(face_normals))
    normals = np.stack(_unit(summed), axis=1)
    # Blender's fallback for a vertex whose contributions cancel (or that has no face): its
    # position as a direction.
    zero = ~normals.any(axis=1)
    if zero.any():
        normals[zero] = np.stack(_unit(_components(positions[zero].astype(np.float64))), axis=1)
    return normals.astype(np.float32)


__all__ = ["angle_weighted_vertex_normals"]
