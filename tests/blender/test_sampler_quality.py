"""What the samplers do to a real image: the Cornell box at 16 spp, against a high-spp
reference, per sampler. Runs under the bpy 5.x wheel in make test, in any Blender by hand
(conftest.ONE_BLENDER; the scene is exported by
the add-on's exporter and rendered by stratum.native directly, without Blender's render
pipeline, to keep the cost down).

Reasoning
---------
MSE(sampler) = mean over pixels and over SEEDS renders of (image - reference)^2. The reference
has its own noise, which adds sigma_p^2 / REF_SPP to every MSE; with REF_SPP = 64 x 16 that is
1/64 of random's MSE at 16 spp, small against the margin asserted (and it makes the ratio
conservative: it adds the same amount to both). Each MSE averages SEEDS x RES^2 = 16384 squared
pixel errors; their relative standard error is measured from the spread of the per-seed MSEs
and printed, and the assertion requires the ratio to hold with 2 standard errors of margin.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
SCENE = REPO / "scenes" / "cornell_box.blend"
RES = 64
SPP = 16
REF_SPP = 1024
SEEDS = 4
MAX_BOUNCES = 8


@pytest.fixture(scope="module")
def cornell(library: Any) -> Any:
    from stratum.export.sync import export_scene

    bpy.ops.wm.open_mainfile(filepath=str(SCENE), load_ui=False)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    scene = library.Scene()
    export_scene(depsgraph, scene)
    yield scene
    scene.close()


def _render(native: Any, scene: Any, sampler: str, spp: int, seed: int) -> np.ndarray:
    with native.Renderer(scene, width=RES, height=RES, samples=spp, seed=seed, sampler=sampler,
                         max_bounces=MAX_BOUNCES) as renderer:
        renderer.start()
        while not renderer.wait(200):
            pass
        return renderer.read_pixels().reshape(RES, RES, 4)[..., :3].astype(np.float64)


@pytest.fixture(scope="module")
def reference(library: Any, cornell: Any) -> np.ndarray:
    return _render(library, cornell, "sobol", REF_SPP, seed=1000)


def _mse_per_seed(native: Any, scene: Any, sampler: str, reference: np.ndarray) -> np.ndarray:
    return np.array([np.mean((_render(native, scene, sampler, SPP, seed) - reference) ** 2)
                     for seed in range(SEEDS)])


def test_sobol_mse_at_16_spp_is_at_most_0_7_of_random(library: Any, cornell: Any,
                                                        reference: np.ndarray) -> None:
    random_mse = _mse_per_seed(library, cornell, "random", reference)
    sobol_mse = _mse_per_seed(library, cornell, "sobol", reference)
    ratio = sobol_mse.mean() / random_mse.mean()
    # Relative standard errors of the two means over seeds, combined for the ratio.
    rel_se = np.sqrt((random_mse.std(ddof=1) / random_mse.mean()) ** 2 / SEEDS
                     + (sobol_mse.std(ddof=1) / sobol_mse.mean()) ** 2 / SEEDS)
    print(f"Cornell box {RES}x{RES}, {SPP} spp, {SEEDS} seeds: MSE random {random_mse.mean():.3e}"
          f", sobol {sobol_mse.mean():.3e}, ratio {ratio:.3f} (relative se {rel_se:.3f})")
    assert ratio * (1.0 + 2.0 * rel_se) <= 0.7, (
        f"sobol/random MSE ratio {ratio:.3f} (+2 se = {ratio * (1 + 2 * rel_se):.3f}) above 0.7")
