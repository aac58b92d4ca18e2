"""Sampling without a scene: the named dimension layout, the points a sampler gives one pixel,
hemisphere warps and the blue-noise texture, exactly as a render reads them (for
`stratum points`, the compare report and the sampler tests)."""

from __future__ import annotations

import ctypes
from typing import Any

import numpy as np

from .library import _check, load_library
from .marshalling import _float_ptr, _uint32


def dimension_name(dimension: int) -> str:
    """Name of a sample dimension in the layout ("filter.x", "bounce1.bsdf.u", ...)."""
    lib = load_library()
    name = ctypes.c_char_p()
    _check(lib, lib.stratum_dimension_name(_uint32(dimension, "dimension"), ctypes.byref(name)),
           "stratum_dimension_name")
    return (name.value or b"").decode()


def camera_dimensions() -> int:
    """Dimensions before the first bounce block (filter, lens, time, ...)."""
    return int(load_library().stratum_camera_dimensions())


def bounce_dimension_stride() -> int:
    """Dimensions per bounce block; bounce k's block starts at camera_dimensions() + k * stride."""
    return int(load_library().stratum_bounce_dimension_stride())


def sampler_points(sampler: str, samples: int, seed: int, width: int, height: int,
                   pixel: tuple[int, int], dims: tuple[int, int], count: int) -> np.ndarray:
    """The first `count` samples of one pixel in two dimensions, as a (count, 2) float32 array:
    exactly what a render of width x height at `samples` spp with `seed` would read. When
    dims = (2k, 2k + 1) the sampler's 2D pair is used, as the integrators do. Indices beyond
    `samples` are allowed (every sampler is defined for any sample index)."""
    lib = load_library()
    px, py = pixel
    da, db = dims
    n = _uint32(count, "count")
    out = np.empty((n, 2), dtype=np.float32)
    status = lib.stratum_sampler_points(
        sampler.encode(), _uint32(samples, "samples"), _uint32(seed, "seed"),
        _uint32(width, "width"), _uint32(height, "height"), _uint32(px, "pixel x"),
        _uint32(py, "pixel y"), _uint32(da, "dimension"), _uint32(db, "dimension"), n,
        _float_ptr(out))
    _check(lib, status, "stratum_sampler_points")
    return out


def warp_hemisphere(distribution: str, uv: Any) -> tuple[np.ndarray, np.ndarray]:
    """Maps points of [0,1)^2 ((n, 2) array-like) through a hemisphere distribution (registry
    'hemisphere'): returns unit vectors (n, 3) with z along the normal, and their solid-angle
    densities (n,)."""
    lib = load_library()
    points = np.ascontiguousarray(np.asarray(uv, dtype=np.float32))
    if points.ndim != 2 or points.shape[1] != 2:
        raise ValueError(f"uv: expected an (n, 2) array, got shape {points.shape}")
    n = _uint32(points.shape[0], "count")
    xyz = np.empty((n, 3), dtype=np.float32)
    pdf = np.empty(n, dtype=np.float32)
    status = lib.stratum_warp_hemisphere(distribution.encode(), _float_ptr(points), n,
                                         _float_ptr(xyz), _float_ptr(pdf))
    _check(lib, status, "stratum_warp_hemisphere")
    return xyz, pdf


BLUENOISE_TEXTURE_SIZE = 128


def bluenoise_texture() -> np.ndarray:
    """The `bluenoise` sampler's void-and-cluster texture as a (128, 128) float32 array indexed
    [y, x]: (rank + 0.5)/16384 per texel, the values the sampler reads."""
    lib = load_library()
    n = BLUENOISE_TEXTURE_SIZE
    out = np.empty((n, n), dtype=np.float32)
    _check(lib, lib.stratum_bluenoise_texture(_float_ptr(out), n * n), "stratum_bluenoise_texture")
    return out
