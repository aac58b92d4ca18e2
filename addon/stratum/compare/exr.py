"""Linear RGB EXR files as float32 (H, W, 3) numpy arrays, through the OpenEXR 3.x module.

Rows are stored top to bottom (as Blender writes them). Writes go to a temporary name in the
same folder and are renamed last, so a crash never leaves a half-written file under the final
name.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np


class ExrError(Exception):
    """An EXR file is missing, unreadable or has no RGB channels."""


def read_rgb(path: str | os.PathLike[str]) -> np.ndarray:
    """The R, G, B channels of an EXR as float32 (H, W, 3); raises ExrError with the reason."""
    import OpenEXR

    path = Path(path)
    if not path.is_file():
        raise ExrError(f"EXR file not found: {path}")
    try:
        with OpenEXR.File(str(path), separate_channels=True) as f:
            channels = f.channels()
            planes = []
            for name in ("R", "G", "B"):
                if name not in channels:
                    raise ExrError(f"{path}: no {name} channel (has {sorted(channels)})")
                planes.append(np.asarray(channels[name].pixels, dtype=np.float32))
    except ExrError:
        raise
    except Exception as exc:  # noqa: BLE001 - OpenEXR raises plain exceptions on bad files
        raise ExrError(f"cannot read EXR {path}: {exc}") from exc
    return np.ascontiguousarray(np.stack(planes, axis=-1))


def write_rgb(path: str | os.PathLike[str], image: np.ndarray) -> None:
    """Writes float32 (H, W, 3) linear RGB as a 32-bit float EXR, atomically (temp + rename)."""
    import OpenEXR

    path = Path(path)
    data = np.ascontiguousarray(np.asarray(image, dtype=np.float32))
    if data.ndim != 3 or data.shape[2] != 3:
        raise ValueError(f"expected an (H, W, 3) image, got shape {data.shape}")
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    channels = {name: np.ascontiguousarray(data[..., i]) for i, name in enumerate("RGB")}
    tmp = path.with_name(f".tmp-{os.getpid()}-{path.name}")
    try:
        with OpenEXR.File(header, channels) as f:
            f.write(str(tmp))
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
