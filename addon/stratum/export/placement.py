"""Which instance transforms can be rendered: finite, and not degenerate (zero scale).

A transform with a NaN or infinite element cannot be rendered: export stops with an error
naming the object and the element. A transform whose linear part is (nearly) singular -- a
linked duplicate scaled (1, 0, 1), an object scaled 1e-18 -- is skipped with a warning naming
the object, because Embree cannot trace it:

Embree intersects an instance in its object space: it maps a world ray (o, d) to
(L^-1 (o - t), L^-1 d), in float32, with L^-1 = adj(L) / det(L), and asserts that every
component of the mapped ray is at most FLT_LARGE = 1.844e18 in magnitude (kernels/common/ray.h,
RayK::valid). As |L^-1 v| <= |v| / s_min, with s_min the smallest singular value of the linear
part L, a unit direction maps to at most 1 / s_min and an origin within R of the object to at
most R / s_min. With s_min >= MIN_SCALE = 1e-9 both stay below FLT_LARGE for R up to 1.8e9
(4.8 times the Earth-Moon distance); and det(L) >= s_min^3 = 1e-27 is a normal float32, so
Embree's 1 / det(L) is finite. Below MIN_SCALE the object is 1e-9 of its modelled size along
some axis: flat or invisible in any scene such a range allows, so nothing visible is lost.
"""

from __future__ import annotations

import numpy as np

MIN_SCALE = 1e-9


def first_non_finite(matrix: np.ndarray) -> tuple[int, float] | None:
    """(row-major element index, value) of the first NaN or infinite element, or None."""
    flat = np.asarray(matrix, dtype=np.float64).reshape(16)
    bad = np.flatnonzero(~np.isfinite(flat))
    return (int(bad[0]), float(flat[bad[0]])) if len(bad) else None


def smallest_scales(matrices: np.ndarray) -> np.ndarray:
    """A lower bound of the smallest singular value of each (N, 4, 4) transform's linear
    part, exact wherever it is below MIN_SCALE (the elements must be finite).

    The bound first: s1 s2 s3 = |det L| and s1 s2 <= (s1^2 + s2^2) / 2 <= |L|_F^2 / 2 give
    s_min >= 2 |det L| / |L|_F^2, a few multiplies per row; only rows where it falls below
    MIN_SCALE get a singular value decomposition (10 000s of instances are common)."""
    linear = np.asarray(matrices, dtype=np.float64).reshape(-1, 4, 4)[:, :3, :3]
    norm2 = np.einsum("nij,nij->n", linear, linear)
    with np.errstate(divide="ignore", invalid="ignore"):
        bound = np.where(norm2 > 0.0, 2.0 * np.abs(np.linalg.det(linear)) / norm2, 0.0)
    low = np.flatnonzero(bound < MIN_SCALE)
    if len(low):
        bound[low] = np.linalg.svd(linear[low], compute_uv=False)[:, -1]
    return bound


def degenerate(matrices: np.ndarray) -> np.ndarray:
    """(N,) bool: the transforms (finite elements) that are too close to singular to trace."""
    return smallest_scales(matrices) < MIN_SCALE
