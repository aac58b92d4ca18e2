"""Power spectra of images for the `stratum compare` report (numpy only, no matplotlib).

Conventions (the same as tests/native/sampling/test_bluenoise.cpp and the zsobol error-spectrum
test in tests/native/sampling/test_sobol_samplers.cpp):

* the image's mean is removed and the DC term excluded;
* power = |DFT|² / (H·W), so for white noise of variance σ² every frequency has expected
  power σ² (Parseval), and the radially averaged spectrum of white noise is flat at σ²;
* frequencies are in cycles per pixel, (f_x, f_y) = (k_x / W, k_y / H) with k in
  [−W/2, W/2), so |f| ≤ 1/8 is the disc |k| ≤ W/8 of the native tests on a W × W image;
* low-frequency ratio = mean power over 0 < |f| ≤ 1/8 divided by the mean power over every
  f ≠ 0. White noise gives ≈ 1; blue noise (error pushed to high frequencies) gives < 1.
"""

from __future__ import annotations

import numpy as np

# Radius of the low-frequency disc, in cycles per pixel: W/8 for a W x W image.
LOW_FREQUENCY_RADIUS = 1.0 / 8.0

# Rec. 709 / sRGB luminance weights of linear RGB.
LUMINANCE_WEIGHTS = np.array([0.2126, 0.7152, 0.0722])


def luminance(image: np.ndarray) -> np.ndarray:
    """Linear luminance of an (H, W, ≥3) RGB(A) image; an (H, W) image is returned as is."""
    a = np.asarray(image, dtype=np.float64)
    if a.ndim == 2:
        return a
    if a.ndim != 3 or a.shape[2] < 3:
        raise ValueError(f"expected an (H, W) or (H, W, >=3) image, got shape {a.shape}")
    return a[..., :3] @ LUMINANCE_WEIGHTS


def _frequency_radius(shape: tuple[int, int]) -> np.ndarray:
    """|f| in cycles per pixel for every bin of an unshifted 2D DFT of an image of `shape`."""
    h, w = shape
    fy = np.fft.fftfreq(h)[:, None]
    fx = np.fft.fftfreq(w)[None, :]
    return np.sqrt(fx * fx + fy * fy)


def power_spectrum(image: np.ndarray) -> np.ndarray:
    """|DFT(image − mean)|² / (H·W) of a 2D image, unshifted (DC at [0, 0])."""
    a = np.asarray(image, dtype=np.float64)
    if a.ndim != 2 or a.size == 0:
        raise ValueError(f"expected a non-empty 2D image, got shape {a.shape}")
    spectrum = np.fft.fft2(a - a.mean())
    return (spectrum.real**2 + spectrum.imag**2) / a.size


def low_frequency_ratio(image: np.ndarray, radius: float = LOW_FREQUENCY_RADIUS) -> float:
    """Mean power within 0 < |f| ≤ radius (cycles per pixel; 1/8 = W/8) over the mean power at
    every f ≠ 0. ≈ 1 for white noise, ≪ 1 for blue noise; nan for an image too small to have
    a low-frequency bin or with zero power."""
    power = power_spectrum(image)
    r = _frequency_radius(power.shape)
    nonzero = r > 0
    low = nonzero & (r <= radius + 1e-12)
    if not low.any() or not nonzero.any():
        return float("nan")
    overall = float(power[nonzero].mean())
    if overall <= 0.0:
        return float("nan")
    return float(power[low].mean() / overall)


def radial_average(image: np.ndarray, bins: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Radially averaged power spectrum of a 2D image: (centres, mean power) of `bins` equal
    rings over 0 < |f| ≤ 1/2 cycles per pixel (the corners beyond the Nyquist circle are left
    out). Empty rings (tiny images) are nan."""
    if bins < 1:
        raise ValueError("bins must be >= 1")
    power = power_spectrum(image)
    r = _frequency_radius(power.shape)
    keep = (r > 0) & (r <= 0.5)
    # Ring index: (0, 1/(2 bins)] -> 0, ..., ((bins-1)/(2 bins), 1/2] -> bins - 1.
    index = np.clip(np.ceil(r[keep] * 2 * bins).astype(np.int64) - 1, 0, bins - 1)
    total = np.bincount(index, weights=power[keep], minlength=bins)
    count = np.bincount(index, minlength=bins)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    centres = (np.arange(bins) + 0.5) / (2 * bins)
    return centres, mean


def error_image(render: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """Luminance of render − reference (linear), as a 2D float64 array."""
    r, ref = np.asarray(render), np.asarray(reference)
    if r.shape[:2] != ref.shape[:2]:
        raise ValueError(f"render {r.shape} and reference {ref.shape} differ in size")
    return luminance(r) - luminance(ref)
