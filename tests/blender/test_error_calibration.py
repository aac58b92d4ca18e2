"""The Stratum Error pass against the error it predicts (issue 16, acceptance 2): on the Cornell
box, for random, sobol, zsobol and halton_owen, the predicted per-pixel error against the error
measured over 32 seeds. Runs under the bpy 5.x wheel in make test, in any Blender by hand
(conftest.ONE_BLENDER: the scene is exported once and rendered by stratum.native directly).

Reasoning
---------
Per pixel, the measured error is the standard deviation of its value over the SEEDS renders
(each seed scrambles the sequences anew, so the renders are independent draws of the pixel's
estimate). The predicted error is the root mean square over the seeds of the pass: its square is
the pass's estimate of the pixel's variance, and its mean over the seeds is what the estimator
predicts, without the spread of one render's estimate. Their ratio per pixel, medianed over the
pixels, must lie within [0.67, 1.5].

Two lightings: full path tracing (8 bounces), where most of the error is in deep indirect paths
that no sequence stratifies much, and direct light only (max_bounces 0), where the sequences
gain most and the independent-samples estimate s/sqrt(n) overstates sobol's error 2.3x (measured
while the estimator was written). The test also asserts that the sobol pass is below that
estimate there, so it measures the gain rather than repeating s/sqrt(n).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import bpy
import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
SCENE = REPO / "scenes" / "cornell_box.blend"
RES = 32
SEEDS = 32
SAMPLERS = ("random", "sobol", "zsobol", "halton_owen")
# (max_bounces, samples): full path tracing, and direct light with more samples (the sequences'
# gain grows with the count).
LIGHTINGS = ((8, 16), (0, 64))


@pytest.fixture(scope="module")
def cornell(library: Any) -> Any:
    from stratum.export.sync import export_scene

    bpy.ops.wm.open_mainfile(filepath=str(SCENE), load_ui=False)
    scene = library.Scene()
    export_scene(bpy.context.evaluated_depsgraph_get(), scene)
    yield scene
    scene.close()


def _render(native: Any, scene: Any, sampler: str, seed: int, bounces: int,
            samples: int) -> tuple[np.ndarray, np.ndarray]:
    with native.Renderer(scene, width=RES, height=RES, samples=samples, seed=seed,
                         sampler=sampler, max_bounces=bounces,
                         passes="Stratum Error") as renderer:
        renderer.start()
        while not renderer.wait(200):
            pass
        image = renderer.read_pixels().reshape(RES, RES, 4)[..., :3].astype(np.float64)
        error = renderer.read_pass("Stratum Error").reshape(RES, RES, 3).astype(np.float64)
        return image, error


def _calibration(native: Any, scene: Any, sampler: str, bounces: int,
                 samples: int) -> tuple[float, np.ndarray, np.ndarray]:
    """Median over pixels of predicted / measured, and both per pixel (RGB)."""
    images, errors = zip(*(_render(native, scene, sampler, 100 + seed, bounces, samples)
                           for seed in range(SEEDS)))
    measured = np.array(images).std(axis=0, ddof=1)
    predicted = np.sqrt((np.array(errors) ** 2).mean(axis=0))
    # Pixels whose value never changes (the black outside of the box) have no error to predict.
    noisy = measured > 1e-6
    return float(np.median(predicted[noisy] / measured[noisy])), predicted, measured


@pytest.mark.parametrize("bounces,samples", LIGHTINGS)
@pytest.mark.parametrize("sampler", SAMPLERS)
def test_predicted_error_matches_the_error_over_32_seeds(library: Any, cornell: Any, sampler: str,
                                                        bounces: int, samples: int) -> None:
    ratio, _, _ = _calibration(library, cornell, sampler, bounces, samples)
    print(f"Cornell box {RES}x{RES}, {samples} spp, max_bounces {bounces}, {sampler}: median "
          f"predicted/measured error {ratio:.3f}")
    assert 0.67 <= ratio <= 1.5, f"{sampler}: median predicted/measured {ratio:.3f}"


def test_the_pass_measures_sobols_gain_in_direct_light(library: Any, cornell: Any) -> None:
    """In direct light sobol's error is well below that of independent samples of the same
    spread, and the pass must say so: the independent-samples estimate s/sqrt(n) would put
    sobol's predicted error next to random's."""
    _, sobol_predicted, sobol_measured = _calibration(library, cornell, "sobol", 0, 64)
    _, _, random_measured = _calibration(library, cornell, "random", 0, 64)
    noisy = (sobol_measured > 1e-6) & (random_measured > 1e-6)
    gain = float(np.median(sobol_measured[noisy] / random_measured[noisy]))
    predicted_gain = float(np.median(sobol_predicted[noisy] / random_measured[noisy]))
    print(f"direct light, 64 spp: error sobol/random measured {gain:.3f}, predicted "
          f"{predicted_gain:.3f}")
    # The gain exists on this scene, and the pass predicts it.
    assert gain < 0.7
    assert predicted_gain < 0.7, f"sobol's pass / random's measured error {predicted_gain:.3f}"
