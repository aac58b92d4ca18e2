"""The pure helpers of the benchmarks (scripts/bench/results.py, summary.py): the
noise measure of the equal-time section, VmHWM parsing and the summary table. No timing."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from scripts.bench import results as bench_results
from scripts.bench import summary as bench_summary


def test_noise_mse_removes_the_reference_noise() -> None:
    """image = truth + N(0, 1), halves = truth + N(0, 0.5^2): the reference (mean of the halves)
    has variance 0.125, so the raw MSE against it is 1.125 and noise_mse must give 1. With
    N = 200 000 values the raw term's standard deviation is 1.125 sqrt(2/N) = 0.0036 and the
    subtracted term's 0.25 sqrt(2/N) / 2 = 0.0004; their sum bounds the difference's: 0.004.
    Tolerance 5 sigma = 0.02, well under the 0.125 a missing correction would leave."""
    rng = np.random.default_rng(15)
    shape = (200, 250, 4)  # 200 000 values
    truth = rng.uniform(0.0, 4.0, shape)
    image = truth + rng.normal(0.0, 1.0, shape)
    half_a = truth + rng.normal(0.0, 0.5, shape)
    half_b = truth + rng.normal(0.0, 0.5, shape)
    assert bench_results.reference_noise(half_a, half_b) == pytest.approx(0.125, abs=0.004 * 5)
    raw = bench_results.mse(image, (half_a + half_b) / 2)
    assert raw == pytest.approx(1.125, abs=0.02)
    assert bench_results.noise_mse(image, half_a, half_b) == pytest.approx(1.0, abs=0.02)


def test_mse_refuses_images_of_different_shapes() -> None:
    with pytest.raises(ValueError, match="shapes differ"):
        bench_results.mse(np.zeros((2, 2, 3)), np.zeros((2, 3, 3)))


def test_vm_hwm_is_read_from_proc_status() -> None:
    text = "Name:\tblender\nVmPeak:\t 2000 kB\nVmHWM:\t  123456 kB\nVmRSS:\t 1000 kB\n"
    assert bench_results.vm_hwm_kib(text) == 123456
    with pytest.raises(ValueError, match="no VmHWM"):
        bench_results.vm_hwm_kib("Name:\tblender\n")
    own = Path("/proc/self/status")
    if own.is_file():
        assert bench_results.vm_hwm_kib(own.read_text()) > 0


def test_row_judges_both_kinds_of_target() -> None:
    assert bench_results.Row("a", "<= 0.8x", 0.8, limit=0.8).met() == "met"
    assert bench_results.Row("a", "<= 0.8x", 0.81, limit=0.8).met() == "NOT met"
    assert bench_results.Row("a", ">= 0.6x", 0.59, at_least=0.6).met() == "NOT met"
    assert bench_results.Row("a", ">= 0.6x", None, at_least=0.6).met() == "n/a"
    assert bench_results.Row("a", "", 3.0).met() == ""


def _quality_scene(cycles: tuple[float, float], samplers: dict[str, tuple[float, float]],
                   ) -> dict[str, Any]:
    def entry(mse_seconds: tuple[float, float]) -> dict[str, float]:
        return {"noise_mse": mse_seconds[0], "seconds": mse_seconds[1]}

    return {"cycles": entry(cycles),
            "stratum": {"samplers": {k: entry(v) for k, v in samplers.items()}}}


def test_summary_finds_the_best_sampler_and_judges_each_target() -> None:
    sections = {
        "render": {"scenes": {"cornell_box": {"cycles": {"trace": 10.0},
                                              "stratum": {"trace": 7.0, "rays_per_s": 3.0,
                                                          "raw_rays_per_s": 10.0}}}},
        # Cycles' MSE x time is 1.0; sobol's 0.5 (best), zsobol's 0.55, halton_owen's 0.7.
        "quality": {"owen_scrambled": ["sobol", "zsobol", "halton_owen"], "scenes": {
            "cornell_box": _quality_scene((0.1, 10.0), {"random": (0.2, 8.0),
                                                        "sobol": (0.05, 10.0),
                                                        "zsobol": (0.05, 11.0),
                                                        "halton_owen": (0.07, 10.0)})}},
        "memory": {"cases": {"monkey_1m": {"cycles": {"before_kib": 100, "after_kib": 300},
                                           "stratum": {"before_kib": 110, "after_kib": 250}}}},
    }
    text = bench_summary.summary(sections)
    lines = {line.split("  ")[0]: line for line in text.splitlines()}
    assert lines["1 path tracing Stratum/Cycles, cornell_box"].endswith("0.70x  met")
    assert lines["1 path tracing Stratum/Cycles, wolf"].endswith("n/a  n/a")
    assert lines["2 rays/s Stratum/raw Embree, cornell_box"].endswith("0.30x  NOT met")
    assert lines["4 MSE x time best Stratum (sobol)/Cycles, cornell_box"].endswith("0.50x  met")
    assert lines["4 MSE x time zsobol/best, cornell_box"].endswith("1.10x  met")
    assert lines["4 MSE x time halton_owen/best, cornell_box"].endswith("1.40x  NOT met")
    assert lines["7 peak RSS Stratum/Cycles, monkey_1m"].endswith("0.83x  met")
    increase = "  RSS increase in render Stratum/Cycles, monkey_1m"
    assert any(line.startswith(increase) and line.endswith("0.70x")
               for line in text.splitlines())
    assert "export: not run (no export.json)" in text
    # Met: path tracing, best/Cycles, sobol/best (1.00), zsobol/best, peak RSS.
    assert "Targets: 5 met, 2 not met, " in text


def test_summary_judges_the_node_cost_of_issue_18() -> None:
    section = {"ratio": 1.6, "cost_ns": {"cycles": 1000.0, "stratum": 1600.0},
               "best": {"cycles": {"P": 3.0, "C": 0.5}, "stratum": {"P": 4.0, "C": 0.6}},
               "agreement": {"agree": True}}
    text = bench_summary.summary({"shader_nodes": section})
    lines = {line.strip().split("  ")[0]: line for line in text.splitlines()}
    assert lines["18 node cost per point Stratum/Cycles, 20 nodes"].endswith("1.60x  NOT met")
    assert lines["node cost per point, Stratum"].endswith("1.6e+03 ns")
    assert lines["T_C (constant material), Cycles"].endswith("0.5 s")
    assert lines["20-node material's channel means agree (2 %)"].endswith("yes")
    assert "Targets: 0 met, 1 not met, " in text
