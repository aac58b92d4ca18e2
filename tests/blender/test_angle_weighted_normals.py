"""The exporter's vertex normals (Blender < 4.1: export/vertex_normals.py, computed by the
library's stratum_vertex_normals) against a straightforward float64 evaluation of their
definition, on random polygon meshes that reach its edge cases: faces of 3 to 6 corners,
repeated vertices, zero-length edges, zero face normals, vertices without faces (one at the
origin), and coordinates from 1e-3 to 1e3; and the same bits for any thread count. Runs in both
Blenders (their numpy builds differ; the normals must not)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

U = 2.0**-53  # float64 unit roundoff


def _random_mesh(seed: int) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    n_vert = 5000
    scale = rng.choice([1e-3, 1.0, 1e3], size=(n_vert, 1))
    positions = (rng.normal(size=(n_vert, 3)) * scale).astype(np.float32)
    positions[:20] = 0.0  # zero-length edges
    positions[-1] = 0.0  # a vertex without faces at the origin: its normal stays zero
    total = rng.integers(3, 7, size=12000).astype(np.uint32)
    # Vertices 4000 on have no face: their normal is their position's direction.
    corner_vert = rng.integers(0, 4000, size=int(total.sum())).astype(np.uint32)
    corner_vert[:600] = corner_vert[600:1200]  # repeated vertices within and across faces
    start = np.concatenate([[0], np.cumsum(total)[:-1]]).astype(np.uint32)
    face_normals = rng.normal(size=(len(total), 3)).astype(np.float32)
    face_normals /= np.linalg.norm(face_normals, axis=1, keepdims=True)
    face_normals[:30] = 0.0
    return positions, corner_vert, start, total, face_normals


def _reference(positions: np.ndarray, corner_vert: np.ndarray, start: np.ndarray,
               total: np.ndarray, face_normals: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The definition (stratum.h, stratum_vertex_normals) in float64, corner by corner, and a
    bound per vertex on |library - reference|. A corner's cosine (rounded differences, two
    normalisations, a dot product) is off by about 10 u in either evaluation, so its angle by
    10 u / sin(theta) + u theta (acos' derivative, then rounding): twice that for the two
    evaluations, summed over the vertex's corners (unit face normals) with the sums' own
    rounding (64 u per unit of angle, generous for 3-term sums over a few corners), moves the
    unit result by at most 2 |delta| / |s|; then float32 rounding, half an ulp: 2^-25 below 1."""
    p = positions.astype(np.float64)
    face = np.repeat(np.arange(len(start)), total)
    first = np.repeat(start.astype(np.int64), total)
    k = np.arange(len(corner_vert)) - first
    size = np.repeat(total.astype(np.int64), total)
    here = p[corner_vert]
    prev = p[corner_vert[first + (k - 1) % size]]
    nxt = p[corner_vert[first + (k + 1) % size]]
    a, b = prev - here, nxt - here
    la, lb = np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1)
    nonzero = (la > 0) & (lb > 0)
    cosine = np.zeros(len(a))
    cosine[nonzero] = (a * b).sum(axis=1)[nonzero] / (la * lb)[nonzero]
    theta = np.arccos(np.clip(cosine, -1.0, 1.0))
    terms = face_normals[face].astype(np.float64) * theta[:, None]
    summed = np.zeros_like(p)
    np.add.at(summed, corner_vert, terms)
    sine = np.sqrt(np.maximum(0.0, 1.0 - cosine * cosine))
    corner_slack = 2 * (np.minimum(4.0, 10 * U / np.maximum(sine, 1e-300)) + U * theta) + 64 * U * theta
    slack = np.bincount(corner_vert, weights=corner_slack, minlength=len(p))
    length = np.linalg.norm(summed, axis=1)
    zero = length == 0
    summed[zero] = p[zero]
    slack[zero] = 0.0
    length = np.linalg.norm(summed, axis=1)
    unit = np.divide(summed, length[:, None], out=np.zeros_like(summed), where=length[:, None] > 0)
    bound = np.divide(2 * slack, length, out=np.zeros_like(length), where=length > 0) + 2.0**-25
    return unit, bound


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_vertex_normals_follow_their_definition_to_float_rounding(stratum_addon: Any,
                                                                  seed: int) -> None:
    from stratum.export.vertex_normals import angle_weighted_vertex_normals

    inputs = _random_mesh(seed)
    ours = angle_weighted_vertex_normals(*inputs)
    assert ours is not None and ours.dtype == np.float32
    reference, bound = _reference(*inputs)
    error = np.abs(ours.astype(np.float64) - reference).max(axis=1)
    worst = int(np.argmax(error / bound))
    assert (error <= bound).all(), (
        f"vertex {worst}: ours {ours[worst]}, definition {reference[worst]}, "
        f"|difference| {error[worst]:.3g} > {bound[worst]:.3g}")
    assert not ours[-1].any()  # the origin without faces


def test_vertex_normals_are_the_same_bits_for_any_thread_count(stratum_addon: Any) -> None:
    from stratum import native

    inputs = _random_mesh(4)
    first = native.vertex_normals(*inputs, threads=1)
    for threads in (2, 7, 0):
        other = native.vertex_normals(*inputs, threads=threads)
        assert first.tobytes() == other.tobytes(), f"{threads} threads differ from 1"


def test_non_finite_face_normals_give_no_vertex_normals(stratum_addon: Any) -> None:
    """A face too large for Blender's float32 cross product has a non-finite normal: the
    exporter then sends no vertex normals (the mesh is shaded with its geometric normals), as it
    does for other non-finite normals, instead of failing the export."""
    from stratum.export.vertex_normals import angle_weighted_vertex_normals

    positions, corner_vert, start, total, face_normals = _random_mesh(5)
    face_normals[7] = np.nan
    assert angle_weighted_vertex_normals(positions, corner_vert, start, total,
                                         face_normals) is None


def test_refused_arrays_raise_an_export_error_naming_the_value(stratum_addon: Any) -> None:
    from stratum.export.common import ExportError
    from stratum.export.vertex_normals import angle_weighted_vertex_normals

    positions, corner_vert, start, total, face_normals = _random_mesh(6)
    corner_vert[11] = len(positions)
    with pytest.raises(ExportError, match=f"corner 11 vertex index {len(positions)} out of range"):
        angle_weighted_vertex_normals(positions, corner_vert, start, total, face_normals)
