"""Stratum against a peer: the Cornell box rendered by Cycles and by Stratum must agree.

Runs in Blender 3.4 (`blender -b --factory-startup --python tests/blender/run_in_blender.py --
tests/blender`) and under the bpy wheel (`.venv/bin/python -m pytest tests/blender`).

What is compared
----------------
scenes/cornell_box.blend at RES x RES, both renderers CPU, MAX_BOUNCES total bounces (Cycles'
diffuse/glossy/transmission limits set to the same number so only the total applies), the same
pixel filter (Blackman-Harris, 1.5 px), no denoising, no adaptive sampling, no clamping, no
glossy blur (Cycles' "Filter Glossy" would change the estimand), and Cycles' probabilistic
light-sample termination off. Both images are linear float EXRs read back with
bpy.data.images.load + pixels.foreach_get. Asserted, per RGB channel c:

    |mean(S_c) - mean(C_c)|            <= 2% of mean(C_c)                    (image mean)
    |block(S_c) - block(C_c)|          <= 5% of block(C_c)  for every 16x16 block whose
                                                           Cycles mean is >= 0.01

Statistical reasoning (why these tolerances are tests of the model, not of the noise)
--------------------------------------------------------------------------------------
Each renderer renders the scene twice, with seeds 1 and 2, at SPP_PER_SEED samples; the image
compared is the average of the two (2 * SPP_PER_SEED = N samples per pixel), and the half
difference of the two is a pure-noise image with the signal removed:

    X = (A1 + A2) / 2,  Var[X_p] = sigma_p^2 / N  and  E[((A1_p - A2_p) / 2)^2] = Var[X_p],

where sigma_p is the standard deviation of one path sample of pixel p. Pixels are independent
(Cycles importance-samples the pixel filter, so a sample lands in one pixel only), so a block
mean over n = 256 pixels and the image mean over RES^2 pixels have

    Var[block(X)] = sum_p Var[X_p] / n^2,   Var[image(X)] = sum_p Var[X_p] / RES^4,

estimated by plugging in ((A1_p - A2_p)/2)^2. Should a renderer correlate neighbouring pixels
(e.g. splatting samples into several pixels), the independence estimate is too small; the
test checks it against the observed spread of the block means of the half-difference image
(their z-scores must have unit variance) and inflates sigma by sqrt(mean z^2) when that is
above 1. The difference D = block(S) - block(C) has Var[D] = Var[block(S)] + Var[block(C)].

Measured on this scene (Blender 3.4 Cycles, 64 x 64, two seeds of 256 spp): the standard
deviation of one path sample relative to the pixel mean, averaged over the image, is r ~ 1.3
per channel; per 16x16 block it is r_b ~ 0.4..3.7 (3.7 in the corner blocks that are half
black border and half dark wall; ~0.45 on the lit floor). With N = 2048 samples per pixel:

    block:  sigma_rel(D) = sqrt(2) * r_b / sqrt(256 * N) = sqrt(2) * 3.7 / 724 = 0.72%
            4 sigma = 2.9% < 5%  (worst block; 1.2% for r_b = 1.5, the typical block)
    image:  sigma_rel(D) = sqrt(2) * 1.3 / sqrt(64^2 * N) = 0.06%,  4 sigma = 0.25% << 2%

(assuming Stratum's noise is no larger than Cycles'; it is measured, not assumed, below).
So a disagreement beyond tolerance has a probability < 1e-4 per compared value of being
noise, i.e. it is a difference of models. test_noise_level_allows_comparison asserts exactly
this with the measured sigmas of the actual renders (4 sigma_D below the tolerance for the
image means and for every compared block), and fails with the numbers if the noise would make
the comparison meaningless (e.g. someone lowers SPP, or a renderer is much noisier).

Cost: 64 x 64 x 2048 = 8.4 M paths per renderer. Measured on 2 (shared, loaded) cores: the
whole file takes ~80 s in Blender 3.4 (Cycles ~2 x 12-24 s, Stratum ~2 x 15 s) and ~45 s
under the bpy 5.0 wheel. Measured noise (Blender 3.4, both renderers): 1 sigma of the
image-mean difference ~0.1% per channel; 4 sigma of the block differences 1.5% (median) to
2.7% (worst block) against the 5% tolerance.

Human-readable output in out/agreement/blender-<version>/: {cycles,stratum}_seed{1,2}.exr
(linear renders), cycles.png, stratum.png (two-seed means, sRGB), difference.png (red: Stratum
brighter, blue: Stratum darker, x DIFF_GAIN), report.txt (means, block table, worst blocks).
"""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from agreement import (
    BLOCK_TOL,
    DARK_BLOCK,
    IMAGE_TOL,
    K_SIGMA,
    MAX_BOUNCES,
    OUT,
    RES,
    SEEDS,
    SPP_PER_SEED,
    Renders,
    compare,
    configure_cycles,
    configure_stratum,
    noise_failures,
    per_channel,
    render_two_seeds,
    save_png,
    stratum_available,
)

# ---- fixtures ------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def cycles() -> Renders:
    return render_two_seeds("cycles", configure_cycles)


@pytest.fixture(scope="module")
def stratum_renders(library) -> Renders:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    return render_two_seeds("stratum", configure_stratum)


# ---- tests -----------------------------------------------------------------------------------


def test_cycles_noise_level_allows_comparison(cycles: Renders) -> None:
    """Cycles alone (runs before Stratum exists): with Stratum's noise taken equal to
    Cycles', 4 sigma of the difference must be below both tolerances."""
    save_png("cycles", cycles.mean, linear_to_srgb=True)
    c_img = cycles.mean.mean(axis=(0, 1))
    assert (c_img > 0.05).all(), f"Cycles image too dark to compare: means {per_channel(c_img)}"
    sd_img = np.sqrt(2.0 * cycles.image_var())
    assert (K_SIGMA * sd_img < 0.5 * IMAGE_TOL * c_img).all(), (
        f"image-mean noise too high: 4 sigma_D = "
        f"{per_channel(K_SIGMA * sd_img / c_img, '{:.3%}')} of the mean, tolerance "
        f"{IMAGE_TOL:.0%}; raise SPP_PER_SEED")
    cb = cycles.block_mean()
    lit = cb >= DARK_BLOCK
    rel = K_SIGMA * np.sqrt(2.0 * cycles.block_var()) / np.maximum(cb, 1e-12)
    worst = float(rel[lit].max())
    print(f"\nCycles {cycles.seconds} s; image 4 sigma_D (Stratum noise = Cycles') "
          f"{per_channel(K_SIGMA * sd_img / c_img, '{:.3%}')}; blocks 4 sigma_D median "
          f"{float(np.median(rel[lit])):.2%}, worst {worst:.2%}; correlation factor "
          f"{cycles.inflation:.2f}")
    assert worst < BLOCK_TOL, (
        f"block noise too high: worst 4 sigma_D = {worst:.2%} of the block mean, tolerance "
        f"{BLOCK_TOL:.0%} (pixel correlation factor {cycles.inflation:.2f}); raise SPP_PER_SEED")


def test_noise_level_allows_comparison(cycles: Renders, stratum_renders: Renders) -> None:
    """With both renderers' measured noise: 4 sigma_D below the tolerances, everywhere."""
    failures = noise_failures(cycles, stratum_renders)
    assert not failures, "; ".join(failures) + "; raise SPP_PER_SEED"


def test_stratum_agrees_with_cycles(cycles: Renders, stratum_renders: Renders) -> None:
    header = (f"Cornell box {RES}x{RES}, {2 * SPP_PER_SEED} spp ({len(SEEDS)} seeds x "
              f"{SPP_PER_SEED}), max_bounces {MAX_BOUNCES}, Blender {bpy.app.version_string}")
    report, agree = compare(cycles, stratum_renders, OUT, header)
    print(report)
    assert agree, f"Stratum and Cycles differ beyond the tolerances:\n{report}\nsee {OUT}"
