"""Image error metrics, confidence intervals over seeds, convergence slopes and the
reference's noise floor. Pure numpy (FLIP through flip_evaluator, imported lazily).

Definitions (all on the comparison region, float64, over pixels and the three RGB channels):

* MSE     = mean((img - ref)^2)
* relMSE  = mean((img - ref)^2 / (ref^2 + REL_MSE_EPSILON)), REL_MSE_EPSILON = 1e-2
* LDR-FLIP: both images are display-transformed first: linear values clamped to [0, 1], then
  the sRGB transfer function (12.92 x below 0.0031308, else 1.055 x^(1/2.4) - 0.055); the
  mean of flip_evaluator's LDR error map.
* HDR-FLIP: the mean of flip_evaluator's HDR error map on the linear images (negative values,
  which a path tracer does not produce, are clamped to 0 as HDR-FLIP requires).
* Noise floor of a reference that is the mean of R renders: per pixel, the variance of the mean
  is s^2 / R (s^2 the sample variance across the R renders, ddof=1); the MSE floor is the mean
  of that over pixels and channels, the relMSE floor the mean of (s^2 / R) / (ref^2 + eps).
  An image as noisy as the reference itself measures about that much MSE against it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

REL_MSE_EPSILON = 1e-2
NOISE_FLOOR_FACTOR = 3.0

Crop = tuple[int, int, int, int]


def crop_region(image: np.ndarray, crop: Crop | None) -> np.ndarray:
    """The (x, y, w, h) region of an (H, W, C) image, x from the left and y from the top."""
    if crop is None:
        return image
    x, y, w, h = crop
    return image[y:y + h, x:x + w]


def mse(image: np.ndarray, reference: np.ndarray) -> float:
    d = np.asarray(image, dtype=np.float64) - np.asarray(reference, dtype=np.float64)
    return float(np.mean(d * d))


def rel_mse(image: np.ndarray, reference: np.ndarray) -> float:
    ref = np.asarray(reference, dtype=np.float64)
    d = np.asarray(image, dtype=np.float64) - ref
    return float(np.mean(d * d / (ref * ref + REL_MSE_EPSILON)))


def srgb_display(linear: np.ndarray) -> np.ndarray:
    """The display transform used for LDR-FLIP: clamp to [0, 1], then the sRGB transfer."""
    x = np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0)
    out = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)
    return out.astype(np.float32)


def flip_ldr(image: np.ndarray, reference: np.ndarray) -> float:
    import flip_evaluator

    _, mean, _ = flip_evaluator.evaluate(srgb_display(reference), srgb_display(image), "LDR",
                                         applyMagma=False)
    return float(mean)


def flip_hdr(image: np.ndarray, reference: np.ndarray) -> float:
    import flip_evaluator

    ref = np.ascontiguousarray(np.maximum(reference, 0.0), dtype=np.float32)
    test = np.ascontiguousarray(np.maximum(image, 0.0), dtype=np.float32)
    _, mean, _ = flip_evaluator.evaluate(ref, test, "HDR", applyMagma=False)
    return float(mean)


def all_metrics(image: np.ndarray, reference: np.ndarray) -> dict[str, float]:
    return {"mse": mse(image, reference), "rel_mse": rel_mse(image, reference),
            "flip_ldr": flip_ldr(image, reference), "flip_hdr": flip_hdr(image, reference)}


def reference_noise_floor(renders: Sequence[np.ndarray], crop: Crop | None = None
                          ) -> tuple[np.ndarray, dict[str, float | None]]:
    """Mean image of R renders (full size) and the noise floor of MSE and relMSE against it on
    the crop region (None when R < 2: the spread cannot be estimated)."""
    stack = np.stack([np.asarray(r, dtype=np.float64) for r in renders])
    mean = stack.mean(axis=0)
    if len(renders) < 2:
        return mean, {"mse": None, "rel_mse": None}
    var_of_mean = crop_region(stack.var(axis=0, ddof=1), crop) / len(renders)
    ref = crop_region(mean, crop)
    return mean, {"mse": float(var_of_mean.mean()),
                  "rel_mse": float(np.mean(var_of_mean / (ref * ref + REL_MSE_EPSILON)))}


# Student t quantiles t_{0.975, df} for df = 1..30 (two-sided 95 %).
_T975 = (12.706205, 4.302653, 3.182446, 2.776445, 2.570582, 2.446912, 2.364624, 2.306004,
         2.262157, 2.228139, 2.200985, 2.178813, 2.160369, 2.144787, 2.131450, 2.119905,
         2.109816, 2.100922, 2.093024, 2.085963, 2.079614, 2.073873, 2.068658, 2.063899,
         2.059539, 2.055529, 2.051831, 2.048407, 2.045230, 2.042272)
# Beyond 30, interpolated linearly in 1/df between these (df = inf is the normal quantile).
_T975_TAIL = ((30, 2.042272), (40, 2.021075), (60, 2.000298), (120, 1.979930),
              (math.inf, 1.959964))


def t975(df: int) -> float:
    """The 0.975 quantile of Student's t with df degrees of freedom (df >= 1)."""
    if df < 1:
        raise ValueError(f"degrees of freedom must be >= 1, got {df}")
    if df <= 30:
        return _T975[df - 1]
    for (d0, t0), (d1, t1) in zip(_T975_TAIL, _T975_TAIL[1:], strict=False):
        if df <= d1:
            a, b, x = 1.0 / d0, (0.0 if math.isinf(d1) else 1.0 / d1), 1.0 / df
            return t0 + (t1 - t0) * (a - x) / (a - b)
    return _T975_TAIL[-1][1]


def mean_ci95(values: Sequence[float]) -> tuple[float, float, float]:
    """(mean, low, high): mean +- t_{0.975, n-1} s / sqrt(n); n = 1 gives (v, v, v)."""
    v = np.asarray(values, dtype=np.float64)
    if v.size == 0:
        raise ValueError("no values")
    m = float(v.mean())
    if v.size == 1:
        return m, m, m
    half = t975(v.size - 1) * float(v.std(ddof=1)) / math.sqrt(v.size)
    return m, m - half, m + half


def loglog_slope(x: Sequence[float], y: Sequence[float]) -> float | None:
    """Least-squares slope of log(y) against log(x); None with fewer than two usable points
    (both coordinates must be > 0 and finite)."""
    xs = np.asarray(x, dtype=np.float64)
    ys = np.asarray(y, dtype=np.float64)
    ok = (xs > 0) & (ys > 0) & np.isfinite(xs) & np.isfinite(ys)
    lx, ly = np.log(xs[ok]), np.log(ys[ok])
    if lx.size < 2 or np.ptp(lx) == 0:
        return None
    lx = lx - lx.mean()
    return float(np.dot(lx, ly - ly.mean()) / np.dot(lx, lx))
