"""Images of the `stratum compare` report: the display transform, the region to magnify
(given `crop` or the most detailed window of the reference), its exposure and magnification."""

from __future__ import annotations

import math

import numpy as np

from .report_data import Results
from .spectra import luminance


def display_transform(linear: np.ndarray, gain: float = 1.0) -> np.ndarray:
    """Display-referred RGB in [0, 1]: linear × gain, clamped to [0, 1], sRGB transfer."""
    x = np.clip(np.nan_to_num(np.asarray(linear, dtype=np.float64)[..., :3] * gain), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def detail_region(reference: np.ndarray) -> tuple[int, int, int, int]:
    """(x, y, w, h) of the quarter-size window (w = W/4, h = H/4, at least 8 px) with the
    largest sum of |∇| of the display-transformed reference luminance (integral image),
    not counting pixels next to clipped ones (a channel > 1: lights), whose edges would win."""
    lum = luminance(display_transform(reference))
    clipped = np.asarray(reference)[..., :3].max(axis=-1) > 1.0
    near = clipped.copy()
    near[1:, :] |= clipped[:-1, :]
    near[:-1, :] |= clipped[1:, :]
    near[:, 1:] |= clipped[:, :-1]
    near[:, :-1] |= clipped[:, 1:]
    h_img, w_img = lum.shape
    w, h = min(w_img, max(8, w_img // 4)), min(h_img, max(8, h_img // 4))
    grad = np.zeros_like(lum)
    grad[:, 1:] += np.abs(np.diff(lum, axis=1))
    grad[1:, :] += np.abs(np.diff(lum, axis=0))
    grad[near] = 0.0
    s = np.zeros((h_img + 1, w_img + 1))
    s[1:, 1:] = grad.cumsum(0).cumsum(1)
    sums = s[h:, w:] - s[:-h, w:] - s[h:, :-w] + s[:-h, :-w]
    y, x = np.unravel_index(int(np.argmax(sums)), sums.shape)
    return int(x), int(y), w, h


def crop_region(results: Results, reference: np.ndarray) -> tuple[tuple[int, int, int, int], str]:
    """The results' `crop` (x, y, w, h from the top-left corner, clipped to the image) if it
    is given and non-empty, else detail_region(); with a sentence saying which."""
    h_img, w_img = reference.shape[:2]
    crop = results.raw.get("crop")
    if isinstance(crop, list | tuple) and len(crop) == 4:
        try:
            x, y, w, h = (int(v) for v in crop)
            x0, y0 = max(0, min(x, w_img - 1)), max(0, min(y, h_img - 1))
            x1, y1 = max(x0 + 1, min(x + w, w_img)), max(y0 + 1, min(y + h, h_img))
            if w > 0 and h > 0:
                how = "the region given as `crop` in results.json, where the metrics were measured"
                return (x0, y0, x1 - x0, y1 - y0), how
        except (TypeError, ValueError):
            pass
    return detail_region(reference), ("no `crop` was given, so the quarter-size window with "
                                      "the most detail in the reference (largest sum of the "
                                      "luminance gradient after the display transform, clipped "
                                      "pixels such as lights and their edges left out)")


def crop_gain(reference_crop: np.ndarray) -> float:
    """Exposure for the magnified crops, a power of two in [1, 16]: brings the reference
    crop's mean luminance towards 0.18 (mid grey). The same gain for every crop."""
    mean = float(luminance(reference_crop).mean())
    if not math.isfinite(mean) or mean <= 0:
        return 1.0
    return float(2.0 ** np.clip(np.round(np.log2(0.18 / mean)), 0, 4))


def magnify(image: np.ndarray, target: int = 220) -> np.ndarray:
    """Nearest-neighbour enlargement by an integer factor so the width approaches `target`."""
    k = max(1, min(16, target // max(1, image.shape[1])))
    return np.repeat(np.repeat(image, k, axis=0), k, axis=1)
