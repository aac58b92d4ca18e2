"""Where the light tree stops losing to `mixed`: the measurement behind light_selection `auto`'s
threshold (LightSet::kAutoTreeLights, issue 16 item 3). No Blender: scenes are built through
the native API.

    .venv/bin/python -m scripts.study.auto_lights [--out out/study] [--quick]

Scenes: a grey floor 10 m x 10 m with three boxes 1 m x 1 m x 1.5 m standing on it, seen by a
perspective camera from (0, -7, 4); N point lamps of radius 5 cm (invisible to the camera),
powers log-uniform over a factor 50 (total power fixed, so images stay comparably bright), in
two layouts:

* scattered: uniform over the floor's central 8 m x 8 m, 0.3-2.5 m up (most lamps light only
  their neighbourhood: the tree's case);
* clustered: within 0.3 m of one point 2.5 m up (every lamp lights every point alike: nothing
  for the tree to gain, only its cost to pay).

For N in 1, 2, 4, ..., 64 and each layout, `path` (max_bounces 2) with `mixed` and `tree`
renders 32 spp with 6 seeds at 96 x 64 (sampler sobol); each noise MSE is measured against a
reference of two independent halves (scripts/bench/results.py's noise_mse). The figure of merit is the
product noise MSE x path-tracing seconds (lower is better; equal-time MSE ratio = product
ratio, since MSE ~ 1/time); tree / mixed < 1 means the tree wins. Written to
<out>/auto_lights.json and printed as a table.
"""

from __future__ import annotations

import argparse
import json
import math
import random
import sys
from pathlib import Path
from typing import Any

import numpy as np

from scripts import REPO
from scripts.bench.results import noise_mse, noise_mse_seconds

LAYOUTS = ("scattered", "clustered")
MODES = ("mixed", "tree")
TOTAL_POWER = 100.0  # W over all lamps
BOXES = [((-2.5, -0.5, 0.0), (-1.5, 0.5, 1.5)), ((0.5, 1.0, 0.0), (1.5, 2.0, 1.5)),
         ((1.5, -2.0, 0.0), (2.5, -1.0, 1.5))]


def look_at(eye: tuple[float, float, float], target: tuple[float, float, float]) -> np.ndarray:
    """Camera-to-world (row-major 4x4): local -Z toward target, +Y up."""
    e, t = np.array(eye, dtype=np.float64), np.array(target, dtype=np.float64)
    back = (e - t) / np.linalg.norm(e - t)
    right = np.cross([0.0, 0.0, 1.0], back)
    right /= np.linalg.norm(right)
    up = np.cross(back, right)
    m = np.eye(4, dtype=np.float32)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, up, back, e
    return m


def box_mesh(lo: tuple[float, ...], hi: tuple[float, ...]) -> tuple[np.ndarray, np.ndarray]:
    v = np.array([(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])],
                 dtype=np.float32)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return v, np.array(tris, dtype=np.uint32)


def build_scene(native: Any, layout: str, lamps: int) -> Any:
    scene = native.Scene()
    grey = scene.add_material({"model": native.closure_model("diffuse"), "base_color": (0.6, 0.6, 0.6)})
    floor = np.array([[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]], dtype=np.float32)
    meshes = [(floor, np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32))]
    meshes += [box_mesh(lo, hi) for lo, hi in BOXES]
    for v, t in meshes:
        scene.add_instance(scene.add_mesh(v, t, np.full(len(t), grey, dtype=np.uint32)),
                           np.eye(4, dtype=np.float32))
    rng = random.Random(1000 * lamps + LAYOUTS.index(layout))
    powers = [math.exp(rng.uniform(0.0, math.log(50.0))) for _ in range(lamps)]
    scale = TOTAL_POWER / sum(powers)
    for power in powers:
        m = np.eye(4, dtype=np.float32)
        if layout == "scattered":
            m[:3, 3] = (rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(0.3, 2.5))
        else:
            while True:
                d = [rng.uniform(-0.3, 0.3) for _ in range(3)]
                if sum(x * x for x in d) <= 0.09:
                    break
            m[:3, 3] = (d[0], d[1], 2.5 + d[2])
        # Invisible to camera rays: a lamp's disc seen directly is a single-pixel firefly that
        # would decide any MSE.
        scene.add_light(type=native.light_type("point"), strength=power * scale, radius=0.05,
                        transform=m, visibility=native.VISIBLE_ALL & ~native.VISIBLE_CAMERA)
    scene.set_camera(native.Camera(lens_mm=24.0, transform=look_at((0.0, -7.0, 4.0), (0.0, 0.0, 0.5))))
    return scene


def render(native: Any, scene: Any, size: tuple[int, int], **settings: Any) -> tuple[np.ndarray, float]:
    with native.Renderer(scene, width=size[0], height=size[1], max_bounces=2, **settings) as r:
        r.start()
        while not r.wait(100):
            pass
        p = r.progress()
        rgb = r.read_pixels().reshape(size[1], size[0], 4)[:, :, :3].astype(np.float64)
    return rgb, p.render_seconds


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(REPO / "out" / "study"))
    p.add_argument("--quick", action="store_true", help="toy sizes, to test the pipeline")
    args = p.parse_args(argv)
    from stratum import native

    native.load_library()
    counts = [1, 2, 8] if args.quick else [1, 2, 4, 8, 16, 32, 64]
    size, spp, seeds, ref_spp = ((32, 24), 4, 2, 64) if args.quick else ((96, 64), 32, 6, 2048)
    results: dict[str, Any] = {"spp": spp, "seeds": seeds, "reference_spp": ref_spp,
                               "size": size, "rows": []}
    print(f"{'layout':10s}{'N':>5s}" + "".join(f"{m + ' MSE':>14s}{m + ' s':>9s}" for m in MODES)
          + f"{'tree/mixed (MSE x s)':>22s}")
    for layout in LAYOUTS:
        for n in counts:
            scene = build_scene(native, layout, n)
            try:
                a, b = (render(native, scene, size, samples=ref_spp // 2, seed=s, sampler="sobol",
                               light_selection="tree")[0] for s in (1001, 1002))
                row: dict[str, Any] = {"layout": layout, "lamps": n}
                # Seeds in turn, each by both modes: a change of the machine's load reaches both.
                runs: dict[str, list[tuple[np.ndarray, float]]] = {m: [] for m in MODES}
                for s in range(1, seeds + 1):
                    for mode in MODES:
                        runs[mode].append(render(native, scene, size, samples=spp, seed=s,
                                                 sampler="sobol", light_selection=mode))
                for mode, done in runs.items():
                    row[mode] = {"noise_mse": float(np.mean([noise_mse(im, a, b) for im, _ in done])),
                                 "seconds": float(np.median([t for _, t in done]))}
            finally:
                scene.close()
            product = {m: noise_mse_seconds(row[m]) for m in MODES}
            row["tree_over_mixed"] = product["tree"] / product["mixed"]
            results["rows"].append(row)
            print(f"{layout:10s}{n:5d}" + "".join(f"{row[m]['noise_mse']:14.4e}{row[m]['seconds']:9.3f}"
                                                  for m in MODES) + f"{row['tree_over_mixed']:22.3f}",
                  flush=True)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "auto_lights.json").write_text(json.dumps(results, indent=1))
    print(f"written {out / 'auto_lights.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
