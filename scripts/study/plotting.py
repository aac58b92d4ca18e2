"""What every figure of the study is drawn with: matplotlib on its file-only backend, and linear
images turned into 8-bit sRGB for display."""

from __future__ import annotations

from typing import Any


def pyplot() -> Any:
    """matplotlib.pyplot on the file-only Agg backend (no display on the study's machines)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def srgb8(linear: Any) -> Any:
    """Linear RGB clipped to [0, 1] and encoded with the sRGB transfer function, as uint8."""
    import numpy as np

    x = np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0)
    s = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)
    return (s * 255.0 + 0.5).astype(np.uint8)
