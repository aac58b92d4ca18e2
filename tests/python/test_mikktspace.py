"""stratum.export.mikktspace against closed forms: on a flat grid with affine UVs every MikkTSpace
tangent is the unit dP/du and the sign the UV orientation; zero-UV-area faces borrow their
vertex's tangent; the same input gives the same bits."""

from __future__ import annotations

import numpy as np
from stratum.export.mikktspace import mikktspace_tangents, tangent_space_normals


def _grid(n: int = 4) -> tuple[np.ndarray, np.ndarray]:
    xs, ys = np.meshgrid(np.arange(n + 1, dtype=np.float32), np.arange(n + 1, dtype=np.float32))
    positions = np.stack([xs.ravel(), ys.ravel(), np.zeros(xs.size, np.float32)], axis=1)
    tris = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            tris += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
    return positions, np.array(tris, dtype=np.uint32)


def _uvs(positions: np.ndarray, triangles: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    return (positions[triangles][..., :2] @ matrix.T).astype(np.float32)


def test_affine_uvs_give_the_unit_dp_du_and_the_orientation() -> None:
    positions, triangles = _grid()
    normals = tangent_space_normals(positions, triangles, None, None)
    for matrix, sign in ((np.array([[0.5, 0.2], [-0.1, 0.4]]), 1.0),
                         (np.array([[-0.5, 0.0], [0.0, 0.3]]), -1.0)):
        t = mikktspace_tangents(positions, triangles, normals, _uvs(positions, triangles, matrix))
        # uv = M p_xy, so p_xy = M^-1 uv and dP/du is the first column of M^-1.
        dp_du = np.linalg.inv(matrix)[:, 0]
        expected = np.array([*dp_du, 0.0]) / np.linalg.norm(dp_du)
        assert np.abs(t[..., :3] - expected).max() < 1e-6
        assert (t[..., 3] == sign).all()


def test_smooth_normals_make_tangents_unit_and_orthogonal() -> None:
    positions, triangles = _grid()
    positions[:, 2] = 0.1 * np.sin(positions[:, 0]) * np.cos(positions[:, 1])
    rng = np.random.default_rng(7)
    vertex_normals = np.array([0.0, 0.0, 1.0]) + 0.2 * rng.standard_normal((len(positions), 3))
    normals = tangent_space_normals(positions, triangles, None, vertex_normals)
    uvs = _uvs(positions, triangles, np.eye(2) * 0.25)
    t = mikktspace_tangents(positions, triangles, normals, uvs)
    assert np.abs(np.linalg.norm(t[..., :3], axis=2) - 1.0).max() < 1e-6
    assert np.abs(np.sum(t[..., :3] * normals, axis=2)).max() < 1e-6
    again = mikktspace_tangents(positions.copy(), triangles.copy(), normals.copy(), uvs.copy())
    assert again.tobytes() == t.tobytes()


def test_a_zero_uv_area_face_takes_its_vertex_tangent() -> None:
    positions, triangles = _grid(2)
    uvs = _uvs(positions, triangles, np.eye(2))
    uvs[0] = uvs[0][0]  # face 0 collapses to a point in UV space
    normals = tangent_space_normals(positions, triangles, None, None)
    t = mikktspace_tangents(positions, triangles, normals, uvs)
    # Its first corner keeps its true UV and welds with face 1's corner there: it borrows +x
    # and the sign of that group. The other two weld with nothing and keep a zero tangent
    # (the normal map then keeps the normal). Every other face keeps +x.
    x = np.array([1.0, 0.0, 0.0])
    assert np.abs(t[1:, :, :3] - x).max() < 1e-6
    assert np.abs(t[0, 0, :3] - x).max() < 1e-6 and t[0, 0, 3] == 1.0
    assert not t[0, 1:, :3].any()
