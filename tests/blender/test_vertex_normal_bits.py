"""export/vertex_normals.py computes on x, y, z component arrays for speed; the floats must stay
those of the row-wise formulation it replaced (renders of smooth meshes in Blender < 4.1 are
recorded bit for bit in test_image_hashes). The row-wise formulation is kept here as the
reference, evaluated on random polygon meshes that reach its edge cases: faces of 3 to 6
corners, repeated vertices, zero-length edges, zero face normals, vertices without faces, and
coordinates from 1e-3 to 1e3."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest


def _unit_rows(v: np.ndarray) -> np.ndarray:
    length = np.sqrt(np.einsum("ij,ij->i", v, v))
    scale = np.divide(1.0, length, out=np.zeros_like(length), where=length > 0.0)
    return v * scale[:, None]


def _row_wise_normals(positions: np.ndarray, corner_vert: np.ndarray, loop_start: np.ndarray,
                      loop_total: np.ndarray, face_normals: np.ndarray) -> np.ndarray:
    n_vert, n_loops = len(positions), len(corner_vert)
    start = loop_start.astype(np.int64)
    total = loop_total.astype(np.int64)
    last = start + total - 1
    next_corner = np.arange(1, n_loops + 1, dtype=np.int64)
    next_corner[last] = start
    prev_corner = np.arange(-1, n_loops - 1, dtype=np.int64)
    prev_corner[start] = last
    corner_position = positions[corner_vert]
    edge = _unit_rows(corner_position[next_corner] - corner_position)
    cos_angle = -np.einsum("ij,ij->i", edge[prev_corner], edge)
    angle = np.arccos(np.clip(cos_angle, -1.0, 1.0)).astype(np.float32)
    summed = np.stack([
        np.bincount(corner_vert, weights=np.repeat(face_normals[:, k], total) * angle,
                    minlength=n_vert)
        for k in range(3)
    ], axis=1)
    normals = _unit_rows(summed)
    zero = ~normals.any(axis=1)
    if zero.any():
        normals[zero] = _unit_rows(positions[zero].astype(np.float64))
    return normals.astype(np.float32)


def _random_mesh(seed: int) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    n_vert = 5000
    scale = rng.choice([1e-3, 1.0, 1e3], size=(n_vert, 1))
    positions = (rng.normal(size=(n_vert, 3)) * scale).astype(np.float32)
    positions[:20] = 0.0  # zero-length edges and a zero position (the fallback's zero vector)
    total = rng.integers(3, 7, size=12000).astype(np.int32)
    # Vertices 4000 on have no face: their normal is their position's direction.
    corner_vert = rng.integers(0, 4000, size=int(total.sum())).astype(np.uint32)
    corner_vert[:600] = corner_vert[600:1200]  # repeated vertices within and across faces
    start = np.concatenate([[0], np.cumsum(total)[:-1]]).astype(np.int32)
    face_normals = rng.normal(size=(len(total), 3)).astype(np.float32)
    face_normals /= np.linalg.norm(face_normals, axis=1, keepdims=True)
    face_normals[:30] = 0.0
    return positions, corner_vert, start, total, face_normals


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_vertex_normals_are_the_row_wise_floats(stratum_addon: Any, seed: int) -> None:
    from stratum.export.vertex_normals import angle_weighted_vertex_normals

    inputs = _random_mesh(seed)
    ours = angle_weighted_vertex_normals(*inputs)
    reference = _row_wise_normals(*inputs)
    differ = np.flatnonzero((ours.view(np.uint32) != reference.view(np.uint32)).any(axis=1))
    assert len(differ) == 0, (f"{len(differ)} vertices differ, first {differ[0]}: "
                              f"{ours[differ[0]]} vs {reference[differ[0]]}")
