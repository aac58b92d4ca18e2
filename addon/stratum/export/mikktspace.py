"""MikkTSpace tangents of a triangle mesh, computed here so that they are the same bits on every
export (pure numpy; no bpy).

Blender's Mesh.calc_tangents cannot be used: it works from normals Blender computes in parallel
(before 4.1 with atomic float adds) and its own MikkTSpace merges vertices in a parallel order,
so the last bits of the tangents change from one call to the next (measured: 20 different
arrays in 20 exports of a 32k-face sphere in 3.4, 2 in 5.0), and so would the image. Cycles
runs MikkTSpace on its triangles with the vertex normal of smooth triangles and the face normal
of flat ones (scene/mesh.cpp mikk_compute_tangents); this module takes the same inputs.

| step       | what MikkTSpace does (Mikkelsen 2008, mikktspace.c)                          |
|------------|------------------------------------------------------------------------------|
| weld       | corners equal in position, normal and UV are one vertex                      |
| face frame | vOs = t31.v d1 - t21.v d2 (dP/du times twice the UV area), normalised, times |
|            | the orientation s = sign(t21.u t31.v - t21.v t31.u); zero UV area adds none  |
| groups     | a vertex's faces of one orientation share a tangent                          |
| tangent    | normalize(sum over the group of angle_c normalize(vOs - (n.vOs) n)), angle_c |
|            | the corner's angle between its edges projected on the normal's plane         |
| sign       | +1 for orientation-preserving groups, -1 otherwise                           |

Difference from MikkTSpace: its groups also split a vertex's faces of one orientation that
touch only at the vertex (no shared edge); here they share one tangent.
"""

from __future__ import annotations

import numpy as np


def _normalized(v: np.ndarray) -> np.ndarray:
    """Rows of v made unit; zero rows stay zero (MikkTSpace normalises only when non-zero)."""
    length = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.divide(v, length, out=np.zeros_like(v), where=length > 0.0)


def _projected(v: np.ndarray, n: np.ndarray) -> np.ndarray:
    return _normalized(v - np.sum(v * n, axis=-1, keepdims=True) * n)


def tangent_space_normals(positions: np.ndarray, triangles: np.ndarray,
                   corner_normals: np.ndarray | None,
                   vertex_normals: np.ndarray | None) -> np.ndarray:
    """(T, 3, 3) unit normals per triangle corner from what a mesh export holds: split normals,
    else vertex normals, else the face normal (a flat mesh)."""
    if corner_normals is not None:
        n = np.asarray(corner_normals, dtype=np.float64).reshape(-1, 3, 3)
    elif vertex_normals is not None:
        n = np.asarray(vertex_normals, dtype=np.float64)[triangles]
    else:
        p = np.asarray(positions, dtype=np.float64)[triangles]
        face = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        n = np.repeat(face[:, None, :], 3, axis=1)
    return _normalized(n)


def mikktspace_tangents(positions: np.ndarray, triangles: np.ndarray, normals: np.ndarray,
                        uvs: np.ndarray) -> np.ndarray:
    """(T, 3, 4) float32: per triangle corner the unit tangent (object space) and the bitangent
    sign. positions (V, 3), triangles (T, 3), normals (T, 3, 3) per corner, uvs (T, 3, 2)."""
    tris = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    n_tri = len(tris)
    out = np.zeros((n_tri, 3, 4), dtype=np.float32)
    if n_tri == 0:
        return out
    p32 = np.asarray(positions, dtype=np.float32)[tris]  # (T, 3, 3)
    n32 = np.asarray(normals, dtype=np.float32).reshape(n_tri, 3, 3)
    uv32 = np.asarray(uvs, dtype=np.float32).reshape(n_tri, 3, 2)
    p, n, uv = p32.astype(np.float64), n32.astype(np.float64), uv32.astype(np.float64)

    # Face frames.
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    t21, t31 = uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0]
    area = t21[:, 0] * t31[:, 1] - t21[:, 1] * t31[:, 0]
    v_os = t31[:, 1:2] * d1 - t21[:, 1:2] * d2
    v_ot = -t31[:, 0:1] * d1 + t21[:, 0:1] * d2
    preserving = area > 0.0
    orientation = np.where(preserving, 1.0, -1.0)
    contributes = (area != 0.0) & (np.linalg.norm(v_os, axis=1) > 0.0) & \
        (np.linalg.norm(v_ot, axis=1) > 0.0)
    v_os = _normalized(v_os) * orientation[:, None]

    # Weld: one id per distinct (position, normal, UV) bit pattern; groups split it by orientation.
    keys = np.concatenate([p32, n32, uv32], axis=2).reshape(n_tri * 3, 8)
    keys = np.ascontiguousarray(keys).view(np.dtype((np.void, 32))).ravel()
    _, weld = np.unique(keys, return_inverse=True)
    weld = weld.reshape(n_tri, 3)
    group = weld * 2 + preserving[:, None].astype(np.int64)

    # Angle-weighted projected face tangents, summed per group in corner order.
    corner_tangent = _projected(np.repeat(v_os[:, None, :], 3, axis=1), n)
    edge_prev = _projected(np.roll(p, 1, axis=1) - p, n)
    edge_next = _projected(np.roll(p, -1, axis=1) - p, n)
    angle = np.arccos(np.clip(np.sum(edge_prev * edge_next, axis=2), -1.0, 1.0))
    weight = np.where(contributes[:, None], angle, 0.0)
    n_groups = int(group.max()) + 1
    flat_group = group.ravel()
    summed = np.stack([np.bincount(flat_group, (weight * corner_tangent[..., k]).ravel(),
                                   minlength=n_groups) for k in range(3)], axis=1)
    has_sum = np.bincount(flat_group, weight.ravel(), minlength=n_groups) > 0.0

    # A corner of a face that adds nothing (zero UV area) takes its vertex's group of the other
    # orientation when its own group is empty, as MikkTSpace hands degenerate faces the frame
    # of a neighbour; with neither, the tangent stays zero (the normal map then keeps N).
    other = group ^ 1
    use_other = ~has_sum[group] & has_sum[np.minimum(other, n_groups - 1)] & (other < n_groups)
    chosen = np.where(use_other, other, group)
    out[..., :3] = _normalized(summed[chosen]).astype(np.float32)
    out[..., 3] = np.where(chosen & 1, 1.0, -1.0).astype(np.float32)
    return out
