"""Texture loading time (issue 12): stratum_scene_add_texture on 4096^2 and 8192^2 8-bit PNGs
and an 8192^2 float EXR-like pixel array, per colour space, each the minimum of --repeats runs
(other processes on shared cores only add time).

    .venv/bin/python -m scripts.bench.textures [--repeats 3] [--out out/bench_textures.txt]

The PNGs are written once into out/bench-textures/ with Pillow: a gradient with per-pixel noise,
so that zlib cannot shrink them to nothing (an 8192^2 one is about 120 MB, as a photographed
texture would be). Issue 12 measured 55 s for the 8192^2 load before the change; the target is
2 s on the 2-core CI machine.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from PIL import Image
from stratum import native

from scripts import REPO

BLENDER_34_CONFIG = Path("/usr/share/blender/datafiles/colormanagement/config.ocio")


def noisy_png(path: Path, side: int) -> Path:
    if not path.is_file():
        path.parent.mkdir(parents=True, exist_ok=True)
        rng = np.random.default_rng(1)
        y, x = np.mgrid[0:side, 0:side]
        rgb = np.stack([x * 255 // side, y * 255 // side, (x + y) % 256], -1)
        rgb = (rgb + rng.integers(-8, 8, rgb.shape)).clip(0, 255).astype(np.uint8)
        Image.fromarray(rgb).save(path, compress_level=6)
    return path


def fastest(texture: native.Texture, repeats: int) -> float:
    best = float("inf")
    for _ in range(repeats):
        with native.Scene() as scene:
            started = time.perf_counter()
            scene.add_texture(texture)
            best = min(best, time.perf_counter() - started)
    return best


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", type=Path, default=REPO / "out" / "bench_textures.txt")
    args = parser.parse_args()
    native.load_library()
    folder = REPO / "out" / "bench-textures"
    config = str(BLENDER_34_CONFIG) if BLENDER_34_CONFIG.is_file() else None
    rows: list[tuple[str, str, float]] = []
    for side in (4096, 8192):
        png = str(noisy_png(folder / f"noise_{side}.png", side))
        for space, ocio in (("sRGB", None), ("sRGB", config), ("Non-Color", config)):
            label = f"{space} ({'Blender 3.4 OCIO config' if ocio else 'built-in'})"
            seconds = fastest(native.Texture(path=png, color_space=space, ocio_config=ocio),
                              args.repeats)
            rows.append((f"{side}^2 8-bit PNG", label, seconds))
    pixels = np.random.default_rng(2).random((8192, 8192, 4), dtype=np.float32)
    rows.append(("8192^2 float pixels", "Linear (no conversion)",
                 fastest(native.Texture(pixels=pixels, color_space="Non-Color"), args.repeats)))
    lines = ["| image | colour space | add_texture (s) |", "|---|---|---|"]
    lines += [f"| {image} | {space} | {seconds:.2f} |" for image, space, seconds in rows]
    text = "\n".join(lines)
    print(text)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
